"""E(μ, p) tables and E_avg (tuibrdf.core.sphere.energy) against closed forms."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tuibrdf.core.registry import get_model
from tuibrdf.core.sphere import energy


def test_ggx_white_furnace_at_alpha_1_is_one_minus_ln2():
    # height-correlated Smith GGX at α = 1 with F = 1, normal incidence: E = 1 − ln 2
    # (Heitz 2014's G2 with α = 1 makes the integral elementary)
    t = energy.energy_table(get_model("ggx"), {"kd": 0.0, "f0": 1.0}, "alpha", 0.5, 1.0, 2, 3)
    assert t.mu.tolist() == [0.0, 0.5, 1.0]
    assert t.values.tolist() == [0.5, 1.0]
    e, err = t.E[-1, -1], t.error[-1, -1]
    assert abs(e - (1.0 - math.log(2.0))) <= max(err, 1e-12)
    assert err < 1e-6
    # a microfacet model with F = 1 loses energy, never gains it (beyond its error)
    assert np.all(t.E - t.error <= 1.0)
    assert np.all(t.E_avg - t.E_avg_error <= 1.0)


@pytest.mark.parametrize("kd", [0.0, 0.3, 1.0])
def test_lambert_is_kd_everywhere_and_on_average(kd):
    # ∫ kd/π cos θ dω = kd at every incidence; 2∫ kd μ dμ = kd
    t = energy.energy_table(get_model("lambert"), {}, "kd", kd, kd, 1, 7)
    assert np.all(np.abs(t.E - kd) <= np.maximum(t.error, 1e-12))
    assert abs(t.E_avg[0] - kd) <= max(t.E_avg_error[0], 1e-12)


@pytest.mark.parametrize("f, exact", [(lambda m: m * m, 0.5),  # 2∫μ³ = 1/2
                                      (np.sqrt, 0.8),  # 2∫μ^1.5 = 4/5
                                      (lambda m: np.exp(-m), 2.0 - 4.0 / math.e)])
def test_e_avg_rule_on_known_integrands(f, exact):
    # 2∫₀¹ e^{−μ} μ dμ = 2(1 − 2/e)
    def e_of(mu):
        return f(mu), np.zeros_like(mu)

    v, err = energy._avg_panels(e_of)
    assert abs(v - exact) <= max(err, 1e-12) + 1e-10
    assert err < 1e-6


def test_e_avg_error_includes_the_albedos_error():
    def e_of(mu):
        return np.ones_like(mu), np.full_like(mu, 1e-4)

    v, err = energy._avg_panels(e_of)
    assert abs(v - 1.0) < 1e-12
    assert err == pytest.approx(1e-4, rel=1e-9)  # 2∫ 1e-4 μ dμ


def test_grids_include_both_ends():
    assert energy.param_grid(0.001, 1.0, 5, log=True)[[0, -1]].tolist() == [0.001, 1.0]
    g = energy.param_grid(0.001, 1.0, 4, log=True)
    assert np.allclose(g[1:] / g[:-1], 10.0)  # geometric
    assert energy.mu_grid(5).tolist() == [0.0, 0.25, 0.5, 0.75, 1.0]
    assert energy.theta_of_mu(np.array([0.0, 1.0])).tolist() == [90.0, 0.0]


@pytest.mark.parametrize("name, lo, hi, n, log, msg", [
    ("fresnel", 0, 1, 2, False, "a choice"),
    ("nope", 0, 1, 2, False, "unknown parameter"),
    ("alpha", 0.5, 0.5, 2, False, "empty"),
    ("alpha", 0.9, 0.5, 2, False, "empty"),
    ("alpha", 0.5, 2.0, 2, False, "invalid"),
])
def test_bad_requests(name, lo, hi, n, log, msg):
    with pytest.raises(ValueError, match=msg):
        energy.check_table(get_model("ggx"), name, lo, hi, n, 4, log)
