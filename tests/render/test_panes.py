"""What the panes' titles and axis labels say, at the widths the viewer gives them (80×24:
a 36-cell section pane, 20-cell compare maps): the numbers stay whole and true."""

from __future__ import annotations

import re

import numpy as np
import pytest
from rich.console import Console

from tuibrdf.core.conventions import fmt_value
from tuibrdf.core.material import Material
from tuibrdf.core.registry import MODELS
from tuibrdf.core.views import frame as core_frame
from tuibrdf.render import panes
from tuibrdf.render.colormap import Scale, colorbar
from tuibrdf.render.views import map_pixels, render_view


def lines(renderable, width=200) -> list[str]:
    con = Console(width=width, color_system=None)
    with con.capture() as cap:
        con.print(renderable)
    return cap.get().rstrip("\n").split("\n")


# ------------------------------------------------------------------------ difference map
@pytest.mark.parametrize("color", ["truecolor", "none"])
def test_difference_map_title_gives_the_true_largest_difference(color):
    look = panes.Look(color=color)
    same = core_frame.compute_frame(core_frame.FrameRequest(
        (Material("lambert"), Material("lambert")), 30.0, map_px=map_pixels(40, 12)))
    # identical sides differ by 0 everywhere (the scale's guard against 0/0 is not a value)
    assert "max |Δ| 0" in lines(panes.pane("diff", same, 0, 40, 12, look))[0]
    assert "max |Δ| 1" not in lines(panes.pane("diff", same, 0, 40, 12, look))[0]
    # Lambert kd = 0.8 vs 0.4: f = kd/π everywhere, so |Δ| = 0.4/π = 0.127 at every pixel
    half = core_frame.compute_frame(core_frame.FrameRequest(
        (Material("lambert", {"kd": 0.8}), Material("lambert", {"kd": 0.4})), 30.0,
        map_px=map_pixels(40, 12)))
    assert f"max |Δ| {fmt_value(0.4 / np.pi)}" in lines(
        panes.pane("diff", half, 0, 40, 12, look))[0]


# ----------------------------------------------------------------------------- colour bar
@pytest.mark.parametrize("width", range(8, 41))
def test_narrow_colour_bar_keeps_its_top_value(width):
    # the bar's top is the number that says what white means: a compare map at 80×24 is 20
    # cells wide and used to show "0  0.0566" only (its right label "0.113 sr⁻¹ (A peak)"
    # did not fit, and was dropped whole)
    ticks = lines(colorbar(Scale(0.113), "grey", width, color_system="none",
                           note="(A peak)"))[-1]
    assert ticks.startswith("0")
    assert re.search(r"0\.113( sr⁻¹)?( \(A peak\))?$", ticks.rstrip()), ticks
    assert len(ticks.rstrip()) <= width
    if width >= len("0 0.113 sr⁻¹ (A peak)"):  # room for all of it: all of it
        assert ticks.rstrip().endswith("0.113 sr⁻¹ (A peak)")
    elif width >= len("0 0.113 sr⁻¹"):  # the note goes before the unit
        assert ticks.rstrip().endswith("0.113 sr⁻¹")


def test_narrow_log_colour_bar_keeps_top_and_log():
    # "0.000113" on the left (three decades below): at 24 cells "0.113 sr⁻¹ (log)" does not
    # fit beside it, "0.113 (log)" does
    ticks = lines(colorbar(Scale(0.113, log=True), "grey", 24, color_system="none",
                           note="(A peak)"))[-1].rstrip()
    assert ticks.startswith("0.000113") and ticks.endswith(" 0.113 (log)"), ticks
    assert len(ticks) <= 24


def test_compare_map_at_80x24_shows_the_shared_top():
    # the seed's specular comparison: B's peak (Cook-Torrance m = 0.07 at θi = 60°, 6.14)
    # tops both bars; each map pane of the 80×24 compare grid is about 20 cells wide
    a = Material("phong", {"kd": 0.0, "ks": 0.08, "n": 70.0})
    b = Material("cook-torrance", {"kd": 0.0, "f0": 0.04, "m": 0.07})
    res = core_frame.compute_frame(core_frame.FrameRequest((a, b), 60.0, map_px=map_pixels(18, 8)),
                              slow=False)
    pb = fmt_value(res.sides[1].peak.value)
    for w in (14, 18, 20):
        bar = lines(panes.pane("map", res, 0, w, 8, panes.Look(color="none")), w)[-1]
        assert pb in bar, (w, bar)


