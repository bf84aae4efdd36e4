"""Small terminals with many parameters: the parameter panel keeps a bounded height and
scrolls, so the polar sections keep a readable size (docs/guide.md, "The viewer's screen").

Expected values come from outside the viewer: the number of parameter rows from the model
file's own ``::begin parameters`` block (a ``color`` is three rows, R, G, B; a ``float`` one),
the readable minimum of a section chosen here (its title and 5 rows of braille: 20 dots
high, whatever the status line's height), and the geometry of the screen (every pane inside
the terminal, none overlapping).
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from tests import DATA_DIR
from tuibrdf.app.app import BrdfApp
from tuibrdf.core.registry import MODELS
from tuibrdf.state.viewer import Side, ViewerState

DISNEY = str(DATA_DIR / "brdf" / "disney.brdf")
SECTION_ROWS = 6  # a section's title and 5 rows of braille


@pytest.fixture(autouse=True)
def config_home(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path))


def declared_rows(path: str) -> int:
    """Parameter rows of a BRDF Explorer file, read from its text (not through the reader)."""
    text = Path(path).read_text(encoding="utf-8")
    block = text.split("::begin parameters", 1)[1].split("::end parameters", 1)[0]
    kinds = [line.split()[0] for line in block.splitlines() if line.strip()
             and not line.lstrip().startswith("#")]
    return sum(3 if k == "color" else 1 for k in kinds)


def more(title: str | None, arrow: str) -> int:
    m = re.search(re.escape(arrow) + r" (\d+) more", title or "")
    return int(m.group(1)) if m else 0


def check_screen(app, w: int, h: int) -> list[str]:
    """The side column's panes fit the screen without overlapping, each shown section is at
    least SECTION_ROWS tall; returns the panel's lines."""
    panel = app.query_one("#panel-a")
    sections = [app.query_one(f"#{p}") for p in ("incidence", "perpendicular")]
    shown = [s for s in sections if s.display]
    assert shown, "no section shown"
    for s in shown:
        assert s.size.height >= SECTION_ROWS, (s.id, s.size, w, h)
        assert s.region.y >= panel.region.bottom  # below the panel, not under it
    status = app.query_one("#status")
    assert status.region.bottom <= h - 1 and shown[-1].region.bottom <= status.region.y
    lines = str(panel.render()).splitlines()
    assert panel.region.height == len(lines) + 2  # every row of its text is on screen
    return lines


@pytest.mark.parametrize("size", [(80, 24), (60, 18)])
async def test_many_parameters_scroll_and_the_selected_row_stays_visible(size):
    total = declared_rows(DISNEY)
    assert total == 13  # baseColor (3) and ten floats: more than fit at these sizes
    app = BrdfApp(ViewerState(sides=[Side(DISNEY)]), sync=True)
    w, h = size
    async with app.run_test(size=size) as pilot:
        await pilot.pause()
        seen = set()
        for k in range(total + 1):  # every row, then past the last: back to the first
            lines = check_screen(app, w, h)
            panel = app.query_one("#panel-a")
            above, below = more(panel.border_title, "↑"), more(panel.border_subtitle, "↓")
            assert above + len(lines) + below == total, (panel.border_title, lines)
            assert len(lines) < total  # it did have to scroll
            sel = app.state.side.selected
            assert sel == k % total
            label = app.state.side.rows()[sel].label
            marked = [ln for ln in lines if ln.lstrip().startswith("▶")]
            assert len(marked) == 1
            name = marked[0].split("▶", 1)[1].split()[0]
            assert label.startswith(name.rstrip("…")), (label, marked)
            assert lines.index(marked[0]) == sel - above  # in its place in the window
            seen.add(sel)
            await pilot.press("down")
            await pilot.pause()
        assert seen == set(range(total))
        await pilot.press("up", "up")  # ↑ from the first row wraps to the last
        await pilot.pause()
        assert app.state.side.selected == total - 1
        lines = check_screen(app, w, h)
        assert more(app.query_one("#panel-a").border_subtitle, "↓") == 0
        assert lines[-1].lstrip().startswith("▶")


