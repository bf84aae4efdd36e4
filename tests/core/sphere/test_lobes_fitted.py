"""The albedo hints of the two fits of measured materials (``lobes._sgd_lobe``,
``lobes._abc_lobe``): where their features sit, against formulas written here, and the
grazing albedos they make take one kernel call, against the tensor Gauss-Legendre reference of
tests/core/sphere/test_albedo.py (no code shared with tuibrdf.core.sphere.integrator).
"""

import math

import numpy as np
import pytest

from tests.core.sphere.test_albedo import _half_frame_wo, reference_albedo
from tuibrdf.core.brdf.materials import material_names, table
from tuibrdf.core.directions import sincos_deg
from tuibrdf.core.registry import get_model
from tuibrdf.core.sphere import albedo as q
from tuibrdf.core.sphere import integrator, lobes
from tuibrdf.core.sphere.integrator import adaptive


def _g1(theta, t):
    """sgd's G1 per channel, as published (Bagher et al. 2012), written here:
    clamp(1 + Λ(1 − exp(c_g·max(0, θ − θ0)^k)), 0, 1)."""
    x = np.maximum(theta - t["theta0"], 0.0)
    with np.errstate(over="ignore"):
        return np.clip(1.0 + t["lambda"] * (1.0 - np.exp(t["c_g"] * x ** t["k"])), 0.0, 1.0)


def _clamp_by_bisection(t, channel):
    """θ* of one channel, where G1 first reaches 0 (bisection on the formula above), or None
    when G1 > 0 up to 90°."""
    if _g1(np.pi / 2, t)[channel] > 0.0:
        return None
    a, b = max(float(t["theta0"][channel]), 0.0), np.pi / 2
    for _ in range(200):
        m = 0.5 * (a + b)
        a, b = (m, b) if _g1(m, t)[channel] > 0.0 else (a, m)
    return 0.5 * (a + b)


def _counted(name, material, theta, rtol=q.DEFAULT_RTOL):
    """(estimate, evaluations, kernel calls) of the default rule."""
    m = get_model(name)
    return q.albedo_rule_counted(m, m.resolve({"material": material}), theta, rtol=rtol)


# ---------------------------------------------------------------------------------------------
# sgd: where the hint's features sit


@pytest.mark.parametrize("material", material_names())
def test_sgd_clamps_sit_where_g1_reaches_zero(material):
    # every G1 clamp below the horizon, by bisection on the published formula, is one of the
    # hint's clamps (to 1e-9 rad), with s·δ² from a finite-difference slope of that formula
    # (s = |G1'| just before θ*, δ = 90° − θ*); the fits put all of them next to the horizon
    t = table("sgd").row(material)
    _, _, _, clamps = lobes._sgd_shape(material)
    found = []
    for ch in range(3):
        ts = _clamp_by_bisection(t, ch)
        if ts is None or ts <= 0.0:
            continue
        found.append(ts)
        assert np.pi / 2 - ts < 3.4e-6
        near = [c for c in clamps if abs(c[0] - ts) < 1e-9]
        assert near, (material, ch)
        # G1 = 1 − Λ(exp(c_g·x^k) − 1) curves over x/k: a step far below that
        h = 1e-4 * (ts - float(t["theta0"][ch])) / float(t["k"][ch])
        slope = float(_g1(ts - 3.0 * h, t)[ch] - _g1(ts - h, t)[ch]) / (2.0 * h)
        s_expected = slope * (np.pi / 2 - ts) ** 2
        assert near[0][1] == pytest.approx(s_expected, rel=0.05)
    assert len(clamps) == len(found)


def test_sgd_clamps_are_panel_ends_only_below_their_share_of_rtol():
    # default rtol: none of the tables' clamps (s·δ² ≤ 1.4e-9 ≤ 0.01·1e-5) is a panel end; at
    # the references' rtol (1e-13) every one is, at the half-frame angle where θo = θ*
    m = get_model("sgd")
    for material in ("gold-metallic-paint", "nickel", "white-acrylic", "chrome"):
        v = m.resolve({"material": material})
        t = table("sgd").row(material)
        stars = [s for s in (_clamp_by_bisection(t, ch) for ch in range(3)) if s]
        assert stars
        theta0 = [x for x in t["theta0"] if 0.0 < x < np.pi / 2]
        for rtol, want in ((q.DEFAULT_RTOL, theta0), (1e-13, theta0 + stars)):
            hint = lobes.lobe(m, v, rtol)
            if not want:
                assert hint.breaks is None
                continue
            ti, psi = math.radians(80.0), 0.3
            rhos = [float(b[0]) for b in hint.breaks(
                np.array([math.sin(ti)]), np.array([math.cos(ti)]), np.array([math.cos(psi)]),
                np.array([np.pi / 2]))]
            thetas = sorted(math.acos(min(_half_frame_wo(80.0, psi, r)[2][2], 1.0))
                            for r in rhos if 0.0 < r < np.pi / 2)
            for w in want:  # each kink is reached at one of the breaks
                assert min(abs(x - w) for x in thetas) < 1e-9, (material, rtol, w)
            assert all(min(abs(x - w) for w in want) < 1e-9 for x in thetas)


