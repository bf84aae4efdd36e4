"""The half/difference-angle pictures (``tuibrdf.render.halfdiff_view``), drawn as the viewer
and ``tuibrdf render`` draw them: ``render_view`` → the frame → ``panes.extra_pane``.

Expected values: normalised Blinn-Phong depends on θh only (every row of its slice is the
same, brightest at θh = 0), and the layout written out below (title, image rows, axes).
"""

from __future__ import annotations

import pytest
from rich.console import Console

from tuibrdf.core.registry import get_model
from tuibrdf.render.views import render_view

BP = {"kd": 0.1, "ks": 0.6, "n": 50}


def show(renderable, width=60) -> list[str]:
    con = Console(width=width, color_system=None)
    with con.capture() as cap:
        con.print(renderable)
    return cap.get().splitlines()


def test_slice_view_layout():
    m = get_model("blinn-phong")
    lines = show(render_view("slice", m, m.resolve(BP), 30.0, 60, 20, color="none"))
    assert len(lines) == 20 and max(len(ln) for ln in lines) <= 60
    assert lines[0].startswith("blinn-phong")
    assert "θh×θd at φd=90°" in lines[0] and "√θh axis" in lines[0]
    # 20 rows: title, 16 image rows (θd = 90° at the top, 0° at the bottom), θh axis, bar
    assert lines[1].lstrip().startswith("90°") and lines[16].lstrip().startswith("0°")
    assert lines[-3].lstrip().startswith("θh 0°")
    # a θh-only model: every image row is the same (columns bright on the left)
    rows = [ln[8:] for ln in lines[1:17]]
    assert all(r == rows[0] for r in rows) and rows[0][0] == "@"


@pytest.mark.parametrize("view", ["theta-h", "theta-d"])
@pytest.mark.parametrize("name", ["blinn-phong", "gltf", "cook-torrance"])
def test_line_views_fit_and_are_deterministic(view, name):
    m = get_model(name)
    v = m.resolve({})

    def draw(**kw):
        return show(render_view(view, m, v, 30.0, 60, 14, color="none", theta_d_deg=0.0,
                                **kw))

    for log in (False, True):
        a = draw(log=log)
        assert a == draw(log=log)
        assert len(a) == 14 and max(len(ln) for ln in a) <= 60
        assert a[-1].lstrip().startswith(("θh 0°", "θd 0°"))
        assert ("f(θh) at θd=0° φd=90°" if view == "theta-h" else
                "f(θd) at θh=0° φd=90°") in a[0]
    ascii_lines = draw(charset="ascii")
    assert all(ord(ch) < 128 for ln in ascii_lines[1:] for ch in ln.replace("°", "")
               .replace("θ", ""))
