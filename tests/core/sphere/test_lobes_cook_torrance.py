"""cook-torrance's far-side outer grading (``lobes._cook_torrance_far``): where its breaks
sit, against the formula written here, and the grazing albedos it makes take one kernel call,
against a tensor Gauss-Legendre reference in the half-vector frame written here, whose radial
panels end at the V-cavity kinks and the horizon located numerically (bisection on the
vector formulas; no code shared with tuibrdf.core.sphere.integrator or the hint's closed forms).
"""

import math

import numpy as np
import pytest

import tuibrdf
from tuibrdf.core.directions import from_degrees
from tuibrdf.core.registry import get_model
from tuibrdf.core.sphere import albedo as q
from tuibrdf.core.sphere import integrator, lobes

# ---------------------------------------------------------------------------------------------
# an independent reference: tensor Gauss-Legendre over the half vector (θh, φh)


def _h(th, ph):
    return np.stack(np.broadcast_arrays(np.sin(th) * np.cos(ph), np.sin(th) * np.sin(ph),
                                        np.cos(th)), -1)


def _bisect(fun, a, b, fa):
    """A root of ``fun`` in each bracket [a, b] (fun(a) = fa, a sign change inside)."""
    for _ in range(60):
        mid = 0.5 * (a + b)
        fm = fun(mid)
        left = np.sign(fm) == np.sign(fa)
        a, fa, b = np.where(left, mid, a), np.where(left, fm, fa), np.where(left, b, mid)
    return 0.5 * (a + b)


def half_frame_reference(params, theta_i, n=16, outer=48):
    """cook-torrance's albedo at θi (φi = 180°) as ∫∫ f cos θo · 4 (wi·h) sin θh dθh dφh
    (dωo = 4 (wi·h) dωh, Walter et al. 2007 eq. 14), φh ∈ [0, π] doubled (isotropic).

    Per outer node φh the radial panels end at: the horizon (first zero of cos θo = 2(wi·h)
    cos θh − cos θi), the three V-cavity kinks (where 2 cos θh cos θo/(wo·h) = 1,
    2 cos θh cos θi/(wi·h) = 1 and cos θo = cos θi: sign changes on 800 samples, then
    bisection), and m·2^k (the Beckmann lobe).  φh: ``outer`` uniform panels plus panels
    graded by 2 toward π/2 from 1e-7 (the horizon turns over there at grazing incidence).
    ``n`` Gauss-Legendre points per panel."""
    ci = math.cos(math.radians(theta_i))
    wi = from_degrees(theta_i, 180.0)
    m = float(get_model("cook-torrance").resolve(params)["m"])
    g = 1e-7 * 2.0 ** np.arange(40)
    g = g[g < np.pi / 2]
    pb = np.unique(np.clip(np.concatenate([np.linspace(0.0, np.pi, outer + 1), np.pi / 2 - g,
                                           np.pi / 2 + g]), 0.0, np.pi))
    x, w = np.polynomial.legendre.leggauss(n)
    ph = (0.5 * (pb[1:] + pb[:-1])[:, None] + 0.5 * (pb[1:] - pb[:-1])[:, None] * x).ravel()
    wph = (0.5 * (pb[1:] - pb[:-1])[:, None] * w).ravel()

    def cos_o(th, p):
        h = _h(th, p)
        return 2.0 * (h @ wi) * h[..., 2] - ci

    # the horizon: the first sign change of cos θo along each radial line (θi < 90° here)
    s = np.linspace(0.0, np.pi / 2, 2001)
    v = cos_o(s[None, :], ph[:, None])
    neg = v[:, 1:] <= 0.0
    first = np.where(neg.any(axis=1), np.argmax(neg, axis=1) + 1, len(s) - 1)
    rows = np.arange(len(ph))
    tmax = _bisect(lambda t: cos_o(t, ph), s[first - 1], s[first], v[rows, first - 1])
    tmax = np.where(neg.any(axis=1), tmax, np.pi / 2)

    def kinks(th, p):
        h = _h(th, p)
        wih = h @ wi  # > 0 inside the domain (cos θo > 0 there)
        co = 2.0 * wih * h[..., 2] - ci
        return (2.0 * h[..., 2] * co / wih - 1.0, 2.0 * h[..., 2] * ci / wih - 1.0, co - ci)

    tt = tmax[:, None] * np.linspace(0.0, 1.0, 801)[1:-1]
    lobe = m * 2.0 ** np.arange(-6, 8)
    cols = [np.zeros((len(ph), 1)), tmax[:, None], np.minimum(lobe[None, :], tmax[:, None])]
    for i, fv in enumerate(kinks(tt, ph[:, None])):
        r, c = np.nonzero(np.sign(fv[:, :-1]) * np.sign(fv[:, 1:]) < 0)
        roots = _bisect(lambda t, r=r, i=i: kinks(t, ph[r])[i], tt[r, c], tt[r, c + 1],
                        fv[r, c])
        col = np.repeat(tmax[:, None], max(np.bincount(r).max() if len(r) else 0, 1), axis=1)
        used = np.zeros(len(ph), dtype=int)
        for ri, val in zip(r, roots, strict=True):
            col[ri, used[ri]] = val
            used[ri] += 1
        cols.append(col)
    br = np.sort(np.concatenate(cols, axis=1), axis=1)  # padded with tmax: empty panels
    lo, hi = br[:, :-1], br[:, 1:]
    th = 0.5 * (lo + hi)[..., None] + 0.5 * (hi - lo)[..., None] * x
    wt = 0.5 * (hi - lo)[..., None] * w
    total = 0.0
    for s0 in range(0, len(ph), 256):
        sl = slice(s0, s0 + 256)
        h = _h(th[sl], ph[sl, None, None])
        wih = h @ wi
        wo = 2.0 * wih[..., None] * h - wi
        co = wo[..., 2]
        f = np.asarray(tuibrdf.evaluate("cook-torrance", params, np.broadcast_to(wi, wo.shape),
                                        wo))
        total += np.sum(wph[sl, None, None] * wt[sl] * f * co * 4.0 * wih * np.sin(th[sl]))
    return 2.0 * total