# ------------------------------------------------------------------------ section titles
@pytest.mark.parametrize("width", range(20, 100, 3))
@pytest.mark.parametrize("compare", [False, True])
def test_section_titles_keep_the_section_max_whole(width, compare):
    # at 80×24 the section pane is 36 cells: the perpendicular title read
    # "perp. through peak θ=34.4° φ=0°  sec", the number gone; at 60×18 (27 cells) the
    # incidence title read "incidence  section max 0.11" for 0.113
    ct = Material("cook-torrance")
    mats = (ct, ct) if compare else (ct,)
    res = core_frame.compute_frame(core_frame.FrameRequest(mats, 30.0), slow=False)
    for plane, key in (("incidence", "incidence"), ("perpendicular", "peak")):
        head = lines(panes.pane(plane, res, 0, width, 12, panes.Look(color="none")), width)[0]
        assert len(head) <= width
        want = fmt_value(max(float(np.max(s.sections[key])) for s in res.sides))
        m = re.search(r"\bmax (\S+)", head)
        assert m and m.group(1) == want, (plane, head)  # the whole number, not a prefix
        # the plane's name, unless the radial scale needs its room (issue 36: every size
        # keeps the circle spacing; the name goes only below ≈ 34 cells)
        assert ("perp." if plane == "perpendicular" else "incidence") in head or (
            width < 34 and "circles" in head), head
        assert "circles" in head  # the radial scale, at every width (issue 36)
        if width >= 48:  # "incidence  section max 0.113  circles every 0.05": 48 cells
            assert f"section max {want}" in head
        # room: where the plane passes (after the lobe's width and the radial scale, issue
        # 36: "perp. through peak θ=34.4° φ=0°  FWHM 35.1°  section max 0.113  circles 0.05")
        if plane == "perpendicular" and width >= 80:
            assert "through peak θ=" in head


def test_a_cropped_title_never_ends_inside_a_word():
    from tuibrdf.render.text import fit_parts

    # two parts that must stay and do not fit: whole words go, never a number's digits
    parts = [("incidence", 0), ("section max 0.113", 0)]
    for width in range(1, 30):
        line = fit_parts(parts, width)
        assert len(line) <= width
        full = "incidence  section max 0.113"
        assert full.startswith(line) and (line == full or full[len(line)] == " " or
                                          " " not in line), (width, line)


# ---------------------------------------------------------------------- f(θh), f(θd) axes
def test_line_plot_labels_the_bottom_of_its_axis():
    # the linear y axis runs from 0: its last row carries "0" (it carried no label, and the
    # tick at −0.0 from the tick rounding would have read "-0")
    ct = MODELS["cook-torrance"]
    rows = lines(render_view("theta-h", ct, ct.resolve({}), 30.0, 60, 14, theta_d_deg=30.0,
                             color="none"), 60)
    labels = [r[:7].strip() for r in rows[1:-1]]  # between the title and the θh axis
    assert labels[-1] == "0"
    assert "-0" not in labels
    nums = [float(s) for s in labels if s]
    assert nums == sorted(nums, reverse=True) and len(nums) >= 2


@pytest.mark.parametrize("channel, tag", [("lum", "Y"), ("G", "green"), ("B", "blue")])
def test_section_max_of_an_rgb_model_says_which_curve(channel, tag):
    # gltf copper-like at θi = 45°: the map's peak is the red channel's (17.7 "(red)"); with
    # the curves switched to the luminance (key C) the incidence section's max was 11 with no
    # word of which curve, beside a "(red)" peak in the same direction.  A channel is named in
    # words: "(B)" would read as side B of compare mode
    mat = Material("gltf", {"base_color": (0.9, 0.5, 0.1), "metallic": 1.0, "roughness": 0.3})
    res = core_frame.compute_frame(core_frame.FrameRequest((mat,), 45.0), slow=False)
    v = res.sides[0].sections["incidence"]
    # Rec.709 luminance weights (ITU-R BT.709), written here rather than taken from the code
    want = {"lum": v @ np.array([0.2126, 0.7152, 0.0722]), "G": v[:, 1], "B": v[:, 2]}[channel]
    head = lines(panes.pane("incidence", res, 0, 120, 20,
                            panes.Look(color="none", channel=channel)), 120)[0]
    assert f"section max {fmt_value(float(np.max(want)))} ({tag})" in head, head
    # all three channels drawn: the max is the largest channel's, no tag
    head = lines(panes.pane("incidence", res, 0, 120, 20, panes.Look(color="none")), 120)[0]
    assert f"section max {fmt_value(float(np.max(v)))}  " in head, head
    # a scalar model has no channels to name
    ct = core_frame.compute_frame(core_frame.FrameRequest((Material("cook-torrance"),), 45.0),
                             slow=False)
    head = lines(panes.pane("incidence", ct, 0, 120, 20,
                            panes.Look(color="none", channel="lum")), 120)[0]
    assert "(Y)" not in head


