"""``render.lines.pane_lines`` (the viewer's fast path from a pane to its rows) against Rich's own
``console.render_lines``: the same character and the same style in every cell, for every view,
colour system and a few sizes; and the padding/cropping rules."""

from __future__ import annotations

import io

import pytest
from rich.console import Console, Group
from rich.segment import Segment
from rich.style import Style
from rich.text import Text

from tuibrdf.render import VIEWS
from tuibrdf.render.lines import BLANK, pane_lines
from tuibrdf.render.views import render_view

SYSTEMS = {"truecolor": "truecolor", "256": "256", "none": None}


def cells(rows: list[list[Segment]]) -> list[list[tuple[str, Style]]]:
    """Per row, one (character, style) per cell; a None style is the null style."""
    out = []
    for row in rows:
        line = []
        for seg in row:
            for ch in seg.text:  # every glyph the panes draw is one cell wide
                line.append((ch, seg.style or Style()))
        out.append(line)
    return out


def console(system: str) -> Console:
    return Console(file=io.StringIO(), color_system=SYSTEMS[system], width=200,
                   force_terminal=system != "none", no_color=system == "none")


@pytest.mark.parametrize("system", list(SYSTEMS))
@pytest.mark.parametrize("view", VIEWS)
@pytest.mark.parametrize("model,values", [("cook-torrance", {}),
                                          ("gltf", {"base_color": (0.9, 0.4, 0.1)})])
def test_same_cells_as_rich(view, system, model, values):
    for w, h in ((88, 45), (61, 19)):
        r = render_view(view, model, values, 40.0, w, h, color=system, cmap="viridis")
        con = console(system)
        want = con.render_lines(r, con.options.update(width=w, height=h), style=BLANK,
                                pad=True)
        got = pane_lines(r, con, w, h)
        assert len(got) == h
        assert all(sum(len(s.text) for s in row) == w for row in got)
        assert cells(got) == cells(want[:h])


def test_pads_and_crops():
    con = console("truecolor")
    r = Group(Text("abc"), Text("de"))
    rows = pane_lines(r, con, 5, 4)  # two rows of text, two blank rows below
    assert ["".join(s.text for s in row) for row in rows] == ["abc  ", "de   ", "     ",
                                                              "     "]
    rows = pane_lines(Text("abcdefgh\nij\nkl", no_wrap=True, overflow="crop"), con, 4, 2)
    assert ["".join(s.text for s in row) for row in rows] == ["abcd", "ij  "]
    assert all(s.style is not None for row in rows for s in row)  # never a None style


@pytest.mark.parametrize("text", [
    Text("title  θi=30°", style="bold"), Text(""), Text("abcdefgh", no_wrap=True, overflow="crop"),
    Text("abcdefgh", no_wrap=True, overflow="ellipsis"), Text("abcdefgh"),
    Text("centred", justify="center"), Text("tab\there"), Text("two\nlines"),
    Text("wide 漢字"), Text("dim part", style="dim red on blue"),
    Text.assemble(("a", "bold"), "b"), Text("a\n"), Text("\n\n"),
    Text.assemble(("θi 30°", "bold"), "  a(θi)=0.835", ("  >1", "bold red"), "\n",
                  ("equal-area map · linear", "dim"), " · keys → A"),
    Text.assemble(("span over\nthe newline", "italic"), " and on", style="blue"),
    Text("ends with spaces   \n  starts with them"), Text("control \x1b[31m code"),
    Text("fits\nbut this line is longer than twenty")])
def test_text_rows_as_rich_draws_them(text):
    # titles (one style, one row) and short lines (the status line's, with spans) take a
    # shortcut past Rich: the same cells as Rich, and the cases the shortcuts must leave to
    # Rich (wrapping, ellipsis, justification, tabs, wide characters, control codes) too
    for system in SYSTEMS:
        con = console(system)
        for w in (4, 20):
            want = con.render_lines(text, con.options.update(width=w, height=None),
                                    style=BLANK, pad=True)
            got = pane_lines(text, con, w, len(want))
            assert cells(got) == cells(want), (system, w)
