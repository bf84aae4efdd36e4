"""The icosahedral hemisphere: counts, hierarchy, horizon, weights, interpolation, adaptivity.

Expected values come from geometry, not from the code: the icosahedron's counts (V − E + F = 2
and four children per face give 10·4ᴸ+2 vertices, 30·4ᴸ edges, 20·4ᴸ faces), the hemisphere
counts derived in ``tuibrdf/core/sphere/mesh.py``'s docstring (equator 5·2ᴸ vertices, since level 1
puts 10 there and each level doubles them; the hemisphere keeps half of the rest), and closed
form integrals over the hemisphere.
"""

import numpy as np
import pytest

from tuibrdf.core.directions import from_degrees
from tuibrdf.core.sphere.mesh import (
    MAX_LEVEL,
    hemisphere,
    interpolate,
    locate,
    refine_adaptive,
    sphere,
)

LEVELS = range(1, 7)


@pytest.mark.parametrize("level", range(0, 7))
def test_sphere_counts(level):
    v, f = sphere(level)
    assert len(v) == 10 * 4**level + 2
    assert len(f) == 20 * 4**level
    # closed surface: every edge shared by exactly two faces, Euler characteristic 2
    e = np.sort(np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]]), axis=1)
    _, counts = np.unique(e, axis=0, return_counts=True)
    assert np.all(counts == 2)
    assert len(v) - len(counts) + len(f) == 2


@pytest.mark.parametrize("level", LEVELS)
def test_hemisphere_counts(level):
    m = hemisphere(level)
    # hand-derived: V = (10·4ᴸ + 2 + 5·2ᴸ)/2, F = 20·4ᴸ / 2 (no face straddles the equator)
    assert len(m.vertices) == 5 * 4**level + 5 * 2 ** (level - 1) + 1
    assert len(m.faces) == 10 * 4**level
    assert np.count_nonzero(m.vertices[:, 2] == 0.0) == 5 * 2**level
    # a disc: Euler characteristic 1
    f = m.faces
    e = np.unique(np.sort(np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]]), axis=1),
                  axis=0)
    assert len(m.vertices) - len(e) + len(f) == 1


def test_level_zero_has_no_horizon_and_is_refused():
    assert not np.any(sphere(0)[0][:, 2] == 0.0)
    with pytest.raises(ValueError, match="level"):
        hemisphere(0)
    with pytest.raises(ValueError, match="level"):
        hemisphere(MAX_LEVEL + 1)


@pytest.mark.parametrize("level", range(1, 6))
def test_prefix_property(level):
    # level-L vertices (sphere and hemisphere) are the first ones of level L+1, bit for bit
    a, b = sphere(level)[0], sphere(level + 1)[0]
    assert np.array_equal(b[: len(a)], a)
    ha, hb = hemisphere(level).vertices, hemisphere(level + 1).vertices
    assert np.array_equal(hb[: len(ha)], ha)


@pytest.mark.parametrize("level", range(0, 6))
def test_sphere_is_centrally_symmetric_to_the_bit(level):
    # the lower ring is built as the exact negation of the upper one, and −(a+b)/|a+b| is the
    # exact negation of (a+b)/|a+b|: every vertex's antipode is a vertex, bit for bit (so two
    # horizon directions are exactly opposite, as the models' wi = −wo case expects)
    v = sphere(level)[0]
    have = {tuple(x) for x in v.tolist()}
    assert all(tuple(x) in have for x in (-v).tolist())


@pytest.mark.parametrize("level", LEVELS)
def test_vertices_unit_and_upper(level):
    m = hemisphere(level)
    assert np.all(m.vertices[:, 2] >= 0.0)
    np.testing.assert_allclose(np.linalg.norm(m.vertices, axis=1), 1.0, rtol=0, atol=1e-15)
    # the pole is a vertex (θ = 0 exists exactly)
    assert np.array_equal(m.vertices[0], [0.0, 0.0, 1.0])


