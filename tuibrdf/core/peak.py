"""The peak of a lobe: the one finder every number on screen comes from.

``find_peaks(model, values, θi)`` returns the largest ``f`` (or ``f·cos θo`` with
``cosine=True``) over the closed upper hemisphere and its direction:

1. candidates: the vertices of ``hemisphere(PEAK_LEVEL)`` (edges ≈ 2°), the mirror direction
   S, the horizon at φ = 0 (where a grazing lobe ends up) and the normal;
2. from the best candidate and from S, a pattern search in the tangent plane: a 7×7 grid of
   half-width ``step`` around the best point so far, ``step`` shrinking by
   :data:`PEAK_SHRINK` (about the grid's spacing, so the new grid covers the old cell) for
   :data:`PEAK_ROUNDS` rounds (from one mesh edge down to ≈ 1e-9°);
   points that fall below the horizon are put back onto it; the search stops early when no
   round improved any value by more than 1e-12 (relative) for :data:`PEAK_PATIENCE` rounds
   (the step has then shrunk 60× below the last move).  A search climbing a lower local
   maximum (often the one from S) stops counting once 10× its last gain cannot lift it to
   the best value of its channel: it no longer keeps the others going for all the rounds
   (median 6.6 → 3.4 ms over 28 cases, values within 6e-11 relative of the full run).  Every
   round is one vectorised kernel call for all the searches.

An RGB model gets four peaks, each with its own direction: the Rec.709 luminance ``Y`` and
each channel ``R``, ``G``, ``B``; a scalar model one.  ``Peak.label`` says which.

A kernel whose value grows without bound toward the horizon (a microfacet lobe at θi = 90°
exactly: ``1/cos θo`` is not cancelled there) has no maximum; the finder then returns the
largest value it reached, ≈ 1e-6° above the horizon, deterministically.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, NamedTuple

import numpy as np

from .conventions import luminance
from .evaluate import evaluate_resolved
from .frame import incident, mirror, phi_of, theta_of
from .mesh import hemisphere
from .params import Model

PEAK_LEVEL = 5
PEAK_ROUNDS = 20
PEAK_SHRINK = 0.35
PEAK_PATIENCE = 4
_PATTERN = np.stack(np.meshgrid(np.linspace(-1, 1, 7), np.linspace(-1, 1, 7)), -1).reshape(-1, 2)
HORIZON_MIRROR = np.array([1.0, 0.0, 0.0])
NORMAL = np.array([0.0, 0.0, 1.0])


class Peak(NamedTuple):
    """The largest value and where it is (degrees; φ in (−180°, 180°], 0 at the normal).
    ``label``: ``""`` for a scalar model, ``"Y"`` (luminance), ``"R"``, ``"G"`` or ``"B"``."""

    value: float
    theta_deg: float
    phi_deg: float
    label: str = ""


def radiance(model: Model, values: Mapping[str, Any], wi: np.ndarray, wo: np.ndarray,
             cosine: bool) -> np.ndarray:
    """``f(wi, wo)`` (times ``cos θo`` when ``cosine``) at ``wo (n, 3)``: ``(n,)``/``(n, 3)``."""
    f = np.asarray(evaluate_resolved(model, values, wi, wo), dtype=float)
    if not cosine:
        return f
    c = wo[:, 2]
    return f * (c[:, None] if f.ndim == 2 else c)


def scores(g: np.ndarray) -> np.ndarray:
    """``(n, 1)`` for scalar values, ``(n, 4)`` = (Y, R, G, B) for RGB ones."""
    if g.ndim == 1:
        return g[:, None]
    return np.concatenate([luminance(g)[:, None], g], axis=1)


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Row-wise cross product of ``(m, 3)`` arrays (``np.cross`` costs 10× more here)."""
    return np.stack([a[:, 1] * b[:, 2] - a[:, 2] * b[:, 1], a[:, 2] * b[:, 0] - a[:, 0] * b[:, 2],
                     a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]], axis=1)


