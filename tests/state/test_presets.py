"""Where presets live (``tuibrdf.state.presets``): saved in platformdirs' configuration
directory, read from there and from where earlier versions saved them, the new one winning.

Expected paths are written out from the platformdirs and XDG rules, with a temporary HOME and
XDG_CONFIG_HOME; a system whose configuration directory is not the old one (macOS:
``~/Library/Application Support``) is stood in for by pointing platformdirs elsewhere.
"""

from __future__ import annotations

import sys

import platformdirs
import pytest

from tuibrdf.state import presets
from tuibrdf.state.viewer import Side, ViewerState


@pytest.fixture
def home(tmp_path, monkeypatch):
    """A temporary HOME, without XDG_CONFIG_HOME."""
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    monkeypatch.delenv("XDG_CONFIG_HOME", raising=False)
    return tmp_path / "home"


@pytest.fixture
def elsewhere(tmp_path, monkeypatch):
    """platformdirs' configuration directory somewhere that is not the old one (as on macOS):
    returns that directory's ``tuibrdf``."""
    new = tmp_path / "Application Support"
    monkeypatch.setattr(platformdirs, "user_config_path",
                        lambda appname, appauthor=None, **kw: new / appname)
    return new / "tuibrdf"


def state(theta_i: float) -> ViewerState:
    return ViewerState(sides=[Side("lambert")], theta_i=theta_i)


def write(directory, name: str, theta_i: float) -> None:
    directory.mkdir(parents=True, exist_ok=True)
    (directory / f"{name}.toml").write_text(presets.to_toml(state(theta_i)))


@pytest.mark.skipif(sys.platform != "linux", reason="the XDG rules are Linux's")
def test_on_linux_presets_are_saved_where_they_always_were(home, tmp_path, monkeypatch):
    # platformdirs honours XDG_CONFIG_HOME on Linux, and ~/.config without it: the new
    # directory is the old one, read once
    assert presets.preset_dir() == home / ".config" / "tuibrdf" / "presets"
    assert presets.preset_dirs() == [home / ".config" / "tuibrdf" / "presets"]
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path / "xdg"))
    assert presets.preset_dirs() == [tmp_path / "xdg" / "tuibrdf" / "presets"]
    path = presets.save_preset(state(12.0), "mine")
    assert path == tmp_path / "xdg" / "tuibrdf" / "presets" / "mine.toml"
    assert presets.list_presets() == ["mine"] and presets.load_preset("mine")[0] == 12.0


@pytest.mark.parametrize("xdg", [True, False])
def test_old_presets_are_still_read_and_the_new_one_wins(home, elsewhere, tmp_path,
                                                         monkeypatch, xdg):
    if xdg:
        monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path / "xdg"))
        old = tmp_path / "xdg" / "tuibrdf" / "presets"
    else:
        old = home / ".config" / "tuibrdf" / "presets"
    new = elsewhere / "presets"
    assert presets.preset_dirs() == [new, old]
    write(old, "only-old", 10.0)
    write(old, "both", 20.0)
    write(new, "both", 40.0)
    assert presets.list_presets() == ["both", "only-old"]
    assert presets.load_preset("only-old")[0] == 10.0
    assert presets.load_preset("both")[0] == 40.0  # the new directory's
    # saving goes to the new directory, and leaves the old file as it was
    assert presets.save_preset(state(50.0), "only-old") == new / "only-old.toml"
    assert presets.load_preset("only-old")[0] == 50.0
    assert presets.from_toml((old / "only-old.toml").read_text())[0] == 10.0
    # a name in neither: the message names both directories
    with pytest.raises(presets.PresetError) as e:
        presets.load_preset("absent")
    assert str(new) in str(e.value) and str(old) in str(e.value)


def test_tuibrdf_view_loads_an_old_preset(home, elsewhere):
    from tuibrdf.cli import build_parser
    from tuibrdf.cli.view import build_state

    write(home / ".config" / "tuibrdf" / "presets", "kept", 33.0)
    args = build_parser(["view"]).parse_args(["view", "--preset", "kept"])
    assert build_state(args).theta_i == 33.0
