"""The peak of a lobe: the one finder every number on screen comes from.

``find_peaks(model, values, wi)`` returns the largest ``f`` (or ``f·cos θo`` with
``cosine=True``) over the closed upper hemisphere and its direction, within ~1e-10 (relative)
of the true maximum (tests/core/sphere/test_peak.py, tests/core/views/test_frame.py).  Every round
below is one
kernel call for all the searches at once; a kernel call costs ~150 µs before its first point
and ~0.2 µs a point, so the finder spends points to save rounds.

1. Candidates: the vertices of ``hemisphere(PEAK_LEVEL)`` (1,321 directions, edges ≈ 4°: a
   lobe wider than that has a vertex in its basin), the mirror direction S (where a lobe too
   sharp for the mesh sits), the horizon on the mirror side (where a grazing lobe ends up) and
   the normal.  Each channel searches from its best candidate and from S.
2. Each round, each search evaluates a 7×7 grid about its centre in the tangent plane, the
   points at 0, ±1/9, ±1/3, ±1 of the grid's half-widths (two: across and up the meridian),
   and its centre.  Where the horizon crosses the grid the rows are spread evenly from the
   horizon up instead (the first row on it exactly: a tangent-plane line projects onto a
   great circle), so no point is put back onto the horizon.
3. A quadratic fitted to the grid (least squares; ``PEAK_TRUST``: largest residual ≤ 5 % of
   the grid's span) gives a Newton step: the next grid is about the fit's vertex, sized to
   its error, so a smooth maximum is reached in 2–4 rounds instead of ~15.  With the best
   point on the horizon row and the fit falling from the horizon up, the row's own quadratic
   gives a step along the horizon.  The search is done when the predicted rise plus twice
   the largest residual is ≤ ``PEAK_TOL`` (1e-11) of the value, the best point inside the
   grid: a sound test for a smooth maximum, which replaces waiting for idle rounds.
4. Where the fit is poor (a crease such as Cook-Torrance's V-cavity G, Oren-Nayar, a lobe
   narrower than the grid) a pattern step: the maximum lies between the grid's best point
   and its neighbours, and the next grid spans that bracket, each axis on its own (1/9 … 4/9
   of the grid a round); two lines through the points either side of a crease meet at its
   maximum, and the grid then shrinks to about that estimate.  A best point on the grid's
   edge moves the grid there and doubles it (up to 4 mesh edges).  A grid about a vertex or
   a crease's estimate that finds nothing higher is followed by one about the best point.
   Done when the grid's span is ≤ ``PEAK_FLAT`` (1e-11) of the value with its best point
   inside (the maximum exceeds it by at most that: a flat or zero function stops after one
   round), or, last, after ``PEAK_PATIENCE`` rounds without gain on a grid that resolves the
   lobe (the centre's 8 nearest points within a quarter of the span; idle rounds counted
   from the start, the earlier rule, stopped at S while the grid was coarser than a sharp
   lobe: 5e-7 below the maximum of cook-torrance m = 0.001 at 30°, 5e-5 below phong
   n = 10⁴ with f·cos θr), or after
   ``PEAK_ROUNDS`` rounds.  A search below its channel's best does not keep the rounds going.
5. The plane of incidence, both sides of the normal (an isotropic lobe is symmetric about
   it, so its maximum there bounds the peak from below).  The 2-D searches can stop short of
   it on a crease running across their grid's axes (rough cook-torrance, m ≥ 0.3: the
   V-cavity crease crosses the plane there; up to 3e-5 below near normal incidence) or climb
   a lower local maximum (up to 4.2e-3 below; scripts/scan_peak_creases.py).  The plane is
   sampled every ``PLANE_STEP_DEG`` (1°) inside (−90°, 90°) in the candidates' call (179
   directions; the horizon is left to the 2-D searches, which keep its rows exact).  A grid
   maximum is refined only where it could beat the 2-D searches' value by a rise as large
   as its larger step to a neighbour, and not where a 2-D search ended in the plane on one
   of its tests (its bracket's maximum is that search's): most lobes refine nothing, and
   the check costs those points and no call.  A refinement is a 1-D search in extra rounds:
   about its best sample, lines through the samples either side of a crease meet at it
   (superlinear on a crease) and a parabola's vertex (on a smooth maximum), each sampled
   with points at ±d/3 and ±d; it stops when the bracket is narrower than ``PLANE_NARROW``
   and the crease lines leave ≤ ``PEAK_TOL`` to gain, when a neighbour is as high as its
   best (a plateau: a table's nearest bin), or when it cannot reach the 2-D searches'
   value: 1–6 rounds where it runs (at most ``PLANE_ROUNDS``, which a tabulated lobe's
   jumps can use up).  Its maximum replaces theirs when higher by more than ``PEAK_TOL``.

An RGB model gets four peaks, each with its own direction: the Rec.709 luminance ``Y`` and
each channel ``R``, ``G``, ``B``; a scalar model one.  ``Peak.label`` says which.

A kernel whose value grows without bound toward the horizon (a microfacet lobe at θi = 90°
exactly: ``1/cos θo`` is not cancelled there) has no maximum; the finder then returns the
largest value it reached in ``PEAK_ROUNDS`` rounds, ≈ 1e-11° above the horizon for
cook-torrance and ggx defaults, deterministically (the same input gives the same output).
The plane check's samples stay 1° or more from the horizon, so it changes nothing there (a
sample at its end, t = 90°, is the horizon only to rounding, cos(π/2) = 6e-17, where
cook-torrance's value is 2.7e10 times the 2-D searches').  Whether a peak is unbounded, and
the scale the pictures use for a peak on the horizon, is :mod:`tuibrdf.core.sphere.horizon`'s.
"""

