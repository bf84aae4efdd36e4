"""What the viewer draws: Rich renderables from the state, via :mod:`tuibrdf.render` (no Textual).

The app asks for one pane at a time with the pane's size in cells.  Single-model panes are
``render_view`` calls; compare mode adds what only the viewer needs: two maps on one colour
scale, a difference map, and cross-sections overlaid.  The directional albedo and the peak come
from :mod:`tuibrdf.core.quadrature`.
"""

from __future__ import annotations

from collections import OrderedDict
from collections.abc import Callable, Hashable
from dataclasses import dataclass
from typing import Any

import numpy as np
from rich.console import Group
from rich.text import Text

from ..core import quadrature
from ..render import views
from ..render.albedo_plot import THETAS, albedo_plot, cached_curve
from ..render.albedo_plot import albedo_curve as render_albedo_curve
from ..render.colormap import CMAPS as CMAPS  # re-exported for the app
from ..render.colormap import Scale, fmt_value, luminance
from ..render.halfblock import HalfBlockImage
from ..render.hemimap import map_values
from ..render.polar import caption_parts, plot_body, polar_plot, section_curves, sections_max
from ..render.text import title
from .state import Side

#: colour levels of the maps: 32 keeps a full 160×48 map update near 50 KiB (docs/app.md)
LEVELS = 32
#: diverging palette of the difference map: blue (B larger) – grey – red (A larger)
DIVERGING = ((59, 76, 192), (221, 221, 221), (180, 4, 38))
SIDE_LABELS = ("A", "B")


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

    def __contains__(self, key: Hashable) -> bool:
        return key in self.data


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


STATS = LRU(64)
_values = LRU(8)


def stats_key(side: Side, theta_i: float, cosine: bool) -> tuple:
    return (side.key(), theta_i, cosine)


def stats(side: Side, theta_i: float, cosine: bool = False) -> Stats:
    """Directional albedo and peak (value, θ, φ) of one side at θi (cached)."""

    def make() -> Stats:
        m, v = side.spec, side.values
        a = np.asarray(quadrature.albedo_resolved(m, v, theta_i), dtype=float)
        pk = quadrature.peak_resolved(m, v, theta_i, cosine=cosine)
        pv = np.asarray(pk.value, dtype=float)
        value = float(luminance(pv)) if pv.ndim == 1 else float(pv)
        alb = float(a) if a.ndim == 0 else tuple(float(x) for x in a)
        return Stats(alb, value, float(pk.theta_deg), float(pk.phi_deg))

    return STATS.get(stats_key(side, theta_i, cosine), make)


# --------------------------------------------------------------------------- single panes
def view_pane(view: str, side: Side, theta_i: float, w: int, h: int, look: Look,
              azimuth: float = -60.0, elevation: float = 25.0):
    """``render_view`` of one side; a short note when the renderer lacks the view."""
    kw: dict[str, Any] = dict(color=look.color, cosine=look.cosine)
    if view in ("map", "solid"):
        kw.update(cmap=look.cmap, log=look.log)
    if view == "map":
        kw.update(levels=LEVELS)
    if view in ("incidence", "perpendicular"):
        kw.update(log=look.log)
    if view == "solid":
        kw.update(azimuth_deg=azimuth, elevation_deg=elevation)
    try:
        return views.render_view(view, side.spec, side.values, theta_i, w, h, **kw)
    except ImportError:  # a renderer module not merged yet
        return Text(f"{view}: not available in this build", justify="center")


# --------------------------------------------------------------------------- compare mode
def _map_data(side: Side, theta_i: float, px_w: int, px_h: int, cosine: bool):
    key = (side.key(), theta_i, px_w, px_h, cosine)
    return _values.get(key, lambda: map_values(side.spec, side.values, theta_i, px_w, px_h,
                                                cosine=cosine))


def _scalar(v: np.ndarray) -> np.ndarray:
    return luminance(v) if v.ndim == 3 else v


