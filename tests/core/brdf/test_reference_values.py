"""Reference values: every built-in model at generic directions, computed independently.

Each expected value is computed here, step by step in scalar Python ``math``, from the model's
published formula (SPEC §2 names each source; the equation is repeated at each reference
function) — never with tuibrdf's own functions, and where a textbook form differs from the
kernel's rearranged one (Snell's law for the exact Fresnel term, ``tan θh`` for GGX's D,
``Λ = (−1 + √(1 + α² tan²θ))/2`` for Smith) the textbook form is used.  Directions are generic:
no normal incidence, outside the plane of incidence, θi ≠ θo, with forward and backward
scattering; parameters are generic (an RGB base colour with distinct channels, both Fresnel
choices, metallic strictly between 0 and 1).

The tolerance is 1e-12 relative: both sides are float64 evaluations of the same real number in
a different order of operations.  Any change of a constant in a formula (a factor 2 → 2.002,
0.17 → 0.17017, an exponent 5 → 5.005) moves the value by far more, so a wrong formula fails
here, not only in a snapshot.  ``scripts/mutation_check.py`` checks that claim constant by
constant.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import tuibrdf
from tests import hiprec
from tests.merl_writer import write_merl
from tuibrdf.core.brdf import fresnel as fresnel_mod
from tuibrdf.core.brdf import microfacet
from tuibrdf.core.registry import MODELS

RTOL = 1e-12
PI = math.pi


# ------------------------------------------------------------------------------ helpers


def direction(theta_deg: float, phi_deg: float) -> tuple[float, float, float]:
    """SPEC §1: dir(θ, φ) = (sin θ cos φ, sin θ sin φ, cos θ)."""
    t, p = math.radians(theta_deg), math.radians(phi_deg)
    return (math.sin(t) * math.cos(p), math.sin(t) * math.sin(p), math.cos(t))


def dot(a, b) -> float:
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def normalize(a) -> tuple[float, float, float]:
    n = math.sqrt(dot(a, a))
    return (a[0] / n, a[1] / n, a[2] / n)


def half(wi, wo) -> tuple[float, float, float]:
    """SPEC §1: H = normalize(wi + wo)."""
    return normalize((wi[0] + wo[0], wi[1] + wo[1], wi[2] + wo[2]))


def polar(w) -> float:
    """θ of a unit vector, from its components (atan2 of sin and cos)."""
    return math.atan2(math.hypot(w[0], w[1]), w[2])


def cos_dphi(wi, wo) -> float:
    """cos(φo − φi) = cos φo cos φi + sin φo sin φi; 0 at the normal (SPEC §2)."""
    si, so = math.hypot(wi[0], wi[1]), math.hypot(wo[0], wo[1])
    if si == 0.0 or so == 0.0:
        return 0.0
    return (wi[0] / si) * (wo[0] / so) + (wi[1] / si) * (wo[1] / so)


def value(model: str, params: dict, wi, wo):
    """The model's value through the public API, as a float or an RGB list."""
    f = np.asarray(tuibrdf.evaluate(model, params, np.array(wi), np.array(wo)), dtype=float)
    return f.tolist() if f.ndim else float(f)


def assert_close(got, want, rtol=RTOL):
    got, want = np.atleast_1d(got), np.atleast_1d(want)
    assert got.shape == want.shape
    for g, w in zip(got, want, strict=True):
        assert g == pytest.approx(w, rel=rtol, abs=0.0), f"got {got.tolist()}, want {want.tolist()}"


# Generic direction pairs (θ, φ in degrees).  The mirror of wi = dir(θ, φ) is dir(θ, φ + 180°).
BACK = (direction(37.0, 203.0), direction(52.0, 31.0))  # opposite sides: cos Δφ = cos 172° < 0
SAME = (direction(28.0, -40.0), direction(66.0, -5.0))  # same side: cos Δφ = cos 35° > 0
SIDE = (direction(58.0, 110.0), direction(23.0, 14.0))  # cos Δφ = cos 96° slightly < 0
NEAR_MIRROR = (direction(37.0, 203.0), direction(41.0, 17.0))  # mirror at (37°, 23°)
GRAZING_MIRROR = (direction(62.0, 190.0), direction(86.0, 4.0))  # V-cavity G < 1 (masking)
GRAZING_SHADOW = (direction(86.0, 190.0), direction(62.0, 14.0))  # V-cavity G < 1 (shadowing)
NEAR_NORMAL = (direction(3.0, 250.0), direction(2.5, 64.0))  # ψ ≈ 2.7°, cos ψ > 0.999
ON_HORIZON = (direction(48.0, 200.0), (math.cos(math.radians(25.0)),
                                        math.sin(math.radians(25.0)), 0.0))  # θo = 90° exactly

# RGB parameters with distinct channels; metallic strictly between 0 and 1
BASE = (0.83, 0.41, 0.17)


# ------------------------------------------------------------------------------ Fresnel


def fresnel_snell(cos_psi: float, f0: float) -> float:
    """Unpolarised Fresnel reflectance of a dielectric (Born & Wolf §1.5; Cook & Torrance 1981),
    from Snell's law: n = (1 + √f0)/(1 − √f0) (inverting f0 = ((n − 1)/(n + 1))²),
    sin θt = sin ψ / n, rs = (cos ψ − n cos θt)/(cos ψ + n cos θt),
    rp = (n cos ψ − cos θt)/(n cos ψ + cos θt), F = (rs² + rp²)/2."""
    if f0 == 0.0:
        return 0.0  # n = 1: no interface
    if f0 == 1.0:
        return 1.0  # n → ∞: a perfect mirror (the limit of the formula)
    r = math.sqrt(f0)
    n = (1.0 + r) / (1.0 - r)
    sin_t = math.sqrt(1.0 - cos_psi * cos_psi) / n
    cos_t = math.sqrt(1.0 - sin_t * sin_t)
    rs = (cos_psi - n * cos_t) / (cos_psi + n * cos_t)
    rp = (n * cos_psi - cos_t) / (n * cos_psi + cos_t)
    return 0.5 * (rs * rs + rp * rp)


