"""``tuibrdf energy``: formats, closed forms through the CLI, bad input (exit 2)."""

from __future__ import annotations

import json
import math
import re

import numpy as np
import pytest

from tuibrdf.cli import main


def run(capsys, *argv: str) -> tuple[int, str, str]:
    rc = main(list(argv))
    out, err = capsys.readouterr()
    return rc, out, err


def test_json_keys_shapes_and_closed_form(capsys):
    rc, out, _ = run(capsys, "energy", "ggx", "-p", "kd=0", "-p", "f0=1", "--param", "alpha",
                     "--range", "0.5:1", "--n", "2", "--mu-n", "3", "--format", "json")
    assert rc == 0
    doc = json.loads(out)
    for key in ("param", "values", "mu", "E", "error", "E_avg", "E_avg_error", "one_minus_E",
                "one_minus_E_avg"):
        assert key in doc
    assert doc["param"] == "alpha" and doc["values"] == [0.5, 1.0] and doc["mu"] == [0, 0.5, 1]
    assert np.shape(doc["E"]) == (2, 3) == np.shape(doc["error"])
    assert abs(doc["E"][1][2] - (1 - math.log(2))) <= max(doc["error"][1][2], 1e-12)
    # Kulla–Conty columns are 1 − E, 1 − E_avg
    assert np.allclose(np.add(doc["E"], doc["one_minus_E"]), 1.0, rtol=0, atol=1e-15)
    assert np.allclose(np.add(doc["E_avg"], doc["one_minus_E_avg"]), 1.0, rtol=0, atol=1e-15)


def test_csv_lambert_columns(capsys):
    rc, out, _ = run(capsys, "energy", "lambert", "--param", "kd", "--n", "3", "--mu-n", "4")
    assert rc == 0
    lines = [ln for ln in out.splitlines() if not ln.startswith("#")]
    head = lines[0].split(",")
    assert head == ["kd", "mu", "E", "error", "1-E", "E_avg", "E_avg_error", "1-E_avg"]
    rows = np.array([[float(x) for x in ln.split(",")] for ln in lines[1:]])
    assert rows.shape == (12, 8)
    kd, e, err, e_avg, e_avg_err = rows[:, 0], rows[:, 2], rows[:, 3], rows[:, 5], rows[:, 6]
    assert np.all(np.abs(e - kd) <= np.maximum(err, 1e-12))  # Lambert: E = kd at every μ
    assert np.all(np.abs(e_avg - kd) <= np.maximum(e_avg_err, 1e-12))


def test_npz_round_trip(tmp_path, capsys):
    path = tmp_path / "t.npz"
    rc, _, _ = run(capsys, "energy", "lambert", "--param", "kd", "--n", "2", "--mu-n", "2",
                   "--format", "npz", "--output", str(path))
    assert rc == 0
    with np.load(path) as z:
        assert z["E"].shape == (2, 2) and z["values"].tolist() == [0.0, 1.0]
        assert str(z["param"]) == "kd"


def test_c_header(tmp_path, capsys):
    path = tmp_path / "t.h"
    rc, _, _ = run(capsys, "energy", "gltf", "--param", "roughness", "--n", "2", "--mu-n", "2",
                   "--format", "h", "-o", str(path))
    assert rc == 0
    text = path.read_text()
    assert "model: gltf" in text and "error bound" in text
    assert "static const float gltf_roughness_E[2][2][3] = {" in text
    assert "static const float gltf_roughness_mu[2]" in text
    # every number is a C float literal
    body = re.findall(r"\{([^}]*)\}", text)
    for block in body:
        for lit in block.replace("\n", " ").split(","):
            assert re.fullmatch(r"-?[0-9.]+(e[-+][0-9]+)?f", lit.strip()), lit


def test_log_param_and_progress(capsys):
    rc, out, err = run(capsys, "energy", "lambert", "--param", "kd", "--range", "0.01:1",
                       "--log-param", "--n", "64", "--mu-n", "64", "--format", "json")
    assert rc == 0
    v = json.loads(out)["values"]
    assert v[0] == 0.01 and v[-1] == 1.0 and v[1] / v[0] == pytest.approx(v[-1] / v[-2])
    assert "64/64 parameter values" in err  # progress on stderr for a large table


@pytest.mark.parametrize("argv, msg", [
    (["ggx", "--param", "fresnel"], "a choice"),
    (["ggx", "--param", "alph"], "did you mean 'alpha'"),
    (["ggx", "--param", "alpha", "--range", "0.5:0.5"], "empty"),
    (["ggx", "--param", "alpha", "--range", "0.5"], "LO:HI"),
    (["ggx", "--param", "alpha", "--range", "0.001:1", "--log-param", "--n", "0"], "n = 0"),
    (["gltf", "--param", "base_color"], "RGB"),
    (["lambert", "--param", "kd", "--range", "0:1", "--log-param"], "above 0"),
])
def test_bad_input_is_one_line_exit_2(capsys, argv, msg):
    rc, out, err = run(capsys, "energy", *argv)
    assert rc == 2 and out == ""
    assert len(err.strip().splitlines()) == 1 and msg in err
