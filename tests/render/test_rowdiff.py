"""A picture drawn after another in the same place takes the rows they share from it
(``pane_lines(..., like=previous)``): the rows must be exactly those drawn from nothing (which
tests/render/test_lines.py checks against Rich's own rendering), and the shared rows must really
be shared (the point of it: a θi step redraws ≈ 20 of a map's 45 rows)."""

from __future__ import annotations

import io

import numpy as np
import pytest
from rich.console import Console

from tuibrdf.render.braille import BrailleCanvas
from tuibrdf.render.halfblock import HalfBlockImage, Mark
from tuibrdf.render.lines import pane_lines
from tuibrdf.render.views import render_view

SYSTEMS = {"truecolor": "truecolor", "256": "256", "none": None}


def console(system: str) -> Console:
    return Console(file=io.StringIO(), color_system=SYSTEMS[system], width=200,
                   force_terminal=system != "none", no_color=system == "none")


def sequence(view: str, system: str):
    """Pictures one after another as a user makes them: θi steps, a parameter step, the probe
    moving (a mark to another row), the log scale, another colour map (another palette),
    another model of the same kind and one with RGB colours."""
    w, h = 78, 40
    base = dict(color=system, levels=32)
    steps = [("phong", {}, 30.0, {}), ("phong", {}, 31.0, {}), ("phong", {}, 32.0, {}),
             ("phong", {"ks": 0.4}, 32.0, {}), ("phong", {"ks": 0.4}, 32.0, {"log": True}),
             ("phong", {"ks": 0.4}, 32.0, {"cmap": "viridis"}),
             ("cook-torrance", {}, 32.0, {"cmap": "viridis"}),
             ("cook-torrance", {}, 33.0, {"cmap": "viridis"}),
             ("gltf", {"base_color": (0.9, 0.4, 0.1)}, 33.0, {}),
             ("gltf", {"base_color": (0.9, 0.4, 0.1)}, 34.0, {})]
    for model, values, theta, extra in steps:
        yield render_view(view, model, values, theta, w, h, **base, **extra), w, h


@pytest.mark.parametrize("system", list(SYSTEMS))
@pytest.mark.parametrize("view", ["map", "incidence", "perpendicular", "theta-h", "slice"])
def test_rows_lent_are_the_rows_drawn_from_nothing(view, system):
    con = console(system)
    prev = None
    for r, w, h in sequence(view, system):
        got = pane_lines(r, con, w, h, prev)
        # the same renderable drawn again from nothing: a fresh one, as its rows are cached
        want = pane_lines(render_again(r, view, system), con, w, h)
        assert got == want
        prev = r


def render_again(r, view, system):
    """An independent copy of the picture ``r`` (no cached rows, no previous picture)."""
    import copy

    fresh = copy.deepcopy(r)
    for part in getattr(fresh, "renderables", [fresh]):
        if isinstance(part, HalfBlockImage):
            part._rows, part._codes = {}, {}
    return fresh


def test_a_theta_step_shares_the_map_rows_it_does_not_change():
    con = console("truecolor")
    a = render_view("map", "phong", {}, 30.0, 78, 48, levels=32)
    b = render_view("map", "phong", {}, 31.0, 78, 48, levels=32)
    ra = pane_lines(a, con, 78, 48)
    rb = pane_lines(b, con, 78, 48, a)
    shared = sum(x is y for x, y in zip(ra, rb, strict=True))
    equal = sum(x == y for x, y in zip(ra, rb, strict=True))
    # the specular lobe moves, the rest of the disc does not: many rows are equal, and every
    # equal image row but those with a mark (the mirror and light marks move) is shared
    assert equal >= 10
    assert shared >= equal - 4
    assert shared < len(ra)


def image(index, marks=()):
    pal = np.array([[0, 0, 0], [255, 0, 0], [0, 255, 0], [0, 0, 255]], dtype=np.uint8)
    return HalfBlockImage(np.asarray(index), pal, marks)


MARK = dict(glyph="×", ascii="x", rgb=(255, 255, 0))