def fresnel_schlick(cos_psi: float, f0: float) -> float:
    """Schlick 1994, eq. 24: F = f0 + (1 − f0)(1 − cos ψ)⁵."""
    return f0 + (1.0 - f0) * (1.0 - cos_psi) ** 5


@pytest.mark.parametrize("cos_psi, f0", [(0.8137, 0.04), (0.2311, 0.37), (0.0005, 0.04),
                                          (0.99971, 0.61), (0.43, 0.0005), (0.12, 0.9995)])
def test_fresnel_exact_against_snell(cos_psi, f0):
    got = float(fresnel_mod.fresnel_exact(np.array(cos_psi), f0))
    assert_close(got, fresnel_snell(cos_psi, f0))


def test_fresnel_ends_and_clipping():
    """f0 = 0 (n = 1, no interface) reflects nothing, f0 = 1 everything; a cosine a hair
    outside [0, 1] (rounding) is read as its end: F(cos ψ = 0) = 1 for a dielectric, F(1) = f0
    (both from Snell's law at grazing and normal incidence)."""
    c = np.array([-1e-4, 0.37, 1.0 + 1e-4])
    assert np.all(fresnel_mod.fresnel_exact(c, 0.0) == 0.0)
    assert np.all(fresnel_mod.fresnel_exact(c, 1.0) == 1.0)
    assert_close(fresnel_mod.fresnel_exact(c[[0, 2]], 0.3), [1.0, 0.3], rtol=1e-12)
    assert_close(fresnel_mod.fresnel_schlick(c[[0, 2]], 0.3), [1.0, 0.3], rtol=1e-12)
    assert np.all(fresnel_mod.fresnel_exact(c[[0, 2]], 0.0) == 0.0)
    assert fresnel_mod.fresnel_schlick(c[2], 0.0) == 0.0  # never (1 − 1.0001)⁵ < 0


@pytest.mark.parametrize("cos_psi, f0", [(0.8137, 0.04), (0.2311, (0.91, 0.52, 0.23))])
def test_fresnel_schlick_reference(cos_psi, f0):
    got = fresnel_mod.fresnel_schlick(np.array(cos_psi), f0)
    want = [fresnel_schlick(cos_psi, f) for f in np.atleast_1d(f0)]
    assert_close(got, want)


@pytest.mark.parametrize("n", [1.5, 2.0])
def test_fresnel_exact_recovers_the_index_from_f0(n):
    """f0 = ((n − 1)/(n + 1))² (glass n = 1.5: f0 = 0.04; n = 2: f0 = 1/9), and the exact
    Fresnel term recovers n from it: at Brewster's angle (tan θ = n) rp = 0 and θ + θt = 90°,
    so rs = −sin(θ − θt) = −(n² − 1)/(n² + 1) and F = rs²/2 (n = 2: a 3-4-5 triangle, F =
    0.18 exactly; n = 1.5: (5/13)²/2 = 0.0739645)."""
    f0 = ((n - 1.0) / (n + 1.0)) ** 2
    got = float(fresnel_mod.fresnel_exact(np.array(1.0 / math.sqrt(1.0 + n * n)), f0))
    assert got == pytest.approx(((n * n - 1.0) / (n * n + 1.0)) ** 2 / 2.0, rel=1e-14)


# ------------------------------------------------------------------------------ Lambert


@pytest.mark.parametrize("pair", [BACK, SAME, SIDE, ON_HORIZON])
def test_lambert(pair):
    """Lambert 1760: f = kd/π everywhere in the closed upper hemisphere."""
    assert_close(value("lambert", {"kd": 0.37}, *pair), 0.37 / PI)
    assert_close(value("lambert", {"kd": 0.37}, *pair[::-1]), 0.37 / PI)


def test_lambert_below_the_horizon_is_zero():
    """SPEC §2: the BRDF is 0 for a direction below the horizon (a hair below counts)."""
    wi, wo = BACK[0], (0.6, 0.8 * math.cos(1e-6), -0.8 * math.sin(1e-6))
    assert value("lambert", {"kd": 0.37}, wi, wo) == 0.0
    assert value("lambert", {"kd": 0.37}, wo, wi) == 0.0


# ------------------------------------------------------------------------------ Phong


def phong_ref(kd, ks, n, wi, wo) -> float:
    """Modified Phong (Lewis 1993): f = kd/π + ks (n + 2)/(2π) max(0, S·wo)ⁿ, S = mirror of wi
    = (−x, −y, z); a lobe of exponent 0 is the half-space S·wo > 0."""
    s = (-wi[0], -wi[1], wi[2])
    c = dot(s, wo)
    lobe = c**n if c > 0.0 else 0.0
    return kd / PI + ks * (n + 2.0) / (2.0 * PI) * lobe


@pytest.mark.parametrize("pair, n", [(NEAR_MIRROR, 20.0), (GRAZING_MIRROR, 7.5), (SAME, 3.0),
                                     (BACK, 133.0)])
def test_phong(pair, n):
    params = {"kd": 0.27, "ks": 0.61, "n": n}
    assert_close(value("phong", params, *pair), phong_ref(0.27, 0.61, n, *pair))


