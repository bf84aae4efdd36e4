"""What the viewer draws, as Rich renderables built from the state (no Textual).

The app asks for one pane at a time with the pane's size in cells; everything heavy is cached
on what it depends on, so a key that changes nothing a pane shows costs nothing.  Pictures come
from :mod:`tuibrdf.render` when it is there, and from :mod:`.fallback` until then; the
directional albedo and the peak from :mod:`tuibrdf.core.quadrature` likewise.
"""

from __future__ import annotations

from collections import OrderedDict
from collections.abc import Callable, Hashable
from dataclasses import dataclass
from typing import Any

import numpy as np
from rich.text import Text

from ..core.params import Model
from ..render.halfblock import HalfBlockImage, Mark
from . import fallback
from .state import Side

try:  # helper render's module (agreed API); the fallback serves until it lands
    from ..render import views as _views  # type: ignore[attr-defined]
except ImportError:  # pragma: no cover - depends on what is merged
    _views = None
try:
    from ..core import quadrature as _quad  # type: ignore[attr-defined]
except ImportError:  # pragma: no cover
    _quad = None

LEVELS = 32  # grey levels of the map: within one level of the converged picture, few runs
LOG_DECADES = 3.0
LUMA = np.array([0.2126, 0.7152, 0.0722])
CMAPS = tuple(getattr(_views, "CMAPS", fallback.CMAPS))


class LRU:
    """A tiny least-recently-used cache: ``get(key, make)``."""

    def __init__(self, size: int = 16) -> None:
        self.size = size
        self.data: OrderedDict[Hashable, Any] = OrderedDict()

    def get(self, key: Hashable, make: Callable[[], Any]) -> Any:
        if key in self.data:
            self.data.move_to_end(key)
            return self.data[key]
        value = self.data[key] = make()
        if len(self.data) > self.size:
            self.data.popitem(last=False)
        return value


@dataclass(frozen=True)
class Look:
    """Display options shared by every pane."""

    color: str = "truecolor"  # truecolor | 256 | none
    cmap: str = "grey"
    log: bool = False
    cosine: bool = False


@dataclass(frozen=True)
class Stats:
    albedo: float | tuple[float, ...]
    peak: float
    peak_theta: float
    peak_phi: float

    @property
    def albedo_max(self) -> float:
        return float(np.max(self.albedo))


_values_cache = LRU(12)
_stats_cache = LRU(64)
_curve_cache = LRU(16)


def side_values(side: Side, theta_i: float, px_w: int, px_h: int, cosine: bool):
    """Map values of one side (cached)."""
    key = (side.key(), theta_i, px_w, px_h, cosine)
    return _values_cache.get(key, lambda: fallback.map_values(
        side.spec, side.values, theta_i, px_w, px_h, cosine=cosine))


def stats(side: Side, theta_i: float, cosine: bool = False) -> Stats:
    """Directional albedo and peak (value, θ, φ) of one side at θi (cached)."""

    def make() -> Stats:
        if _quad is not None:
            m, v = side.spec, side.values
            a = _quad.albedo_resolved(m, v, theta_i)
            pk = _quad.peak_resolved(m, v, theta_i, cosine=cosine)
            return Stats(_plain(a), float(pk.value), float(pk.theta_deg), float(pk.phi_deg))
        a, (pv, pt, pp) = fallback.albedo_and_peak(side.spec, side.values, theta_i,
                                                   cosine=cosine)
        return Stats(_plain(a), pv, pt, pp)

    return _stats_cache.get((side.key(), theta_i, cosine), make)


def _plain(a) -> float | tuple[float, ...]:
    a = np.asarray(a, dtype=float)
    return float(a) if a.ndim == 0 else tuple(float(x) for x in a)


# --------------------------------------------------------------------------- maps
def _scalar(v: np.ndarray) -> np.ndarray:
    return v @ LUMA if v.ndim == 3 else v


