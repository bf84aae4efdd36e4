"""``tuibrdf check``: each broken model fails exactly its check (exit 1); the built-ins."""

from __future__ import annotations

import json
import textwrap

import pytest

from tests import ROOT
from tuibrdf.cli import main
from tuibrdf.core.registry import MODELS
from tuibrdf.core.sphere.checks import run_checks

HEAD = """
import numpy as np
from tuibrdf.core.params import Model, Param

def up(wi, wo):
    return (wi[..., 2] > 0.0) & (wo[..., 2] > 0.0)
"""

#: name → (kernel body, the one check that must fail)
BROKEN = {
    # f depends on θi only: energy ≤ 0.75, positive, not reciprocal
    "nonreciprocal": ("np.where(up(wi, wo), 0.5 / np.pi * (1 + 0.5 * wi[..., 2]), 0.0)",
                      "reciprocity"),
    # symmetric, negative where cos θi cos θo > 2/3 (the clamped albedo stays below 0.5)
    "negative": ("np.where(up(wi, wo), 0.5 / np.pi * (1 - 1.5 * wi[..., 2] * wo[..., 2]), 0.0)",
                 "positivity"),
    # a constant 2/π: albedo 2 at every incidence
    "albedo2": ("np.where(up(wi, wo), 2.0 / np.pi, 0.0)", "energy"),
}


def write_model(tmp_path, name: str, body: str, extra: str = "") -> str:
    path = tmp_path / f"{name}.py"
    path.write_text(HEAD + textwrap.dedent(f"""
def kernel(wi, wo):
    return {body}
{extra}
MODEL = Model("{name}", "{name}", (), kernel)
"""))
    return str(path)


def run(capsys, *argv):
    rc = main(list(argv))
    out, err = capsys.readouterr()
    return rc, out, err


@pytest.mark.parametrize("name", list(BROKEN))
def test_each_broken_model_fails_exactly_its_check(tmp_path, capsys, name):
    body, failing = BROKEN[name]
    path = write_model(tmp_path, name, body)
    rc, out, err = run(capsys, "check", path, "--json")
    assert rc == 1, err
    doc = json.loads(out)
    verdicts = {c["name"]: c["ok"] for c in doc["checks"]}
    assert verdicts == {"finite": True, "positivity": True, "reciprocity": True,
                        "energy": True, failing: False}
    bad = next(c for c in doc["checks"] if c["name"] == failing)
    if failing == "positivity":  # the raw minimum: 0.5/π·(1 − 1.5) at the normal pair
        assert bad["worst"] == pytest.approx(-0.25 / 3.141592653589793, rel=1e-12)
        assert "θ 0°" in bad["where"]
    if failing == "energy":
        assert bad["worst"] == pytest.approx(2.0, abs=1e-5)


def test_text_output_and_exit_0(capsys):
    rc, out, _ = run(capsys, "check", str(ROOT / "docs/examples/lambert_sampled.py"))
    assert rc == 0, out
    lines = out.splitlines()
    assert [ln.split()[0] for ln in lines[1:]] == ["finite", "positivity", "reciprocity",
                                                   "energy", "chi2"]
    assert all(ln.split()[1] == "ok" for ln in lines[1:])


def test_nan_fails_finite_with_where(tmp_path, capsys):
    body = "np.where(wi[..., 2] == 1.0, np.nan, 0.1)"
    rc, out, _ = run(capsys, "check", write_model(tmp_path, "nan", body), "--json")
    assert rc == 1
    checks = json.loads(out)["checks"]
    c = checks[0]
    assert c["name"] == "finite" and not c["ok"] and "NaN" in c["where"]
    assert "wi (θ 0°" in c["where"]
    # the albedo cannot be integrated through a NaN: energy says so, and fails
    assert checks[3]["name"] == "energy" and "not evaluated" in checks[3]["detail"]