def test_phong_exponent_zero_is_a_half_space():
    """n = 0: max(0, c)⁰ is 1 for c > 0 (even tiny) and 0 for c ≤ 0 (SPEC §2's max(0, ·))."""
    wi = direction(40.0, 200.0)
    s = (-wi[0], -wi[1], wi[2])  # the mirror direction, dir(40°, 20°)
    p = direction(130.0, 20.0)  # ⟂ S; flipped below to z > 0
    p = (-p[0], -p[1], -p[2])
    for delta in (4e-4, -4e-4):
        wo = normalize(tuple(a + delta * b for a, b in zip(p, s, strict=True)))
        c = dot(s, wo)
        assert (c > 0) == (delta > 0) and abs(c) < 1e-3 and wo[2] > 0.5
        assert_close(value("phong", {"kd": 0.2, "ks": 0.5, "n": 0.0}, wi, wo),
                     phong_ref(0.2, 0.5, 0.0, wi, wo))


# ------------------------------------------------------------------------------ Blinn-Phong


def blinn_phong_ref(kd, ks, n, wi, wo) -> float:
    """Normalised Blinn-Phong (gKit2 lesson; Akenine-Möller et al., RTR 4th ed. eq. 9.50):
    f = kd/π + ks (n + 8)/(8π) max(0, N·H)ⁿ."""
    nh = half(wi, wo)[2]
    return kd / PI + ks * (n + 8.0) / (8.0 * PI) * max(0.0, nh) ** n


#: the mirror pair 0.5° and 0.01° above the horizon: |wi + wo| = 2 cos θ is small (0.017,
#: 3.5e-4) but H is the normal exactly, the lobe's maximum
GRAZING_MIRRORS = [(direction(t, 200.0), direction(t, 20.0)) for t in (89.5, 89.99)]


@pytest.mark.parametrize("pair, n", [(NEAR_MIRROR, 20.0), (GRAZING_MIRROR, 57.0), (SAME, 4.5),
                                     *((p, 20.0) for p in GRAZING_MIRRORS)])
def test_blinn_phong(pair, n):
    params = {"kd": 0.19, "ks": 0.73, "n": n}
    assert_close(value("blinn-phong", params, *pair), blinn_phong_ref(0.19, 0.73, n, *pair))


# ------------------------------------------------------------------------------ microfacet


def tan2_of(w) -> float:
    """tan²θ = (x² + y²)/z² of a unit vector (no cancellation near the pole)."""
    return (w[0] * w[0] + w[1] * w[1]) / (w[2] * w[2])


def beckmann_ref(h, m: float) -> float:
    """Beckmann D (Cook & Torrance 1981 eq. 7): exp(−tan²θh/m²)/(π m² cos⁴θh)."""
    return math.exp(-tan2_of(h) / (m * m)) / (PI * m * m * h[2] ** 4)


def vcavity_ref(cos_h, cos_i, cos_o, cos_psi) -> float:
    """Cook & Torrance 1981 eq. 6 (Torrance & Sparrow's V-cavities):
    G = min(1, 2 cosθh cosθo / cosψ, 2 cosθh cosθi / cosψ)."""
    return max(0.0, min(1.0, 2.0 * cos_h * cos_o / cos_psi, 2.0 * cos_h * cos_i / cos_psi))


def ggx_d_ref(h, alpha: float) -> float:
    """GGX / Trowbridge-Reitz D in Walter et al. 2007 eq. 33's form:
    α² / (π cos⁴θh (α² + tan²θh)²)."""
    return alpha * alpha / (PI * h[2] ** 4 * (alpha * alpha + tan2_of(h)) ** 2)


def smith_lambda_ref(w, alpha: float) -> float:
    """Heitz 2014 eq. 72: Λ = (−1 + √(1 + α² tan²θ))/2."""
    return 0.5 * (-1.0 + math.sqrt(1.0 + alpha * alpha * tan2_of(w)))


def cook_torrance_ref(kd, f0, m, kind, wi, wo) -> float:
    """Cook & Torrance 1981: f = kd/π + F(ψ) D G / (4 cosθi cosθo) (SPEC §2)."""
    h = half(wi, wo)
    ci, co, ch, cpsi = wi[2], wo[2], h[2], dot(h, wi)
    f = fresnel_snell(cpsi, f0) if kind == "exact" else fresnel_schlick(cpsi, f0)
    return kd / PI + f * beckmann_ref(h, m) * vcavity_ref(ch, ci, co, cpsi) / (4.0 * ci * co)


def ggx_ref(kd, f0, alpha, kind, wi, wo) -> float:
    """Walter et al. 2007 / Heitz 2014: f = kd/π + F D G2 / (4 cosθi cosθo), height-correlated
    G2 = 1/(1 + Λ(wi) + Λ(wo)) (Heitz eq. 99)."""
    h = half(wi, wo)
    ci, co, cpsi = wi[2], wo[2], dot(h, wi)
    f = fresnel_snell(cpsi, f0) if kind == "exact" else fresnel_schlick(cpsi, f0)
    g2 = 1.0 / (1.0 + smith_lambda_ref(wi, alpha) + smith_lambda_ref(wo, alpha))
    return kd / PI + f * ggx_d_ref(h, alpha) * g2 / (4.0 * ci * co)


CT_CASES = [
    # (params, pair): near the mirror (G = 1), masking and shadowing at grazing (G < 1),
    # off the lobe; both Fresnel choices
    ({"kd": 0.13, "f0": 0.04, "m": 0.2, "fresnel": "exact"}, NEAR_MIRROR),
    ({"kd": 0.0, "f0": 0.37, "m": 0.35, "fresnel": "schlick"}, GRAZING_MIRROR),
    ({"kd": 0.05, "f0": 0.61, "m": 0.45, "fresnel": "exact"}, GRAZING_SHADOW),
    ({"kd": 0.21, "f0": 0.08, "m": 0.6, "fresnel": "schlick"}, SAME),
    ({"kd": 0.0, "f0": 0.9, "m": 0.15, "fresnel": "exact"}, NEAR_NORMAL),
    # far down a sharp lobe's tail: exp(−tan²θh/m²) = 7.6e-4, still a value
    ({"kd": 0.0, "f0": 0.04, "m": 0.1, "fresnel": "schlick"},
     (direction(37.0, 203.0), direction(67.0, 23.0))),
    # the exact mirror at θ = 89°: H = N, G = 1, cosθi cosθo = 3e-4
    ({"kd": 0.0, "f0": 0.04, "m": 0.2, "fresnel": "exact"},
     (direction(89.0, 200.0), direction(89.0, 20.0))),
]


