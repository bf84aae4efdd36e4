"""The viewer's screen: Textual's partial update doing only the work whose result reaches the
terminal, each change written from its first cell.

Textual 8's compositor repaints the dirty regions of a frame like this
(``Compositor.render_partial_update``): every visible widget whose clip overlaps the bounding
box of all dirty regions renders all its lines; every line holding a dirty span then divides
every such widget's strip at every widget edge on that line (the frontmost widget's piece of
each interval between two edges wins); ``ChopsUpdate.render_segments`` then writes, per dirty
span, every piece it overlaps from the piece's first cell to the span's end.  A θi key at
160×48 dirties the map, both sections and the status line, whose bounding box is the whole
screen: the screen, its four containers, the parameter panel and the footer were rendered and
divided on every dirty line for nothing, and a change in the middle of a map row was written
from the map's left edge.

:class:`ViewerCompositor` fills only the pieces that overlap a span, front to back, so a widget
renders only when one of its pieces is written and no widget in front has filled it;
:class:`SpansUpdate` writes each span from its first cell.  The cells on the terminal are the
same as with Textual's own update after every paint (tests/test_paint.py replays both into a
terminal model); the bytes are fewer and the paint cheaper (θi steps at 160×48: ≈ 0.72× the
characters, ≈ 0.26× the paint's CPU time; ``python scripts/bench_paint.py``).  The Textual internals
this relies on are reached through :mod:`.textual_internals`; without them
(:data:`~.textual_internals.PARTIAL_PAINT` false) the screen is Textual's, unchanged.
"""

from __future__ import annotations

from rich.cells import cell_len
from rich.color import ColorSystem
from rich.console import COLOR_SYSTEMS, Console
from rich.segment import Segment
from textual.geometry import Region
from textual.strip import Strip

from tuibrdf.app.textual_internals import (
    HOLD_PAINTS,
    ChopsUpdate,
    Compositor,
    HeldPaints,
    install_compositor,
    regions_to_spans,
    take_dirty_regions,
)


def _cells(strip: Strip, start: int, stop: int, system: ColorSystem) -> tuple[int, str]:
    """The terminal text of ``strip``'s cells ``[start, stop)`` (as Textual's
    ``strip.crop(start, stop).render(...)``, without the new strip), and the cell it starts at:
    ``start``, or the first cell of a segment holding a character more than one cell wide
    that ``start`` falls in (cut there, it would be written as spaces)."""
    render = Strip.render_style
    out: list[str] = []
    pos, first = 0, -1
    for text, style, _ in strip:
        n = cell_len(text)
        if first < 0:
            if pos + n <= start:
                pos += n
                continue
            if pos < start and len(text) == n:  # one cell a character: cut at start
                text, n, pos = text[start - pos:], n - (start - pos), start
            first = pos
        if pos + n > stop:  # the end cut as Textual's crop makes it
            text = Segment(text, style).split_cells(stop - pos)[0].text
        if text:
            out.append(text if style is None else render(style, text, system))
        pos += n
        if pos >= stop:
            break
    return (start if first < 0 else first), "".join(out)


class SpansUpdate(ChopsUpdate):
    """Textual's partial update, each span written from its first cell.  Textual writes a
    span from the start of the widget's piece it falls in (``ChopsUpdate.render_segments``
    crops only its end: "TODO: crop to x extents"), so a change in the middle of a map row
    re-sent the row from the map's left edge; the cells before the span did not change."""

    def render_segments(self, console: Console) -> str:
        # the colour system Strip.render uses (Rich's name for it, back to the enum)
        system = COLOR_SYSTEMS.get(console.color_system) or ColorSystem.TRUECOLOR
        sequences: list[str] = []
        append = sequences.append
        chops, chop_ends = self.chops, self.chop_ends
        last_y = self.spans[-1][0]
        for y, x1, x2 in self.spans:
            for end, (x, strip) in zip(chop_ends[y], chops[y].items(), strict=False):
                if strip is None or x >= x2 or end <= x1:
                    continue
                if x >= x1 and end <= x2:  # the whole piece (its text cached in the strip)
                    append(f"\x1b[{y + 1};{x + 1}H")  # Rich's Control.move_to(x, y)
                    append(strip.render(console))
                    continue
                first, text = _cells(strip, max(x1 - x, 0), min(end, x2) - x, system)
                append(f"\x1b[{y + 1};{x + first + 1}H")
                append(text)
            if y != last_y:
                append("\n")
        return "".join(sequences)


class ViewerCompositor(Compositor):
    """Textual's compositor; its partial update renders and divides only what is written."""

    def render_partial_update(self) -> ChopsUpdate | None:
        regions = take_dirty_regions(self)
        if not regions:
            return None
        height = self.size.height
        spans = [span for span in regions_to_spans(self, regions) if 0 <= span[0] < height]
        if not spans:
            return None
        cuts = self.cuts
        chops: list[dict[int, Strip | None]] = [dict.fromkeys(row[:-1]) for row in cuts]
        # per line, the pieces that overlap a span ({cut: end}) and are not yet filled
        need: dict[int, dict[int, int]] = {}
        for y, x1, x2 in spans:
            row = cuts[y]
            line = need.setdefault(y, {})
            for x, end in zip(row, row[1:], strict=False):
                if x < x2 and end > x1:
                    line[x] = end
            if not line:
                del need[y]
        for widget, (region, clip) in self.visible_widgets.items():
            if not need:
                break
            render = region.intersection(clip)
            if not (render.width and render.height):
                continue
            x0, y0 = render.x, render.y
            first, last = render.column_span
            lines = [y for y in range(y0, y0 + render.height)
                     if (line := need.get(y)) and any(first <= x < last for x in line)]
            if not lines:
                continue
            if clip.contains_region(region):
                strips = widget.render_lines(Region(0, 0, region.width, region.height))
            else:
                strips = widget.render_lines(Region(x0 - region.x, y0 - region.y,
                                                    render.width, render.height))
            for y in lines:
                inside = [x for x in cuts[y] if first <= x <= last]
                strip = strips[y - y0]
                pieces = [strip] if len(inside) == 2 else strip.divide([x - x0 for x in inside[1:]])
                line, chop = need[y], chops[y]
                for x, piece in zip(inside, pieces, strict=False):  # the last edge ends a piece
                    if x in line:  # else filled by a widget in front, or not written
                        chop[x] = piece
                        del line[x]
                if not line:
                    del need[y]
        return SpansUpdate(chops, spans, [row[1:] for row in cuts])


class ViewerScreen(HeldPaints):
    """The viewer's main screen, painted by :class:`ViewerCompositor` when Textual has what it
    uses.

    Held (:class:`~.textual_internals.HeldPaints`) while a new layout waits for its frame:
    at start-up until the first frame is drawn, and after a key that shows other panes (a view,
    a model, compare mode, a resize) until theirs is, ``BrdfApp.HOLD_S`` at most.  Textual
    paints a layout as soon as it is made: at start-up three times with empty panes and then
    the first frame's screen twice (117 kB at 160×48 for a screen of 44 kB), and at a view
    change the new panes empty, then filled."""

    def __init__(self, *args, **kw) -> None:
        super().__init__(*args, **kw)
        install_compositor(self, ViewerCompositor())
        self.held = HOLD_PAINTS
