"""Every analytic model against expectations derived independently of its code: closed forms,
published limits, normalisation integrals, the seed's qualitative remarks.

Integrals use the tensor Gauss-Legendre rule of ``tests/quad.py`` (not the icosahedral mesh).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import tuibrdf
from tests.quad import albedo, gauss, hemisphere_rule
from tuibrdf.core.brdf.fresnel import fresnel_exact, fresnel_schlick
from tuibrdf.core.brdf.microfacet import beckmann_d, ggx_d, ggx_lambda_cos
from tuibrdf.core.directions import from_degrees, incident
from tuibrdf.core.registry import MODELS

ANALYTIC = [name for name, m in MODELS.items() if not any(p.kind == "path" for p in m.params)]


# -- Lambert -------------------------------------------------------------------------------


@pytest.mark.parametrize("kd", [0.0, 0.18, 0.5, 1.0])
@pytest.mark.parametrize("theta_i", [0.0, 37.0, 89.0])
def test_lambert_albedo_is_kd(kd, theta_i):
    # ∫ kd/π cos θ dω = kd exactly; the GL rule in u = cos θ is exact for polynomials
    assert albedo("lambert", {"kd": kd}, theta_i) == pytest.approx(kd, abs=1e-13)


def test_lambert_is_constant_and_zero_below_horizon():
    wo = from_degrees([0, 30, 90, 90, 120], [0, 45, 0, 180, 0])
    f = tuibrdf.evaluate("lambert", {"kd": 0.5}, incident(40), wo)
    np.testing.assert_array_equal(f[:4], 0.5 / math.pi)
    assert f[4] == 0.0  # θo = 120°: below the surface


# -- Fresnel -------------------------------------------------------------------------------


def fresnel_textbook(theta: float, n: float) -> float:
    """Unpolarised Fresnel reflectance air → index n from Snell's law (Hecht, Optics §4.6)."""
    st = math.sin(theta) / n
    ct = math.sqrt(1.0 - st * st)
    ci = math.cos(theta)
    rs = (ci - n * ct) / (ci + n * ct)
    rp = (n * ci - ct) / (n * ci + ct)
    return 0.5 * (rs * rs + rp * rp)


@pytest.mark.parametrize("f0", [0.02, 0.04, 0.2, 0.5, 0.9])
def test_fresnel_exact_normal_and_grazing(f0):
    assert float(fresnel_exact(1.0, f0)) == pytest.approx(f0, rel=1e-14)
    assert float(fresnel_exact(0.0, f0)) == pytest.approx(1.0, abs=1e-15)  # F(ψ = 90°) = 1
    assert float(fresnel_schlick(1.0, f0)) == pytest.approx(f0, rel=1e-15)
    assert float(fresnel_schlick(0.0, f0)) == 1.0


@pytest.mark.parametrize("n", [1.33, 1.5, 2.4])
@pytest.mark.parametrize("theta_deg", [10.0, 45.0, 70.0, 85.0])
def test_fresnel_exact_matches_snell_form(n, theta_deg):
    f0 = ((n - 1) / (n + 1)) ** 2
    got = float(fresnel_exact(math.cos(math.radians(theta_deg)), f0))
    assert got == pytest.approx(fresnel_textbook(math.radians(theta_deg), n), rel=1e-12)


def test_fresnel_glass_brewster():
    # at Brewster's angle rp = 0, so F = rs²/2; for n = 1.5 published R ≈ 0.0739 at 56.31°
    f0 = 0.04
    theta_b = math.atan(1.5)
    assert float(fresnel_exact(math.cos(theta_b), f0)) == pytest.approx(0.0739, abs=5e-4)


def test_fresnel_ends_of_range():
    c = np.linspace(0, 1, 11)
    np.testing.assert_array_equal(fresnel_exact(c, 0.0), 0.0)
    np.testing.assert_array_equal(fresnel_exact(c, 1.0), 1.0)


# -- Phong-type lobes -----------------------------------------------------------------------