@pytest.mark.parametrize("params, pair", CT_CASES)
def test_cook_torrance(params, pair):
    want = cook_torrance_ref(params["kd"], params["f0"], params["m"], params["fresnel"], *pair)
    assert_close(value("cook-torrance", params, *pair), want)


@pytest.mark.parametrize("kind", ["exact", "schlick"])
def test_cook_torrance_nearly_opposite_grazing_directions(kind):
    """θi = 89.95°, θo = 89.7° on opposite azimuths: H ≈ N (θh = 0.13°) but cos ψ = 0.003, so
    the V-cavity min picks 2 cosθh cosθo / cosψ (masking) in one order and the shadowing term
    in the other; G/(cosθi cosθo) is 1.25e5 there.  cos ψ = |wi + wo|/2 comes from a sum whose
    horizontal parts cancel (to 0.3%), computed differently here and in the kernel: 1e-9."""
    wi, wo = direction(89.95, 180.0), direction(89.7, 0.0)
    params = {"kd": 0.0, "f0": 0.04, "m": 0.2, "fresnel": kind}
    for a, b in ((wi, wo), (wo, wi)):
        assert_close(value("cook-torrance", params, a, b),
                     cook_torrance_ref(0.0, 0.04, 0.2, kind, a, b), rtol=1e-9)


def test_vcavity_cases_cover_both_masking_and_shadowing():
    """The grazing cases above exercise each branch of the V-cavity min (a sanity check of the
    test data, with the reference function)."""
    for pair, branch in ((GRAZING_MIRROR, "o"), (GRAZING_SHADOW, "i")):
        wi, wo = pair
        h = half(wi, wo)
        g_o = 2.0 * h[2] * wo[2] / dot(h, wi)
        g_i = 2.0 * h[2] * wi[2] / dot(h, wi)
        assert min(g_o, g_i) < 1.0
        assert (g_o < g_i) == (branch == "o")


def test_cook_torrance_one_direction_on_the_horizon_is_the_limit():
    """θo = 90°: G = 2 cosθh cosθo / cosψ near the horizon, so G/(4 cosθi cosθo) tends to
    2 cosθh / (4 cosψ cosθi) (microfacet_models docstring; SPEC §2's limit rule)."""
    wi, wo = ON_HORIZON
    h = half(wi, wo)
    cpsi = dot(h, wi)
    for kind, f in (("exact", fresnel_snell(cpsi, 0.3)), ("schlick", fresnel_schlick(cpsi, 0.3))):
        want = 0.1 / PI + f * beckmann_ref(h, 0.5) * 2.0 * h[2] / (4.0 * cpsi * wi[2])
        got = value("cook-torrance", {"kd": 0.1, "f0": 0.3, "m": 0.5, "fresnel": kind}, wi, wo)
        assert_close(got, want)
        got = value("cook-torrance", {"kd": 0.1, "f0": 0.3, "m": 0.5, "fresnel": kind}, wo, wi)
        assert_close(got, want)


GGX_CASES = [
    ({"kd": 0.11, "f0": 0.04, "alpha": 0.2, "fresnel": "exact"}, NEAR_MIRROR),
    ({"kd": 0.0, "f0": 0.55, "alpha": 0.42, "fresnel": "schlick"}, GRAZING_MIRROR),
    ({"kd": 0.3, "f0": 0.17, "alpha": 0.8, "fresnel": "exact"}, BACK),
    ({"kd": 0.0, "f0": 0.9, "alpha": 0.07, "fresnel": "schlick"}, NEAR_NORMAL),
]


@pytest.mark.parametrize("params, pair", GGX_CASES)
def test_ggx(params, pair):
    want = ggx_ref(params["kd"], params["f0"], params["alpha"], params["fresnel"], *pair)
    assert_close(value("ggx", params, *pair), want)


def test_ggx_one_direction_on_the_horizon_is_the_limit():
    """θo = 90°: cosθo·Λ(θo) → α sinθo/2 = α/2, so G2/(4 cosθi cosθo) → 1/(2α cosθi)
    (Heitz eq. 72, 99 with the limit taken by hand)."""
    wi, wo = ON_HORIZON
    h = half(wi, wo)
    f = fresnel_snell(dot(h, wi), 0.3)
    want = 0.1 / PI + f * ggx_d_ref(h, 0.5) / (2.0 * 0.5 * wi[2])
    for a, b in ((wi, wo), (wo, wi)):
        assert_close(value("ggx", {"kd": 0.1, "f0": 0.3, "alpha": 0.5}, a, b), want)
    # the sharpest lobe, α = 0.001, just off the mirror (no diffuse term): the same limit
    wi, wo = direction(30.0, 200.0), (math.cos(math.radians(20.01)),
                                      math.sin(math.radians(20.01)), 0.0)
    h = half(wi, wo)
    want = fresnel_snell(dot(h, wi), 0.3) * ggx_d_ref(h, 1e-3) / (2.0 * 1e-3 * wi[2])
    for a, b in ((wi, wo), (wo, wi)):
        assert_close(value("ggx", {"kd": 0.0, "f0": 0.3, "alpha": 1e-3}, a, b), want)


