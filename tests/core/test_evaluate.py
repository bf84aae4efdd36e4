"""The input contract of ``evaluate`` and an adversarial stability sweep (issue 17, item 7).

Contract (docs/design.md): shape ``(..., 3)``; finite; any non-zero vector is normalised
(a direction is a direction); the zero vector, NaN and inf are ``ValueError`` naming the
argument and the index.  Expected values come from the unit vector's own evaluation (the
contract says the length does not matter) and from closed forms (Lambert kd/π, Phong at the
mirror kd/π + ks(n+2)/2π).

The sweep: every analytic model at every corner of its parameters, over direction pairs built
to break the kernels — z = 0 exactly, subnormal z (5e-324, 1e-320, 1e-310), z at the bottom of
the normal range (2.2e-308, 1e-308, 1e-300), z where z² underflows (1e-160, 1e-154), directions
a hair apart, equal, mirrored and antipodal — all valid unit vectors.  Before the guards in
``core/microfacet.py``, cook-torrance, ggx and gltf raised FloatingPointError on 9 % of them
(72 124 of 779 100 cases of the first version of this sweep); directions just below the
horizon are included because a first version of those guards forgot that H can point down.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from tuibrdf.core.evaluate import BLOCK, as_directions, evaluate, evaluate_resolved, f_cos
from tuibrdf.core.registry import MODELS

ANALYTIC = [m for m in MODELS.values() if not any(p.kind == "path" for p in m.params)]


# ------------------------------------------------------------------ the issue's reproductions


def test_issue_reproductions_are_finite():
    """FloatingPointError before; the values are the horizon limits now."""
    ct = evaluate("cook-torrance", {}, [1, 0, 1e-310], [0, 0, 1])
    ggx = evaluate("ggx", {}, [1, 0, 0], [1, 0, 1e-308])
    gltf = evaluate("gltf", {}, [1, 0, 0], [1, 0, 1e-308])
    for v in (ct, ggx, gltf):
        assert np.all(np.isfinite(v)) and np.all(np.asarray(v) >= 0)
    # cook-torrance with wi on the horizon, wo the normal equals wi exactly on the horizon
    # (z = 1e-310 and z = 0 are the same direction to double precision)
    assert ct == pytest.approx(float(evaluate("cook-torrance", {}, [1, 0, 0], [0, 0, 1])),
                               rel=1e-12)


def test_non_unit_vectors_are_normalised():
    """`wi = (0,0,2)` with phong gave 1.8e6 instead of 1.81; length 1e200 overflowed."""
    unit = float(evaluate("phong", {}, [0, 0, 1], [0, 0, 1]))
    # closed form at the mirror: kd/π + ks(n+2)/(2π), defaults kd 0.2, ks 0.5, n 20
    assert unit == pytest.approx(0.2 / math.pi + 0.5 * 22 / (2 * math.pi), rel=1e-14)
    for scale in (2.0, 1e200, 1e-200, 1e-310, 1.7e308):
        for m in ANALYTIC:
            a = evaluate(m, {}, np.array([0.3, -0.2, 0.8]) * scale, [0.1, 0.4, 0.7])
            b = evaluate(m, {}, np.array([0.3, -0.2, 0.8]) / math.sqrt(0.77),
                         np.array([0.1, 0.4, 0.7]) / math.sqrt(0.66))
            np.testing.assert_allclose(a, b, rtol=1e-12, err_msg=f"{m.name} × {scale}")


def test_unit_vectors_are_left_alone():
    rng = np.random.default_rng(7)
    w = rng.normal(size=(1000, 3))
    w /= np.linalg.norm(w, axis=-1, keepdims=True)
    from tuibrdf.core.evaluate import as_directions

    np.testing.assert_allclose(as_directions(w, "w"), w, rtol=0, atol=4e-16)


def test_unit_float64_vectors_pass_uncopied_and_others_are_normalised():
    """The fast path: float64 unit vectors are the input itself (no copy); a vector a little
    further from unit length than the tolerance (|w|² = 1 + 1e-12) is normalised, and a NaN
    mixed into unit vectors is still refused."""
    from tuibrdf.core.evaluate import as_directions

    w = np.array([[0.0, 0.0, 1.0], [0.6, 0.0, 0.8], [0.0, -1.0, 0.0]])
    assert as_directions(w, "w") is w
    long = np.array([0.0, 0.0, 1.0 + 5e-13])  # |w|² = 1 + 1e-12 + …, far outside 8 ulps
    assert as_directions(long, "w")[2] == 1.0  # divided by its own length: exactly 1
    bad = w.copy()
    bad[1, 0] = np.nan
    with pytest.raises(ValueError, match=r"w\[1\] contains NaN"):
        as_directions(bad, "w")
    inf = w.copy()
    inf[2, 1] = -np.inf
    with pytest.raises(ValueError, match=r"w\[2\] contains NaN or inf"):
        as_directions(inf, "w")


@pytest.mark.parametrize("scale", [2.0, 1e-140, 1e149, 1e-160, 1e152, 1e-310, 1e307])
def test_both_normalising_paths_give_the_unit_vector_to_an_ulp(scale):
    """Lengths whose squares stay normal and finite are divided by √|w|² at once, the others
    scaled by their largest component first (core/evaluate.py, SQUARES_EXACT): either way,
    each component within 4 ulps of the vector divided by ``math.hypot`` of it: the result's
    |w|² of three squares and two sums is within 2.5 units of rounding, its square root and
    division add ½ each (≤ 2.25 units in all, up to 2.25 ulps just above a power of two), and
    the reference's hypot (< 1 ulp) and division (½) 1.5 more."""
    from tuibrdf.core.evaluate import as_directions

    rng = np.random.default_rng(3)
    w = rng.normal(size=(200, 3)) * scale
    w[0] = [0.0, 0.0, scale]  # an axis: exactly (0, 0, 1)
    got = as_directions(w, "w")
    assert got[0].tolist() == [0.0, 0.0, 1.0]
    for v, u in zip(w.tolist(), got, strict=True):
        big = max(abs(x) for x in v)
        s = [x / big for x in v]  # in [-1, 1]: hypot neither overflows nor underflows
        h = math.hypot(*s)
        ref = np.array([x / h for x in s])
        assert np.all(np.abs(u - ref) <= 4 * np.spacing(np.abs(ref)) + 1e-300), (v, u, ref)


