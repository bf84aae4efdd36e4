"""The χ² sampling test (tuibrdf.core.sphere.chi2) and the GGX VNDF sampler."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from tuibrdf.core.brdf.sampling import GGX_VNDF, Sampler, ggx_pdf, ggx_sample
from tuibrdf.core.directions import incident
from tuibrdf.core.registry import get_model
from tuibrdf.core.sphere import chi2


@pytest.mark.parametrize("x", [0.01, 0.5, 2.5, 10.0, 40.0])
def test_gamma_q_closed_forms(x):
    # Q(1, x) = e^{−x}; χ² with 1 dof: P(χ² ≥ s) = erfc(√(s/2)); with 2 dof: e^{−s/2};
    # Q(3, x) = e^{−x}(1 + x + x²/2)
    assert chi2.gamma_q(1.0, x) == pytest.approx(math.exp(-x), rel=1e-12, abs=1e-300)
    assert chi2.chi2_sf(x, 1) == pytest.approx(math.erfc(math.sqrt(x / 2)), rel=1e-10,
                                               abs=1e-300)
    assert chi2.chi2_sf(x, 2) == pytest.approx(math.exp(-x / 2), rel=1e-12)
    assert chi2.gamma_q(3.0, x) == pytest.approx(math.exp(-x) * (1 + x + x * x / 2), rel=1e-12)


def test_chi2_sf_large_dof_is_near_one_half_at_the_mean():
    # the χ² distribution's median is ≈ k(1 − 2/(9k))³ (Wilson–Hilferty)
    k = 800
    assert chi2.chi2_sf(k * (1 - 2 / (9 * k)) ** 3, k) == pytest.approx(0.5, abs=2e-3)


def test_pearson_pools_low_cells():
    obs = np.array([100.0, 90.0, 1.0, 2.0, 3.0])
    exp = np.array([95.0, 95.0, 2.0, 2.0, 2.0])  # the three low cells pool into (6, 6)
    stat, dof = chi2.pearson(obs, exp)
    assert dof == 2
    assert stat == pytest.approx(25 / 95 + 25 / 95 + 0.0)


def test_vndf_pdf_is_normalised_over_the_sphere():
    # ∫ pdf over the whole sphere = 1 (the reflection of visible normals covers both
    # hemispheres); Monte Carlo with uniform directions, 4σ
    rng = np.random.default_rng(5)
    n = 400_000
    z = 2 * rng.random(n) - 1
    phi = 2 * np.pi * rng.random(n)
    s = np.sqrt(1 - z * z)
    wo = np.stack([s * np.cos(phi), s * np.sin(phi), z], axis=-1)
    wi = np.broadcast_to(incident(50.0, 180.0), wo.shape)
    p = ggx_pdf(wi, wo, 0.0, 0.04, 0.5, "exact") * 4 * np.pi
    assert abs(p.mean() - 1.0) < 4 * p.std() / math.sqrt(n)


def test_vndf_at_normal_incidence_has_the_ggx_mean_cosine():
    # at normal incidence the visible normals are D(h) cos θh: E[cos θh] = ∫ D cos² dω,
    # which for GGX α = 1 is the uniform-hemisphere... D = 1/π: ∫ cos²/π dω = 2/3
    rng = np.random.default_rng(3)
    n = 200_000
    wi = np.broadcast_to([0.0, 0.0, 1.0], (n, 3))
    wo, _ = ggx_sample(wi, rng.random(n), rng.random(n), 0.0, 1.0, 1.0, "exact")
    h = wo + wi
    h /= np.linalg.norm(h, axis=-1, keepdims=True)
    assert abs(h[:, 2].mean() - 2 / 3) < 4 * h[:, 2].std() / math.sqrt(n)


@pytest.mark.parametrize("params", [{}, {"kd": 0.5}, {"alpha": 1.0}, {"alpha": 0.5,
                                                                      "f0": 1.0}])
def test_ggx_sampler_passes(params):
    m = get_model("ggx")
    assert m.sampler is GGX_VNDF
    v = chi2.chi2_test(m, m.resolve(params), seed=11)
    assert v.resolved and v.ok, v


def _wrong_pdf(wi, wo, **kw):
    # ×1.1 where wo points to +y: one half of the hemisphere
    return ggx_pdf(wi, wo, **kw) * np.where(np.asarray(wo)[..., 1] > 0, 1.1, 1.0)


def _wrong_sample(wi, u1, u2, **kw):
    wo, _ = ggx_sample(wi, u1, u2, **kw)
    return wo, _wrong_pdf(wi, wo, **kw)


def test_a_pdf_wrong_by_ten_percent_in_one_half_fails():
    m = replace(get_model("ggx"), sampler=Sampler(_wrong_sample, _wrong_pdf))
    v = chi2.chi2_test(m, m.resolve({}), seed=11)
    assert v.resolved and not v.ok and v.p_value < 1e-12


def test_a_sample_pdf_disagreeing_with_pdf_fails():
    def sample(wi, u1, u2, **kw):
        wo, p = ggx_sample(wi, u1, u2, **kw)
        return wo, 2 * p

    m = replace(get_model("ggx"), sampler=Sampler(sample, ggx_pdf))
    v = chi2.chi2_test(m, m.resolve({}), seed=11)
    assert not v.ok and max(r.pdf_mismatch for r in v.results) == pytest.approx(0.5)


def test_maps_are_densities():
    m = get_model("ggx")
    r = chi2.chi2_at(m, m.resolve({"alpha": 1.0}), 30.0, seed=2)
    inside = np.isfinite(r.pdf_map)
    assert r.pdf_map.shape == (chi2.RES, chi2.RES)
    # the histogram's density and the pdf's agree pixel by pixel within sampling noise:
    # summed over the map, 2e5 samples leave ~0.3 % (4σ: 1.2 %)
    assert abs(np.nansum(r.hist_map) / np.nansum(r.pdf_map) - 1) < 0.012
    # and the interior pixels sum to the hemisphere's share: Σ density × pixel sr ≤ 1 − lost
    pix = (2 * math.sqrt(2) / chi2.RES) ** 2
    assert np.nansum(r.pdf_map) * pix >= (1 - r.lost) - 0.01
    assert np.all(r.pdf_map[inside] >= 0)


# -- the sampler against an independent scalar implementation --------------------------------
def _vndf_reference(wi, u1, u2, a):
    """Heitz 2018 ("Sampling the GGX Distribution of Visible Normals", JCGT 7(4), listing 1),
    isotropic α, written again with the math module, one sample at a time."""
    vx, vy, vz = a * wi[0], a * wi[1], wi[2]
    n = math.sqrt(vx * vx + vy * vy + vz * vz)
    vx, vy, vz = vx / n, vy / n, vz / n
    lensq = vx * vx + vy * vy
    t1 = (-vy / math.sqrt(lensq), vx / math.sqrt(lensq), 0.0) if lensq > 0 else (1.0, 0.0, 0.0)
    t2 = (vy * t1[2] - vz * t1[1], vz * t1[0] - vx * t1[2], vx * t1[1] - vy * t1[0])
    r, phi = math.sqrt(u1), 2 * math.pi * u2
    p1, p2 = r * math.cos(phi), r * math.sin(phi)
    s = (1 + vz) / 2
    p2 = (1 - s) * math.sqrt(1 - p1 * p1) + s * p2
    p3 = math.sqrt(max(0.0, 1 - p1 * p1 - p2 * p2))
    nh = [p1 * t1[k] + p2 * t2[k] + p3 * v for k, v in enumerate((vx, vy, vz))]
    ne = (a * nh[0], a * nh[1], max(0.0, nh[2]))
    m = math.sqrt(sum(c * c for c in ne))
    return [c / m for c in ne]


def _pdf_reference(wi, wo, kd, a):
    """The density of the reflected visible normals, D_wi(h) / (4 wo·h) with
    D_wi(h) = G1(wi) max(0, wi·h) D(h) / cos θi and wo·h = wi·h, plus a cosine lobe with half
    the samples when kd > 0 (docs/reference/formats.md)."""
    hx, hy, hz = (wi[k] + wo[k] for k in range(3))
    n = math.sqrt(hx * hx + hy * hy + hz * hz)
    hz /= n
    ci = wi[2]
    tan2 = (wi[0] ** 2 + wi[1] ** 2) / (ci * ci)
    g1 = 2 / (1 + math.sqrt(1 + a * a * tan2))
    d = a * a / (math.pi * (hz * hz * (a * a - 1) + 1) ** 2)
    spec = g1 * d / (4 * ci) if hz > 0 else 0.0
    if kd > 0:
        return 0.5 * spec + 0.5 * max(wo[2], 0.0) / math.pi
    return spec


def test_the_vndf_sampler_is_heitz_2018_and_its_pdf_is_the_reflected_density():
    rng = np.random.default_rng(11)
    for a in (0.05, 0.3, 1.0):
        for theta, phi in ((0.0, 180.0), (35.0, 180.0), (80.0, 140.0), (50.0, -65.0)):
            wi = incident(theta, phi)
            u1, u2 = rng.random(64), rng.random(64)
            wo, pdf = ggx_sample(np.broadcast_to(wi, (64, 3)), u1, u2, 0.0, 1.0, a, "exact")
            for k in range(64):
                h = _vndf_reference(wi, u1[k], u2[k], a)
                dot = sum(wi[j] * h[j] for j in range(3))
                ref = [2 * dot * h[j] - wi[j] for j in range(3)]  # wi reflected about h
                # a unit vector from a dozen rounded operations: 1e-12 is generous
                assert np.allclose(wo[k], ref, atol=1e-12), (a, theta, k)
                if ref[2] > 1e-6:
                    assert pdf[k] == pytest.approx(_pdf_reference(wi, ref, 0.0, a), rel=1e-10)
            for kd in (0.0, 0.5):  # the mixture's density at other directions too
                wo2 = incident(25.0, 30.0)
                got = float(ggx_pdf(wi, wo2, kd, 0.04, a, "exact"))
                if theta < 90.0:
                    assert got == pytest.approx(_pdf_reference(wi, wo2, kd, a), rel=1e-12)


def test_with_a_diffuse_term_half_the_samples_are_cosine_weighted():
    """kd > 0: u1 < ½ picks the cosine lobe with u1/½ (Malley: the disc point (√u, 2πu2)
    lifted to the hemisphere), u1 ≥ ½ the visible normals with (u1 − ½)/½."""
    rng = np.random.default_rng(12)
    wi = incident(40.0, 120.0)
    u1, u2 = rng.random(64), rng.random(64)
    wo, _ = ggx_sample(np.broadcast_to(wi, (64, 3)), u1, u2, 0.5, 0.04, 0.3, "exact")
    for k in range(64):
        if u1[k] < 0.5:
            u = u1[k] / 0.5
            r, phi = math.sqrt(u), 2 * math.pi * u2[k]
            ref = [r * math.cos(phi), r * math.sin(phi), math.sqrt(1 - u)]
        else:
            h = _vndf_reference(wi, (u1[k] - 0.5) / 0.5, u2[k], 0.3)
            dot = sum(wi[j] * h[j] for j in range(3))
            ref = [2 * dot * h[j] - wi[j] for j in range(3)]
        assert np.allclose(wo[k], ref, atol=1e-12), k