def compare_map(sides: list[Side], k: int, theta_i: float, w: int, h: int, look: Look):
    """Side ``k``'s map on the colour scale shared by both sides (title, disc, colour bar)."""
    px_w, px_h = w, 2 * (h - 3)
    data = [_map_data(s, theta_i, px_w, px_h, look.cosine) for s in sides]
    scale = Scale(max(Scale.for_values(d).vmax for d, _ in data), look.log)
    vals, info = data[k]
    return views.map_picture(vals, info, theta_i, w, label=f"{SIDE_LABELS[k]}: {sides[k].model}",
                             color=look.color, cmap=look.cmap, log=look.log,
                             cosine=look.cosine, levels=LEVELS, scale=scale)


def diff_map(sides: list[Side], theta_i: float, w: int, h: int, look: Look):
    """A − B on a diverging scale symmetric about 0 (red: A larger, blue: B larger)."""
    px_w, px_h = w, 2 * (h - 3)
    (va, _), (vb, _) = (_map_data(s, theta_i, px_w, px_h, look.cosine) for s in sides)
    d = _scalar(va) - _scalar(vb)
    finite = np.isfinite(d)
    m = float(np.max(np.abs(d[finite]))) if finite.any() else 0.0
    m = m if m > 0 else 1.0  # identical sides: all mid-grey, no division by zero
    t = np.clip(d / m * 0.5 + 0.5, 0.0, 1.0)
    idx = np.where(finite, np.rint(np.nan_to_num(t) * (LEVELS - 1)), -1).astype(np.int64)
    stops = np.array(DIVERGING, dtype=float)
    x = np.linspace(0, 1, LEVELS)
    pal = np.stack([np.interp(x, [0, 0.5, 1], stops[:, c]) for c in range(3)], -1)
    img = HalfBlockImage(idx, np.rint(pal).astype(np.uint8), (), color_system=look.color)
    head = title([("A − B", 1), (f"max |Δ| {fmt_value(m)}", 0)], w)
    return Group(head, img, title([("red: A>B  blue: B>A", 0)], w))


def compare_section(sides: list[Side], theta_i: float, plane: str, w: int, h: int,
                    look: Look):
    """Both sides' cross-sections overlaid (A first colour, B second)."""
    curves = []
    for k, s in enumerate(sides):
        for label, th, v in section_curves(s.spec, s.values, theta_i, plane,
                                           cosine=look.cosine):
            curves.append((f"{SIDE_LABELS[k]}:{s.model}" if label == s.model else label, th, v))
    vmax = max(sections_max(s.spec, s.values, theta_i, look.cosine) for s in sides)
    text, caption = polar_plot(curves, w, h - 1, log=look.log, color=look.color,
                               theta_i_deg=theta_i if plane == "incidence" else None,
                               vmax=vmax)
    head = title([(plane, 0), (f"A {sides[0].model} vs B {sides[1].model}", 2),
                  *caption_parts(caption)], w)
    return Group(head, plot_body(text, look.color))


# --------------------------------------------------------------------------- albedo curve
def albedo_curve(side: Side) -> np.ndarray:
    """The side's a(θi) curve (:func:`tuibrdf.render.albedo_plot.albedo_curve`, cached)."""
    return render_albedo_curve(side.spec, side.values)[1]


def albedo_curve_ready(side: Side) -> bool:
    return cached_curve(side.spec, side.values) is not None


def albedo_pane(sides: list[Side], theta_i: float, w: int, h: int, look: Look):
    """a(θi) over 0–90° for each side (luminance for RGB), θi marked, a = 1 drawn."""
    curves = []
    for k, s in enumerate(sides):
        c = albedo_curve(s)
        label = f"{SIDE_LABELS[k]}: {s.model}" if len(sides) > 1 else s.model
        curves.append((label, luminance(c) if c.ndim == 2 else c))
    text = albedo_plot(THETAS, curves, w, h - 1, theta_i_deg=theta_i, color=look.color)
    head = title([("directional albedo a(θi) = ∫ f cos θr dω", 0), ("(line: a = 1)", 1)], w)
    return Group(head, plot_body(text, look.color))
