"""``tuibrdf materials``, ``-p material=...`` and its errors (issue 15).

Expected values: the header's names (dj_brdf.h), the sRGB transfer function's definition, and
the stored albedo table (checked against fresh quadrature in test_material_albedo.py).
"""

from __future__ import annotations

import json
import re

import pytest

from tests import ROOT
from tuibrdf.cli import main
from tuibrdf.cli.materials import srgb8
from tuibrdf.core.brdf.materials import material_names
from tuibrdf.core.sphere.material_albedo import stored

ESC = "\x1b["


def run(capsys, *argv):
    rc = main(list(argv))
    out, err = capsys.readouterr()
    return rc, out, err


def test_lists_the_100_names_sorted_with_four_albedos_plain_when_piped(capsys):
    rc, out, err = run(capsys, "materials")
    assert rc == 0 and err == "" and ESC not in out  # capsys is not a terminal: plain text
    lines = [ln for ln in out.splitlines() if ln and not ln.startswith("#")][1:]
    assert [ln.split()[0] for ln in lines] == sorted(material_names())
    gold = next(ln for ln in lines if ln.split()[0] == "gold-metallic-paint")
    triples = re.findall(r"(\d\.\d{3}),(\d\.\d{3}),(\d\.\d{3})", gold)
    assert len(triples) == 4
    want = stored()["gold-metallic-paint"]
    got = [[float(x) for x in t] for t in triples]
    expected = [want["abc"][0], want["abc"][1], want["sgd"][0], want["sgd"][1]]
    for g, w in zip(got, expected, strict=True):
        assert g == pytest.approx(w.tolist(), abs=5e-4)
    assert run(capsys, "materials") == (0, out, "")  # deterministic


def test_swatches_only_with_colour(capsys, monkeypatch):
    rc, out, _ = run(capsys, "materials", "--color", "truecolor")
    assert rc == 0
    line = next(ln for ln in out.splitlines() if "gold-metallic-paint " in ln)
    r, g, b = srgb8(stored()["gold-metallic-paint"]["abc"][0])
    assert f"{ESC}38;2;{r};{g};{b}m██" in line
    assert ESC not in run(capsys, "materials", "--no-color")[1]
    monkeypatch.setenv("NO_COLOR", "1")
    assert ESC not in run(capsys, "materials", "--color", "auto")[1]


def test_truecolor_swatches_after_256_colour_ones_in_one_process(capsys):
    # Rich keeps a Style's escape codes on it for the first colour system that rendered it: a
    # swatch style shared with an earlier 256-colour rendering came out in 256 colours
    r, g, b = srgb8(stored()["gold-metallic-paint"]["abc"][0])
    for color, code in (("256", f"{ESC}38;5;"), ("truecolor", f"{ESC}38;2;{r};{g};{b}m")):
        rc, out, _ = run(capsys, "materials", "--color", color)
        line = next(ln for ln in out.splitlines() if "gold-metallic-paint " in ln)
        assert rc == 0 and code in line, (color, line)


def test_srgb8_follows_the_transfer_function():
    # IEC 61966-2-1: 0 → 0, 1 → 255, 0.0031308 → 12.92·0.0031308 = 0.04045 → 10,
    # 0.5 → 1.055·0.5^(1/2.4) − 0.055 = 0.735357 → 188; out-of-range values clip
    assert srgb8((0.0, 1.0, 0.0031308)) == (0, 255, 10)
    assert srgb8((0.5, -1.0, 2.0)) == (188, 0, 255)


