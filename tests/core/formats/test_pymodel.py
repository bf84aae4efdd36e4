"""Python model files (``.py``) and plugin models (entry-point group ``tuibrdf.models``).

Expected values: Minnaert's closed form f = ρ/π (cos θi cos θo)^(k−1) and its normal-incidence
albedo 2ρ/(k+1) (∫₀¹ 2μ^k dμ); errors in user code are reported with the user's file and line.
"""

from __future__ import annotations

import sys
import textwrap

import numpy as np
import pytest

import tuibrdf
from tests import ROOT
from tests.core.formats.test_userfiles import sweep
from tuibrdf.cli import main
from tuibrdf.core.formats import userfiles
from tuibrdf.core.formats.userfiles import UserFileError
from tuibrdf.core.registry import get_model

EXAMPLE = ROOT / "docs" / "examples" / "minnaert.py"


def test_documented_example_matches_the_closed_form():
    rng = np.random.default_rng(5)
    d = rng.normal(size=(2, 500, 3))
    d[..., 2] = np.abs(d[..., 2]) + 1e-3
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    got = tuibrdf.evaluate(str(EXAMPLE), {"albedo": 0.6, "k": 0.7}, d[0], d[1])
    want = 0.6 / np.pi * (d[0, :, 2] * d[1, :, 2]) ** (0.7 - 1)
    np.testing.assert_allclose(got, want, rtol=1e-14)
    m = get_model(str(EXAMPLE))
    assert m.title == "Minnaert" and m.name == str(EXAMPLE) and not m.rgb


def test_documented_example_albedo():
    # a(0) = ∫ ρ/π μ^(k−1) μ dω = 2ρ/(k+1)
    a = tuibrdf.albedo(str(EXAMPLE), {"albedo": 0.5, "k": 1.3}, 0.0)
    assert float(a) == pytest.approx(2 * 0.5 / 2.3, rel=1e-4)


def test_documented_example_is_stable():
    assert sweep(get_model(str(EXAMPLE))) > 0


def test_cli_view_state_and_eval(capsys):
    from tuibrdf.cli.common import Parser
    from tuibrdf.cli.view import add_args, build_state

    p = Parser(prog="tuibrdf view")
    add_args(p)
    state = build_state(p.parse_args([str(EXAMPLE), "-p", "k=1.2"]))
    assert state.sides[0].spec.title == "Minnaert" and state.sides[0].values["k"] == 1.2
    rc = main(["eval", str(EXAMPLE), "-p", "k=1", "--theta-i", "10", "--theta-r", "40",
               "--phi-r", "90"])
    out, _ = capsys.readouterr()
    assert rc == 0 and f"{0.8 / np.pi:.6g}" in out  # k = 1: Lambert 0.8/π


def write(tmp_path, text, name="user_model.py"):
    f = tmp_path / name
    f.write_text(textwrap.dedent(text))
    return f


MODEL_HEAD = """\
import numpy as np
from tuibrdf.core.params import Model, Param
"""


@pytest.mark.parametrize("body,line,what", [
    ("import numpy_does_not_exist\n", 3, "ModuleNotFoundError: No module named"),
    ("def oops(:\n", 3, "SyntaxError"),
    ("raise RuntimeError('boom')\n", 3, "RuntimeError: boom"),
    ("raise SystemExit(3)\n", 3, "SystemExit"),
    ("X = 1\n", None, "does not define MODEL"),
    ("MODEL = 42\n", None, "defines MODEL as a int"),
    ("MODEL = Model('m', 'M', (Param('kd', 'kd', 5.0),), lambda wi, wo, kd: kd)\n", None,
     "defaults are invalid"),
])
def test_import_errors_name_file_and_line(tmp_path, body, line, what):
    f = write(tmp_path, MODEL_HEAD + body)
    with pytest.raises(UserFileError) as e:
        get_model(str(f))
    msg = str(e.value)
    assert "\n" not in msg and what in msg, msg
    assert msg.startswith(f"{f}:{line}:" if line else f"{f}:"), msg


KERNELS = {
    "raises": ("def k(wi, wo, kd):\n    x = 1\n    return wi[..., 5]\n", 5, "IndexError"),
    "fp_error": ("def k(wi, wo, kd):\n    return np.float64(kd) / (wi[..., 2] * 0.0)\n", 4,
                 "FloatingPointError"),
    "shape": ("def k(wi, wo, kd):\n    return np.zeros(7)\n", 3, "returned shape (7,)"),
    "nan": ("def k(wi, wo, kd):\n    return np.where(wo[..., 0] > 0, np.nan, kd)\n", 3,
            "returned NaN"),
    "type": ("def k(wi, wo, kd):\n    return 'abc'\n", 3, "not an array of numbers"),
}