@pytest.mark.parametrize("level", LEVELS)
def test_horizon_ring_is_evenly_spaced(level):
    # the equator vertices are 5·2ᴸ points 360°/(5·2ᴸ) apart; level 1 puts them at the band
    # edges' azimuths, 18° + 36°k (between upper ring 72°k and lower ring 36° + 72°k)
    m = hemisphere(level)
    h = m.vertices[m.vertices[:, 2] == 0.0]
    phi = np.sort(np.round(np.degrees(np.arctan2(h[:, 1], h[:, 0])), 9) % 360.0)
    k = 5 * 2**level
    # midpoints of equator arcs bisect their azimuths, so the ring is {18° + j·360°/k}
    np.testing.assert_allclose(phi, np.sort((18.0 + 360.0 / k * np.arange(k)) % 360.0),
                               atol=1e-9)


@pytest.mark.parametrize("level", LEVELS)
def test_weights_sum_to_two_pi(level):
    m = hemisphere(level)
    assert np.all(m.weights > 0)
    assert abs(m.weights.sum() - 2 * np.pi) < 1e-9


def test_arrays_are_readonly_and_cached():
    m = hemisphere(3)
    assert hemisphere(3) is m
    for a in (m.vertices, m.faces, m.weights):
        with pytest.raises(ValueError):
            a[0] = 0


@pytest.mark.parametrize("level", LEVELS)
@pytest.mark.parametrize("k", [0, 1, 2])
def test_weights_integrate_cos_powers_exactly(level, k):
    # ∫ cosᵏθ dω over the hemisphere = 2π/(k+1): the weights are scaled to make k = 0, 1, 2
    # exact (a constant BRDF's albedo, Lambert's, is then exact: the equal-share weights
    # gave 0.799964 for kd = 0.8 at level 6)
    m = hemisphere(level)
    assert abs(m.integrate(m.vertices[:, 2] ** k) - 2 * np.pi / (k + 1)) < 1e-13


def test_exact_weights_stay_close_to_the_triangle_shares():
    # the scaling is an O(h²) correction: 8.1e-4 relative at level 6 (measured), ~4× less
    # per level
    from tuibrdf.core.sphere.mesh import vertex_weights

    dev = []
    for level in (5, 6, 7):
        m = hemisphere(level)
        w0 = vertex_weights(m.vertices, m.faces)
        dev.append(np.max(np.abs(m.weights / w0 - 1.0)))
    assert dev[1] < 1e-3
    assert 3.0 < dev[0] / dev[1] < 5.0 and 3.0 < dev[1] / dev[2] < 5.0


def test_smooth_lobe_second_order():
    # ∫ cos⁸θ dω = 2π/9: not made exact by the weights, converges at ~4× per level
    errs = [abs(hemisphere(L).integrate(hemisphere(L).vertices[:, 2] ** 8) - 2 * np.pi / 9)
            for L in range(3, 8)]
    ratios = np.array(errs[:-1]) / np.array(errs[1:])
    assert np.all((ratios > 3.5) & (ratios < 4.5)), ratios


@pytest.mark.parametrize("level", [1, 3, 5])
def test_interpolation_reproduces_vertex_values(level):
    m = hemisphere(level)
    vals = np.random.default_rng(level).random(len(m.vertices))
    np.testing.assert_allclose(interpolate(m, vals, m.vertices), vals, rtol=0, atol=1e-12)


@pytest.mark.parametrize("level", [1, 4])
def test_interpolation_exact_for_linear_on_flat_triangles(level):
    # g(p) = k·q, q = p's central projection onto its flat triangle: linear on the triangle, so
    # barycentric interpolation of g's vertex values must give it exactly
    m = hemisphere(level)
    k = np.array([0.3, -1.2, 2.0])
    rng = np.random.default_rng(7)
    d = rng.normal(size=(2000, 3))
    d[:, 2] = np.abs(d[:, 2])
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    ids, bary, inside = locate(m, d)
    assert inside.all() and np.all(bary >= 0) and np.allclose(bary.sum(axis=1), 1.0)
    a, b, c = (m.vertices[ids[:, i]] for i in range(3))
    nrm = np.cross(b - a, c - a)
    q = d * (np.sum(nrm * a, axis=1) / np.sum(nrm * d, axis=1))[:, None]
    got = interpolate(m, m.vertices @ k, d)
    np.testing.assert_allclose(got, q @ k, rtol=0, atol=1e-12)


