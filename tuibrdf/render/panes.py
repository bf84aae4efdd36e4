"""Panes: one :class:`~tuibrdf.core.views.frame.FrameResult` in, Rich renderables out.

Every number a pane shows comes from the result, so the panes agree: the map's title, its
colour bar's top, the solid's scale and the status line show the same peak
(:func:`shown_peak`: for an RGB model the luminance ``Y``, or the largest channel when the map
shows the channels in colour, and the text says which) and the same scale (:func:`shown_scale`:
the peak, or the largest value at θ ≤ 89° (drawn, or a shown lobe) when the peak is above 89° or
unbounded, "f → ∞"; :mod:`tuibrdf.core.sphere.horizon`); the cross-sections say "section max" (the
largest value along the two planes, below the peak when it lies off them).  In compare mode
both maps share one colour scale topped by the larger of the two scales, and the bar says
whose it is.

=================  =================================================================
:func:`pane`       dispatch by view name (``map``, ``incidence``, ``perpendicular``,
                   ``solid``, ``albedo``, ``extra``: the request's lit or
                   half/difference view; plus ``diff`` in compare mode)
:func:`stats_text` the status line's numbers: albedo, energy flag, peak and direction
=================  =================================================================
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from rich.console import Group, RenderableType
from rich.text import Text

from tuibrdf.core.conventions import decimals_for, fmt_error, fmt_value, luminance
from tuibrdf.core.display import DISPLAY
from tuibrdf.core.numerics import snapped_rint
from tuibrdf.core.sphere.horizon import HORIZON_DEG, Horizon, PeakScale
from tuibrdf.core.sphere.peak import Peak
from tuibrdf.core.views.frame import CURVE_THETAS, SECTION_THETAS, FrameResult, SideFrame
from tuibrdf.core.views.hemimap import geometry
from tuibrdf.render import VIEW_TITLES
from tuibrdf.render.colormap import (
    DEFAULT_LEVELS,
    LOG_DECADES,
    Scale,
    colorbar,
    colorize,
    tick_line,
)
from tuibrdf.render.curves import CHANNEL_WORDS, side_curves
from tuibrdf.render.halfblock import HalfBlockImage, Mark
from tuibrdf.render.sections import caption_parts, fwhm_text, polar_canvas
from tuibrdf.render.text import (
    INCIDENT_MARK,
    MIRROR_MARK,
    RING_RGB,
    first_fitting,
    mark_legend,
    phi_deg_text,
    title,
    where,
)

#: the probe's mark on the map (issue 13 §4)
PROBE_MARK = dict(glyph="+", ascii="+", rgb=(0, 230, 230))

SIDE_LABELS = ("A", "B")
#: how a section's caption names the curves of an RGB model (Look.channel): Y the luminance,
#: as the status line's "(Y)" peak, a channel as the peak's
CHANNEL_TAGS = {"lum": "Y", **CHANNEL_WORDS}
#: diverging palette of the difference map: B's violet (B larger) – dark grey (equal) – A's
#: orange (A larger), the sides' own hues (render.curves.SIDE_HUES); zero is neutral and
#: dark, so a small difference does not glare
DIVERGING = ((178, 102, 255), (40, 40, 40), (255, 140, 26))


@dataclass(frozen=True)
class Look:
    """How the numbers are drawn (none of it changes a number); the defaults are
    :data:`~tuibrdf.core.display.DISPLAY`'s."""

    color: str = "truecolor"  # truecolor | 256 | none
    cmap: str = DISPLAY.cmap
    log: bool = False
    levels: int = DEFAULT_LEVELS
    rgb_mode: str = "auto"  # auto | color | luminance
    azimuth: float = DISPLAY.azimuth.default  # the 3D solid's camera
    elevation: float = DISPLAY.elevation.default
    exposure: float = DISPLAY.exposure.default  # the lit views' tone mapping (core/views/lit.py)
    gamma: float = DISPLAY.gamma.default
    charset: str = "braille"  # the sections and line plots (render/braille.py)
    #: the curves of an RGB model (sections, albedo): rgb (three) | lum | R | G | B
    channel: str = "rgb"
    #: the 3D solid's and the sections' magnification (the viewer's mouse wheel)
    zoom: float = 1.0
    #: the θh×θd slice's own scale (None: as ``log``; the viewer's default is log)
    slice_log: bool | None = None

    @property
    def rgb(self) -> str:
        """RGB pictures: channels in colour with the grey map, else the luminance (auto)."""
        if self.rgb_mode == "auto":
            return "color" if self.cmap == "grey" else "luminance"
        return self.rgb_mode