@pytest.mark.parametrize("n", [0.0, 1.0, 5.0, 20.0, 70.0, 500.0])
def test_phong_albedo_normal_incidence_is_one(n):
    # kd=0, ks=1, θi=0: S = N, a = (n+2)/(2π) ∫ cos^(n+1) θ dω = (n+2)/(2π)·2π/(n+2) = 1
    # (GL in u with 400 nodes is exact for u^(n+1) up to degree 799; numpy's nodes carry
    # ~1e-14 relative error, which u^501 amplifies ~500×)
    a = albedo("phong", {"kd": 0.0, "ks": 1.0, "n": n}, 0.0, n_u=400, n_phi=8)
    assert a == pytest.approx(1.0, abs=1e-11)


def test_phong_peak_value_on_mirror():
    # f(S) = kd/π + ks (n+2)/(2π) exactly, for any θi
    for t in (0.0, 30.0, 75.0):
        wi = incident(t)
        s = np.array([-wi[0], -wi[1], wi[2]])
        f = tuibrdf.evaluate("phong", {"kd": 0.1, "ks": 0.4, "n": 70}, wi, s)
        assert f == pytest.approx(0.1 / math.pi + 0.4 * 72 / (2 * math.pi), rel=1e-13)


def test_blinn_phong_on_mirror_is_normalisation():
    # wo = mirror ⇒ H = N ⇒ N·H = 1: f = kd/π + ks (n+8)/(8π)
    wi = incident(50.0)
    s = np.array([-wi[0], 0.0, wi[2]])
    f = tuibrdf.evaluate("blinn-phong", {"kd": 0.0, "ks": 1.0, "n": 100}, wi, s)
    assert f == pytest.approx(108 / (8 * math.pi), rel=1e-12)


# -- microfacet distributions and masking ------------------------------------------------


@pytest.mark.parametrize("alpha", [0.001, 0.01, 0.1, 0.5, 1.0])
def test_ggx_d_projected_area_is_one(alpha):
    # ∫ D(h) cos θh dω = 1.  Substitute tan θh = α tan ψ: the integrand becomes
    # 2π D cosθh sinθh dθh/dψ, smooth on ψ ∈ [0, π/2]; analytically it is 2π sinψ cosψ/π·π...
    psi, w = gauss(0.0, math.pi / 2, 200)
    th = np.arctan(alpha * np.tan(psi))
    dth = alpha / np.cos(psi) ** 2 / (1 + (alpha * np.tan(psi)) ** 2)
    d = ggx_d(np.cos(th) ** 2, np.sin(th) ** 2, alpha)
    total = np.sum(w * 2 * np.pi * d * np.cos(th) * np.sin(th) * dth)
    assert total == pytest.approx(1.0, abs=1e-12)


@pytest.mark.parametrize("m", [0.001, 0.01, 0.07, 0.3, 1.0])
def test_beckmann_d_projected_area_is_one(m):
    # tan θh = m t, t ∈ [0, 40] in panels (exp(−t²) is negligible beyond); exact value 1
    edges = np.linspace(0.0, 40.0, 41)
    total = 0.0
    for a, b in zip(edges[:-1], edges[1:], strict=True):
        t, w = gauss(a, b, 40)
        th = np.arctan(m * t)
        dth = m / (1 + (m * t) ** 2)
        d = beckmann_d(np.cos(th) ** 2, np.sin(th) ** 2, m)
        total += np.sum(w * 2 * np.pi * d * np.cos(th) * np.sin(th) * dth)
    assert total == pytest.approx(1.0, abs=1e-10)


