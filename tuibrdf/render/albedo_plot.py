"""Directional albedo curve a(θi) over 0–90° (SPEC §4 view 4), drawn with plotext (the one
plot that still is: the others are braille canvases, :mod:`.braille`).

The curve, ``a(θi) = ∫ f(wi, wo) cos θr dω`` at every 3°, comes with the frame (each side's
``curve``, :mod:`tuibrdf.core.views.frame`, cached per material: moving θi only moves the
marker); the pane with its title is :func:`tuibrdf.render.panes.albedo_pane`.  The axis is
scaled to the curves (a specular albedo of 0.05 fills the plot; the line ``a = 1`` is drawn
when it is in range) and labelled; θi is marked by a vertical line and a point on each curve,
the x range starting just left of 0° so that θi = 0 stays visible.  RGB models get the curves
the channel choice asks for; in compare mode each side has its own marker.
"""

from __future__ import annotations

import math
import threading
from functools import lru_cache

import numpy as np
from rich.text import Text

from tuibrdf.core.lru import LRU
from tuibrdf.core.numerics import snap
from tuibrdf.render.curves import curve_color

#: plotext keeps its figure in module-global state: every build runs under this lock
#: (``clf`` → plot → ``build`` → ``clf``), so it is deterministic, and the app may draw from
#: worker threads
PLOT_LOCK = threading.Lock()
GUIDE_COLOR = 244  # xterm grey: the line a = 1
INCIDENT_COLOR = "yellow"  # the θi marker


def albedo_plot(
    thetas: np.ndarray,
    curves: list[tuple[str, np.ndarray]],
    width: int,
    height: int,
    *,
    theta_i_deg: float | None = None,
    color: str = "truecolor",
) -> Text:
    """The curves with the line a = 1 and a marker at ``theta_i_deg``, as a non-wrapping Rich
    ``Text`` (no colours when ``color == "none"``).

    plotext draws the curves once per (curves, size, colours) and they are kept: a θi key
    moves the marker only, drawn on a copy of the kept plot (:func:`_marked`: the cells
    plotext itself gives, tested against its own marked plot), not a new plot (≈ 7–10 ms
    each, the albedo view's largest cost per key)."""
    styles = [_curve_style(j, c) for j, c in enumerate(curves)]
    colours = [c for _, c, _ in styles]
    key = (thetas.tobytes(), tuple((label, np.asarray(a).tobytes(), tuple(st))
                                   for (label, a, *st) in curves), width, height, color)
    top = nice_top(max(float(np.max(a)) for _, a, *_ in curves))
    labels = [label for label, *_ in curves]
    plot = _PLOTS.get(key, lambda: _Plot(_build(thetas, curves, styles, top, width, height,
                                                None, color), top, labels, color))
    if theta_i_deg is None:
        return plot.text()
    points = [float(on_axis_grid(np.interp(theta_i_deg, thetas, on_axis_grid(a, top)), top))
              for _, a, *_ in curves]
    # plotext draws the marker itself where the copy could not tell what it would: without
    # axes, off the x range, at a point off the canvas, or where telling which curve drew a
    # cell last needs a colour each
    if (plot.axes is None or not X_LIM[0] <= theta_i_deg <= X_LIM[1]
            or not all(0.0 <= p <= top for p in points)
            or (len(curves) > 1 and (color == "none" or len(set(colours)) < len(colours)))):
        return plot_body(_build(thetas, curves, styles, top, width, height, theta_i_deg,
                                color), color)
    return _marked(plot, float(theta_i_deg), points, colours)


def _curve_style(j: int, curve: tuple) -> tuple[str, object, str]:
    """(plotext marker, plotext colour, label) of the ``j``-th curve ``(label, a, *style)``."""
    label, _a, *style = curve
    marker = style[0] if style else "braille"
    col = style[1] if len(style) > 1 else curve_color(label, j)
    if isinstance(col, str) and col.startswith("#"):  # a side's hue (curves.SIDE_HUES)
        col = tuple(int(col[i:i + 2], 16) for i in (1, 3, 5))  # plotext takes RGB
    return marker, col, label