def test_json_has_every_material_aliases_and_albedos(capsys):
    rc, out, _ = run(capsys, "materials", "--json")
    assert rc == 0
    doc = json.loads(out)
    mats = {m["name"]: m for m in doc["materials"]}
    assert sorted(mats) == sorted(material_names()) and doc["theta_i"] == [0.0, 60.0]
    # from the header: { "beige-fabric", "fabric-beige", ... }, { "alum-bronze",
    # "alum-bronze", ... } (same name: no alias), { "white-fabric2", "", ... }
    assert mats["beige-fabric"]["aliases"] == ["fabric-beige"]
    assert mats["alum-bronze"]["aliases"] == [] and mats["white-fabric2"]["aliases"] == []
    for m in mats.values():
        for fit in ("abc", "sgd"):
            assert set(m["albedo"][fit]) == {"0", "60"}
            assert all(len(v) == 3 and all(0.0 < x < 1.0 for x in v)
                       for v in m["albedo"][fit].values())


def test_material_parameter_from_the_command_line(capsys):
    rc, out, _ = run(capsys, "eval", "sgd", "-p", "material=fabric-beige", "--theta-i", "30",
                     "--theta-r", "30", "--phi-r", "0", "--json")
    rc2, out2, _ = run(capsys, "eval", "sgd", "-p", "material=beige-fabric", "--theta-i", "30",
                       "--theta-r", "30", "--phi-r", "0", "--json")
    assert rc == rc2 == 0
    # the alias resolves to the canonical name: the same parameters, the same values
    assert json.loads(out)["params"] == {"material": "beige-fabric"}
    assert json.loads(out) == json.loads(out2)
    rc, _, err = run(capsys, "render", "abc", "-p", "material=gold-metalic-paint")
    assert rc == 2 and err.count("\n") == 1
    assert "did you mean 'gold-metallic-paint'" in err and "tuibrdf materials" in err


# ------------------------------------------------------------------ tuibrdf view --material


def view_state(*argv):
    from tuibrdf.cli import build_parser
    from tuibrdf.cli.view import build_state

    return build_state(build_parser().parse_args(["view", *argv]))


def test_view_material_opens_a_fit_and_compare_modes():
    s = view_state("--material", "gold-metallic-paint", "--theta-i", "45")
    assert [(x.model, x.values) for x in s.sides] == [("abc", {"material": "gold-metallic-paint"})]
    assert s.theta_i == 45.0 and not s.compare
    s = view_state("--material", "metallic-gold", "--fit", "sgd")  # SGD's name for it
    assert [(x.model, x.values) for x in s.sides] == [("sgd", {"material": "gold-metallic-paint"})]
    s = view_state("--material", "blue-fabric", "--compare-fit")
    assert s.compare and [(x.model, x.values["material"]) for x in s.sides] == [
        ("abc", "blue-fabric"), ("sgd", "blue-fabric")]
    s = view_state("--material", "blue-fabric", "--fit", "sgd", "--compare-material",
                   "fabric-beige")
    assert s.compare and [(x.model, x.values["material"]) for x in s.sides] == [
        ("sgd", "blue-fabric"), ("sgd", "beige-fabric")]


@pytest.mark.parametrize(("argv", "expected"), [
    (["--fit", "sgd"], "--fit needs --material"),
    (["--compare-fit"], "--compare-fit needs --material"),
    (["phong", "--material", "blue-fabric"], "not both"),
    (["--material", "blue-fabric", "--preset", "diffuse"], "give one"),
    (["--material", "blue-fabric", "--compare-fit", "--compare-material", "red-fabric"],
     "give one"),
    (["--material", "blue-fabirc"], "did you mean 'blue-fabric'"),
    (["--material", "blue-fabric", "--compare-material", "nope"], "unknown choice 'nope'"),
    (["--material", "blue-fabric", "--fit", "ggx"], "unknown fit"),
])
def test_view_material_errors_are_one_line(capsys, argv, expected):
    rc = main(["view", *argv])
    err = capsys.readouterr().err
    assert rc == 2 and expected in err and err.count("\n") == 1 and "Traceback" not in err


def test_materials_doc_outputs_are_current():
    # every "$ tuibrdf ..." block of docs/reference/materials.md is the command's real output
    import subprocess
    import sys

    root = ROOT
    r = subprocess.run([sys.executable, "scripts/gen_materials_doc.py", "--check"], cwd=root,
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
