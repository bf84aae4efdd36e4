"""A pane's renderable as rows of segments, each exactly the pane's width: what
``console.render_lines(renderable, width, height, pad=True)`` gives, without most of its cost.

Rich renders a ``Group`` by flattening every part into one segment stream and splitting it
again at each newline, measuring every segment's cells on the way: ≈ 5 ms for a half-block
map at 160×48, most of a key's drawing time.  The pictures of this package already know their
rows (:meth:`HalfBlockImage.rows`, :meth:`BrailleCanvas.rows`, each exactly their width), so
:func:`pane_lines` takes those as they are and sends only the rest (one-line titles, colour
bar ticks) through Rich.  tests/render/test_lines.py checks the two agree cell for cell on
every pane.
"""

from __future__ import annotations

from rich.cells import cell_len
from rich.console import Console, Group, RenderableType
from rich.segment import Segment
from rich.style import Style
from rich.text import Text

from tuibrdf.render.braille import BrailleCanvas
from tuibrdf.render.halfblock import HalfBlockImage, console_system
from tuibrdf.render.halfdiff_view import LeftLabelled

BLANK = Style()  # never None: Textual's NO_COLOR filter crashes on a None style


def _plain_line(text: Text, width: int) -> bool:
    """One row of one style that Rich would not wrap, justify or expand: its characters are
    its cells."""
    plain = text.plain
    return (not text.spans and "\n" not in plain and "\t" not in plain
            and text.justify in (None, "default", "left") and plain.isprintable()
            and len(plain) == cell_len(plain)
            and (len(plain) <= width or (text.no_wrap and text.overflow == "crop")))


def _short_lines(text: Text, width: int) -> list[Text] | None:
    """The lines of ``text`` when each is one row as it is (printable, one cell a character,
    at most ``width`` cells, no tab, not justified): Rich would neither wrap nor crop nor
    move them, so each line's own segments are its row (the status line's two or three
    lines: ≈ 0.4 ms a key less than Rich's line splitting).  Else None."""
    plain = text.plain
    flat = plain.replace("\n", "")
    if (text.justify not in (None, "default", "left") or "\t" in plain
            or not flat.isprintable() or len(flat) != cell_len(flat)):
        return None
    lines = text.split("\n", allow_blank=True)
    return None if any(len(line.plain) > width for line in lines) else lines


def fit_row(row: list[Segment], own: int, width: int, pad: Style = BLANK) -> list[Segment]:
    """``row`` (``own`` cells) cropped or padded to ``width`` cells (padding in ``pad``)."""
    if own == width:
        return row
    if own < width:
        return [*row, Segment(" " * (width - own), pad)]
    return Segment.adjust_line_length(row, width, pad)


def _styled(segments) -> list[Segment]:
    """``segments`` with a ``None`` style made :data:`BLANK` (Rich may leave one; Textual's
    NO_COLOR filter crashes on it)."""
    return [s if s.style is not None else Segment(s.text, BLANK) for s in segments]


def render_rows(part: RenderableType, console: Console, width: int,
                like: RenderableType | None = None) -> list[list[Segment]]:
    """Every row of ``part`` at ``width`` cells (its own height, not cropped or padded).
    ``like``: what was drawn before in the same place; a picture in it at the same position
    lends ``part``'s picture the rows they share (:meth:`HalfBlockImage.rows`,
    :meth:`BrailleCanvas.rows`), so an unchanged row is the same list as before."""
    if isinstance(part, Group):
        same = (isinstance(like, Group) and len(like.renderables) == len(part.renderables))
        olds = like.renderables if same else [None] * len(part.renderables)
        return [row for p, o in zip(part.renderables, olds, strict=True)
                for row in render_rows(p, console, width, o)]
    if isinstance(part, HalfBlockImage):
        prev = like if isinstance(like, HalfBlockImage) else None
        rows = part.rows(part.color_system or console_system(console), prev)
        return [fit_row(r, part.width, width) for r in rows]
    if isinstance(part, BrailleCanvas):
        rows = part.rows(like if isinstance(like, BrailleCanvas) else None)
        return [fit_row(r, part.width, width) for r in rows]
    if isinstance(part, LeftLabelled):
        return [fit_row(r, part.width, width) for r in part.rows()]
    if isinstance(part, Text) and _plain_line(part, width):  # a title: one style, one line
        style = console.get_style(part.style) if part.style else BLANK
        text = part.plain
        return [fit_row([Segment(text, style)] if text else [], len(text), width)]
    if isinstance(part, Text) and (lines := _short_lines(part, width)) is not None:
        return [fit_row(_styled(line.render(console, end="")), len(line.plain), width)
                for line in lines]
    rows = console.render_lines(part, console.options.update(width=width, height=None),
                                style=BLANK, pad=True)
    return [_styled(row) for row in rows]  # (the pictures above never leave a None style)


def fit_rows(rows: list[list[Segment]], width: int, height: int) -> list[list[Segment]]:
    """``rows`` of ``width`` cells as ``height`` rows (cropped, or padded with blank rows); the
    rows kept are the same lists."""
    return rows[:height] + [[Segment(" " * width, BLANK)] for _ in range(height - len(rows))]


def pane_lines(renderable: RenderableType, console: Console, width: int, height: int,
               like: RenderableType | None = None) -> list[list[Segment]]:
    """``height`` rows of ``width`` cells of ``renderable`` (:func:`fit_rows`); ``like`` as
    :func:`render_rows`."""
    return fit_rows(render_rows(renderable, console, width, like), width, height)
