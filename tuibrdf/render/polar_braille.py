"""Polar cross-sections drawn straight from numpy on a braille canvas (:mod:`.braille`).

The same pictures as :mod:`.polar` (plotext), at a fraction of the cost (``scripts/
bench_plots.py``; numbers in ``docs/render.md``): curves ``r(θ)`` drawn at ``x = r sin θ``,
``y = r cos θ`` for ``θ ∈ [−90°, 90°]``, guide circles (1-2-5 steps, or one per decade in log
mode) and the horizon line, the incident direction as a line, one data unit the same length
on screen in x and y (a cell is twice as tall as wide).  Titles and captions are those of
:mod:`.polar`.

- :func:`section_view` takes the arguments of :func:`.polar.section_view` (a drop-in
  alternative for the planes through the normal);
- :func:`peak_section_view` draws the section through the lobe's peak
  (:mod:`tuibrdf.core.sections`): the great circle through the peak of the plane of incidence,
  turned by the *section azimuth* ψ about it (90° = perpendicular to the plane of incidence,
  the seed's "largeur … dans un plan perpendiculaire"; 0° = the plane of incidence itself).
  The plot puts the peak straight up: θ on the plot is the signed angle ``t`` from the peak
  along the section, so its width reads off directly.

``charset="ascii"`` gives one marker character per cell (:mod:`.braille`); each curve has its
own dot pattern as well as its colour, so plain text still tells the curves apart.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
from rich.console import Group

from ..core.evaluate import evaluate_resolved
from ..core.frame import incident, sincos_deg
from ..core.params import Model
from ..core.scene import PLANES, section_directions
from ..core.sections import PERPENDICULAR, center_direction, peak_in_plane, section_values
from .braille import BrailleCanvas, curve_layers, draw_legend
from .colormap import LOG_DECADES, fmt_value
from .polar import (
    CELL_ASPECT,
    caption_parts,
    channel_curves,
    curve_color,
    nice_step,
    radius,
)
from .text import title

GUIDE = "color(244)"
INCIDENT = "yellow"
#: samples along a section (1° steps, as :func:`.polar.section_curves`)
N_SAMPLES = 181

Curve = tuple[str, np.ndarray, np.ndarray]  # (label, θ degrees, values)


def section_curves(model: Model, values: dict[str, Any], theta_i_deg: float, plane: str, *,
                   n: int = N_SAMPLES, cosine: bool = False) -> list[Curve]:
    """The model's values along ``plane`` (through the normal): one curve, or R, G, B."""
    thetas = np.linspace(-90.0, 90.0, n)
    wo = section_directions(plane, thetas)
    f = np.asarray(evaluate_resolved(model, values, incident(theta_i_deg), wo), dtype=float)
    if cosine:
        f = f * (wo[:, 2][:, None] if f.ndim == 2 else wo[:, 2])
    return [(label, thetas, v) for label, v in channel_curves(model.name, f)]


def sections_max(model: Model, values: dict[str, Any], theta_i_deg: float,
                 cosine: bool = False) -> float:
    """The largest value over both planes (every channel): the common scale of the plots."""
    return max(float(np.max(v)) for plane in PLANES
               for _, _, v in section_curves(model, values, theta_i_deg, plane, cosine=cosine))


def plot_window(width: int, height: int, rmax: float) -> tuple[float, float, float]:
    """``(xr, y0, y1)``: the data window of a ``width × height`` polar plot of radius
    ``rmax`` (x in [−xr, xr], y in [y0, y1]); equal aspect, as :mod:`.polar`: one data unit
    spans the same length in x and y on screen."""
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


def polar_canvas(
    curves: Sequence[Curve],
    width: int,
    height: int,
    *,
    theta_i_deg: float | None = None,
    log: bool = False,
    decades: float = LOG_DECADES,
    color: str = "truecolor",
    vmax: float | None = None,
    charset: str = "braille",
) -> tuple[BrailleCanvas, str]:
    """The polar plot of ``curves`` on a ``width × height`` canvas; returns ``(canvas,
    caption)`` as :func:`.polar.polar_plot` returns ``(text, caption)``."""
    own = max((float(np.max(v)) for _, _, v in curves), default=0.0)
    vmax = max(own, vmax or 0.0)
    vmax = vmax if vmax > 0 else 1.0  # an all-zero curve still gets a unit circle
    if log:
        rmax, guides = 1.0, [1.0 - k / decades for k in range(int(decades))]
        caption = (f"section max {fmt_value(own)} · log, circles every decade below "
                   f"{fmt_value(vmax)}")
    else:
        step = nice_step(vmax)
        guides = list(step * np.arange(1, int(np.floor(vmax / step + 1e-9)) + 1))
        rmax = max(vmax, guides[-1] if guides else vmax)
        caption = f"section max {fmt_value(own)} · circles every {fmt_value(step)}"
    xr, y0, y1 = plot_window(width, height, rmax)
    canvas = BrailleCanvas(width, height, (-xr, xr), (y0, y1), color=color, charset=charset)
    guide = canvas.layer(GUIDE, "sparse", ".")
    # every guide in one polyline call (NaN between pieces): one pass of numpy, not one each
    xs, ys = [np.array([-rmax, rmax])], [np.zeros(2)]
    for g in guides:
        x, y = canvas.arc_points(0.0, 0.0, float(g), -90.0, 90.0)
        xs += [np.array([np.nan]), x]
        ys += [np.array([np.nan]), y]
    canvas.polyline(np.concatenate(xs), np.concatenate(ys), guide)
    if theta_i_deg is not None:
        s, c = sincos_deg(float(theta_i_deg))
        light = canvas.layer(INCIDENT, "solid", "#")
        canvas.polyline(np.array([0.0, -float(s) * rmax]), np.array([0.0, float(c) * rmax]),
                        light)
    colors = [curve_color(label, j) for j, (label, _, _) in enumerate(curves)]
    ids = curve_layers(canvas, curves, colors)
    for (_, thetas, vals), lid in zip(curves, ids, strict=True):
        r = radius(vals, vmax, log, decades)
        s, c = sincos_deg(np.asarray(thetas, dtype=float))
        canvas.polyline(r * s, r * c, lid)
    if len(curves) > 1:
        draw_legend(canvas, curves, ids)
    return canvas, caption