@pytest.mark.parametrize("cos_t, alpha", [(0.77, 0.3), (0.12, 0.65), (0.999, 0.05), (1e-4, 1e-3)])
def test_smith_g1(cos_t, alpha):
    """G1 = 1/(1 + Λ) (Heitz eq. 43 with eq. 72), as cos/(cos + cos·Λ) from the cos·Λ the
    models' G2 is built from (:func:`~tuibrdf.core.brdf.microfacet.ggx_lambda_cos`)."""
    cos_lambda = float(microfacet.ggx_lambda_cos(np.array(cos_t), np.array(1.0 - cos_t * cos_t),
                                                 alpha))
    got = cos_t / (cos_t + cos_lambda)
    w = (math.sqrt(1.0 - cos_t * cos_t), 0.0, cos_t)
    assert_close(got, 1.0 / (1.0 + smith_lambda_ref(w, alpha)))


# ------------------------------------------------------------------------------ glTF, UE4


def gltf_ref(base, metallic, roughness, wi, wo) -> list[float]:
    """glTF 2.0 appendix B (the pre-2024 form, SPEC §2): α = max(roughness², 0.001) (the
    documented floor), F0 = mix(0.04, base, metallic), c_diff = mix(base, 0, metallic),
    F = Schlick per channel, f = (1 − F) c_diff/π + F D G2/(4 |N·wi| |N·wo|)."""
    alpha = max(roughness * roughness, 1e-3)
    h = half(wi, wo)
    ci, co, cpsi = wi[2], wo[2], dot(h, wi)
    d = ggx_d_ref(h, alpha)
    g2 = 1.0 / (1.0 + smith_lambda_ref(wi, alpha) + smith_lambda_ref(wo, alpha))
    out = []
    for b in base:
        f0 = 0.04 * (1.0 - metallic) + b * metallic
        c_diff = b * (1.0 - metallic)
        f = fresnel_schlick(cpsi, f0)
        out.append((1.0 - f) * c_diff / PI + f * d * g2 / (4.0 * abs(ci) * abs(co)))
    return out


def ue4_ref(base, metallic, roughness, wi, wo) -> list[float]:
    """Karis 2013 (SPEC §2): c_diff = (1 − metallic) base, F0 = mix(0.04, base, metallic),
    α = max(roughness², 0.001), Schlick F, G = G1(wi) G1(wo) with G1(c) = c/(c(1 − k) + k),
    k = (roughness + 1)²/8; f = c_diff/π + F D G/(4 cosθi cosθo)."""
    alpha = max(roughness * roughness, 1e-3)
    k = (roughness + 1.0) ** 2 / 8.0
    h = half(wi, wo)
    ci, co, cpsi = wi[2], wo[2], dot(h, wi)
    d = ggx_d_ref(h, alpha)

    def g1(c):
        return c / (c * (1.0 - k) + k)

    out = []
    for b in base:
        f = fresnel_schlick(cpsi, 0.04 * (1.0 - metallic) + b * metallic)
        out.append((1.0 - metallic) * b / PI + f * d * g1(ci) * g1(co) / (4.0 * ci * co))
    return out


PBR_CASES = [
    ({"base_color": BASE, "metallic": 0.3, "roughness": 0.45}, NEAR_MIRROR),
    ({"base_color": BASE, "metallic": 0.0, "roughness": 0.7}, BACK),
    ({"base_color": (0.95, 0.64, 0.54), "metallic": 0.85, "roughness": 0.22}, GRAZING_MIRROR),
    ({"base_color": BASE, "metallic": 1.0, "roughness": 0.6}, SAME),
]


@pytest.mark.parametrize("params, pair", PBR_CASES)
def test_gltf(params, pair):
    want = gltf_ref(params["base_color"], params["metallic"], params["roughness"], *pair)
    assert_close(value("gltf", params, *pair), want)


@pytest.mark.parametrize("params, pair", PBR_CASES)
def test_ue4(params, pair):
    want = ue4_ref(params["base_color"], params["metallic"], params["roughness"], *pair)
    assert_close(value("ue4", params, *pair), want)


@pytest.mark.parametrize("model, ref", [("gltf", gltf_ref), ("ue4", ue4_ref)])
def test_roughness_zero_is_floored_at_the_documented_alpha(model, ref):
    """Roughness 0 (a Dirac mirror) is drawn with α = 0.001 (SPEC §2, as pbrt and Mitsuba):
    at H = N, D = 1/(π α²) = 1/(π·10⁻⁶); a hair off the mirror, D depends on α steeply."""
    wi = direction(35.0, 200.0)
    params = {"base_color": BASE, "metallic": 0.4, "roughness": 0.0}
    for wo in (direction(35.0, 20.0), direction(35.05, 20.02)):
        assert_close(value(model, params, wi, wo), ref(BASE, 0.4, 0.0, wi, wo))
    assert microfacet.ALPHA_MIN == 1e-3


def test_ue4_one_direction_on_the_horizon():
    """θo = 90°: G1(cosθo)/cosθo = 1/(cosθo(1 − k) + k) → 1/k (Schlick-GGX has no pole)."""
    wi, wo = ON_HORIZON
    r, metallic = 0.5, 0.3
    k = (r + 1.0) ** 2 / 8.0
    h = half(wi, wo)
    d = ggx_d_ref(h, r * r)
    g1_i = wi[2] / (wi[2] * (1.0 - k) + k)
    want = []
    for b in BASE:
        f = fresnel_schlick(dot(h, wi), 0.04 * (1.0 - metallic) + b * metallic)
        want.append((1.0 - metallic) * b / PI + f * d * g1_i / k / (4.0 * wi[2]))
    params = {"base_color": BASE, "metallic": metallic, "roughness": r}
    assert_close(value("ue4", params, wi, wo), want)
    assert_close(value("ue4", params, wo, wi), want)


# ------------------------------------------------------------------------------ Disney diffuse


