"""The polar cross-sections, drawn straight from numpy on a braille canvas (:mod:`.braille`):
the panes ``incidence`` and ``perpendicular`` (:func:`tuibrdf.render.panes.section_pane`).

A section's values ``r(θ)`` for ``θ ∈ [−90°, 90°]`` (the frame's section arrays,
:mod:`tuibrdf.core.views.frame`; nothing is evaluated here) are drawn at ``x = r sin θ``,
``y = r cos θ``, negative θ on the left:

- plane of incidence: ``wo = (sin θr, 0, cos θr)`` turned to the light's azimuth: the right half
  is the mirror side, the left half the light's side; the incident direction is drawn as a line;
- the section through the lobe's peak: the great circle through the frame's peak turned by the
  *section azimuth* ψ about it (90° = across the peak's vertical plane, the seed's "largeur …
  dans un plan perpendiculaire"; 0° = that plane itself), the peak straight up, so that θ on
  the plot is the signed angle from the peak and the width reads off (:func:`fwhm_text`).

Radius = value (linear), or in log mode ``1 + log10(v / vmax) / decades`` clipped at 0 (the
centre is ``vmax·10^-decades`` and below: :func:`radius`).  Guide circles: 1-2-5 steps in linear
mode (:func:`circle_step`), one per decade in log mode, and the horizon line; the caption says
their spacing.  The window gives one data unit the same length on screen in x and y, a cell
being twice as tall as wide (:data:`CELL_ASPECT`): circles are round.  Several curves
(comparisons, or the R, G, B channels of a colour model) share one radius scale and get a
legend in the top-left corner.

- :func:`polar_canvas` draws the curves on a canvas and returns it with its caption;
- :func:`angle_at` inverts the plot's geometry (a click on a section);
- :func:`fwhm_text` the width of a lobe.

``charset="ascii"`` gives one marker character per cell (:mod:`.braille`); each curve has its
own dot pattern as well as its colour, so plain text still tells the curves apart.
"""

from __future__ import annotations

from collections.abc import Sequence
from functools import lru_cache

import numpy as np

from tuibrdf.core.conventions import fmt_value
from tuibrdf.core.directions import sincos_deg
from tuibrdf.render.braille import BrailleCanvas, curve_layers, draw_legend
from tuibrdf.render.colormap import LOG_DECADES
from tuibrdf.render.curves import SIDE_MARKERS, curve_color
from tuibrdf.render.text import LIGHT_RGB

GUIDE = "color(244)"
#: the light in the sections: the colour of its mark on the map and of its line in the solid
INCIDENT = "#{:02x}{:02x}{:02x}".format(*LIGHT_RGB)
CELL_ASPECT = 2.0  # a terminal cell is about twice as tall as it is wide
#: side A and side B of a comparison (:data:`.curves.SIDE_MARKERS`) on the braille canvas: dot
#: pattern and ASCII marker
SIDE_PATTERNS = ("solid", "dotted")
SIDE_ASCII = ("*", "+")


def circle_step(vmax: float) -> float:
    """A 1-2-5 step giving 2 to 5 guide circles up to ``vmax``."""
    if vmax <= 0:
        return 1.0
    e = 10.0 ** np.floor(np.log10(vmax))
    for m in (0.2, 0.5, 1.0, 2.0, 5.0):
        if vmax / (m * e) <= 5:
            return m * e
    return 10 * e  # not reached: vmax / (5e) < 2


def radius(values: np.ndarray, vmax: float, log: bool, decades: float) -> np.ndarray:
    """Plot radius of ``values``: the value itself, or the log position in [0, 1]."""
    v = np.asarray(values, dtype=float)
    if not log:
        return v
    # values at or below the centre value (zeros included) sit at the centre; lo > 0 even for
    # a subnormal vmax, whose vmax·10⁻³ underflows to 0 (log10(0) would warn)
    lo = max(vmax * 10.0**-decades, 5e-324)
    r = 1.0 + np.log10(np.maximum(v, lo) / vmax) / decades
    return np.clip(np.where(v > lo, r, 0.0), 0.0, 1.0)


def caption_parts(caption: str) -> list[tuple[str, int]]:
    """A caption as title parts: the maximum stays, the circle spacing may go (as a whole:
    a cropped "circles every 0.1" would read "circles every 0")."""
    first, *rest = caption.split(" · ")
    return [(first, 0), *((r, 1) for r in rest)]


def plot_window(width: int, height: int, rmax: float) -> tuple[float, float, float]:
    """``(xr, y0, y1)``: the data window of a ``width × height`` polar plot of radius
    ``rmax`` (x in [−xr, xr], y in [y0, y1]); equal aspect: one data unit spans the same length
    in x and y on screen."""
    span = rmax * 1.08
    k = max(2 * span / width, span / (CELL_ASPECT * height))
    y0 = -0.03 * rmax
    return k * width / 2, y0, y0 + k * CELL_ASPECT * height


def angle_at(col: int, row: int, width: int, height: int) -> float | None:
    """The signed polar angle θ (degrees from straight up, positive to the right) of the cell
    ``(col, row)`` of a ``width × height`` polar plot, or None below the horizon line.  The
    window scales with the radius, so the angle does not depend on it."""
    xr, y0, y1 = plot_window(width, height, 1.0)
    x = -xr + (col + 0.5) / width * 2 * xr
    y = y1 - (row + 0.5) / height * (y1 - y0)
    if y < 0:
        return None
    return float(np.degrees(np.arctan2(x, y)))


