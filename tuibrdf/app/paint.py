"""The viewer's screen and its compositor: Textual's partial update, doing only the work whose
result reaches the terminal.

Textual 8's compositor repaints the dirty regions of a frame like this
(``Compositor.render_partial_update``): every visible widget whose clip overlaps the bounding
box of all dirty regions renders all its lines; every line holding a dirty span then divides
every such widget's strip at every widget edge on that line (the frontmost widget's piece of
each interval between two edges wins); finally ``ChopsUpdate.render_segments`` writes, per
dirty span, the pieces it overlaps.  A θi key at 160×48 dirties the map, both sections and the
status line, whose bounding box is the whole screen: the screen, its four containers, the
parameter panel and the footer were rendered and divided on every dirty line, for nothing.

:class:`ViewerCompositor` fills only the pieces ``render_segments`` writes (the same test it
applies: a piece from ``x`` to ``end`` is written for a span ``[x1, x2)`` unless
``x > x2 or end <= x1``), front to back, so a widget renders only when one of its pieces is
written and is still unfilled by a widget in front; ``render_segments`` is Textual's own, so
the bytes are the same (tests/test_paint.py compares them with Textual's compositor frame by
frame).  Textual's internals it relies on are checked once (:data:`SUPPORTED`); without them
the screen uses Textual's compositor unchanged.
"""

from __future__ import annotations

from textual._compositor import ChopsUpdate, Compositor
from textual.geometry import Region
from textual.screen import Screen
from textual.strip import Strip

_EMPTY = Strip([], 0)


def _supported() -> bool:
    """Textual's compositor has what :class:`ViewerCompositor` uses (Textual 8.2)."""
    probe = Compositor()
    return all(hasattr(probe, name) for name in
               ("_dirty_regions", "_regions_to_spans", "cuts", "visible_widgets",
                "render_partial_update", "size")) and hasattr(ChopsUpdate, "render_segments")


SUPPORTED = _supported()


class ViewerCompositor(Compositor):
    """Textual's compositor; its partial update renders and divides only what is written."""

    def render_partial_update(self) -> ChopsUpdate | None:
        regions = self._dirty_regions.copy()
        self._dirty_regions.clear()
        if not regions:
            return None
        screen = self.size.region
        spans = list(self._regions_to_spans(regions))
        cuts = self.cuts
        chops: list[dict[int, Strip | None]] = [dict.fromkeys(row[:-1]) for row in cuts]
        # per line, the pieces render_segments writes ({cut: end}), not yet filled; a piece
        # that starts where a span ends is written as a cursor move and no cell: any strip
        # does for it
        need: dict[int, dict[int, int]] = {}
        for y, x1, x2 in spans:
            if not 0 <= y < screen.height:
                continue
            row = cuts[y]
            line = need.setdefault(y, {})
            for x, end in zip(row, row[1:], strict=False):
                if x < x2 and end > x1:
                    line[x] = end
                elif x == x2 and chops[y][x] is None:
                    chops[y][x] = _EMPTY
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
            lines = [y for y, line in need.items() if y0 <= y < y0 + render.height
                     and any(first <= x < last for x in line)]
            if not lines:
                continue
            if clip.contains_region(region):
                strips = widget.render_lines(Region(0, 0, region.width, region.height))
            else:
                strips = widget.render_lines(Region(x0 - region.x, y0 - region.y,
                                                    render.width, render.height))
            for y in lines:
                inside = [x for x in cuts[y] if first <= x <= last]
                pieces = strips[y - y0].divide([x - x0 for x in inside[1:]])
                line, chop = need[y], chops[y]
                for x, piece in zip(inside, pieces, strict=False):  # the last edge ends a piece
                    if x in line:  # else filled by a widget in front, or not written
                        chop[x] = piece
                        del line[x]
                if not line:
                    del need[y]
        return ChopsUpdate(chops, spans, [row[1:] for row in cuts])


#: what a widget or screen has pending besides a repaint (then Textual paints, as always)
_PENDING = ("_layout_required", "_scroll_required", "_recompose_required")


#: the screen's update-timer tick that :meth:`ViewerScreen.paint_now` runs (Textual 8.2)
PAINT_NOW = SUPPORTED and callable(getattr(Screen, "_on_timer_update", None))


class ViewerScreen(Screen):
    """The viewer's main screen: :class:`ViewerCompositor` when Textual has what it uses,
    and :meth:`paint_now`."""

    def __init__(self, *args, **kw) -> None:
        super().__init__(*args, **kw)
        if SUPPORTED:
            self._compositor = ViewerCompositor()

    def paint_now(self) -> bool:
        """Paint the widgets waiting for a repaint now, as the screen's update timer would
        on its next tick, when a repaint is all that waits (no layout, scroll, style or
        recompose pending anywhere on the screen, no message in its queue).  Otherwise, or
        without what it needs from Textual (:data:`PAINT_NOW`), Textual paints as always.

        Textual's own way from ``Widget.refresh`` to the terminal takes a round of the event
        loop per widget (each sees it is idle and posts ``Update`` to the screen), one for the
        screen (idle: it resumes its update timer) and one for the timer's task: ≈ 1 ms a
        key after the frame is drawn (docs/app.md).  Returns whether it painted."""
        app = self.app
        try:
            if not (PAINT_NOW and self.is_current and not app._batch_count
                    and not app.is_inline and self._message_queue.empty()
                    and not self._repaint_required
                    and not any(getattr(self, name) for name in _PENDING)):
                return False
            dirty = []
            for widget in self.walk_children(with_self=False):
                if widget._refresh_styles_required or any(getattr(widget, n) for n in _PENDING):
                    return False
                if widget._repaint_required and widget.display:  # as Widget._check_refresh
                    dirty.append(widget)
        except AttributeError:  # not the Textual this was written for: Textual paints
            return False
        if not dirty:
            return False
        for widget in dirty:  # each one's Update, as Screen._on_update takes it
            widget._repaint_required = False
            self._dirty_widgets.add(widget)
        self._on_timer_update()
        return True
