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

Tolerance: not bit equality, since numpy evaluates exp, log, pow, expm1 and arctan2 in SIMD
or scalar loops that differ by CPU (AVX-512 or not) and numpy version in the last bits, and the
two sides reach them through different layouts.  Each comparison has a bound from an error
analysis (see "error model" below: the roundings of every step that is not the same operation
on the same numbers on both sides, times the condition number of what follows), per point:
for the specular product ~30 ulps of the term; for G1 the propagation through expm1 (×(1 + x)),
θ's own ulps times G1's slope, and within the clamp test's rounding of its threshold the value
G1 takes there: below 3e-12 absolute over the tables, but relative to 1, not to G1 (near the
threshold 1 − Λ·expm1(x) cancels, and the specular term's relative error is large there on
any machine).  A constant 0.1% off moves a value by ~1e-3 of itself: far outside the bounds
(scripts/mutation_check.py).  Where the
kernel skips the specular term (ci·co at its floor, exp(−a) = 0) the bound is that of
(ρd + 0)/π, and below the horizon it is 0: equal to the last bit.
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


# ------------------------------------------------------------------ error model
#
# Both sides of every comparison below start from the same float64 numbers (Geometry's cosines
# and sines, the table's parameters) and differ in the order of the operations and in which
# loop evaluates a transcendental: numpy takes a SIMD loop (AVX-512, AVX2, ...) or the C
# library's scalar one depending on the CPU, the numpy version and the arrays' layout (a
# contiguous row, a broadcast column, a 0-d scalar, math.log on a Python float), and those
# differ in the last bits.  So the bounds count, for each step that is not the same operation
# on the same numbers on both sides, its rounding on each side, times the condition number of
# what follows it.  The unit roundoff EPS bounds + − × / √ (correctly rounded); TAU bounds one
# transcendental (exp, expm1, log, log1p, pow, arctan2): 4 ulps, ULP being the relative size
# of an ulp at most (numpy validates its float64 exp, expm1, log, log1p to 1 ulp,
# numpy/_core/tests/data/umath-validation-set-*.csv; pow and arctan2 come from SVML, SLEEF or
# the C library, each documented within a few ulps).  Products of two first-order terms are
# < 1e-28 relative and absorbed by the rounding up of the counts.

ULP = 2.0**-52
EPS = ULP / 2.0
TAU = 4.0 * ULP


def plain_g1(theta, lam, c_g, k, th0, dt=0.0):
    """``(G1, bound)``, one channel, as written: clamp(1 − Λ·expm1(c_g·t^k), 0, 1), t = max(0,
    θ − θ0), 0 where log c_g + k·log t ≥ log log(1 + 1/Λ) (the docstring's test).

    ``bound`` bounds |G1 − G1'| for any other evaluation G1' of the same formula from a t' with
    |t' − t| ≤ ``dt`` (0: the same t, i.e. the same θ; t = θ − θ0 is one correctly rounded
    subtraction, the same bits on both sides), each side ≤ TAU per transcendental:

    * the value, per side (a live point, exact t): x = c_g·t^k to TAU + EPS, expm1(x) to TAU
      plus x·e^x/expm1(x) ≤ 1 + x times x's error, y = Λ·expm1(x) one more rounding, and
      1 − y one more: |ΔG1| ≤ y·(2 + x)·(TAU + EPS) + EPS (y = 1 − G1 ≤ 1 where G1 > 0);
    * the shift of t by dt: |dG1/dt| = Λ·e^x·x·k/t grows with t up to the clamp's threshold
      t* and is 0 beyond, so dt times its value at min(t + dt, t*);
    * the clamp's test: D = log c_g + k·log t − log log(1 + 1/Λ) is computed to E = (TAU +
      2·EPS)·(|log c_g| + k·|log t| + |log log(1 + 1/Λ)| + 1) (each log to TAU of its value,
      the sums and k·log t rounded) plus k·dt/t from the shift; a side may decide wrongly only
      where the exact D is within E of 0, i.e. where this D is within 2E, and there its error
      is at most the value G1 takes at distance E from the threshold: G1 = (1 + Λ)·(1 −
      e^(x − x*)) ≈ (1 + Λ)·x*·|D| with x* = log(1 + 1/Λ), i.e. (1 + Λ)·x*·E (×1.01 for the
      second order); two sides.
    """
    t = np.maximum(theta - th0, 0.0)
    x_star = math.log1p(1.0 / lam)
    log_thr = math.log(x_star)
    with np.errstate(divide="ignore", over="ignore", invalid="ignore", under="ignore"):
        log_t = np.log(t)
        d = math.log(c_g) + k * log_t - log_thr
        dead = d >= 0.0
        x = np.where(dead, 0.0, c_g * t**k)
        g = np.where(dead, 0.0, np.clip(1.0 - lam * np.expm1(x), 0.0, 1.0))
        y = np.where(dead | (t == 0.0), 0.0, lam * np.expm1(x))
        value = y * (2.0 + x) * (TAU + EPS) + EPS
        # the slope at min(t + dt, t*), from logarithms (t^k overflows beyond t*)
        t_up = t + dt
        x_up = np.exp(np.minimum(math.log(c_g) + k * np.log(t_up), log_thr))
        shift = np.where(t_up > 0.0, lam * np.exp(x_up) * x_up * k / t_up * dt, 0.0)
        e = ((TAU + 2.0 * EPS) * (abs(math.log(c_g)) + k * np.abs(log_t) + abs(log_thr) + 1.0)
             + np.where(t > 0.0, k * dt / t, np.inf))
        kink = np.where((t > 0.0) & (np.abs(d) <= 2.0 * e),
                        2.02 * (1.0 + lam) * x_star * e, 0.0)
    bound = 2.0 * value + shift + kink
    return g, np.minimum(np.nan_to_num(bound, nan=1.0, posinf=1.0), 1.0)


