"""``tuibrdf albedo`` and ``tuibrdf render``: values from closed forms, pictures from goldens
checked by eye, and one line + exit 2 for every kind of bad input.
"""

from __future__ import annotations

import json
import re
import sys

import numpy as np
import pytest
from rich.cells import cell_len

from tests import ROOT
from tuibrdf.cli import main

sys.path.insert(0, str(ROOT / "scripts"))
from update_goldens import GOLDENS  # noqa: E402

ANSI = re.compile(r"\x1b\[[0-9;]*m")


def run(capsys, *argv):
    rc = main(list(argv))
    out, err = capsys.readouterr()
    return rc, out, err


# -- albedo ---------------------------------------------------------------------------------
def test_albedo_lambert_is_kd_at_every_angle(capsys):
    # ∫ kd/π cos θ dω = kd: the table prints the digits the error estimate leaves and the
    # estimate ("± 4e-13"), JSON every digit and the error
    rc, out, _ = run(capsys, "albedo", "lambert", "-p", "kd=0.5")
    assert rc == 0
    rows = [ln.split() for ln in out.splitlines() if not ln.startswith("#")][1:]
    assert [r[0] for r in rows] == ["0", "15", "30", "45", "60", "75", "89"]
    for r in rows:
        assert len(r) == 4 and r[2] == "±" and float(r[3]) < 1e-9
        assert r[1].startswith("0.5000000") and float(r[1]) == pytest.approx(0.5, abs=1e-9)
    rc, out, _ = run(capsys, "albedo", "lambert", "-p", "kd=0.5", "--theta-i", "0", "70",
                     "--json")
    doc = json.loads(out)
    assert rc == 0 and doc["model"] == "lambert" and doc["params"] == {"kd": 0.5}
    assert [v["theta_i"] for v in doc["values"]] == [0.0, 70.0]
    for v in doc["values"]:
        assert v["albedo"] == pytest.approx(0.5, abs=1e-9) and v["energy_conserving"]
        assert 0 <= v["error"] < 1e-9


def test_albedo_phong_lobe_closed_form(capsys):
    # modified Phong, kd = 0, ks = 1: ∫ (n+2)/(2π) cos^n α cos θ dω = cos θi while the whole
    # lobe is above the horizon (n = 200: lobe width ~10°, so θi = 0..60 qualify)
    rc, out, _ = run(capsys, "albedo", "phong", "-p", "kd=0", "-p", "ks=1", "-p", "n=200",
                     "--theta-i", "0", "60", "--json")
    vals = [v["albedo"] for v in json.loads(out)["values"]]
    assert rc == 0
    assert vals == pytest.approx([1.0, 0.5], abs=1e-3)


def test_albedo_rgb_model_prints_three_channels(capsys):
    # glTF with a red base colour and metallic = 1: the specular is coloured by the base, so
    # R > G = B (G, B come from base 0.1)
    rc, out, _ = run(capsys, "albedo", "gltf", "-p", "base_color=0.9,0.1,0.1", "-p",
                     "metallic=1", "--theta-i", "30")
    assert rc == 0 and "a_R" in out and "a_G" in out and "a_B" in out
    r, g, b = (float(x) for x in out.splitlines()[-1].split()[1:4])
    assert r > g == b > 0


def test_albedo_above_one_is_flagged(capsys):
    # ggx with kd = 1: the Lambert term alone returns everything (albedo exactly 1), so any
    # specular on top (f0 = 0.5) exceeds 1; with kd = 0.5 and f0 = 0.04 it stays below
    rc, out, _ = run(capsys, "albedo", "ggx", "-p", "kd=1", "-p", "f0=0.5", "--theta-i", "0",
                     "--json")
    value = json.loads(out)["values"][0]
    assert rc == 0 and value["albedo"] > 1.1 and not value["energy_conserving"]
    rc, out, _ = run(capsys, "albedo", "ggx", "-p", "kd=1", "-p", "f0=0.5", "--theta-i", "0")
    assert rc == 0 and out.splitlines()[-1].endswith("> 1: not energy-conserving")
    rc, out, _ = run(capsys, "albedo", "ggx", "-p", "kd=0.5", "--theta-i", "0", "45")
    assert rc == 0 and "not energy" not in out


