"""The viewer's widgets: a Line-API picture, the parameter panel, the status line."""

from __future__ import annotations

import os
from collections.abc import Callable
from os.path import commonprefix

from rich.cells import cell_len
from rich.console import RenderableType
from rich.segment import Segment
from rich.style import Style
from rich.text import Text
from textual import events
from textual.css.scalar import Unit
from textual.filter import ANSIToTruecolor
from textual.geometry import Region
from textual.strip import Strip
from textual.style import Style as TextualStyle
from textual.widget import Widget
from textual.widgets import Static

from tuibrdf.app.guard import survives
from tuibrdf.app.keys import Key, footer_items
from tuibrdf.app.textual_internals import styles_key
from tuibrdf.core.conventions import fmt_number
from tuibrdf.render.lines import BLANK, fit_row, pane_lines, render_rows
from tuibrdf.render.rowdiff import ChangedRow
from tuibrdf.state.viewer import Side, ViewerState


def changed_span(sa: list[Segment], sb: list[Segment], width: int) -> tuple[int, int]:
    """Cells ``[x0, x1)`` of two rows of ``width`` cells outside what they share at both ends
    (what must be redrawn to turn ``sa`` into ``sb``): the equal segments at each end, then
    the common start (end) of the first (last) segments that differ when their styles are
    equal.  Cells ``[0, x0)`` and ``[x1, width)`` are equal; ``x1 <= x0``: nothing changed."""
    n = min(len(sa), len(sb))
    x0 = i = 0
    while i < n and sa[i] == sb[i]:
        x0 += cell_len(sa[i].text)
        i += 1
    if i < n and sa[i].style == sb[i].style:  # both start at x0: a common start is equal
        x0 += cell_len(commonprefix([sa[i].text, sb[i].text]))
    x1, j = width, 0
    while j < n - i and sa[-1 - j] == sb[-1 - j]:
        x1 -= cell_len(sb[-1 - j].text)
        j += 1
    if j < n and sa[-1 - j].style == sb[-1 - j].style:  # both end at x1: so does a common end
        x1 -= cell_len(commonprefix([sa[-1 - j].text[::-1], sb[-1 - j].text[::-1]]))
    return x0, max(x0, x1)