def test_interpolation_rgb_horizon_and_below():
    m = hemisphere(4)
    vals = np.stack([m.vertices[:, 0], m.vertices[:, 1], 1 + m.vertices[:, 2]], axis=1)
    d = from_degrees(np.array([90.0, 90.0, 45.0]), np.array([0.0, 123.0, 200.0]))
    got = interpolate(m, vals, d)
    assert got.shape == (3, 3)
    # on the horizon the interpolant uses only horizon vertices: z-channel exactly 1
    np.testing.assert_allclose(got[:2, 2], 1.0, atol=1e-15)
    np.testing.assert_allclose(got, np.stack([d[:, 0], d[:, 1], 1 + d[:, 2]], axis=1),
                               atol=0.02)
    assert np.isnan(interpolate(m, vals[:, 0], np.array([[0.0, 0.6, -0.8]]))).all()


def _sharp_lobe(n):
    """Modified Phong lobe at normal incidence times cos θ: ∫ = 1 (closed form (n+2)/(n+2))."""
    def f(w):
        return (n + 2) / (2 * np.pi) * w[:, 2] ** (n + 1)
    return f


def test_adaptive_weights_and_accuracy():
    f = _sharp_lobe(1000)
    a = refine_adaptive(f, 1e-4, max_level=9, focus=np.array([0.0, 0.0, 1.0]))
    assert abs(a.weights.sum() - 2 * np.pi) < 1e-9
    assert a.evaluations == len(a.vertices) == len(a.values)
    np.testing.assert_allclose(a.values, f(a.vertices), rtol=0, atol=0)
    assert abs(a.integrate() - 1.0) < 1e-3
    # the error estimate (rule against its four children's, summed) has the right size
    assert 0.2 * a.error <= abs(a.integrate() - 1.0) <= 5.0 * a.error


def test_adaptive_budget_is_respected():
    # a step in azimuth never converges: the evaluation budget bounds the work (the round
    # that crosses it finishes: at most 4× the triangles then active)
    def f(w):
        return (w[:, 0] > 0.1234).astype(float)

    a = refine_adaptive(f, 1e-12, max_level=16, max_evals=20_000)
    assert a.evaluations < 100_000
    # the step's integral is the area of the cap x > 0.1234 on the hemisphere
    assert a.integrate() == pytest.approx(np.pi * (1 - 0.1234), abs=1e-2)


def test_adaptive_beats_uniform_on_sharp_lobe():
    # lobe cos^1000 off the pole (so no vertex sits on its peak): uniform needs level 8
    # (~330k vertices) for 1e-3; adaptive gets there with far fewer evaluations
    n = 1000
    s = from_degrees(37.0, 11.0)

    def f(w):
        return (n + 2) / (2 * np.pi) * np.maximum(w @ s, 0.0) ** n

    # ∫_{α<90°} cos^n α dω = 2π/(n+1); the lobe lies far above the horizon (cos^1000 53° ≈ 0)
    exact = (n + 2) / (n + 1)
    a = refine_adaptive(f, 1e-4, max_level=9, focus=s)
    err_a = abs(a.integrate() - exact)
    # uniform: the first level that is as accurate
    for level in range(3, 9):
        m = hemisphere(level)
        if abs(m.integrate(f(m.vertices)) - exact) <= err_a:
            break
    else:
        level = None
    uniform_evals = len(hemisphere(level).vertices) if level else np.inf
    assert err_a < 2e-3
    assert a.evaluations * 5 < uniform_evals, (a.evaluations, level)


def test_adaptive_without_refinement_is_the_base_mesh():
    a = refine_adaptive(lambda w: np.ones(len(w)), 1e-3, base_level=2)
    base = hemisphere(2)
    assert len(a.faces) == len(base.faces)
    # the midpoints of level 2 were evaluated to test linearity: level-3 vertex count
    assert a.evaluations == len(hemisphere(3).vertices)
    assert abs(a.integrate() - 2 * np.pi) < 1e-12