def section_view(
    plane: str,
    model: Model,
    values: dict[str, Any],
    theta_i_deg: float,
    width: int,
    height: int,
    *,
    color: str = "truecolor",
    log: bool = False,
    cosine: bool = False,
    charset: str = "braille",
) -> Group:
    """:func:`.polar.section_view` on the braille canvas: title line + polar plot of
    ``model`` in ``plane`` (``incidence`` or ``perpendicular`` through the normal), both planes
    on one scale."""
    curves = section_curves(model, values, theta_i_deg, plane, cosine=cosine)
    canvas, caption = polar_canvas(
        curves, width, height - 1, log=log, color=color, charset=charset,
        theta_i_deg=theta_i_deg if plane == "incidence" else None,
        vmax=sections_max(model, values, theta_i_deg, cosine))
    what = "f·cosθr" if cosine else "f"
    sides = "φ 180°|0°" if plane == "incidence" else "φ 270°|90°"
    head = title([(model.name, 2), (f"θi={theta_i_deg:g}°", 3), (plane, 0), (f"({sides})", 4),
                  (what, 1), *caption_parts(caption)], width)
    return Group(head, canvas)


def peak_section_curves(
    model: Model,
    values: dict[str, Any],
    theta_i_deg: float,
    azimuth_deg: float = PERPENDICULAR,
    *,
    n: int = N_SAMPLES,
    cosine: bool = False,
) -> tuple[list[Curve], float]:
    """``(curves, θ_peak)``: the model along the great circle through its in-plane peak
    (signed ``t`` from the peak over [−90°, 90°]; 0 below the horizon), and the peak's signed
    θr in degrees."""
    peak, _ = peak_in_plane(model, values, theta_i_deg)
    t = np.linspace(-90.0, 90.0, n)
    f, _ = section_values(model, values, theta_i_deg, center_direction(peak), t, azimuth_deg,
                          cosine=cosine)
    return [(label, t, v) for label, v in channel_curves(model.name, f)], peak


def peak_section_view(
    model: Model,
    values: dict[str, Any],
    theta_i_deg: float,
    width: int,
    height: int,
    *,
    azimuth_deg: float = PERPENDICULAR,
    color: str = "truecolor",
    log: bool = False,
    cosine: bool = False,
    charset: str = "braille",
) -> Group:
    """Title + polar plot of the section through the lobe's peak at section azimuth
    ``azimuth_deg`` (the peak straight up).  Its scale is the larger of its own maximum and the
    plane of incidence's, so it compares with the incidence plot; the title gives the peak's
    direction and the section's FWHM."""
    curves, peak = peak_section_curves(model, values, theta_i_deg, azimuth_deg, cosine=cosine)
    inc = section_curves(model, values, theta_i_deg, "incidence", cosine=cosine)
    vmax = max(float(np.max(v)) for _, _, v in inc)
    canvas, caption = polar_canvas(curves, width, height - 1, log=log, color=color,
                                   charset=charset, vmax=vmax)
    what = "f·cosθr" if cosine else "f"
    name = "perpendicular" if azimuth_deg == PERPENDICULAR else f"section ψ={azimuth_deg:g}°"
    t, v = curves[0][1], np.sum([c[2] for c in curves], axis=0)
    width_s = fwhm_text(t, v)
    (first, _), *rest = caption_parts(caption)
    head = title([(model.name, 2), (f"θi={theta_i_deg:g}°", 4),
                  (f"{name} through peak θ={abs(peak):.1f}°", 0), (width_s, 1), (what, 5),
                  (first, 0), *((r, 3) for r, _ in rest)], width)
    return Group(head, canvas)


def fwhm_text(t: np.ndarray, v: np.ndarray) -> str:
    """``FWHM 6.6°`` of the part around the maximum (linear interpolation of the crossings),
    or ``""`` for a flat or empty curve."""
    vmax = float(np.max(v))
    if vmax <= 0 or float(np.min(v)) >= 0.5 * vmax:
        return ""
    k = int(np.argmax(v))
    half = 0.5 * vmax
    i = k
    while i > 0 and v[i - 1] >= half:
        i -= 1
    j = k
    while j < len(v) - 1 and v[j + 1] >= half:
        j += 1
    # v[i-1] < half ≤ v[i]: the denominators are > 0
    lo = t[0] if i == 0 else t[i - 1] + (half - v[i - 1]) * (t[i] - t[i - 1]) / (v[i] - v[i - 1])
    hi = t[-1] if j == len(v) - 1 else t[j] + (half - v[j]) * (t[j + 1] - t[j]) / (v[j + 1] - v[j])
    return f"FWHM {float(hi - lo):.1f}°"
