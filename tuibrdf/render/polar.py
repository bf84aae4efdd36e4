"""Polar cross-sections with plotext (SPEC §4 view 2): curves in, text out (the values come from
:mod:`tuibrdf.core.views.frame`, the pane from :mod:`.panes`).

plotext has no polar axes: a curve is drawn as ``x = r sin θr``, ``y = r cos θr`` for
``θr ∈ [−90°, 90°]`` with braille dots; negative ``θr`` is the left half of the plot.

- plane of incidence: ``wo = (sin θr, 0, cos θr)``: the right half is φr = 0 (mirror side), the
  left half φr = 180° (the light's side); the incident direction is drawn as a (yellow) line;
- perpendicular plane: ``wo = (0, sin θr, cos θr)``: right half φr = 90°, left half φr = 270°.

Radius = value (linear), or in log mode ``1 + log10(v / vmax) / decades`` clipped at 0 (the centre
is ``vmax·10^-decades`` and below).  Guide circles: 1-2-5 steps in linear mode, one per decade in
log mode; the title says their spacing.  The axis limits are set so that one data unit has the
same length on screen in x and y, with terminal cells twice as tall as wide: circles are round.

plotext keeps its figure in module-global state, so every build runs under :data:`PLOT_LOCK`
(``clf`` → plot → ``build``) and is deterministic; the app may call it from worker threads.
Several curves (comparisons, or the R, G, B channels of a colour model) share one radius scale
and get a legend in the top-left corner.
"""

from __future__ import annotations

import threading
from collections.abc import Sequence

import numpy as np
from rich.text import Text

PLOT_LOCK = threading.Lock()
#: curve colours in order (plotext's 16-colour names: readable on dark and light terminals)
CURVE_COLORS = ("red", "cyan", "green", "magenta", "yellow", "blue")
GUIDE_COLOR = 244  # xterm grey
INCIDENT_COLOR = "yellow"
CELL_ASPECT = 2.0  # a terminal cell is about twice as tall as it is wide

#: (label, θr degrees, values[, marker[, colour]]): compare mode gives each side its own
#: marker (a line style that survives every colour mode) and the channels their colours
Curve = tuple
#: the marker of each side in compare mode: A braille dots, B a '+' per sample
SIDE_MARKERS = ("braille", "+")
#: an RGB channel where a side may be named too (compare mode's legends, a peak's channel):
#: in words, so that "B" only ever means side B, never the blue channel
CHANNEL_WORDS = {"R": "red", "G": "green", "B": "blue"}


def curve_color(label: str, j: int) -> str:
    """Channel curves R, G, B in their own colour, other curves in :data:`CURVE_COLORS` order."""
    return {"R": "red", "G": "green", "B": "blue"}.get(label, CURVE_COLORS[j % len(CURVE_COLORS)])


def nice_step(vmax: float) -> float:
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


def channel_curves(label: str, values: np.ndarray, channel: str = "rgb"
                   ) -> list[tuple[str, np.ndarray]]:
    """``[(label, v)]`` for ``(n,)`` values; for ``(n, 3)`` the ``channel`` choice: ``rgb``
    ``[("R", r), ("G", g), ("B", b)]``, ``lum`` the Rec.709 luminance, or one of R, G, B."""
    if values.ndim != 2:
        return [(label, values)]
    if channel == "lum":
        from tuibrdf.core.conventions import luminance

        return [("lum", luminance(values))]
    if channel in ("R", "G", "B"):
        return [(channel, values[:, "RGB".index(channel)])]
    return [(ch, values[:, k]) for k, ch in enumerate("RGB")]


def side_curves(sides: Sequence[tuple[str, np.ndarray]], channel: str = "rgb") -> list[tuple]:
    """The curves of one or two sides ``(label, values)``: alone, :func:`channel_curves`;
    in compare mode each label prefixed ``A:``/``B:`` and each side drawn with its own marker
    (:data:`SIDE_MARKERS`), channels in their colours, scalar sides in A's and B's colours,
    so the sides differ in every colour mode.  Items: ``(label, values, marker, colour)``."""
    if len(sides) == 1:
        return [(lab, v) for lab, v in channel_curves(sides[0][0], sides[0][1], channel)]
    out = []
    for k, (name, values) in enumerate(sides):
        side = "AB"[k]
        for lab, v in channel_curves(name, values, channel):
            col = {"R": "red", "G": "green", "B": "blue"}.get(lab, CURVE_COLORS[k])
            text = f"{side}:{name}" if lab == name else f"{side}:{CHANNEL_WORDS.get(lab, lab)}"
            out.append((text, v, SIDE_MARKERS[k], col))
    return out
