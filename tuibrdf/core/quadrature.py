"""Quadrature on the icosahedral hemisphere: albedo, albedo curve, reciprocity error, peak.

Directional albedo ``a(θi) = ∫ f(wi, wo) cos θo dωo`` is the vertex rule of
:func:`tuibrdf.core.mesh.hemisphere` (second order: the error falls ~4× per level once the mesh
resolves the lobe), or, with ``tol=``, the adaptive mesh of
:func:`tuibrdf.core.mesh.refine_adaptive` focused on the mirror direction (what a sharp lobe
needs).  :data:`DEFAULT_LEVEL` and :data:`DEFAULT_TOL` were chosen from
``scripts/bench_accuracy.py`` (``docs/accuracy.md``).

Every public function takes a model (registry name or :class:`~tuibrdf.core.params.Model`) and
user parameter values, validated with ``Model.resolve``; the ``*_resolved`` variants take a
``Model`` and values that are already resolved (the app and renderers resolve once).  RGB models
give ``(3,)`` per albedo and ``(n, 3)`` per curve.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any, NamedTuple

import numpy as np

from .evaluate import evaluate_resolved
from .frame import incident, mirror, phi_of, theta_of
from .mesh import hemisphere, refine_adaptive
from .models import get_model
from .params import Model

#: Uniform level of the albedo / peak quadrature: 20,641 vertices; the albedo of a moderately
#: sharp lobe (phong n = 200, ggx α = 0.1, cook-torrance m = 0.1) is within 1e-3 (measured in
#: docs/accuracy.md).
DEFAULT_LEVEL = 6
#: Adaptive tolerance (relative midpoint-interpolation error) giving ~1e-3 on the hard lobes.
DEFAULT_TOL = 1e-4
#: Finest level adaptive refinement may reach (0.25° edges at level 8, 0.06° at 10).
ADAPTIVE_MAX_LEVEL = 10
#: Level of the all-pairs reciprocity check (341 directions, 116,281 pairs).
RECIPROCITY_LEVEL = 3


class Peak(NamedTuple):
    """The largest value over the hemisphere and where it is (degrees, φ in (−180°, 180°])."""

    value: float | np.ndarray
    theta_deg: float
    phi_deg: float


def _resolve(model: str | Model, params: Mapping[str, Any] | None) -> tuple[Model, dict]:
    m = get_model(model)
    return m, m.resolve(params)


def _check_theta(theta_i_deg: float) -> float:
    t = float(theta_i_deg)
    if not 0.0 <= t <= 90.0:  # also rejects NaN
        raise ValueError(f"theta_i = {theta_i_deg!r} is invalid: expected in [0, 90]°")
    return t


def _radiance(model: Model, values: Mapping[str, Any], wi: np.ndarray, wo: np.ndarray,
              cosine: bool = True) -> np.ndarray:
    """``f(wi, wo)·cos θo`` (or ``f`` alone) for many ``wo (n, 3)`` and one ``wi (3,)``."""
    wo = np.asarray(wo, dtype=float)
    f = np.asarray(evaluate_resolved(model, values, np.broadcast_to(wi, wo.shape), wo))
    if not cosine:
        return f
    c = wo[:, 2]
    return f * (c[:, None] if f.ndim == 2 else c)


def _scalar(x: np.ndarray) -> float | np.ndarray:
    x = np.asarray(x, dtype=float)
    return float(x) if x.ndim == 0 else x


# ---------------------------------------------------------------------------------------------
# albedo


def albedo_resolved(model: Model, values: Mapping[str, Any], theta_i_deg: float, *,
                    level: int = DEFAULT_LEVEL, tol: float | None = None
                    ) -> float | np.ndarray:
    """Directional albedo ``∫ f cos θo dω`` at incidence ``theta_i_deg``: a float, or ``(3,)``
    for an RGB model.  ``tol`` switches to adaptive refinement (from ``level`` if it is ≤ 3,
    else from level 2) focused on the mirror direction."""
    wi = incident(_check_theta(theta_i_deg))
    if tol is None:
        mesh = hemisphere(level)
        return _scalar(mesh.integrate(_radiance(model, values, wi, mesh.vertices)))
    a = refine_adaptive(lambda wo: _radiance(model, values, wi, wo), tol,
                        max_level=ADAPTIVE_MAX_LEVEL, base_level=2,
                        focus=mirror(wi))
    return _scalar(a.integrate())


def albedo(model: str | Model, params: Mapping[str, Any] | None = None,
           theta_i_deg: float = 0.0, *, level: int = DEFAULT_LEVEL, tol: float | None = None
           ) -> float | np.ndarray:
    """Directional albedo of ``model`` with user ``params`` (see :func:`albedo_resolved`)."""
    m, v = _resolve(model, params)
    return albedo_resolved(m, v, theta_i_deg, level=level, tol=tol)


def albedo_curve_resolved(model: Model, values: Mapping[str, Any],
                          thetas_deg: Sequence[float] | np.ndarray, *,
                          level: int = DEFAULT_LEVEL, tol: float | None = None) -> np.ndarray:
    """Albedo at each incidence: ``(n,)``, or ``(n, 3)`` for an RGB model.

    Vectorised over the mesh; the loop is over incidence angles only (a ``(n, N)`` batch would
    hold every kernel temporary n times)."""
    thetas = np.atleast_1d(np.asarray(thetas_deg, dtype=float))
    out = [albedo_resolved(model, values, t, level=level, tol=tol) for t in thetas]
    return np.array(out, dtype=float)


def albedo_curve(model: str | Model, params: Mapping[str, Any] | None,
                 thetas_deg: Sequence[float] | np.ndarray, *, level: int = DEFAULT_LEVEL,
                 tol: float | None = None) -> np.ndarray:
    m, v = _resolve(model, params)
    return albedo_curve_resolved(m, v, thetas_deg, level=level, tol=tol)


# ---------------------------------------------------------------------------------------------
# reciprocity


def reciprocity_error_resolved(model: Model, values: Mapping[str, Any], *,
                               level: int = RECIPROCITY_LEVEL) -> float:
    """``max |f(wi, wo) − f(wo, wi)| / max f`` over all pairs of mesh vertices (0 for a model
    that is 0 everywhere)."""
    v = hemisphere(level).vertices
    wi, wo = np.broadcast_arrays(v[:, None, :], v[None, :, :])
    a = np.asarray(evaluate_resolved(model, values, wi, wo))
    b = np.asarray(evaluate_resolved(model, values, wo, wi))
    top = float(np.max(np.abs(a)))
    if top == 0.0:
        return 0.0
    return float(np.max(np.abs(a - b)) / top)


def reciprocity_error(model: str | Model, params: Mapping[str, Any] | None = None, *,
                      level: int = RECIPROCITY_LEVEL) -> float:
    m, v = _resolve(model, params)
    return reciprocity_error_resolved(m, v, level=level)


# ---------------------------------------------------------------------------------------------
# peak

#: Local search after the best mesh vertex: PEAK_STEPS rounds of a 5×5 tangent-plane pattern
#: shrinking by PEAK_SHRINK (0.6³⁰ ≈ 2e-7 of the starting step, below 1e-5°).
PEAK_STEPS = 30
PEAK_SHRINK = 0.6
_PATTERN = np.stack(np.meshgrid(np.linspace(-1, 1, 5), np.linspace(-1, 1, 5)), -1).reshape(-1, 2)


def _tangents(d: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Two unit vectors orthogonal to ``d`` and to each other (any pair)."""
    ref = np.array([1.0, 0.0, 0.0]) if abs(d[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    t1 = np.cross(d, ref)
    t1 /= np.linalg.norm(t1)  # ≠ 0: ref is never parallel to d
    return t1, np.cross(d, t1)


def _upper(d: np.ndarray) -> np.ndarray:
    """Unit directions, pushed onto the horizon if they fell below it."""
    d = np.array(d, dtype=float)
    d[..., 2] = np.maximum(d[..., 2], 0.0)
    return d / np.linalg.norm(d, axis=-1, keepdims=True)  # ≠ 0: steps are ≪ 1 rad


def peak_resolved(model: Model, values: Mapping[str, Any], theta_i_deg: float, *,
                  level: int = DEFAULT_LEVEL, cosine: bool = False) -> Peak:
    """Largest ``f`` (or ``f cos θo`` with ``cosine=True``) over the hemisphere.

    The best of the mesh vertices, the mirror direction and the normal, then a local pattern
    search in the tangent plane (which works at the pole and clamps to the horizon).  An RGB
    model is ranked by its channel mean and returns its ``(3,)`` value there.
    """
    wi = incident(_check_theta(theta_i_deg))
    cand = np.concatenate([hemisphere(level).vertices, [mirror(wi)], [[0.0, 0.0, 1.0]]])

    def score(wo: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        g = _radiance(model, values, wi, wo, cosine)
        return (g.mean(axis=1) if g.ndim == 2 else g), g

    s, g = score(cand)
    k = int(np.argmax(s))
    best, best_s, best_g = cand[k], s[k], g[k]
    step = np.radians(63.4) / 2**level  # about one mesh edge
    for _ in range(PEAK_STEPS):
        t1, t2 = _tangents(best)
        trial = _upper(best + step * (_PATTERN[:, :1] * t1 + _PATTERN[:, 1:] * t2))
        s, g = score(trial)
        k = int(np.argmax(s))
        if s[k] > best_s:
            best, best_s, best_g = trial[k], s[k], g[k]
        step *= PEAK_SHRINK
    theta = float(np.degrees(theta_of(best)))
    phi = float(np.degrees(phi_of(best))) if theta > 0.0 else 0.0
    return Peak(_scalar(best_g), theta, phi)


def peak(model: str | Model, params: Mapping[str, Any] | None = None,
         theta_i_deg: float = 0.0, *, level: int = DEFAULT_LEVEL, cosine: bool = False) -> Peak:
    m, v = _resolve(model, params)
    return peak_resolved(m, v, theta_i_deg, level=level, cosine=cosine)
