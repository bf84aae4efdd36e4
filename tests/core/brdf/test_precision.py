"""The formulas' last digits where they cancel, against 60-digit references (tests/hiprec.py).

Each reference is the model's published formula evaluated in 60-digit decimals at exactly the
float64 directions the kernel sees (``as_directions``: the directions are normalised once, an
ulp from unit), those directions taken as the unit vectors they stand for (normalised in 60
digits).  Bounds: 1e-13 relative, or where a formula is ill-conditioned in its inputs (a lobe
far down its tail: ``c^n`` with a large exponent n(1 − c)), a few ulp times that condition
number, which the inputs' own rounding (an ulp) already moves it by.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import tuibrdf
from tests import hiprec
from tests.core.brdf.test_reference_values import (
    cook_torrance_ref,
    direction,
    ggx_ref,
    oren_nayar_decimal,
)
from tuibrdf.core.brdf.fresnel import fresnel_exact
from tuibrdf.core.evaluate import as_directions

D = hiprec.D
EPS = 2.0**-52


def rel_err(got, want) -> float:
    with hiprec.precise():
        return float(abs((D(got) - want) / want))


def value(model, params, wi, wo) -> float:
    return float(tuibrdf.evaluate(model, params, np.array(wi), np.array(wo)))


# ---------------------------------------------------------------- Oren-Nayar at the horizon


def test_oren_nayar_back_scatter_at_the_horizon_issue_case():
    """Issue 37's example: C2 = B (sin α − (2β/π)³) cancels as α, β → 90° and tan β ≈ 1e9
    multiplies the cancellation back (it was 1.6e-6 off)."""
    wi, wo = (1.0, 0.0, 1.000000143972711e-9), (-1.0, 0.0, 1.3000001687948222e-9)
    want = oren_nayar_decimal(0.8, math.radians(70.0), wi, wo)
    assert str(want).startswith("0.007683812295807")
    for a, b in ((wi, wo), (wo, wi)):
        assert rel_err(value("oren-nayar", {"kd": 0.8, "sigma": 70.0}, a, b), want) < 1e-13


def _grazing(eps: float, phi_deg: float) -> list[float]:
    p = math.radians(phi_deg)
    w = np.array([math.cos(eps) * math.cos(p), math.cos(eps) * math.sin(p), math.sin(eps)])
    return as_directions(w, "w").tolist()


def test_oren_nayar_seeded_sweep_near_the_horizon():
    """Both directions 1e-12…1e-3 rad above the horizon, Δφ near 180° (back-scatter, the
    cancelling branch) and random elsewhere, random kd and σ: within 1e-13 of 60 digits
    wherever the value is not clamped (the reference leaves out the clamp at 0)."""
    rng = np.random.default_rng(37)
    checked = 0
    for k in range(60):
        e1 = 10.0 ** rng.uniform(-12, -3)
        e2 = e1 * rng.uniform(1.0, 2.0) if k % 2 else 10.0 ** rng.uniform(-12, -3)
        p1 = rng.uniform(0, 360)
        p2 = p1 + 180.0 + (rng.normal(0, 1e-3) if k % 3 else rng.uniform(-90, 90))
        kd, sigma = rng.uniform(0.05, 1.0), rng.uniform(5.0, 90.0)
        wi, wo = _grazing(e1, p1), _grazing(e2, p2)
        want = oren_nayar_decimal(kd, math.radians(sigma), wi, wo)
        if want <= 0:
            continue
        checked += 1
        got = value("oren-nayar", {"kd": kd, "sigma": sigma}, wi, wo)
        bound = max(1e-13, 2.0 * ulp_sensitivity(
            lambda a, b, kd=kd, sigma=sigma: oren_nayar_decimal(kd, math.radians(sigma), a, b),
            wi, wo, want))
        assert rel_err(got, want) < bound, (kd, sigma, wi, wo, got, str(want))
    assert checked > 40


def ulp_sensitivity(ref, wi, wo, want) -> float:
    """How far the reference moves, relatively, when one horizontal component of a direction
    moves by an ulp: what the inputs' own rounding explains.  With Δφ within 1e-5 rad of 180°
    an ulp turns Δφ by 1e-16 rad, so 1 − |cos Δφ| ≈ Δφ²/2 moves by 1e-11 relative, and
    tan((α + β)/2) ≈ 1/ε carries that into the value."""
    worst = 0.0
    for k in range(4):
        a, b = list(wi), list(wo)
        w = a if k < 2 else b
        w[k % 2] = float(np.nextafter(w[k % 2], 2.0))
        worst = max(worst, rel_err(ref(a, b), want))
    return worst


# ---------------------------------------------------------------- exact Fresnel at tiny f0


def fresnel_decimal(c: float, f0: float):
    """Snell's law in 60 digits (Born & Wolf §1.5): n = (1 + √f0)/(1 − √f0), sin θt = sinψ/n,
    rs = (cos ψ − n cos θt)/(cos ψ + n cos θt), rp = (n cos ψ − cos θt)/(n cos ψ + cos θt)."""
    with hiprec.precise():
        r = hiprec.sqrt(D(f0))
        n = (1 + r) / (1 - r)
        c = D(c)
        st = hiprec.sqrt(1 - c * c) / n
        ct = hiprec.sqrt(1 - st * st)
        rs = (c - n * ct) / (c + n * ct)
        rp = (n * c - ct) / (n * c + ct)
        return (rs * rs + rp * rp) / 2


@pytest.mark.parametrize("f0", [1e-30, 1e-20, 1e-12, 1e-8, 1e-4, 0.04, 0.5, 0.999,
                                1.0 - 1e-12])
def test_fresnel_exact_against_60_digits(f0):
    """rs and rp no longer cancel as n → 1 (they were ~1/(4√f0) ulp off: 6e-11 at f0 = 1e-12),
    nor the index as n → ∞ (1 − √f0 lost the root's digits: 5.5e-8 at f0 = 1 − 1e-12)."""
    rng = np.random.default_rng(int(-math.log10(f0 if f0 < 0.5 else 1.0 - f0 + 1e-300)))
    for c in [*rng.uniform(0.0, 1.0, 25), 0.0, 1.0, 1e-9, 0.7071067811865476]:
        got = float(fresnel_exact(np.array(c), f0))
        assert rel_err(got, fresnel_decimal(c, f0)) < 1e-14, (c, f0)


@pytest.mark.parametrize("model, ref, rough", [("cook-torrance", cook_torrance_ref, "m"),
                                               ("ggx", ggx_ref, "alpha")])
def test_microfacet_models_at_tiny_f0(model, ref, rough):
    """The models' value with f0 = 1e-12: the float reference of test_reference_values with its
    Fresnel factor from Snell's law in 60 digits (the rest is well conditioned: 1e-12)."""
    wi, wo = direction(37.0, 203.0), direction(41.0, 17.0)
    params = {"kd": 0.0, "f0": 1e-12, rough: 0.3, "fresnel": "exact"}
    got = value(model, params, wi, wo)
    base = ref(0.0, 0.5, 0.3, "schlick", wi, wo)  # F D G/(4 cos cos) with Schlick's F
    h = np.add(wi, wo) / np.linalg.norm(np.add(wi, wo))
    cpsi = float(np.dot(h, wi))
    f_schlick = 0.5 + 0.5 * (1.0 - cpsi) ** 5
    want = base / f_schlick * float(fresnel_decimal(cpsi, 1e-12))
    assert got == pytest.approx(want, rel=1e-12, abs=0.0)


# ---------------------------------------------------------------- Phong lobes at n ≈ 10⁴


def lobe_decimal(model: str, n: float, wi, wo):
    """(Modified Phong's max(0, S·wo)ⁿ or Blinn-Phong's max(0, N·H)ⁿ, the exponent n(1 − c))
    in 60 digits, the directions normalised."""
    with hiprec.precise():
        wi, wo = [D(x) for x in wi], [D(x) for x in wo]
        li, lo = hiprec.sqrt(sum(x * x for x in wi)), hiprec.sqrt(sum(x * x for x in wo))
        wi, wo = [x / li for x in wi], [x / lo for x in wo]
        if model == "phong":
            c = -wi[0] * wo[0] - wi[1] * wo[1] + wi[2] * wo[2]
        else:
            h = [a + b for a, b in zip(wi, wo, strict=True)]
            c = h[2] / hiprec.sqrt(sum(x * x for x in h))
        return (c ** D(n) if c > 0 else D(0)), float(D(n) * (1 - c))


def lobe_raw_decimal(model: str, n: float, wi, wo):
    """The same lobe at the float directions as they are (an ulp from unit, not normalised):
    the difference is what the inputs' own rounding explains."""
    with hiprec.precise():
        wi, wo = [D(x) for x in wi], [D(x) for x in wo]
        if model == "phong":
            c = -wi[0] * wo[0] - wi[1] * wo[1] + wi[2] * wo[2]
        else:
            h = [a + b for a, b in zip(wi, wo, strict=True)]
            c = h[2] / hiprec.sqrt(sum(x * x for x in h))
        return c ** D(n) if c > 0 else D(0)


@pytest.mark.parametrize("model", ["phong", "blinn-phong"])
@pytest.mark.parametrize("n", [10000.0, 9999.5, 2500.0, 200.0])
def test_sharp_lobes_against_60_digits(model, n):
    """ks = 1, kd = 0 at random directions in and around the lobe (θi up to 89.99°): the lobe
    to 1e-13 relative, or 8 ulp per unit of the exponent n(1 − c) far down its tail, where
    exp(n log c) is that ill-conditioned in the inputs, or twice what the directions' own
    rounding to unit explains (near the horizon wi + wo has small horizontal parts that an ulp
    of the length moves relatively much): it was n ulp, 2e-12 at n = 10⁴."""
    rng = np.random.default_rng(int(n))
    norm = (n + 2.0) / (2.0 * math.pi) if model == "phong" else (n + 8.0) / (8.0 * math.pi)
    checked = 0
    for _ in range(40):
        t, p = rng.uniform(0.0, 89.99), rng.uniform(0.0, 360.0)
        wi = np.array(direction(t, p))
        wo = np.array([-wi[0], -wi[1], wi[2]]) + rng.normal(0.0, 1.5 / math.sqrt(n), 3)
        if wo[2] <= 0.0:
            continue
        wi, wo = as_directions(wi, "wi").tolist(), as_directions(wo, "wo").tolist()
        lobe, expo = lobe_decimal(model, n, wi, wo)
        if lobe < D("1e-290"):
            continue
        checked += 1
        got = value(model, {"kd": 0.0, "ks": 1.0, "n": n}, wi, wo) / norm
        bound = max(1e-13, 8.0 * EPS * (1.0 + expo),
                    2.0 * rel_err(lobe_raw_decimal(model, n, wi, wo), lobe))
        assert rel_err(got, lobe) < bound, (wi, wo, got, str(lobe), expo)
    assert checked > 20


@pytest.mark.parametrize("t_i, t_o, dphi", [(8.0, 6.0, 170.0), (8.0, 6.0, 12.0),
                                            (40.0, 65.0, 178.0), (40.0, 65.0, 3.0),
                                            (40.0, 65.0, 120.0), (3.0, 2.5, 186.0)])
def test_oren_nayar_one_minus_cos_dphi_near_0_and_180(t_i, t_o, dphi):
    """1 − |cos Δφ| (C3's factor) from the cross product where |cos Δφ| > 1/2, near the normal
    too (both directions within 8°: products of small horizontal parts): 1e-13 of 60 digits."""
    wi = as_directions(np.array(direction(t_i, 180.0)), "wi").tolist()
    wo = as_directions(np.array(direction(t_o, 180.0 + dphi)), "wo").tolist()
    want = oren_nayar_decimal(0.6, math.radians(40.0), wi, wo)
    for a, b in ((wi, wo), (wo, wi)):
        assert rel_err(value("oren-nayar", {"kd": 0.6, "sigma": 40.0}, a, b), want) < 1e-13


@pytest.mark.parametrize("c", [4e-4, -0.2])
def test_sharp_phong_lobe_far_out_and_outside(c):
    """n = 65 (the sharp path): where S·wo = 4e-4 the lobe c⁶⁵ ≈ 1e-221 is still a value
    (within its conditioning of 60 digits); where S·wo < 0 (outside the lobe) f is exactly
    kd/π."""
    wi = np.array(direction(40.0, 200.0))
    axis = np.array([-wi[0], -wi[1], wi[2]])  # S, the mirror direction
    perp = np.array([0.0, 0.0, 1.0]) - axis[2] * axis  # the normal's part ⟂ S: z > 0
    perp /= np.linalg.norm(perp)
    wo = c * axis + math.sqrt(1.0 - c * c) * perp
    assert wo[2] > 0.0
    wi, wo = as_directions(wi, "wi").tolist(), as_directions(wo, "wo").tolist()
    if c < 0:
        assert value("phong", {"kd": 0.2, "ks": 0.5, "n": 65.0}, wi, wo) == 0.2 / math.pi
        return
    lobe, _ = lobe_decimal("phong", 65.0, wi, wo)
    got = value("phong", {"kd": 0.0, "ks": 1.0, "n": 65.0}, wi, wo) / (67.0 / (2 * math.pi))
    # c = S·wo is a sum of terms ~0.5 that cancel to 4e-4: an ulp of the inputs moves it by
    # ~1e-16, and c⁶⁵ by 65·1e-16/c relative: the bound is 8 ulp of that
    assert lobe > D("1e-230") and rel_err(got, lobe) < 8 * EPS * 65.0 / c
