"""PDF figures with matplotlib (the optional ``[plot]`` extra: ``pip install 'tuibrdf[plot]'``),
imported only here, when a PDF is asked for (never on the viewer's or ``--help``'s path).

- ``map``: the Lambert equal-area map (the numbers of :func:`~tuibrdf.core.views.tables.
  map_table`) with its colour bar, circles of constant θ (30°, 60°, 90°) and lines of constant
  φ every 30°, the mirror direction (×) and the light's Lambert point (○);
- ``incidence``, ``perpendicular``: the section on polar axes (θ = 0 up, the signed angle
  around, ``f`` as the radius);
- ``albedo``: a(θi) with its error band; ``theta-h``, ``theta-d``: ``f`` against the angle.

The bytes are the same for the same figure: no creation date is written
(``metadata={"CreationDate": None}``) and matplotlib's PDF ids are derived from the content.
"""

from __future__ import annotations

import io
import math
from typing import Any

import numpy as np

from tuibrdf.core.views.tables import Table

VIEWS = ("map", "incidence", "perpendicular", "albedo", "theta-h", "theta-d")
CMAP_NAMES = {"grey": "gray", "viridis": "viridis", "inferno": "inferno"}


def available() -> bool:
    import importlib.util

    return importlib.util.find_spec("matplotlib") is not None


def _figure(size_in: tuple[float, float]):
    from matplotlib.figure import Figure  # no pyplot: no backend, no global state

    return Figure(figsize=size_in, layout="constrained")


def _map(fig, table: Table, cmap: str, log: bool) -> None:
    from matplotlib.colors import LogNorm, Normalize

    f = table.columns["f"]
    if f.ndim == 3:  # RGB: the Rec. 709 luminance
        f = f @ np.array([0.2126, 0.7152, 0.0722])
    r = math.sqrt(2.0)
    ax = fig.add_subplot()
    top = float(np.nanmax(f)) if np.isfinite(f).any() else 1.0
    top = top if top > 0 else 1.0
    norm = LogNorm(top * 1e-3, top) if log else Normalize(0.0, top)
    shown = np.where(f > top * 1e-3, f, top * 1e-3) if log else f
    n = f.shape[0]
    # the grid's pixel centres span the disc's diameter plus the margin (hemimap.geometry)
    d = table.meta["disc_diameter_px"]
    cx, cy = table.meta["disc_center_px"]
    k = r / (d / 2.0)
    extent = (-cx * k, (n - cx) * k, (cy - n) * k, cy * k)
    im = ax.imshow(shown, cmap=CMAP_NAMES.get(cmap, cmap), norm=norm, extent=extent,
                   interpolation="nearest")
    fig.colorbar(im, ax=ax, label="f (sr⁻¹)" + (" (log)" if log else ""), shrink=0.85)
    t = np.linspace(0.0, 2.0 * math.pi, 361)
    for th in (30.0, 60.0, 90.0):
        rr = 2.0 * math.sin(math.radians(th) / 2.0)
        ax.plot(rr * np.cos(t), rr * np.sin(t), color="0.6", lw=0.6)
        ax.annotate(f"θ={th:g}°", (rr * math.cos(math.radians(105)), rr * math.sin(
            math.radians(105))), color="0.5", fontsize=7, ha="center", va="bottom")
    for ph in range(0, 360, 30):
        c, s = math.cos(math.radians(ph)), math.sin(math.radians(ph))
        ax.plot([0.0, r * c], [0.0, r * s], color="0.6", lw=0.4)
        ax.annotate(f"φ={ph}°" if ph == 0 else f"{ph}°", (1.1 * r * c, 1.1 * r * s),
                    ha="center", va="center", fontsize=7, color="0.4")
    wi = np.array(table.meta["wi"])
    for w, mark, label in ((wi * np.array([-1.0, -1.0, 1.0]), "x", "mirror"), (wi, "o",
                                                                              "light")):
        kk = math.sqrt(2.0 / (1.0 + w[2]))
        ax.plot(w[0] * kk, w[1] * kk, mark, color="red" if mark == "x" else "cyan",
                mfc="none", ms=8, label=label)
    ax.set_xlim(-1.2 * r, 1.2 * r)
    ax.set_ylim(-1.2 * r, 1.2 * r)
    ax.set_aspect("equal")
    ax.set_axis_off()
    ax.legend(loc="lower right", fontsize=7, frameon=False)


