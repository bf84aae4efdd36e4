"""Half-block images: two pixels per terminal cell.

Each cell shows ``'▀'`` with the foreground colour = top pixel and the background colour = bottom
pixel, so a ``W × H`` cell area holds ``W × 2H`` pixels; terminal cells are about 1:2, which makes
these pixels roughly square.

Input is a *level-index image* (``H_px × W_px`` ints) plus a palette (``L × 3`` uint8); the index
``-1`` (:data:`TRANSPARENT`) leaves the terminal background visible.  An RGB image goes through
:meth:`HalfBlockImage.from_rgb`, which builds the palette from the image's distinct colours.

Fast by construction (≈ 111 ms per 160×48 frame with one ``Style`` per cell, ≈ 1.5 ms like
this, when it was written; ``scripts/bench_draw.py`` measures a frame's drawing now):

1. per cell, ``code = (top + 1) · base + (bottom + 1)`` over the colours drawn (the packed
   24-bit colour, the xterm index, the plain character), not the palette's indices: a code
   means one look in every picture, so looks and runs are kept across frames whatever the
   palette (an RGB picture's is new each frame), and rows whose codes did not change are
   kept;
2. runs of equal codes along a row are found with numpy and become **one** ``Segment`` each;
3. one ``Style`` per (foreground, background) pair, cached across frames;
4. a run whose top and bottom colours are equal is drawn as spaces on a background colour.

Colour systems (``rows(system)``):

===========  ================================================================================
truecolor    24-bit colours, as given
256          the palette is first mapped to the xterm colours 16–255 (nearest, squared RGB
             distance; a colour map's ramp nearest in OKLab with its lightness never
             falling, :func:`ramp_to_xterm`), *then* runs are found, so neighbours landing
             on one index merge
none         plain text: one character per cell from :data:`ASCII_RAMP`, by the mean Rec.709
             luma of its two pixels, so the picture stays readable in a log file
===========  ================================================================================

Every segment has a non-None ``Style`` (Textual 8.2's ``NO_COLOR`` filter crashes on ``None``).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import lru_cache
from typing import Literal

import numpy as np
from rich.color import Color, ColorTriplet, ColorType
from rich.console import Console, ConsoleOptions, RenderResult
from rich.measure import Measurement
from rich.segment import Segment
from rich.style import Style

from tuibrdf.core.conventions import REC709  # here applied to 8-bit values: a luma
from tuibrdf.core.numerics import snapped_rint
from tuibrdf.render.rowdiff import kept_rows, mark_changed

ColorSystem = Literal["truecolor", "256", "none"]
COLOR_SYSTEMS: tuple[str, ...] = ("truecolor", "256", "none")

UPPER_HALF = "▀"
LOWER_HALF = "▄"
#: density ramp of the plain-text fallback, dark → bright
ASCII_RAMP = " .:-=+*#%@"
#: the plain-text guide (horizon ring): not in :data:`ASCII_RAMP`, so never read as a value
RING_CHAR = "~"
#: index of a pixel that shows the terminal's own background
TRANSPARENT = -1
#: shades per channel of a photograph-like picture in truecolor (the lit views, a map in RGB
#: colours): each 8-bit channel is drawn on the nearest of 64 evenly spaced values (≤ 2/255
#: off).  Nearly every pixel of such a picture is a colour of its own and every new colour is
#: a new terminal style: a lit sphere had ~2,600 runs of equal cells instead of ~1,750 and
#: cost ~15–20 ms a key instead of ~4; disney.brdf's map met 980 new colour pairs a key
#: instead of 245, and its rows took 9.5 ms to build instead of 3.1.  Only the drawing is
#: quantised: the image's palette, which exports read, keeps every bit
SHADES = 64


def quantise_channels(rgb: np.ndarray, levels: int = SHADES) -> np.ndarray:
    """8-bit colours rounded to the nearest of ``levels`` evenly spaced values (0 and 255
    kept); each rounding decided on the snapped value (core.numerics.snap)."""
    step = 255.0 / (levels - 1)  # levels ≥ 2
    return snapped_rint(snapped_rint(np.asarray(rgb) / step) * step).astype(np.uint8)


@dataclass(frozen=True)
class Mark:
    """A glyph drawn over one cell (e.g. the mirror direction): ``glyph`` in ``rgb`` on the
    cell's mean colour; ``ascii`` replaces it in the plain-text fallback."""

    row: int  # cell row
    col: int  # cell column
    glyph: str = "×"
    ascii: str = "X"
    rgb: tuple[int, int, int] = (255, 0, 0)


