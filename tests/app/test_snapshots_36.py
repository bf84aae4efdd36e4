"""Screenshots for issue 36 (pytest-textual-snapshot; --snapshot-update regenerates): the
first screen at the three sizes, one colour mode each; the help at 60×18; the slice in its
default log scale; a grey RGB material; viridis in 256 colours."""

import pytest

from tuibrdf.app.app import BrdfApp
from tuibrdf.cli.view import FIRST_HINT, FIRST_MODEL
from tuibrdf.state.viewer import Side, ViewerState


@pytest.fixture(autouse=True)
def config_home(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path))


def first(color=None):
    return BrdfApp(ViewerState(sides=[Side.of(FIRST_MODEL)]), color=color, message=FIRST_HINT,
                   sync=True)


@pytest.mark.parametrize("size,color", [((60, 18), "truecolor"), ((80, 24), "256"),
                                        ((160, 48), "none")],
                         ids=["60x18-truecolor", "80x24-256", "160x48-none"])
def test_first_screen(snap_compare, size, color):
    assert snap_compare(first(color), terminal_size=size)


def test_help_fits_60x18(snap_compare):
    assert snap_compare(first(), terminal_size=(60, 18), press=["question_mark"])


def test_slice_in_log_by_default_80x24(snap_compare):
    app = BrdfApp(ViewerState(sides=[Side.of("cook-torrance")], view="slice"), sync=True)
    assert snap_compare(app, terminal_size=(80, 24))


def test_grey_rgb_material_80x24(snap_compare):
    app = BrdfApp(ViewerState(sides=[Side.of("gltf", {"base_color": (0.8, 0.8, 0.8)})]),
                  sync=True)
    assert snap_compare(app, terminal_size=(80, 24))


def test_viridis_in_256_colours_160x48(snap_compare):
    state = ViewerState(sides=[Side.of("oren-nayar")], theta_i=60.0, cmap="viridis")
    assert snap_compare(BrdfApp(state, color="256", sync=True), terminal_size=(160, 48))
