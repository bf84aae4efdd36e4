"""Polish a daily user notices (issue 36): one φ convention in every title, one value and one
curve where an RGB model's channels are equal, render titles that always carry model, θi and
φi.  Expected texts come from the geometry (the mirror of the light at φi is at φi − 180°,
written in (−180°, 180°])."""

from __future__ import annotations

import re

import pytest

from tuibrdf.cli import main
from tuibrdf.render.text import phi_deg_text


@pytest.mark.parametrize("phi,want", [(0, "0"), (315, "-45"), (-45, "-45"), (180, "180"),
                                      (-180, "180"), (540, "180"), (-0.4, "0"), (359.6, "0"),
                                      (181, "-179")])
def test_phi_text_is_in_minus_180_to_180(phi, want):
    assert phi_deg_text(phi) == want


def render_first_line(capsys, *args):
    assert main(["render", *args, "--color", "none"]) == 0
    return capsys.readouterr().out.splitlines()[1]  # [0]: the context line


def test_map_and_section_titles_write_the_same_phi(capsys):
    # the light at φi = 135°: the mirror direction, Phong's peak, is at φ = 135 − 180 = −45°
    common = ["phong", "--phi-i", "135", "--theta-i", "40", "--width", "100", "--height", "8"]
    phis = [re.findall(r"φ=(-?\d+)°", render_first_line(capsys, *common, "--view", v))
            for v in ("map", "perpendicular")]
    assert phis == [["-45"], ["-45"]]
    inc = render_first_line(capsys, *common, "--view", "incidence")
    assert "(φ 135°|-45°)" in inc


@pytest.mark.parametrize("width", [12, 24, 40, 80, 160])
@pytest.mark.parametrize("view", ["map", "incidence", "perpendicular", "albedo", "slice",
                                  "overview"])
def test_render_always_names_model_theta_i_and_phi_i(capsys, width, view):
    assert main(["render", "cook-torrance", "--theta-i", "37", "--phi-i", "300", "--view", view,
                 "--width", str(width), "--height", "8", "--color", "none"]) == 0
    out = capsys.readouterr().out
    head = " ".join(out.splitlines()[:3])  # at 12 columns the three words take three lines
    # φi = 300° is written −60° (the one convention)
    for word in ("cook-torrance", "θi=37°", "φi=-60°"):
        assert word in head.replace(" ", ""), (word, head)
    assert max(len(line) for line in out.splitlines()) <= width


def test_overview_is_the_four_panes_and_all_still_works(capsys):
    assert main(["render", "phong", "--view", "overview", "--width", "40", "--height", "8",
                 "--color", "none"]) == 0
    overview = capsys.readouterr().out
    assert main(["render", "phong", "--view", "all", "--width", "40", "--height", "8",
                 "--color", "none"]) == 0
    assert capsys.readouterr().out == overview
    # context line, then four panes of 8 rows with a blank line between them
    assert len(overview.rstrip("\n").split("\n")) == 1 + 4 * 8 + 3
    assert main(["render", "--help"]) == 0
    assert "overview" in capsys.readouterr().out


def test_a_grey_rgb_model_shows_one_value_and_one_curve(capsys):
    # gltf with base_color 0.8 on every channel: R = G = B everywhere, so no channel to name,
    # one albedo, one curve (no R/G/B legend); a coloured one keeps all three
    def overview(color):
        assert main(["render", "gltf", "-p", f"base_color={color}", "--view", "overview",
                     "--width", "60", "--height", "10", "--color", "none"]) == 0
        return capsys.readouterr().out

    grey = overview("0.8")
    assert "(red)" not in grey and "(Y)" not in grey
    assert re.search(r"a\(θi=30°\) = 0\.\d+\s*$", grey, re.M)  # one number, no (r,g,b)
    assert not re.search(r"^\S+ R\s*$|⠤⠤⠤ R", grey, re.M)  # no channel legend
    coloured = overview("0.8,0.5,0.2")
    assert "(red)" in coloured and "a(θi=30°) = (" in coloured
    assert "R" in coloured and "G" in coloured


def test_albedo_text_of_equal_channels_is_one_number():
    from tuibrdf.render.panes import albedo_text

    assert albedo_text((0.82, 0.82, 0.82)) == "0.82"
    assert albedo_text((0.82, 0.8, 0.82)) == "(0.82,0.8,0.82)"


def test_the_slice_scale_shows_the_specular_strip(capsys):
    # Cook-Torrance (m = 0.2, f0 = 0.04): along θh = 0 at θd = 30° the specular value is
    # F·D·G/(4 cos²θd) ≈ 0.04 · 7.96 / (4 · 0.75) ≈ 0.11 sr⁻¹ (D = 1/(π m²) at θh = 0), while
    # at grazing θd the 1/cos blows up (10⁴ sr⁻¹).  The scale stops at θ ≤ 60° (the title
    # says so), where the largest value is ≈ 0.55 (θd = 60°: F ≈ 0.06, 1/(4·0.25)), so the
    # strip is drawn well above black even in linear scale
    assert main(["render", "cook-torrance", "--view", "slice", "--width", "60", "--height",
                 "20", "--color", "none"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert "(θ≤60°)" in lines[1]
    rows = lines[2:18]  # 16 rows of θd from 90° (top) to 0°
    row30 = rows[round((90 - 30) / 90 * 16)]
    ramp = " .:-=+*#%@"
    strip, far = ramp.index(row30[8]), ramp.index((row30 + " " * 60)[40])
    assert strip >= 2 and strip > far  # the strip at θh ≈ 0 stands out


async def test_the_viewer_slice_is_log_by_default_and_l_toggles_it():
    from tuibrdf.app.app import BrdfApp
    from tuibrdf.state.viewer import Side, ViewerState

    app = BrdfApp(ViewerState(sides=[Side.of("cook-torrance")], view="slice"), sync=True)
    async with app.run_test(size=(120, 40)) as pilot:
        await pilot.pause()
        title = "".join(s.text for s in app.query_one("#extra-a")._strips[0])
        assert "log, 3 decades" in title
        await pilot.press("l")
        await pilot.pause()
        assert app.state.slice_log is False and app.state.log is False
        title = "".join(s.text for s in app.query_one("#extra-a")._strips[0])
        assert "log" not in title
