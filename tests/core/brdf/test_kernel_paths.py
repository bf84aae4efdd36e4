"""The kernels' fast paths agree with the plain ones (issue 16).

Each fast path computes the same formula in a different layout or order, chosen by the size
of the call or a parameter's value; the expected values here come from the other path, or
from numpy's ``pow`` and an independent Fresnel formula, never from the path under test:

* ``evaluate_resolved`` evaluates a direction broadcast along every axis (zero strides) once;
  the same call with that direction materialised as a full array is the reference;
* :class:`~tuibrdf.core.directions.Geometry` works on ``(…, 3)`` arrays for a few points and on
  components for many (``PACKED_MAX``); both are forced here and compared;
* RGB models compute their channels together for a few points and one at a time for many
  (``rgb.TOGETHER_MAX``); both are forced and compared (abc and sgd compute theirs as the rows
  of ``(3, M)`` arrays at every size: tests/core/brdf/test_fitted.py compares them with the plain
  formulas);
* ``lobe_power`` takes an integer exponent ≤ 64 by repeated squaring: against ``np.power``,
  within the bound its docstring states (n·2⁻⁵³ relative);
* ``fresnel_dielectric`` skips the total-reflection masks for η > 1: against the textbook
  s/p form with the refraction angle (Born & Wolf §1.5.2), a different formula;
* ``safe_div`` on scalars branches instead of dividing under a mask.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from tests import hiprec
from tuibrdf.core import directions as frame
from tuibrdf.core.brdf import rgb
from tuibrdf.core.brdf.fitted import fresnel_dielectric
from tuibrdf.core.brdf.phong import INT_POWER_MAX, lobe_power
from tuibrdf.core.directions import Geometry, incident
from tuibrdf.core.evaluate import evaluate_resolved
from tuibrdf.core.numerics import kernel_errstate, safe_div
from tuibrdf.core.registry import BROADCAST_KERNELS, MODELS

BUILTIN = [m for m in MODELS.values() if m.kernel in BROADCAST_KERNELS]
#: the RGB models that go through rgb.rgb (abc and sgd lay out their channels themselves)
RGB = [m for m in BUILTIN if m.rgb and m.name not in ("abc", "sgd")]
#: last-ulp differences between numpy's vectorised and scalar loops of a transcendental
#: function (exp, log, atan2, pow) are allowed; everything else is the same operations
RTOL = 1e-14


def directions(n: int, seed: int) -> np.ndarray:
    """Random directions of the whole sphere plus the normal, horizon and a subnormal z."""
    rng = np.random.default_rng(seed)
    v = rng.normal(size=(n, 3))
    v /= np.linalg.norm(v, axis=1)[:, None]
    special = np.array([[0, 0, 1], [1, 0, 0], [-1, 0, 0], [0.6, 0.8, 0], [1, 0, 1e-310],
                        [0, 0, -1]], dtype=float)
    return np.concatenate([special, v])


def params_of(m):
    """Defaults and one other parameter set per model."""
    other = {"phong": {"n": 7.0}, "blinn-phong": {"n": 300.0}, "cook-torrance": {"m": 0.05},
             "ggx": {"alpha": 0.05, "fresnel": "schlick"}, "oren-nayar": {"sigma": 60.0},
             "oren-nayar-simple": {"sigma": 60.0},
             "gltf": {"metallic": 0.5, "base_color": (0.9, 0.3, 0.1)},
             "ue4": {"metallic": 0.5, "base_color": (0.9, 0.3, 0.1)},
             "disney-diffuse": {"roughness": 1.0, "base_color": (0.9, 0.3, 0.1)},
             "abc": {"material": "white-fabric2"}, "sgd": {"material": "chrome"}}
    return [m.resolve({}), m.resolve(other.get(m.name, {}))]


def assert_close(a, b, what):
    a, b = np.asarray(a), np.asarray(b)
    assert a.shape == b.shape, what
    np.testing.assert_allclose(a, b, rtol=RTOL, atol=0, err_msg=what)


@pytest.mark.parametrize("model", BUILTIN, ids=lambda m: m.name)
def test_a_broadcast_direction_gives_the_values_of_the_full_array(model):
    wo = directions(300, 1)
    for values in params_of(model):
        for theta in (0.0, 40.0, 89.0):
            wi = incident(theta)
            view = np.broadcast_to(wi, wo.shape)  # zero strides: evaluated once
            full = np.ascontiguousarray(view)  # the same numbers, one per element
            ref = evaluate_resolved(model, values, full, wo)
            assert_close(evaluate_resolved(model, values, view, wo), ref, model.name)
            # the other side broadcast, and the kernel's own (3,) against (N, 3)
            assert_close(evaluate_resolved(model, values, wo, view),
                         evaluate_resolved(model, values, wo, full), model.name)
            assert_close(evaluate_resolved(model, values, wi, wo), ref, model.name)


def test_a_broadcast_along_some_axes_only_is_left_alone():
    # one stride 0 among others: not a single direction, evaluated as given
    v = directions(20, 2)
    wi, wo = np.broadcast_arrays(v[:, None, :], v[None, :, :])
    m = MODELS["ggx"]
    f = evaluate_resolved(m, m.resolve({}), wi, wo)
    assert f.shape == (len(v), len(v))
    assert_close(f, evaluate_resolved(m, m.resolve({}), wi.copy(), wo.copy()), "ggx")


@pytest.mark.parametrize("packed_max", [0, 10**9])
def test_geometry_layouts_agree(monkeypatch, packed_max):
    wi, wo = directions(400, 3), directions(400, 4)
    ref = {}
    with kernel_errstate():
        for wi_, wo_ in ((wi, wo), (incident(30.0), wo), (wi, incident(70.0))):
            monkeypatch.setattr(frame, "PACKED_MAX", 10**9 - packed_max)
            ref = Geometry(wi_, wo_)
            monkeypatch.setattr(frame, "PACKED_MAX", packed_max)
            g = Geometry(wi_, wo_)
            for name in ("cos_i", "cos_o", "sin2_i", "sin2_o", "h_valid", "cos_h", "sin2_h",
                         "cos_d", "above"):
                # the same operations on the same numbers: equal to the last bit
                np.testing.assert_array_equal(getattr(g, name), getattr(ref, name), name)


@pytest.mark.parametrize("model", RGB, ids=lambda m: m.name)
def test_rgb_layouts_agree(monkeypatch, model):
    wo = directions(300, 5)
    for values in params_of(model):
        for wi in (incident(35.0), directions(300, 6)):
            monkeypatch.setattr(rgb, "TOGETHER_MAX", 10**9)
            together = evaluate_resolved(model, values, wi, wo)
            monkeypatch.setattr(rgb, "TOGETHER_MAX", 0)
            per_channel = evaluate_resolved(model, values, wi, wo)
            assert together.shape == per_channel.shape == (len(wo), 3)
            assert_close(per_channel, together, model.name)


def test_rgb_layouts_agree_for_a_single_pair(monkeypatch):
    # scalars all the way (both directions single): shape (3,), either layout
    m = MODELS["gltf"]
    wi, wo = incident(30.0), incident(20.0, 0.0)
    monkeypatch.setattr(rgb, "TOGETHER_MAX", 0)
    a = evaluate_resolved(m, m.resolve({}), wi, wo)
    monkeypatch.setattr(rgb, "TOGETHER_MAX", 10**9)
    b = evaluate_resolved(m, m.resolve({}), wi, wo)
    assert a.shape == b.shape == (3,)
    assert_close(a, b, "gltf")


def test_integer_lobe_power_is_within_its_bound_of_pow():
    rng = np.random.default_rng(7)
    # bases over the whole range, down to where c^n leaves the normal range
    c = np.concatenate([rng.random(2000), 10.0 ** rng.uniform(-320, 0, 2000),
                        [0.0, 1.0, 1e-5, 0.5, np.nextafter(1.0, 0.0)], -rng.random(10)])
    with kernel_errstate():
        for n in range(1, INT_POWER_MAX + 1):
            ref = np.power(np.maximum(c, 0.0), float(n))  # numpy's pow: within an ulp
            got = lobe_power(c, float(n))
            normal = ref >= np.finfo(float).tiny
            # n·2⁻⁵³ from the squarings, plus the ulp of pow itself
            bound = (n + 1) * 2.0**-53
            np.testing.assert_allclose(got[normal], ref[normal], rtol=bound, atol=0)
            # below the normal range the elements are pow's own (recomputed)
            np.testing.assert_array_equal(got[~normal], ref[~normal])
        # not an integer, or above the limit: pow itself
        for n in (0.5, 20.25, INT_POWER_MAX + 1.0, 1e4):
            np.testing.assert_array_equal(lobe_power(c, n), np.power(np.maximum(c, 0.0), n))
        # n = 0: the half-space c > 0, 0 elsewhere (0^0 is not 1 here)
        np.testing.assert_array_equal(lobe_power(c, 0.0), (c > 0.0).astype(float))


def textbook_fresnel(c: np.ndarray, eta: float) -> np.ndarray:
    """Unpolarised reflectance from the s and p amplitudes with the refraction angle (Born &
    Wolf, Principles of Optics, §1.5.2): sin θt = sin θi/η; total reflection gives 1."""
    sin_t2 = (1.0 - c * c) / (eta * eta)
    out = np.ones_like(c)
    ok = sin_t2 < 1.0
    ct = np.sqrt(1.0 - sin_t2[ok])
    ci = c[ok]
    rs = (ci - eta * ct) / (ci + eta * ct)
    rp = (eta * ci - ct) / (eta * ci + ct)
    out[ok] = 0.5 * (rs * rs + rp * rp)
    return out


@pytest.mark.parametrize("eta", [1.04, 1.5, 2.4, 100.0, 0.7, 1.0])
def test_fresnel_dielectric_matches_the_textbook_form(eta):
    """η > 1 (the tables' η: the fast path), η < 1 (total reflection beyond the critical
    angle), η = 1 (no interface: 0, but 1 at grazing incidence, the limit)."""
    c = np.concatenate([np.linspace(0.0, 1.0, 1001), [1e-300, 0.9999999999]])
    with kernel_errstate():
        got = fresnel_dielectric(c, eta)
    np.testing.assert_allclose(got, textbook_fresnel(c, eta), rtol=1e-12, atol=1e-15)


def exact_fresnel(c: float, eta: float) -> float:
    """The textbook form at 60 digits, at exactly the double ``c``."""
    with hiprec.precise():
        c, e = hiprec.D(c), hiprec.D(eta)
        sin_t2 = (1 - c * c) / (e * e)
        if sin_t2 >= 1:
            return 1.0
        ct = hiprec.sqrt(1 - sin_t2)
        rs, rp = (c - e * ct) / (c + e * ct), (e * c - ct) / (e * c + ct)
        return float((rs * rs + rp * rp) / 2)


@pytest.mark.parametrize("eta", [0.7, 0.9999])
def test_fresnel_dielectric_at_the_critical_angle(eta):
    """η < 1 just past the critical angle (relative distance δ = 1e-6…1e-2), where F rises
    to 1 with an infinite slope (F ≈ 1 − K√δ; 0.44…0.99 here): against a 60-digit evaluation,
    within 1e-9 (the rounding of c and of η² − 1 times that slope: 3.5e-10 measured at
    η = 0.9999, δ = 1e-6; float64's textbook form does no better), and 1 at and below it."""
    cc = math.sqrt(1.0 - eta * eta)
    c = cc * (1.0 + np.geomspace(1e-6, 1e-2, 41))
    with kernel_errstate():
        got = fresnel_dielectric(c, eta)
        below = fresnel_dielectric(cc * np.array([1.0 - 1e-9, 0.5, 0.0]), eta)
    np.testing.assert_allclose(got, [exact_fresnel(x, eta) for x in c], rtol=0, atol=1e-9)
    assert np.all(below == 1.0)


def test_safe_div_on_scalars_divides_only_where_asked():
    with kernel_errstate():
        assert safe_div(np.float64(1.0), np.float64(0.0), False, fill=7.0) == 7.0  # no 1/0
        assert safe_div(np.float64(3.0), np.float64(4.0), True) == 0.75
        with pytest.raises(FloatingPointError):  # the policy holds for scalars too
            safe_div(np.float64(1.0), np.float64(0.0), True)
        out = safe_div(np.array([1.0, 2.0]), np.array([0.0, 4.0]), np.array([False, True]))
        np.testing.assert_array_equal(out, [0.0, 0.5])
        assert safe_div(1.0, np.array([[2.0], [4.0]]), np.array([True, False])).shape == (2, 2)