@lru_cache(maxsize=16)
def guide_dots(width: int, height: int, xr: float, y0: float, y1: float, rmax: float,
               guides: tuple[float, ...]) -> np.ndarray:
    """The dots of the guides (horizon line and circles) as layer 0 of an empty canvas: the
    same for every frame whose window and circles are the same (a θi step of a model whose
    peak does not change), so drawn once (read-only: copied onto each canvas)."""
    canvas = BrailleCanvas(width, height, (-xr, xr), (y0, y1))
    guide = canvas.layer(GUIDE, "sparse", ".")
    # every guide in one polyline call (NaN between pieces): one pass of numpy, not one each
    xs, ys = [np.array([-rmax, rmax])], [np.zeros(2)]
    for g in guides:
        x, y = canvas.arc_points(0.0, 0.0, float(g), -90.0, 90.0)
        xs += [np.array([np.nan]), x]
        ys += [np.array([np.nan]), y]
    canvas.polyline(np.concatenate(xs), np.concatenate(ys), guide)
    canvas.owner.flags.writeable = False
    return canvas.owner


def polar_canvas(
    curves: Sequence[tuple],
    width: int,
    height: int,
    *,
    theta_i_deg: float | None = None,
    log: bool = False,
    decades: float = LOG_DECADES,
    color: str = "truecolor",
    vmax: float | None = None,
    charset: str = "braille",
    zoom: float = 1.0,
) -> tuple[BrailleCanvas, str]:
    """The polar plot of ``curves`` (:data:`.curves.Curve`) on a ``width × height`` canvas;
    returns ``(canvas, caption)``.  ``zoom`` > 1 magnifies about the origin (what leaves the
    window is clipped; the caption says ×zoom)."""
    own = max((float(np.max(c[2])) for c in curves), default=0.0)
    vmax = max(own, vmax or 0.0)
    vmax = vmax if vmax > 0 else 1.0  # an all-zero curve still gets a unit circle
    if log:
        rmax, guides = 1.0, [1.0 - k / decades for k in range(int(decades))]
        caption = (f"section max {fmt_value(own)} · log, circles every decade below "
                   f"{fmt_value(vmax)}")
    else:
        step = circle_step(vmax)
        guides = list(step * np.arange(1, int(np.floor(vmax / step + 1e-9)) + 1))
        rmax = max(vmax, guides[-1] if guides else vmax)
        caption = f"section max {fmt_value(own)} · circles every {fmt_value(step)}"
    if zoom != 1.0:  # after the maximum: the circle spacing goes first in a narrow title
        first, sep, rest = caption.partition(" · ")
        caption = f"{first} · zoom ×{zoom:.3g}{sep}{rest}"
    xr, y0, y1 = plot_window(width, height, rmax / zoom)  # zoom ≥ 1/8 (ViewerState.zoom_by)
    canvas = BrailleCanvas(width, height, (-xr, xr), (y0, y1), color=color, charset=charset)
    canvas.layer(GUIDE, "sparse", ".")  # layer 0
    canvas.owner[...] = guide_dots(width, height, xr, y0, y1, rmax, tuple(guides))
    if theta_i_deg is not None:
        s, c = sincos_deg(float(theta_i_deg))
        light = canvas.layer(INCIDENT, "solid", "#")
        canvas.polyline(np.array([0.0, -float(s) * rmax]), np.array([0.0, float(c) * rmax]),
                        light)
    colors = [c[4] if len(c) > 4 else curve_color(c[0], j) for j, c in enumerate(curves)]
    if any(len(c) > 3 for c in curves):
        # a compare side's own style (curves.side_curves): A and B differ in every colour
        # mode, by hue, dot pattern and marker.  A cell shows its last layer's colour (and
        # ASCII marker): the curves go on in decreasing order of their largest radius, so the
        # smaller lobe, inside the larger one, is drawn last and keeps its cells
        ids = [0] * len(curves)
        tops = [float(np.max(radius(c[2], vmax, log, decades), initial=0.0)) for c in curves]
        for j in sorted(range(len(curves)), key=lambda j: -tops[j]):
            k = SIDE_MARKERS.index(curves[j][3])
            ids[j] = canvas.layer(colors[j], SIDE_PATTERNS[k], SIDE_ASCII[k])
    else:
        ids = curve_layers(canvas, [c[:3] for c in curves], colors)
    for (_, thetas, vals, *_style), lid in zip(curves, ids, strict=True):
        r = radius(vals, vmax, log, decades)
        s, c = sincos_deg(np.asarray(thetas, dtype=float))
        canvas.polyline(r * s, r * c, lid)
    if len(curves) > 1:
        draw_legend(canvas, [c[:3] for c in curves], ids)
    return canvas, caption


def fwhm_text(width) -> str:
    """``FWHM 6.6°`` (``FWHM 0.17°`` below 1°) of a width in degrees from the core
    (:func:`tuibrdf.core.views.sections.fwhm`: the crossings on the function), or ``""`` for
    none (NaN or None)."""
    if width is None or not np.isfinite(float(width)):
        return ""
    w = float(width)
    return f"FWHM {w:.2f}°" if w < 1.0 else f"FWHM {w:.1f}°"