from __future__ import annotations

import bisect
import math
from collections.abc import Mapping
from typing import Any, NamedTuple

import numpy as np

from tuibrdf.core.conventions import luminance
from tuibrdf.core.directions import incident, mirror, phi_of, theta_of
from tuibrdf.core.evaluate import evaluate_resolved, f_cos
from tuibrdf.core.params import Model
from tuibrdf.core.sphere.mesh import hemisphere

PEAK_LEVEL = 4
PEAK_ROUNDS = 20
PEAK_PATIENCE = 4
PEAK_TRUST = 0.05
PEAK_TOL = 1e-12
PEAK_FLAT = 1e-11
PEAK_NOISE = 5e-12
HORIZON_MIRROR = np.array([1.0, 0.0, 0.0])
NORMAL = np.array([0.0, 0.0, 1.0])
# The 7×7 grid of a search, in the tangent plane at its centre c (half-width s): a across,
# b up, at c + s (a t1 + b t2).  Away from the horizon a and b take the values _P, dense at
# the centre; where the horizon crosses the grid (its line b = lo) the rows are spread evenly
# over [lo, 1] instead, the first on the horizon.  Both are written b = lo + (1 − lo) κ
# (lo = −1 away from it), so one fit in (a, κ) serves.  Point 49 is the centre (0, 0).
_P = np.array([-1.0, -1.0 / 3.0, -1.0 / 9.0, 0.0, 1.0 / 9.0, 1.0 / 3.0, 1.0])
_GA = np.tile(_P, 7)
_GA50 = np.append(_GA, 0.0)
_GB50 = np.append(np.repeat(_P, 7), 0.0)
_K7 = np.arange(7.0)
_NEAR = [7 * kk + aa for kk in (2, 3, 4) for aa in (2, 3, 4) if (kk, aa) != (3, 3)]
# the bracket about grid index 1…5 along an axis: its middle and half-width
_MID = [(_P[i - 1] + _P[i + 1]) / 2.0 if 0 < i < 6 else 0.0 for i in range(7)]
_HALF = [(_P[i + 1] - _P[i - 1]) / 2.0 if 0 < i < 6 else 0.0 for i in range(7)]
_KAPPA = (np.repeat((_P + 1.0) / 2.0, 7), np.repeat(np.linspace(0.0, 1.0, 7), 7))


def _lsq(x: np.ndarray) -> np.ndarray:
    """Least squares with the basis ``x (p, m)``: ``u @ M`` gives the ``m`` coefficients, then
    the ``p`` residuals."""
    fit = np.linalg.pinv(x)
    return np.concatenate([fit.T, np.eye(len(x)) - (x @ fit).T], axis=1)


# q = c0 + c1 a + c2 κ + c3 a² + c4 aκ + c5 κ² on the grid (away, horizon), each (49, 55); and
# q = r0 + r1 a + r2 a² on the bottom row alone, (7, 10)
_FIT = tuple(_lsq(np.stack([np.ones(49), _GA, kap, _GA * _GA, _GA * kap, kap * kap], axis=1))
             for kap in _KAPPA)
_FIT1 = _lsq(np.stack([np.ones(7), _P, _P * _P], axis=1))


class Peak(NamedTuple):
    """The largest value and where it is (degrees; φ in (−180°, 180°], 0 at the normal).
    ``label``: ``""`` for a scalar model, ``"Y"`` (luminance), ``"R"``, ``"G"`` or ``"B"``."""

    value: float
    theta_deg: float
    phi_deg: float
    label: str = ""


def f_or_f_cos(model: Model, values: Mapping[str, Any], wi: np.ndarray, wo: np.ndarray,
               cosine: bool) -> np.ndarray:
    """What the panes show at ``wo (n, 3)``: ``f(wi, wo)``, or ``f·cos θo`` when ``cosine``
    (:func:`~tuibrdf.core.evaluate.f_cos`); ``(n,)``/``(n, 3)``."""
    f = np.asarray(evaluate_resolved(model, values, wi, wo), dtype=float)
    return f_cos(f, wo) if cosine else f


