"""Presets remember the whole look (view, φi, ψ, log, colour map, channel, exposure, gamma,
the fixed angles, the solid's camera), and a preset written before looks were (θi and sides
only, as earlier versions saved it: the text below is such a file) loads as before."""

from __future__ import annotations

import pytest

from tuibrdf.state import presets
from tuibrdf.state.viewer import Side, ViewerState

#: what tuibrdf saved before this change (copied from an old preset, not generated)
OLD = '''# tuibrdf preset
theta_i = 45.0

[[sides]]
model = "phong"
params = { kd = 0.0, ks = 0.08, n = 70.0 }
'''

LOOK = {"view": "sphere", "phi_i": 135.0, "section_azimuth": 30.0, "log": True,
        "cmap": "viridis", "channel": "G", "exposure": 4.0, "gamma": 1.8, "theta_d": 12.0,
        "theta_h": 7.0, "phi_d": 45.0, "azimuth": 10.0, "elevation": -20.0, "cosine": True,
        "sqrt_h": False, "slice_log": False}


@pytest.fixture
def config(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path))
    monkeypatch.setenv("HOME", str(tmp_path))
    return tmp_path


def test_every_look_setting_round_trips(config):
    s = ViewerState(sides=[Side("cook-torrance")], theta_i=52.0)
    for k, v in LOOK.items():
        setattr(s, k, v)
    presets.save_preset(s, "look")
    fresh = ViewerState()
    presets.apply_loaded(fresh, *presets.load_preset("look"))
    assert {k: getattr(fresh, k) for k in LOOK} == LOOK
    assert fresh.theta_i == 52.0 and fresh.side.model == "cook-torrance"
    assert set(LOOK) == set(presets.LOOK)  # the test covers every saved setting


def test_an_old_preset_loads_as_before():
    theta, sides, look = presets.from_toml(OLD)
    assert theta == 45.0 and look == {}
    assert sides[0].model == "phong" and sides[0].values["n"] == 70.0
    s = ViewerState()
    s.view, s.log, s.phi_i = "solid", True, 90.0
    presets.apply_loaded(s, theta, sides, look)
    assert (s.view, s.log, s.phi_i, s.theta_i) == ("solid", True, 90.0, 45.0)  # look kept


def test_unknown_look_keys_are_ignored():
    _, _, look = presets.from_toml(OLD.replace("[[sides]]", "[look]\nfuture = 3\nlog = true\n"
                                               "\n[[sides]]"))
    assert look == {"log": True}


@pytest.mark.parametrize("line,words", [('view = "nope"', "look.view"),
                                        ("gamma = 9.0", "look.gamma"),
                                        ('log = "yes"', "true or false"),
                                        ("phi_i = 1e999", "look.phi_i"),
                                        ("exposure = true", "look.exposure")])
def test_a_bad_look_is_one_line(line, words):
    with pytest.raises(presets.PresetError, match=words) as e:
        presets.from_toml(OLD.replace("[[sides]]", f"[look]\n{line}\n\n[[sides]]"), "p.toml")
    assert "\n" not in str(e.value) and str(e.value).startswith("p.toml: ")


def test_view_flag_wins_over_the_preset_look(config):
    from tuibrdf.cli import build_parser
    from tuibrdf.cli.view import build_state

    s = ViewerState(sides=[Side("phong")])
    s.view, s.log = "albedo", True
    presets.save_preset(s, "p")
    got = build_state(build_parser().parse_args(["view", "--preset", "p"]))
    assert (got.view, got.log) == ("albedo", True)
    got = build_state(build_parser().parse_args(["view", "--preset", "p", "--view", "plane"]))
    assert (got.view, got.log) == ("plane", True)