def disney_ref(base, roughness, wi, wo) -> list[float]:
    """Burley 2012 eq. (B.1 / §5.3): f = base/π (1 + (FD90 − 1)(1 − cosθi)⁵)
    (1 + (FD90 − 1)(1 − cosθo)⁵), FD90 = 0.5 + 2 roughness cos²θd, cosθd = wi·H."""
    cd = dot(half(wi, wo), wi)
    fd90 = 0.5 + 2.0 * roughness * cd * cd
    shape = (1.0 + (fd90 - 1.0) * (1.0 - wi[2]) ** 5) * (1.0 + (fd90 - 1.0) * (1.0 - wo[2]) ** 5)
    return [b / PI * shape for b in base]


@pytest.mark.parametrize("roughness, pair", [(0.5, BACK), (0.9, GRAZING_MIRROR), (0.15, SIDE),
                                             (0.7, ON_HORIZON), (0.35, NEAR_NORMAL)])
def test_disney_diffuse(roughness, pair):
    params = {"base_color": BASE, "roughness": roughness}
    assert_close(value("disney-diffuse", params, *pair), disney_ref(BASE, roughness, *pair))


# ------------------------------------------------------------------------------ Oren-Nayar


def oren_nayar_ref(kd, sigma_deg, wi, wo, simple=False, clamp=True) -> float:
    """Oren & Nayar 1994, the qualitative model (SPEC §2, paper's C3), σ in radians:
    A = 1 − 0.5 σ²/(σ² + 0.33), B = 0.45 σ²/(σ² + 0.09), α = max(θi, θo), β = min(θi, θo),
    C2 = B sin α if cos Δφ ≥ 0 else B (sin α − (2β/π)³), C3 = 0.125 σ²/(σ² + 0.09)(4αβ/π²)²,
    f = kd/π (A + C2 cosΔφ tan β + C3 (1 − |cosΔφ|) tan((α + β)/2))
        + 0.17 kd²/π σ²/(σ² + 0.13) (1 − cosΔφ (2β/π)²), clamped at 0.
    Simplified: f = kd/π (A + B max(0, cosΔφ) sin α tan β)."""
    s2 = math.radians(sigma_deg) ** 2
    a = 1.0 - 0.5 * s2 / (s2 + 0.33)
    b = 0.45 * s2 / (s2 + 0.09)
    ti, to = polar(wi), polar(wo)
    al, be = max(ti, to), min(ti, to)
    cphi = cos_dphi(wi, wo)
    if simple:
        return kd / PI * (a + b * max(0.0, cphi) * math.sin(al) * math.tan(be))
    c2 = b * math.sin(al) if cphi >= 0.0 else b * (math.sin(al) - (2.0 * be / PI) ** 3)
    c3 = 0.125 * s2 / (s2 + 0.09) * (4.0 * al * be / PI**2) ** 2
    single = kd / PI * (a + c2 * cphi * math.tan(be)
                        + c3 * (1.0 - abs(cphi)) * math.tan((al + be) / 2.0))
    inter = 0.17 * kd * kd / PI * s2 / (s2 + 0.13) * (1.0 - cphi * (2.0 * be / PI) ** 2)
    return max(single + inter, 0.0) if clamp else single + inter


ON_CASES = [(0.8, 20.0, BACK), (0.63, 35.0, SAME), (0.5, 50.0, SIDE), (0.9, 12.0, ON_HORIZON),
            (0.44, 27.0, GRAZING_MIRROR),
            # |cos Δφ| < 1e-3 on either side of 0: each side of the C2 switch
            (0.7, 30.0, (direction(50.0, 10.0), direction(70.0, 100.03))),
            (0.7, 30.0, (direction(50.0, 10.0), direction(70.0, 99.97)))]


@pytest.mark.parametrize("kd, sigma, pair", ON_CASES)
def test_oren_nayar(kd, sigma, pair):
    params = {"kd": kd, "sigma": sigma}
    for a, b in (pair, pair[::-1]):
        assert_close(value("oren-nayar", params, a, b), oren_nayar_ref(kd, sigma, a, b))


@pytest.mark.parametrize("kd, sigma, pair", ON_CASES)
def test_oren_nayar_simple(kd, sigma, pair):
    params = {"kd": kd, "sigma": sigma}
    for a, b in (pair, pair[::-1]):
        assert_close(value("oren-nayar-simple", params, a, b),
                     oren_nayar_ref(kd, sigma, a, b, simple=True))


def test_oren_nayar_clamps_where_the_formula_goes_negative():
    """σ = 90° at grazing back-scatter (cos Δφ < 0): the formula is negative, the value is 0
    (SPEC §2); a little less grazing it is positive and must be the formula's value."""
    wi, wo = direction(89.0, 180.0), direction(88.0, 3.0)
    assert oren_nayar_ref(0.7, 90.0, wi, wo, clamp=False) < -0.004  # the test data is negative
    assert value("oren-nayar", {"kd": 0.7, "sigma": 90.0}, wi, wo) == 0.0
    wi, wo = direction(89.0, 180.0), direction(84.0, 3.0)
    want = oren_nayar_ref(0.7, 90.0, wi, wo)
    assert want > 0.0
    assert_close(value("oren-nayar", {"kd": 0.7, "sigma": 90.0}, wi, wo), want)


@pytest.mark.parametrize("model", ["oren-nayar", "oren-nayar-simple"])
def test_oren_nayar_both_on_the_horizon_is_zero(model):
    """θi = θo = 90°: tan β has no limit there; the documented value is 0 (SPEC §2)."""
    wi = (math.cos(math.radians(200.0)), math.sin(math.radians(200.0)), 0.0)  # z exactly 0
    wo = (math.cos(math.radians(35.0)), math.sin(math.radians(35.0)), 0.0)
    assert value(model, {"kd": 0.8, "sigma": 20.0}, wi, wo) == 0.0


