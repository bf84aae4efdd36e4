"""``tuibrdf compare``: closed forms (two Lambert sides) and the one-line error policy."""

from __future__ import annotations

import json

import pytest

from tuibrdf.cli import main


def run(capsys, *argv):
    rc = main(list(argv))
    out, err = capsys.readouterr()
    return rc, out, err


def test_lambert_pair_json(capsys):
    rc, out, err = run(capsys, "compare", "lambert", "-p", "kd=0.8", "lambert", "-q", "kd=0.4",
                       "--theta-i", "0", "60", "--json")
    assert rc == 0 and err == ""
    doc = json.loads(out)
    assert [d["theta_i"] for d in doc] == [0.0, 60.0]
    for d in doc:
        # albedo = kd; fA − fB = fB: rel_l2 = 1, max diff +100 % of B's peak (closed forms)
        assert d["albedo_a"] == pytest.approx(0.8, abs=1e-12)
        assert d["albedo_b"] == pytest.approx(0.4, abs=1e-12)
        assert d["rel_l2"] == pytest.approx(1.0, abs=1e-9)
        assert d["max_diff"] == pytest.approx(1.0, rel=1e-12)
        assert d["reference"] == "b"
        assert {"albedo_a_error", "albedo_b_error", "rel_l2_error", "max_diff_theta_o",
                "max_diff_phi_o"} <= set(d)


def test_table_and_material_side(capsys):
    rc, out, _ = run(capsys, "compare", "lambert", "material:alum-bronze:sgd", "--theta-i", "45")
    assert rc == 0
    assert "# B: sgd" in out
    # luminance row, then one per channel
    assert [line.split()[0] for line in out.splitlines()[-4:]] == ["45", "R", "G", "B"]


def test_identical_sides_are_zero(capsys):
    rc, out, _ = run(capsys, "compare", "ggx", "ggx", "--theta-i", "30", "--json")
    (d,) = json.loads(out)
    assert d["rel_l2"] == 0.0 and d["max_diff"] == 0.0


def test_without_theta_i_the_rows_are_the_albedo_commands(capsys):
    # no --theta-i: the incidences `tuibrdf albedo` prints by default, row for row
    rc, out, _ = run(capsys, "compare", "lambert", "lambert", "-q", "kd=0.4", "--json")
    assert rc == 0
    rc, alb, _ = run(capsys, "albedo", "lambert", "--json")
    assert [d["theta_i"] for d in json.loads(out)] == \
        [d["theta_i"] for d in json.loads(alb)["values"]]
    assert len(json.loads(out)) > 1


@pytest.mark.parametrize("argv, needle", [
    (["compare", "lambert", "nope", "--theta-i", "3"], "unknown model 'nope'"),
    (["compare", "lambert", "material:x:zz", "--theta-i", "3"], "unknown fit 'zz'"),
    (["compare", "lambert", "lambert", "-q", "kd=7", "--theta-i", "3"], "kd"),
    (["compare", "lambert", "x.binary", "--theta-i", "3"], "x.binary"),
    (["compare", "lambert", "lambert", "--theta-i"], "--theta-i"),
])
def test_bad_input_is_one_line(capsys, argv, needle):
    rc, out, err = run(capsys, *argv)
    assert rc == 2 and out == ""
    assert len(err.strip().splitlines()) == 1 and needle in err


def test_render_compare_and_preset(capsys):
    rc, out, err = run(capsys, "render", "phong", "-p", "kd=0", "--compare", "cook-torrance",
                       "-q", "kd=0", "--view", "incidence", "--color", "none")
    assert rc == 0 and err == ""
    assert "A:phong" in out and "B:cook-torrance" in out and "rel_l2" in out
    rc, out2, _ = run(capsys, "render", "--preset", "specular", "--view", "map", "--color",
                      "none", "--width", "60", "--height", "14")
    assert rc == 0
    # both maps and the A − B map, then the numbers
    assert "A: phong" in out2 and "B: cook-torrance" in out2 and "A − B" in out2
    assert out2.rstrip().splitlines()[-1].startswith("θi=")


@pytest.mark.parametrize("argv, needle", [
    (["render", "lambert", "-q", "kd=0.5"], "needs --compare"),
    (["render", "--preset", "specular", "--compare", "ggx"], "--preset and --compare"),
    (["render", "--preset", "specular", "lambert"], "drop MODEL"),
    (["render", "--preset", "no-such"], "no preset named"),
    (["render"], "give a MODEL"),
    (["render", "lambert", "--compare", "lambert", "-q", "kd=2"], "kd"),
])
def test_render_compare_errors(capsys, argv, needle):
    rc, out, err = run(capsys, *argv)
    assert rc == 2 and out == "" and needle in err and len(err.splitlines()) == 1


def test_view_compare_builds_two_sides():
    from tuibrdf.cli import build_parser
    from tuibrdf.cli.view import build_state

    args = build_parser(["view"]).parse_args(
        ["view", "phong", "-p", "n=70", "--compare", "material:alum-bronze:sgd", "-q",
         "material=gold-paint"])
    state = build_state(args)
    assert state.compare and [s.model for s in state.sides] == ["phong", "sgd"]
    assert state.sides[0].values["n"] == 70.0
    assert state.sides[1].values["material"] == "gold-paint"  # -q after the spec wins
    bad = build_parser(["view"]).parse_args(["view", "--preset", "specular", "--compare",
                                              "ggx"])
    with pytest.raises(Exception, match="--preset and --compare"):
        build_state(bad)