@pytest.mark.parametrize("alpha", [0.1, 0.3, 0.7, 1.0])
@pytest.mark.parametrize("theta_o", [0.0, 30.0, 60.0, 80.0])
def test_smith_g1_weak_white_furnace(alpha, theta_o):
    # Heitz 2014 eq. 4: ∫ G1(wo) max(0, wo·h) D(h) dωh = cos θo for the Smith G1 of D
    psi, wpsi = gauss(0.0, math.pi / 2, 160)
    th = np.arctan(alpha * np.tan(psi))
    dth = alpha / np.cos(psi) ** 2 / (1 + (alpha * np.tan(psi)) ** 2)
    phi, wphi = gauss(0.0, 2 * math.pi, 160)
    th_g, phi_g = np.meshgrid(th, phi, indexing="ij")
    h = np.stack([np.sin(th_g) * np.cos(phi_g), np.sin(th_g) * np.sin(phi_g), np.cos(th_g)], -1)
    wo = from_degrees(theta_o, 0.0)
    d = ggx_d(np.cos(th_g) ** 2, np.sin(th_g) ** 2, alpha)
    co, s2o = math.cos(math.radians(theta_o)), math.sin(math.radians(theta_o)) ** 2
    g1 = co / (co + ggx_lambda_cos(co, s2o, alpha))  # G1 = 1/(1 + Λ)
    integrand = g1 * np.maximum(0.0, h @ wo) * d * np.sin(th_g)
    total = np.einsum("i,ij,j->", wpsi * dth, integrand, wphi)
    # the max(0, ·) kink limits the tensor rule to ~1e-5 at grazing θo
    assert total == pytest.approx(math.cos(math.radians(theta_o)), abs=2e-5)


# -- Oren-Nayar ----------------------------------------------------------------------------


@pytest.mark.parametrize("name", ["oren-nayar", "oren-nayar-simple"])
def test_oren_nayar_tends_to_lambert(name):
    # A → 1, B, C3 and the interreflection term → 0 as σ²: |f − kd/π| = O(σ²)
    wo = from_degrees(np.linspace(0, 89, 30), np.linspace(-180, 180, 30))
    wi = incident(60.0)
    errors = []
    for sigma_deg in (4.0, 2.0, 1.0):
        f = tuibrdf.evaluate(name, {"kd": 0.8, "sigma": sigma_deg}, wi, wo)
        errors.append(np.max(np.abs(f - 0.8 / math.pi)))
    assert errors[0] > 3.5 * errors[1] > 3.5**2 * errors[2]  # quadratic convergence
    f0 = tuibrdf.evaluate(name, {"kd": 0.8, "sigma": 0.0}, wi, wo)
    np.testing.assert_allclose(f0, 0.8 / math.pi, rtol=1e-15)


def test_oren_nayar_backscatter_exceeds_forward():
    # rough surfaces look brighter toward the light (Oren & Nayar 1994, fig. 7)
    wi = incident(60.0)
    back, fwd = tuibrdf.evaluate("oren-nayar", {"sigma": 30}, wi, from_degrees([60, 60], [180, 0]))
    assert back > fwd > 0


def test_oren_nayar_simple_published_form():
    # direct transcription of the simplified formula at one configuration
    s = math.radians(20.0)
    a = 1 - 0.5 * s * s / (s * s + 0.33)
    b = 0.45 * s * s / (s * s + 0.09)
    ti, to, dphi = math.radians(30), math.radians(50), math.radians(180 - 40)
    expected = 0.8 / math.pi * (a + b * max(0, math.cos(dphi)) * math.sin(to) * math.tan(ti))
    wo = from_degrees(50.0, 40.0)  # wi at φ = 180°: Δφ = 140°, cos < 0 ⇒ only A
    got = tuibrdf.evaluate("oren-nayar-simple", {"kd": 0.8, "sigma": 20}, incident(30), wo)
    assert got == pytest.approx(expected, rel=1e-13)
    wo2 = from_degrees(50.0, 180.0 - 10.0)  # Δφ = 10°
    expected2 = 0.8 / math.pi * (a + b * math.cos(math.radians(10)) * math.sin(to) * math.tan(ti))
    got2 = tuibrdf.evaluate("oren-nayar-simple", {"kd": 0.8, "sigma": 20}, incident(30), wo2)
    assert got2 == pytest.approx(expected2, rel=1e-13)


# -- Disney diffuse ------------------------------------------------------------------------


