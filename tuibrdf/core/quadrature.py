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
from .mesh import MAX_LEVEL, hemisphere, refine_adaptive
from .models import get_model
from .params import Model

#: Uniform level of the albedo / peak quadrature: 20,641 vertices; the albedo of a moderately
#: sharp lobe (phong n = 200, ggx α = 0.1, cook-torrance m = 0.1) is within 1e-3 (measured in
#: docs/accuracy.md).
DEFAULT_LEVEL = 6
#: Adaptive tolerance (relative midpoint-interpolation error) for lobes the uniform mesh does
#: not resolve: ≤ 5e-5 albedo error on phong n = 5000 and cook-torrance m = 0.01 at ≤ 85°.
DEFAULT_TOL = 1e-5
#: Finest level adaptive refinement reaches in the quadrature (0.06° edges at level 10).
ADAPTIVE_MAX_LEVEL = 10
#: "auto" keeps the uniform result when the next coarser level agrees within this (relative);
#: second order, so the error is then about a third of it.
RESOLVED_RTOL = 3e-3
METHODS = ("auto", "uniform", "adaptive")
#: Below this cos θi (85°) adaptive refinement may go deeper (see adaptive_max_level).
GRAZING_COS = float(np.cos(np.radians(85.0)))
GRAZING_EXTRA_LEVELS = 3
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


def _uniform(model: Model, values, wi: np.ndarray, level: int) -> tuple[np.ndarray, float]:
    """Vertex rule at ``level`` and how far from resolved the integrand looks there.

    The second value is ``|a_L − a_(L−1)| / (RESOLVED_RTOL·|a_L|)`` (the level below is a prefix
    of this one, so its values are already computed): ≤ 1 means resolved; since the rule is
    second order, one more level divides it by about 4.  It is ``inf`` when a vertex misses the
    lobe's top by more than 2× (``f·cos`` at the mirror direction, where a sharp lobe can hide
    between vertices while both levels agree on missing it).
    """
    mesh = hemisphere(level)
    g = _radiance(model, values, wi, mesh.vertices)
    a = mesh.integrate(g)
    coarse = hemisphere(level - 1)
    a0 = coarse.integrate(g[: len(coarse.vertices)])
    bad = float(np.max(np.abs(a - a0) / (RESOLVED_RTOL * np.abs(a) + 1e-12)))
    top = _radiance(model, values, wi, mirror(wi)[None, :])[0]
    if np.any(top > 2.0 * g.max(axis=0)):
        bad = np.inf
    return a, bad


def adaptive_max_level(cos_i: float) -> int:
    """:data:`ADAPTIVE_MAX_LEVEL`, plus up to 3 levels at grazing incidence.

    A microfacet lobe reflected at θi is squeezed across the plane of incidence by about
    cos θi (a tilt δ of H moves wo by ~2δ·cos θi sideways): at θi = 89° a lobe of width α =
    0.005 is 0.01° thin, below the 0.06° edges of level 10.  One level per halving of cos θi
    below cos 85°, at most 3 (measured in docs/accuracy.md).
    """
    ratio = GRAZING_COS / max(float(cos_i), 1e-300)
    extra = int(np.clip(np.round(np.log2(ratio)), 0, GRAZING_EXTRA_LEVELS)) if ratio > 1 else 0
    return ADAPTIVE_MAX_LEVEL + extra


def albedo_resolved(model: Model, values: Mapping[str, Any], theta_i_deg: float, *,
                    level: int = DEFAULT_LEVEL, tol: float = DEFAULT_TOL,
                    method: str = "auto") -> float | np.ndarray:
    """Directional albedo ``∫ f cos θo dω`` at incidence ``theta_i_deg``: a float, or ``(3,)``
    for an RGB model.

    ``method="uniform"``: the vertex rule of ``hemisphere(level)``.  ``"adaptive"``:
    :func:`refine_adaptive` at ``tol`` from level 2 down to :data:`ADAPTIVE_MAX_LEVEL`,
    focused on the mirror direction (deeper at grazing incidence: :func:`adaptive_max_level`).
    ``"auto"`` (default): uniform at ``level``, or one level
    finer when that should suffice, if the lobe is resolved there (see :func:`_uniform`), else
    adaptive
    (``docs/accuracy.md`` has the measurements behind this).
    """
    if method not in METHODS:
        raise ValueError(f"method = {method!r} is invalid: expected one of {', '.join(METHODS)}")
    wi = incident(_check_theta(theta_i_deg))
    if method == "uniform":
        return _scalar(_uniform(model, values, wi, level)[0])
    if method == "auto":
        a, bad = _uniform(model, values, wi, level)
        if bad <= 1.0:
            return _scalar(a)
        if bad <= 4.0 and level < MAX_LEVEL:  # one more level should do (second order)
            a, bad = _uniform(model, values, wi, level + 1)
            if bad <= 1.0:
                return _scalar(a)
    ad = refine_adaptive(lambda wo: _radiance(model, values, wi, wo), tol,
                         max_level=adaptive_max_level(wi[2]), base_level=2, focus=mirror(wi))
    return _scalar(ad.integrate())


def albedo(model: str | Model, params: Mapping[str, Any] | None = None,
           theta_i_deg: float = 0.0, *, level: int = DEFAULT_LEVEL, tol: float = DEFAULT_TOL,
           method: str = "auto") -> float | np.ndarray:
    """Directional albedo of ``model`` with user ``params`` (see :func:`albedo_resolved`)."""
    m, v = _resolve(model, params)
    return albedo_resolved(m, v, theta_i_deg, level=level, tol=tol, method=method)


def albedo_curve_resolved(model: Model, values: Mapping[str, Any],
                          thetas_deg: Sequence[float] | np.ndarray, *,
                          level: int = DEFAULT_LEVEL, tol: float = DEFAULT_TOL,
                          method: str = "auto") -> np.ndarray:
    """Albedo at each incidence: ``(n,)``, or ``(n, 3)`` for an RGB model.

    Vectorised over the mesh; the loop is over incidence angles only (a ``(n, N)`` batch would
    hold every kernel temporary n times)."""
    thetas = np.atleast_1d(np.asarray(thetas_deg, dtype=float))
    out = [albedo_resolved(model, values, t, level=level, tol=tol, method=method)
           for t in thetas]
    return np.array(out, dtype=float)


def albedo_curve(model: str | Model, params: Mapping[str, Any] | None,
                 thetas_deg: Sequence[float] | np.ndarray, *, level: int = DEFAULT_LEVEL,
                 tol: float = DEFAULT_TOL, method: str = "auto") -> np.ndarray:
    m, v = _resolve(model, params)
    return albedo_curve_resolved(m, v, thetas_deg, level=level, tol=tol, method=method)


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