def scores(g: np.ndarray) -> np.ndarray:
    """``(n, 1)`` for scalar values, ``(n, 4)`` = (Y, R, G, B) for RGB ones."""
    if g.ndim == 1:
        return g[:, None]
    return np.concatenate([luminance(g)[:, None], g], axis=1)


def _angles(w: np.ndarray) -> tuple[float, float]:
    theta = float(np.degrees(theta_of(w)))
    phi = float(np.degrees(phi_of(w))) if theta > 0.0 else 0.0
    return theta, phi


def _vertex(cf: list[float], row: list[float] | None) -> tuple[float, float, float, bool]:
    """The maximum of a fitted quadratic ``cf`` inside the grid ``|a| ≤ 1, 0 ≤ κ ≤ 1``.  Given
    ``row`` (the best point is on the horizon row, κ = 0), the vertex of that row's own
    concave quadratic where the fit falls from the horizon upward (a maximum on the horizon);
    else the interior vertex of a concave fit.  Returns ``(a, κ, q, on)``, ``q`` the value
    predicted there, ``on`` if the row's vertex is used; ``a`` is NaN when there is none."""
    c0, c1, c2, c3, c4, c5 = cf
    if row is not None and row[2] < 0.0:  # concave: row[2] ≠ 0
        r0, r1, r2 = row
        a = -r1 / (2.0 * r2)
        if abs(a) <= 1.0 and c2 + c4 * a <= 0.0:
            return a, 0.0, r0 + r1 * a + r2 * a * a, True
    det = 4.0 * c3 * c5 - c4 * c4
    if c3 < 0.0 and det > 0.0:  # concave: det ≠ 0
        a = (c4 * c2 - 2.0 * c5 * c1) / det
        kappa = (c4 * c1 - 2.0 * c3 * c2) / det
        if abs(a) <= 1.0 and 0.0 <= kappa <= 1.0:
            return a, kappa, c0 + c1 * a + c2 * kappa + c3 * a * a + c4 * a * kappa \
                + c5 * kappa * kappa, False
    return math.nan, 0.0, 0.0, False


def _crease(x, y: list[float], i: int, mid: float,
            half: float) -> tuple[float, float, bool]:
    """The bracket ``(middle, half-width)`` about ``x[i]`` (``y[i]`` the largest of ``y``, i in
    1…5) narrowed when a crease explains the values: lines through the two points either
    side of it (for a crease left of ``x[i]``, points (i−2, i−1) and (i, i+1); right of it,
    (i−1, i) and (i+1, i+2)) that rise to meet inside its interval.  Then the next bracket
    is about where they meet, 3× the move wide (at least 1/27 of the bracket); the third
    value says whether it was narrowed."""
    meet = _lines_meet(x, y, i)
    if not meet:
        return mid, half, False
    at = float(max(meet, key=lambda p: p[1])[0])  # the higher meeting (the first on a tie)
    return at, min(max(3.0 * abs(at - x[i]), half / 27.0), half), True


#: the plane of incidence's check (step 5 of the module's docstring): a grid of PLANE_STEP_DEG
#: inside (−90°, 90°), the horizon left to the 2-D searches; at most PLANE_STARTS brackets per
#: column refined, each for at most PLANE_ROUNDS rounds, until narrower than PLANE_NARROW rad
PLANE_STEP_DEG = 1.0
PLANE_STARTS = 2
PLANE_ROUNDS = 6
PLANE_NARROW = 1e-5
_PLANE_T = np.radians(np.arange(-90.0 + PLANE_STEP_DEG, 90.0 - 0.5 * PLANE_STEP_DEG,
                                PLANE_STEP_DEG))
# the grid's directions, _along(_PLANE_T, axis), are _PLANE_SIN * axis + _PLANE_UP
_PLANE_SIN = np.sin(_PLANE_T)[:, None]
_PLANE_UP = np.cos(_PLANE_T)[:, None] * NORMAL


def _along(t: np.ndarray, axis: np.ndarray) -> np.ndarray:
    """The directions at angles ``t`` (radians) from the normal toward ``axis``, a horizontal
    unit vector (the mirror side's horizon; t < 0 on the light's side): ``(n, 3)``."""
    return np.sin(t)[:, None] * axis + np.cos(t)[:, None] * NORMAL