@pytest.mark.parametrize("material", ["gold-metallic-paint", "chrome", "teflon", "white-fabric",
                                      "black-obsidian", "nickel"])
def test_sgd_scale_is_one_and_a_half_half_widths(material):
    # the core × envelope factor of D, exp(−t²/α)·(1 + t²/α²)^−p (t = tan θh), written here,
    # is half its peak at tan(scale/1.5) for the narrowest channel, and above half before
    t = table("sgd").row(material)
    scale = lobes._sgd_shape(material)[0]
    x = math.tan(scale / lobes.SGD_WIDTH)

    def factor(tt):
        return np.exp(-tt * tt / t["alpha"]) * (1.0 + (tt / t["alpha"]) ** 2) ** -np.maximum(
            t["p"], 0.0)

    assert float(np.min(factor(x))) == pytest.approx(0.5, abs=1e-9)
    assert float(np.min(factor(0.999 * x))) > 0.5


@pytest.mark.parametrize("material", material_names())
def test_sgd_envelope_end_where_the_grading_has_none(material):
    # the ring is where the narrowest envelope exp(−tan²θh/α) is e^−25, and is there exactly
    # when none of the radial grading's panel ends (scale·4^j, written here) falls where the
    # envelope is between e^−6.25 and e^−49 (tan θh/√α in [2.5, 7])
    t = table("sgd").row(material)
    scale, rings, _, _ = lobes._sgd_shape(material)
    a = float(np.min(t["alpha"]))
    ends, g = [], scale
    while g < np.pi / 2:
        ends.append(math.tan(g) / math.sqrt(a))
        g *= 4.0
    covered = any(2.5 <= e <= 7.0 for e in ends)
    assert len(rings) == (0 if covered else 1)
    for r in rings:
        assert math.exp(-math.tan(r) ** 2 / a) == pytest.approx(math.exp(-25.0), rel=1e-9)
    assert (adaptive.GRADING, adaptive.FIRST_PANEL) == (4.0, 1.0)  # the grading written out above


@pytest.mark.parametrize("theta_i,expected", [
    (60.0, None), (68.0, None), (70.0, 2.0 / math.tan(math.radians(70.0))),
    (75.0, 2.0 / math.tan(math.radians(75.0))), (78.5, 2.0 / math.tan(math.radians(78.5))),
    (80.0, None), (89.9, None), (90.0, None), (0.0, None),
])
def test_sgd_far_side_azimuth(theta_i, expected):
    # π/2 + 2 cot θi on the far side where the integrator's grading toward π/2 (from 2 cot θi while
    # that is below π/8) is empty and 2 cot θi < π/4: θi in (68.5°, 78.9°)
    ti = math.radians(theta_i)
    got = lobes._sgd_azimuths(math.sin(ti), math.cos(ti))
    if expected is None:
        assert got == []
    else:
        assert got == [pytest.approx(np.pi / 2 + expected, rel=1e-15)]


# ---------------------------------------------------------------------------------------------
# abc: where the hint's azimuths sit


@pytest.mark.parametrize("theta_i", [30.0, 60.0, 75.0, 78.0, 80.0, 84.0, 84.5, 85.0, 89.0,
                                     89.9, 90.0])
def test_abc_azimuths(theta_i):
    # the V-cavity kink curves meet where tan θi cos ψ = 1 and 1/√3 (written here); those
    # within 2 cot θi of π/2, inside the integrator's first outer grading panel, are left out at the
    # default rtol where that panel is narrower than π/16 (θi > 84.3°) and kept at 1e-13; at
    # 90° one end π/16 from π/2 instead
    st, ct = (float(x) for x in sincos_deg(theta_i))  # exact at 90° (cos θi = 0), as the rule's
    meet = [math.acos(t * ct / st) for t in (1.0, 1.0 / math.sqrt(3.0)) if t * ct / st < 1.0]
    v = get_model("abc").resolve({})
    default = sorted(lobes.lobe(get_model("abc"), v, q.DEFAULT_RTOL).azimuths(st, ct))
    exact = sorted(lobes.lobe(get_model("abc"), v, 1e-13).azimuths(st, ct))
    if theta_i == 90.0:
        assert default == exact == [pytest.approx(np.pi / 2 - np.pi / 16, rel=1e-15)]
        return
    first = 2.0 * ct / st  # polar's first grading break, from π/2
    drops = ct < 0.5 * st and first < np.pi / 16
    np.testing.assert_allclose(exact, sorted(meet), rtol=1e-14)
    keep = [a for a in meet if not (drops and np.pi / 2 - a < first)]
    np.testing.assert_allclose(default, sorted(keep), rtol=1e-14)
    assert (len(keep) < len(meet)) == (theta_i >= 84.5)


# ---------------------------------------------------------------------------------------------
# the grazing albedos: one kernel call, against the tensor rule


