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