def plain_sgd(row, wi, wo):
    """``(f, bound)``, each (..., 3): the formula, and the bound on the difference of any other
    evaluation of it from the same Geometry (a, tan²θh, c2, ci·co, cos θd: the same bits).

    What may differ: θ of each direction (arctan2 of the same numbers in another loop: TAU·θ
    each side, and t = θ − θ0 one more rounding: dt = 2·TAU·θ + 3·EPS·t); G1 of each
    (:func:`plain_g1`); exp(−a) and a^p (TAU each side: 4·TAU); (1 − cos θd)⁵ (here pow, TAU; the
    kernel's u²·u²·u, 3·EPS), and the two sums of F each side (2·EPS·(|f0| + |cd·f1| + |u⁵(1 −
    f0)|)); the specular product's ≤ 12 roundings each side (24·EPS); (ρd + s)/π, 2 roundings
    each side (4·EPS·(ρd + |s|)/π).  Each enters through its factor of the product: |ΔF|
    times |s/F|, |ΔG1(wi)| times |s/G1(wi)| (computed without dividing), and so on."""
    g = Geometry(wi, wo)
    ci, co, ch, cd = (np.broadcast_to(x, np.shape(g.above)) for x in
                      (g.cos_i, g.cos_o, g.cos_h, g.cos_d))
    s2h = np.broadcast_to(g.sin2_h, ci.shape)
    th_i = np.arctan2(np.sqrt(g.sin2_i), g.cos_i)
    th_o = np.arctan2(np.sqrt(g.sin2_o), g.cos_o)
    c2 = ch * ch
    cc = ci * co
    live = g.above & (cc > 1e-290)  # the documented floor of ci·co (SGD_MIN_COS_PRODUCT)
    f, bound = np.zeros(ci.shape + (3,)), np.zeros(ci.shape + (3,))
    for k in range(3):
        v = {n: row[n][k] for n in ("rho_d", "rho_s", "alpha", "p", "f0", "f1", "kappa",
                                    "lambda", "c_g", "k", "theta0")}
        g1 = {}
        for side, th in (("i", th_i), ("o", th_o)):
            t = np.maximum(th - v["theta0"], 0.0)
            g1[side] = plain_g1(th, v["lambda"], v["c_g"], v["k"], v["theta0"],
                                dt=2.0 * TAU * th + 3.0 * EPS * t)
        (gi, dgi), (go, dgo) = g1["i"], g1["o"]
        with np.errstate(divide="ignore", over="ignore", invalid="ignore", under="ignore"):
            tan2 = np.where(c2 > s2h / HUGE, s2h / c2, np.inf)
            a = v["alpha"] + tan2 / v["alpha"]
            d = np.where(np.exp(-a) > 0.0,
                         v["kappa"] * np.exp(-a) / (np.pi * a ** v["p"] * c2 * c2), 0.0)
            u5 = (1.0 - cd) ** 5 * (1.0 - v["f0"])
            fres = v["f0"] - cd * v["f1"] + u5
            d_fres = (TAU + 3.0 * EPS) * np.abs(u5) + 2.0 * EPS * (
                abs(v["f0"]) + np.abs(cd * v["f1"]) + np.abs(u5))
            base = np.where(live, v["rho_s"] * d / cc, 0.0)  # ρs·D/(ci co) ≥ 0
            spec = base * fres * gi * go
            d_spec = (np.abs(spec) * (4.0 * TAU + 24.0 * EPS) + base * gi * go * d_fres
                      + base * np.abs(fres) * (go * dgi + gi * dgo + dgi * dgo))
        assert np.all(np.isfinite(spec)) and np.all(np.isfinite(d_spec))
        f[..., k] = np.where(g.above, np.maximum((v["rho_d"] + spec) / np.pi, 0.0), 0.0)
        bound[..., k] = np.where(
            g.above, (d_spec + 4.0 * EPS * (v["rho_d"] + np.abs(spec))) / np.pi, 0.0)
    return f, bound