@pytest.mark.parametrize("wi, words", [
    ([0, 0, 0], ["wi", "zero vector"]),
    ([[0, 0, 1], [0, 0, 0]], ["wi[1]", "zero vector"]),
    ([0, np.nan, 1], ["wi", "NaN or inf"]),
    ([[0, 0, 1], [np.inf, 0, 1]], ["wi[1]", "NaN or inf"]),
    ([1, 2], ["wi", "shape"]),
    (3.0, ["wi", "shape"]),
    ("up", ["wi", "numbers"]),
])
def test_bad_directions_are_value_errors(wi, words):
    with pytest.raises(ValueError) as e:
        evaluate("lambert", {}, wi, [0, 0, 1])
    for w in words:
        assert w in str(e.value)


def test_wo_is_checked_too():
    with pytest.raises(ValueError, match="wo is the zero vector"):
        evaluate("lambert", {}, [0, 0, 1], [0.0, -0.0, 0.0])


def _in_one_piece(m, wi, wo):
    """``evaluate`` as one call over the whole inputs: the check, then the kernel."""
    wi, wo = np.broadcast_arrays(as_directions(wi, "wi"), as_directions(wo, "wo"))
    return evaluate_resolved(m, m.resolve({}), wi, wo)


@pytest.mark.parametrize("model", ANALYTIC, ids=lambda m: m.name)
def test_large_inputs_in_blocks_give_the_values_of_one_piece(model):
    """``evaluate`` takes large inputs a block at a time (core/evaluate.py, BLOCK): each step
    of a kernel is elementwise, so the values are those of one call over the whole inputs, bit
    for bit, in every way the inputs broadcast, unit vectors (passed as they are) or not
    (normalised); a bad direction in a later block is still named by its index in the whole
    input.  (Unit and other vectors are not mixed here: the check passes a unit vector
    unchanged only if all those checked with it are unit, in one piece or in a block; either
    way it moves by a few ulps at most, module docstring.)"""
    n = 2 * BLOCK + 37  # two whole blocks and a short one
    rng = np.random.default_rng(11)
    wi, wo = rng.normal(size=(2, n, 3))  # a third of them below the horizon, about
    wi /= np.linalg.norm(wi, axis=-1, keepdims=True)
    wo /= np.linalg.norm(wo, axis=-1, keepdims=True)
    one = wi[5]
    for a, b in [(wi, wo), (one, wo), (wi, one[None]), (wi[:, None], np.stack([wo, wi], 1)),
                 (wi * 3.0, wo), (one, wo * 0.5)]:
        np.testing.assert_array_equal(evaluate(model, {}, a, b), _in_one_piece(model, a, b),
                                      err_msg=f"{model.name} {a.shape} {b.shape}")
    # empty along a later axis (no pair in any block): the empty result, as in one piece
    empty = evaluate(model, {}, np.zeros((n, 0, 3)) + [0.0, 0.0, 1.0], one)
    assert empty.shape == _in_one_piece(model, np.zeros((n, 0, 3)), one).shape
    bad = wo.copy()
    bad[n - 2, 1] = np.nan
    with pytest.raises(ValueError, match=rf"wo\[{n - 2}\] contains NaN"):
        evaluate(model, {}, wi, bad)


def test_below_the_horizon_is_zero_not_an_error():
    for m in ANALYTIC:
        v = evaluate(m, {}, [0, 0, -1], [0, 0, 1])
        assert np.all(np.asarray(v) == 0.0), m.name


# ------------------------------------------------------------------ adversarial sweep

TINY_Z = [0.0, 5e-324, 1e-320, 1e-310, 2.2250738585072014e-308, 1e-308, 1e-300, 1e-200,
          1e-160, 1e-154, 1e-100, 1e-20, 1e-8]