def test_albedo_sharp_mirror_lobe_is_not_flagged_and_shows_its_error(capsys):
    # ggx α = 0.001, f0 = 1, kd = 0: the albedo is at most 1 at every incidence (F = 1, Smith
    # G ≤ 1; issue 18's reference: 0.999999 at 0°, 0.99993 at 85°), never flagged
    rc, out, _ = run(capsys, "albedo", "ggx", "-p", "kd=0", "-p", "f0=1", "-p", "alpha=0.001",
                     "--theta-i", "0", "85", "87", "89", "89.9", "90", "--json")
    assert rc == 0
    for v in json.loads(out)["values"]:
        assert v["energy_conserving"] and v["albedo"] - v["error"] <= 1.0
        assert 0 < v["error"] < 1e-3
    assert json.loads(out)["values"][1]["albedo"] == pytest.approx(0.99993, abs=1e-4)


def test_render_albedo_plot_flags_only_a_model_that_gains_energy(capsys):
    # the albedo view's flag is the same test (albedo − error > 1) over the whole curve: ggx
    # α = 0.001, f0 = 1, kd = 0 stays ≤ 1 at every θi (sharp lobe, grazing included); ggx
    # kd = 1 with a specular lobe on top exceeds 1 (its Lambert term alone reflects exactly 1)
    common = ("--view", "albedo", "--color", "none", "--width", "70", "--height", "14")
    rc, out, _ = run(capsys, "render", "ggx", "-p", "kd=0", "-p", "f0=1", "-p", "alpha=0.001",
                     *common)
    assert rc == 0 and "not energy-conserving" not in out
    rc, out, _ = run(capsys, "render", "ggx", "-p", "kd=1", "-p", "f0=0.5", *common)
    assert rc == 0 and "not energy-conserving" in out.splitlines()[1]


# -- render ---------------------------------------------------------------------------------
@pytest.mark.parametrize("name", sorted(GOLDENS))
def test_render_goldens(capsys, name):
    """Goldens (``python scripts/update_goldens.py``), each checked by eye when written:

    - lambert-map-24x12: the title says the value is the same everywhere (0.8/π = 0.255); the
      disc is uniformly the brightest glyph '@'; 'o' (light, θi = 30°) left of centre, 'X'
      (mirror) at the same distance right of it; colour bar 0 … 0.255.
    - phong-map-32x14: n = 200, ks = 1 at θi = 45°: peak (n+2)/(2π) = 32.1 at θ = 45° φ = 0°;
      the only bright pixels are at the 'X', right of centre; the colour bar tops at the peak.
    - cook-torrance-incidence-48x16: the seed's example at 60°: the light's line up and to the
      left, the lobe on the right beyond the mirror direction (peak 6.14 at θ ≈ 62°).
    - phong-map-16x8-truecolor: 24-bit escapes, peak (50+2)/(2π) = 8.28, the colour bar's top.
    - cook-torrance-perpendicular-48x16: the section through the peak (θ = 62.0°) across the
      plane of incidence at 60°: a thin lobe straight up (FWHM 6.6°, too long for the title at
      this width), reaching the max 6.14 (the outer guide at 6; guides every 2).
    - phong-plane-40x14 / cook-torrance-plane-40x14 (the seed's specular pair at θi = 75°,
      exposure 0.5): Phong's highlight is round (about 28 cells × 13 rows = 28 × 26 square
      pixels down to the faintest '.'), Cook-Torrance's a vertical streak about 6 cells wide
      and 12 rows (24 pixels) tall, reaching the horizon (row 1, blank: the sky is not drawn
      in plain text).
    - cook-torrance-sphere-32x14: kd = 0.5, m = 0.2, light 45° to the left: brightest ('%')
      left of centre (x ≈ −0.42 R), near where the normal is the half vector (22.5° left:
      x = −0.38 R; the Lambert term, brightest at 45°, pulls it further left); the right
      edge falls to ':' toward the terminator (normals 90° from the light just beyond the rim).
    - blinn-phong-slice-48x16: θh-only model: every row the same, bright at θh = 0 falling off
      by θh ≈ 20° (the √θh axis spreads it over a third of the width); max (58/8π)·0.6 +
      0.1/π = 1.42.
    - blinn-phong-theta-h-48x12: the same curve against θh: 1.42 at 0, half at about 9.5°
      (cos⁵⁰ θh = ½), flat kd/π = 0.032 beyond.
    - cook-torrance-theta-d-48x12 (defaults, log, θh = 5°): rising with θd as 1/cos² θd, the
      scale set at θ ≤ 85° (120 sr⁻¹) and the curve leaving the top near θd = 85°.
    - phong-sphere-24x10-truecolor: 24-bit escapes; the specular spot saturates (255) left of
      centre.
    """
    rc, out, err = run(capsys, *GOLDENS[name])
    assert rc == 0, err
    assert out == (ROOT / "tests" / "golden" / name).read_text(encoding="utf-8")


