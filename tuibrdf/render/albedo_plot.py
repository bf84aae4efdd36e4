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

import numpy as np
from rich.text import Text

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
) -> str:
    """plotext line plot of the curves with the line a = 1 and a marker at ``theta_i_deg``."""
    import plotext as plt  # ≈ 20 ms: when the albedo view is first drawn, not at start

    peak = max(float(np.max(a)) for _, a, *_ in curves)
    top = nice_top(peak)
    step = nice_step(top)
    with PLOT_LOCK:
        plt.clf()
        plt.theme("clear")
        plt.plotsize(width, height)
        plt.xlim(-3.0, 90.0)  # left of 0°: the θi line at 0° is not hidden by the axis
        plt.ylim(0.0, top)
        plt.xticks([0, 30, 60, 90])
        plt.yticks([float(f"{v:.6g}") for v in np.arange(0.0, top + step / 2, step)])
        plt.xlabel("θi (°)")
        plt.ylabel("a(θi)")
        if top >= 1.0:
            plt.hline(1.0, GUIDE_COLOR)
        if theta_i_deg is not None:
            plt.vline(float(theta_i_deg), INCIDENT_COLOR)
        for j, (label, a, *style) in enumerate(curves):
            marker = style[0] if style else "braille"
            col = style[1] if len(style) > 1 else curve_color(label, j)
            if col.startswith("#"):  # a side's hue (curves.SIDE_HUES): plotext takes RGB
                col = tuple(int(col[i:i + 2], 16) for i in (1, 3, 5))
            a = on_axis_grid(a, top)
            plt.plot(thetas.tolist(), a.tolist(), marker=marker, color=col,
                     label=label if len(curves) > 1 else None)
            if theta_i_deg is not None:  # the point a(θi) on the curve
                at = float(on_axis_grid(np.interp(theta_i_deg, thetas, a), top))
                plt.scatter([float(theta_i_deg)], [at], marker="o", color=col)
        return finish_plot(color)


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
    """``plt.build()`` then ``plt.clf()`` (call under :data:`PLOT_LOCK`): the figure's text
    without plotext's final newline, without colours when ``color == "none"``."""
    import plotext as plt  # ≈ 20 ms: when a plot is drawn, not at the viewer's start

    text = plt.build()
    plt.clf()
    if text.endswith("\n"):  # plotext ends its last line with a newline
        text = text[:-1]
    return plt.uncolorize(text) if color == "none" else text


def plot_body(text: str, color: str) -> Text:
    """A built plot as a non-wrapping Rich ``Text`` (ANSI colours parsed unless plain)."""
    body = Text(text) if color == "none" else Text.from_ansi(text)
    body.no_wrap = True
    return body
