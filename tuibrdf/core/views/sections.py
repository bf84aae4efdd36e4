"""Sections of the hemisphere of outgoing directions that do not go through the normal.

The polar cross-sections of :mod:`tuibrdf.render.sections` lie in planes through the normal N; a
glossy lobe sits far from N at large θi, so the "perpendicular" plane through N (φr = ±90°)
misses it entirely (the seed's Cook-Torrance, kd = 0, f0 = 0.04, m = 0.07: 6.9e-30 sr⁻¹ there
at θi = 60° against a peak of 6.14).  The seed's claim about the lobe's width *across* the
plane of incidence is a statement about the great circle through the lobe's peak,
perpendicular to the plane of incidence.  This module gives those great circles.

A section is the great circle through a unit direction ``c`` (the *centre*: the peak, or the
mirror direction S) that leaves ``c`` along the unit tangent ::

    u(ψ) = cos ψ · e_θ + sin ψ · e_φ

where ``e_θ`` is the tangent at ``c`` toward larger θ in the vertical plane of ``c`` and
``e_φ = N × c / |N × c|`` the horizontal tangent (``e_y`` for a centre at φ = 0).  Its points
are ``w(t) = cos t · c + sin t · u(ψ)`` for the signed angle ``t`` from the centre.

- ``ψ = 90°``: perpendicular to the vertical plane of ``c`` (for ``c`` in the plane of
  incidence, the section across the lobe that the seed speaks of);
- ``ψ = 0°``: the vertical plane of ``c`` itself (for ``c`` in the plane of incidence: the
  plane of incidence, with ``t = θr − θc``);
- ``c = N``: ``e_θ = e_x``, ``e_φ = e_y`` by convention, so ``w(t)`` is the section through the
  normal at azimuth ``ψ`` (BRDF Explorer's θv plot with φv = ψ; its "unlocked" mode).

Only the part above the horizon (``w_z ≥ 0``) is a BRDF section; :func:`great_circle` returns
that mask with the directions.  Angles are in degrees (the user-facing unit), exact at
multiples of 90° (:func:`~tuibrdf.core.directions.sincos_deg`).  The frame's section through
its peak (:func:`tuibrdf.core.views.frame.compute_frame`, ``sections["peak"]``) is one.
"""

from __future__ import annotations

import numpy as np

from tuibrdf.core.directions import sincos_deg

#: azimuth of the section that crosses the plane of incidence at right angles
PERPENDICULAR = 90.0


