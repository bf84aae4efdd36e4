"""``.bparam`` files written by the CLI (``eval --save-bparam``) and the viewer (``s`` beside
the preset): the format BRDF Explorer writes (checked line by line against the file format's
description, docs/reference/formats.md), and they load back (through the independent reader,
``load_bparam``) to exactly the values saved."""

from __future__ import annotations

import shutil

import numpy as np

import tuibrdf
from tests import DATA_DIR
from tuibrdf.cli import main
from tuibrdf.core.registry import get_model
from tuibrdf.state.bparams import save_bparams
from tuibrdf.state.viewer import Side, ViewerState

BRDF = DATA_DIR / "brdf"
VALUES = {"alpha_x": 0.123456789, "alpha_y": 0.4, "Cd": (0.1, 0.2, 0.3),
          "Cs": (1.0, 0.5, 0.25), "isotropic": "1"}


def test_cli_writes_a_bparam_that_loads_back(tmp_path, capsys):
    shutil.copy(BRDF / "ward.brdf", tmp_path / "ward.brdf")
    out = tmp_path / "mine.bparam"
    args = [f"{k}={','.join(map(str, v)) if isinstance(v, tuple) else v}"
            for k, v in VALUES.items()]
    rc = main(["eval", str(tmp_path / "ward.brdf"), *sum((["-p", a] for a in args), []),
               "--theta-i", "30", "--theta-r", "30", "--phi-r", "0", "--save-bparam", str(out)])
    assert rc == 0, capsys.readouterr().err
    lines = out.read_text().splitlines()
    assert lines[0] == "bparam ward.brdf"  # relative to the .bparam's folder
    # the ranges are ward.brdf's own (float alpha_x 0.01 1 0.15)
    assert lines[1:] == ["", "::begin parameters", "float alpha_x 0.01 1 0.123456789",
                         "float alpha_y 0.01 1 0.4", "color Cd 0.1 0.2 0.3",
                         "color Cs 1 0.5 0.25", "bool isotropic 1", "::end parameters"]
    m = get_model(str(out))
    want = dict(VALUES, isotropic="on")
    assert m.defaults() == want
    wi, wo = np.array([0.3, 0.1, 0.9]), np.array([-0.2, 0.5, 0.7])
    np.testing.assert_array_equal(tuibrdf.evaluate(str(out), {}, wi, wo),
                                  tuibrdf.evaluate(str(tmp_path / "ward.brdf"), want, wi, wo))


def test_a_bparam_model_saves_against_its_brdf(tmp_path):
    shutil.copytree(BRDF, tmp_path / "b")
    m = get_model(str(tmp_path / "b" / "ggx.bparam"))
    out = tmp_path / "again.bparam"
    assert main(["eval", str(tmp_path / "b" / "ggx.bparam"), "-p", "kd=0.5", "--theta-i", "0",
                 "--theta-r", "0", "--phi-r", "0", "--save-bparam", str(out)]) == 0
    assert out.read_text().splitlines()[0] == "bparam b/ggx.brdf"
    assert get_model(str(out)).defaults() == {**m.defaults(), "kd": 0.5}


def test_cli_refuses_a_built_in_model(tmp_path, capsys):
    rc = main(["eval", "phong", "--theta-i", "0", "--theta-r", "0", "--phi-r", "0",
               "--save-bparam", str(tmp_path / "x.bparam")])
    err = capsys.readouterr().err
    assert rc == 2 and "not one" in err and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "x.bparam").exists()


def test_viewer_save_writes_bparams_beside_the_preset(tmp_path):
    ward, ggx = str(BRDF / "ward.brdf"), str(BRDF / "ggx.brdf")
    s = ViewerState(sides=[Side(ward, {"isotropic": "on"}), Side(ggx, {"f0": 0.5})])
    preset = tmp_path / "look.toml"
    note = save_bparams(s, preset)
    assert note == " + look.bparam + look-B.bparam"
    assert get_model(str(tmp_path / "look.bparam")).defaults()["isotropic"] == "on"
    assert get_model(str(tmp_path / "look-B.bparam")).defaults()["f0"] == 0.5
    assert save_bparams(ViewerState(sides=[Side("phong")]), tmp_path / "p.toml") == ""