def plain_abc(row, wi, wo):
    """``(f, bound)`` of Löw et al.'s model, one channel at a time.

    The same operations as the kernel on the same numbers (Geometry's cosines, F, G/(ci co))
    except: D's base 1 + B·sin²θh/(1 + cos θh), grouped as (B·s²)/(1 + c) here and B·(s²/(1 +
    c)) in the kernel, 4 roundings each side (≤ 4·EPS relative after the + 1, as the term is
    ≥ 0); the power ^C, TAU each side and the base's error times C; the specular product's 3
    roundings each side (6·EPS); (kd + s)/π, 2 roundings each side (4·EPS·f).  All terms are
    ≥ 0."""
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
    f, bound = np.zeros(ci.shape + (3,)), np.zeros(ci.shape + (3,))
    rel = 2.0 * (TAU + 4.0 * EPS * row["c"]) + 6.0 * EPS
    for k in range(3):
        spec = row["a"][k] / (1.0 + row["b"] * s2h / (1.0 + ch)) ** row["c"] * fres * g_cc
        f[..., k] = np.where(g.above, (row["kd"][k] + spec) / np.pi, 0.0)
        bound[..., k] = np.where(g.above, (rel * spec + 4.0 * EPS * (row["kd"][k] + spec))
                                 / np.pi, 0.0)
    return f, bound


PLAIN = {"abc": plain_abc, "sgd": plain_sgd}


def assert_within(got, want, bound, what):
    """|got − want| ≤ bound elementwise (a bound of 0: equal to the last bit)."""
    err = np.abs(got - want)
    bad = err > bound
    assert not bad.any(), (what, np.flatnonzero(bad)[:3], got[bad][:3], want[bad][:3],
                           err[bad][:3], bound[bad][:3])