def tangents(center: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(e_θ, e_φ)``: the unit tangents at ``center`` toward larger θ and larger φ.

    At the normal (and the nadir) the azimuth is undefined; ``e_θ = e_x`` and ``e_φ = e_y``
    there by convention, the limits for a centre approaching N along φ = 0."""
    c = np.asarray(center, dtype=float)
    rho = float(np.hypot(c[0], c[1]))
    if rho == 0.0:  # the pole: no vertical plane; φ = 0 by convention
        return np.array([1.0, 0.0, 0.0]), np.array([0.0, 1.0, 0.0])
    cp, sp = c[0] / rho, c[1] / rho  # rho > 0 checked above
    e_phi = np.array([-sp, cp, 0.0])
    e_theta = np.array([c[2] * cp, c[2] * sp, -rho])
    return e_theta, e_phi


def great_circle(
    center: np.ndarray,
    t_deg: np.ndarray,
    azimuth_deg: float = PERPENDICULAR,
) -> tuple[np.ndarray, np.ndarray]:
    """``(w, above)``: the directions ``w(t) = cos t · c + sin t · u(ψ)`` (shape ``(n, 3)``)
    for signed angles ``t_deg`` from ``center``, and where they lie above the horizon
    (``w_z ≥ 0``).  ``azimuth_deg`` is ψ (90° = across the vertical plane of ``center``)."""
    c = np.asarray(center, dtype=float)
    norm = float(np.sqrt(np.sum(c * c)))
    if c.shape != (3,) or not np.isfinite(norm) or norm == 0.0:
        raise ValueError(f"center must be a nonzero finite 3-vector, got {center!r}")
    c = c / norm  # norm > 0 checked above
    e_theta, e_phi = tangents(c)
    sa, ca = sincos_deg(float(azimuth_deg))
    u = float(ca) * e_theta + float(sa) * e_phi
    st, ct = sincos_deg(np.asarray(t_deg, dtype=float))
    w = ct[..., None] * c + st[..., None] * u
    w = w / np.sqrt(np.sum(w * w, axis=-1))[..., None]  # |w| = 1 up to rounding: renormalise
    return w, w[..., 2] >= 0.0


#: Rounds of :func:`fwhm` (one kernel call each, both sides at once) and the parts each splits
#: its brackets into: 16³ = 4096, so the bracket is then 1°/4096 (as 12 bisection steps, in a
#: quarter of the calls: a measured table's call costs ~0.5 ms before its first point); the
#: crossing is interpolated linearly inside it
FWHM_ROUNDS = 3
FWHM_SPLIT = 16
#: the inner points of a split bracket, as fractions of it
_FRACTIONS = np.arange(1, FWHM_SPLIT) / FWHM_SPLIT


def fwhm(fn, center: np.ndarray, azimuth_deg: float, t_deg: np.ndarray, v: np.ndarray,
         rounds: int = FWHM_ROUNDS) -> float | None:
    """The full width at half maximum (degrees) of the lobe around the largest of the samples
    ``v`` (scalar values at the signed angles ``t_deg`` along :func:`great_circle`'s section
    through ``center`` at ``azimuth_deg``), its two half-maximum crossings found *on the
    function* ``fn(w (n, 3)) → (n,)`` between the samples that bracket them: each round
    splits a bracket into :data:`FWHM_SPLIT` parts and keeps the first (from the lobe's side)
    that crosses half, then linear interpolation in the last bracket (a lobe narrower than
    the samples' spacing has its own width, not the spacing's).  The maximum is the largest
    sample (the section through the peak has it at t = 0).  A side that stays above half to
    the end of the samples ends there; None for a flat, empty or non-positive curve."""
    v = np.asarray(v, dtype=float)
    t = np.asarray(t_deg, dtype=float)
    if v.size == 0 or not np.all(np.isfinite(v)):
        return None
    vmax = float(np.max(v))
    if vmax <= 0.0 or float(np.min(v)) >= 0.5 * vmax:
        return None
    k = int(np.argmax(v))
    half = 0.5 * vmax
    below = np.flatnonzero(v < half)
    left, right = below[below < k], below[below > k]
    # brackets: a (value ≥ half) and b (value < half) on each side; an open side (no sample
    # below half) is the end sample, a = b
    ia = np.array([left[-1] + 1 if len(left) else 0, right[0] - 1 if len(right) else len(v) - 1])
    ib = np.array([left[-1] if len(left) else 0, right[0] if len(right) else len(v) - 1])
    a, b, fa, fb = t[ia], t[ib], v[ia], v[ib]
    side = np.arange(2)
    for _ in range(rounds if len(left) or len(right) else 0):
        # (2, SPLIT + 1) points per side, a … b; the inner ones evaluated, one call for both
        pts = np.concatenate([a[:, None], a[:, None] + (b - a)[:, None] * _FRACTIONS,
                              b[:, None]], axis=1)
        w, _above = great_circle(center, pts[:, 1:-1].reshape(-1), azimuth_deg)
        fm = np.asarray(fn(w), dtype=float).reshape(2, -1)
        vals = np.concatenate([fa[:, None], fm, fb[:, None]], axis=1)
        # the first point not at or above half (b itself if none is; a is): the bracket ends
        # there
        out = ~(vals >= half)
        j = np.argmax(out[:, 1:], axis=1) + 1
        j = np.where(out[side, j], j, FWHM_SPLIT)
        a, fa = pts[side, j - 1], vals[side, j - 1]
        b, fb = pts[side, j], vals[side, j]
    # fa ≥ half > fb where a ≠ b: the denominator is > 0 there
    open_side = a == b
    frac = np.divide(fa - half, fa - fb, out=np.zeros(2), where=~open_side)
    x = a + frac * (b - a)
    return float(x[1] - x[0])