@pytest.mark.parametrize("theta", [75.0, 85.0, 89.0, 89.9])
def test_sgd_grazing_defaults_in_one_call_against_tensor_reference(theta):
    # 2–3 kernel calls each before this hint (scripts/bench_accuracy.py); the tensor rule written in
    # test_polar converges to 1e-12 here (two orders)
    r, n, calls = _counted("sgd", "gold-metallic-paint", theta)
    assert calls == 1
    ref = reference_albedo("sgd", {}, theta, n=24)
    assert np.max(np.abs(reference_albedo("sgd", {}, theta) - ref) / ref) < 1e-12
    value, error = r.value[0], r.error[0]
    assert np.max(np.abs(value - ref) / ref) < 1e-8
    assert np.all(np.abs(value - ref) <= error)
    assert np.all(error <= q.DEFAULT_RTOL * np.abs(value) + 1e-13)


@pytest.mark.parametrize("theta", [89.9, 90.0])
def test_abc_grazing_defaults_in_one_call_against_tensor_reference(theta):
    # 90°: two kernel calls before (an outer refinement); 89.9°: one, with 7,897 evaluations
    # (now 5,763).  The tensor rule's panels do not follow the V-cavity kinks: it converges
    # only to its two orders' difference (2e-8 at 89.9°, 3e-10 at 90°), the tolerance here
    r, n, calls = _counted("abc", "gold-metallic-paint", theta)
    assert calls == 1
    assert n < 7897
    ref = reference_albedo("abc", {}, theta, n=24)
    conv = np.max(np.abs(reference_albedo("abc", {}, theta) - ref) / ref)
    assert conv < 1e-7
    value, error = r.value[0], r.error[0]
    assert np.max(np.abs(value - ref) / ref) < 3.0 * conv + 1e-9
    assert np.all(np.abs(value - ref) <= error + 3.0 * conv * ref)


@pytest.mark.parametrize("theta", [0.0, 30.0, 60.0, 75.0])
def test_abc_unchanged_below_the_outer_grading(theta):
    # below 79° polar has no outer grading toward π/2 and abc's hint drops nothing: the albedo
    # is the one of the hint as it was (V-cavity breaks and all meeting points), to the bit
    m = get_model("abc")
    v = m.resolve({})
    b = float(table("abc").row(v["material"])["b"])
    before = lobes.Lobe("half", math.sqrt(2.0 / b), lobes._vcavity_breaks,
                    azimuths=lobes._vcavity_azimuths)
    r, r0 = q.albedo_rule(m, v, theta), q.albedo_rule(m, v, theta, hint=before)
    np.testing.assert_array_equal(r.value, r0.value)
    np.testing.assert_array_equal(r.evaluations, r0.evaluations)


@pytest.mark.parametrize("name", ["phong", "cook-torrance", "ggx", "gltf", "oren-nayar"])
def test_analytic_hints_do_not_depend_on_rtol(name):
    # only abc's and sgd's hints leave panel ends out by tolerance: the others' albedo is
    # the same with the hint made for rtol 1e-13, to the bit
    m = get_model(name)
    v = m.resolve({})
    for theta in (60.0, 89.9):
        r = q.albedo_rule(m, v, theta)
        r0 = q.albedo_rule(m, v, theta, hint=lobes.lobe(m, v, 1e-13))
        np.testing.assert_array_equal(r.value, r0.value)
        np.testing.assert_array_equal(r.evaluations, r0.evaluations)


def test_outer_k7_panels():
    # integrator.integrate(outer_k7=w): outer panels narrower than w use K7/G3.  f = 1 + x² (normal
    # frame, any θi) integrates to π + π/4 (∫ sin²θ cos²φ cos θ dω = π ∫ sin³θ cos θ dθ = π/4):
    # within the estimate, with 7 outer nodes per panel instead of 15
    def f(wi, wo):
        return 1.0 + wo[:, 0] ** 2

    c = integrator.cases(np.array([0.5]), np.array([math.sqrt(0.75)]), np.array([0.0]),
                    np.array([1.0]))
    ref = np.pi * 1.25
    runs = {w: integrator.integrate(f, "normal", c, scale=np.pi / 2, symmetric=True, outer_k7=w)
            for w in (0.0, 10.0)}
    for r in runs.values():
        assert abs(r.value[0] - ref) <= r.error[0] + 1e-15
        assert abs(r.value[0] - ref) < 1e-9 * ref
    assert runs[10.0].evaluations[0] * 15 == runs[0.0].evaluations[0] * 7


def test_outer_k7_only_for_sgd():
    # sgd's inner integral has no kink curves meeting next to ψ = π/2 (abc's V-cavity ones do:
    # K7 there cost cook-torrance and abc extra kernel calls): only sgd's hint asks for it
    for name in lobes.LOBE_HINTS:
        if name == "merl":
            continue
        m = get_model(name)
        hint = lobes.lobe(m, m.resolve({}), q.DEFAULT_RTOL)
        assert hint.outer_k7 == (lobes.SGD_OUTER_K7 if name == "sgd" else 0.0)