# ---------------------------------------------------------------------------------------------
# where the breaks sit


def _expected_far(theta_i, m):
    """The far-side breaks ψ − π/2 by the rule, written out: none unless the horizon at ψ = π,
    (π/2 − θi)/2 from the normal (half frame), is within m; else polar's own far grading
    (2 cot θi × 8^j below π/8) continued to π/2 in pieces of ratio ≤ 8, evenly in log, or,
    where the integrator has none, 2 cot θi itself."""
    t = math.radians(theta_i)
    if (np.pi / 2 - t) / 2 >= m or theta_i == 0.0 or 2.0 / math.tan(t) >= np.pi / 2:
        return []
    w = 2.0 / math.tan(t)
    if math.cos(t) < 0.5 * math.sin(t) and w < np.pi / 8:
        while 8.0 * w < np.pi / 8:
            w *= 8.0
        out = []
    else:
        out = [w]
    k = 1
    while (np.pi / 2 / w) ** (1.0 / k) > 8.0:
        k += 1
    return out + [w * (np.pi / 2 / w) ** (j / k) for j in range(1, k)]


@pytest.mark.parametrize("theta,m,count", [
    (75.0, 0.2, 1),  # ρmax(π) = 7.5° = 0.13 rad < m; polar has no grading: 2 cot 75° only
    (85.0, 0.2, 1),  # polar's 2 cot 85° = 0.175, π/2 is 9.0 times it: one break between
    (88.5, 0.2, 1),  # polar's 0.052, π/2 is 30 times it: one break, √30 times it
    (70.0, 0.2, 1),
    (60.0, 0.2, 0),  # ρmax(π) = 15° = 0.26 rad > m: the horizon does not cut the lobe
    (80.0, 0.2, 0),  # polar's 0.353, π/2 is 4.5 times it
    (89.0, 0.2, 0),  # polar's 0.035 and 0.279: π/2 is 5.6 times the last
    (89.9, 0.2, 0),  # polar's last 0.223: 7.0 times
    (70.0, 0.1, 0),  # ρmax(π) = 0.17 > m
    (85.0, 0.05, 1),
    (89.5, 0.01, 1),  # polar's last 0.140, 11 times; ρmax(π) = 0.0044 < m
    (89.0, 0.01, 0),
    (89.9, 0.001, 0),
    (0.0, 1.0, 0),  # normal incidence: no far side
    (30.0, 1.0, 0),  # 2 cot 30° = 3.5 > π/2
])
def test_far_breaks_where_the_formula_says(theta, m, count):
    st, ct = math.sin(math.radians(theta)), math.cos(math.radians(theta))
    got = lobes._cook_torrance_far(st, ct, m)
    want = _expected_far(theta, m)
    assert len(got) == len(want) == count
    np.testing.assert_allclose(got, want, rtol=1e-12)
    # together with polar's own grading no far panel is wider than 8 times its start
    if count:
        ends = sorted(got + [2.0 * ct / st * 8.0**j for j in range(4)
                             if ct < 0.5 * st and 2.0 * ct / st * 8.0**j < np.pi / 8])
        ends = [e for e in ends if e < np.pi / 2] + [np.pi / 2]
        assert all(b / a <= 8.0 + 1e-9 for a, b in zip(ends[:-1], ends[1:], strict=False))
    # in the hint: the far side only, with the V-cavity azimuths from m = 0.3 on
    model = get_model("cook-torrance")
    hint = lobes.lobe(model, model.resolve({"m": m}), q.DEFAULT_RTOL)
    near = lobes._vcavity_azimuths(st, ct) if m >= 0.3 else []
    assert hint.azimuths(st, ct) == pytest.approx(near + [np.pi / 2 + w for w in want])