def _lines_meet(xs: list[float], ys: list[float], i: int) -> list[tuple[float, float]]:
    """Where lines through the two samples either side of a crease next to ``xs[i]`` meet,
    and how high: for a crease left of it, samples (i−2, i−1) and (i, i+1); right of it,
    (i−1, i) and (i+1, i+2); each pair rising to meet inside its interval."""
    out = []
    for l0, r0 in ((i - 2, i), (i - 1, i + 1)):
        if l0 < 0 or r0 + 1 >= len(xs):
            continue
        sl = (ys[l0 + 1] - ys[l0]) / (xs[l0 + 1] - xs[l0])  # the xs are distinct
        sr = (ys[r0 + 1] - ys[r0]) / (xs[r0 + 1] - xs[r0])
        if not sl > 0.0 > sr:
            continue
        xm = (ys[r0] - ys[l0] + sl * xs[l0] - sr * xs[r0]) / (sl - sr)  # sl − sr > 0
        if xs[l0 + 1] <= xm <= xs[r0]:
            out.append((xm, ys[l0] + sl * (xm - xs[l0])))
    return out


def _parabola(xs: list[float], ys: list[float], i: int) -> list[tuple[float, float]]:
    """The vertex of the parabola through samples i − 1, i, i + 1 and its height, when it is
    concave (none otherwise)."""
    if i < 1 or i + 1 >= len(xs):
        return []
    x0, x1, x2 = xs[i - 1:i + 2]
    y0, y1, y2 = ys[i - 1:i + 2]
    d1 = (y1 - y0) / (x1 - x0)  # the xs are distinct
    d2 = (y2 - y1) / (x2 - x1)
    c2 = (d2 - d1) / (x2 - x0)
    if not c2 < 0.0:
        return []
    xv = 0.5 * (x0 + x1) - d1 / (2.0 * c2)  # c2 < 0
    return [(xv, y0 + d1 * (xv - x0) + c2 * (xv - x0) * (xv - x1))]


def _plane_starts(gs: np.ndarray, val: list[float], at: list[np.ndarray], ended: list[str],
                  axis: np.ndarray, normal: bool) -> list[tuple[int, list[float], list[float]]]:
    """The brackets of the plane's grid worth refining: about a local maximum of the grid
    (``gs``, its scores) that could exceed the 2-D searches' value ``val``: by a rise as large
    as its larger step to a neighbour (a crease or a smooth maximum between grid points rises
    less); but not the bracket holding a 2-D search's point ``at`` that ended in the plane
    (to 1e-6) on one of its tests (``ended``, not out of rounds): that maximum is the
    search's.  At most PLANE_STARTS per column, the highest first, each as ``(column, t,
    values)``: the 5 grid points about the maximum.  ``normal``: the light is at the normal,
    where every vertical plane is one of incidence (the point's own plane)."""
    g = gs[1:-1]
    bound = 2.0 * g - np.minimum(gs[:-2], gs[2:])
    ok = (g >= np.maximum(gs[:-2], gs[2:])) & (bound > [x + PEAK_TOL * abs(x) for x in val])
    if not np.count_nonzero(ok):  # (count_nonzero: a tenth of any's cost here)
        return []
    n = len(_PLANE_T)
    t0, dt = float(_PLANE_T[0]), float(_PLANE_T[1] - _PLANE_T[0])
    ax, ay, _ = axis.tolist()
    for c in range(len(val)):
        x, y, z = at[c].tolist()
        if not ended[c] or not (normal or abs(ay * x - ax * y) <= 1e-6):
            continue
        own = math.acos(min(z, 1.0)) if normal else math.atan2(ax * x + ay * y, z)
        for o in (own, -own) if normal else (own,):
            # the brackets [t_{j−1}, t_{j+1}] holding o: |t_j − o| ≤ dt
            p = (o - t0) / dt
            for j in range(max(math.ceil(p - 1.0), 1), min(math.floor(p + 1.0), n - 2) + 1):
                ok[j - 1, c] = False
    if not np.count_nonzero(ok):
        return []
    t = _PLANE_T.tolist()
    starts = []
    for c in range(len(val)):
        js = np.flatnonzero(ok[:, c]) + 1
        if not len(js):
            continue
        js = js[np.argsort(-bound[js - 1, c], kind="stable")][:PLANE_STARTS]
        for j in js.tolist():
            lo, hi = max(j - 2, 0), min(j + 3, n)
            starts.append((c, t[lo:hi], gs[lo:hi, c].tolist()))
    return starts


#: a 2-D result in the plane between the grid's end (90° − PLANE_STEP_DEG) and this far from
#: the horizon is searched along the plane too, from samples PLANE_NEAR_STEPS rad either side
PLANE_NEAR_GAP = 1e-6
PLANE_NEAR_STEPS = (-4e-3, -1e-3, -2.5e-4, 0.0, 2.5e-4, 1e-3)


