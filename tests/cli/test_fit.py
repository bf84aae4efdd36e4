"""``tuibrdf fit`` on a file named after a MERL material also scores the published ABC and SGD
fits on the same objective (issue 15).

Synthetic files (tests/merl_writer.py, the exact MERL format) written from the ``abc`` and
``sgd`` models of one material.  Expected values: a model scored on data it wrote has residual 0
(up to the file's float64 rounding), and the objective is symmetric in model and data, so the
SGD fit scored on ABC's file equals the ABC fit scored on SGD's file.
"""

from __future__ import annotations

import json

import pytest

import tuibrdf
from tests.merl_writer import table_from_directions, write_merl
from tuibrdf.cli import main
from tuibrdf.core.fit import material_of

MATERIAL = "blue-metallic-paint"


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    d = tmp_path_factory.mktemp("published")
    out = {}
    for model in ("abc", "sgd"):
        sub = d / model
        sub.mkdir()
        out[model] = write_merl(sub / f"{MATERIAL}.binary", table_from_directions(
            lambda wi, wo, m=model: tuibrdf.evaluate(m, {"material": MATERIAL}, wi, wo)))
    return out


def test_file_names_select_the_material():
    assert material_of("/data/gold-metallic-paint.binary") == "gold-metallic-paint"
    assert material_of("metallic-gold.binary") == "gold-metallic-paint"  # SGD's name for it
    assert material_of("Gold-Metallic-Paint.binary") == "gold-metallic-paint"
    assert material_of("ggx.binary") is None and material_of("gold.binary") is None


def test_fit_reports_the_published_fits_next_to_the_fitted_model(files, capsys):
    res = {}
    for model, path in files.items():
        rc = main(["fit", str(path), "--model", "lambert", "--stride", "3,6,30", "--json"])
        out, err = capsys.readouterr()
        assert rc == 0, err
        doc = json.loads(out)
        pub = doc["published"]
        assert pub["material"] == MATERIAL
        res[model] = pub
        # the model that wrote the file scores 0; a fitted Lambert does worse than it
        assert pub[model] < 1e-12
        assert doc["residual"] > pub[model]
    other = {"abc": "sgd", "sgd": "abc"}
    assert res["abc"]["sgd"] > 1e-3  # two different fits of one material
    assert res["abc"]["sgd"] == pytest.approx(res["sgd"]["abc"], rel=1e-9)
    for model in ("abc", "sgd"):
        assert res[model][other[model]] > 0.0


def test_fit_text_names_both_published_residuals(files, capsys):
    rc = main(["fit", str(files["abc"]), "--model", "lambert", "--stride", "3,6,30"])
    out = capsys.readouterr().out
    assert rc == 0
    line = next(ln for ln in out.splitlines() if ln.startswith("published fits of"))
    assert MATERIAL in line and "abc residual" in line and "sgd residual" in line


def test_other_files_have_no_published_section(tmp_path, capsys):
    path = write_merl(tmp_path / "measured.binary", table_from_directions(
        lambda wi, wo: tuibrdf.evaluate("lambert", {"kd": 0.5}, wi, wo)))
    rc = main(["fit", str(path), "--model", "lambert", "--stride", "3,6,30", "--json"])
    assert rc == 0 and "published" not in json.loads(capsys.readouterr().out)