class Rows(Widget):
    """Shows stored rows of segments; ``render_line`` only returns a stored ``Strip``, and a
    new set of rows marks only the cells that changed for repaint (:meth:`_set`)."""

    def __init__(self, **kw) -> None:
        super().__init__(**kw)
        self._strips: list[Strip] = []
        self._lines: list[list[Segment]] = []  # the segments of each strip

    def _set(self, lines: list[list[Segment]], w: int, h: int) -> None:
        """Show ``h`` rows of ``w`` cells; only the cells that changed go to the terminal: per
        changed row, the span between the first and the last segment that differ (an
        unchanged row keeps its Strip)."""
        old, old_lines = self._strips, self._lines
        self._lines = lines
        if len(old) != h or any(s.cell_length != w for s in old):
            self._strips = [Strip(line, w) for line in lines]
            self.refresh()
            return
        regions = []
        strips = []
        for y, (a, a_line, line) in enumerate(zip(old, old_lines, lines, strict=True)):
            if a_line is line:  # the same row: the picture lent it
                strips.append(a)
                continue
            # a row drawn against this very row knows its changed cells (render.rowdiff)
            known = line.span if type(line) is ChangedRow and line.against is a_line else None
            if known is None and a_line == line:
                strips.append(a)
                continue
            strips.append(Strip(line, w))
            x0, x1 = known or changed_span(a_line, line, w)
            if x1 > x0:
                regions.append(Region(x0, y, x1 - x0, 1))
        self._strips = strips
        if regions:
            self.refresh(*regions)

    def _blank_style(self) -> Style:
        """The style of the blank cells below the rows."""
        return BLANK

    def render_line(self, y: int) -> Strip:
        if y < len(self._strips):
            return self._strips[y]
        return Strip([Segment(" " * self.size.width, self._blank_style())], self.size.width)

    def _styles_key(self) -> tuple:
        """What the widget's look depends on: the styles of the widget and its ancestors."""
        return styles_key(self)

    #: (the styles' keys of the widget and its ancestors, the side padding or None, its
    #: style): :meth:`_sides`, computed again when any of those styles changed
    _direct: tuple | None = None
    _padded: dict[int, tuple[Strip, Style, Strip]] | None = None  # id(row) → (row, pad, padded)

    def _sides(self) -> tuple[tuple[int, int] | None, Style | None]:
        """The side padding when nothing else of Textual's styling touches the rows (no
        border, outline, padding above or below, tint, text opacity or hatch, no opacity
        here or in an ancestor), else ``None``; and the padding's style, as Textual's styles
        cache pads a line.  Kept until a style of the widget or an ancestor changes (looking
        them up costs ≈ 50 µs, more than handing the rows over)."""
        key = self._styles_key()
        if self._direct is None or self._direct[0] != key:
            s = self.styles
            g, p = s.gutter, s.padding
            plain = (not (g.top or g.bottom) and (g.left, g.right) == (p.left, p.right)
                     and not any(s.outline.spacing) and not s.tint.a
                     and s.text_opacity == 1.0 and not (s.has_rule("hatch") and s.hatch != "none")
                     and self.opacity == 1.0)
            base, background = self.background_colors
            pad = TextualStyle(background=base + background).rich_style  # StylesCache's inner
            self._direct = key, ((p.left, p.right) if plain else None), pad
        return self._direct[1], self._direct[2]

    def render_lines(self, crop: Region) -> list[Strip]:
        """The stored strips as they are when Textual would not change them (:meth:`_sides`,
        no line filter, no hovered link), with Textual's side padding: a changed line costs
        the compositor no new strip, an unchanged one no cache look-up (≈ 1 ms a 160×48
        frame, docs/benchmarks.md).  Otherwise Textual's own way."""
        sides, pad = self._sides()
        hover = self.hover_style
        if (sides is None or self.get_line_filters()
                or (self.auto_links and hover.link_id and "@click" in hover.meta)):
            return super().render_lines(crop)
        (left, right), outer, strips = sides, self.outer_size, self._strips
        width = outer.width - left - right
        if (len(strips) != outer.height or crop.bottom > len(strips)
                or any(row.cell_length != width for row in strips)):
            return super().render_lines(crop)
        lines = strips[crop.y:crop.bottom]
        if left or right:  # as Textual's StylesCache.render_line pads a content line
            old, new = self._padded or {}, {}
            ends = ([Segment(" " * left, pad)] if left else [],
                    [Segment(" " * right, pad)] if right else [])
            for i, row in enumerate(lines):
                done = old.get(id(row))
                if done is None or done[0] is not row or done[1] != pad:
                    done = row, pad, Strip([*ends[0], *row, *ends[1]], outer.width)
                new[id(row)] = done
                lines[i] = done[2]
            self._padded = new
        if crop.x or crop.right != outer.width:
            lines = [line.crop(crop.x, crop.right) for line in lines]
        return lines

    def get_line_filters(self):
        # ANSIToTruecolor costs ≈ 10 ms per 160×48 frame and our colours are RGB already;
        # keep the others (NO_COLOR relies on Monochrome)
        return [f for f in super().get_line_filters() if not isinstance(f, ANSIToTruecolor)]


#: the largest picture the viewer draws, in cells (a pane larger than this, in a huge
#: terminal, shows it centred with a note): the frame's pixels, and so its memory, are
#: bounded whatever the terminal's size
MAX_PANE = (400, 200)


def drawn_size(width: int, height: int) -> tuple[int, int]:
    """The size a picture is drawn at in a ``width × height`` pane (:data:`MAX_PANE`)."""
    return min(width, MAX_PANE[0]), min(height, MAX_PANE[1])