def _near_horizon_starts(model: Model, values: Mapping[str, Any], wi: np.ndarray,
                         cosine: bool, axis: np.ndarray, at: list[np.ndarray]) -> list:
    """Starts for :func:`_plane_refine` about each column's 2-D result that lies on the
    plane's mirror side beyond the grid (above 90° − PLANE_STEP_DEG) but not on the horizon:
    a V-cavity crease a few hundredths of a degree above it, which the 2-D search's fit can
    take for a smooth maximum (cook-torrance m = 0.001 at θi = 89.9°: 3.9e-7 below)."""
    top = 0.5 * math.pi - PLANE_NEAR_GAP
    ts, cols = [], []
    for c, w in enumerate(at):
        t = math.atan2(float(w @ axis), float(w[2]))
        across = float(w[0] * axis[1] - w[1] * axis[0])  # off the plane (both unit vectors)
        if abs(across) > 1e-9 or not math.radians(90.0 - PLANE_STEP_DEG) < t < top:
            continue
        xs = sorted({min(max(t + d, 0.0), top) for d in PLANE_NEAR_STEPS})
        ts.append(xs)
        cols.append(c)
    if not ts:
        return []
    flat = np.array([x for xs in ts for x in xs])
    sc = scores(f_or_f_cos(model, values, wi, _along(flat, axis), cosine))
    out, k = [], 0
    for c, xs in zip(cols, ts, strict=True):
        out.append((c, xs, sc[k:k + len(xs), c].tolist()))
        k += len(xs)
    return out


def _plane_next(xs: list[float], ys: list[float], floor: float) -> list[float]:
    """The next samples of a search along the plane (``xs`` sorted, radians): the midpoints
    either side of the best sample, and about each crease and vertex estimate next to it
    points at 0, ±d/3 and ±d from it (d its move from the best sample, at least 1/1000 of
    the best's bracket).  None when the bracket is narrower than PLANE_NARROW and what is
    left to gain by the crease estimates is ≤ PEAK_TOL of the value; when a neighbour is as
    high as the best (a plateau, as a table's nearest-bin lookup gives); when the search cannot
    reach ``floor`` (the 2-D searches' value) by a rise as large as the steeper of its
    neighbours' slopes over its wider gap (the test of :func:`_plane_starts`); or when the
    best is at the search's end (rising past its bracket: another search's, or the 2-D
    searches' near the horizon)."""
    i = max(range(len(ys)), key=ys.__getitem__)
    if i == 0 or i == len(xs) - 1:
        return []
    y = ys[i]
    if ys[i - 1] == y or ys[i + 1] == y:
        return []  # flat at the best sample (a table's nearest bin): its value is reached
    lo, x0, hi = xs[i - 1], xs[i], xs[i + 1]
    # the xs are distinct
    slope = max((y - ys[i - 1]) / (x0 - lo), (y - ys[i + 1]) / (hi - x0))
    if y + slope * max(x0 - lo, hi - x0) <= floor:
        return []
    meet = _lines_meet(xs, ys, i)
    if hi - lo <= PLANE_NARROW and max([y] + [h for _, h in meet]) - y <= PEAK_TOL * abs(y):
        return []
    new = [0.5 * (lo + x0), 0.5 * (x0 + hi)]
    for x, _ in meet + _parabola(xs, ys, i):
        d = max(abs(x - x0), 1e-3 * (hi - lo))
        for u in (0.0, -1.0, 1.0, -1.0 / 3.0, 1.0 / 3.0):
            p = x + u * d
            if lo < p < hi:
                new.append(p)
    return new


def _plane_refine(model: Model, values: Mapping[str, Any], wi: np.ndarray, cosine: bool,
                  axis: np.ndarray, starts: list,
                  val: list[float]) -> list[tuple[int, float, float]]:
    """Each start's search along the plane (``axis``: the mirror side's horizon), to beat its
    column's value ``val``: ``(column, value, t)``."""
    live = [(c, list(xs), list(ys)) for c, xs, ys in starts]
    done = []
    for _ in range(PLANE_ROUNDS):
        asks = []
        keep = []
        for c, xs, ys in live:
            floor = val[c] + PEAK_TOL * abs(val[c])
            new = sorted(set(_plane_next(xs, ys, floor)) - set(xs))
            if new:
                asks.append(new)
                keep.append((c, xs, ys))
            else:
                done.append((c, xs, ys))
        live = keep
        if not live:
            break
        tt = np.array([x for new in asks for x in new])
        st = scores(f_or_f_cos(model, values, wi, _along(tt, axis), cosine))
        k = 0
        for (c, xs, ys), new in zip(live, asks, strict=True):
            for x, v in zip(new, st[k:k + len(new), c].tolist(), strict=True):
                j = bisect.bisect(xs, x)
                xs.insert(j, x)
                ys.insert(j, v)
            k += len(new)
    out = []
    for c, xs, ys in done + live:
        i = max(range(len(ys)), key=ys.__getitem__)
        out.append((c, ys[i], xs[i]))
    return out


def _at_normal(wi: np.ndarray) -> bool:
    """The light is at the normal (to rounding): the mirror direction has no azimuth."""
    return math.hypot(wi[0], wi[1]) <= 1e-100