def _f_columns(table: Table) -> list[tuple[str, np.ndarray]]:
    c = table.columns
    if "f" in c:
        return [("f", c["f"])]
    return [(name, c[name]) for name in ("f_r", "f_g", "f_b")]


def _section(fig, table: Table, log: bool) -> None:
    ax = fig.add_subplot(projection="polar")
    ax.set_theta_zero_location("N")
    ax.set_theta_direction(-1)  # positive θ (the mirror side) to the right
    ax.set_thetamin(-90)
    ax.set_thetamax(90)
    t = np.radians(table.columns["theta"])
    colours = {"f": "black", "f_r": "red", "f_g": "green", "f_b": "blue"}
    for name, f in _f_columns(table):
        ax.plot(t, f, color=colours[name], lw=1.0, label=name)
    if log:
        ax.set_rscale("symlog")
    from matplotlib.ticker import MaxNLocator

    ax.yaxis.set_major_locator(MaxNLocator(3))
    ax.tick_params(labelsize=7)
    ax.set_rlabel_position(-60)  # on the light's side, away from a lobe on the mirror side
    ax.set_title(f"{table.view}: f (sr⁻¹) against θ", fontsize=9)


def _lines(fig, table: Table, log: bool) -> None:
    ax = fig.add_subplot()
    c = table.columns
    if table.view == "albedo":
        t = c["theta_i"]
        names = [("albedo", "error", "black")] if "albedo" in c else [
            (f"albedo_{ch}", f"error_{ch}", col) for ch, col in zip("rgb", ("red", "green",
                                                                              "blue"),
                                                                  strict=True)]
        for a, e, col in names:
            ax.plot(t, c[a], color=col, lw=1.0, label=a)
            ax.fill_between(t, c[a] - c[e], c[a] + c[e], color=col, alpha=0.2, lw=0)
        ax.axhline(1.0, color="0.6", lw=0.6)
        ax.set_xlabel("θi (°)")
        ax.set_ylabel("a(θi)")
    else:
        x = c["theta_h" if table.view == "theta-h" else "theta_d"]
        for name, f in _f_columns(table):
            ax.plot(x, f, lw=1.0, label=name)
        ax.set_xlabel("θh (°)" if table.view == "theta-h" else "θd (°)")
        ax.set_ylabel("f (sr⁻¹)")
        if log:
            ax.set_yscale("log")
    ax.set_xlim(0, 90)
    ax.grid(True, lw=0.3)


def pdf(table: Table, *, cmap: str = "grey", log: bool = False,
        title: str | None = None) -> bytes:
    """The PDF of ``table`` (a view of :data:`VIEWS`)."""
    if table.view not in VIEWS:
        raise ValueError(f"no PDF figure of the {table.view} view: {', '.join(VIEWS)}")
    fig = _figure((5.0, 4.2) if table.view == "map" else (5.0, 3.6))
    if table.view == "map":
        _map(fig, table, cmap, log)
    elif table.view in ("incidence", "perpendicular"):
        _section(fig, table, log)
    else:
        _lines(fig, table, log)
    meta = table.meta
    fig.suptitle(title or _title(meta), fontsize=9)
    buf = io.BytesIO()
    fig.savefig(buf, format="pdf", metadata={"CreationDate": None, "Creator": "tuibrdf"})
    return buf.getvalue()


def _title(meta: dict[str, Any]) -> str:
    params = " ".join(f"{k}={v}" for k, v in meta.get("params", {}).items())
    at = f"  θi={meta['theta_i']:g}°" if "theta_i" in meta else ""
    return f"{meta.get('model', '')}  {params}{at}"