def centred(lines: list[list[Segment]], cw: int, width: int, height: int,
            note: str) -> list[list[Segment]]:
    """``lines`` (rows of ``cw`` cells) centred in ``height`` rows of ``width`` cells, the
    ``note`` under them; the blank rows are one shared row."""
    x0 = (width - cw) // 2
    left, right = Segment(" " * x0, BLANK), Segment(" " * (width - cw - x0), BLANK)
    rows = [[left, *line, right] for line in lines]
    text = note[:width]
    rows.append([Segment(text.center(width), BLANK)])
    blank = [Segment(" " * width, BLANK)]
    top = max(0, (height - len(rows)) // 2)
    out = [blank] * top + rows
    return (out + [blank] * (height - len(out)))[:height]


class Picture(Rows):
    """A pane: the app renders its renderable once per change (:meth:`show`), not once per
    refresh."""

    DEFAULT_CSS = "Picture { width: 1fr; height: 1fr; }"

    def __init__(self, pane: str, **kw) -> None:
        super().__init__(**kw)
        self.pane = pane
        self.shown_for: object = None  # what the strips were made from (the app's key)
        #: the renderable shown: the next one takes the rows they share from it
        self._shown: RenderableType | None = None

    def show(self, renderable: RenderableType, key: object = None) -> None:
        """Show ``renderable``, drawn from ``key`` (None: from nothing the app names); in a
        pane larger than :data:`MAX_PANE` it is drawn at that size, centred, with a note."""
        w, h = self.size.width, self.size.height
        self.shown_for = key
        like, self._shown = self._shown, renderable
        cw, ch = drawn_size(w, h)
        lines = pane_lines(renderable, self.app.console, cw, ch, like)
        if (cw, ch) != (w, h):
            lines = centred(lines, cw, w, h, f"(drawn at {cw}×{ch} cells: the largest "
                                             f"picture the viewer draws; this pane is {w}×{h})")
        self._set(lines, w, h)

    @survives
    def on_resize(self, event) -> None:
        self.shown_for = None
        request = getattr(self.app, "request_rebuild", None)
        if request is not None and self.display:
            request()

    #: where the button went down (None: not pressed here) and whether it moved since
    _press: tuple[int, int] | None = None
    _dragged = False

    @survives
    def on_click(self, event) -> None:
        """A click reads the picture there (the app decides: the probe on a map or a section,
        a readout elsewhere); the end of a drag is not a click."""
        if self._dragged:
            self._dragged = False
            return
        offset = event.get_content_offset(self)
        clicked = getattr(self.app, "picture_clicked", None)
        if offset is not None and clicked is not None:
            clicked(self.pane, offset.x, offset.y)

    @survives
    def on_mouse_down(self, event) -> None:
        offset = event.get_content_offset(self)
        if offset is not None:
            self._press, self._dragged = (offset.x, offset.y), False
            self.capture_mouse()  # the drag goes on outside the pane

    @survives
    def on_mouse_move(self, event) -> None:
        """A drag (button held): the app moves the light (lit views) or turns the solid."""
        if self._press is None or not event.button:
            return
        offset = event.get_content_offset_capture(self)
        if (offset.x, offset.y) == self._press:
            return
        dx, dy = offset.x - self._press[0], offset.y - self._press[1]
        self._press, self._dragged = (offset.x, offset.y), True
        dragged = getattr(self.app, "picture_dragged", None)
        if dragged is not None:
            dragged(self.pane, offset.x, offset.y, dx, dy)

    @survives
    def on_mouse_up(self, event) -> None:
        self._press = None
        self.release_mouse()

    @survives
    def on_mouse_scroll_up(self, event) -> None:
        self._scrolled(+1)

    @survives
    def on_mouse_scroll_down(self, event) -> None:
        self._scrolled(-1)

    def _scrolled(self, steps: int) -> None:
        scrolled = getattr(self.app, "picture_scrolled", None)
        if scrolled is not None:
            scrolled(self.pane, steps)


def min_cells(widget: Widget) -> int:
    """``widget``'s min-height in cells (a panel as tall as the longest model's, layout.py);
    0 when it has none, or one in other units."""
    floor = widget.styles.min_height
    return int(floor.value) if floor is not None and floor.unit == Unit.CELLS else 0


class QuietStatic(Static):
    """A ``Static`` updated only when its text changes, and re-laid out (which costs a layout
    and compositing of the whole screen) only when its height may change: a new number of
    lines, or a line wrapping differently at the widget's width, beyond its min-height (a
    panel as tall as the longest model's keeps its height when the model changes)."""

    _shown: tuple | None = None
    _rows: tuple | None = None

    def _row_count(self, text: Text) -> tuple:
        width = max(1, self.content_region.width)
        if text.no_wrap or self.styles.text_wrap == "nowrap":
            rows = text.plain.count("\n") + 1
        else:
            rows = len(text.wrap(self.app.console, width))  # Rich's own word wrap
        return max(rows + self.styles.gutter.height, min_cells(self)), width

    def show_text(self, text: Text) -> None:
        key = (text.plain, tuple(text.spans), str(text.style))  # Text == ignores the style
        if key != self._shown:
            self._shown = key
            rows = self._row_count(text)
            self.update(text, layout=rows != self._rows)
            self._rows = rows

    @survives
    def on_resize(self, event) -> None:
        self._rows = None  # the next text is laid out at the new width


class DrawnRows(Rows):
    """Rows a widget draws from its own content (:meth:`_draw`), its height following them:
    the parameter panel and the status line."""

    #: its last rows asked for another height: the screen is laid out again before the next
    #: paint, and the panes below move (until then their sizes are the old ones); False until
    #: it has drawn rows (it asked for nothing)
    moving = False

    def _draw(self) -> None:
        raise NotImplementedError

    def _place(self, lines: list[list[Segment]], width: int) -> None:
        """Show ``lines`` of ``width`` cells: only the cells that changed are repainted; a
        height of its own other than the widget's (its rows and gutter, at least its
        min-height) lays the screen out again, these rows drawn in the same paint (the rows
        below them blank: :meth:`Rows.render_line`)."""
        self.moving = max(len(lines) + self.styles.gutter.height, min_cells(self)) != \
            self.outer_size.height
        if self.moving:
            self._strips = [Strip(line, width) for line in lines]
            self._lines = lines
            self.refresh(layout=True)
            return
        h = self.size.height
        blank = [Segment(" " * width, self._blank_style())]  # rows below (min-height)
        self._set(lines[:h] + [blank] * (h - len(lines)), width, h)

    @survives
    def on_resize(self, event) -> None:
        self.moving = False
        if self._strips and event.size.width == self._strips[0].cell_length:
            return  # a new height for rows already drawn at this width
        self._draw()


#: the parameter panel's label column: at least, at most (cells)
LABEL_WIDTH = (7, 16)


class ParamPanel(DrawnRows):
    """The parameter rows of one side: value, range, unit; the selected row highlighted.  At
    most :attr:`max_rows` rows (the layout's, from the terminal's height): a window over them
    that follows the selected row, the rows above and below it counted in the borders
    ("↑ 3 more", "↓ 5 more").  Rows of segments (:class:`Rows`): a new value repaints the
    cells around it on its row, not the whole panel through Textual's styles cache (a
    ``Static`` did: ≈ 1.7 ms of compositing a parameter key at 160×48, docs/benchmarks.md)."""

    DEFAULT_CSS = """
    ParamPanel { height: auto; padding: 0 1; border: round $primary-darken-2; }
    ParamPanel.active { border: round $accent; }
    """

    _for: tuple | None = None  # what the panel shows now (:meth:`show`)
    _titles: tuple = ()  # the border's title and subtitle shown (plain text)
    max_rows: int | None = None  # how many parameter rows fit (None: all)
    _top = 0  # the first row shown when they do not all fit

    def _window(self, n_rows: int, selected: int) -> tuple[int, int]:
        """``(first, count)`` of the rows shown: all, or :attr:`max_rows` of them with the
        selected one inside (the window moves only when the selection leaves it)."""
        n = n_rows if self.max_rows is None else max(1, min(self.max_rows, n_rows))
        top = min(max(self._top, selected - n + 1), selected)
        self._top = top = max(0, min(top, n_rows - n))
        return top, n

    def __init__(self, **kw) -> None:
        super().__init__(**kw)
        #: the rows shown: per row its pieces, ``(text, style name)``
        self._parts: tuple[tuple[tuple[str, str], ...], ...] = ()
        self._base: tuple | None = None  # (the styles' keys, the widget's own style)

    def render(self) -> Text:
        """The text shown (tests read it)."""
        text = Text(no_wrap=True, overflow="ellipsis")
        for i, row in enumerate(self._parts):
            if i:
                text.append("\n")
            for piece, style in row:
                text.append(piece, style=style)
        return text

    def _style(self) -> Style:
        """The widget's colours (Textual works them out from every ancestor: ≈ 0.3 ms; kept
        until a style of the widget or an ancestor changes)."""
        key = self._styles_key()
        if self._base is None or self._base[0] != key:
            self._base = key, self.rich_style
        return self._base[1]

    _blank_style = _style

    def _rows(self, width: int) -> list[list[Segment]]:
        """The rows over the widget's colours, as a ``Static`` renders its content (so
        "reverse" swaps the theme's colours, not the terminal's); a row longer than ``width``
        ends in "…" (as Rich's ``overflow="ellipsis"``).  Built from the pieces directly:
        Rich's line splitting cost ≈ 0.3 ms a key."""
        base, get = self._style(), self.app.console.get_style
        out = []
        for row in self._parts:
            segments = [Segment(t, base + get(s) if s else base) for t, s in row if t]
            n = sum(cell_len(t) for t, _ in row)
            if n > width:  # "…" in the last cell, in the style of the piece it replaces
                cut = Segment.adjust_line_length(segments, max(width - 1, 0), base)
                last = Segment.adjust_line_length(segments, width, base)[-1].style
                segments = [*cut, Segment("…", last)] if width else []
            out.append(fit_row(segments, min(n, width), width, base))
        return out

    def get_content_height(self, container, viewport, width: int) -> int:
        return max(1, len(self._parts))

    def _draw(self) -> None:
        width = self.size.width
        if width >= 1:  # (else not laid out yet: drawn by on_resize)
            self._place(self._rows(width), width)

    def show(self, state: ViewerState, side_index: int) -> None:
        side: Side = state.sides[side_index]
        active = side_index == state.active
        width = self.outer_size.width
        key = (side.material, side.selected, active, state.compare, self.max_rows, width)
        if key == self._for:  # every key of the viewer shows the panels: most change nothing
            return
        self._for = key
        self.set_class(active and state.compare, "active")
        rows = side.rows()
        selected = min(side.selected, len(rows) - 1)
        top, n = self._window(len(rows), max(selected, 0))
        above, below = top, max(0, len(rows) - top - n)  # no rows: 0 below, not −1
        label = "AB"[side_index] + ": " if state.compare else ""
        name = side.spec.title
        if os.path.isabs(name):  # a model file without a title of its own: its file name
            name = os.path.basename(name)
        up = f" ↑ {above} more" if above else ""
        if up and width > 0:  # the count stays whole: the name gives way ("╭─ " … " ─╮")
            room = max(1, width - 6 - len(label) - len(up))
            name = name if len(name) <= room else name[:max(0, room - 1)] + "…"
        title = f"{label}{name}{up}"
        subtitle = " · ".join(x for x in (f"↓ {below} more" if below else "",
                                          "m/M model" if active else "") if x)
        if self._titles != (title, subtitle):  # as Text: a file's name is never markup
            self._titles = (title, subtitle)
            self.border_title, self.border_subtitle = Text(title), Text(subtitle)
        # one label column for every row: as wide as the longest label (a .brdf file's
        # "clearcoatGloss"), within LABEL_WIDTH; a longer one ends in "…"
        lw = min(max((len(r.label) for r in rows), default=0), LABEL_WIDTH[1])
        if width > 0:  # a narrow panel: the label gives way to the value ("▶ ", 8, " unit")
            lw = min(lw, width - 4 - 2 - 8 - 3)  # the border and padding: 4
        lw = max(lw, LABEL_WIDTH[0])
        parts = []
        for i, row in enumerate(rows[top:top + n], start=top):
            sel = active and i == selected
            v = state.row_value(row, side)
            p = row.param
            label = row.label if len(row.label) <= lw else row.label[:lw - 1] + "…"
            shown = os.path.basename(str(v)) if p.kind == "path" else fmt_number(v)
            unit = p.unit if p.unit not in ("", None) else ""
            line = [(f"{'▶' if sel else ' '} {label:<{lw}}", ""),
                    (f"{shown:>8}", "reverse" if sel else "bold"), (f" {unit:<2}", "")]
            if p.kind in ("float", "rgb"):
                line.append((f" {p.min:g}–{p.max:g}", "dim"))
            elif p.kind == "choice" and len(p.choices) > 4:  # a long list: = opens a picker
                line.append((f" {len(p.choices)} names: = picks", "dim"))
            elif p.kind == "choice":
                line.append((" " + "/".join(p.choices), "dim"))
            if sel:  # the selected row in bold
                line = [(t, f"bold {st}".rstrip()) for t, st in line]
            parts.append(tuple(line))
        if not rows:
            parts.append((("(no parameters)", "dim"),))
        parts = tuple(parts)
        if parts != self._parts:
            self._parts = parts
            self._draw()


class StatusLine(DrawnRows):
    """Two lines: θi and the frame's numbers; the view, scale, colour map and a message.  The
    numbers may wrap to a third line; the last line is cut with "…" at the width, so a long
    message never adds one.  The text comes in forms, the full one first and each shorter
    (:func:`.text.status_text`'s ``terse``): the first that fits the three rows is shown; if
    none does, the tersest is cut after its third row, which ends in "…" (never a silent
    cut).  A picture, so a new number re-sends only the cells around it (a ``Static``
    re-sent both lines whole: ≈ 1.1 kB a key at 160 columns)."""

    DEFAULT_CSS = "StatusLine { height: auto; max-height: 3; padding: 0 1; }"
    MAX_ROWS = 3

    def __init__(self, **kw) -> None:
        super().__init__(**kw)
        self._forms: Callable[[int], Text] = lambda k: Text()  # the text's forms (re-cut at a
        self._n_forms = 1  # new width)
        self._made: dict[int, Text] = {}  # the forms made so far
        self._text = Text()  # as shown
        self._key: tuple | None = None

    def render(self) -> Text:
        """The text shown (tests read it)."""
        return self._text

    def _rows(self, width: int) -> list[list[Segment]]:
        return render_rows(self._text, self.app.console, max(1, width))[:self.MAX_ROWS]

    def get_content_height(self, container, viewport, width: int) -> int:
        return max(1, len(self._rows(width)))

    def show_text(self, text: Text) -> None:
        self.show_forms(lambda k: text, 1)

    def show_forms(self, forms: Callable[[int], Text], n: int) -> None:
        """Show the first of ``forms(0)``, …, ``forms(n − 1)`` that fits (made only as far
        as needed: the full form usually fits)."""
        text = forms(0)
        key = (text.plain, tuple(text.spans), str(text.style))  # Text == ignores the style
        if key == self._key:
            return
        self._key, self._forms, self._n_forms, self._made = key, forms, n, {0: text}
        self._draw()

    def _form(self, k: int) -> Text:
        if k not in self._made:
            self._made[k] = self._forms(k)
        return self._made[k]

    def _fitted(self, width: int) -> Text:
        """The first form that fits :attr:`MAX_ROWS` rows at ``width``, its last line cut
        with "…"; else the tersest's first rows, the last ending in "…"."""
        if width <= 10:
            return self._form(0)
        for k in range(self._n_forms):
            lines = self._form(k).split("\n")
            if len(lines) > 1:
                last = lines[-1]
                last.truncate(width, overflow="ellipsis")
                lines = [*lines[:-1], last]
            text = Text("\n").join(lines)
            if len(lines) <= self.MAX_ROWS and all(ln.cell_len <= width for ln in lines):
                return text  # no line wraps: no need to wrap it to know
            rows = text.wrap(self.app.console, width)
            if len(rows) <= self.MAX_ROWS:
                return text
        keep = list(rows)[:self.MAX_ROWS]
        last = keep[-1]
        last.rstrip()
        last.truncate(width - 1)
        last.append("…")
        return Text("\n").join(keep)

    def _draw(self) -> None:
        width = self.size.width
        self._text = self._fitted(width)
        if width >= 1:  # (else not laid out yet: drawn by on_resize)
            self._place(self._rows(width), width)


class KeyBar(Widget):
    """The footer: the key table's footer keys (:func:`~tuibrdf.app.keys.footer_items`) on one
    line, as many whole ones as fit; a click on a key presses it.

    Not Textual's ``Footer``: that one composes a widget per key only after the screen's first
    refresh, so its keys came about 90 ms after the first picture; this one is drawn with the
    first frame, from the table, as one line of text (start-up to the complete screen 610 →
    513 ms, ``python scripts/bench_startup.py``)."""

    ALLOW_SELECT = False
    COMPONENT_CLASSES = {"keybar--key", "keybar--label"}
    DEFAULT_CSS = """
    KeyBar { dock: bottom; height: 1; background: $footer-background;
             color: $footer-foreground; pointer: pointer; }
    KeyBar > .keybar--key { color: $footer-key-foreground; background: $footer-key-background;
                            text-style: bold; }
    KeyBar > .keybar--label { color: $footer-description-foreground;
                              background: $footer-description-background; }
    """
    #: the gap between two items
    GAP = "  "

    def __init__(self, **kw) -> None:
        super().__init__(**kw)
        self._items = footer_items()
        #: the key at each cell: ``(x0, x1, key)``, from the last render
        self._targets: list[tuple[int, int, Key]] = []

    def render(self) -> Text:
        key_style = self.get_component_rich_style("keybar--key")
        label_style = self.get_component_rich_style("keybar--label")
        text, targets, width = Text(" "), [], self.size.width
        for keys, label in self._items:
            if not all(self._acts(k.action) for k in keys):
                continue  # (a modal screen is open: the viewer's keys wait)
            item = sum(cell_len(k.shown) for k in keys) + 1 + cell_len(label)
            gap = self.GAP if len(text) > 1 else ""
            if text.cell_len + len(gap) + item > width:
                break  # whole items only: a key cut mid-word reads as another key
            text.append(gap)
            start = text.cell_len
            for k in keys:
                x = text.cell_len
                text.append(k.shown, key_style)
                targets.append((x, text.cell_len, k))
            text.append(" " + label, label_style)
            if len(keys) == 1:  # a single key's label presses it too
                targets[-1] = (start, text.cell_len, targets[-1][2])
        self._targets = targets
        return text

    def _acts(self, action: str) -> bool:
        """Whether the app acts on ``action`` now (``App.check_action``)."""
        name, _, _ = action.partition("(")
        return self.app.check_action(name, ()) is not False

    @survives
    def on_mount(self) -> None:
        # drawn again when the screen's bindings change (a modal screen opens or closes)
        self.screen.bindings_updated_signal.subscribe(self, self._bindings_changed)

    @survives
    def on_unmount(self) -> None:
        self.screen.bindings_updated_signal.unsubscribe(self)

    def _bindings_changed(self, screen) -> None:
        self.refresh()

    def _at(self, x: int) -> Key | None:
        return next((k for x0, x1, k in self._targets if x0 <= x < x1), None)

    @survives
    def on_mouse_down(self, event: events.MouseDown) -> None:
        k = self._at(event.x)
        if k is not None:
            self.app.simulate_key(k.key)

    @survives
    def on_mouse_move(self, event: events.MouseMove) -> None:
        k = self._at(event.x)  # the key's help line (the help screen's) as its tooltip
        tip = None if k is None else k.help
        if tip != self.tooltip:
            self.tooltip = tip