def mirror_horizon(wi: np.ndarray, phi_i_deg: float) -> np.ndarray:
    """The horizon on the mirror side, a horizontal unit vector: HORIZON_MIRROR turned with the
    light's azimuth (from the mirror direction itself, but at the normal, where it has
    none)."""
    if _at_normal(wi):
        return incident(90.0, float(phi_i_deg) + 180.0)
    r = math.hypot(wi[0], wi[1])  # > 0
    return np.array([-wi[0] / r, -wi[1] / r, 0.0])


def find_peaks(model: Model, values: Mapping[str, Any], wi: np.ndarray, *,
               cosine: bool = False, level: int = PEAK_LEVEL,
               phi_i_deg: float = 180.0) -> tuple[Peak, ...]:
    """``(Peak,)`` for a scalar model, ``(Y, R, G, B)`` peaks for an RGB one (see module);
    the light at ``wi`` (:func:`~tuibrdf.core.directions.incident`; the frame's
    :attr:`~tuibrdf.core.views.frame.FrameRequest.wi`).  ``phi_i_deg``, the light's azimuth,
    matters only where ``wi`` is the normal and has none (:func:`mirror_horizon`)."""
    s_dir = mirror(wi)
    h_mirror = mirror_horizon(wi, phi_i_deg)
    cand = np.concatenate([hemisphere(level).vertices, [s_dir, h_mirror, NORMAL]])
    # one kernel call for the candidates and the plane's grid
    line = _PLANE_SIN * h_mirror + _PLANE_UP
    sc = scores(f_or_f_cos(model, values, wi, np.concatenate([cand, line]), cosine))
    sc, gs = sc[:len(cand)], sc[len(cand):]
    val, at, ended = _climb(model, values, wi, cosine, cand, sc, level)
    starts = _plane_starts(gs, val, at, ended, h_mirror, _at_normal(wi))
    starts += _near_horizon_starts(model, values, wi, cosine, h_mirror, at)
    if starts:
        for c, v, t in _plane_refine(model, values, wi, cosine, h_mirror, starts, val):
            # higher by more than the searches' own tolerance (a tie would move the place of a
            # flat maximum for nothing)
            if v > val[c] + PEAK_TOL * abs(val[c]):
                val[c], at[c] = v, _along(np.array([t]), h_mirror)[0]
    labels = ("",) if len(val) == 1 else ("Y", "R", "G", "B")
    if len(val) == 4 and np.array_equal(sc[:, 1], sc[:, 2]) and np.array_equal(sc[:, 1],
                                                                                sc[:, 3]):
        labels = ("",) * 4  # a grey RGB model (R = G = B at every candidate): no channel to name
    return tuple(Peak(v, *_angles(w), lab) for v, w, lab in zip(val, at, labels, strict=True))