def test_wrong_sampler_fails_chi2(tmp_path, capsys):
    extra = textwrap.dedent("""
    from tuibrdf.core.brdf.sampling import ggx_pdf, ggx_sample

    def pdf(wi, wo):  # wrong by ×1.1 in the half y > 0
        return ggx_pdf(wi, wo, 0.0, 0.04, 0.3, "exact") * np.where(wo[..., 1] > 0, 1.1, 1.0)

    def sample(wi, u1, u2):
        wo, _ = ggx_sample(wi, u1, u2, 0.0, 0.04, 0.3, "exact")
        return wo, pdf(wi, wo)
    """)
    path = write_model(tmp_path, "wrongpdf", "np.where(up(wi, wo), 0.1, 0.0)", extra)
    rc, out, _ = run(capsys, "check", path, "--json")
    assert rc == 1
    verdicts = {c["name"]: c["ok"] for c in json.loads(out)["checks"]}
    assert verdicts == {"finite": True, "positivity": True, "reciprocity": True,
                        "energy": True, "chi2": False}


def test_sample_without_pdf_is_bad_input(tmp_path, capsys):
    path = write_model(tmp_path, "half", "np.where(up(wi, wo), 0.1, 0.0)",
                       "def sample(wi, u1, u2):\n    return wi, u1\n")
    rc, out, err = run(capsys, "check", path)
    assert rc == 2 and out == "" and "no function pdf" in err
    assert len(err.strip().splitlines()) == 1


def test_bad_input_exit_2(capsys):
    rc, _, err = run(capsys, "check", "ggx", "-p", "alpha=7")
    assert rc == 2 and len(err.strip().splitlines()) == 1


#: energy at the parameters' ends, verified (docs/reference/checks.md says why each is so):
#: every other check of every built-in holds at its defaults and ends
ENERGY_GAINS = {
    "blinn-phong": {"ks=1"},  # the (n+8)/(8π) normalisation is approximate: E = 1.06 at n = 20
    "cook-torrance": {"kd=1"},  # kd/π + specular: kd is not weighted by 1 − F
    "ggx": {"kd=1"},  # the same
    "oren-nayar": {"kd=1"},  # the interreflection term adds up to 5 % at grazing
    "gltf": {"base_color=1,1,1", "roughness=0"},  # (1 − F(v·h)) c_diff + specular at grazing
    "disney-diffuse": {"base_color=1,1,1", "roughness=1"},  # grazing retro-reflection FD90
    "ue4": {"base_color=1,1,1"},  # c_diff/π + specular, no (1 − F)
    "sgd": {"material=color-changing-paint1", "material=color-changing-paint2",
            "material=gold-metallic-paint2", "material=two-layer-gold",
            "material=two-layer-silver", "material=white-paint",
            "material=yellow-matte-plastic"},  # published fits, not energy-bounded
}


@pytest.mark.parametrize("name", [n for n, m in MODELS.items()
                                  if not any(p.kind == "path" for p in m.params)])
def test_every_built_in_at_defaults_and_ends(name):
    from tuibrdf.core.sphere.checks import _energy, configurations

    m = MODELS[name]
    results = {r.name: r for r in run_checks(m, None)}
    for check in ("finite", "positivity", "reciprocity"):
        assert results[check].ok, results[check]
    if "chi2" in results:
        assert results["chi2"].ok
    configs = configurations(m, None)
    assert _energy(m, configs[:1]).ok  # the defaults
    gains = {label for label, v in configs[1:] if not _energy(m, [(label, v)]).ok}
    assert gains == ENERGY_GAINS.get(name, set())


BRDF_FILE = """analytic

::begin parameters
float k 0 1 0.5
::end parameters

::begin shader
vec3 BRDF( vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y )
{
    // negative where L and V are both near the normal; not reciprocal (L.z only)
    return vec3(0.1 - k * 0.2 * dot(L, N) * dot(V, N) + 0.05 * dot(L, N));
}
::end shader
"""


def test_a_brdf_file_is_checked_on_its_raw_values(tmp_path, capsys):
    # the .brdf format clamps negatives to 0 when drawing; the check sees the shader's value:
    # at k = 1 and the normal pair 0.1 − 0.2 + 0.05 = −0.05
    path = tmp_path / "neg.brdf"
    path.write_text(BRDF_FILE)
    rc, out, _ = run(capsys, "check", str(path), "--json")
    assert rc == 1
    checks = {c["name"]: c for c in json.loads(out)["checks"]}
    assert not checks["positivity"]["ok"]
    assert checks["positivity"]["worst"] == pytest.approx(-0.05, abs=1e-12)
    assert "k=1" in checks["positivity"]["where"]
    assert not checks["reciprocity"]["ok"] and checks["finite"]["ok"]