#: how the texts name a scale that is not the peak (:mod:`tuibrdf.core.sphere.horizon`)
CAP_TEXT = f"max θ≤{HORIZON_DEG:g}°"


def _mode(view: str, look: Look) -> str:
    return "luminance" if view == "solid" else look.rgb


def shown_peak(side: SideFrame, view: str, look: Look) -> Peak:
    """The peak the pictures of ``view`` show (the solid: the luminance's)."""
    return side.peak_for(_mode(view, look))


def shown_scale(side: SideFrame, view: str, look: Look) -> PeakScale | None:
    """The top of the scale the picture of ``view`` (map or solid) is drawn on: the value of
    :func:`shown_peak`, or the largest value it draws at θ ≤ 89° when that peak is above 89°
    or unbounded (``capped``); None for a view without one."""
    return side.scale_for(look.rgb, "solid" if view == "solid" else "map")


def peak_horizon(side: SideFrame, view: str, look: Look) -> Horizon:
    """Where :func:`shown_peak` is (``kind == "unbounded"``: f → ∞)."""
    return side.peak_horizon(_mode(view, look))


def scale_text(scale: PeakScale, short: bool = False) -> str:
    """``scale: max θ≤89° 513`` (``scale 513 (θ≤89°)`` short), with the channel for RGB: the
    largest value at θ ≤ 89° (:meth:`~tuibrdf.core.views.frame.SideFrame.scale_for`)."""
    ch = channel_tag(scale)
    if short:
        return f"scale {fmt_value(scale.value)}{ch} (θ≤{HORIZON_DEG:g}°)"
    return f"scale: {CAP_TEXT} {fmt_value(scale.value)}{ch}"


def toward_text(hz: Horizon) -> str:
    """``φ=0°``: the azimuth along which f grows without bound (whole degrees)."""
    ph = round(hz.toward_deg)
    return f"φ={ph + 360 if ph <= -180 else ph}°"


def _label(res: FrameResult, k: int) -> str:
    name = res.sides[k].material.label
    return name if len(res.sides) == 1 else f"{SIDE_LABELS[k]}: {name}"


def _unit(cosine: bool) -> str:
    """f and f·cos θr are both in sr⁻¹ (the cosine has no unit); the title says which."""
    return "sr⁻¹"


def channel_tag(peak: Peak | PeakScale) -> str:
    """`` (Y)``, `` (red)``, `` (green)``, `` (blue)`` for an RGB model's peak (or scale),
    else ``""``."""
    return f" ({CHANNEL_WORDS.get(peak.label, peak.label)})" if peak.label else ""


def peak_text(peak: Peak, cosine: bool, ps: Horizon | PeakScale | None = None,
              short: bool = False) -> str:
    """``f peak 425 sr⁻¹`` (``… (Y)`` or ``(red)`` for an RGB model); ``f → ∞ toward the
    horizon`` when ``ps`` (where the peak is) says it is unbounded."""
    what = "f·cosθr" if cosine else "f"
    ch = channel_tag(peak)
    if ps is not None and ps.kind == "unbounded":
        return f"{what} → ∞ {'at' if short else 'toward the'} horizon{ch}"
    if short:
        return f"{what} peak {fmt_value(peak.value)}{ch}"
    return f"{what} peak {fmt_value(peak.value)} {_unit(cosine)}{ch}"


def albedo_text(a, error=None) -> str:
    """3 significant digits, or fewer with ``±error`` when the error estimate reaches the third
    (the digits shown follow the error)."""
    if a is None:
        return "…"
    if isinstance(a, tuple) and len(set(a)) == 1:
        a = a[0]  # R = G = B (a grey model): one value
        error = None if error is None else float(np.max(np.asarray(error, dtype=float)))
    vals = a if isinstance(a, tuple) else (a,)
    top = max(abs(float(x)) for x in vals)
    err = None if error is None else float(np.max(np.asarray(error, dtype=float)))
    # the third significant digit's unit; ≥ 1e-300 so that log10 of 0 is never taken
    unit = 10.0 ** (np.floor(np.log10(max(top, 1e-300))) - 2)
    if err is None or err < 0.5 * unit:
        text = [fmt_value(x) for x in vals]
        tail = ""
    else:
        d = decimals_for(err)
        text = [f"{float(x):.{d}f}" for x in vals]
        tail = f"±{fmt_error(err, d)}"  # the estimate plus the rounding of the digits shown
    return ("(" + ",".join(text) + ")" if isinstance(a, tuple) else text[0]) + tail