def _climb(model: Model, values: Mapping[str, Any], wi: np.ndarray, cosine: bool,
           cand: np.ndarray, sc: np.ndarray,
           level: int) -> tuple[list[float], list[np.ndarray], list[str]]:
    """The 2-D searches (steps 2–4 of the module's docstring) from the candidates ``cand``
    (the mesh, then S, the mirror side's horizon and the normal) and their scores ``sc``: each
    column's largest value, where, and how its search ended: ``"smooth"`` (the fit's test for
    a smooth maximum), ``"flat"`` (the grid's span), ``"idle"`` (rounds without gain) or
    ``""`` (out of rounds, or stopped below its column's other search)."""
    s_dir = cand[-3]
    k = sc.shape[1]
    first = np.argmax(sc, axis=0)
    i_mirror = len(cand) - 3
    # two searches per column: from its best candidate and from the mirror direction (none
    # when that is the best candidate)
    best = np.concatenate([cand[first], np.repeat(s_dir[None, :], k, axis=0)])
    col = list(range(k)) * 2
    val = sc[first, range(k)].tolist() + sc[i_mirror].tolist()
    centre = best.copy()
    s0 = math.radians(63.4) / 2**level  # about one mesh edge
    step = [s0] * (2 * k)  # the grid's half-width across (a)
    stepb = [s0] * (2 * k)  # and up (b)
    idle = [0] * (2 * k)
    covers = [True] * (2 * k)  # the search's grid covers its best point
    spec = [False] * (2 * k)  # the search's grid is about a fitted vertex
    rows: list = []
    res7: list = []
    kinky = [0] * (2 * k)  # fitted vertices that proved lower
    ended = [""] * (2 * k)  # how the search ended (see the docstring)
    live = list(range(k)) + [i + k for i in range(k) if first[i] != i_mirror]
    for _ in range(PEAK_ROUNDS):
        n = len(live)
        c = centre[live]
        # the grid's axes, t1 across (horizontal) and t2 up the meridian, scaled to its half-
        # widths; its rows go up from the horizon's line b = −c_z / (s_b t2_z) where that
        # crosses the grid (a line of the tangent plane projects onto a great circle), else
        # from b = −1.  Plain floats: a handful of searches, where numpy's per-call cost
        # would dominate
        t1, t2, lol, onl = [], [], [], []
        for (x, y, z), i in zip(c.tolist(), live, strict=True):
            sa, sb = step[i], stepb[i]
            r = math.hypot(x, y)
            if r > 1e-100:  # r ≠ 0, and −z / (r s_b) finite
                t1.append((-y / r * sa, x / r * sa, 0.0))
                t2.append((-z * x / r * sb, -z * y / r * sb, r * sb))
                hb = -z / (r * sb)
            else:  # the pole (to rounding): t1 = y, t2 = −x
                t1.append((0.0, sa, 0.0))
                t2.append((-sb, 0.0, 0.0))
                hb = -math.inf
            lol.append(max(hb, -1.0))
            onl.append(hb >= -1.0)
        t1, t2 = np.array(t1), np.array(t2)
        near = any(onl)
        if near:
            on_h, lo = np.array(onl), np.array(lol)
            b = np.zeros((n, 50))
            b[:, :49] = lo[:, None] + (1.0 - lo)[:, None] * np.where(on_h[:, None],
                                                                     *_KAPPA[::-1])
            q = c[:, None, :] + _GA50[:, None] * t1[:, None, :] + b[:, :, None] * t2[:, None, :]
            q[:, :, 2] = np.maximum(q[:, :, 2], 0.0)
            q[on_h, :7, 2] = 0.0  # the bottom row on the horizon exactly
        else:  # every point above the horizon (hb < −1)
            q = c[:, None, :] + _GA50[:, None] * t1[:, None, :] + _GB50[:, None] * t2[:, None, :]
        q /= np.sqrt(np.einsum("nij,nij->ni", q, q))[:, :, None]  # ≠ 0: steps are ≪ 1 rad
        st = scores(f_or_f_cos(model, values, wi, q.reshape(-1, 3), cosine))
        v = st.reshape(n, 50, k)[np.arange(n), :, [col[i] for i in live]]
        j = v.argmax(axis=1)
        vmax = v[np.arange(n), j]
        span = vmax - v.min(axis=1)
        # the quadratic fit, in units of the grid's span below its best value (a flat grid's
        # u is 0: the guard)
        u = (v[:, :49] - vmax[:, None]) / np.where(span > 0.0, span, 1.0)[:, None]
        f2 = u @ _FIT[0]
        if near:
            f2[on_h] = u[on_h] @ _FIT[1]
            f1 = u[:, :7] @ _FIT1
            rows, res7 = f1[:, :3].tolist(), np.abs(f1[:, 3:]).max(axis=1).tolist()
        res = np.abs(f2[:, 6:]).max(axis=1).tolist()
        cfs = f2[:, :6].tolist()
        fa, fb = [0.0] * n, [0.0] * n
        use = [False] * n  # the next centre is (fa, fb), else the best point
        still = []
        jl, vml, spl, v49 = j.tolist(), vmax.tolist(), span.tolist(), v[:, 49].tolist()
        vl = v.tolist()
        for r, i in enumerate(live):
            jr, top, sp, lor, onr = jl[r], vml[r], spl[r], lol[r], onl[r]
            sa, sb_ = step[i], stepb[i]
            up = top - val[i]
            if up > 0.0:
                val[i] = top
                best[i] = q[r, jr]
            scale = abs(val[i])
            # the grid's best point (the centre when as high, to rounding)
            if v49[r] < top - 1e-15 * scale:
                ja, jk = jr % 7, jr // 7
            else:  # (a centre on the horizon is on the bottom row)
                ja, jk = 3, 0 if onr and lor >= 0.0 else -1
            edge = ja in (0, 6) or jk == 6 or (jk == 0 and not onr)
            inside = not edge
            ea = jr % 7
            if inside and sp <= PEAK_FLAT * scale and up >= -PEAK_FLAT * scale:
                # the maximum is between the grid's best point and its neighbours, and
                # exceeds it by at most the grid's span: done (a flat or zero function too)
                ended[i] = "flat"
                continue
            if spec[i] and v49[r] < val[i] - PEAK_FLAT * scale:
                kinky[i] += 1  # a vertex that proved lower (3 times: no more fits here)
            spec[i] = False
            if up <= 0.0 and not covers[i]:
                # a grid about a fitted vertex or a crease's estimate found nothing higher:
                # the next one is about the best point, as large
                covers[i] = True
                still.append(r)
                continue
            # a round without gain counts toward stopping once the grid resolves the lobe:
            # the centre's 8 nearest points within a quarter of the grid's span of it (a
            # lobe narrower than the grid's spacing has them near the bottom)
            vr = vl[r]
            resolved = onr or min(vr[x] for x in _NEAR) >= top - 0.25 * sp
            idle[i] = idle[i] + 1 if up <= 0.01 * PEAK_TOL * scale and resolved else 0
            if idle[i] >= PEAK_PATIENCE:
                ended[i] = "idle"
                continue
            on_row = onr and jk == 0
            a, kappa, pred, on = _vertex(cfs[r], rows[r] if on_row else None)
            rr = res7[r] if on else res[r]
            # a vertex (not NaN), a close fit, and fits here have not failed 3 times
            if a == a and rr <= PEAK_TRUST and kinky[i] < 3:
                fb_ = lor + (1.0 - lor) * kappa
                # what is left to gain: the predicted rise, plus twice the fit's largest
                # residual (its error at the vertex), if the grid's best point is inside it
                if inside and sp * max(pred, 0.0) <= PEAK_TOL * scale \
                        and sp * rr <= PEAK_NOISE * scale:
                    ended[i] = "smooth"
                    continue
                # the next grid: about the vertex's error, fine enough for the fit to reach
                # the tolerance (the guard: a perfect fit); it covers the best point when
                # the vertex is that close to it
                fine = (0.1 * PEAK_TOL * scale / max(rr * sp, 1e-300)) ** (1.0 / 3.0)
                f = min(max(3.0 * rr, fine, 1e-3), 0.5)
                if jr == 49:
                    ba, bb = 0.0, 0.0
                else:
                    ba = _P[ea]
                    bb = lor + (1.0 - lor) * _KAPPA[1 if onr else 0][jr]
                dist = max(abs(a - ba), abs(fb_ - bb))  # from the best point
                if kinky[i] and dist > 0.5 * f and up <= 0.0:
                    # a vertex here proved lower before, and the best point did not move:
                    # the next grid about the best point, holding the vertex
                    f = min(2.0 * dist, 0.5)
                else:
                    use[r], spec[i], fa[r], fb[r] = True, True, a, fb_
                    covers[i] = dist <= 0.5 * f
                step[i], stepb[i] = f * sa, f * sb_
            elif up <= 0.0 and edge:
                pass  # an edge point no higher than the best: the same grid about the best
            else:
                # a pattern step, along each axis: to the grid's edge (the horizon row
                # excepted), the maximum may be farther: the grid moves there and doubles (up
                # to 4 mesh edges); inside, the maximum lies between the grid's best point
                # and its neighbours (one of them would be higher otherwise): the next grid
                # spans that bracket, or, about a crease (e.g. a V-cavity G) found in it,
                # where the lines either side of it meet
                ca = cb = False
                if ja in (0, 6):
                    ma, step[i] = _P[ja], min(2.0 * sa, 4.0 * s0)
                else:
                    ma, ha = _MID[ja], _HALF[ja]
                    if jk >= 0:
                        ma, ha, ca = _crease(_P, vr[7 * jk:7 * jk + 7], ja, ma, ha)
                    step[i] = ha * sa
                if not onr:
                    if jk == 6 or jk == 0:
                        mb, stepb[i] = _P[jk], min(2.0 * sb_, 4.0 * s0)
                    else:
                        jk = 3 if jk < 0 else jk
                        mb, hb_, cb = _crease(_P, vr[ja:49:7], jk, _MID[jk], _HALF[jk])
                        stepb[i] = hb_ * sb_
                elif jk == 6:
                    mb, stepb[i] = 1.0, min(2.0 * sb_, 4.0 * s0)
                else:
                    d = (1.0 - lor) / 6.0  # the rows' spacing
                    b1 = d if jk < 0 else lor + (jk + 1) * d
                    b0 = max(b1 - 2.0 * d, lor)
                    mb, hb_ = (b1 + b0) / 2.0, (b1 - b0) / 2.0
                    if jk > 0:
                        mb, hb_, cb = _crease(lor + d * _K7, vr[ja:49:7], jk, mb, hb_)
                    stepb[i] = hb_ * sb_
                fa[r], fb[r], use[r] = ma, mb, True
                covers[i] = not (ca or cb)
            still.append(r)
        if any(use):
            m = np.array(use)
            w = c[m] + np.array(fa)[m, None] * t1[m] + np.array(fb)[m, None] * t2[m]
            w[:, 2] = np.maximum(w[:, 2], 0.0)
            centre[np.array(live)[m]] = w / np.sqrt(np.einsum("ni,ni->n", w, w))[:, None]
        for r, i in enumerate(live):
            if not use[r]:
                centre[i] = best[i]
        live = [live[r] for r in still]
        # only a search at its column's best keeps the rounds going; the others go on with it
        if not any(val[i] >= max(val[col[i]], val[col[i] + k]) for i in live):
            break
    out_v, out_w, out_e = [], [], []
    for c in range(k):
        a, b = c, c + k
        w = a if val[a] >= val[b] else b
        out_v.append(float(val[w]))
        out_w.append(best[w])
        out_e.append(ended[w])
    return out_v, out_w, out_e
