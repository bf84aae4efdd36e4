"""Half/difference-angle views (:mod:`tuibrdf.core.views.halfdiff`) drawn from the frame's samples
(:func:`tuibrdf.render.panes.extra_pane`): the θh × θd image at fixed φd and the line plots
f(θh) at fixed θd, f(θd) at fixed θh.

**Image slice** (:func:`slice_picture`): θh along x (0° left … 90° right, uniform in √θh by
default as MERL's table), θd along y (0° at the bottom … 90° at the top), half-block pixels in
the chosen colour map (RGB models in colour with ``grey``), background where ``wi`` or ``wo``
is below the horizon; θd tick labels on the left, θh ticks underneath, then the colour bar.

**Line plots** (:func:`line_picture`): braille curves (:mod:`.braille`) over 0–90° with y ticks
(linear, or decades in log mode); the curve stops where the angles leave the hemisphere.  RGB
models get one curve per channel, told apart by colour and by dot pattern.
"""

from __future__ import annotations

import numpy as np
from rich.console import Console, ConsoleOptions, Group, RenderResult
from rich.measure import Measurement
from rich.segment import Segment
from rich.text import Text

from tuibrdf.core.conventions import fmt_value
from tuibrdf.core.display import DISPLAY
from tuibrdf.core.views.halfdiff import SCALE_LIMIT_DEG, scale_max
from tuibrdf.render.braille import NULL_STYLE, BrailleCanvas, curve_layers, draw_legend, nice_ticks
from tuibrdf.render.colormap import (
    DEFAULT_LEVELS,
    LOG_DECADES,
    Scale,
    colorbar,
    colorize,
)
from tuibrdf.render.curves import channel_curves, curve_color
from tuibrdf.render.halfblock import HalfBlockImage
from tuibrdf.render.text import first_fitting

#: width of the y tick labels and the space after them
MARGIN = 8
TICKS_DEG = (0, 15, 30, 45, 60, 75, 90)
GUIDE = "color(244)"


class LeftLabelled:
    """Rows of a renderable (:class:`HalfBlockImage` or :class:`BrailleCanvas`) with a text
    label before each row (``labels[k]`` right-aligned in :data:`MARGIN` − 1 cells)."""

    def __init__(self, body, labels: list[str], system: str | None = None) -> None:
        self.body, self.labels, self.system = body, labels, system

    @property
    def width(self) -> int:
        return self.body.width + MARGIN

    def rows(self) -> list[list[Segment]]:
        """Per row its label and the body's segments, each exactly :attr:`width` cells."""
        if isinstance(self.body, HalfBlockImage):
            body = self.body.rows(self.system or "truecolor")
        else:
            body = self.body.rows()
        return [[Segment(self.labels[k].rjust(MARGIN - 1)[: MARGIN - 1] + " ", NULL_STYLE),
                 *row] for k, row in enumerate(body)]

    def __rich_console__(self, console: Console, options: ConsoleOptions) -> RenderResult:
        for row in self.rows():
            yield from row
            yield Segment.line()

    def __rich_measure__(self, console: Console, options: ConsoleOptions) -> Measurement:
        return Measurement(self.width, self.width)


def axis_line(width: int, positions: list[float], labels: list[str], name: str) -> Text:
    """Tick labels centred on cell ``positions`` (fractions 0..1 of ``width``), skipping any that
    would touch the previous one, after the axis ``name`` in the margin."""
    line = [" "] * width
    last = -2
    for p, s in zip(positions, labels, strict=True):
        c0 = int(round(p * (width - 1))) - len(s) // 2
        c0 = min(max(c0, 0), width - len(s))
        if c0 <= last + 1:
            continue
        line[c0:c0 + len(s)] = s
        last = c0 + len(s) - 1
    head = name.rjust(MARGIN - 1)[: MARGIN - 1] + " "
    return Text(head + "".join(line).rstrip(), no_wrap=True, overflow="crop")