# -- near the horizon: an independent evaluation with 60-digit decimals


def oren_nayar_decimal(kd, sigma_rad, wi, wo, simple=False):
    """:func:`oren_nayar_ref` in 60-digit decimal arithmetic (tests/hiprec.py), at exactly the
    float64 inputs: θ = atan2(√(x² + y²), z), then tan, sin of the angles, as the paper writes
    them; the clamp at 0 is left out (the cases below are positive)."""
    D = hiprec.D
    with hiprec.precise():
        pi = hiprec.pi()
        si = hiprec.sqrt(D(wi[0]) ** 2 + D(wi[1]) ** 2)
        so = hiprec.sqrt(D(wo[0]) ** 2 + D(wo[1]) ** 2)
        ti, to = hiprec.atan2(si, D(wi[2])), hiprec.atan2(so, D(wo[2]))
        cphi = (D(wi[0]) * D(wo[0]) + D(wi[1]) * D(wo[1])) / (si * so)
        al, be = max(ti, to), min(ti, to)
        s2 = D(sigma_rad) ** 2
        a = 1 - D("0.5") * s2 / (s2 + D("0.33"))
        b = D("0.45") * s2 / (s2 + D("0.09"))
        kd = D(kd)
        if simple:
            return kd / pi * (a + b * max(D(0), cphi) * hiprec.sin(al) * hiprec.tan(be))
        c2 = b * hiprec.sin(al) if cphi >= 0 else b * (hiprec.sin(al) - (2 * be / pi) ** 3)
        c3 = D("0.125") * s2 / (s2 + D("0.09")) * (4 * al * be / pi**2) ** 2
        single = kd / pi * (a + c2 * cphi * hiprec.tan(be)
                            + c3 * (1 - abs(cphi)) * hiprec.tan((al + be) / 2))
        inter = D("0.17") * kd * kd / pi * s2 / (s2 + D("0.13")) * (1 - cphi * (2 * be / pi) ** 2)
        return single + inter


def unit(v) -> np.ndarray:
    v = np.array(v, dtype=float)
    return v / np.linalg.norm(v)


def grazing(eps: float, phi_deg: float) -> np.ndarray:
    """A direction ε rad above the horizon at azimuth φ."""
    p = math.radians(phi_deg)
    return np.array([math.cos(eps) * math.cos(p), math.cos(eps) * math.sin(p), math.sin(eps)])


HORIZON_CASES = [
    # the case measured in issue 18 (the float64 tan of an atan2 angle was 1.1e-7 off there)
    (0.2913, 39.686, unit([-0.0620123355, -0.9980753830, 1.0087e-9]),
     unit([-0.1922251847, 0.9813508437, 1.0196e-9])),
    (0.8, 20.0, grazing(3e-9, 180.0), grazing(7e-10, 11.0)),  # forward, cos Δφ < 0
    (0.5, 60.0, grazing(2e-8, 200.0), grazing(5e-8, 230.0)),  # same side, cos Δφ > 0
    (0.37, 5.0, grazing(1e-12, -70.0), grazing(4e-6, 60.0)),
    (0.9, 85.0, grazing(1e-14, 10.0), grazing(3e-14, 130.0)),
]


@pytest.mark.parametrize("kd, sigma, wi, wo", HORIZON_CASES)
@pytest.mark.parametrize("model", ["oren-nayar", "oren-nayar-simple"])
def test_oren_nayar_precise_near_the_horizon(model, kd, sigma, wi, wo):
    """Both directions within 1e-14…4e-6 rad of the horizon: the kernel is within 1e-13 of a
    60-digit evaluation of the paper's formula (the tangents are ~1e9…1e14 there)."""
    want = oren_nayar_decimal(kd, math.radians(sigma), wi, wo, simple=model.endswith("simple"))
    assert want > 0
    for a, b in ((wi, wo), (wo, wi)):
        got = value(model, {"kd": kd, "sigma": sigma}, a, b)
        with hiprec.precise():
            err = abs((hiprec.D(got) - want) / want)
        assert err < 1e-13, f"{model}: {got!r} vs {want}: relative error {float(err):.2g}"


def test_hiprec_functions():
    """The decimal functions against known values: π's digits, tan(π/4) = 1, atan(√3) = π/3,
    sin(π/6) = 1/2."""
    with hiprec.precise():
        pi = hiprec.pi()
        assert str(pi).startswith("3.14159265358979323846264338327950288419716939937510")
        assert abs(hiprec.tan(pi / 4) - 1) < hiprec.D("1e-50")
        assert abs(hiprec.atan(hiprec.sqrt(3)) - pi / 3) < hiprec.D("1e-50")
        assert abs(hiprec.sin(pi / 6) - hiprec.D("0.5")) < hiprec.D("1e-50")
        assert abs(hiprec.cos(pi / 3) - hiprec.D("0.5")) < hiprec.D("1e-50")


# ------------------------------------------------------------------------------ every model


ANALYTIC = {"lambert": {}, "phong": {}, "blinn-phong": {}, "cook-torrance": {"kd": 0.2},
            "oren-nayar": {}, "oren-nayar-simple": {}, "ggx": {"kd": 0.2}, "gltf": {},
            "disney-diffuse": {}, "ue4": {}}


@pytest.mark.parametrize("model", ANALYTIC)
def test_below_the_horizon_is_zero(model):
    """SPEC §2: a BRDF is defined on the upper hemisphere; a direction 1e-6 rad below the
    horizon gives 0 (in either argument)."""
    below = (math.cos(1e-6) * math.cos(0.4), math.cos(1e-6) * math.sin(0.4), -math.sin(1e-6))
    for a, b in ((BACK[0], below), (below, BACK[0])):
        assert np.all(np.asarray(value(model, ANALYTIC[model], a, b)) == 0.0)