@pytest.mark.parametrize("view", ["map", "incidence", "perpendicular", "solid", "albedo", "all",
                                  "sphere", "plane", "slice", "theta-h", "theta-d"])
@pytest.mark.parametrize("model", ["phong", "oren-nayar", "gltf"])
def test_render_every_view_is_deterministic_and_fits(capsys, view, model):
    argv = ["render", model, "--theta-i", "45", "--view", view, "--width", "40",
            "--height", "12"]
    outs = []
    for color in ("none", "truecolor", "256"):
        rc, out, err = run(capsys, *argv, "--color", color)
        assert rc == 0 and err == ""
        again = run(capsys, *argv, "--color", color)[1]
        assert out == again  # the same bytes twice
        plain = ANSI.sub("", out)
        assert max(cell_len(ln) for ln in plain.splitlines()) <= 40
        outs.append(out)
    none, true, c256 = outs
    assert "\x1b" not in none and not any(ln != ln.rstrip() for ln in none.splitlines())
    assert "\x1b[" in true and "\x1b[" in c256
    if view in ("map", "solid", "all", "sphere", "plane", "slice"):
        assert "\x1b[38;2;" in true and "\x1b[38;5;" in c256


def test_render_all_stacks_the_four_views(capsys):
    rc, out, _ = run(capsys, "render", "cook-torrance", "-p", "kd=0", "-p", "f0=0.04", "-p",
                     "m=0.07", "--theta-i", "60", "--view", "all", "--color", "none")
    assert rc == 0
    lines = out.splitlines()
    # after the context line, 24 rows a view and a blank line
    titles = [lines[k] for k in range(1, len(lines), 25)]
    assert len(titles) == 4
    assert "peak 6.14" in titles[0] and "incidence" in titles[1]
    assert "through peak" in titles[2] and "a(θi=60°)" in titles[3]
    assert len(out.splitlines()) == 1 + 4 * 24 + 3  # context, four 80×24 views, blank lines


def test_render_auto_color(capsys, monkeypatch):
    from tuibrdf.cli.render import color_system

    class Tty:
        def isatty(self):
            return True

    assert color_system("auto", {}, Tty()) == "256"
    assert color_system("auto", {"COLORTERM": "truecolor"}, Tty()) == "truecolor"
    assert color_system("auto", {"COLORTERM": "truecolor", "NO_COLOR": ""}, Tty()) == "none"
    assert color_system("auto", {"TERM": "dumb"}, Tty()) == "none"
    assert color_system("auto", {"COLORTERM": "truecolor"}, object()) == "none"
    assert color_system("256", {"NO_COLOR": "1"}, object()) == "256"  # explicit wins
    # under pytest stdout is not a terminal: auto is plain text
    rc, out, _ = run(capsys, "render", "lambert", "--width", "20", "--height", "8")
    assert rc == 0 and "\x1b" not in out
    rc, out2, _ = run(capsys, "render", "lambert", "--width", "20", "--height", "8",
                      "--no-color")
    assert out2 == out