# ----------------------------------------------------------------------------------- map
def _top(values: np.ndarray, rgb_mode: str) -> float:
    """The largest value a picture of ``values`` draws (its luminance for an RGB picture not
    in ``"color"`` mode); 0 when none is finite."""
    v = np.asarray(values, dtype=float)
    if v.ndim == 3 and v.shape[-1] == 3 and rgb_mode != "color":
        v = luminance(v)
    finite = v[np.isfinite(v)]
    return float(finite.max()) if finite.size else 0.0


@lru_cache(maxsize=16)
def ring_mask(px_w: int, px_h: int) -> np.ndarray:
    """Pixels outside the disc that touch it (8-neighbourhood): the horizon ring."""
    inside = geometry(px_w, px_h).inside
    grown = inside.copy()
    grown[1:] |= inside[:-1]
    grown[:-1] |= inside[1:]
    g2 = grown.copy()
    g2[:, 1:] |= grown[:, :-1]
    g2[:, :-1] |= grown[:, 1:]
    ring = g2 & ~inside
    ring.setflags(write=False)
    return ring


def map_pane(res: FrameResult, k: int, w: int, h: int, look: Look) -> Group:
    """Title, half-block disc (× on the mirror direction, o on the light's) and colour bar,
    on the frame's peak scale (shared by both sides in compare mode)."""
    side = res.sides[k]
    data, info = side.map
    px_h, px_w = data.shape[:2]
    cosine = res.request.cosine
    peak, ps = shown_peak(side, "map", look), peak_horizon(side, "map", look)
    scales = [shown_scale(s, "map", look) for s in res.sides]  # maps: never None
    k_top = max(range(len(scales)), key=lambda j: scales[j].value)
    top = scales[k_top].value
    # the bar's note: whose scale (compare mode), and that values above it are clipped
    whose = (SIDE_LABELS[k_top] + " " + ("peak" if not scales[k_top].capped else CAP_TEXT)
             if len(res.sides) > 1 else (CAP_TEXT if scales[k_top].capped else ""))
    # pixels above a scale that is not the peak (closer to the horizon than 89°: the CLI's
    # largest maps) take the top colour
    clipped = any(sc.capped and _top(s.map[0], look.rgb) > sc.value
                  for s, sc in zip(res.sides, scales, strict=True))
    note = f"({whose}{', clipped' if clipped else ''})" if whose else ""
    scale = Scale(top if top > 0 else 1.0, look.log)  # an all-zero BRDF: the lowest colour
    col = colorize(data, look.cmap, levels=look.levels, log=look.log, rgb_mode=look.rgb,
                   scale=scale)
    ring_index = len(col.palette)
    index = np.where(ring_mask(px_w, px_h), ring_index, col.index)
    pal = np.concatenate([col.palette, np.array([RING_RGB], dtype=np.uint8)])
    marks = [Mark(info.mirror_px[0] // 2, info.mirror_px[1], **MIRROR_MARK)]
    r, c = info.incident_px
    if (r // 2, c) != (marks[0].row, marks[0].col):
        marks.append(Mark(r // 2, c, **INCIDENT_MARK))
    if res.request.probe is not None:  # the probe, over the other marks
        r, c = geometry(px_w, px_h).to_pixel(np.asarray(res.request.probe, dtype=float))
        marks = [mk for mk in marks if (mk.row, mk.col) != (r // 2, c)]
        marks.append(Mark(r // 2, c, **PROBE_MARK))
    image = HalfBlockImage(index, pal, marks, color_system=look.color, ring=ring_index,
                           shades=col.shades)
    own = shown_scale(side, "map", look)
    bar_cmap = "grey" if (data.ndim == 3 and look.rgb == "color") else look.cmap
    bar = colorbar(scale, bar_cmap, w, levels=look.levels, unit=_unit(cosine),
                   color_system=look.color, note=note)
    t = res.request.theta_i
    lead = [(_label(res, k), 2), (f"θi={t:g}°", 3)]
    if not own.capped and info.vmin >= peak.value * (1.0 - 1e-12):  # Lambert: no "the" peak
        what = "f·cosθr" if cosine else "f"
        parts = [[(f"{what} = {fmt_value(peak.value)} {_unit(cosine)}", 0), ("everywhere", 1)]]
    elif not own.capped:
        parts = [[(peak_text(peak, cosine), 0), (f"at {where(peak.theta_deg, peak.phi_deg)}", 1)]]
    else:
        # the peak above 89° (or none: f → ∞) and the scale the map is drawn on, both named
        at = (f"at {toward_text(ps)}" if ps.kind == "unbounded"
              else f"at {where(peak.theta_deg, peak.phi_deg)}")
        parts = [[(peak_text(peak, cosine, ps, short), 0), (at, 1),
                  (scale_text(own, short), 0)] for short in (False, True)]
    head_line = first_fitting([lead + p + [(mark_legend(look.color), 4)] for p in parts], w)
    return Group(head_line, image, bar)


def diff_pane(res: FrameResult, w: int, h: int, look: Look) -> Group:
    """A − B (luminance for RGB) on a diverging scale symmetric about 0: B's hue where B is
    larger, A's where A is, dark grey at zero (:data:`DIVERGING`), with the horizon ring, the
    mirror and light marks and a labelled colour bar.  Its scale is the largest |A − B| of
    the functions (:attr:`FrameResult.diff_max`), not of the pixels, so it does not change
    with the window's size."""
    va, vb = (s.map[0] for s in res.sides)
    info = res.sides[0].map[1]
    d = (luminance(va) if va.ndim == 3 else va) - (luminance(vb) if vb.ndim == 3 else vb)
    finite = np.isfinite(d)
    largest = float(np.max(np.abs(d[finite]))) if finite.any() else 0.0
    at = ""
    if res.diff_max is not None:  # on the function; the pixels never exceed it by much
        largest, th, ph = max(res.diff_max[0], largest), res.diff_max[1], res.diff_max[2]
        at = f"at {where(th, ph)}"
    m = largest if largest > 0 else 1.0  # identical sides: all zero, no division by zero
    t = np.clip(d / m * 0.5 + 0.5, 0.0, 1.0)
    levels = DIFF_LEVELS
    # identical sides give t = ½ exactly: the middle level (levels is odd), decided on the
    # snapped value (core.numerics.snap), as every level of every picture
    idx = np.where(finite, snapped_rint(np.nan_to_num(t) * (levels - 1)), -1).astype(np.int64)
    what = " of f·cosθr" if res.request.cosine else ""
    ch = " (Y)" if va.ndim == 3 or vb.ndim == 3 else ""
    head = title([("A − B", 1), (f"max |Δ| {fmt_value(largest)} {_unit(False)}{ch}", 0),
                  (what, 3), (at, 2)], w)
    m_t = fmt_value(largest)
    # the sides' words go first in a narrow pane (the title and the legend say them)
    lo_t, hi_t = next(((lo, hi) for lo, hi in ((f"-{m_t} B>A", f"A>B +{m_t}"),
                                              (f"-{m_t}", f"+{m_t}"))
                       if len(lo) + 1 + len(hi) <= w), (f"-{m_t}", f"+{m_t}"))
    ticks = Text(tick_line(w, lo_t, "0", hi_t))
    px_h, px_w = d.shape
    if look.color == "none":  # no colour to tell the sign: characters that say it
        marks = [(info.mirror_px[0] // 2, info.mirror_px[1], MIRROR_MARK["ascii"]),
                 (info.incident_px[0] // 2, info.incident_px[1], INCIDENT_MARK["ascii"])]
        return Group(head, signed_text(np.where(finite, t - 0.5, np.nan), marks),
                     title([("+# A>B  -= B>A  . same", 0), (mark_legend("none"), 1)], w),
                     ticks)
    pal = diverging_palette(levels)
    ring_index = len(pal)
    index = np.where(ring_mask(px_w, px_h), ring_index, idx)
    pal = np.concatenate([pal, np.array([RING_RGB], dtype=np.uint8)])
    marks = [Mark(info.mirror_px[0] // 2, info.mirror_px[1], **MIRROR_MARK)]
    r, c = info.incident_px
    if (r // 2, c) != (marks[0].row, marks[0].col):
        marks.append(Mark(r // 2, c, **INCIDENT_MARK))
    img = HalfBlockImage(index, pal, marks, color_system=look.color, ring=ring_index)
    bar_t = (np.arange(w) + 0.5) / w
    bar_idx = snapped_rint(bar_t * (levels - 1)).astype(np.int64)[None, :].repeat(2, axis=0)
    bar = HalfBlockImage(bar_idx, pal[:-1], color_system=look.color)
    return Group(head, img, bar, ticks)


#: levels of the difference map: odd, so that zero is one level exactly
DIFF_LEVELS = 33


@lru_cache(maxsize=4)
def diverging_palette(levels: int) -> np.ndarray:
    """``(levels, 3)`` uint8: :data:`DIVERGING` from B's end through dark grey to A's,
    linear in each channel (read-only)."""
    stops = np.array(DIVERGING, dtype=float)
    x = np.linspace(0, 1, levels)
    pal = np.stack([np.interp(x, [0, 0.5, 1], stops[:, c]) for c in range(3)], -1)
    out = snapped_rint(pal).astype(np.uint8)
    out.setflags(write=False)
    return out


def signed_text(d: np.ndarray, marks=()) -> Text:
    """The difference map in plain text, one character per cell (two pixel rows): ``.``
    within 5 % of the largest |Δ| of each other, ``+``/``#`` A larger (under/over half of
    it), ``-``/``=`` B larger; blank outside the disc; ``marks`` ``(row, col, char)`` over
    the cells (the mirror and light marks)."""
    if d.shape[0] % 2:
        d = np.vstack([d, np.full((1, d.shape[1]), np.nan)])
    pair = d.reshape(d.shape[0] // 2, 2, d.shape[1])
    ok = np.isfinite(pair)
    inside = ok.any(axis=1)
    # the mean of the finite halves; max(count, 1): no 0/0 outside the disc
    v = np.where(ok, pair, 0.0).sum(axis=1) / np.maximum(ok.sum(axis=1), 1)
    chars = np.full(v.shape, " ")
    chars[inside] = "."
    chars[inside & (v > 0.025)] = "+"
    chars[inside & (v > 0.25)] = "#"
    chars[inside & (v < -0.025)] = "-"
    chars[inside & (v < -0.25)] = "="
    for r, c, ch in marks:
        if 0 <= r < chars.shape[0] and 0 <= c < chars.shape[1]:
            chars[r, c] = ch
    return Text("\n".join("".join(row) for row in chars), no_wrap=True)


# ----------------------------------------------------------------------- cross-sections
def section_pane(res: FrameResult, plane: str, w: int, h: int, look: Look) -> Group:
    """The sides' values along ``plane`` (R, G, B curves for an RGB model alone) on a braille
    canvas, both sides on one radius scale; the caption gives the section max.
    ``perpendicular`` is the great circle through the frame's peak (``peaks[0]``) at the
    request's section azimuth, the peak straight up (``sections["peak"]``)."""
    compare = len(res.sides) > 1
    key = "peak" if plane == "perpendicular" else plane
    curves = [(label, SECTION_THETAS, v, *style) for label, v, *style in side_curves(
        [(s.material.label, s.sections[key]) for s in res.sides], look.channel)]
    vmax = max(max(s.section_max, float(np.max(s.sections["peak"]))) for s in res.sides)
    t = res.request.theta_i
    canvas, caption = polar_canvas(curves, w, h - 1, log=look.log, color=look.color,
                                   theta_i_deg=t if plane == "incidence" else None, vmax=vmax,
                                   charset=look.charset, zoom=look.zoom)
    az = res.request.section_azimuth
    if plane == "perpendicular":
        s0 = res.sides[0]
        th, ph = s0.section_center
        name = "perp." if az == 90.0 else f"ψ={az:g}°"
        # where the plane passes may go (the map's title has the peak's direction): a narrow
        # pane keeps "section max …" whole rather than cropping it to "sec"
        if s0.peaks[0].theta_deg > HORIZON_DEG:
            # the section across a peak on the horizon is the horizon: it goes through the
            # peak's direction lowered to 89° instead, and says so
            at = f"θ={th:g}° φ={phi_deg_text(ph)}°"
            whats = [f"{name} through {at}, below the peak", f"{name} {at} below peak", name]
        else:
            whats = [f"{name} through peak θ={round(th, 1):g}° φ={phi_deg_text(ph)}°", name]
    else:
        whats = [plane]
    if compare:
        a, b = (s.material.label for s in res.sides)
        parts = [(None, 0), (f"A {a} vs B {b}", 2)]
    else:
        fn = "f·cosθr" if res.request.cosine else "f"
        if plane == "perpendicular":
            width_s = fwhm_text(res.sides[0].sections["fwhm"])
            # the width across the lobe is the point of this view (issue 13 §1): it goes
            # before the model's name (which the panel shows) when the title is cropped
            parts = [(res.sides[0].material.label, 2), (f"θi={t:g}°", 4), (None, 0),
                     (width_s, 1), (fn, 5)]
        else:
            parts = [(res.sides[0].material.label, 2), (f"θi={t:g}°", 3), (None, 0),
                     (f"(φ {phi_deg_text(res.request.phi_i)}°|"
                      f"{phi_deg_text(res.request.phi_i + 180)}°)", 4),
                     (fn, 1)]
    cap = caption_parts(caption)
    shown = "lum" if compare and look.channel == "rgb" else look.channel  # (side_curves)
    if shown not in ("rgb", "all") and any(s.sections[key].ndim == 2 for s in res.sides):
        # an RGB model's curves are its luminance or one channel (C): say which, or
        # "section max" reads as a disagreement with the map's "(red)" peak
        cap[0] = (f"{cap[0][0]} ({CHANNEL_TAGS.get(shown, shown)})", 0)
    # narrower: "max 0.113" (the pane's title says it is a section) before any crop
    # the radial scale (max and circle spacing) is kept whole at every width (issue 36: at
    # 80×24 the spacing went first): narrower, "max" and a shorter log note, then without
    # the plane's name
    cap = [(t, 0) for t, _ in cap]
    short = [(t.replace("section max", "max", 1).replace(
        "log, circles every decade below", "log, decades below"), 0) for t, _ in cap]
    # the lobe's width whole first (then the longer wordings of where the plane passes)
    width_first = [(s, 0 if s and s.startswith("FWHM") else r) for s, r in parts]
    brief = [(t.replace("circles every", "circles"), r) for t, r in cap]
    variants = [[(what if s is None else s, r) for s, r in first] + c
                for first in (width_first, parts) for what in whats for c in (cap, brief)]
    variants.append([(whats[-1] if s is None else s, r) for s, r in parts] + short)
    bare = [(whats[-1] if s is None else s, 1 if s is None else r) for s, r in parts]
    tiny = [(re.sub(r"^log, decades below .*", "log decades", t.replace(
        "circles every", "circles")), 0) for t, _ in short]
    named = [(whats[-1] if s is None else s, r) for s, r in parts]
    variants += [named + tiny, bare + short, bare + tiny]
    return Group(first_fitting(variants, w), canvas)


# ---------------------------------------------------------------- lit, half/difference
def extra_pane(res: FrameResult, k: int, w: int, h: int, look: Look) -> RenderableType:
    """The request's extra view (sphere, plane, slice, θh or θd curve) of side ``k``; in
    compare mode both sides on one scale (the same exposure, the larger maximum)."""
    from tuibrdf.render import halfdiff_view, lit_view

    req, side = res.request, res.sides[k]
    name = _label(res, k)
    if side.extra_problem is not None:  # (the current values' numbers are on the status line)
        return Text(f"{name}: no {VIEW_TITLES[req.extra]}: {side.extra_problem}")
    drawn = [s for s in res.sides if s.extra is not None]  # the shared scale: sides drawn
    if req.extra in ("sphere", "plane"):
        rad, mask = side.extra
        return lit_view.lit_picture(req.extra, name, req.theta_i, rad, mask, w,
                                    exposure=look.exposure, gamma=look.gamma, color=look.color)
    if req.extra == "energy":
        from tuibrdf.render.energy_view import energy_picture

        return energy_picture(name, side.extra[0], w, h, cmap=look.cmap, levels=look.levels,
                              color=look.color)
    if req.extra == "slice":
        f, valid, th, td = side.extra
        vmax = max(halfdiff_view.slice_scale(s.extra, req.phi_d) for s in drawn)
        return halfdiff_view.slice_picture(name, f, valid, th, td, w, h, phi_d_deg=req.phi_d,
                                           sqrt_h=req.sqrt_h, vmax=vmax,
                                           log=look.log if look.slice_log is None
                                           else look.slice_log,
                                           cmap=look.cmap, levels=look.levels,
                                           rgb_mode=look.rgb_mode, color=look.color)
    vmax = max(halfdiff_view.line_scale(req.extra, s.extra, req) for s in drawn)
    return halfdiff_view.line_picture(req.extra, name, side.extra, req.theta_d, req.theta_h,
                                      req.phi_d, vmax, w, h, log=look.log, color=look.color,
                                      charset=look.charset)


# --------------------------------------------------------------------------------- solid
def solid_pane(res: FrameResult, k: int, w: int, h: int, look: Look) -> Group:
    """Title and the photometric solid as half blocks, its radius scale the frame's peak."""
    from tuibrdf.render.solid import solid_image  # (as every view but the map's: when shown)

    side = res.sides[k]
    peak, sc = shown_peak(side, "solid", look), shown_scale(side, "solid", look)
    # compare mode: both solids on one radius scale, the larger of the two (as the maps share
    # one colour scale), so the smaller lobe is drawn smaller
    rmax = max(shown_scale(s, "solid", look).value for s in res.sides)
    index, pal = solid_image(side.solid, res.request.theta_i, w, 2 * (h - 1), rmax=rmax,
                             phi_i_deg=res.request.phi_i,
                             cmap=look.cmap, log=look.log, azimuth_deg=look.azimuth,
                             elevation_deg=look.elevation, zoom=look.zoom)
    what = "f·cosθr·wo" if res.request.cosine else "f·wo"
    if look.log:
        what += f" (log, {LOG_DECADES:g} decades)"
    ch = channel_tag(peak)
    if sc.capped:  # the radius scale is not the peak: say which it is, and that it clips
        ps = peak_horizon(side, "solid", look)
        solid = np.asarray(side.solid, dtype=float)
        over = _top(luminance(solid) if solid.ndim == 2 else solid, "color") > sc.value
        num = [(f"solid {what}, {scale_text(sc)}{', clipped' if over else ''}", 0),
               (peak_text(peak, res.request.cosine, ps, short=True), 1)]
    else:
        num = [(f"solid {what}, peak {fmt_value(peak.value)}{ch}", 0)]
    if len(res.sides) > 1:
        k_top = max(range(len(res.sides)),
                    key=lambda j: shown_scale(res.sides[j], "solid", look).value)
        num.append((f"(scale: {SIDE_LABELS[k_top]}'s)", 1))
    head = title([(_label(res, k), 2), (f"θi={res.request.theta_i:g}°", 3), *num,
                  (f"az {look.azimuth:g}° el {look.elevation:g}°", 4)], w)
    return Group(head, HalfBlockImage(index, pal, color_system=look.color))


# ---------------------------------------------------------------------------- albedo curve
def albedo_pane(res: FrameResult, w: int, h: int, look: Look) -> RenderableType:
    """a(θi) over 0–90° per side (channels for one RGB model, luminance in compare mode), θi
    marked, the line a = 1 drawn; flagged when a curve exceeds 1 by more than its error estimate
    (:func:`tuibrdf.core.sphere.albedo.exceeds_one`)."""
    failed = [f"{s.material.label}: no albedo curve a(θi) over 0–90°: {s.curve_problem}"
              for s in res.sides if s.curve_problem is not None]
    if failed:  # (the albedo at the current θi is on the status line)
        return Text("\n".join(failed))
    if any(s.curve is None for s in res.sides):
        return Text("computing a(θi) over 0–90° …", justify="center")
    t = res.request.theta_i
    curves = side_curves([(s.material.label, s.curve) for s in res.sides], look.channel)
    top = max(float(np.max(s.curve)) for s in res.sides)
    over = any(s.curve_exceeds_one() for s in res.sides)
    flag = f"a>1 (max {fmt_value(top)}): not energy-conserving" if over else ""
    from tuibrdf.render.albedo_plot import albedo_plot

    plot = albedo_plot(CURVE_THETAS, curves, w, h - 1, theta_i_deg=t, color=look.color)
    if len(res.sides) == 1:
        s0 = res.sides[0]
        parts = [(s0.material.label, 2),
                 (f"a(θi={t:g}°) = {albedo_text(s0.albedo, s0.albedo_error)}", 0), (flag, 1)]
    else:
        parts = [("directional albedo a(θi) = ∫ f cos θr dω", 0), ("(line: a = 1)", 2),
                 (flag, 1)]
    style = "bold red" if over and look.color != "none" else ""
    return Group(title(parts, w, style=style), plot)


# ---------------------------------------------------------------------------------- both
def pane(view: str, res: FrameResult, k: int, w: int, h: int, look: Look) -> RenderableType:
    """The renderable of ``view`` for side ``k`` in ``w × h`` cells."""
    if view == "map":
        return map_pane(res, k, w, h, look)
    if view == "diff":
        return diff_pane(res, w, h, look)
    if view in ("incidence", "perpendicular"):
        return section_pane(res, view, w, h, look)
    if view == "solid":
        return solid_pane(res, k, w, h, look)
    if view == "albedo":
        return albedo_pane(res, w, h, look)
    if view == "extra":
        return extra_pane(res, k, w, h, look)
    raise ValueError(f"unknown pane {view!r}")


def stats_text(res: FrameResult, view: str, look: Look, terse: int = 0) -> Text:
    """``a(θi)=0.835  peak 0.703 (Y) at θ=90° φ=0°`` per side (``A: a=… B: a=…`` in compare
    mode), the albedo flagged in red when above 1 by more than its error estimate; for a
    narrow status line ``terse`` 1 leaves out the peak's direction and the scale (the map's bar
    says it), 2 the peak."""
    compare = len(res.sides) > 1
    line = Text()
    for k, side in enumerate(res.sides):
        tag = f"  {SIDE_LABELS[k]}:" if compare else " "
        a = albedo_text(side.albedo, side.albedo_error)
        line.append(f"{tag} {'a' if compare else 'a(θi)'}={a}")
        if side.albedo_exceeds_one():
            line.append(" >1 NOT energy-conserving", style="bold red")
        if terse >= 2:
            continue
        pk, ps = shown_peak(side, view, look), peak_horizon(side, view, look)
        sc = shown_scale(side, view, look) if view in ("map", "solid") else None
        what = "f·cos peak" if res.request.cosine else "peak"
        ch = channel_tag(pk)
        if ps.kind == "unbounded":  # no maximum: the finder's value would be an artefact
            fn = "f·cos" if res.request.cosine else "f"
            at = toward_text(ps)
            at = f"({at})" if compare else f"at {at}"
            line.append(f"  {fn} → ∞ toward the horizon{ch}{'' if terse else ' ' + at}")
        else:
            at = where(pk.theta_deg, pk.phi_deg)
            at = f"({at.replace('θ=', '').replace(' φ=', ',')})" if compare else f"at {at}"
            line.append(f"  {what} {fmt_value(pk.value)}{ch}{'' if terse else ' ' + at}")
        if sc is not None and sc.capped and not terse:  # (the map's bar says it too)
            line.append(f" · {scale_text(sc, short=compare)}")
    if compare:
        line.append_text(compare_text(res.numbers, terse))
    return line


def compare_text(n, terse: int = 0) -> Text:
    """Compare mode's numbers (:func:`tuibrdf.core.sphere.compare.compare`, the frame's
    :attr:`~tuibrdf.core.views.frame.FrameResult.numbers`): ``rel_l2 0.802 · max Δ −86 % of
    B's peak (62°,0°)``; ``rel_l2 …`` while they are computed (they come with the albedo)."""
    out = Text()
    if terse >= 2:  # the tersest status line (80 columns, RGB sides, the probe): no room
        return out
    if n is None:
        out.append("  rel_l2 …")
        return out
    ref = "A" if n.reference == "a" else "B"
    if n.rel_l2 is None:
        out.append(f"  rel_l2 — ({ref} is 0)")
        return out
    out.append(f"  rel_l2 {albedo_text(n.rel_l2, n.rel_l2_error)}", style="bold")
    out.append(f" ({ref} ref)" if terse else f" (vs {ref})")
    if n.max_diff is not None:
        at = "" if terse else f" ({n.max_diff_theta_o:.0f}°,{n.max_diff_phi_o:.0f}°)"
        out.append(f" · max Δ {100 * n.max_diff:+.3g}% of {ref} peak{at}")
    return out