def check(model, name, wi, wo):
    m = MODELS[model]
    with kernel_errstate():
        got = evaluate_resolved(m, m.resolve({"material": name}), wi, wo)
        want, bound = PLAIN[model](table(model).row(name), wi, wo)
    assert got.shape == want.shape, (name, got.shape, want.shape)
    assert_within(got, want, bound, (model, name))
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
    # clamp's threshold and of θ0: the same operations on the same θ, equal up to the
    # transcendentals' last bits (plain_g1's bound; the logarithms here come from math, the
    # package's from numpy's loops), and either both sides decide the clamp or the value left
    # is within the test's rounding of the threshold
    for name in material_names():
        r = table("sgd").row(name)
        th = g1_boundaries(r)
        with kernel_errstate():
            got = sgd_g1(th, r["lambda"], r["c_g"], r["k"], r["theta0"])
        for k in range(3):
            want, bound = plain_g1(th, r["lambda"][k], r["c_g"][k], r["k"][k], r["theta0"][k])
            assert_within(got[:, k], want, bound, name)
        # the clamp: G1 ∈ [0, 1] exactly, whatever rounding leaves next to the threshold
        assert np.all((got >= 0.0) & (got <= 1.0)), name


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
    # factor, so swapping the directions gives the same bits.  Exact by construction on any
    # CPU: a and b have the same shape and layout, so G1(wi) of one call and G1(wo) of the
    # other go through the same numpy loops on the same numbers (a SIMD loop's lanes do not
    # depend on each other, and 3600 points leave no remainder for a vector of 2, 4 or 8)
    w = directions(60, 9)
    a, b = np.broadcast_arrays(w[:, None, :], w[None, :, :])
    for model in ("abc", "sgd"):
        m = MODELS[model]
        for name in ("gold-metallic-paint", "white-fabric2", "black-obsidian", "chrome"):
            v = m.resolve({"material": name})
            np.testing.assert_array_equal(evaluate_resolved(m, v, a, b),
                                          evaluate_resolved(m, v, b, a))


def test_sgd_single_light_cached_g1_gives_the_uncached_values():
    # a single wi's G1 is kept per material: a second call with the same wi, and calls with
    # other lights in between (more than the 64 kept), must give the first call's bits (the
    # same scalar operations on the same numbers, from the cache or computed again: exact by
    # construction); the same wi as a (1, 3) array computes G1 per point, through other numpy
    # loops (a row instead of a scalar), so it and the first call are each held to the plain
    # formula's bound
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
            want, bound = plain_sgd(table("sgd").row(name), incident(70.0)[None, :], wo)
        assert_within(first, want, bound, name)
        assert_within(as_array, want, bound, name)


def test_sgd_kernel_g1_equals_the_plain_g1_within_its_rounding():
    # the kernel's G1 (t clipped at t*·(1 + band), the log test only inside the band) against
    # plain_g1 (the logarithmic test on every point, as the docstring writes G1): _sgd_g1's
    # docstring promises the formula's values, so no level of the band or of the clip may move
    # a value by more than the transcendentals' rounding (plain_g1's bound: ≤ 2e-14 away from
    # the clamp's threshold, where a band or clip 0.1% off would give 1e-3·k·x* or a 0 for a
    # live value).  θ: every channel's kinks (inside and outside the band) and a grid over
    # [0, π/2]
    grid = np.linspace(0.0, np.pi / 2, 2001)
    for name in material_names():
        r = table("sgd").row(name)
        th = np.concatenate([g1_boundaries(r), grid])
        th = th[(th >= 0.0) & (th <= np.pi / 2)]
        with kernel_errstate():
            got = _sgd_g1(th, _sgd_params(name))
        for k in range(3):
            want, bound = plain_g1(th, r["lambda"][k], r["c_g"][k], r["k"][k], r["theta0"][k])
            assert_within(got[k], want, bound, name)
        assert np.all((got >= 0.0) & (got <= 1.0)), name  # the clamp, exactly


def test_sgd_g1_closed_form_with_unit_parameters():
    # Λ = c_g = k = 1: G1(θ0 + s) = 1 − (e^s − 1) = 2 − e^s for 0 < s < log 2, 0 from log 2
    # on (the clamp), 1 for s ≤ 0 (expected values from math.exp).  s = 5e-4 puts G1 visibly
    # below 1 (0.9995) close to θ0; log 2·(1 ∓ 1e-6) sits on either side of the clamp.
    # Tolerance (the error model above): θ0 + s − θ0 rounds s by ≤ 6e-17, times |dG1/ds| =
    # e^s ≤ 2 where G1 is live; x = t^1 to TAU and expm1(x) ≤ 1 to TAU plus (1 + x) ≤ 1.7
    # times x's error: 2.7·TAU = 2.4e-15 (numpy's pow and expm1 on this CPU); the expected
    # value's exp (≤ 2, an ulp of it 4.4e-16) and its subtraction: < 3e-15 in all
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
        np.testing.assert_allclose(got[:, k], want, rtol=0.0, atol=3e-15)


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