@pytest.mark.parametrize("system", ["truecolor", "256", "none"])
def test_a_mark_row_is_never_lent(system):
    """A mark's cell code names the mark, not the colours under it (its background): the
    same mark on the same cell over another pixel colour has the same codes but must be drawn
    again; so must a row whose mark moved away."""
    index = np.tile(np.arange(4), (4, 2))  # 4 pixel rows = 2 cell rows of 8 cells
    other = index.copy()
    other[0, 3] = 1  # the top pixel under the mark at cell (0, 3)
    a = image(index, [Mark(0, 3, **MARK)])
    b = image(other, [Mark(0, 3, **MARK)])
    ra = a.rows(system)
    rb = b.rows(system, like=a)
    assert rb == image(other, [Mark(0, 3, **MARK)]).rows(system)
    assert rb[0] is not ra[0]
    assert rb[1] is ra[1]  # no mark, the same pixels: lent
    c = image(index, [Mark(1, 3, **MARK)])  # the mark moved to row 1
    rc = c.rows(system, like=a)
    assert rc == image(index, [Mark(1, 3, **MARK)]).rows(system)
    glyph = "x" if system == "none" else "×"
    assert glyph not in "".join(s.text for s in rc[0])
    assert glyph in "".join(s.text for s in rc[1])


def test_another_palette_lends_nothing():
    index = np.tile(np.arange(4), (4, 2))
    a = image(index)
    pal = np.array([[9, 9, 9], [255, 0, 0], [0, 255, 0], [0, 0, 255]], dtype=np.uint8)
    b = HalfBlockImage(index, pal)
    rb = b.rows("truecolor", like=a)
    assert not any(x is y for x, y in zip(a.rows("truecolor"), rb, strict=True))
    assert rb == HalfBlockImage(index, pal).rows("truecolor")


def canvas(color="red", text=None):
    cv = BrailleCanvas(10, 3, (0.0, 20.0), (0.0, 12.0))
    a = cv.layer(color)
    cv.polyline(np.array([0.5, 19.5]), np.array([11.5, 11.5]), a)  # the top row
    cv.polyline(np.array([0.5, 19.5]), np.array([0.5, 0.5]), a)  # the bottom row
    if text:
        cv.text(1, 2, text, "cyan")
    return cv


def test_canvas_lends_equal_rows_only():
    a = canvas()
    ra = a.rows()
    b = canvas(text="hi")  # the middle row gains a label
    rb = b.rows(like=a)
    assert rb == canvas(text="hi").rows()
    assert rb[0] is ra[0] and rb[2] is ra[2] and rb[1] is not ra[1]
    c = canvas(color="blue")  # the same dots in another colour: nothing to lend
    rc = c.rows(like=b)
    assert rc == canvas(color="blue").rows()
    assert not any(x is y for x, y in zip(rb, rc, strict=True))


def test_changed_rows_know_their_changed_cells_and_hold_no_chain():
    """A row drawn again names the row it was compared with and the cells that differ: the
    span must cover every cell whose character or style differs (checked cell by cell here)
    and the rows outside it must be equal; an old row forgets what it was compared with once
    a newer picture is drawn against it (no chain of every frame's rows)."""
    from tuibrdf.render.rowdiff import ChangedRow

    con = console("truecolor")

    def cells(row):
        return [(ch, s.style) for s in row for ch in s.text]

    frames = [render_view(v, "phong", {}, t, 78, 40, levels=32)
              for t in (30.0, 31.0, 35.0, 35.5) for v in ("map",)]
    frames += [render_view("incidence", "phong", {}, t, 78, 40) for t in (30.0, 31.0, 40.0)]
    checked = 0
    for a, b in zip(frames, frames[1:], strict=False):
        if type(a) is not type(b) or len(a.renderables) != len(b.renderables):
            continue
        ra = pane_lines(a, con, 78, 40)
        rb = pane_lines(b, con, 78, 40, a)
        for x, y in zip(ra, rb, strict=True):
            if type(y) is ChangedRow and y.against is x:
                x0, x1 = y.span
                cx, cy = cells(x), cells(y)
                assert len(cx) == len(cy) == 78
                differ = [i for i in range(78) if cx[i] != cy[i]]
                assert differ and x0 <= differ[0] and differ[-1] < x1
                checked += 1
        assert not any(type(x) is ChangedRow and x.against is not None for x in ra)
    assert checked >= 20