# ---------------------------------------------------------------------------------------------
# xterm 256-colour palette


def xterm_palette() -> np.ndarray:
    """The 256 xterm colours as ``(256, 3)`` uint8.

    0–15 are the terminal's themable system colours (values here are xterm's defaults, never
    chosen by :func:`to_xterm`); 16–231 the 6×6×6 cube on levels 0, 95, 135, 175, 215, 255;
    232–255 the grey ramp 8, 18, …, 238.
    """
    system = [
        (0, 0, 0), (205, 0, 0), (0, 205, 0), (205, 205, 0),
        (0, 0, 238), (205, 0, 205), (0, 205, 205), (229, 229, 229),
        (127, 127, 127), (255, 0, 0), (0, 255, 0), (255, 255, 0),
        (92, 92, 255), (255, 0, 255), (0, 255, 255), (255, 255, 255),
    ]  # fmt: skip
    levels = np.array([0, 95, 135, 175, 215, 255])
    r, g, b = np.meshgrid(levels, levels, levels, indexing="ij")
    cube = np.stack([r.ravel(), g.ravel(), b.ravel()], axis=1)
    grey = np.repeat((8 + 10 * np.arange(24))[:, None], 3, axis=1)
    return np.concatenate([np.array(system), cube, grey]).astype(np.uint8)


XTERM = xterm_palette()


def to_xterm(rgb: np.ndarray) -> np.ndarray:
    """Nearest xterm colour index in 16–255 (squared RGB distance, ties to the lower index) for
    ``rgb`` of shape ``(..., 3)``; the themable system colours 0–15 are never used."""
    rgb = np.asarray(rgb, dtype=np.int64)
    cand = XTERM[16:].astype(np.int64)
    d = ((rgb[..., None, :] - cand) ** 2).sum(axis=-1)
    return (16 + np.argmin(d, axis=-1)).astype(np.int64)


def oklab(rgb: np.ndarray) -> np.ndarray:
    """OKLab ``(L, a, b)`` of 8-bit sRGB colours ``(..., 3)`` (Ottosson 2020: sRGB decoded to
    linear, the LMS matrix, a cube root, the Lab matrix); L ≈ perceived lightness in [0, 1]."""
    c = np.asarray(rgb, dtype=float) / 255.0
    lin = np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)
    lms = np.cbrt(lin @ _OK_M1.T)
    return lms @ _OK_M2.T


_OK_M1 = np.array([[0.4122214708, 0.5363325363, 0.0514459929],
                   [0.2119034982, 0.6806995451, 0.1073969566],
                   [0.0883024619, 0.2817188376, 0.6299787005]])
_OK_M2 = np.array([[0.2104542553, 0.7936177850, -0.0040720468],
                   [1.9779984951, -2.4285922050, 0.4505937099],
                   [0.0259040371, 0.7827717662, -0.8086757660]])
_XTERM_LAB = oklab(XTERM[16:])
#: colour-map ramps (:func:`register_ramp`, as bytes) → their xterm indices, lightness never
#: falling; None until a picture is first drawn in 256 colours (a ramp's choice costs ≈ 5 ms,
#: which a truecolor viewer's first frame need not wait for)
_RAMPS: dict[bytes, np.ndarray | None] = {}


def ramp_to_xterm(ramp: np.ndarray) -> np.ndarray:
    """xterm indices (16–255) for an ordered colour ramp: each entry the nearest colour in
    OKLab among those at least as light as the previous entry's choice, so the ramp never
    steps back in lightness (nearest in RGB, viridis' dark blues went through colour 60, a
    grey-lilac lighter than its neighbours: a false contour around every lobe)."""
    lab = oklab(ramp)
    out = np.empty(len(lab), dtype=np.int64)
    floor = -np.inf
    for i, c in enumerate(lab):
        d = ((_XTERM_LAB - c) ** 2).sum(axis=-1)
        d[_XTERM_LAB[:, 0] < floor - 1e-12] = np.inf  # darker than the last choice: not allowed
        j = int(np.argmin(d))
        out[i], floor = 16 + j, _XTERM_LAB[j, 0]
    return out


