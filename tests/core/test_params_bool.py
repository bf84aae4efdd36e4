"""Bool parameters (BRDF Explorer's ``bool NAME 0|1``): every spelling a user brings — 0/1,
true/false, on/off, yes/no, Python ``True``/``False`` — means the same switch on the command
line, in the Python API, in presets and in a typed value; anything else is refused with the
accepted spellings.  Expected values: the ``on``/``off`` spelling's evaluation (already checked
against an independent Ward implementation in test_brdf_explorer.py)."""

from __future__ import annotations

import numpy as np
import pytest

import tuibrdf
from tests import DATA_DIR
from tuibrdf.cli import main
from tuibrdf.core.params import parse_bool
from tuibrdf.core.registry import get_model
from tuibrdf.state.presets import from_toml
from tuibrdf.state.viewer import Side, ViewerState

WARD = str(DATA_DIR / "brdf" / "ward.brdf")
ON = ["1", "on", "ON", "true", "True", "yes", " 1 ", True, 1, 1.0]
OFF = ["0", "off", "false", "FALSE", "no", False, 0, 0.0]


@pytest.mark.parametrize("v", ON)
def test_on_spellings(v):
    assert parse_bool(v) == "on"


@pytest.mark.parametrize("v", OFF)
def test_off_spellings(v):
    assert parse_bool(v) == "off"


@pytest.mark.parametrize("v", ["2", "y", "", "onn", 0.5, None, (1,)])
def test_not_a_switch(v):
    assert parse_bool(v) is None


def _wiwo():
    wi = np.array([[0.3, 0.1, 0.9]])
    wo = np.array([[-0.2, 0.5, 0.7]])
    return wi, wo


@pytest.mark.parametrize("v", ["1", "true", "yes", True, 1])
def test_api_accepts_bool_spellings(v):
    wi, wo = _wiwo()
    base = {"alpha_x": 0.1, "alpha_y": 0.4}
    want = tuibrdf.evaluate(WARD, {**base, "isotropic": "on"}, wi, wo)
    other = tuibrdf.evaluate(WARD, {**base, "isotropic": "off"}, wi, wo)
    assert not np.allclose(want, other)  # the switch matters here, so the test can fail
    np.testing.assert_array_equal(tuibrdf.evaluate(WARD, {**base, "isotropic": v}, wi, wo), want)


def test_api_refuses_other_values():
    wi, wo = _wiwo()
    with pytest.raises(ValueError, match="isotropic.*1/0, true/false"):
        tuibrdf.evaluate(WARD, {"isotropic": 2}, wi, wo)


@pytest.mark.parametrize("v,want", [("1", "on"), ("0", "off"), ("true", "on"), ("no", "off")])
def test_cli_p_accepts_0_1(v, want, capsys):
    args = ["eval", WARD, "--theta-i", "30", "--theta-r", "40", "--phi-r", "20"]
    assert main([*args, "-p", f"isotropic={v}"]) == 0
    got = capsys.readouterr().out
    assert main([*args, "-p", f"isotropic={want}"]) == 0
    assert got == capsys.readouterr().out


def test_cli_p_refuses_with_spellings(capsys):
    assert main(["eval", WARD, "--theta-i", "30", "--theta-r", "40", "--phi-r", "20",
                 "-p", "isotropic=2"]) == 2
    err = capsys.readouterr().err
    assert "unknown choice '2'" in err and "1/0, true/false, yes/no" in err
    assert "Traceback" not in err


def test_preset_bool_values():
    for raw, want in [("1", "on"), ("0", "off"), ("true", "on"), ('"yes"', "on")]:
        sides = from_toml(f'theta_i = 30.0\n[[sides]]\nmodel = "{WARD}"\n'
                             f"params = {{ isotropic = {raw} }}\n").sides
        assert sides[0].values["isotropic"] == want


@pytest.mark.parametrize("typed,want", [("1", "on"), ("0", "off"), ("true", "on"),
                                         ("off", "off"), ("Yes", "on")])
def test_typed_value_accepts_every_spelling(typed, want):
    model = get_model(WARD)
    s = ViewerState(sides=[Side(model.name)])
    s.side.selected = next(i for i, r in enumerate(s.side.rows())
                           if r.param.name == "isotropic")
    assert s.type_value(typed) is None
    assert s.side.values["isotropic"] == want
    assert "1/0" in s.type_value("2")
