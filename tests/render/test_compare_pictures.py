"""Issue 32: the seed's specular pair at θi = 60° (Phong 6.7× smaller than Cook-Torrance on
the shared scale) shows both sides in the incidence section, in either order, in truecolor,
256 colours and without colour (characters); the difference map's scale is a property of the
functions, not of the window."""

from __future__ import annotations

import io
import re

import numpy as np
import pytest
from rich.console import Console

from tuibrdf.core.material import Material
from tuibrdf.core.views import frame as core_frame
from tuibrdf.render import panes
from tuibrdf.render.curves import SIDE_HUES
from tuibrdf.render.halfblock import xterm_palette
from tuibrdf.render.pair import render_pair
from tuibrdf.render.sections import SIDE_ASCII
from tuibrdf.render.views import map_pixels

PHONG = ("phong", {"kd": 0.0, "ks": 0.08, "n": 70.0})
CT = ("cook-torrance", {"kd": 0.0, "f0": 0.04, "m": 0.07})
SGR = re.compile(r"\x1b\[([0-9;]*)m")


def rgb(hexs: str) -> tuple[int, int, int]:
    return tuple(int(hexs[i:i + 2], 16) for i in (1, 3, 5))


def nearest_256(c) -> int:
    """The xterm colour (16–255) nearest ``c`` in squared RGB distance, written here."""
    pal = np.asarray(xterm_palette(), dtype=float)[16:]
    return 16 + int(np.argmin(((pal - np.asarray(c, dtype=float)) ** 2).sum(axis=1)))


def cells_by_colour(ansi: str) -> dict[str, int]:
    """Braille cells per SGR foreground code, legend lines (``A:``/``B:``) left out."""
    out: dict[str, int] = {}
    for line in ansi.split("\n"):
        if "A:" in SGR.sub("", line) or "B:" in SGR.sub("", line):
            continue
        fg = ""
        for piece in re.split(r"(\x1b\[[0-9;]*m)", line):
            m = SGR.fullmatch(piece)
            if m:
                fg = m.group(1)
                continue
            n = sum(1 for ch in piece if "\u2801" <= ch <= "\u28ff")
            out[fg] = out.get(fg, 0) + n
    return out


def picture(a, b, color, w=60, h=20, charset="braille"):
    buf = io.StringIO()  # as `tuibrdf render` prints (cli/render.py)
    con = Console(file=buf, width=w, color_system=None if color == "none" else color,
                  force_terminal=color != "none", _environ={})
    con.print(render_pair("incidence", a, b, 60.0, w, h, color=color, charset=charset))
    return buf.getvalue()


@pytest.mark.parametrize("order", ["phong-first", "ct-first"])
@pytest.mark.parametrize("size", [(40, 12), (60, 20), (120, 35)])
def test_both_sides_visible_in_colour(order, size):
    a, b = (PHONG, CT) if order == "phong-first" else (CT, PHONG)
    for color in ("truecolor", "256"):
        counts = cells_by_colour(picture(a, b, color, *size))
        for k in (0, 1):
            c = rgb(SIDE_HUES[k][0])
            code = (f"38;2;{c[0]};{c[1]};{c[2]}" if color == "truecolor"
                    else f"38;5;{nearest_256(c)}")
            # each side's hue on at least 3 cells of the plot (the smaller lobe, a few
            # cells wide at 40×12, is drawn last and keeps its cells)
            assert counts.get(code, 0) >= 3, (color, k, counts)


@pytest.mark.parametrize("order", ["phong-first", "ct-first"])
def test_both_sides_visible_without_colour(order):
    a, b = (PHONG, CT) if order == "phong-first" else (CT, PHONG)
    text = picture(a, b, "none", 60, 20, charset="ascii")
    body = [ln for ln in text.split("\n")[1:] if "A:" not in ln and "B:" not in ln]
    for marker in SIDE_ASCII:
        assert sum(ln.count(marker) for ln in body) >= 3, (marker, text)


def test_sides_and_light_differ_in_256_colours():
    from tuibrdf.render.text import LIGHT_RGB

    codes = {nearest_256(rgb(SIDE_HUES[0][0])), nearest_256(rgb(SIDE_HUES[1][0])),
             nearest_256(LIGHT_RGB)}
    assert len(codes) == 3


def test_difference_scale_does_not_depend_on_the_window():
    a, b = Material(*PHONG), Material(*CT)
    tops = []
    for w, h in ((40, 12), (60, 20), (120, 40)):
        res = core_frame.compute_frame(core_frame.FrameRequest(
            (a, b), 60.0, map_px=map_pixels(w, h)))
        head = panes.pane("diff", res, 0, w, h, panes.Look(color="none"))
        con = Console(width=w, color_system=None, _environ={})
        with con.capture() as cap:
            con.print(head)
        tops.append(re.search(r"max \|Δ\| (\S+)", cap.get()).group(1))
    assert len(set(tops)) == 1, tops
    # and it is the functions' largest difference: at least the difference at the mirror
    # direction, where both lobes peak (an independent lower bound)
    from tuibrdf.core.directions import incident, mirror
    from tuibrdf.core.evaluate import evaluate

    wi = incident(60.0)
    d = abs(float(evaluate(PHONG[0], PHONG[1], wi, mirror(wi))
                  - evaluate(CT[0], CT[1], wi, mirror(wi))))
    assert float(tops[0]) >= float(f"{d:.3g}")


def test_status_line_has_the_numbers_once_the_albedo_is_there():
    from tests.core.sphere.test_compare import reference

    a, b = Material(*PHONG), Material(*CT)
    req = core_frame.FrameRequest((a, b), 60.0, map_px=map_pixels(40, 12))
    core_frame.clear_caches()
    fast = core_frame.compute_frame(req, slow=False)
    look = panes.Look(color="none")
    assert fast.numbers is None and not fast.complete
    assert "rel_l2 …" in panes.stats_text(fast, "map", look).plain
    full = core_frame.compute_frame(req)
    assert full.complete
    text = panes.stats_text(full, "map", look).plain
    rl2 = reference(PHONG, CT, 60.0)[2]  # the product Gauss–Legendre rule of the core test
    shown = float(re.search(r"rel_l2 ([0-9.]+)", text).group(1))
    assert shown == pytest.approx(rl2, rel=1e-2)  # 3 digits shown
    assert "(vs B)" in text and "max Δ" in text


def test_difference_map_without_colour_has_the_marks():
    res = core_frame.compute_frame(core_frame.FrameRequest(
        (Material(*PHONG), Material(*CT)), 60.0, map_px=map_pixels(40, 14)))
    buf = io.StringIO()
    Console(file=buf, width=40, color_system=None, _environ={}).print(
        panes.pane("diff", res, 0, 40, 14, panes.Look(color="none")))
    body = buf.getvalue()
    assert "X" in body and "o" in body  # the mirror direction and the light
    assert "-" in body or "=" in body  # B larger at the mirror direction (its peak is 6.7×)