def adversarial_directions() -> np.ndarray:
    """Unit vectors at tiny heights over several azimuths, and a hair off the normal."""
    d = []
    for z in TINY_Z:
        s = math.sqrt(1.0 - z * z)
        for phi in (0.0, 30.0, 45.0, 90.0, 180.0):
            r = math.radians(phi)
            d.append([s * math.cos(r), s * math.sin(r), z])
    d += [[0, 0, 1], [1e-310, 0, 1], [1e-160, 0, 1], [1e-8, 0, 1], [0, 1e-310, 1],
          [-1e-310, 0, 1]]
    # a hair below the horizon, and straight down: H can point down (a guard once forgot)
    d += [[1, 0, -1e-310], [1, 0, -1e-8], [0.6, 0, -0.8], [0, 0, -1]]
    return np.array(d)


def adversarial_pairs() -> tuple[np.ndarray, np.ndarray]:
    d = adversarial_directions()
    wi = np.repeat(d, len(d), axis=0)
    wo = np.tile(d, (len(d), 1))
    # relational cases: equal, mirrored, antipodal in azimuth, nudged by an ulp
    mir = d * np.array([-1.0, -1.0, 1.0])
    anti = d * np.array([-1.0, -1.0, 0.0]) + np.array([0, 0, 1]) * d[:, 2:3]
    nudged = np.nextafter(d, 2.0)
    wi = np.concatenate([wi, d, d, d, d])
    wo = np.concatenate([wo, d, mir, anti, nudged])
    return wi, wo


def corners(p) -> list:
    if p.kind == "choice":
        return list(p.choices)
    if p.kind == "rgb":
        return [(p.min,) * 3, (p.max,) * 3]
    return sorted({p.min, p.max, p.default})


def corner_params(m):
    for combo in itertools.product(*(corners(p) for p in m.params)):
        try:
            yield m.resolve(dict(zip((p.name for p in m.params), combo, strict=True)))
        except ValueError:  # a violated constraint: not a corner
            continue


@pytest.mark.parametrize("model", ANALYTIC, ids=lambda m: m.name)
def test_adversarial_directions_are_finite_and_non_negative(model):
    wi, wo = adversarial_pairs()
    n = 0
    for values in corner_params(model):
        f = np.asarray(evaluate_resolved(model, values, wi, wo))  # raises on an FP exception
        assert np.all(np.isfinite(f)), (model.name, values)
        assert np.all(f >= 0.0), (model.name, values)
        n += len(wi)
    assert n > 0


@pytest.mark.parametrize("model", ANALYTIC, ids=lambda m: m.name)
def test_adversarial_through_evaluate_and_scaled(model):
    """The same pairs through ``evaluate`` (normalising), scaled by hostile lengths: ×2⁹⁹⁶
    (6.7e299, whose squares overflow: the scaled path) loses no bit, the values are those of
    the same vectors ×2 (divided by √|w|² directly), bit for bit: a power of two scales
    exactly and the scaled path scales by one; ×1e-300 flushes the tiny components to 0 (a
    different direction, so only finite and ≥ 0 is asked).  (Unscaled, the vectors within 8
    ulps of unit length would pass unnormalised; at heights of 1e-300 over the horizon some
    kernels' grazing guards tell such 2-ulp differences apart: abc's value moved by 75 % at 6
    of its 17,775 pairs between ×2 and ×1e300, which rounds.)"""
    wi, wo = adversarial_pairs()
    ref = np.asarray(evaluate(model, {}, wi * 2.0, wo * 2.0))
    big = np.asarray(evaluate(model, {}, wi * 2.0**996, wo * 2.0**996))
    np.testing.assert_array_equal(big, ref, err_msg=model.name)
    small = np.asarray(evaluate(model, {}, wi * 1e-300, wo))
    assert np.all(np.isfinite(small)) and np.all(small >= 0.0)


def test_f_cos_weights_by_cos_theta_o_and_is_zero_below_the_horizon():
    # wo at θo = 0°, 60°, 90° and 120° (below): cos θo = 1, 1/2, 0, and 0 below the horizon
    wo = np.array([[0.0, 0.0, 1.0], [math.sqrt(3) / 2, 0.0, 0.5], [0.0, 1.0, 0.0],
                   [math.sqrt(3) / 2, 0.0, -0.5]])
    f = np.array([2.0, 2.0, 2.0, 2.0])
    assert f_cos(f, wo).tolist() == [2.0, 1.0, 0.0, 0.0]
    rgb = np.array([[1.0, 2.0, 4.0]] * 4)  # an RGB model: each channel weighted alike
    assert f_cos(rgb, wo).tolist() == [[1.0, 2.0, 4.0], [0.5, 1.0, 2.0], [0.0] * 3, [0.0] * 3]
    # one direction (the probe): a scalar, or three channels
    assert float(f_cos(np.float64(3.0), wo[1])) == 1.5
    assert f_cos(np.array([1.0, 2.0, 4.0]), wo[1]).tolist() == [0.5, 1.0, 2.0]