def test_disney_diffuse_normal_incidence_is_base_over_pi_times_fd90_factors():
    # θi = θo = 0: both Schlick factors are 1 ⇒ f = base/π exactly, whatever the roughness
    f = tuibrdf.evaluate("disney-diffuse", {"base_color": (0.2, 0.5, 0.9), "roughness": 0.7},
                         incident(0.0), from_degrees(0.0, 0.0))
    np.testing.assert_allclose(f, np.array([0.2, 0.5, 0.9]) / math.pi, rtol=1e-15)


def test_disney_diffuse_grazing_retroreflection():
    # θi = θo = 90°, wo = wi: θd = 0, FD90 = 0.5 + 2r; f = base/π FD90²
    wi = incident(90.0)
    r = 0.8
    f = tuibrdf.evaluate("disney-diffuse", {"base_color": 1.0, "roughness": r}, wi, wi)
    np.testing.assert_allclose(f, (0.5 + 2 * r) ** 2 / math.pi, rtol=1e-13)


# -- Cook-Torrance, GGX, glTF, UE4 ----------------------------------------------------------


def plane_of_incidence(model, params, theta_i, n=9001):
    """θr (signed, φ = 0 side positive) and f along the plane of incidence."""
    t = np.linspace(-89.99, 89.99, n)
    wo = from_degrees(np.abs(t), np.where(t >= 0, 0.0, 180.0))
    return t, tuibrdf.evaluate(model, params, incident(theta_i), wo)


def test_cook_torrance_peak_grows_and_shifts_past_mirror_at_grazing():
    # the seed: "the lobe's maximum increases and moves away from the mirror direction
    # toward the horizon as incidence becomes grazing" (off-specular peak, Torrance-Sparrow)
    params = {"kd": 0.0, "f0": 0.04, "m": 0.07}
    peaks, shifts = [], []
    for ti in (0.0, 30.0, 60.0, 75.0, 85.0):
        t, f = plane_of_incidence("cook-torrance", params, ti)
        k = int(np.argmax(f))
        peaks.append(f[k])
        shifts.append(t[k] - ti)
    assert all(b > a for a, b in zip(peaks, peaks[1:], strict=False))
    assert abs(shifts[0]) < 0.01  # normal incidence: the peak is on the mirror
    assert shifts[-1] > 1.0 and shifts[-1] > shifts[-2] > 0  # past the mirror, growing


@pytest.mark.parametrize("model,params", [
    ("cook-torrance", {"kd": 0.0, "f0": 1.0, "m": 0.3}),
    ("ggx", {"kd": 0.0, "f0": 1.0, "alpha": 0.3}),
])
def test_specular_peak_at_normal_incidence_closed_form(model, params):
    # θi = θo = 0: H = N, F = 1 (f0 = 1), G = 1, D(0) = 1/(π m²) (Beckmann) or 1/(π α²) (GGX)
    f = tuibrdf.evaluate(model, params, incident(0.0), from_degrees(0.0, 0.0))
    width = params.get("m", params.get("alpha"))
    assert f == pytest.approx(1.0 / (math.pi * width**2) / 4.0, rel=1e-13)


def test_ggx_white_furnace_closed_form_alpha_one():
    # F = 1, kd = 0, α = 1, θi = 0: D = 1/π, Λi = 0, Λo = (sec θo − 1)/2, so
    # G2 = 2 cos θo/(1 + cos θo), f = 1/(2π(1 + cos θo)), a = ∫₀¹ u/(1+u) du = 1 − ln 2
    a = albedo("ggx", {"kd": 0.0, "f0": 1.0, "alpha": 1.0}, 0.0, 64, 8)
    assert a == pytest.approx(1.0 - math.log(2.0), abs=1e-13)


def test_ggx_white_furnace_loses_energy_monotonically():
    # Smith masking only removes energy: a ≤ 1, decreasing with α, → 1 as α → 0
    a = [albedo("ggx", {"kd": 0.0, "f0": 1.0, "alpha": al}, 30.0, 200, 256)
         for al in (0.02, 0.1, 0.3, 0.6, 1.0)]
    assert all(x <= 1.0 for x in a)
    assert all(y < x for x, y in zip(a, a[1:], strict=False))
    assert a[0] > 0.99