# -------------------------------------------------------------------------- help screen
def test_help_lines_wrap_under_their_own_column():
    # the help screen is 64 cells wide (about 58 for the text): a long help line used to go
    # on under the key column ("exponents: ×1.1" where the next key is expected)
    from tuibrdf.app import keys

    rows = lines(keys.help_text(), 58)
    shown = {k.shown for k in keys.KEYS}
    body = rows[2:rows.index("", 2)]  # between the heading and the closing note
    assert len(body) > len(keys.KEYS)  # some lines wrap at this width
    for row in body:
        key = row[:keys.KEY_COLUMN].strip()
        assert key == "" or key in shown, row  # the key column holds keys or nothing
    keyed = [r[:keys.KEY_COLUMN].strip() for r in body if r[:keys.KEY_COLUMN].strip()]
    assert keyed == [k.shown for k in keys.KEYS]
    assert "shift+left" not in shown and "shift+←" in shown  # keys are written as keys


# ------------------------------------------------------------------- clipped line plots
@pytest.mark.parametrize("width", range(40, 101, 4))
def test_clipped_theta_d_plot_says_where_its_axis_stops(width):
    # Cook-Torrance at θh = 0 grows as 1/(4 cos²θd) toward grazing (D, G = 1 and F fixed or
    # growing), so the plot's axis stops at the largest value with both directions within
    # 85° of the normal: θd = 85° itself, wi = (0, sin 85°, cos 85°), wo = (0, −sin 85°,
    # cos 85°) (φd = 90°).  At 80×24 (44 cells) the title used to drop that note whole
    from tuibrdf import evaluate

    t = np.radians(85.0)
    top = float(evaluate("cook-torrance", {}, np.array([0.0, np.sin(t), np.cos(t)]),
                         np.array([0.0, -np.sin(t), np.cos(t)])))
    ct = MODELS["cook-torrance"]
    head = lines(render_view("theta-d", ct, ct.resolve({}), 30.0, width, 12, theta_h_deg=0.0,
                             color="none"), width)[0]
    assert head.startswith("f(θd) at θh=0° φd=90°") or "  f(θd) at θh=0° φd=90°" in head
    assert re.search(rf"scale {re.escape(fmt_value(top))}( sr⁻¹)? \(θ≤85°\)", head), head
    assert len(head) <= width


# ------------------------------------------------------------------- "B": side B, not blue
def test_b_means_side_b_and_the_blue_channel_says_blue():
    # "(B)" meant the blue channel of an RGB peak and "B" side B of compare mode ("B:",
    # "(B peak)"): two bluish RGB sides, B's the larger peak, so every place that names a
    # channel or a side shows up.  Expected: the blue channel written "(blue)" (a glTF base
    # colour with blue the largest component gives a peak in blue: the Schlick specular is
    # white, the diffuse term base·(1−metallic)/π is largest in blue), "(B)" nowhere, and
    # B's peak still said "(B peak)" on the shared colour bar.
    from tuibrdf.app.text import TERSE_FORMS, status_text
    from tuibrdf.state.viewer import Side, ViewerState

    a = Material("gltf", {"base_color": (0.1, 0.2, 0.5), "roughness": 0.6})
    b = Material("gltf", {"base_color": (0.2, 0.3, 0.9), "roughness": 0.6})
    res = core_frame.compute_frame(core_frame.FrameRequest((a, b), 30.0, map_px=map_pixels(40, 14),
                                                 solid=True, probe=(0.1, 0.05)), slow=False)
    look = panes.Look(cmap="grey", color="none")
    state = ViewerState(sides=[Side.of("gltf", dict(a.values)), Side.of("gltf", dict(b.values))],
                        theta_i=30.0, probe=(0.1, 0.05))
    texts = [status_text(state, res, look, {}, "", k).plain for k in range(TERSE_FORMS)]
    for k in (0, 1):
        texts += lines(panes.pane("map", res, k, 40, 14, look), 40)
        texts += lines(panes.pane("solid", res, k, 40, 14, look), 40)
    # the channels of both sides ("all": compare mode's default is the luminance)
    sections = [ln for view in ("incidence", "perpendicular")
                for ln in lines(panes.pane(view, res, 0, 60, 16,
                                           panes.Look(cmap="grey", color="none", channel="all")),
                                60)]
    for t in texts + sections:
        assert "(B)" not in t and "(R)" not in t and "(G)" not in t, t
        assert "A:B" not in t and "B:B" not in t, t  # the legends: side, then channel
    assert "(blue)" in texts[0] and "B:" in texts[0]
    assert any("(B peak)" in t for t in texts)
    assert any("B:blue" in t for t in sections) and any("A:red" in t for t in sections)


def test_cli_render_title_names_the_blue_channel(capsys):
    # `tuibrdf render` prints the same map title: "(blue)", not "(B)"
    from tuibrdf.cli import main

    rc = main(["render", "gltf", "-p", "base_color=0.2,0.3,0.9", "--width", "64", "--height",
               "12", "--color", "none"])
    title = capsys.readouterr().out.splitlines()[1]  # [0]: the context line
    assert rc == 0 and "(blue)" in title and "(B)" not in title, title
