"""``tuibrdf fit`` (issue 32): RGL ``.bsdf`` targets, several files with ``--jobs``, the
rel_l2 verdict, ``--compare``.

Expected values: a model fitted to a file it wrote matches it (rel_l2 ≈ 0, up to the MERL
table's trilinear lookup); Lambert cannot match a GGX lobe (its rel_l2 is flagged); a ``.bsdf``
target is sampled at the same MERL positions as a ``.binary`` one (the same count).
"""

from __future__ import annotations

import json

import pytest

import tuibrdf
from tests.merl_writer import table_from_directions, write_merl
from tests.rgl_writer import material, write_tensor
from tuibrdf.cli import main
from tuibrdf.core import fit

GGX = {"kd": 0.2, "alpha": 0.2}
STRIDE = "3,6,30"


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    d = tmp_path_factory.mktemp("fit32")
    return {
        "ggx": write_merl(d / "ggx.binary", table_from_directions(
            lambda wi, wo: tuibrdf.evaluate("ggx", GGX, wi, wo))),
        "bsdf": write_tensor(d / "synthetic.bsdf", material()),
    }


def test_rel_l2_verdict(files, capsys):
    rc = main(["fit", str(files["ggx"]), "--model", "ggx", "--mean", "--stride", STRIDE,
               "--json"])
    good = json.loads(capsys.readouterr().out)
    assert rc == 0
    # the model that wrote the file: rel_l2 small at every θi (the table's lookup and bins
    # differ from the kernel by well under 1 % here)
    assert max(max(r["rel_l2"]) for r in good["rel_l2"]) < 0.01
    assert not good["worst_rel_l2"]["poor"]
    rc = main(["fit", str(files["ggx"]), "--model", "lambert", "--mean", "--stride", STRIDE])
    out = capsys.readouterr().out
    assert rc == 0 and "poor fit: rel_l2" in out


def test_bsdf_target(files, capsys):
    rc = main(["fit", str(files["bsdf"]), "--model", "gltf", "--stride", STRIDE, "--json"])
    doc = json.loads(capsys.readouterr().out)
    assert rc == 0 and doc["file"].endswith(".bsdf") and doc["model"] == "gltf"
    merl = fit.sample_set(fit.load_target(str(files["ggx"])), (3, 6, 30))
    assert doc["samples"] == len(merl.cos_io)  # the same positions
    assert len(doc["rel_l2"]) == len(fit.ALBEDO_THETAS)


def test_several_files_in_a_pool(files, tmp_path, capsys):
    missing = tmp_path / "missing.binary"
    rc = main(["fit", str(files["ggx"]), str(missing), str(files["ggx"]), "--model",
               "lambert", "--mean", "--stride", STRIDE, "--jobs", "2"])
    out, err = capsys.readouterr()
    assert rc == 2  # one file failed
    docs = [json.loads(line) for line in out.splitlines()]
    assert [d["file"] for d in docs] == [str(files["ggx"]), str(missing), str(files["ggx"])]
    assert "error" in docs[1] and "missing.binary" in docs[1]["error"]
    assert docs[0]["fits"] == docs[2]["fits"]  # deterministic, whichever process ran it
    # not a terminal: no progress (each file's line is), one line says one failed
    assert err.splitlines() == ['tuibrdf: error: 1 of 3 files could not be fitted: see their '
                                '"error" lines']


def test_several_files_show_their_progress_on_a_terminal(files, tmp_path, monkeypatch,
                                                          capsys):
    import tuibrdf.cli.fit as cli_fit

    monkeypatch.setattr(cli_fit, "isatty", lambda stream: True)
    rc = main(["fit", str(files["ggx"]), str(tmp_path / "missing.binary"), "--model",
               "lambert", "--mean", "--stride", STRIDE, "--jobs", "1"])
    err = capsys.readouterr().err
    assert rc == 2
    progress, error = err.split("\n")[:2]
    # one line rewritten in place: "\r" before each file's count
    assert [p.split(" … ")[0] for p in progress.split("\r")[1:]] == [
        "fitted 1/2 files (0 failed)", "fitted 2/2 files (1 failed)"]
    assert error.startswith("tuibrdf: error: 1 of 2 files could not be fitted")


@pytest.mark.parametrize("argv, needle", [
    (["--compare"], "view needs a terminal"),
    (["--compare", "--model", "ggx"], "--mean"),
])
def test_compare_errors_come_first(files, capsys, argv, needle):
    args = ["fit", str(files["ggx"]), "--stride", STRIDE, *argv]
    if "--model" not in argv:
        args += ["--model", "lambert", "--mean"]
    rc = main(args)
    out, err = capsys.readouterr()
    assert rc == 2 and out == "" and needle in err


def test_comparison_state_is_data_against_fit(files):
    from tuibrdf.cli.fit import comparison_state

    data, result = fit.fit_file(str(files["ggx"]), "ggx", stride=(3, 6, 30), mean=True)
    state = comparison_state(data, result)
    assert [s.model for s in state.sides] == ["merl", "ggx"]
    assert state.sides[0].values["file"] == str(files["ggx"])