def scale_note(f: np.ndarray, valid: np.ndarray, vmax: float,
               limit_deg: float = SCALE_LIMIT_DEG) -> list[list[tuple[str, int]]]:
    """Title parts, in wordings from the longest: ``max 0.65 sr⁻¹``, or when grazing values
    clip ``scale 0.65 sr⁻¹ (θ≤85°)`` and (less important) ``max 1e+32``.  A clipped scale is
    kept (without its unit in a narrow view) rather than dropped: a curve leaving the top of
    the plot must say where the axis stops and why."""
    v = f[valid] if f.ndim == valid.ndim else f[valid].max(axis=-1)
    peak = float(v.max()) if v.size else 0.0
    if peak > vmax * (1 + 1e-9):
        top, limit = fmt_value(vmax), f"(θ≤{limit_deg:g}°)"
        rest = (f"max {fmt_value(peak)}", 3)
        return [[(f"scale {top} sr⁻¹ {limit}", 0), rest], [(f"scale {top} {limit}", 0), rest],
                [(f"scale {top} sr⁻¹ {limit}", 1), rest]]
    return [[(f"max {fmt_value(peak)} sr⁻¹", 1)]]


def slice_pixels(width: int, height: int) -> tuple[int, int]:
    """``(n_h, n_d)``: the θh × θd samples of a ``width × height`` slice view."""
    return int(width) - MARGIN, 2 * (int(height) - 4)


#: the slice's colour scale stops at the largest value with wi and wo within this of the
#: normal: a grazing blow-up (Cook-Torrance's 1/cos, 10⁴ sr⁻¹ at θd → 90°) would otherwise
#: leave the specular strip at θh ≈ 0 black; the title names the limit when it clips
SLICE_LIMIT_DEG = 60.0


def slice_scale(extra: tuple, phi_d_deg: float) -> float:
    """The colour scale's top of a slice ``(f, valid, θh, θd)`` (:func:`scale_max` within
    :data:`SLICE_LIMIT_DEG`)."""
    f, _, th, td = extra
    return scale_max(f, th[None, :], td[:, None], phi_d_deg, SLICE_LIMIT_DEG)


