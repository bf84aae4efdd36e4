"""The fast ABC and SGD kernels against a plain evaluation of their formulas (issue 16).

The kernels compute the three channels as rows of ``(3, M)`` arrays, reorder the specular
product, skip the points where the specular term is 0, and decide SGD's G1 clamp with a
threshold computed once per material instead of a logarithm per point.  The reference here is
the formula as the module docstring writes it, one channel at a time, in the plainest numpy:
each factor computed on every point, masks for the guards, G1's clamp decided by the
logarithmic test on every point.  It takes the angular quantities from
:class:`~tuibrdf.core.directions.Geometry` (tested on its own in tests/core/views/test_frame.py and
tests/core/brdf/test_kernel_paths.py; tests/core/brdf/test_materials.py compares the kernels with
a scalar
evaluation that shares nothing with the package), so that both sides start from the same
numbers and differ only by the order of the operations.

Tolerance: the specular product is reordered (≤ 6 roundings either way) and a few factors are
grouped differently here (abc's D base as B·sin²/(1 + cos) against B·(sin²/(1 + cos)), whose
rounding C ≤ 2.7 amplifies; the Fresnel factor's squares), so each channel may differ by a
few ulps of the terms it adds: ``16ε·(ρd + |specular|)/π`` (ε = 2⁻⁵³; observed ≤ 8.6ε over
these cases).  Where the kernel skips the specular term (ci·co at its floor, exp(−a) = 0) and
below the horizon the values must be equal to the last bit.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from tuibrdf.core.brdf.fitted import _sgd_g1, _sgd_params, fresnel_dielectric, sgd_g1
from tuibrdf.core.brdf.materials import material_names, table
from tuibrdf.core.directions import Geometry, from_degrees, incident
from tuibrdf.core.evaluate import evaluate_resolved
from tuibrdf.core.numerics import kernel_errstate
from tuibrdf.core.registry import MODELS

EPS = 2.0**-53
HUGE = 1e300


def unit(v):
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def directions(n: int, seed: int) -> np.ndarray:
    """Random directions of the upper hemisphere and of the whole sphere, plus the normal, the
    horizon (exactly, 1e-9 above it, a subnormal z), grazing ones and one below."""
    rng = np.random.default_rng(seed)
    up = rng.normal(size=(n, 3))
    up[:, 2] = np.abs(up[:, 2])
    anywhere = rng.normal(size=(n // 4, 3))
    special = [[0, 0, 1], [1, 0, 0], [-1, 0, 0], [0.6, 0.8, 0], [1, 0, 1e-9], [-1, 0, 1e-9],
               [1, 0, 1e-310], [0, 0, -1], [0.3, -0.2, -1e-9]]
    grazing = from_degrees(np.array([89.0, 89.9, 89.99, 89.999]), np.array([0, 30, 180, 250]))
    return np.concatenate([unit(special), grazing, unit(up), unit(anywhere)])


def theta_dirs(theta: np.ndarray, phi_deg: float = 0.0) -> np.ndarray:
    """Directions at polar angles ``theta`` (radians) in [0, π/2]."""
    theta = np.asarray(theta, dtype=float)
    theta = theta[(theta >= 0.0) & (theta <= np.pi / 2)]
    p = math.radians(phi_deg)
    return np.stack([np.sin(theta) * math.cos(p), np.sin(theta) * math.sin(p), np.cos(theta)],
                    axis=-1)


def g1_boundaries(row) -> np.ndarray:
    """Polar angles at G1's kinks, per channel: θ0 (G1 leaves 1) and θ0 + t* (the clamp reaches
    0, t* = (log(1 + 1/Λ)/c_g)^(1/k), from the docstring's x = c_g t^k = log(1 + 1/Λ)),
    each exactly and moved by relative steps around it (inside and outside 1e-9)."""
    out = []
    for ch in range(3):
        lam, c_g, k, th0 = (row[f][ch] for f in ("lambda", "c_g", "k", "theta0"))
        t_star = math.exp((math.log(math.log1p(1.0 / lam)) - math.log(c_g)) / k)
        out += [th0, np.nextafter(th0, 1.0), np.nextafter(th0, -1.0)]
        for r in (0.0, 1e-12, -1e-12, 5e-10, -5e-10, 1e-9, -1e-9, 2e-9, -2e-9, 1e-6, -1e-6):
            out.append(th0 + t_star * (1.0 + r))
    return np.array(out)


# ------------------------------------------------------------------ plain references


def plain_g1(theta, lam, c_g, k, th0):
    """G1 as written, one channel: clamp(1 − Λ·expm1(c_g·t^k), 0, 1), t = max(0, θ − θ0), 0
    where log c_g + k·log t ≥ log log(1 + 1/Λ) (the docstring's test)."""
    t = np.maximum(theta - th0, 0.0)
    with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
        dead = math.log(c_g) + k * np.log(t) >= math.log(math.log1p(1.0 / lam))
        x = np.where(dead, 0.0, c_g * t**k)
        g = np.clip(1.0 - lam * np.expm1(x), 0.0, 1.0)
    return np.where(dead, 0.0, g)


def plain_sgd(row, wi, wo):
    """``(f, scale)``, each (..., 3): the formula and its terms' size (ρd + |specular|)/π."""
    g = Geometry(wi, wo)
    ci, co, ch, cd = (np.broadcast_to(x, np.shape(g.above)) for x in
                      (g.cos_i, g.cos_o, g.cos_h, g.cos_d))
    s2h = np.broadcast_to(g.sin2_h, ci.shape)
    th_i = np.arctan2(np.sqrt(g.sin2_i), g.cos_i)
    th_o = np.arctan2(np.sqrt(g.sin2_o), g.cos_o)
    c2 = ch * ch
    cc = ci * co
    live = g.above & (cc > 1e-290)  # the documented floor of ci·co (SGD_MIN_COS_PRODUCT)
    f, scale = np.zeros(ci.shape + (3,)), np.zeros(ci.shape + (3,))
    for k in range(3):
        v = {n: row[n][k] for n in ("rho_d", "rho_s", "alpha", "p", "f0", "f1", "kappa",
                                    "lambda", "c_g", "k", "theta0")}
        with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
            tan2 = np.where(c2 > s2h / HUGE, s2h / c2, np.inf)
            a = v["alpha"] + tan2 / v["alpha"]
            d = np.where(np.exp(-a) > 0.0,
                         v["kappa"] * np.exp(-a) / (np.pi * a ** v["p"] * c2 * c2), 0.0)
            fres = v["f0"] - cd * v["f1"] + (1.0 - cd) ** 5 * (1.0 - v["f0"])
            g11 = (plain_g1(th_i, v["lambda"], v["c_g"], v["k"], v["theta0"])
                   * plain_g1(th_o, v["lambda"], v["c_g"], v["k"], v["theta0"]))
            spec = np.where(live, v["rho_s"] * fres * d * g11 / cc, 0.0)
        assert np.all(np.isfinite(spec))
        f[..., k] = np.where(g.above, np.maximum((v["rho_d"] + spec) / np.pi, 0.0), 0.0)
        scale[..., k] = np.where(g.above, (v["rho_d"] + np.abs(spec)) / np.pi, 0.0)
    return f, scale


def plain_abc(row, wi, wo):
    """``(f, scale)`` of Löw et al.'s model, one channel at a time (all terms ≥ 0: scale = f)."""
    g = Geometry(wi, wo)
    ci, co, ch, cd = (np.broadcast_to(x, np.shape(g.above)) for x in
                      (g.cos_i, g.cos_o, g.cos_h, g.cos_d))
    s2h = np.broadcast_to(g.sin2_h, ci.shape)
    eta = row["eta"]
    gg = np.sqrt(eta * eta - 1.0 + cd * cd)
    fres = (0.5 * (gg - cd) ** 2 / (gg + cd) ** 2
            * (1.0 + (cd * (gg + cd) - 1.0) ** 2 / (cd * (gg - cd) + 1.0) ** 2))
    with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
        # G/(ci co) = min(1/(ci co), 2ch/(cd co), 2ch/(cd ci)): its limit where one cosine is
        # 0 (the infinite terms drop out of the min), 0 where all three are infinite
        g_cc = np.minimum(1.0 / (ci * co), 2.0 * ch / (cd * np.maximum(ci, co)))
        g_cc = np.where(np.isfinite(g_cc) & (g_cc < HUGE), g_cc, 0.0)
    f = np.zeros(ci.shape + (3,))
    for k in range(3):
        d = row["a"][k] / (1.0 + row["b"] * s2h / (1.0 + ch)) ** row["c"]
        f[..., k] = np.where(g.above, (row["kd"][k] + d * fres * g_cc) / np.pi, 0.0)
    return f, f


PLAIN = {"abc": plain_abc, "sgd": plain_sgd}


def check(model, name, wi, wo):
    m = MODELS[model]
    with kernel_errstate():
        got = evaluate_resolved(m, m.resolve({"material": name}), wi, wo)
        want, scale = PLAIN[model](table(model).row(name), wi, wo)
    assert got.shape == want.shape, (name, got.shape, want.shape)
    err = np.abs(got - want)
    bound = 16.0 * EPS * scale
    bad = err > bound
    assert not bad.any(), (model, name, got[bad][:3], want[bad][:3], (err / scale)[bad][:3])
    return got


# ------------------------------------------------------------------ tests


@pytest.mark.parametrize("model", ["abc", "sgd"])
def test_every_material_equals_the_plain_formula(model):
    wo = directions(300, 16)
    for name in material_names():
        extra = theta_dirs(g1_boundaries(table("sgd").row(name)), 30.0) if model == "sgd" \
            else np.zeros((0, 3))
        w = np.concatenate([wo, extra])
        for theta_i in (0.0, 30.0, 75.0, 89.9, 90.0):
            check(model, name, incident(theta_i), w)  # one wi, many wo: the albedo's calls
        check(model, name, w[:40], w[40:80])  # pairs: both arrays
        check(model, name, w[:5, None, :], w[None, :7, :])  # broadcast axes
        check(model, name, incident(35.0), incident(20.0, 10.0))  # a single pair


def test_sgd_at_the_g1_kinks_equals_the_plain_formula():
    # both directions at the kinks of every channel (θ0, and the clamp's threshold with
    # neighbours inside and outside the band where the kernel takes the logarithmic test)
    hit = 0
    for name in material_names():
        th = g1_boundaries(table("sgd").row(name))
        w = theta_dirs(th, 0.0)
        hit += len(w)
        check("sgd", name, w[:, None, :], theta_dirs(th, 120.0)[None, :, :])
    assert hit > 1000  # the kinks lie in [0°, 90°] for many materials


def test_sgd_g1_matches_the_plain_clamp_at_its_threshold():
    # the public sgd_g1 (the formula as written) against plain_g1 on θ within 1e-6 of the
    # clamp's threshold and of θ0: the same operations, equal values
    for name in material_names():
        r = table("sgd").row(name)
        th = g1_boundaries(r)
        with kernel_errstate():
            got = sgd_g1(th, r["lambda"], r["c_g"], r["k"], r["theta0"])
        for k in range(3):
            want = plain_g1(th, r["lambda"][k], r["c_g"][k], r["k"][k], r["theta0"][k])
            np.testing.assert_array_equal(got[:, k], want, name)


def test_sgd_specular_is_skipped_only_where_it_is_zero():
    # θi = 90°: ci·co = 0 everywhere, the value is ρd/π at every wo above the horizon, exactly;
    # a sharp material (chrome, α ~ 1e-4) at 40°: most wo have exp(−a) = 0 in every channel
    m = MODELS["sgd"]
    wo = directions(200, 3)
    above = wo[:, 2] >= 0.0
    for name in ("gold-metallic-paint", "chrome", "black-obsidian"):
        r = table("sgd").row(name)
        f = evaluate_resolved(m, m.resolve({"material": name}), incident(90.0), wo)
        want = np.broadcast_to(r["rho_d"] / np.pi, (above.sum(), 3))
        np.testing.assert_array_equal(f[above], want)
        np.testing.assert_array_equal(f[~above], 0.0)
        check("sgd", name, incident(40.0), wo)


def test_both_kernels_stay_reciprocal_to_the_last_bit():
    # every factor is symmetric in (wi, wo); the reordered product keeps G1(wi)·G1(wo) as one
    # factor, so swapping the directions gives the same bits
    w = directions(60, 9)
    a, b = np.broadcast_arrays(w[:, None, :], w[None, :, :])
    for model in ("abc", "sgd"):
        m = MODELS[model]
        for name in ("gold-metallic-paint", "white-fabric2", "black-obsidian", "chrome"):
            v = m.resolve({"material": name})
            np.testing.assert_array_equal(evaluate_resolved(m, v, a, b),
                                          evaluate_resolved(m, v, b, a))


def test_sgd_single_light_cached_g1_gives_the_uncached_values():
    # a single wi's G1 is kept per material: a second call with the same wi, calls with other
    # lights in between (more than the 64 kept), and the same wi as a (1, 3) array (G1
    # computed per point, not cached) must all give the first call's bits
    m = MODELS["sgd"]
    wo = directions(100, 4)
    for name in ("gold-metallic-paint", "alum-bronze", "black-obsidian"):
        v = m.resolve({"material": name})
        with kernel_errstate():
            first = m.kernel(incident(70.0), wo, **m.kernel_params(v))
        for theta in np.linspace(0.0, 90.0, 70):
            evaluate_resolved(m, v, incident(theta), wo)
            np.testing.assert_array_equal(evaluate_resolved(m, v, incident(70.0), wo), first)
        with kernel_errstate():
            as_array = m.kernel(incident(70.0)[None, :], wo, **m.kernel_params(v))
        np.testing.assert_array_equal(as_array, first)


def test_sgd_kernel_g1_equals_the_plain_g1_to_the_bit():
    # the kernel's G1 (t clipped at t*·(1 + band), the log test only inside the band) against
    # plain_g1 (the logarithmic test on every point, as the docstring writes G1): _sgd_g1's
    # docstring promises the same values, so no level of the band or of the clip may change
    # one bit.  θ: every channel's kinks (inside and outside the band) and a grid over [0, π/2]
    grid = np.linspace(0.0, np.pi / 2, 2001)
    for name in material_names():
        r = table("sgd").row(name)
        th = np.concatenate([g1_boundaries(r), grid])
        th = th[(th >= 0.0) & (th <= np.pi / 2)]
        with kernel_errstate():
            got = _sgd_g1(th, _sgd_params(name))
        for k in range(3):
            want = plain_g1(th, r["lambda"][k], r["c_g"][k], r["k"][k], r["theta0"][k])
            np.testing.assert_array_equal(got[k], want, name)


def test_sgd_g1_closed_form_with_unit_parameters():
    # Λ = c_g = k = 1: G1(θ0 + s) = 1 − (e^s − 1) = 2 − e^s for 0 < s < log 2, 0 from log 2
    # on (the clamp), 1 for s ≤ 0 (expected values from math.exp).  s = 5e-4 puts G1 visibly
    # below 1 (0.9995) close to θ0; log 2·(1 ∓ 1e-6) sits on either side of the clamp.
    # Tolerance: θ0 + s − θ0 rounds s by ≤ 6e-17, and |dG1/ds| = e^s ≤ 2.7
    th0 = 0.25
    s = np.array([-0.1, 0.0, 5e-4, 0.3, math.log(2.0) * (1.0 - 1e-6),
                  math.log(2.0) * (1.0 + 1e-6), 1.0])
    want = [1.0, 1.0, 2.0 - math.exp(5e-4), 2.0 - math.exp(0.3),
            2.0 - math.exp(math.log(2.0) * (1.0 - 1e-6)), 0.0, 0.0]
    one = np.ones(3)
    with kernel_errstate():
        got = sgd_g1(th0 + s, one, one, one, np.full(3, th0))
    assert got.shape == (len(s), 3)
    for k in range(3):
        np.testing.assert_allclose(got[:, k], want, rtol=0.0, atol=1e-15)


@pytest.mark.parametrize("eta", [1.5, 0.8])
def test_fresnel_dielectric_clips_cosines_outside_0_1(eta):
    # the public function clips cos θd to [0, 1] (a caller's rounding): F(−ε) = F(0) = 1
    # (c = 0: (g − c)²/(g + c)² = 1 and (c(g + c) − 1)²/(c(g − c) + 1)² = 1, F = ½·1·2; for
    # η < 1 total reflection, F = 1) and F(1 + ε) = F(1) = ((η − 1)/(η + 1))² (normal
    # incidence, the textbook closed form)
    with kernel_errstate():
        low = fresnel_dielectric(np.array([-5e-4, -1e-9, 0.0]), eta)
        high = fresnel_dielectric(np.array([1.0 + 5e-4, 1.0 + 1e-9, 1.0]), eta)
    np.testing.assert_allclose(low, 1.0, rtol=4 * EPS, atol=0.0)
    np.testing.assert_allclose(high, ((eta - 1.0) / (eta + 1.0)) ** 2, rtol=8 * EPS, atol=0.0)