def normalise(v: np.ndarray, vmax: float, log: bool) -> np.ndarray:
    """Values in [0, 1] (NaN stays NaN): linear v/vmax, or log over :data:`LOG_DECADES`."""
    vmax = vmax if vmax > 0 else 1.0
    t = v / vmax  # vmax > 0 (guarded above)
    if log:  # log10 only where t > 0 (0 and NaN would warn); the rest is the bottom level
        pos = t > 0
        lt = np.full(t.shape, np.nan)
        np.log10(t, out=lt, where=pos)
        t = np.where(pos, lt / LOG_DECADES + 1.0, np.where(np.isnan(t), np.nan, 0.0))
    return np.clip(t, 0.0, 1.0)


def vmax_of(*arrays: np.ndarray) -> float:
    m = max((float(np.nanmax(_scalar(a))) if np.isfinite(_scalar(a)).any() else 0.0)
            for a in arrays)
    return m if m > 0 else 1.0


def image(values: np.ndarray, info: dict, theta_i: float, look: Look, vmax: float,
          cmap: str | None = None) -> HalfBlockImage:
    """Quantise map values to a half-block image with a mirror mark."""
    inside = np.isfinite(_scalar(values))
    marks = []
    mx, my = info.get("mirror_px", (None, None))
    if mx is not None:
        marks.append(Mark(int(my // 2), int(min(mx, values.shape[1] - 1)), "×", "X",
                          (255, 60, 60)))
    system = look.color
    if values.ndim == 3 and cmap is None:  # an RGB model: its own colours
        t = normalise(values, vmax, look.log)
        rgb = np.rint(np.nan_to_num(t) * (LEVELS - 1)) * 255 / (LEVELS - 1)
        return HalfBlockImage.from_rgb(np.rint(rgb).astype(int), inside, marks, system)
    t = normalise(_scalar(values), vmax, look.log)
    idx = np.where(inside, np.rint(np.nan_to_num(t) * (LEVELS - 1)), -1).astype(np.int64)
    return HalfBlockImage(idx, fallback.palette(cmap or look.cmap, LEVELS), marks, system)


def map_pane(side: Side, theta_i: float, w: int, h: int, look: Look, vmax: float | None = None):
    """``(renderable, vmax)`` of the equal-area map of one side in ``w × h`` cells."""
    vals, info = side_values(side, theta_i, w, 2 * h, look.cosine)
    vmax = vmax if vmax is not None else vmax_of(vals)
    return image(vals, info, theta_i, look, vmax), vmax


def compare_vmax(sides: list[Side], theta_i: float, w: int, h: int, look: Look) -> float:
    return vmax_of(*(side_values(s, theta_i, w, 2 * h, look.cosine)[0] for s in sides))


def diff_pane(a: Side, b: Side, theta_i: float, w: int, h: int, look: Look):
    """``(renderable, max |A − B|)``: the difference map on a diverging scale (red: A > B)."""
    va, info = side_values(a, theta_i, w, 2 * h, look.cosine)
    vb, _ = side_values(b, theta_i, w, 2 * h, look.cosine)
    d = _scalar(va) - _scalar(vb)
    m = float(np.nanmax(np.abs(d))) if np.isfinite(d).any() else 0.0
    t = d / (m if m > 0 else 1.0) * 0.5 + 0.5  # m > 0 (guarded)
    idx = np.where(np.isfinite(d), np.rint(np.nan_to_num(t) * (LEVELS - 1)), -1)
    return HalfBlockImage(idx.astype(np.int64), fallback.palette("diverging", LEVELS), (),
                          look.color), m


# --------------------------------------------------------------------------- plots
SIDE_COLORS = ("cyan", "orange")


def polar_pane(sides: list[Side], theta_i: float, plane: str, w: int, h: int, look: Look):
    """Polar cross-section(s) drawn with plotext: radius = f, θr from −90° to 90°; one curve
    per side (overlaid in compare mode), the light direction as a dotted ray."""
    import plotext as plt

    curves = [fallback.plane_curve(s.spec, s.values, theta_i, plane, cosine=look.cosine)
              for s in sides]
    r = max(float(np.max(f)) for _, f in curves) or 1.0
    plt.clear_figure()
    plt.plotsize(max(w, 10), max(h, 4))
    plt.theme("clear")
    plt.frame(False)
    plt.xticks([])
    plt.yticks([])
    for k in (0.5, 1.0):  # guide circles at half and full radius
        t = np.radians(np.linspace(-90, 90, 91))
        plt.plot((k * r * np.sin(t)).tolist(), (k * r * np.cos(t)).tolist(),
                 marker="braille", color="gray")
    if plane == "incidence":  # the light's direction, on the φ = 180° (left) side
        s_, c_ = np.sin(np.radians(theta_i)), np.cos(np.radians(theta_i))
        ln = np.linspace(0, r, 20)
        plt.plot((-s_ * ln).tolist(), (c_ * ln).tolist(), marker="dot", color="yellow")
    for (t, f), col in zip(curves, SIDE_COLORS, strict=False):
        a = np.radians(t)
        plt.plot((f * np.sin(a)).tolist(), (f * np.cos(a)).tolist(), marker="braille",
                 color=col)
    plt.xlim(-r, r)
    plt.ylim(0, r)
    text = Text.from_ansi(plt.build())
    if look.color == "none":
        text = Text(text.plain)
    return text


def albedo_pane(sides: list[Side], theta_i: float, w: int, h: int, look: Look):
    """The directional albedo a(θi) over θi ∈ [0°, 90°], the current θi marked, 1 dotted."""
    import plotext as plt

    thetas = np.linspace(0.0, 90.0, 31)
    plt.clear_figure()
    plt.plotsize(max(w, 20), max(h, 6))
    plt.theme("clear")
    top = 1.0
    for s, col in zip(sides, SIDE_COLORS, strict=False):
        curve = _curve_cache.get(s.key(), lambda s=s: _albedo_curve(s.spec, s.values, thetas))
        y = curve @ LUMA if curve.ndim == 2 else curve
        top = max(top, float(np.max(y)))
        plt.plot(thetas.tolist(), y.tolist(), marker="braille", color=col, label=s.model)
    plt.plot([0, 90], [1, 1], marker="dot", color="red")
    plt.vertical_line(theta_i, color="yellow")
    plt.xlim(0, 90)
    plt.ylim(0, top * 1.05)
    plt.xlabel("θi (°)")
    text = Text.from_ansi(plt.build())
    return Text(text.plain) if look.color == "none" else text


def _albedo_curve(model: Model, values: dict, thetas: np.ndarray) -> np.ndarray:
    if _quad is not None:
        return np.asarray(_quad.albedo_curve_resolved(model, values, thetas), dtype=float)
    return fallback.albedo_curve(model, values, thetas)


def solid_pane(side: Side, theta_i: float, w: int, h: int, look: Look, azimuth: float,
               elevation: float):
    """The 3D photometric solid (helper render's ``solid`` view), or a note until it lands."""
    if _views is not None:
        return _views.render_view("solid", side.spec, side.values, theta_i, w, h,
                                  color=look.color, cmap=look.cmap, log=look.log,
                                  cosine=look.cosine)
    return Text(f"3D photometric solid\n(azimuth {azimuth:g}°, elevation {elevation:g}°)\n"
                "waiting for tuibrdf.render.solid", justify="center")


def colorbar(look: Look, vmax: float, width: int) -> Text:
    """``0 ▁▂▃ 2.4 sr⁻¹`` in the map's colours (a strip of cells)."""
    width = max(4, width)
    pal = fallback.palette(look.cmap, width)
    bar = Text()
    for r, g, b in pal.tolist():
        bar.append(" ", style=f"on rgb({r},{g},{b})" if look.color != "none" else "")
    if look.color == "none":
        bar = Text(" .:-=+*#%@"[:width].ljust(width, "@"))
    lo = f"{vmax * 10 ** -LOG_DECADES:.3g}" if look.log else "0"
    return Text.assemble(f"{lo} ", bar, f" {vmax:.3g} sr⁻¹")