def test_render_constants_match_the_renderer():
    # the CLI keeps its choices without importing rich (fast --help); they must agree
    from tuibrdf.cli import render as cli_render
    from tuibrdf.render import views
    from tuibrdf.render.colormap import CMAPS

    assert cli_render.VIEWS == views.VIEWS and cli_render.CMAPS == CMAPS
    assert (cli_render.MIN_WIDTH, cli_render.MIN_HEIGHT) == (views.MIN_WIDTH, views.MIN_HEIGHT)


# -- bad input ------------------------------------------------------------------------------
BAD = [
    (["render", "cook-torance"], "did you mean 'cook-torrance'"),
    (["render", "phong", "-p", "nn=3"], "unknown parameter 'nn'"),
    (["render", "phong", "-p", "kd=2"], "expected in [0, 1]"),
    (["render", "phong", "-p", "kd=nan"], "expected in [0, 1]"),
    (["render", "phong", "-p", "kd=inf"], "expected in [0, 1]"),
    (["render", "phong", "-p", "kd"], "missing value"),
    (["render", "phong", "-p", "kd=abc"], "kd = 'abc'"),
    (["render", "phong", "-p", "kd=0.8", "-p", "ks=0.5"], "kd + ks"),
    (["render", "phong", "--width", "5"], "width = 5 is out of range"),
    (["render", "phong", "--height", "3"], "height = 3 is out of range"),
    (["render", "phong", "--width", "100000"], "expected 12 to 1000"),
    (["render", "phong", "--width", "wide"], "not an integer"),
    (["render", "phong", "--view", "mapp"], "did you mean 'map'"),
    (["render", "phong", "--cmap", "viridys"], "did you mean 'viridis'"),
    (["render", "phong", "--color", "true"], "unknown color mode"),
    (["render", "phong", "--theta-i", "95"], "expected [0, 90]"),
    (["render", "phong", "--theta-i", "nan"], "out of range"),
    (["albedo", "phong", "--theta-i", "-1"], "expected [0, 90]"),
    (["render", "phong", "--view", "plane", "--exposure", "-1"], "exposure"),
    (["render", "phong", "--view", "sphere", "--gamma", "0"], "gamma"),
    (["render", "phong", "--view", "theta-h", "--theta-d", "91"], "theta-d"),
    (["render", "phong", "--view", "slice", "--phi-d", "nan"], "phi-d"),
    (["render", "phong", "--view", "perpendicular", "--section-azimuth", "x"], "azimuth"),
    (["render", "phong", "--view", "sphre"], "did you mean 'sphere'"),
    (["albedo", "lamberd"], "did you mean 'lambert'"),
    (["albedo", "phong", "-p", "ks=1.5"], "expected in [0, 1]"),
]


@pytest.mark.parametrize("argv, words", BAD, ids=[" ".join(a[1:]) for a, _ in BAD])
def test_bad_input_is_one_line_and_exit_2(capsys, argv, words):
    rc, out, err = run(capsys, *argv)
    assert rc == 2 and out == ""
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err, err
    assert words in err, err


