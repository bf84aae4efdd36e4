"""The stored albedo table ``tuibrdf materials`` reads (issue 15).

Expected values: an independent 1D integral at normal incidence (written here), the bound
a ≥ kd of a Lambert term plus a non-negative lobe, and a fresh computation of the stored
entries (the table is a cache: it must say what the quadrature says today).
"""

from __future__ import annotations

import numpy as np
import pytest

import tuibrdf
from tuibrdf.core.brdf.materials import material_names, table
from tuibrdf.core.sphere import material_albedo as ma


def test_stored_table_lists_every_material_and_matches_a_fresh_computation():
    data = ma.stored()
    assert sorted(data) == sorted(material_names())
    for name in material_names()[::5]:
        for model in ("abc", "sgd"):
            fresh = ma.fit_albedo(model, name)
            np.testing.assert_allclose(data[name][model], fresh, rtol=1e-5, atol=1e-9)


def test_stored_albedo_is_at_least_the_diffuse_term():
    # f = diffuse/π + (a lobe ≥ 0 for abc), and the Lambert term alone has albedo kd:
    # a(θi) ≥ kd for every material and angle; both stay below 1 (no fit creates energy at
    # these angles)
    data = ma.stored()
    for name in material_names():
        kd = table("abc").row(name)["kd"]
        assert np.all(data[name]["abc"] >= kd - 1e-6), name
        for model in ("abc", "sgd"):
            assert np.all(data[name][model] > 0.0) and np.all(data[name][model] < 1.0)


@pytest.mark.parametrize("model", ["abc", "sgd"])
@pytest.mark.parametrize("name", ["steel", "alumina-oxide", "black-obsidian", "blue-fabric",
                                  "gold-metallic-paint"])
def test_rule_matches_a_one_dimensional_integral_at_normal_incidence(model, name):
    # at θi = 0 both fits depend on wo through θo only (H at θo/2, cos θd = cos(θo/2)), so
    # a(0) = 2π ∫ f(θo) cos θo sin θo dθo: a 1D trapezoid on a log-spaced grid (1e-9 to π/2
    # rad, 200,001 points) resolves even steel's α = 5.8e-5 lobe (0.4° wide); an independent
    # reference for the sharpest lobes, which the mesh quadrature only approaches
    t = np.concatenate([[0.0], np.logspace(-9, np.log10(np.pi / 2), 200_001)])
    wo = np.stack([np.sin(t), 0.0 * t, np.cos(t)], axis=-1)  # θo = t at φo = 0
    f = tuibrdf.evaluate(model, {"material": name}, np.array([0.0, 0.0, 1.0]), wo)
    ref = 2 * np.pi * np.trapezoid(f * (np.cos(t) * np.sin(t))[:, None], t, axis=0)
    got = ma.stored()[name][model][0]
    np.testing.assert_allclose(got, ref, rtol=2e-5)


def _albedo_at_normal_incidence(model, name):
    """a(0) = 2π ∫ f(θo) cos θo sin θo dθo by composite 20-point Gauss–Legendre on 2,000
    uniform panels plus 400 log-spaced ones from 1e-9 rad (the sharpest lobes): converged to
    ~3e-14 (doubling the panels moves it by that), far below a 6-digit rounding's margin."""
    x, w = np.polynomial.legendre.leggauss(20)
    edges = np.unique(np.concatenate([[0.0], np.logspace(-9, np.log10(np.pi / 2), 400),
                                      np.linspace(0.0, np.pi / 2, 2000)]))
    a, b = edges[:-1, None], edges[1:, None]
    t = (0.5 * (b - a) * x + 0.5 * (b + a)).ravel()
    wt = (0.5 * (b - a) * w).ravel()
    wo = np.stack([np.sin(t), 0.0 * t, np.cos(t)], axis=-1)
    f = tuibrdf.evaluate(model, {"material": name}, np.array([0.0, 0.0, 1.0]), wo)
    return 2 * np.pi * np.einsum("n,nc->c", wt * np.cos(t) * np.sin(t), f)


@pytest.mark.parametrize("name", ["cherry-235", "pink-fabric2", "pink-jasper",
                                  "light-brown-fabric", "white-fabric2", "steel",
                                  "gold-metallic-paint", "blue-fabric"])
def test_stored_digits_are_correctly_rounded(name):
    """Issue 37 §8: 9 of the 400 stored values were not correctly rounded (abc cherry-235 0°
    blue: 0.0235307 for 0.02353075…).  The stored text at θi = 0 (both fits, every channel) is
    the independent integral rounded to 6 digits, wherever that rounding is decided by more
    than 1e-11 (relative) of the reference (else that value is not checked)."""
    text = {ln.split("\t")[0]: ln.split("\t")[1:] for ln in
            ma.STORED.read_text(encoding="utf-8").splitlines() if not ln.startswith("#")}
    checked = 0
    for k, model in enumerate(("abc", "sgd")):
        ref = _albedo_at_normal_incidence(model, name)
        stored = text[name][6 * k:6 * k + 3]  # θi = 0 columns of this fit
        for r, s in zip(ref, stored, strict=True):
            lo, hi = f"{r * (1 - 1e-11):.6g}", f"{r * (1 + 1e-11):.6g}"
            if lo == hi:
                checked += 1
                assert s == lo, (model, name, s, float(r))
    assert checked >= 5