# ---------------------------------------------------------------------------------------------
# the albedo


def _counted(params, theta, far=True):
    """(result, evaluations, kernel calls) of the default rule, optionally without the far
    breaks (the hint's azimuths as before them: the V-cavity ones from m = 0.3, else none)."""
    model = get_model("cook-torrance")
    v = model.resolve(params)
    hint = lobes.lobe(model, v, q.DEFAULT_RTOL)
    if not far:
        hint = hint._replace(azimuths=lobes._vcavity_azimuths if v["m"] >= 0.3 else None)
    return q.albedo_rule_counted(model, v, theta, hint=hint)


@pytest.mark.parametrize("theta", [75.0, 85.0])
def test_defaults_at_75_and_85_in_one_call_against_half_frame_reference(theta):
    r, n, calls = _counted({}, theta)
    assert calls == 1
    _, n0, calls0 = _counted({}, theta, far=False)
    assert calls0 == 2 and n < n0  # without the far breaks: a second call, more evaluations
    ref = half_frame_reference({}, theta)
    conv = abs(half_frame_reference({}, theta, n=12, outer=32) - ref) / ref
    assert conv < 1e-13  # its panels follow every kink: converged
    value, error = float(r.value[0]), float(r.error[0])
    assert abs(value - ref) / ref < 1e-8  # measured 5.8e-10 (75°), 8.9e-10 (85°)
    assert abs(value - ref) <= error  # the estimate covers the error
    assert error <= q.DEFAULT_RTOL * abs(value)


@pytest.mark.parametrize("params,theta", [
    ({}, 0.0), ({}, 30.0), ({}, 60.0), ({}, 80.0), ({}, 89.0), ({}, 89.9), ({}, 90.0),
    ({"m": 0.01}, 85.0), ({"m": 0.01}, 89.0), ({"m": 0.01}, 89.9),
    ({"kd": 0.0, "f0": 1.0, "m": 0.001}, 89.9),
])
def test_far_breaks_are_targeted(params, theta):
    # where the horizon does not cut the lobe, or polar's own grading already has no far
    # panel wider than 8 times its start, the layout, counts and value are those without
    r, n, calls = _counted(params, theta)
    r0, n0, calls0 = _counted(params, theta, far=False)
    assert (n, calls) == (n0, calls0)
    np.testing.assert_array_equal(r.value, r0.value)


def test_polar_grading_constants_the_rule_assumes():
    # the formula above restates polar's far grading: from 2 cot θi by 8 below π/8
    assert (integrator.OUTER_START, integrator.OUTER_GRADING, integrator.OUTER_LIMIT) == (
        2.0, 8.0, np.pi / 8)