def slice_picture(name: str, f: np.ndarray, valid: np.ndarray, th: np.ndarray, td: np.ndarray,
                  width: int, height: int, *, phi_d_deg: float = DISPLAY.phi_d.default,
                  sqrt_h: bool = DISPLAY.sqrt_h, vmax: float | None = None, log: bool = False,
                  cmap: str = DISPLAY.cmap, levels: int = DEFAULT_LEVELS, rgb_mode: str = "auto",
                  color: str = "truecolor") -> Group:
    """The slice view of precomputed samples (:func:`slice_image`); ``vmax`` the colour
    scale's top (default: the slice's own, :func:`slice_scale`)."""
    img_w, rows = int(width) - MARGIN, int(height) - 4
    if img_w < 4 or rows < 2:
        raise ValueError(f"view size {width}×{height} too small for the θh × θd image")
    data = np.where(valid[..., None] if f.ndim == 3 else valid, f, np.nan)[::-1]  # θd up
    if rgb_mode == "auto":
        rgb_mode = "color" if cmap == "grey" else "luminance"
    if vmax is None:
        vmax = slice_scale((f, valid, th, td), phi_d_deg)
    scale = Scale(vmax if vmax > 0 else 1.0, log)  # all zero: the lowest colour, no division
    col = colorize(data, cmap, levels=levels, log=log, rgb_mode=rgb_mode, scale=scale)
    image = HalfBlockImage(col.index, col.palette, color_system=color, shades=col.shades)
    labels = [""] * rows
    for deg in (90, 45, 0):  # θd of the cell rows: row r covers pixels 2r, 2r+1 from the top
        r = min(int((90.0 - deg) / 90.0 * rows), rows - 1)
        labels[r] = f"{deg}°"
    labels[0] = labels[0] or "θd"
    if not labels[rows // 4]:
        labels[rows // 4] = "θd"
    if sqrt_h:
        ticks = [0, 5, 10, 20, 45, 90]
        pos = [np.sqrt(t / 90.0) for t in ticks]
    else:
        ticks = list(TICKS_DEG)
        pos = [t / 90.0 for t in ticks]
    axis = axis_line(img_w, pos, [f"{t}°" for t in ticks], "θh")
    bar_cmap = "grey" if (data.ndim == 3 and rgb_mode == "color") else cmap
    bar = colorbar(col.scale, bar_cmap, int(width), levels=levels, color_system=color)
    head = first_fitting([[(name, 2), (f"θh×θd at φd={phi_d_deg:g}°", 0), *note,
                           (f"log, {LOG_DECADES:g} decades" if log else "", 1),
                           ("√θh axis" if sqrt_h else "linear θh", 3)]
                          for note in scale_note(f, valid, vmax, SLICE_LIMIT_DEG)], int(width))
    return Group(head, LeftLabelled(image, labels, color), axis, bar)


def line_scale(view: str, extra: tuple, req) -> float:
    """The y axis's top of a ``theta-h``/``theta-d`` curve ``(x, f, valid)`` of request
    ``req`` (its fixed angles)."""
    xs, f, _ = extra
    if view == "theta-h":
        return scale_max(f, xs, req.theta_d, req.phi_d)
    return scale_max(f, req.theta_h, xs, req.phi_d)


def line_picture(view: str, name: str, extra: tuple, theta_d_deg: float, theta_h_deg: float,
                 phi_d_deg: float, vmax: float, width: int, height: int, *, log: bool = False,
                 color: str = "truecolor", charset: str = "braille") -> Group:
    """The ``theta-h`` or ``theta-d`` plot of precomputed samples ``(x, f, valid)``."""
    xs, f, valid = extra
    if view == "theta-h":
        what, xlabel = f"f(θh) at θd={theta_d_deg:g}° φd={phi_d_deg:g}°", "θh"
    else:
        what, xlabel = f"f(θd) at θh={theta_h_deg:g}° φd={phi_d_deg:g}°", "θd"
    return line_view([(name, 2), (what, 0)], xs, f, valid, name, vmax, width, height,
                     xlabel=xlabel, log=log, color=color, charset=charset)


def line_view(
    title_parts: list[tuple[str, int]],
    xs: np.ndarray,
    f: np.ndarray,
    valid: np.ndarray,
    label: str,
    scale: float,
    width: int,
    height: int,
    *,
    xlabel: str,
    log: bool = False,
    decades: float = LOG_DECADES,
    color: str = "truecolor",
    charset: str = "braille",
) -> Group:
    """Title, a braille line plot of ``f(x)`` over 0–90° (y ticks on the left) and the x axis."""
    plot_w, rows = int(width) - MARGIN, int(height) - 2
    if plot_w < 4 or rows < 2:
        raise ValueError(f"view size {width}×{height} too small for a line plot")
    f_raw = f
    f = np.where(valid[:, None] if f.ndim == 2 else valid, f, np.nan)  # a break, not a drop
    curves = [(lab, xs, v) for lab, v in channel_curves(label, f)]
    vmax = scale if scale > 0 else 1.0  # all zero: a unit axis, no division
    if log:
        lo = vmax * 10.0 ** -decades
        ys = [np.log10(np.maximum(v, lo)) for _, _, v in curves]  # ≥ lo > 0
        ylim = (np.log10(lo), np.log10(vmax) + 0.05 * decades)
        ticks = np.arange(np.ceil(ylim[0] - 1e-9), np.floor(ylim[1]) + 1)
        tick_labels = [fmt_value(10.0**t) for t in ticks]
    else:
        ys = [v for _, _, v in curves]
        ylim = (0.0, vmax * 1.05)
        ticks = nice_ticks(0.0, ylim[1], 4)
        tick_labels = [fmt_value(t + 0.0) for t in ticks]  # + 0.0: a tick of −0.0 reads "0"
    canvas = BrailleCanvas(plot_w, rows, (0.0, 90.0), ylim, color=color, charset=charset)
    guide = canvas.layer(GUIDE, "sparse", ".")
    for t in ticks:
        canvas.polyline(np.array([0.0, 90.0]), np.array([t, t]), guide)
    for x in TICKS_DEG[1:-1]:
        canvas.polyline(np.array([x, x]), np.array(ylim), guide)
    colors = [curve_color(lab, j) for j, (lab, _, _) in enumerate(curves)]
    ids = curve_layers(canvas, curves, colors)
    for y, lid in zip(ys, ids, strict=True):
        canvas.polyline(xs, y, lid)
    if len(curves) > 1:
        draw_legend(canvas, curves, ids, col=1)
    labels = [""] * rows
    for t, s in zip(ticks, tick_labels, strict=True):
        r = int((ylim[1] - t) / (ylim[1] - ylim[0]) * rows)  # ylim[1] > ylim[0]
        if t >= ylim[0]:  # the axis's lower end (0, or the lowest decade) labels the last row
            r = min(r, rows - 1)
        if 0 <= r < rows:
            labels[r] = s
    axis = axis_line(plot_w, [t / 90.0 for t in TICKS_DEG], [f"{t}°" for t in TICKS_DEG],
                     xlabel)
    tail = [(f"log, {decades:g} decades", 4)] if log else []
    head = first_fitting([[*title_parts, *note, *tail] for note in scale_note(f_raw, valid, scale)],
                         int(width))
    return Group(head, LeftLabelled(canvas, labels), axis)