def test_auto_color_looks_at_stdout_as_it_is_at_the_call(monkeypatch):
    # `--color auto` must ask the standard output of the call, not the one the module saw
    # when it was imported; a closed or broken stream is not a terminal (no exception)
    import io

    from tuibrdf.cli.render import color_system

    class Tty(io.StringIO):
        def isatty(self):
            return True

    monkeypatch.setattr(sys, "stdout", Tty())
    assert color_system("auto", {}) == "256"
    closed = io.StringIO()
    closed.close()
    monkeypatch.setattr(sys, "stdout", closed)
    assert color_system("auto", {}) == "none"

    class Broken:
        def isatty(self):
            raise OSError("bad file descriptor")

    assert color_system("auto", {}, Broken()) == "none"


@pytest.mark.parametrize("model, params", [("lambert", ["kd=0.7"]),
                                           ("oren-nayar", ["sigma=30"]),
                                           ("disney-diffuse", []), ("ggx", []),
                                           ("phong", ["n=300"])])
def test_albedo_printed_interval_holds_the_reference(capsys, model, params):
    """Every row's printed interval (value as printed ± error as printed) holds the albedo of
    the same rule run to 1e-12 (six orders tighter), and the printed error is at least the
    rounding of the printed value (it printed 0.753864743041 ± 1e-15 for 0.75386474304118)."""
    from tuibrdf.core.sphere.albedo import albedo_estimate

    argv = ["albedo", model, *(x for p in params for x in ("-p", p)), "--theta-i",
            "0", "33", "61", "80", "89.5"]
    rc, out, _ = run(capsys, *argv)
    assert rc == 0
    rows = [ln.split() for ln in out.splitlines() if not ln.startswith("#")][1:]
    pdict = dict(p.split("=") for p in params)
    for r in rows:
        theta, text, err = float(r[0]), r[1 : -2], float(r[-1])
        ref = albedo_estimate(model, {k: float(v) for k, v in pdict.items()}, theta,
                              rtol=1e-12, max_evals=10_000_000).value
        for t, ref_c in zip(text, np.atleast_1d(ref), strict=True):
            decimals = len(t.split(".")[1])
            assert err >= 0.5 * 10.0 ** -decimals
            assert abs(float(t) - ref_c) <= err, (model, theta, t, ref_c, err)


@pytest.mark.parametrize("view", ["slice", "sphere"])
def test_a_png_of_a_view_the_kernel_fails_in_is_one_line(tmp_path, capsys, view):
    # the kernel returns NaN at grazing light, which the slice and the lit sphere reach at
    # θi = 30°: no picture to write, so one line saying why and exit status 2 (it was an
    # internal error once such views drew their message instead of failing)
    from tests.render.test_albedo_plot import NAN_AT_GRAZING

    path = tmp_path / "nan_grazing.py"
    path.write_text(NAN_AT_GRAZING)
    out = tmp_path / "x.png"
    assert main(["render", str(path), "--view", view, "--format", "png", "--output",
                 str(out)]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and "returned NaN" in err and not out.exists()


def test_every_format_a_refusal_offers_is_one_the_view_takes():
    # `--format X` refused for a view names what that view can be written as instead: each
    # such format must then be accepted (the energy view's refusals once sent png to csv and
    # csv back to png)
    import argparse

    from tuibrdf.cli.common import UsageError
    from tuibrdf.cli.export import _check, offered
    from tuibrdf.render import VIEWS

    def takes(view, fmt):
        try:
            _check(argparse.Namespace(format=fmt, view=view, output="x", inline="off"))
        except UsageError:
            return False
        return True

    for view in VIEWS:
        offer = offered(view)
        named = [f for f in ("png", "npz", "csv", "json") if re.search(rf"\b{f}\b", offer)]
        if "tuibrdf energy" in offer:
            named = [f for f in named if f not in ("csv", "json")]  # (that command's formats)
        assert all(takes(view, f) for f in named), (view, offer)
        for fmt in ("png", "npz", "csv", "json"):
            if not takes(view, fmt):
                with pytest.raises(UsageError, match=re.escape(f"the {view} view: {offer}")):
                    _check(argparse.Namespace(format=fmt, view=view, output="x", inline="off"))