def register_ramp(ramp: np.ndarray) -> None:
    """Declare ``ramp`` (``(L, 3)`` uint8, dark to light) a colour map's palette: a picture whose
    palette begins with it is drawn in 256 colours with :func:`ramp_to_xterm`."""
    _RAMPS.setdefault(np.ascontiguousarray(ramp, dtype=np.uint8).tobytes(), None)


def xterm_indices(palette: np.ndarray) -> np.ndarray:
    """The xterm colours a palette is drawn with in 256 colours: a registered ramp's
    (:func:`register_ramp`) for the entries it begins with, :func:`to_xterm` for the rest
    (the ring, marks, an RGB picture's colours)."""
    pal = np.ascontiguousarray(palette, dtype=np.uint8)
    for key, xi in _RAMPS.items():
        n = len(key) // 3
        if len(pal) >= n and pal[:n].tobytes() == key:
            if xi is None:
                xi = _RAMPS[key] = ramp_to_xterm(np.frombuffer(key, np.uint8).reshape(n, 3))
            return np.concatenate([xi, to_xterm(pal[n:])]) if len(pal) > n else xi
    return to_xterm(pal)


def luma(rgb: np.ndarray) -> np.ndarray:
    """Rec.709 luma in [0, 1] of 8-bit colours ``(..., 3)``."""
    return np.asarray(rgb, dtype=float) @ REC709 / 255.0


# ---------------------------------------------------------------------------------------------
# styles, cached across frames


@lru_cache(maxsize=1 << 16)
def cell_style(fg: int | tuple[int, int, int] | None, bg: int | tuple[int, int, int] | None):
    """The ``Style`` for a foreground/background pair: an int is an xterm index, a tuple an RGB
    colour, ``None`` the terminal default.  Never returns ``None`` (see module docstring).
    Built with ``Style.from_color`` (no parsing: 3 µs, not 13 µs, which counts for a lit
    sphere's thousands of new colours a frame)."""
    return Style.from_color(_color(fg), _color(bg))


def _color(c: int | tuple[int, int, int] | None) -> Color | None:
    """What ``Color.from_rgb`` / ``Color.from_ansi`` return, made directly (and kept: an RGB
    picture's new colour pairs are mostly of colours met before, and making a colour costs
    8 times its look-up)."""
    if c is None:
        return None
    if isinstance(c, tuple):
        return _rgb(*c)
    return Color.from_ansi(c)


@lru_cache(maxsize=1 << 16)
def _rgb(r: int, g: int, b: int) -> Color:
    r, g, b = int(r), int(g), int(b)  # numpy integers too (a cache key equal to the int's)
    return Color(f"#{r:02x}{g:02x}{b:02x}", ColorType.TRUECOLOR, triplet=ColorTriplet(r, g, b))


NULL_STYLE = Style()


# ---------------------------------------------------------------------------------------------
# run detection


