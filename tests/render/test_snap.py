"""Pictures that do not depend on the last bits (core.numerics.snap and the renderers' use of it).

numpy's exp, sin, pow and matrix products differ by CPU (AVX-512 or not) and numpy version in
the last bits, and a picture's geometry puts points exactly on a dot or pixel boundary (x = 0
in a symmetric window, a line a whole number of dots long).  Each test below draws such a
picture from inputs moved by a few ulps either way and checks that every version gives the
same picture, the one the documented geometry says (expected values worked out here).
"""

from __future__ import annotations

import numpy as np

from tuibrdf.core.numerics import SNAP, snap
from tuibrdf.render.braille import BrailleCanvas
from tuibrdf.render.solid import rasterise

NUDGES = (0, 1, -1, 4, -4, 64, -64)  # ulps


def nudged(v: float, n: int) -> float:
    """``v`` moved by ``n`` ulps (toward +inf for n > 0)."""
    for _ in range(abs(n)):
        v = float(np.nextafter(v, np.inf if n > 0 else -np.inf))
    return v


def test_snap_rounds_to_multiples_of_2_to_the_minus_30_exactly():
    assert SNAP == 2.0**-30
    k = np.array([-3, 0, 1, 7, 2**40, 2**52 - 1], dtype=float)
    np.testing.assert_array_equal(snap(k * SNAP), k * SNAP)  # on the grid: unchanged
    # a few ulps off a grid point: on it (64 ulps of 1.5 are 2e-14, far inside 2⁻³¹)
    for n in NUDGES:
        assert float(snap(nudged(1.5, n))) == 1.5
        assert float(snap(nudged(-26.5, n))) == -26.5
    # elsewhere it moves a number by at most half a step
    v = np.random.default_rng(7).uniform(-1e4, 1e4, 1000)
    assert np.max(np.abs(snap(v) - v)) <= SNAP / 2
    # beyond 2²² every float is a multiple of the step; inf and NaN pass (no warning: the
    # suite turns warnings into errors)
    big = np.array([2.0**22 + 0.5**30, 1e300, -1.7e308, np.inf, -np.inf])
    np.testing.assert_array_equal(snap(big), big)
    assert np.isnan(snap(np.nan))


def test_a_line_on_dot_boundaries_draws_the_same_dots_whatever_its_last_bits():
    # 27 × 2 cells = 54 × 8 dots over x ∈ [−1.08, 1.08], y ∈ [−1, 7]: x = ±1 falls on dot
    # column (±1 + 1.08)·54/2.16 − ½ = 1.5 and 51.5 (dot boundaries: 50 dots long), y = 0 on
    # dot row (7 − 0)·8/8 − ½ = 6.5.  Dot c covers [c − ½, c + ½): the 51 samples at 1.5,
    # 2.5, …, 51.5 light columns 2 … 52 of row 7, however the ends and the window's limits
    # (the polar window's come from a product and a division) are rounded
    want = {(7, c) for c in range(2, 53)}
    for n in NUDGES:
        for m in NUDGES:
            cv = BrailleCanvas(27, 2, (-nudged(1.08, n), nudged(1.08, m)),
                               (-1.0, nudged(7.0, m)), color="none")
            cv.polyline(np.array([nudged(-1.0, m), nudged(1.0, n)]), np.zeros(2),
                        cv.layer(None))
            rows, cols = np.nonzero(cv.owner >= 0)
            assert set(zip(rows.tolist(), cols.tolist(), strict=True)) == want, (n, m)


def test_a_point_on_the_window_centre_is_drawn_right_of_it():
    # x = 0 in a symmetric window of 2W dot columns is dot column W − ½: dot W, whatever
    # last bits sin(0°) or a product left on it; y = 3 on y ∈ [−1, 7] over 8 dot rows is dot
    # row (7 − 3) − ½ = 3.5: row 4
    for tiny in (0.0, 1e-17, -1e-17, 5e-324, -5e-324):
        for y in (3.0, nudged(3.0, 4), nudged(3.0, -4)):
            cv = BrailleCanvas(27, 2, (-1.08, 1.08), (-1.0, 7.0), color="none")
            cv.polyline(np.array([tiny]), np.array([y]), cv.layer(None))  # one point: a dot
            assert list(zip(*np.nonzero(cv.owner >= 0), strict=True)) == [(4, 27)], (tiny, y)


def test_a_triangle_corner_on_a_pixel_centre_covers_the_same_pixels():
    # the right triangle (0.5, 0.5), (3.5, 0.5), (0.5, 3.5) in pixel units: pixel (c, r) has
    # its centre at (c + ½, r + ½), inside (edges included) where c, r ≥ 0 and c + r ≤ 3: 10
    # pixels, whichever way a projection rounded the edges on the centres of column 0 and
    # row 0 (the box's first column and row are decided by them)
    want = sorted(r * 8 + c for r in range(4) for c in range(4) if r + c <= 3)
    for n in NUDGES:
        for m in NUDGES:
            x = np.array([[nudged(0.5, n), 3.5, nudged(0.5, n)]])
            y = np.array([[nudged(0.5, m), nudged(0.5, m), 3.5]])
            pid, _, tri = rasterise(x, y, np.zeros((1, 3)), 8, 8)
            assert sorted(pid.tolist()) == want, (n, m)
            assert set(tri.tolist()) == {0}


def test_snap_of_small_arrays_and_of_mixed_ones_round_alike():
    """The all-small path (a picture's coordinates: three passes) and the general one (any
    magnitude, inf, NaN) round each element the same way: the small elements of a mixed array
    equal the all-small array's, bit for bit, ties (odd multiples of 2⁻³¹) to even."""
    rng = np.random.default_rng(11)
    small = np.concatenate([rng.uniform(-2.0**21, 2.0**21, 500), rng.uniform(-1, 1, 500),
                            (2 * np.arange(-8, 8) + 1) * 2.0**-31, [0.0, -0.0]])
    mixed = np.concatenate([small, [2.0**22, -2.0**40, np.inf, np.nan]])
    a, b = snap(small), snap(mixed)
    np.testing.assert_array_equal(a, b[:len(small)])
    assert np.array_equal(np.signbit(a), np.signbit(b[:len(small)]))  # −0 stays −0
    # ties to even: (2j + 1)·2⁻³¹ → the even one of j·2⁻³⁰ and (j + 1)·2⁻³⁰
    j = np.arange(-8, 8)
    np.testing.assert_array_equal(a[1000:1016], np.where(j % 2 == 0, j, j + 1) * SNAP)
    assert snap(np.array([])).shape == (0,)
    assert float(snap(1.5 + 2.0**-40)) == 1.5  # a Python float: a 0-d array back
