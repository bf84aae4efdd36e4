"""The command line: ``main([...])`` for every subcommand, closed-form values, error policy.

Expected numbers come from closed forms stated next to each test, never from the CLI's own
earlier output.
"""

from __future__ import annotations

import json
import math
import subprocess
import sys

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tuibrdf.cli import SUBCOMMANDS, main
from tuibrdf.cli.common import UsageError, parse_params
from tuibrdf.core.params import Model, Param
from tuibrdf.core.registry import MODELS


def run(capsys, *argv: str) -> tuple[int, str, str]:
    rc = main(list(argv))
    out, err = capsys.readouterr()
    return rc, out, err


def table_rows(out: str) -> list[list[float]]:
    """The numeric rows of an ``eval``/``albedo`` table (comment and header lines skipped)."""
    rows = []
    for line in out.splitlines():
        cells = line.split()
        try:
            rows.append([float(c) for c in cells])
        except ValueError:
            continue
    return rows


# --------------------------------------------------------------------------- tuibrdf (no command)


def test_help_lists_every_subcommand(capsys):
    rc, out, _ = run(capsys, "--help")
    assert rc == 0
    for name, _, _ in SUBCOMMANDS:
        assert name in out


def test_help_does_not_import_textual_rich_or_plotext():
    """``tuibrdf --help`` stays fast: the heavy UI libraries load only when needed."""
    code = ("import sys\nfrom tuibrdf.cli import main\nrc = main(['--help'])\n"
            "print('MODULES', ' '.join(sorted(sys.modules)))\nraise SystemExit(rc)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    line = next(x for x in out.stdout.splitlines() if x.startswith("MODULES "))
    top = {m.split(".")[0] for m in line.split()[1:]}
    assert not top & {"textual", "rich", "plotext"}, top & {"textual", "rich", "plotext"}


def test_unknown_command_gets_a_close_match(capsys):
    rc, out, err = run(capsys, "evl", "phong")
    assert rc == 2 and out == ""
    assert "unknown command 'evl' (did you mean 'eval'?)" in err


# --------------------------------------------------------------------------- models


def test_models_lists_every_model_and_parameter(capsys):
    rc, out, _ = run(capsys, "models")
    assert rc == 0
    for m in MODELS.values():
        assert f"{m.name} — {m.title}" in out
        for p in m.params:
            assert p.range_text() in out
        for c in m.constraints:
            assert f"constraint: {c.text}" in out
    assert run(capsys, "models") == (0, out, "")  # deterministic


def test_models_json_matches_declarations(capsys):
    rc, out, _ = run(capsys, "models", "--json")
    assert rc == 0
    doc = json.loads(out)
    assert [d["name"] for d in doc] == list(MODELS)
    for d in doc:
        m = MODELS[d["name"]]
        assert d["reciprocal"] == m.reciprocal and d["rgb"] == m.rgb
        assert [p["name"] for p in d["params"]] == [p.name for p in m.params]
        for p in d["params"]:
            if p["kind"] == "float":
                assert p["min"] <= p["default"] <= p["max"]


def test_models_filter_and_typo(capsys):
    rc, out, _ = run(capsys, "models", "phong")
    assert rc == 0 and out.startswith("phong — ") and "lambert" not in out
    rc, out, err = run(capsys, "models", "phnog")
    assert rc == 2 and "unknown model 'phnog' (did you mean 'phong'?)" in err


# --------------------------------------------------------------------------- eval


def test_eval_lambert_closed_form(capsys):
    """Lambert: f = kd/π for every pair of directions above the horizon."""
    rc, out, _ = run(capsys, "eval", "lambert", "-p", "kd=0.5", "--theta-i", "30",
                     "--theta-r", "0", "--phi-r", "0")
    assert rc == 0
    [[tr, pr, f]] = table_rows(out)
    assert (tr, pr) == (0, 0)
    assert f"{0.5 / math.pi:.6g}" == "0.159155"
    assert out.splitlines()[-1].split()[-1] == "0.159155"


def test_eval_phong_at_mirror_closed_form(capsys):
    """Modified Phong at the mirror direction (θr = θi, φr = 0): S·wo = 1, so
    f = kd/π + ks(n+2)/(2π)."""
    kd, ks, n = 0.2, 0.7, 35.0
    rc, out, _ = run(capsys, "eval", "phong", "-p", f"kd={kd}", "-p", f"ks={ks}", "-p", f"n={n}",
                     "--theta-i", "40", "--theta-r", "40", "--phi-r", "0", "--json")
    assert rc == 0
    doc = json.loads(out)
    expected = kd / math.pi + ks * (n + 2) / (2 * math.pi)
    assert doc["values"][0]["f"] == pytest.approx(expected, rel=1e-12)


def test_eval_outer_product_order(capsys):
    """θr × φr, θr slowest.  Lambert is constant, so check the directions and the value
    kd/π (default kd from the declaration)."""
    rc, out, _ = run(capsys, "eval", "lambert", "--theta-i", "10", "--theta-r", "0", "30", "60",
                     "--phi-r", "0", "180")
    assert rc == 0
    rows = table_rows(out)
    assert [(r[0], r[1]) for r in rows] == [(0, 0), (0, 180), (30, 0), (30, 180), (60, 0),
                                            (60, 180)]
    kd = MODELS["lambert"].param("kd").default
    assert all(r[2] == pytest.approx(kd / math.pi, rel=1e-5) for r in rows)


def test_eval_several_theta_i(capsys):
    """``--theta-i 20 50``: θi slowest, then θr × φr, with a theta_i column; each value is the
    modified Phong closed form kd/π + ks(n+2)/(2π)·cosⁿα, α the angle between wo and the mirror
    of wi (both in the plane φ = 0/180°, so α = |θr − θi| for φr = 0)."""
    kd, ks, n = 0.2, 0.5, 20.0
    rc, out, _ = run(capsys, "eval", "phong", "-p", f"kd={kd}", "-p", f"ks={ks}", "-p", f"n={n}",
                     "--theta-i", "20", "50", "--theta-r", "20", "50", "--phi-r", "0", "--json")
    assert rc == 0
    doc = json.loads(out)
    assert doc["theta_i"] == [20, 50]
    got = [(v["theta_i"], v["theta_r"], v["phi_r"], v["f"]) for v in doc["values"]]
    assert [g[:3] for g in got] == [(20, 20, 0), (20, 50, 0), (50, 20, 0), (50, 50, 0)]
    for ti, tr, _, f in got:
        want = kd / math.pi + ks * (n + 2) / (2 * math.pi) * math.cos(math.radians(tr - ti)) ** n
        assert f == pytest.approx(want, rel=1e-12)
    rc, out, _ = run(capsys, "eval", "phong", "--theta-i", "20", "50", "--theta-r", "20",
                     "--phi-r", "0")
    lines = out.splitlines()
    assert "theta_i=" not in lines[0] and lines[1].split()[:3] == ["theta_i", "theta_r", "phi_r"]
    assert [r.split()[0] for r in lines[2:]] == ["20", "50"]


def test_eval_cosine_multiplies_by_cos_theta_r(capsys):
    """Lambert with --cosine at θr = 60°: kd/π · cos 60° = kd/(2π)."""
    rc, out, _ = run(capsys, "eval", "lambert", "-p", "kd=1", "--theta-i", "0",
                     "--theta-r", "60", "--phi-r", "45", "--cosine", "--json")
    assert rc == 0
    assert json.loads(out)["values"][0]["f"] == pytest.approx(1 / (2 * math.pi), rel=1e-12)


def test_eval_json_carries_resolved_params(capsys):
    rc, out, _ = run(capsys, "eval", "phong", "-p", "kd=0.1", "--theta-i", "30",
                     "--theta-r", "30", "45", "--phi-r", "0", "--json")
    assert rc == 0
    doc = json.loads(out)
    defaults = MODELS["phong"].defaults()
    assert doc["model"] == "phong" and doc["theta_i"] == 30
    assert doc["params"] == {**defaults, "kd": 0.1}
    assert [(v["theta_r"], v["phi_r"]) for v in doc["values"]] == [(30, 0), (45, 0)]


def test_eval_phong_below_mirror_is_smaller(capsys):
    """The Phong lobe is maximal at the mirror: any other θr in the plane gives less."""
    rc, out, _ = run(capsys, "eval", "phong", "--theta-i", "30", "--theta-r", "0", "20", "30",
                     "40", "90", "--phi-r", "0")
    f = [r[2] for r in table_rows(out)]
    assert rc == 0 and max(f) == f[2]


def test_eval_same_name_twice_last_wins(capsys):
    rc, out, _ = run(capsys, "eval", "lambert", "-p", "kd=0.9", "-p", "kd=0.5", "--theta-i", "0",
                     "--theta-r", "0", "--phi-r", "0")
    assert rc == 0 and table_rows(out)[0][2] == pytest.approx(0.5 / math.pi, rel=1e-5)


# --------------------------------------------------------------------------- -p parsing by kind

FAKE = Model(
    "fake", "Fake",
    (Param("albedo", "ρ", (0.5, 0.5, 0.5), 0.0, 1.0, kind="rgb"),
     Param("distribution", "D", "ggx", kind="choice", choices=("beckmann", "ggx")),
     Param("file", "F", "", kind="path"),
     Param("sigma", "σ", 0.0, 0.0, 90.0, unit="deg")),
    lambda wi, wo, **kw: wi[..., 2] * 0,
)


def test_parse_rgb_triple_and_grey():
    assert parse_params(FAKE, ["albedo=0.9,0.6,0.2"]) == {"albedo": (0.9, 0.6, 0.2)}
    assert parse_params(FAKE, ["albedo=0.25"]) == {"albedo": (0.25, 0.25, 0.25)}
    assert parse_params(FAKE, [" albedo = 1, 0 ,0 "]) == {"albedo": (1.0, 0.0, 0.0)}


@pytest.mark.parametrize("token, words", [
    ("albedo=0.9,0.6", ["albedo", "three values in [0, 1]"]),
    ("albedo=0.9,0.6,1.2", ["albedo", "three values in [0, 1]"]),
    ("albedo=red", ["albedo", "'red'", "one grey value"]),
    ("albedo=nan", ["albedo", "three values in [0, 1]"]),
    ("distribution=beckman", ["unknown choice 'beckman' (did you mean 'beckmann'?)", "ggx"]),
    ("file=/no/such/file.binary", ["file", "no such file"]),
    ("sigma=91", ["sigma", "[0, 90]°"]),
    ("sigma=-inf", ["sigma", "[0, 90]°"]),
])
def test_parse_bad_values_by_kind(token, words):
    with pytest.raises(UsageError) as e:
        parse_params(FAKE, [token])
    for w in words:
        assert w in str(e.value)


def test_parse_choice_is_case_insensitive_and_path_exists(tmp_path):
    f = tmp_path / "x.binary"
    f.write_bytes(b"")
    got = parse_params(FAKE, ["distribution=Beckmann", f"file={f}"])
    assert got == {"distribution": "beckmann", "file": str(f)}


# --------------------------------------------------------------------------- bad input → 2

EVAL = ["--theta-i", "30", "--theta-r", "0", "--phi-r", "0"]

BAD = [
    (["eval", "cook-torance", *EVAL], ["unknown model 'cook-torance'", "valid: lambert"]),
    (["eval", "phong", "-p", "kd=nan", *EVAL], ["kd", "in [0, 1]"]),
    (["eval", "phong", "-p", "kd=inf", *EVAL], ["kd", "in [0, 1]"]),
    (["eval", "phong", "-p", "kd=1.5", *EVAL], ["kd", "in [0, 1]"]),
    (["eval", "phong", "-p", "n=-1", *EVAL], ["n", "in [0, 10000]"]),
    (["eval", "phong", "-p", "kd", *EVAL], ["kd", "missing value", "in [0, 1]"]),
    (["eval", "phong", "-p", "kd=abc", *EVAL], ["kd", "'abc'", "in [0, 1]"]),
    (["eval", "phong", "-p", "kd=", *EVAL], ["kd", "in [0, 1]"]),
    (["eval", "phong", "-p", "=3", *EVAL], ["missing parameter name", "kd, ks, n"]),
    (["eval", "phong", "-p", "exponent=3", *EVAL], ["unknown parameter 'exponent'",
                                                  "kd, ks, n"]),
    (["eval", "phong", "-p", "nn=3", *EVAL], ["did you mean 'n'"]),
    (["eval", "phong", "-p", "kd=0.6", "-p", "ks=0.7", *EVAL], ["kd + ks ≤ 1", "kd = 0.6",
                                                                "ks = 0.7"]),
    (["eval", "phong", "--theta-i", "95", "--theta-r", "0", "--phi-r", "0"],
     ["theta_i = 95", "[0, 90]"]),
    (["eval", "phong", "--theta-i", "-1", "--theta-r", "0", "--phi-r", "0"],
     ["theta_i", "[0, 90]"]),
    (["eval", "phong", "--theta-i", "nan", "--theta-r", "0", "--phi-r", "0"],
     ["theta_i = nan", "[0, 90]"]),
    (["eval", "phong", "--theta-i", "x", "--theta-r", "0", "--phi-r", "0"],
     ["theta_i = 'x' is not a number", "[0, 90]"]),
    (["eval", "phong", "--theta-i", "30", "--theta-r", "91", "--phi-r", "0"],
     ["theta_r = 91", "[0, 90]"]),
    (["eval", "phong", "--theta-i", "30", "--theta-r", "9", "--phi-r", "inf"],
     ["phi_r = inf", "[-360, 360]"]),
    (["eval", "phong", "--theta-i", "30"], ["required", "--theta-r"]),
    (["eval", "phong", "--theta", "3"], ["ambiguous option"]),
    (["eval"], ["required", "MODEL"]),
    (["models", "--jsn"], ["unrecognized arguments: --jsn"]),
]


@pytest.mark.parametrize("argv, words", BAD, ids=[" ".join(a[:4]) for a, _ in BAD])
def test_bad_input_is_one_line_exit_2(capsys, argv, words):
    rc, out, err = run(capsys, *argv)
    assert rc == 2
    assert out == ""
    assert len(err.strip().splitlines()) == 1, err
    assert "Traceback" not in err
    for w in words:
        assert w in err


# --------------------------------------------------------------------------- fuzz

MODEL_TOKENS = [*MODELS, "cook-torance", "", "phong2"]
TOKENS = [
    "models", "eval", "albedo", "--json", "--cosine", "-p", "--param", "--theta-i",
    "--theta-r", "--phi-r", "--theta", "-h", "--", "-", "kd=0.5", "ks=0.5", "kd=0.6", "ks=0.7",
    "n=1e4", "n=0", "n=1e9", "kd", "=3", "kd=abc", "kd=nan", "kd=", "kd==1", "sigma=30",
    "0", "30", "45", "89.9", "90", "95", "-30", "-0", "1e-300", "nan", "inf", "-inf", "abc",
    "180", "-360", "361", "0x10", "1_0", "é", "kd=0.5,0.5,0.5",
]


@settings(max_examples=300, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(st.lists(st.sampled_from(TOKENS + MODEL_TOKENS), max_size=12),
       st.sampled_from(["eval", "albedo", "models", None]))
def test_fuzz_main_exits_0_or_2(capsys, tokens, command):
    """Any argv built from plausible tokens ends with 0 or 2 and never a traceback."""
    argv = ([command] if command else []) + tokens
    rc = main(argv)
    _, err = capsys.readouterr()
    assert rc in (0, 2), (argv, err)
    assert "Traceback" not in err
    if rc == 2:
        assert len(err.strip().splitlines()) == 1, (argv, err)


def test_version(capsys):
    import tuibrdf
    from tuibrdf.cli import main

    assert main(["--version"]) == 0
    assert capsys.readouterr().out.strip() == f"tuibrdf {tuibrdf.__version__}"