@pytest.mark.parametrize("model", [name for name, m in MODELS.items()
                                   if not any(p.kind == "path" for p in m.params)])
def test_below_the_horizon_is_zero_in_a_batch(model):
    """The same for 400 pairs at once (the kernels take other paths for large batches: the
    RGB channels one by one, integer powers by squaring), with kd = 0 where the model has a
    kd (no diffuse term to mask a specular fill): every pair with a direction below the
    horizon is exactly 0, and at the defaults the others are not all 0."""
    rng = np.random.default_rng(7)
    w = rng.normal(size=(2, 400, 3))
    w /= np.linalg.norm(w, axis=-1, keepdims=True)
    w[0, :, 2] = np.abs(w[0, :, 2])
    w[1, ::2, 2] = np.abs(w[1, ::2, 2])  # every other wo above the horizon
    w[1, 1::2, 2] = -np.abs(w[1, 1::2, 2]) - 1e-9  # the others below
    has_kd = any(p.name == "kd" for p in MODELS[model].params)
    for params in ({}, {"kd": 0.0}) if has_kd else ({},):
        for wi, wo in ((w[0], w[1]), (w[1], w[0])):
            f = np.asarray(tuibrdf.evaluate(model, params, wi, wo))
            below = (wi[:, 2] < 0) | (wo[:, 2] < 0)
            assert np.all(f[below] == 0.0), (model, params)
            assert params or np.any(f[~below] > 0.0), model


@pytest.mark.parametrize("model, params, diffuse", [
    ("cook-torrance", {"kd": 0.2}, [0.2 / PI]),
    ("ggx", {"kd": 0.2}, [0.2 / PI]),
    ("gltf", {"base_color": BASE, "metallic": 0.3}, [0.0, 0.0, 0.0]),  # (1 − F) = 0 at ψ = 90°
    ("ue4", {"base_color": BASE, "metallic": 0.3}, [b * 0.7 / PI for b in BASE]),
    ("blinn-phong", {"kd": 0.0, "ks": 0.5, "n": 1.0}, [0.0]),
])
def test_opposite_directions_on_the_horizon_have_no_specular_term(model, params, diffuse):
    """wi = −wo on the horizon: H is undefined; the specular term is 0 there (documented in
    each model's horizon note), leaving the diffuse term."""
    wi = (math.cos(math.radians(200.0)), math.sin(math.radians(200.0)), 0.0)  # z exactly 0
    wo = (-wi[0], -wi[1], 0.0)
    assert_close(value(model, params, wi, wo), diffuse if len(diffuse) > 1 else diffuse[0])


# ------------------------------------------------------------------------------ MERL


# A synthetic table linear in the bin indices, channel c: a_c + b_c·iθh + c_c·iθd + d_c·iφd.
# Bin i's value sits at the bin's centre, bin coordinate i + ½ (SPEC §6), and trilinear
# interpolation of a linear function is the function itself, so at a direction with continuous
# bin coordinates (tθh, tθd, tφd) trilinear gives the linear function at index t − ½, and
# nearest gives it at ⌊t⌋ (bin i covers [i, i + 1)).
LIN = np.array([[0.5, 0.01, 0.003, 0.0005],
                [0.3, 0.02, 0.001, 0.0007],
                [0.2, 0.005, 0.002, 0.0002]])


@pytest.fixture(scope="module")
def linear_merl(tmp_path_factory):
    ih, idd, ip = np.meshgrid(np.arange(90.0), np.arange(90.0), np.arange(180.0), indexing="ij")
    table = np.stack([c[0] + c[1] * ih + c[2] * idd + c[3] * ip for c in LIN])
    return str(write_merl(tmp_path_factory.mktemp("merl") / "linear.binary", table))


def merl_coordinates(wi, wo) -> tuple[float, float, float]:
    """SPEC §6 from its definitions: θh = angle(H, N); d = Rot_y(−θh)·Rot_z(−φh)·wi is wi in
    the frame (T, B, H) with B = (−sin φh, cos φh, 0), T = B × H (the images of x, y, z under
    Rot_z(φh)·Rot_y(θh)), so θd = angle(wi, H), φd = atan2(wi·B, wi·T) folded to [0, π);
    tθh = 90 √(θh/(π/2)), tθd = 90 θd/(π/2), tφd = 180 φd/π."""
    h = half(wi, wo)
    theta_h, phi_h = polar(h), math.atan2(h[1], h[0])
    b = (-math.sin(phi_h), math.cos(phi_h), 0.0)
    t = (b[1] * h[2] - b[2] * h[1], b[2] * h[0] - b[0] * h[2], b[0] * h[1] - b[1] * h[0])
    theta_d = math.acos(dot(wi, h))
    phi_d = math.atan2(dot(wi, b), dot(wi, t))
    if phi_d < 0.0:
        phi_d += PI
    return (90.0 * math.sqrt(theta_h / (PI / 2)), 90.0 * theta_d / (PI / 2), 180.0 * phi_d / PI)


@pytest.mark.parametrize("pair", [NEAR_MIRROR, BACK, SAME, SIDE])
def test_merl_lookups(linear_merl, pair):
    t = merl_coordinates(*pair)
    # interior coordinates, between the first and last bin centres: no end handling
    assert all(0.5 < x < n - 0.5 for x, n in zip(t, (90, 90, 180), strict=True))
    for lookup, coords in (("trilinear", [x - 0.5 for x in t]),
                           ("nearest", [math.floor(x) for x in t])):
        want = [c[0] + c[1] * coords[0] + c[2] * coords[1] + c[3] * coords[2] for c in LIN]
        got = value("merl", {"file": linear_merl, "lookup": lookup}, *pair)
        assert_close(got, want, rtol=1e-10)  # t passes through sqrt/acos: a few ulps of 90