@pytest.mark.parametrize("model", sorted(MODELS))
async def test_every_model_at_80x24_keeps_both_sections_readable(model):
    app = BrdfApp(ViewerState(sides=[Side.of(model)]), sync=True)
    async with app.run_test(size=(80, 24)) as pilot:
        await pilot.pause()
        rows = app.state.side.rows()
        for _ in range(len(rows)):
            lines = check_screen(app, 80, 24)
            assert all(app.query_one(f"#{p}").display for p in ("incidence", "perpendicular"))
            label = rows[app.state.side.selected].label
            assert any(ln.lstrip().startswith("▶") and label[:6] in ln for ln in lines)
            await pilot.press("down")
            await pilot.pause()


async def test_compare_at_80x24_scrolls_the_active_sides_panel():
    app = BrdfApp(ViewerState(sides=[Side(DISNEY), Side(DISNEY)], active=1), sync=True)
    async with app.run_test(size=(80, 24)) as pilot:
        await pilot.press("up")  # wraps to the last row
        await pilot.pause()
        panel = app.query_one("#panel-b")
        assert panel.display and not app.query_one("#panel-a").display
        lines = str(panel.render()).splitlines()
        assert lines[-1].lstrip().startswith("▶")
        assert more(panel.border_title, "↑") == 13 - len(lines)
        assert panel.border_title.startswith("B: disney.brdf")
        assert app.query_one("#incidence").size.height >= SECTION_ROWS


async def test_scrolling_the_panel_never_lays_the_screen_out_again():
    # a key re-lays out the whole screen only when a widget's height may change: moving the
    # window over the rows keeps the panel's height, so no ↓ asks for a layout
    from tuibrdf.app.widgets import ParamPanel

    app = BrdfApp(ViewerState(sides=[Side(DISNEY)]), sync=True)
    async with app.run_test(size=(80, 24)) as pilot:
        await pilot.press("down")  # the first text after the panel's first resize is laid out
        await pilot.pause()
        panel = app.query_one("#panel-a")
        calls = []
        refresh = ParamPanel.refresh

        def spy(self, *a, **kw):
            calls.append(kw.get("layout", False))
            return refresh(self, *a, **kw)

        panel.refresh = spy.__get__(panel)
        for _ in range(12):  # rows 2 … 13 and back to 1: the window moves both ways
            await pilot.press("down")
        await pilot.pause()
        assert len(calls) >= 12 and not any(calls)  # every ↓ repaints, none lays out


async def test_a_narrow_panel_cuts_its_rows_with_an_ellipsis_at_its_width():
    # at 60×18 cook-torrance's rows are wider than the panel: each drawn row is exactly the
    # panel's width, a row cut ends in "…" in its last cell, and the cells before it are the
    # row's own text (render(): the rows as text, uncut)
    app = BrdfApp(ViewerState(sides=[Side.of("cook-torrance")]), sync=True)
    async with app.run_test(size=(60, 18)) as pilot:
        await pilot.pause()
        panel = app.query_one("#panel-a")
        width = panel.size.width
        full = str(panel.render()).splitlines()
        drawn = ["".join(s.text for s in row) for row in panel._lines[:len(full)]]
        assert any(len(line) > width for line in full)  # the case this is about
        for text, row in zip(full, drawn, strict=True):
            assert len(row) == width
            if len(text) > width:
                assert row == text[:width - 1] + "…"
            else:
                assert row == text.ljust(width)


async def test_a_model_of_another_panel_height_draws_its_sections_once_at_their_new_size():
    # below BOTH_PANELS_H the panel's height follows the model's rows: the new model's
    # sections are drawn once the layout has given them their new size, not first at the
    # old one and again on the resize that follows
    from tuibrdf.app import frames
    from tuibrdf.app.widgets import drawn_size

    app = BrdfApp(ViewerState(sides=[Side.of("lambert")]), sync=True)
    async with app.run_test(size=(80, 24)) as pilot:
        await pilot.pause()
        before = app.query_one("#incidence").size.height
        drawn = []
        pane = frames.panes.pane

        def spy(view, res, k, w, h, look):
            drawn.append((view, w, h))
            return pane(view, res, k, w, h, look)

        frames.panes.pane = spy
        try:
            await pilot.press("m")
            await pilot.pause()
            await pilot.pause()
        finally:
            frames.panes.pane = pane
        assert app.state.side.material.name != "lambert"
        pics = {p: app.query_one(f"#{p}") for p in ("incidence", "perpendicular")}
        assert pics["incidence"].size.height != before  # the panel's height did change
        for view, w, h in drawn:
            if view in pics:
                assert (w, h) == drawn_size(*pics[view].size), (view, w, h)
        assert sorted(v for v, _, _ in drawn if v in pics) == sorted(pics)  # each once
