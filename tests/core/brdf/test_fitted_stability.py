"""Stability of the fitted MERL models over all 200 (model, material) pairs (issue 15).

``tests/core/brdf/test_stability.py`` already sweeps every registered model at each end of every
parameter, which for ``abc`` and ``sgd`` means every material (a choice's ends are all its
values).  This file adds a denser grid of hard directions for each of the 200 pairs and checks
the documented horizon values (``docs/reference/materials.md``): finite, ≥ 0, no floating-point
exception (the kernels run under the raising errstate), reciprocal to 1e-12 of the batch's maximum.
"""

from __future__ import annotations

import numpy as np
import pytest

from tuibrdf.core.brdf.materials import material_names, table
from tuibrdf.core.directions import from_degrees, mirror
from tuibrdf.core.evaluate import evaluate_resolved
from tuibrdf.core.registry import MODELS

HAIR = 1e-9
THETAS = [0.0, HAIR, 1.0, 30.0, 60.0, 85.0, 89.0, 89.9, 90.0 - 1e-6, 90.0 - HAIR, 90.0]
PHIS = [0.0, 45.0, 90.0, 180.0, 270.0]
PAIRS = [(m, name) for m in ("abc", "sgd") for name in material_names()]


def hard_pairs() -> tuple[np.ndarray, np.ndarray]:
    t, p = np.meshgrid(THETAS, PHIS, indexing="ij")
    d = from_degrees(t.ravel(), p.ravel())
    wi = np.repeat(d, len(d), axis=0)
    wo = np.tile(d, (len(d), 1))
    horizon = from_degrees(90.0, np.array(PHIS))
    opposite = horizon * np.array([-1.0, -1.0, 1.0])  # wi = −wo on the horizon: H undefined
    wi = np.concatenate([wi, d, d, horizon])
    wo = np.concatenate([wo, d, mirror(d), opposite])  # wo = wi, then H = N (wo = S)
    return wi, wo


WI, WO = hard_pairs()


@pytest.mark.parametrize(("model", "material"), PAIRS, ids=[f"{m}-{n}" for m, n in PAIRS])
def test_finite_nonnegative_reciprocal_on_hard_directions(model, material):
    m = MODELS[model]
    values = {"material": material}
    f = np.asarray(evaluate_resolved(m, values, WI, WO))  # raises on any FP exception
    g = np.asarray(evaluate_resolved(m, values, WO, WI))
    assert f.shape == (len(WI), 3)
    assert np.all(np.isfinite(f)) and np.all(f >= 0.0)
    assert np.max(np.abs(f - g)) <= 1e-12 * np.max(f)


@pytest.mark.parametrize("material", material_names())
def test_horizon_values_are_the_documented_ones(material):
    n = np.array([0.0, 0.0, 1.0])
    h = from_degrees(90.0, 0.0)
    # sgd: on the horizon the specular term (no limit: it diverges like 1/cos θ) is 0 and the
    # diffuse term ρd/π remains, for θo = 90° and for both at 90°
    rho_d = table("sgd").row(material)["rho_d"]
    for wi, wo in ((n, h), (h, h), (from_degrees(40.0, 180.0), h)):
        f = evaluate_resolved(MODELS["sgd"], {"material": material}, wi, wo)
        np.testing.assert_array_equal(f, rho_d / np.pi)
    # abc: where one direction is on the horizon, the V-cavity limit: the value at 90° equals
    # the limit of values approaching it (G/cos θo stays finite)
    wi = from_degrees(40.0, 180.0)
    near = [evaluate_resolved(MODELS["abc"], {"material": material}, wi, from_degrees(t, 0.0))
            for t in (90.0 - 1e-5, 90.0 - 1e-7)]
    at = evaluate_resolved(MODELS["abc"], {"material": material}, wi, h)
    np.testing.assert_allclose(at, near[1], rtol=1e-6)
    np.testing.assert_allclose(near[0], near[1], rtol=1e-4)
    # abc with both on the horizon (different azimuths): specular 0, kd/π remains
    both = evaluate_resolved(MODELS["abc"], {"material": material}, h, from_degrees(90.0, 90.0))
    np.testing.assert_array_equal(both, table("abc").row(material)["kd"] / np.pi)


def test_below_the_horizon_is_zero():
    below = from_degrees(120.0, 0.0)
    for model, material in PAIRS[::17]:
        f = evaluate_resolved(MODELS[model], {"material": material}, below, np.array([0, 0, 1.0]))
        assert np.all(f == 0.0)
