"""Quadrature on the hemisphere: the directional albedo (with an error estimate) and the albedo
curve.  (The peak of a lobe is :func:`tuibrdf.core.sphere.peak.find_peaks`, the one peak finder.)

Directional albedo ``a(wi) = ∫ f(wi, wo) cos θo dωo`` is, by default (``method="auto"``), the
nested adaptive Gauss–Kronrod rule of :mod:`~tuibrdf.core.sphere.integrator` in polar
coordinates about the model's lobe: the frame, the lobe's width and the integrand's kinks come
from :func:`tuibrdf.core.sphere.lobes.lobe` (the per-model knowledge of where lobes are).  It
returns an error estimate with the value (:func:`albedo_estimate`); :func:`exceeds_one` is the
one energy test (albedo minus its error above 1).  ``method="uniform"`` is the vertex rule of
:func:`tuibrdf.core.sphere.mesh.hemisphere` at ``level`` and ``method="adaptive"`` the adaptive
mesh of :func:`tuibrdf.core.sphere.mesh.refine_adaptive` at ``tol``, kept for comparison
(``scripts/bench_accuracy.py``, ``docs/reference/accuracy.md``).

Every public function takes a model (registry name or :class:`~tuibrdf.core.params.Model`) and
user parameter values, validated with ``Model.resolve``; the ``*_resolved`` variants take a
``Model`` and values that are already resolved (the app and renderers resolve once).  RGB models
give ``(3,)`` per albedo and ``(n, 3)`` per curve.  The incidence is ``(θi, φi)`` in degrees,
``φi = 180°`` by default (the viewer's light; for an isotropic model φi changes nothing).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from typing import Any, NamedTuple

import numpy as np

from tuibrdf.core.directions import check_phi_i, check_theta_i, incident, mirror, sincos_deg
from tuibrdf.core.evaluate import evaluate_resolved, f_cos
from tuibrdf.core.params import Model
from tuibrdf.core.registry import get_model
from tuibrdf.core.sphere import integrator
from tuibrdf.core.sphere.lobes import MEASURED_MAX_EVALS, Lobe, lobe
from tuibrdf.core.sphere.mesh import hemisphere, refine_adaptive

#: Uniform level of ``method="uniform"``: 20,641 vertices.
DEFAULT_LEVEL = 6
#: Adaptive-mesh tolerance of ``method="adaptive"`` (relative integral error per triangle).
DEFAULT_TOL = 1e-5
#: Relative tolerance of the default albedo, per channel: its error estimate is at most this
#: (or the evaluation budget ran out, and the estimate says so).  The estimate (|K − G|
#: summed) is pessimistic: measured errors are ≤ 2.2e-8 at every model's defaults and
#: ≤ 3.4e-7 on the hard cases (docs/reference/accuracy.md).  1e-6 costs 25 % more evaluations for
#: errors already below 1e-7; 1e-4 saves 4 % for errors up to 4.3e-7 (2.8e-6 before the
#: horizon grading): too close to the 1e-6 target.
DEFAULT_RTOL = 1e-5
#: Absolute floor of the tolerance (an albedo of 0 needs no relative accuracy).
ATOL = 1e-13
#: Evaluations per incidence after which refinement stops (a discontinuous integrand, e.g.
#: measured data with nearest-bin lookup): bounds time and memory; the error says how far it
#: got.  ~0.2 µs per evaluation for the analytic models.
MAX_EVALS = 200_000
#: Finest level adaptive refinement reaches in the quadrature (0.06° edges at level 10).
ADAPTIVE_MAX_LEVEL = 10
METHODS = ("auto", "uniform", "adaptive")
#: Below this cos θi (85°) adaptive refinement may go deeper (see adaptive_max_level).
GRAZING_COS = float(np.cos(np.radians(85.0)))
GRAZING_EXTRA_LEVELS = 3


class AlbedoEstimate(NamedTuple):
    """A directional albedo and an estimate of its absolute error (same shape: a float, or
    ``(3,)`` for an RGB model; ``(n,)``/``(n, 3)`` for a curve)."""

    value: float | np.ndarray
    error: float | np.ndarray


def exceeds_one(estimate: AlbedoEstimate | tuple) -> bool:
    """The energy test: True when the albedo is above 1 by more than its error estimate
    (``value − error > 1`` in some channel or at some incidence).  A model that conserves
    energy is never flagged because of quadrature error."""
    value, error = estimate
    return bool(np.any(np.asarray(value, dtype=float) - np.asarray(error, dtype=float) > 1.0))


def _resolve(model: str | Model, params: Mapping[str, Any] | None) -> tuple[Model, dict]:
    m = get_model(model)
    return m, m.resolve(params)


def albedo_f(model: Model, values: Mapping[str, Any]) -> Callable[[np.ndarray, np.ndarray],
                                                                  np.ndarray]:
    """The f ``(wi, wo) -> f`` the albedo of ``model`` integrates: its kernel, or what it
    names instead (:attr:`Model.albedo_kernel`: a ``.bsdf`` file's own f to the horizon)."""
    if model.albedo_kernel is not None:
        return model.albedo_kernel

    def f(wi, wo):
        return evaluate_resolved(model, values, wi, wo)

    return f


def _integrand(model: Model, values: Mapping[str, Any], wi: np.ndarray,
               wo: np.ndarray) -> np.ndarray:
    """The albedo's integrand ``f(wi, wo)·cos θo`` for many ``wo (n, 3)`` and one ``wi (3,)``
    (the uniform and adaptive mesh rules)."""
    wo = np.asarray(wo, dtype=float)
    return f_cos(albedo_f(model, values)(np.broadcast_to(wi, wo.shape), wo), wo)


def _scalar(x: np.ndarray) -> float | np.ndarray:
    x = np.asarray(x, dtype=float)
    return float(x) if x.ndim == 0 else x


# ---------------------------------------------------------------------------------------------
# albedo


def albedo_rule(model: Model, values: Mapping[str, Any],
                thetas_deg: Sequence[float] | np.ndarray, phi_i_deg: float = 180.0, *,
                rtol: float = DEFAULT_RTOL, max_evals: int = MAX_EVALS, hint: Lobe | None = None,
                kernel: Callable[[np.ndarray, np.ndarray], np.ndarray] | None = None):
    """The default rule's whole result (:func:`tuibrdf.core.sphere.integrator.integrate`: value,
    error
    estimate, evaluations per incidence) at each incidence, in one batch.  ``hint`` replaces
    the model's :func:`lobe` and ``kernel(wi, wo)`` its :func:`albedo_f` (the benchmarks and
    tests count calls, or drop one part of the hint, through them)."""
    thetas = np.atleast_1d(np.asarray(thetas_deg, dtype=float))
    for t in thetas.tolist():
        check_theta_i(t)
    # one call for θi and φi (elementwise: the same values as two)
    s, c = sincos_deg(np.append(thetas, check_phi_i(phi_i_deg)))
    st, ct = s[:-1], c[:-1]
    sp, cp = np.full(len(thetas), s[-1]), np.full(len(thetas), c[-1])
    if hint is None:
        hint = lobe(model, values, rtol)
        if model.measured:  # measured data's albedo: in effect the rule's first round
            hint = hint._replace(max_evals=MEASURED_MAX_EVALS)
    kernel = kernel or albedo_f(model, values)

    def run(azimuths, sel=slice(None)):
        return integrator.integrate(kernel, hint.frame,
                                    integrator.cases(st[sel], ct[sel], sp[sel], cp[sel]),
                                    scale=hint.scale, radial_breaks=hint.breaks,
                                    symmetric=hint.symmetric, rtol=rtol, atol=ATOL,
                                    max_evals=min(max_evals, hint.max_evals or max_evals),
                                    azimuth_breaks=azimuths, horizon=hint.horizon,
                                    rings=hint.rings, outer_k7=hint.outer_k7)

    r = run(hint.azimuths)
    if hint.second_layout is not None and np.any(ct < hint.second_layout):
        # the integrand has kinks the hint does not place (lobes.Lobe.second_layout): these
        # incidences again on a second outer layout; the difference joins the error
        sel = np.flatnonzero(ct < hint.second_layout)
        r2 = run(_shifted(hint.azimuths), sel)
        r.error[sel] = np.maximum(r.error[sel], r2.error) + np.abs(r.value[sel] - r2.value)
        r.evaluations[sel] += r2.evaluations
    return r


def _shifted(azimuths):
    """Outer breakpoints between the usual ones: ψ = (2k + 1)π/16 besides ``azimuths``."""
    extra = [(2 * k + 1) * np.pi / 16 for k in range(8)]

    def out(st, ct):
        return [*(azimuths(st, ct) if azimuths is not None else []), *extra]

    return out


def albedo_rule_counted(model: Model, values: Mapping[str, Any],
                        thetas_deg: Sequence[float] | np.ndarray, phi_i_deg: float = 180.0,
                        **kw: Any) -> tuple[Any, int, int]:
    """:func:`albedo_rule`'s result, its evaluations at the first incidence and the number of
    kernel calls it made (how the benchmarks and tests count the rule's rounds); ``kw`` as
    :func:`albedo_rule` takes them (but ``kernel``)."""
    calls, g = 0, albedo_f(model, values)

    def f(wi, wo):
        nonlocal calls
        calls += 1
        return g(wi, wo)

    r = albedo_rule(model, values, thetas_deg, phi_i_deg, kernel=f, **kw)
    return r, int(r.evaluations[0]), calls


def albedo_curve_estimate_resolved(model: Model, values: Mapping[str, Any],
                                   thetas_deg: Sequence[float] | np.ndarray,
                                   phi_i_deg: float = 180.0, *, rtol: float = DEFAULT_RTOL,
                                   max_evals: int = MAX_EVALS) -> AlbedoEstimate:
    """Albedo and error estimate at each incidence, integrated in one batch (one kernel call
    per refinement round for the whole curve): arrays ``(n,)``, or ``(n, 3)`` for RGB."""
    r = albedo_rule(model, values, thetas_deg, phi_i_deg, rtol=rtol, max_evals=max_evals)
    return AlbedoEstimate(r.value, r.error)


def albedo_estimate_resolved(model: Model, values: Mapping[str, Any], theta_i_deg: float,
                             phi_i_deg: float = 180.0, *, rtol: float = DEFAULT_RTOL,
                             max_evals: int = MAX_EVALS) -> AlbedoEstimate:
    """Directional albedo at ``(θi, φi)`` (degrees) with an estimate of its absolute error
    (:mod:`tuibrdf.core.sphere.integrator`: nested adaptive Gauss–Kronrod about the model's
    lobe)."""
    e = albedo_curve_estimate_resolved(model, values, [theta_i_deg], phi_i_deg, rtol=rtol,
                                       max_evals=max_evals)
    return AlbedoEstimate(_scalar(e.value[0]), _scalar(e.error[0]))


def albedo_estimate(model: str | Model, params: Mapping[str, Any] | None = None,
                    theta_i_deg: float = 0.0, phi_i_deg: float = 180.0, *,
                    rtol: float = DEFAULT_RTOL, max_evals: int = MAX_EVALS) -> AlbedoEstimate:
    """:func:`albedo_estimate_resolved` with a model name and user ``params``."""
    m, v = _resolve(model, params)
    return albedo_estimate_resolved(m, v, theta_i_deg, phi_i_deg, rtol=rtol,
                                    max_evals=max_evals)


def _uniform(model: Model, values, wi: np.ndarray, level: int) -> np.ndarray:
    """Vertex rule of ``hemisphere(level)``."""
    mesh = hemisphere(level)
    return mesh.integrate(_integrand(model, values, wi, mesh.vertices))


def adaptive_max_level(cos_i: float) -> int:
    """:data:`ADAPTIVE_MAX_LEVEL`, plus up to 3 levels at grazing incidence.

    A microfacet lobe reflected at θi is squeezed across the plane of incidence by about
    cos θi (a tilt δ of H moves wo by ~2δ·cos θi sideways).  One level per halving of cos θi
    below cos 85°, at most 3.
    """
    ratio = GRAZING_COS / max(float(cos_i), 1e-300)
    extra = int(np.clip(np.round(np.log2(ratio)), 0, GRAZING_EXTRA_LEVELS)) if ratio > 1 else 0
    return ADAPTIVE_MAX_LEVEL + extra


def _check_method(method: str) -> None:
    if method not in METHODS:
        raise ValueError(f"method = {method!r} is invalid: expected one of {', '.join(METHODS)}")


def albedo_resolved(model: Model, values: Mapping[str, Any], theta_i_deg: float,
                    phi_i_deg: float = 180.0, *, level: int = DEFAULT_LEVEL,
                    tol: float = DEFAULT_TOL, method: str = "auto") -> float | np.ndarray:
    """Directional albedo ``∫ f cos θo dω`` at incidence ``(θi, φi)`` (degrees): a float, or
    ``(3,)`` for an RGB model.

    ``method="auto"`` (default): :func:`albedo_estimate_resolved`'s value.  ``"uniform"``: the
    vertex rule of ``hemisphere(level)``.  ``"adaptive"``: :func:`refine_adaptive` at ``tol``
    from level 2 down to :data:`ADAPTIVE_MAX_LEVEL` (deeper at grazing incidence), focused on
    the mirror direction.
    """
    _check_method(method)
    if method == "auto":
        return albedo_estimate_resolved(model, values, theta_i_deg, phi_i_deg).value
    wi = incident(check_theta_i(theta_i_deg), check_phi_i(phi_i_deg))
    if method == "uniform":
        return _scalar(_uniform(model, values, wi, level))
    ad = refine_adaptive(lambda wo: _integrand(model, values, wi, wo), tol,
                         max_level=adaptive_max_level(wi[2]), base_level=2, focus=mirror(wi))
    return _scalar(ad.integrate())


def albedo(model: str | Model, params: Mapping[str, Any] | None = None,
           theta_i_deg: float = 0.0, phi_i_deg: float = 180.0, *, level: int = DEFAULT_LEVEL,
           tol: float = DEFAULT_TOL, method: str = "auto") -> float | np.ndarray:
    """Directional albedo of ``model`` with user ``params`` (see :func:`albedo_resolved`)."""
    m, v = _resolve(model, params)
    return albedo_resolved(m, v, theta_i_deg, phi_i_deg, level=level, tol=tol, method=method)


def albedo_curve_resolved(model: Model, values: Mapping[str, Any],
                          thetas_deg: Sequence[float] | np.ndarray, phi_i_deg: float = 180.0,
                          *, level: int = DEFAULT_LEVEL, tol: float = DEFAULT_TOL,
                          method: str = "auto") -> np.ndarray:
    """Albedo at each incidence: ``(n,)``, or ``(n, 3)`` for an RGB model (``"auto"``: one
    batch, :func:`albedo_curve_estimate_resolved`)."""
    _check_method(method)
    if method == "auto":
        return np.asarray(albedo_curve_estimate_resolved(model, values, thetas_deg,
                                                         phi_i_deg).value, dtype=float)
    thetas = np.atleast_1d(np.asarray(thetas_deg, dtype=float))
    out = [albedo_resolved(model, values, t, phi_i_deg, level=level, tol=tol, method=method)
           for t in thetas]
    return np.array(out, dtype=float)
