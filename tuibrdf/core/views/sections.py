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
