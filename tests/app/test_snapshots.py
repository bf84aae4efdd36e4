"""Screenshots of the viewer (pytest-textual-snapshot); regenerate with --snapshot-update.

Deterministic: frames are computed on the loop (``sync=True``), nothing time-dependent is shown,
and conftest.py pops NO_COLOR / TEXTUAL_THEME / COLORTERM.  Small sizes keep the SVGs small.
"""

import pytest

from tests import DATA_DIR
from tuibrdf.app.app import BrdfApp
from tuibrdf.state.viewer import Side, ViewerState


@pytest.fixture(autouse=True)
def config_home(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path))


def app_for(model="lambert", theta=30.0, **params):
    return BrdfApp(ViewerState(sides=[Side.of(model, params)], theta_i=theta), sync=True)


def test_default_80x24(snap_compare):
    assert snap_compare(app_for(), terminal_size=(80, 24))


def test_default_160x48(snap_compare):
    assert snap_compare(app_for(), terminal_size=(160, 48))


@pytest.mark.parametrize("model", ["phong", "cook-torrance", "oren-nayar", "ue4"])
def test_model_families(snap_compare, model):
    assert snap_compare(app_for(model, theta=45.0), terminal_size=(80, 24))


@pytest.mark.parametrize("presses", [["p"], ["p", "p"]], ids=["diffuse", "specular"])
def test_compare_seed_presets(snap_compare, presses):
    assert snap_compare(app_for(), terminal_size=(120, 36), press=presses)


def test_solid_view(snap_compare):
    assert snap_compare(app_for("phong"), terminal_size=(80, 24), press=["v"])


def test_albedo_view(snap_compare):
    assert snap_compare(app_for("phong"), terminal_size=(80, 24), press=["v", "v"])


def test_help_screen(snap_compare):
    assert snap_compare(app_for(), terminal_size=(80, 24), press=["question_mark"])


def test_too_small_message(snap_compare):
    assert snap_compare(app_for(), terminal_size=(50, 14))


def compare_rgb_app(color=None):
    """An RGB A (gltf) against a scalar B (ggx): the case where both sides used to look the
    same (issue 12 item 2)."""
    state = ViewerState(sides=[Side.of("gltf", {"base_color": (0.9, 0.5, 0.2)}),
                               Side.of("ggx", {"alpha": 0.1})], theta_i=30.0)
    return BrdfApp(state, color=color, sync=True)


def test_compare_rgb_sides_120x36(snap_compare):
    assert snap_compare(compare_rgb_app(), terminal_size=(120, 36))


def test_compare_rgb_sides_no_color_120x36(snap_compare):
    assert snap_compare(compare_rgb_app("none"), terminal_size=(120, 36))


def test_compare_albedo_rgb_sides_no_color_100x30(snap_compare):
    assert snap_compare(compare_rgb_app("none"), terminal_size=(100, 30), press=["v", "v"])


def test_minimum_60x18(snap_compare):
    assert snap_compare(app_for("ggx"), terminal_size=(60, 18))


def test_compare_at_80x24(snap_compare):
    assert snap_compare(compare_rgb_app(), terminal_size=(80, 24))


def test_compare_below_its_minimum_60x18(snap_compare):
    assert snap_compare(compare_rgb_app(), terminal_size=(60, 18))


def test_typed_entry_80x24(snap_compare):
    assert snap_compare(app_for("phong"), terminal_size=(80, 24),
                        press=["down", "down", "equals_sign"])


def test_material_picker_80x24(snap_compare):
    app = BrdfApp(ViewerState(sides=[Side.of("abc")]), sync=True)

    async def pick(pilot):
        app.state.side.selected = [r.param.name for r in app.state.side.rows()].index(
            "material")
        await pilot.press("enter", *"gold")

    assert snap_compare(app, terminal_size=(80, 24), run_before=pick)


def test_specular_compare_on_the_lit_plane(snap_compare):
    # issue 13's done-when: the seed's specular pair (p twice) on the lit plane at a grazing
    # θi = 75°, one exposure for both (X X: 1/4): Phong's highlight is round, Cook-Torrance's
    # stretches toward the horizon
    presses = ["p", "p", "v", "v", "v", "v", "X", "X"]
    assert snap_compare(app_for(theta=75.0), terminal_size=(120, 36), press=presses)


@pytest.mark.parametrize("views", [1, 2, 3, 4, 5],
                         ids=["sphere", "plane", "slice", "theta-h", "theta-d"])
def test_new_views(snap_compare, views):
    # v from the albedo view on: lit sphere, lit plane, θh × θd slice, f(θh), f(θd)
    presses = ["v"] * (2 + views)
    assert snap_compare(app_for("cook-torrance", theta=45.0), terminal_size=(80, 24),
                        press=presses)


def test_many_parameters_scroll_at_80x24(snap_compare):
    # a .brdf file with 13 parameter rows at 80×24: the panel shows a window of them around
    # the selected row, "↑ 3 more" / "↓ 5 more" in its borders, and both sections keep their
    # rows (they were squeezed to "36×3: too small for this pane")

    path = str(DATA_DIR / "brdf" / "disney.brdf")
    app = BrdfApp(ViewerState(sides=[Side(path)], theta_i=30.0), sync=True)
    assert snap_compare(app, terminal_size=(80, 24), press=["down"] * 8)


def test_compare_rgb_legend_folds_at_80x24(snap_compare):
    # two RGB sides in sections squeezed to 6 rows by a 13-row panel: the sections' legends
    # name all 6 curves on 2 lines, one a side (the last channel, B:blue, was cut before);
    # channel "all": compare mode shows each side's luminance unless C asks for the channels

    path = str(DATA_DIR / "brdf" / "disney.brdf")
    state = ViewerState(sides=[Side(path), Side.of("gltf", {"base_color": (0.9, 0.5, 0.2)})],
                        theta_i=30.0, channel="all")
    assert snap_compare(BrdfApp(state, sync=True), terminal_size=(80, 24))
