"""A plot canvas drawn straight from numpy onto a braille grid (U+2800–U+28FF).

Each terminal cell holds 2 × 4 dots, so a ``W × H`` cell canvas is a ``2W × 4H`` dot grid; a
cell is about twice as tall as wide, so the dots are about square.  Curves are polylines
rasterised with numpy in one pass (every segment sampled at ≤ 1 dot steps along its major
axis, all segments at once), so a 181-point section costs a few array operations, not a
Python loop per point.

**Layers.**  Everything drawn belongs to a layer (:meth:`BrailleCanvas.layer`): a colour, a
dot pattern and an ASCII marker.  A cell's braille character is the union of every layer's
dots; its colour is that of the last-added layer with a dot in it (curves are added after the
guides, so they stay on top).

**Styles that survive ``--color none``.**  The dot pattern runs along the path: ``solid`` (every
dot), ``dashed`` (3 on, 2 off), ``dotted`` (1 on, 1 off), ``dashdot``; guides use ``sparse``
(1 on, 3 off) so they never read as a curve.  Curves are told apart by their pattern as well as
their colour, so a plain-text plot of the R, G, B channels still shows three different lines.

**ASCII fallback** (``charset="ascii"``: plain logs, terminals without UTF-8): one character per
cell, the marker of the cell's top layer (``*``, ``o``, ``+``, ``x``, … for curves, ``.`` for
guides); text overlays are unchanged.

Colours are Rich colour names or ``color(N)``; ``color="none"`` draws no colours at all.  The
output is deterministic: the same calls give the same segments.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from rich.console import Console, ConsoleOptions, RenderResult
from rich.measure import Measurement
from rich.segment import Segment
from rich.style import Style

from tuibrdf.core.numerics import snap, snapped_ceil
from tuibrdf.render.rowdiff import kept_rows, mark_changed

BRAILLE_BASE = 0x2800
#: bit of the dot at (row 0..3, column 0..1) of a cell (Unicode braille numbering 1-8)
DOT_BITS = np.array([[0x01, 0x08], [0x02, 0x10], [0x04, 0x20], [0x40, 0x80]], dtype=np.int64)
PATTERNS: dict[str, tuple[bool, ...]] = {
    "solid": (True,),
    "dashed": (True, True, True, False, False),
    "dotted": (True, False),
    "dashdot": (True, True, True, True, False, False, True, False, False),
    "sparse": (True, False, False, False),
}
#: patterns given to the curves of one plot, in order
CURVE_PATTERNS = ("solid", "dashed", "dotted", "dashdot")
#: ASCII markers given to the curves of one plot, in order
CURVE_MARKERS = "*o+x#%"
CHARSETS = ("braille", "ascii")
NULL_STYLE = Style()
#: the 256 braille characters by bit mask, with the empty cell as a plain space
BRAILLE_CHARS = np.array([" "] + [chr(BRAILLE_BASE + i) for i in range(1, 256)])


@dataclass(frozen=True)
class Layer:
    color: str | None  # a Rich colour ("red", "color(244)") or None (terminal default)
    pattern: str = "solid"
    marker: str = "*"  # ASCII fallback character


@lru_cache(maxsize=256)
def _style(color: str | None, system: str = "truecolor") -> Style:
    # one Style per colour system: Rich caches a Style's escape codes on the object for the
    # first console that renders it (Style._ansi), so a style shared by a truecolor and a
    # 256-colour picture in one process would give the second the first one's codes
    return Style(color=color) if color else NULL_STYLE


_COLOUR_IDS: dict[str | None, int] = {None: 0}


def _colour_id(color: str | None) -> int:
    """A number per colour name, the same on every canvas (rows of two canvases compare by
    it; a canvas's own colour ids index its own list of layer and overlay colours)."""
    return _COLOUR_IDS.setdefault(color or None, len(_COLOUR_IDS))


class BrailleCanvas:
    """A ``width × height`` cell canvas mapping data ``xlim × ylim`` onto its dots (y up).

    ``color``: ``truecolor``/``256`` (layer colours) or ``none``; ``charset``: ``braille`` or
    ``ascii``.  Draw with :meth:`polyline` (lines, lone points, arcs from :meth:`arc_points`)
    and :meth:`text`; it is a Rich renderable and :meth:`rows` gives the segments per row
    (exactly ``width`` cells)."""

    def __init__(
        self,
        width: int,
        height: int,
        xlim: tuple[float, float],
        ylim: tuple[float, float],
        *,
        color: str = "truecolor",
        charset: str = "braille",
    ) -> None:
        if width < 1 or height < 1:
            raise ValueError(f"canvas size {width}×{height}: at least 1×1 cells")
        if charset not in CHARSETS:
            raise ValueError(f"charset {charset!r}: expected one of {', '.join(CHARSETS)}")
        (x0, x1), (y0, y1) = (float(v) for v in xlim), (float(v) for v in ylim)
        if not (np.isfinite([x0, x1, y0, y1]).all() and x1 > x0 and y1 > y0):
            raise ValueError(f"limits must be finite and increasing, got {xlim}, {ylim}")
        self.width, self.height = int(width), int(height)
        self.xlim, self.ylim = (x0, x1), (y0, y1)
        self.color, self.charset = color, charset
        self.dot_w, self.dot_h = 2 * self.width, 4 * self.height
        #: the last layer that set each dot (−1: none)
        self.owner = np.full((self.dot_h, self.dot_w), -1, dtype=np.int16)
        self.layers: list[Layer] = []
        self.overlays: list[tuple[int, int, str, str | None]] = []
        #: what :meth:`rows` drew: per cell its character and colour (:func:`_colour_id`), and
        #: the rows of segments
        self._drawn: tuple[np.ndarray, np.ndarray, list[list[Segment]]] | None = None

    # -- coordinates ---------------------------------------------------------------------------
    def to_dots(self, x: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Continuous dot coordinates ``(column, row)`` of data points; dot ``(c, r)`` covers
        ``[c − ½, c + ½) × [r − ½, r + ½)`` (row 0 at the top)."""
        (x0, x1), (y0, y1) = self.xlim, self.ylim
        cx = (np.asarray(x, dtype=float) - x0) * (self.dot_w / (x1 - x0)) - 0.5  # x1 > x0
        ry = (y1 - np.asarray(y, dtype=float)) * (self.dot_h / (y1 - y0)) - 0.5  # y1 > y0
        return cx, ry

    def layer(self, color: str | None, pattern: str = "solid", marker: str = "*") -> int:
        """Add a layer; returns its id (later layers draw over earlier ones)."""
        if pattern not in PATTERNS:
            raise ValueError(f"pattern {pattern!r}: expected one of {', '.join(PATTERNS)}")
        self.layers.append(Layer(color, pattern, marker))
        return len(self.layers) - 1

    # -- drawing -------------------------------------------------------------------------------
    def _set(self, cols: np.ndarray, rows: np.ndarray, layer: int) -> None:
        # dot c covers [c − ½, c + ½): the nearest dot, halves up, decided on the snapped
        # coordinate (core.numerics.snap): many points sit on a dot boundary by construction
        # (x = 0 is one in the symmetric polar window, the horizon line's samples are), and a
        # last-ulp difference in sin or exp must not move them.  The canvas covers dot
        # coordinates [−½, dot_w − ½] × [−½, dot_h − ½], both ends included: a point on the
        # limits (f = 0 on a y axis from 0, θ = 90° on one to 90°) is drawn in the edge dot,
        # not dropped (dot_w − ½ rounds up to dot_w, one past it)
        cols, rows = snap(cols), snap(rows)
        ok = ((cols >= -0.5) & (cols <= self.dot_w - 0.5)
              & (rows >= -0.5) & (rows <= self.dot_h - 0.5))
        c = np.minimum(np.floor(cols[ok] + 0.5).astype(np.int64), self.dot_w - 1)
        r = np.minimum(np.floor(rows[ok] + 0.5).astype(np.int64), self.dot_h - 1)
        self.owner[r, c] = layer

    def polyline(self, x: np.ndarray, y: np.ndarray, layer: int) -> None:
        """The segments between consecutive points (a non-finite point breaks the line), dots
        kept by the layer's pattern counted along the whole path."""
        cx, ry = self.to_dots(np.ravel(x), np.ravel(y))
        if cx.size == 0:
            return
        finite = np.isfinite(cx) & np.isfinite(ry)
        if cx.size == 1:
            if finite[0]:
                self._set(cx, ry, layer)
            return
        seg_ok = finite[:-1] & finite[1:]
        x0, y0 = cx[:-1][seg_ok], ry[:-1][seg_ok]
        dx, dy = cx[1:][seg_ok] - x0, ry[1:][seg_ok] - y0
        # clip each segment to the canvas (one dot of slack): a point far outside (a value
        # 1e30 times the axis) must not become 1e30 samples
        fx, fy = cx[finite], ry[finite]
        if fx.size and (fx.min() >= -1.0 and fx.max() <= self.dot_w and fy.min() >= -1.0
                        and fy.max() <= self.dot_h):
            inside = np.ones(x0.size, dtype=bool)  # every point on the canvas: nothing to clip
        else:
            t0, t1 = clip_segments(x0, y0, dx, dy, (-1.0, self.dot_w), (-1.0, self.dot_h))
            inside = t0 <= t1
            x0, y0 = x0 + t0 * dx, y0 + t0 * dy
            dx, dy = (t1 - t0) * dx, (t1 - t0) * dy
            x0, y0, dx, dy = (np.where(inside, a, 0.0) for a in (x0, y0, dx, dy))
        # each segment sampled at ≤ 1 dot steps along its major axis; at least one sample (the
        # count decided on the snapped length: a segment a whole number of dots long, as the
        # horizon line is, gets the same samples whatever the last bits, and with them the
        # same phase of the dot pattern along the rest of the path)
        steps = np.maximum(snapped_ceil(np.maximum(np.abs(dx), np.abs(dy))), 1.0)
        n = steps.astype(np.int64)
        total = int(n.sum())
        seg = np.repeat(np.arange(n.size), n)
        k = np.arange(total) - np.repeat(np.cumsum(n) - n, n)
        frac = k / steps[seg]  # steps ≥ 1
        # the last point of each run of valid segments (the samples stop short of it)
        ok_next = np.zeros_like(seg_ok)
        ok_next[:-1] = seg_ok[1:]
        ends = (seg_ok & ~ok_next)[seg_ok]
        drawn = np.repeat(inside, n)  # samples of clipped-away segments are dropped
        xs = np.concatenate([(x0[seg] + frac * dx[seg])[drawn], (x0 + dx)[ends & inside]])
        ys = np.concatenate([(y0[seg] + frac * dy[seg])[drawn], (y0 + dy)[ends & inside]])
        touched = np.zeros(cx.size, dtype=bool)  # points on a valid segment
        touched[:-1] |= seg_ok
        touched[1:] |= seg_ok
        lone = finite & ~touched  # isolated points
        pat = np.array(PATTERNS[self.layers[layer].pattern])
        keep = pat[np.arange(xs.size) % pat.size]
        self._set(xs[keep], ys[keep], layer)
        self._set(cx[lone], ry[lone], layer)

    def arc_points(self, cx: float, cy: float, r: float, t0_deg: float = 0.0,
                   t1_deg: float = 360.0) -> tuple[np.ndarray, np.ndarray]:
        """The points of an arc of radius ``r`` (data units, x and y scaled alike) from angle
        ``t0`` to ``t1`` measured from +y toward +x (the polar plots' θ), about one dot apart:
        :meth:`polyline` draws it (several arcs in one call, separated by NaN)."""
        (x0, x1) = self.xlim
        r_dots = abs(r) * self.dot_w / (x1 - x0)  # x1 > x0
        n = int(np.clip(snapped_ceil(np.radians(abs(t1_deg - t0_deg)) * r_dots), 8, 20000))
        t = np.radians(np.linspace(t0_deg, t1_deg, n + 1))
        return cx + r * np.sin(t), cy + r * np.cos(t)

    def text(self, row: int, col: int, s: str, color: str | None = None) -> None:
        """Text over the cells from ``(row, col)`` (cropped at the right edge)."""
        self.overlays.append((int(row), int(col), str(s), color))

    # -- output --------------------------------------------------------------------------------
    def cells(self) -> tuple[np.ndarray, np.ndarray]:
        """``(codes, top)``: per cell the braille bit mask (0–255) and the id of the last
        layer with a dot there (−1: empty)."""
        codes = np.zeros((self.height, self.width), dtype=np.int64)
        top = np.full((self.height, self.width), -1, dtype=np.int16)
        for r in range(4):  # 8 strided views, one per dot position: cheaper than a 4-D reduce
            for c in range(2):
                o = self.owner[r::4, c::2]
                codes |= np.where(o >= 0, int(DOT_BITS[r, c]), 0)
                np.maximum(top, o, out=top)
        return codes, top

    def rows(self, like: BrailleCanvas | None = None) -> list[list[Segment]]:
        """Segments per cell row, each row exactly :attr:`width` cells.  ``like``: the canvas
        shown before in the same place; a row whose characters and colours are the same as its
        row is that row's list itself, not built again."""
        self._drawn = self._build(like)
        return self._drawn[2]

    def _build(self, like: BrailleCanvas | None) -> tuple:
        codes, top = self.cells()
        if self.charset == "ascii":
            markers = np.array([ly.marker for ly in self.layers] + [" "])
            chars = markers[top]  # top = −1 picks the trailing " "
        else:
            chars = BRAILLE_CHARS[codes]  # code 0 is the blank braille cell: a space instead
        chars = np.ascontiguousarray(chars, dtype="<U1")
        # colour ids: layer colours, then overlay colours; −1 (and code 0) = no colour
        palette: list[str | None] = [ly.color for ly in self.layers]
        cid = np.where(codes == 0, -1, top).astype(np.int64)
        for row, col, s, color in self.overlays:
            if not 0 <= row < self.height:
                continue
            lo, hi = max(col, 0), min(col + len(s), self.width)
            if hi <= lo:
                continue
            palette.append(color)
            chars[row, lo:hi] = list(s[lo - col:hi - col])
            cid[row, lo:hi] = len(palette) - 1
        if self.color == "none":
            cid[:] = -1
        palette.append(None)  # id −1
        # a blank cell shows no colour: it joins the run on its left (fewer segments)
        blank = chars == " "
        cols = np.where(blank, 0, np.arange(self.width)[None, :])
        np.maximum.accumulate(cols, axis=1, out=cols)
        cid = np.take_along_axis(cid, cols, axis=1)
        # each cell's colour as a number that means the same colour on every canvas
        colour = np.array([_colour_id(c) for c in palette])[cid]
        old = None if like is None else like._drawn
        diff = None
        if old is not None and old[0].shape == chars.shape:
            diff = (old[0] != chars) | (old[1] != colour)
        out, same = kept_rows(None if diff is None else old[2], diff, self.height)
        starts = np.ones(cid.shape, dtype=bool)
        starts[:, 1:] = cid[:, 1:] != cid[:, :-1]
        starts[same] = False  # only the runs of the rows that changed
        # every run of every row at once (as the half-block rows): a run ends where the next
        # begins in the flat cell order, or at the end of its row
        rows, cols = np.nonzero(starts)
        flat = rows * self.width + cols
        ends = np.minimum(np.append(flat[1:], self.height * self.width),
                          (rows + 1) * self.width)
        styles = [_style(c, self.color) for c in palette]
        run_styles = [styles[i] for i in cid[rows, cols].tolist()]
        # one character per cell: the rows of the contiguous U1 array as one string
        text = "".join(chars.view(f"<U{self.width}")[:, 0].tolist())
        for r, a, b, st in zip(rows.tolist(), flat.tolist(), ends.tolist(), run_styles,
                               strict=True):
            out[r].append(Segment(text[a:b], st))
        if diff is not None:
            mark_changed(out, old[2], ~same, diff)
        return chars, colour, out

    def __rich_console__(self, console: Console, options: ConsoleOptions) -> RenderResult:
        new_line = Segment.line()
        for row in self.rows():
            yield from row
            yield new_line

    def __rich_measure__(self, console: Console, options: ConsoleOptions) -> Measurement:
        return Measurement(self.width, self.width)


def clip_segments(x0, y0, dx, dy, xlim, ylim) -> tuple[np.ndarray, np.ndarray]:
    """Liang-Barsky, vectorised: the parameter range ``[t0, t1]`` ⊂ [0, 1] of each segment
    ``(x0, y0) + t (dx, dy)`` inside the box; ``t0 > t1`` where it misses the box."""
    t0 = np.zeros_like(x0)
    t1 = np.ones_like(x0)
    for p, q in ((-dx, x0 - xlim[0]), (dx, xlim[1] - x0), (-dy, y0 - ylim[0]),
                 (dy, ylim[1] - y0)):
        par = p == 0.0
        # parallel to this edge: inside if q ≥ 0, else the whole segment is out
        t1 = np.where(par & (q < 0), -1.0, t1)
        r = np.divide(q, p, out=np.zeros_like(q), where=~par)  # p = 0 handled above
        t0 = np.where(~par & (p < 0), np.maximum(t0, r), t0)
        t1 = np.where(~par & (p > 0), np.minimum(t1, r), t1)
    return t0, t1


def legend_sample(pattern: str, charset: str, marker: str, n: int = 3) -> str:
    """``n`` cells showing a horizontal line in ``pattern`` (its markers in ASCII)."""
    if charset == "ascii":
        return marker * n
    pat = PATTERNS[pattern]
    code = ""
    for c in range(n):
        bits = 0
        for k in range(2):  # the two dots of the cell's third row
            if pat[(2 * c + k) % len(pat)]:
                bits |= int(DOT_BITS[2, k])
        code += chr(BRAILLE_BASE + bits) if bits else " "
    return code


def charset_for(encoding: str | None) -> str:
    """``braille`` when ``encoding`` can encode U+2800, else ``ascii`` (a non-UTF terminal).
    No encoding (an in-memory text stream) means text, which Python writes as UTF-8."""
    try:
        chr(BRAILLE_BASE + 0xFF).encode(encoding or "utf-8")
    except (LookupError, UnicodeEncodeError):
        return "ascii"
    return "braille"


def nice_ticks(lo: float, hi: float, target: int = 5) -> np.ndarray:
    """Round tick values (1-2-5 steps) inside ``[lo, hi]``, about ``target`` of them."""
    span = hi - lo
    if not np.isfinite(span) or span <= 0:
        return np.array([lo])
    raw = span / max(target, 1)
    e = 10.0 ** np.floor(np.log10(raw))
    step = next(m * e for m in (1.0, 2.0, 5.0, 10.0) if m * e >= raw)
    first = np.ceil(lo / step - 1e-9) * step
    return np.arange(first, hi + step * 1e-9, step)


Curve = tuple[str, np.ndarray, np.ndarray]  # (label, x, y)


def curve_layers(canvas: BrailleCanvas, curves: Sequence[Curve],
                 colors: Sequence[str]) -> list[int]:
    """One layer per curve: colours as given, patterns and markers in turn."""
    return [canvas.layer(colors[j], CURVE_PATTERNS[j % len(CURVE_PATTERNS)],
                         CURVE_MARKERS[j % len(CURVE_MARKERS)]) for j in range(len(curves))]


def draw_legend(canvas: BrailleCanvas, curves: Sequence[Curve], ids: Sequence[int],
                row: int = 0, col: int = 0) -> None:
    """One line per curve, top-left: a sample of its line, then its label.  When the canvas
    has fewer rows below ``row`` than there are curves, the curves of one compare side drawn
    alike (labels ``A:red``, ``A:green`` …, one pattern: only their colours differ) share a
    line, each name in its own colour: ``•••• A:red green blue``."""
    layers = [canvas.layers[lid] for lid in ids]
    lines: list[list[int]] = []  # the curves of each line
    fold = len(curves) > canvas.height - row
    for k, ((label, _, _), ly) in enumerate(zip(curves, layers, strict=True)):
        last = lines[-1][-1] if lines else None
        if (fold and last is not None and ":" in label
                and label.split(":")[0] == curves[last][0].split(":")[0]
                and (ly.pattern, ly.marker) == (layers[last].pattern, layers[last].marker)):
            lines[-1].append(k)
        else:
            lines.append([k])
    for r, members in enumerate(lines):
        first = layers[members[0]]
        text = legend_sample(first.pattern, canvas.charset, first.marker) + " "
        x = col
        for n, k in enumerate(members):
            label = curves[k][0]
            piece = text + label if n == 0 else " " + label.split(":", 1)[1]
            canvas.text(row + r, x, piece, layers[k].color)
            x += len(piece)
