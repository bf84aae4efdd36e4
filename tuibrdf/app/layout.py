"""The viewer's layout: its CSS and which panes and panels show in each mode."""

from __future__ import annotations

from rich.text import Text

from tuibrdf.app.text import PANES, visible_panes
from tuibrdf.core.registry import MODELS
from tuibrdf.state.viewer import panel_rows

MIN_W, MIN_H = 60, 18
#: compare mode draws three maps, two panels and two sections: below this it says so
COMPARE_MIN_W, COMPARE_MIN_H = 80, 24
#: below this height only the plane-of-incidence section is shown (each gets too few rows)
BOTH_SECTIONS_H = 24
BOTH_PANELS_H = 40  # compare mode shows both parameter panels from this height
STEADY_PANEL_H = max(len(panel_rows(m)) for m in MODELS.values()) + 2  # rows + border
#: the fewest rows a polar section keeps beside the parameter panel: its title and 5 rows of
#: braille (20 dots; a pane's minimum, render.MIN_HEIGHT); the panel scrolls when its
#: parameters would take more
SECTION_MIN_H = 6
FOOTER_H, STATUS_H = 1, 3  # the status line at its tallest (its numbers wrapped)
PANEL_BORDER = 2


def panel_rows_shown(h: int, compare: bool) -> int:
    """How many parameter rows a panel shows in a terminal ``h`` rows tall: what is left of the
    side column when every section shown keeps :data:`SECTION_MIN_H` rows, whatever the
    status line's height (shared by two panels when both show), at least one."""
    sections = 2 if h >= BOTH_SECTIONS_H else 1
    panels = 2 if compare and h >= BOTH_PANELS_H else 1
    room = h - FOOTER_H - STATUS_H - sections * SECTION_MIN_H
    return max(1, room // panels - PANEL_BORDER)

CSS = """
Screen { layout: vertical; }
#root { height: 1fr; }
#body { height: 1fr; }
#main { width: 55%; height: 1fr; }
#main.compare-map { layout: grid; grid-size: 2 2; }
#main.compare-solid, #main.compare-extra { layout: horizontal; }
#side { width: 1fr; height: 1fr; }
#side Picture { height: 1fr; }
Picture { border-title-color: $text-muted; }
#main Picture { border: none; }
#main.compare-map Picture, #main.compare-solid Picture, #main.compare-extra Picture {
    border: round $primary-darken-3; }
#legend { padding: 0 1; }
#toosmall { width: 1fr; height: 1fr; content-align: center middle; display: none; }
Screen.small #toosmall { display: block; }
Screen.small #root { display: none; }
"""


def arrange(app) -> None:
    """Show ``app``'s panes for its state's mode; the too-small message below the minimum."""
    w, h = app.size
    s = app.state
    cramped = s.compare and (w < COMPARE_MIN_W or h < COMPARE_MIN_H)
    app.screen.set_class(w < MIN_W or h < MIN_H or cramped, "small")
    if w < MIN_W or h < MIN_H:
        msg = (f"The terminal is {w}×{h}: tuibrdf needs at least {MIN_W}×{MIN_H}.\n"
               "Enlarge the window (q quits).")
    else:
        msg = (f"The terminal is {w}×{h}: compare mode needs at least "
               f"{COMPARE_MIN_W}×{COMPARE_MIN_H}.\nEnlarge the window, or press c for one side "
               "(q quits).")
    app.one("toosmall").show_text(Text(msg))
    visible = set(visible_panes(s))
    main = app.one("main")
    main.set_class(s.compare and s.view == "map", "compare-map")
    main.set_class(s.compare and s.view == "solid", "compare-solid")
    main.set_class(s.compare and s.view not in ("map", "solid", "albedo"), "compare-extra")
    for pic in (app.one(p) for p in PANES):
        pic.display = pic.pane in visible and (pic.pane != "perpendicular"
                                               or h >= BOTH_SECTIONS_H)
    app.one("legend").display = s.compare and s.view == "map"
    # both panels when there is room; otherwise only the side the keys act on
    both = s.compare and h >= BOTH_PANELS_H
    app.one("panel-a").display = not s.compare or both or s.active == 0
    app.one("panel-b").display = both or (s.compare and s.active == 1)
    # tall terminals: panels as tall as the longest model's, so cycling models never
    # resizes the plots below; short ones keep every row for the plots
    shown = panel_rows_shown(h, s.compare)
    steady = min(STEADY_PANEL_H, shown + PANEL_BORDER) if h >= BOTH_PANELS_H else None
    for panel in (app.one("panel-a"), app.one("panel-b")):
        panel.styles.min_height = steady
        panel.max_rows = shown  # more parameters than that: the panel scrolls
    if s.compare:
        for pane in ("map-a", "map-b", "solid-a", "solid-b", "extra-a", "extra-b"):
            k = PANES[pane][1]
            app.one(pane).border_title = f"{'AB'[k]}: {s.sides[k].material.label}"
        app.one("diff").border_title = "A − B"