def _tangents(d: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Two unit vectors orthogonal to each row of ``d (m, 3)`` and to each other."""
    ref = np.where((np.abs(d[:, 0]) < 0.9)[:, None], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0])
    t1 = _cross(d, ref)
    t1 /= np.linalg.norm(t1, axis=1, keepdims=True)  # ≠ 0: ref is never parallel to d
    return t1, _cross(d, t1)


def _upper(d: np.ndarray) -> np.ndarray:
    """Unit directions, put onto the horizon if they fell below it."""
    d = np.array(d, dtype=float)
    d[..., 2] = np.maximum(d[..., 2], 0.0)
    return d / np.linalg.norm(d, axis=-1, keepdims=True)  # ≠ 0: steps are ≪ 1 rad


def _angles(w: np.ndarray) -> tuple[float, float]:
    theta = float(np.degrees(theta_of(w)))
    phi = float(np.degrees(phi_of(w))) if theta > 0.0 else 0.0
    return theta, phi


def find_peaks(model: Model, values: Mapping[str, Any], theta_i_deg: float, *,
               cosine: bool = False, level: int = PEAK_LEVEL,
               phi_i_deg: float = 180.0) -> tuple[Peak, ...]:
    """``(Peak,)`` for a scalar model, ``(Y, R, G, B)`` peaks for an RGB one (see module);
    the light at ``θi``, ``φi`` (:func:`~tuibrdf.core.frame.incident`)."""
    if not 0.0 <= float(theta_i_deg) <= 90.0:  # also refuses NaN
        raise ValueError(f"theta_i = {theta_i_deg!r} is invalid: expected in [0, 90]°")
    wi = incident(theta_i_deg, phi_i_deg)
    s_dir = mirror(wi)
    # the horizon on the mirror side: HORIZON_MIRROR turned with the light's azimuth
    h_mirror = incident(90.0, float(phi_i_deg) + 180.0)
    cand = np.concatenate([hemisphere(level).vertices, [s_dir, h_mirror, NORMAL]])
    sc = scores(radiance(model, values, wi, cand, cosine))
    k = sc.shape[1]
    cols = np.arange(k)
    first = np.argmax(sc, axis=0)
    i_mirror = len(cand) - 3
    # two searches per column: from its best candidate and from the mirror direction
    pts = np.concatenate([cand[first], np.repeat(s_dir[None, :], k, axis=0)])
    col = np.concatenate([cols, cols])
    val = np.concatenate([sc[first, cols], sc[i_mirror, cols]])
    step = np.radians(63.4) / 2**level  # about one mesh edge
    rows = np.arange(len(pts))
    idle = 0
    for _ in range(PEAK_ROUNDS):
        t1, t2 = _tangents(pts)
        trial = _upper(pts[:, None, :] + step * (_PATTERN[None, :, :1] * t1[:, None, :]
                                                 + _PATTERN[None, :, 1:] * t2[:, None, :]))
        st = scores(radiance(model, values, wi, trial.reshape(-1, 3), cosine))
        v = st.reshape(len(pts), len(_PATTERN), k)[rows, :, col]  # (searches, 25)
        j = np.argmax(v, axis=1)
        better = v[rows, j] > val
        up = np.where(better, v[rows, j] - val, 0.0)
        pts[better] = trial[rows, j][better]
        val[better] = v[rows, j][better]
        # a search below its column's best counts only while it could still reach it (its
        # gains shrink geometrically, ≈ 8× per round near a smooth maximum: 10× its last gain
        # bounds what is left); the guard keeps 0/0 out for a zero function
        top = np.tile(np.maximum(val[:k], val[k:]), 2)
        contender = val + 10.0 * up >= top
        gain = np.max(np.where(contender, up, 0.0) / np.maximum(np.abs(val), 1e-300))
        step *= PEAK_SHRINK
        idle = idle + 1 if gain <= 1e-12 else 0
        if idle >= PEAK_PATIENCE:
            break
    labels = ("",) if k == 1 else ("Y", "R", "G", "B")
    out = []
    for c in range(k):
        a, b = c, c + k
        w = a if val[a] >= val[b] else b
        out.append(Peak(float(val[w]), *_angles(pts[w]), labels[c]))
    return tuple(out)


def peak_of(model: Model, values: Mapping[str, Any], theta_i_deg: float, *,
            cosine: bool = False) -> Peak:
    """The one peak a scalar reading uses: the value, or the luminance of an RGB model."""
    return find_peaks(model, values, theta_i_deg, cosine=cosine)[0]