def find_runs(codes: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Runs of equal values along each row of a 2-D int array.

    Returns ``(row, start, length)`` arrays, in reading order; each row's runs cover it exactly.
    """
    h, w = codes.shape
    change = np.ones((h, w), dtype=bool)
    np.not_equal(codes[:, 1:], codes[:, :-1], out=change[:, 1:])
    rows, starts = np.nonzero(change)
    flat = rows * w + starts
    # change[:, 0] is always set, so a row's last run ends where the next row's first begins
    lengths = np.diff(np.append(flat, h * w))
    return rows, starts, lengths


def split_halves(index: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(top, bottom)`` pixel rows of each cell row; an odd last row gets a transparent
    bottom."""
    if index.shape[0] % 2:
        pad = np.full((1, index.shape[1]), TRANSPARENT, dtype=index.dtype)
        index = np.concatenate([index, pad])
    return index[0::2], index[1::2]


#: a run's key in a code table's segments: ``code * RUN_KEY + length`` (a run of 2¹⁴ cells
#: or more is not kept); a truecolor code is below 2⁴⁹, so the key stays below 2⁶³
RUN_KEY = 1 << 14
#: a colour system's code table is emptied when it holds this many runs (a session of RGB
#: pictures meets new colour pairs every frame; ~200 bytes a run)
RUNS_KEPT = 1 << 17
_TABLES: dict[str, tuple[dict, dict]] = {}


def _code_table(system: str) -> tuple[dict, dict]:
    """``(looks, runs)`` of ``system``'s cells: ``code → (character, style)`` (the codes of
    :meth:`HalfBlockImage._build`, which say the cell's colours themselves, whatever the
    palette; a mark's look is keyed by the mark and its two pixels' colours) and ``code *
    RUN_KEY + length → Segment`` of a run; filled as they are met and kept for the next
    frames: a frame meets the same colour pairs and runs again, an RGB picture too (its
    palette is its own colours, new each frame), and working each out anew was ≈ 40 % of
    drawing it."""
    table = _TABLES.get(system)
    if table is None or len(table[1]) > RUNS_KEPT:
        table = _TABLES[system] = ({}, {})
    return table


# ---------------------------------------------------------------------------------------------
# the renderable


class HalfBlockImage:
    """A level-index image drawn with half blocks.

    ``index``: ``(H_px, W_px)`` ints in ``[-1, L)``; ``palette``: ``(L, 3)`` values in 0–255;
    ``marks``: glyphs drawn over cells.  ``color_system`` fixes the output; ``None`` follows the
    console it is printed to.  ``shades``: in truecolor, each channel is drawn on that many
    levels (:func:`quantise_channels`; for photograph-like pictures, :data:`SHADES`).
    :meth:`rows` gives the per-row segment lists, each exactly :attr:`width` cells long (a
    Textual widget wraps them in ``Strip`` objects).
    """

    def __init__(
        self,
        index: np.ndarray,
        palette: np.ndarray,
        marks: Sequence[Mark] = (),
        color_system: ColorSystem | None = None,
        ring: int | None = None,
        shades: int | None = None,
    ) -> None:
        index = np.asarray(index)
        palette = np.asarray(palette)
        if index.ndim != 2 or not np.issubdtype(index.dtype, np.integer):
            raise ValueError(f"index must be a 2-D integer array, got {index.dtype} {index.shape}")
        if palette.ndim != 2 or palette.shape[1] != 3:
            raise ValueError(f"palette must have shape (L, 3), got {palette.shape}")
        if palette.size and (palette.min() < 0 or palette.max() > 255):
            raise ValueError("palette values must lie in 0..255")
        if index.size and (index.min() < TRANSPARENT or index.max() >= len(palette)):
            raise ValueError(f"index values must lie in [-1, {len(palette)})")
        if color_system is not None and color_system not in COLOR_SYSTEMS:
            raise ValueError(f"color system {color_system!r}: expected one of {COLOR_SYSTEMS}")
        if shades is not None and not 2 <= shades <= 256:
            raise ValueError(f"shades must lie in 2..256, got {shades}")
        self.index = index.astype(np.int64)
        self.palette = palette.astype(np.uint8)
        self.marks = tuple(marks)
        self.color_system = color_system
        #: a palette index that is a guide, not data (the map's horizon ring): plain text
        #: draws it with :data:`RING_CHAR`, never a character of the density ramp
        self.ring = ring
        self.shades = shades
        self.width = int(index.shape[1])
        self.height = (int(index.shape[0]) + 1) // 2
        self._rows: dict[str, list[list[Segment]]] = {}
        self._codes: dict[str, np.ndarray] = {}  # each system's cell codes (:meth:`_build`)

    @classmethod
    def from_rgb(
        cls,
        rgb: np.ndarray,
        mask: np.ndarray | None = None,
        marks: Sequence[Mark] = (),
        color_system: ColorSystem | None = None,
        shades: int | None = None,
    ) -> HalfBlockImage:
        """From an ``(H_px, W_px, 3)`` RGB image (0–255); pixels where ``mask`` is False are
        transparent.  The palette is the sorted set of distinct colours."""
        rgb = np.asarray(rgb)
        if rgb.ndim != 3 or rgb.shape[2] != 3:
            raise ValueError(f"rgb must have shape (H, W, 3), got {rgb.shape}")
        packed = (rgb[..., 0].astype(np.int64) << 16) | (rgb[..., 1].astype(np.int64) << 8)
        packed |= rgb[..., 2].astype(np.int64)
        colors, inverse = np.unique(packed, return_inverse=True)
        index = inverse.reshape(packed.shape)
        if mask is not None:
            index = np.where(mask, index, TRANSPARENT)
        palette = np.stack([colors >> 16, (colors >> 8) & 255, colors & 255], axis=1)
        return cls(index, palette, marks, color_system, shades=shades)

    # -- segments ------------------------------------------------------------------------------

    def rows(self, system: ColorSystem = "truecolor",
             like: HalfBlockImage | None = None) -> list[list[Segment]]:
        """One list of segments per cell row (cached per colour system).  ``like``: the image
        shown before in the same place; a row whose cells are the same as its row is that
        row's list itself, not built again (a θi step changes ≈ 20 of a map's 45 rows)."""
        if system not in COLOR_SYSTEMS:
            raise ValueError(f"color system {system!r}: expected one of {COLOR_SYSTEMS}")
        if system not in self._rows:
            self._rows[system] = self._build(system, like)
        return self._rows[system]

    def _differ(self, codes: np.ndarray, system: str,
                like: HalfBlockImage | None) -> np.ndarray | None:
        """Cells that may differ from ``like``'s (None: all of them): the codes differ (they
        say the cells' colours, whatever the palettes), or a mark of either is there (a
        mark's code names a mark, not the colours under it)."""
        old = None if like is None else like._codes.get(system)
        if old is None or old.shape != codes.shape or like.ring != self.ring:
            return None
        diff = codes != old
        for m in (*self.marks, *like.marks):
            if 0 <= m.row < self.height and 0 <= m.col < self.width:
                diff[m.row, m.col] = True
        return diff

    def _build(self, system: str, like: HalfBlockImage | None = None) -> list[list[Segment]]:
        top, bottom = split_halves(self.index)
        if system == "none":
            codes, make = self._plain_codes(top, bottom)
        else:
            codes, make = self._color_codes(top, bottom, system)
        # marks get codes of their own (negative), so they split runs and never merge
        for k, m in enumerate(self.marks):
            if 0 <= m.row < self.height and 0 <= m.col < self.width:
                codes[m.row, m.col] = -(k + 1)
        self._codes[system] = codes
        diff = self._differ(codes, system, like)
        out, same = kept_rows(None if diff is None else like._rows[system], diff, self.height)
        looks, segments = _code_table(system)
        rows, starts, lengths = find_runs(codes)
        if same.any():  # only the runs of the rows that changed
            keep = ~same[rows]
            rows, starts, lengths = rows[keep], starts[keep], lengths[keep]
        run_codes = codes[rows, starts]
        # a run's segment, kept by code and length: one dict look-up a run; a mark's
        # (code < 0) key never matches
        keys = np.where((run_codes >= 0) & (lengths < RUN_KEY), run_codes * RUN_KEY + lengths,
                        -1).tolist()
        flat = [segments.get(k) for k in keys]
        if None in flat:
            for i in [i for i, seg in enumerate(flat) if seg is None]:
                code, n = int(run_codes[i]), int(lengths[i])
                key = code
                if code < 0:  # a mark: its glyph and colour over its two pixels' mean colour
                    m = self.marks[-code - 1]
                    r, c = int(rows[i]), int(starts[i])
                    under = tuple(tuple(self.palette[j].tolist()) if j >= 0 else None
                                  for j in (int(top[r, c]), int(bottom[r, c])))
                    key = (m.glyph, m.ascii, m.rgb, *under)
                got = looks.get(key)
                if got is None:
                    got = looks[key] = (make(code) if code >= 0
                                        else self._mark(m, key[3], key[4], system))
                flat[i] = seg = Segment(got[0] * n, got[1])
                if keys[i] >= 0:
                    segments[keys[i]] = seg
        # the runs are in reading order: each changed row's are the next ones
        ends = np.cumsum(np.bincount(rows, minlength=self.height)).tolist()
        for r in np.flatnonzero(~same).tolist():
            out[r] = flat[ends[r - 1] if r else 0:ends[r]]
        if diff is not None:
            mark_changed(out, like._rows[system], ~same, diff)
        return out

    def _color_codes(self, top, bottom, system):
        """A cell's code says its two colours, whatever the palette: ``(top + 1)·base +
        (bottom + 1)`` over the xterm index (256 colours) or the packed 24-bit colour
        (truecolor), −1 for transparent; so a code's look is the same in every picture."""
        if system == "256":
            colors = np.append(xterm_indices(self.palette), -1)  # index -1: the appended -1
            base = 257
        else:
            p = self.palette if self.shades is None else quantise_channels(self.palette,
                                                                           self.shades)
            p = p.astype(np.int64)
            colors = np.append((p[:, 0] << 16) | (p[:, 1] << 8) | p[:, 2], -1)
            base = (1 << 24) + 1
        top, bottom = colors[top], colors[bottom]
        rgb = system != "256"

        def color(c: int):
            return (c >> 16, (c >> 8) & 255, c & 255) if rgb else c

        def make(code: int) -> tuple[str, Style]:
            t, b = divmod(code, base)
            t, b = t - 1, b - 1
            ct = color(t) if t >= 0 else None
            cb = color(b) if b >= 0 else None
            if t == b:
                return " ", cell_style(None, cb) if cb is not None else NULL_STYLE
            if b < 0:
                return UPPER_HALF, cell_style(ct, None)
            if t < 0:
                return LOWER_HALF, cell_style(cb, None)
            return UPPER_HALF, cell_style(ct, cb)

        return (top + 1) * base + (bottom + 1), make

    def _plain_codes(self, top, bottom):
        y = np.append(luma(self.palette), 0.0)  # transparent reads as dark
        if self.ring is not None:  # half ring, half data: the data half alone
            rt, rb = top == self.ring, bottom == self.ring
            # ... unless the ring half is its column's outermost ring pixel (the pixel beyond
            # it, in the cell above a top half or below a bottom half, is not ring): where
            # the disc's top (bottom) edge is flat the ring is one pixel row, all of it in
            # such cells, and showing the data there left a gap in the guide
            above = np.vstack([np.zeros_like(rt[:1]), rb[:-1]])  # pixel above each top half
            below = np.vstack([rt[1:], np.zeros_like(rb[:1])])  # pixel below each bottom half
            outermost = (rt & (bottom >= 0) & ~rb & ~above) | (rb & (top >= 0) & ~rt & ~below)
            top, bottom = np.where(rt, bottom, top), np.where(rb, top, bottom)
        # the luma comes through a matrix product (the BLAS's order of operations): the ramp
        # step is decided on the snapped value (core.numerics.snap)
        level = snapped_rint((y[top] + y[bottom]) / 2 * (len(ASCII_RAMP) - 1)).astype(np.int64)
        if self.ring is not None:  # ring and ring, or ring and outside: the guide
            level[(top == self.ring) | (top < 0) & (bottom == self.ring)] = len(ASCII_RAMP)
            level[(rt | rb) & (top < 0) & (bottom < 0)] = len(ASCII_RAMP)
            level[outermost] = len(ASCII_RAMP)

        def make(code: int) -> tuple[str, Style]:
            return (ASCII_RAMP + RING_CHAR)[code], NULL_STYLE

        return level, make

    def _mark(self, m: Mark, t: tuple | None, b: tuple | None, system: str
              ) -> tuple[str, Style]:
        """A mark's look over its cell's two pixels' colours ``t``, ``b`` (None:
        transparent)."""
        if system == "none":
            return m.ascii, NULL_STYLE
        under = [np.array(c, dtype=float) for c in (t, b) if c is not None]
        bg = tuple(int(v) for v in np.rint(np.mean(under, axis=0))) if under else None
        fg = m.rgb
        if system == "256":
            fg = int(to_xterm(np.array(fg)))
            bg = int(to_xterm(np.array(bg))) if bg is not None else None
        return m.glyph, cell_style(fg, bg)

    def plain(self) -> str:
        """The plain-text fallback as a string (one line per cell row)."""
        return "\n".join("".join(s.text for s in row) for row in self.rows("none"))

    # -- Rich protocol -------------------------------------------------------------------------

    def __rich_console__(self, console: Console, options: ConsoleOptions) -> RenderResult:
        system = self.color_system or console_system(console)
        new_line = Segment.line()
        for row in self.rows(system):
            yield from row
            yield new_line

    def __rich_measure__(self, console: Console, options: ConsoleOptions) -> Measurement:
        return Measurement(self.width, self.width)


def console_system(console: Console) -> ColorSystem:
    """Map a Rich console's colour system onto ours (16-colour consoles get the 256 palette,
    which Rich downgrades itself)."""
    cs = console.color_system
    if cs is None:
        return "none"
    return "truecolor" if cs == "truecolor" else "256"