@pytest.mark.parametrize("metallic,expect_f0", [(0.0, 0.04), (1.0, None)])
def test_gltf_metal_rough_mixing(metallic, expect_f0):
    # θi = θo = 0: F = F0 = mix(0.04, base, metallic); D = 1/(π α²), G2 = 1
    base = np.array([0.9, 0.5, 0.1])
    r = 0.5
    f = tuibrdf.evaluate("gltf", {"base_color": tuple(base), "metallic": metallic,
                                  "roughness": r}, incident(0.0), from_degrees(0.0, 0.0))
    f0 = np.full(3, 0.04) if expect_f0 is not None else base
    c_diff = base * (1 - metallic)
    expected = (1 - f0) * c_diff / math.pi + f0 / (math.pi * (r * r) ** 2) / 4
    np.testing.assert_allclose(f, expected, rtol=1e-13)


def test_ue4_normal_incidence():
    # Karis 2013: G1(1) = 1/(1−k+k) = 1 ⇒ f = c_diff/π + F0 D(0)/4 with D(0) = 1/(π α²)
    base = np.array([0.3, 0.6, 0.9])
    f = tuibrdf.evaluate("ue4", {"base_color": tuple(base), "metallic": 0.0, "roughness": 0.6},
                         incident(0.0), from_degrees(0.0, 0.0))
    expected = base / math.pi + 0.04 / (math.pi * 0.36**2) / 4
    np.testing.assert_allclose(f, expected, rtol=1e-13)


# -- API shapes and validation -------------------------------------------------------------


@pytest.mark.parametrize("name", ANALYTIC)
def test_shapes_broadcast(name):
    m = MODELS[name]
    wi = incident(30.0)
    wo = from_degrees(np.zeros((4, 5)) + 20.0, np.zeros((4, 5)))
    f = tuibrdf.evaluate(name, {}, wi, wo)
    assert f.shape == ((4, 5, 3) if m.rgb else (4, 5))


@pytest.mark.parametrize("params,needle", [
    ({"kd": 1.5}, "kd"),
    ({"kd": float("nan")}, "[0, 1]"),
    ({"ks": -0.1}, "ks"),
    ({"nn": 3}, "did you mean 'n'"),
    ({"kd": 0.6, "ks": 0.6}, "kd + ks ≤ 1"),
])
def test_invalid_parameters_name_the_parameter(params, needle):
    with pytest.raises(ValueError, match=None) as e:
        tuibrdf.evaluate("phong", params, incident(0), incident(0))
    assert needle in str(e.value)


def test_unknown_model_suggests():
    with pytest.raises(ValueError) as e:
        tuibrdf.evaluate("cook-torance", {}, incident(0), incident(0))
    assert "cook-torrance" in str(e.value)


def test_directions_validated():
    with pytest.raises(ValueError, match="shape"):
        tuibrdf.evaluate("lambert", {}, [0, 0, 1], [0, 1])
    with pytest.raises(ValueError, match="NaN"):
        tuibrdf.evaluate("lambert", {}, [0, 0, 1], [0, float("nan"), 1])


def test_hemisphere_rule_sanity():
    # the reference rule itself: ∫ dω = 2π, ∫ cos dω = π over the hemisphere
    d, w = hemisphere_rule()
    assert w.sum() == pytest.approx(2 * math.pi, rel=1e-14)
    assert (w * d[:, 2]).sum() == pytest.approx(math.pi, rel=1e-14)


def test_a_parameter_name_means_one_declaration():
    """Parameters shared by several models are declared once (core/models/common_params.py):
    wherever a name recurs, only its default and one-line doc may differ."""
    seen = {}
    for m in MODELS.values():
        for p in m.params:
            key = (p.symbol, p.kind, p.min, p.max, p.step, p.unit, p.choices, p.coarse_step)
            assert seen.setdefault(p.name, (m.name, key))[1] == key, (
                f"{p.name}: {m.name} and {seen[p.name][0]} declare it differently")
