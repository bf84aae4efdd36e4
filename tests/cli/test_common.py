"""Command-line arguments that looked valid to Python but not to a user (issue 17 item 8,
issue 12 item 10): numbers, case, help wording, φ convention, units, warnings."""

from __future__ import annotations

import os

import pytest

from tuibrdf.cli import build_parser, main

EVAL = ["--theta-r", "10", "--phi-r", "0"]


def run(capsys, *argv):
    rc = main(list(argv))
    out, err = capsys.readouterr()
    return rc, out, err


# ------------------------------------------------------------------ numbers: ASCII only

NOT_NUMBERS = ["1_0", "0_5", "٣", "٠.٥", "３", "1e1_0", " 3", "3 ", "0x10", "1,5", "½", "𝟑",
               "1e", ".", "e3", "+-1", "1.2.3", "infinit"]


@pytest.mark.parametrize("text", NOT_NUMBERS)
def test_theta_refuses_what_float_accepts(capsys, text):
    """float() takes '1_0', Arabic-Indic and full-width digits, spaces: the CLI does not."""
    rc, out, err = run(capsys, "eval", "lambert", "--theta-i", text, *EVAL)
    assert rc == 2 and out == ""
    assert "not a number" in err and len(err.strip().splitlines()) == 1


@pytest.mark.parametrize("text", ["0_1", "٠.٥", "1_0", "0.1,0_2,0.3", "0.1,٠.٢,0.3"])
def test_parameters_refuse_what_float_accepts(capsys, text):
    name = "kd" if "," not in text else "base_color"
    model = "phong" if name == "kd" else "gltf"
    rc, out, err = run(capsys, "eval", model, "-p", f"{name}={text}", "--theta-i", "0", *EVAL)
    assert rc == 2 and out == ""
    assert f"{name} = {text!r} is invalid" in err


@pytest.mark.parametrize("argv", [["render", "lambert", "--width", "1_00"],
                                  ["render", "lambert", "--height", "٣٠"],
                                  ["fit", "x.binary", "--model", "ggx", "--stride", "1,٣,1"],
                                  ["fit", "x.binary", "--model", "ggx", "--stride", "1,3,1_5"]])
def test_integers_refuse_what_int_accepts(capsys, argv):
    rc, out, err = run(capsys, *argv)
    assert rc == 2 and ("not an integer" in err or "is invalid" in err)


@pytest.mark.parametrize("text, value", [("30", 30.0), ("+30", 30.0), ("3e1", 30.0),
                                         ("30.", 30.0), (".5", 0.5), ("1E1", 10.0),
                                         ("-0", 0.0)])
def test_ascii_numbers_still_work(capsys, text, value):
    rc, out, err = run(capsys, "eval", "lambert", "--theta-i", text, *EVAL, "--json")
    assert rc == 0, err
    import json

    assert json.loads(out)["theta_i"] == value


def test_inf_and_nan_keep_their_range_message(capsys):
    rc, _, err = run(capsys, "eval", "lambert", "--theta-i", "inf", *EVAL)
    assert rc == 2 and "theta_i = inf is out of range" in err


# ------------------------------------------------------------------ case-insensitive matches


@pytest.mark.parametrize("argv, hint", [
    (["eval", "cook-torrance", "-p", "M=0.1", "--theta-i", "0", *EVAL], "did you mean 'm'?"),
    (["eval", "phong", "-p", "KD=0.1", "--theta-i", "0", *EVAL], "did you mean 'kd'?"),
    (["eval", "GGX", "--theta-i", "0", *EVAL], "did you mean 'ggx'?"),
    (["Models"], "did you mean 'models'?"),
    (["models", "Lambert"], "did you mean 'lambert'?"),
    (["render", "phong", "--view", "MAP"], "did you mean 'map'?"),
])
def test_wrong_case_gets_a_suggestion(capsys, argv, hint):
    rc, _, err = run(capsys, *argv)
    assert rc == 2 and hint in err


# ------------------------------------------------------------------ help wording, options


def _help(sub: str) -> str:
    parser = build_parser()
    action = next(a for a in parser._actions if a.dest == "command")
    return action.choices[sub].format_help()


def test_theta_i_help_is_singular_where_one_value_is_taken():
    for sub in ("render", "view"):  # eval takes several θi (issue 36)
        h = " ".join(_help(sub).split())
        assert "incidence angle θi in degrees" in h and "angle(s) θi" not in h, sub
    h = " ".join(_help("albedo").split())
    assert "incidence angles θi" in h


def test_view_has_no_color(monkeypatch, capsys):
    import tuibrdf.cli.view as view

    seen = []
    monkeypatch.setattr(view, "check_terminal", lambda: None)
    monkeypatch.setattr(view, "open_viewer", lambda state, color, *hint: seen.append(color))
    # view.run sets NO_COLOR itself: setenv first, so monkeypatch restores "unset" afterwards
    monkeypatch.setenv("NO_COLOR", "")
    monkeypatch.delenv("NO_COLOR")
    assert main(["view", "phong", "--no-color"]) == 0
    assert seen == ["none"] and os.environ.get("NO_COLOR") == "1"


# ------------------------------------------------------------------ output conventions


def test_peak_azimuth_is_in_the_half_open_range(capsys):
    """Oren-Nayar's back-scatter peak sits at the light (φ = 180°): it was printed as −180°
    for one model and 180° for another; the convention is (−180°, 180°]."""
    for model, p in (("oren-nayar", "sigma=90"), ("disney-diffuse", "roughness=1")):
        rc, out, _ = run(capsys, "render", model, "-p", p, "--theta-i", "60", "--width", "40",
                         "--height", "12", "--color", "none")
        assert rc == 0
        head = out.splitlines()[1]  # [0]: the context line
        assert "φ=180°" in head and "φ=-180°" not in head, head


def test_cosine_unit_is_per_steradian(capsys):
    rc, out, _ = run(capsys, "render", "phong", "--cosine", "--color", "none", "--width", "40",
                     "--height", "12")
    assert rc == 0
    assert "sr⁻¹·cos" not in out and "f·cosθr peak" in out and "sr⁻¹" in out


@pytest.mark.parametrize("view", ["map", "incidence", "perpendicular", "solid", "all"])
def test_log_scale_of_subnormal_values_warns_nothing(capsys, view):
    """`render --log` on values ~1e-322 leaked a log10 RuntimeWarning (pytest turns warnings
    into errors, and main() reports an escaped one as an internal error, exit 70)."""
    rc, out, err = run(capsys, "render", "phong", "-p", "kd=0", "-p", "ks=1e-322", "-p", "n=1",
                       "--log", "--view", view, "--width", "30", "--height", "8",
                       "--color", "none")
    assert rc == 0, err
    assert err == ""


def test_view_options_without_the_view_command(monkeypatch, capsys):
    """`tuibrdf` alone opens the viewer, so `tuibrdf --color none` is the viewer in no colour
    (it said "unknown command 'none'"); a misspelt option is the viewer's one-line error."""
    import tuibrdf.cli.view as view

    seen = []
    monkeypatch.setattr(view, "check_terminal", lambda: None)
    monkeypatch.setattr(view, "open_viewer", lambda state, color, *hint: seen.append(color))
    # view.run sets NO_COLOR itself: setenv first, so monkeypatch restores "unset" afterwards
    monkeypatch.setenv("NO_COLOR", "")
    monkeypatch.delenv("NO_COLOR")
    assert main(["--color", "none"]) == 0
    assert seen == ["none"]
    assert main(["--colr", "none"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--colr" in err and "Traceback" not in err
    assert main(["--version"]) == 0