@pytest.mark.parametrize("case", list(KERNELS))
def test_kernel_errors_are_the_users(tmp_path, case, capsys):
    src, line, what = KERNELS[case]
    f = write(tmp_path, MODEL_HEAD + src +
              "MODEL = Model('m', 'M', (Param('kd', 'kd', 0.5),), k)\n")
    wi = np.array([[0.6, 0.0, 0.8], [0.0, 0.0, 1.0]])
    with pytest.raises(UserFileError) as e:
        tuibrdf.evaluate(str(f), {}, wi, wi)
    msg = str(e.value)
    assert "\n" not in msg and msg.startswith(f"{f}:{line}:") and what in msg, msg
    # the command line: one line on stderr, exit 2, no traceback
    rc = main(["eval", str(f), "--theta-i", "30", "--theta-r", "30", "--phi-r", "0"])
    _, err = capsys.readouterr()
    assert rc == 2 and err.count("\n") == 1 and "Traceback" not in err, err


def test_scalar_results_broadcast_and_negatives_clamp(tmp_path):
    f = write(tmp_path, MODEL_HEAD + "MODEL = Model('c', 'C', (Param('kd', 'kd', 0.5),), "
                                     "lambda wi, wo, kd: kd - 0.75, rgb=True)\n")
    wi = np.array([[0.0, 0.0, 1.0]] * 4)
    assert tuibrdf.evaluate(str(f), {"kd": 1.0}, wi, wi).tolist() == [[0.25] * 3] * 4
    assert tuibrdf.evaluate(str(f), {"kd": 0.0}, wi, wi).tolist() == [[0.0] * 3] * 4


# --------------------------------------------------------------------------- plugins


@pytest.fixture
def plugin_dist(tmp_path, monkeypatch):
    """A fake installed distribution declaring three entry points: a good model, a module that
    fails to import and an object that is not a Model."""
    site = tmp_path / "site"
    dist = site / "tuibrdf_fake_plugin-1.0.dist-info"
    dist.mkdir(parents=True)
    (dist / "METADATA").write_text("Metadata-Version: 2.1\nName: tuibrdf-fake-plugin\n"
                                   "Version: 1.0\n")
    (dist / "entry_points.txt").write_text(
        "[tuibrdf.models]\nfake-lambert = fake_plugin_mod:MODEL\n"
        "fake-broken = fake_broken_mod:MODEL\nfake-notmodel = fake_plugin_mod:NOT_A_MODEL\n")
    (site / "fake_plugin_mod.py").write_text(
        MODEL_HEAD + "NOT_A_MODEL = 3\n"
        "MODEL = Model('fake-lambert', 'Fake Lambert', (Param('kd', 'kd', 0.5),),\n"
        "              lambda wi, wo, kd: np.full(np.shape(wi)[:-1], kd / np.pi))\n")
    (site / "fake_broken_mod.py").write_text("raise ImportError('missing dependency xyz')\n")
    monkeypatch.syspath_prepend(str(site))
    monkeypatch.setattr(userfiles, "_PLUGINS", {})
    yield site
    for mod in ("fake_plugin_mod", "fake_broken_mod"):
        sys.modules.pop(mod, None)


def test_plugin_model_by_name(plugin_dist):
    m = get_model("fake-lambert")
    assert m.title == "Fake Lambert"
    wi = np.array([0.0, 0.0, 1.0])
    assert tuibrdf.evaluate("fake-lambert", {"kd": 0.3}, wi, wi) == pytest.approx(0.3 / np.pi)


def test_a_broken_plugin_is_a_one_line_error_naming_why(plugin_dist):
    # a plugin is reached by its name (get_model: `tuibrdf eval NAME`, `tuibrdf view NAME`):
    # one that fails to import, or whose object is not a Model, is one line naming the
    # plugin and the reason; the good one of the same distribution still loads
    for name, why in (("fake-broken", "failed to load: ImportError: missing dependency xyz"),
                      ("fake-notmodel", "is a int, not a tuibrdf Model")):
        with pytest.raises(ValueError) as e:
            get_model(name)
        assert name in str(e.value) and why in str(e.value), e.value
        assert "\n" not in str(e.value)
    assert get_model("fake-lambert").title == "Fake Lambert"


def test_unknown_name_is_still_a_close_match_error(plugin_dist):
    with pytest.raises(ValueError, match="unknown model 'lamberd' \\(did you mean 'lambert'"):
        get_model("lamberd")


def test_a_model_file_cannot_name_its_own_albedo_kernel(tmp_path):
    """``albedo_kernel`` (a ``.bsdf`` file's model has one: its own f to the horizon) would run
    a function of the file's unguarded, so an exception from it would escape as a traceback:
    a model file naming one is a one-line error; its albedo integrates its guarded kernel."""
    f = write(tmp_path, MODEL_HEAD + textwrap.dedent("""\
        def boom(wi, wo):
            raise RuntimeError("not guarded")
        MODEL = Model("m", "M", (Param("kd", "kd", 0.5, 0.0, 1.0),),
                      lambda wi, wo, kd: np.full(np.broadcast_shapes(wi.shape, wo.shape)[:-1],
                                                 kd / np.pi), albedo_kernel=boom)
        """))
    with pytest.raises(UserFileError) as e:
        get_model(str(f))
    assert str(e.value) == (f"{f}: MODEL.albedo_kernel is not for model files: the albedo "
                            "integrates the kernel")