def _build(thetas, curves, styles, top: float, width: int, height: int,
           theta_i_deg: float | None, color: str) -> str:
    """plotext's text of the plot up to ``top`` (its marker at ``theta_i_deg`` unless None)."""
    import plotext as plt  # ≈ 20 ms: when the albedo view is first drawn, not at start

    step = nice_step(top)
    with PLOT_LOCK:
        plt.clf()
        plt.theme("clear")
        plt.plotsize(width, height)
        plt.xlim(*X_LIM)  # left of 0°: the θi line at 0° is not hidden by the axis
        plt.ylim(0.0, top)
        plt.xticks([0, 30, 60, 90])
        plt.yticks([float(f"{v:.6g}") for v in np.arange(0.0, top + step / 2, step)])
        plt.xlabel("θi (°)")
        plt.ylabel("a(θi)")
        if top >= 1.0:
            plt.hline(1.0, GUIDE_COLOR)
        if theta_i_deg is not None:
            plt.vline(float(theta_i_deg), INCIDENT_COLOR)
        for (label, a, *_), (marker, col, _) in zip(curves, styles, strict=True):
            a = on_axis_grid(a, top)
            plt.plot(thetas.tolist(), a.tolist(), marker=marker, color=col,
                     label=label if len(curves) > 1 else None)
            if theta_i_deg is not None:  # the point a(θi) on the curve
                at = float(on_axis_grid(np.interp(theta_i_deg, thetas, a), top))
                plt.scatter([float(theta_i_deg)], [at], marker="o", color=col)
        return finish_plot(color)


#: the x axis' range: from just left of 0°, so that the θi line at 0° clears the y axis
X_LIM = (-3.0, 90.0)
#: the plots drawn lately without their marker (a side's curve, a compare pair, channels)
_PLOTS = LRU(8)


class _Plot:
    """A plot without its marker: its rows, where plotext put its canvas (the area inside
    the axes, found from the axes' corners; ``axes`` None when it has none: a plot too small
    for them is drawn by plotext, marker and all) and its legend's box."""

    def __init__(self, text: str, top: float, labels: list[str], color: str) -> None:
        self.rows = plot_body(text, color).split("\n", allow_blank=True)
        self.color = color
        self.top = top  # the y axis' end
        self.axes = None
        #: the legend's columns and its rows (the canvas' first): plotext draws one for
        #: several curves, 3 marker cells and the padded labels, where it fits
        self.legend: tuple[range, int] = (range(0), 0)
        plain = [r.plain for r in self.rows]
        top_rows = [i for i, r in enumerate(plain) if "┌" in r]
        bottom_rows = [i for i, r in enumerate(plain) if "└" in r]
        if len(top_rows) == 1 and len(bottom_rows) == 1:
            t, b = top_rows[0], bottom_rows[0]
            c0, c1 = plain[b].index("└") + 1, plain[b].find("┘")
            if c1 > c0 and b - t > 1:
                self.axes = (t, b, c0, c1)  # rows of the axes, first and last canvas column
                width = 3 + max(len(label) + 2 for label in labels)
                if len(labels) > 1 and c1 - c0 >= width and b - t - 1 >= len(labels):
                    self.legend = (range(c0, c0 + width), len(labels))

    def text(self) -> Text:
        return _joined(self.rows)


def _joined(rows: list[Text]) -> Text:
    """Rows as one non-wrapping ``Text``."""
    body = Text("\n").join(rows)
    body.no_wrap = True
    return body


def _matrix_cell(value: float, lo: float, hi: float, bins: int) -> int:
    """The canvas cell plotext puts ``value`` of the range ``lo``–``hi`` in, of ``bins``:
    its own arithmetic (``get_matrix_data``), term by term, so the same cell."""
    return math.floor(round(0.5 + (bins - 1) * (value - lo) / (hi - lo), 8))


def _marked(plot: _Plot, theta: float, points: list[float], colours: list) -> Text:
    """``plot`` with the θi marker as plotext draws it: a line at θi where nothing else is
    drawn (crossing the line a = 1 as ``┼``, ticking both x axes), then each curve's point
    ``o`` unless a later curve drew over its cell; a legend (drawn last) hides both."""
    t, b, c0, c1 = plot.axes
    rows = list(plot.rows)
    hc = b - t - 1
    col = c0 + _matrix_cell(theta, *X_LIM, c1 - c0)
    columns, legend_rows = plot.legend
    under_legend = col in columns  # then the legend's rows t + 1 … t + legend_rows hide it
    none = plot.color == "none"

    def put(i: int, ch: str, style) -> None:  # the cell's style kept, unless one is given
        row = rows[i] = rows[i].copy()
        row.plain = row.plain[:col] + ch + row.plain[col + 1:]
        if style is not None:
            row.stylize(style, col, col + 1)

    line = None if none else _style(INCIDENT_COLOR)
    for i in range(t + 1, b):
        if under_legend and i - t <= legend_rows:
            continue
        ch = rows[i].plain[col]
        if ch == " ":
            put(i, "│", line)
        elif ch == "─":  # the line a = 1: plotext marks the crossing in its colour
            put(i, "┼", None)
    put(t, "┬", None)
    put(b, "┴", None)
    styles = [None if none else _style(c) for c in colours]
    for j, value in enumerate(points):
        i = b - 1 - _matrix_cell(value, 0.0, plot.top, hc)
        if under_legend and i - t <= legend_rows:
            continue
        drawn = plot.rows[i][col:col + 1]  # as plotext drew it, before the marker
        style = drawn.spans[0].style if drawn.spans else None
        if any(style == s for s in styles[j + 1:]):
            continue  # a later curve drew this cell, over the point
        put(i, "o", styles[j])
    return _joined(rows)


@lru_cache(maxsize=64)
def _style(col):
    """The Rich style plotext's colour ``col`` comes out as (its own escape codes, parsed)."""
    import plotext as plt

    spans = Text.from_ansi(plt.colorize("o", col)).spans
    return spans[0].style if spans else None


def on_axis_grid(v, top: float) -> np.ndarray:
    """``v`` snapped (core.numerics.snap) in units of ``top``'s power of two: plotext decides
    each point's dot by its own rounding, so what it is given is made the same on every
    machine (the albedo's last bits depend on the CPU's exp and pow), and a value on a dot
    boundary in exact arithmetic stays on it.  Exact: powers of two."""
    unit = math.ldexp(1.0, math.frexp(top)[1])  # top < unit ≤ 2·top (top > 0)
    return snap(np.asarray(v, dtype=float) / unit) * unit


#: the smallest axis end: an albedo below it (1e-322 from a subnormal parameter) is drawn on
#: a 0–1e-4 axis (plotext's tick arithmetic fails on subnormal ranges); the title has the value
MIN_TOP = 1e-4


def nice_top(peak: float) -> float:
    """The y axis end: 1.1 × the curves' maximum rounded up to 1, 2, 2.5, 5 × 10^k (at
    least 1.1 when the maximum is near or above 1, so the line a = 1 shows)."""
    if not peak > 0:  # all zero (or NaN guarded): a unit axis
        return 1.0
    peak = max(peak, MIN_TOP)
    if peak >= 0.9:
        peak = max(peak, 1.0)
    want = peak * 1.1
    e = 10.0 ** np.floor(np.log10(want))
    for m in (1.0, 1.2, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0):
        if m * e >= want:
            return float(m * e)
    return float(10 * e)


def nice_step(top: float) -> float:
    """A tick step giving 3 to 6 ticks up to ``top``."""
    e = 10.0 ** np.floor(np.log10(top))
    for m in (0.1, 0.2, 0.25, 0.5, 1.0, 2.0):
        if top / (m * e) <= 6:
            return m * e
    return 2 * e


def finish_plot(color: str) -> str:
    """``plt.build()`` (call under :data:`PLOT_LOCK`; the figure stays until the next plot's
    ``plt.clf()``): its text without plotext's final newline, without colours when
    ``color == "none"``."""
    import plotext as plt  # ≈ 20 ms: when a plot is drawn, not at the viewer's start

    text = plt.build()
    if text.endswith("\n"):  # plotext ends its last line with a newline
        text = text[:-1]
    return plt.uncolorize(text) if color == "none" else text


def plot_body(text: str, color: str) -> Text:
    """A built plot as a non-wrapping Rich ``Text`` (ANSI colours parsed unless plain)."""
    body = Text(text) if color == "none" else Text.from_ansi(text)
    body.no_wrap = True
    return body
