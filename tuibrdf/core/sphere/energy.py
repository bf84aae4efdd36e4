"""Energy tables: the directional albedo ``E(μ, p)`` over a grid of ``μ = cos θi`` and of one
parameter ``p``, each entry with its error estimate, and the hemispherical average
``E_avg(p) = 2 ∫₀¹ E(μ) μ dμ`` with its own.

These are the tables of multiple-scattering compensation (Kulla & Conty 2017, "Revisiting
physically based shading at Imageworks"): the missing energy ``1 − E(μ)`` and ``1 − E_avg``.

``E`` is :func:`tuibrdf.core.sphere.albedo.albedo_rule` (adaptive Gauss–Kronrod about the lobe,
one batch per parameter value); its error is that rule's estimate.  ``E_avg`` is integrated over
μ by an adaptive Gauss–Kronrod (K15/G7, :mod:`tuibrdf.core.sphere.integrator.rules`) whose nodes
are albedos too; its error is ``|K − G|`` summed over the panels plus the albedo errors weighted
by the rule (``2 Σ wₖ μₖ err(μₖ)``).  ``E_avg`` is therefore not the table's own quadrature: a
table of 8 values of μ still has an ``E_avg`` accurate to its error bound.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from tuibrdf.core.params import Model, Param
from tuibrdf.core.sphere.albedo import albedo_rule
from tuibrdf.core.sphere.integrator.rules import WG15, WK15, X15

#: Largest grid the table accepts per axis (validated before anything is allocated).
MAX_N = 4096
#: Largest table (parameter values × values of μ).
MAX_CELLS = 1 << 20
#: Relative tolerance of E_avg's μ quadrature (its |K − G| per panel); absolute floor below.
AVG_RTOL = 1e-6
AVG_ATOL = 1e-12
#: Bisection rounds of E_avg's μ panels at most (2⁶ panels at the finest).
AVG_MAX_ROUNDS = 6


@dataclass(frozen=True)
class EnergyTable:
    """``E (P, M)`` (``(P, M, 3)`` for an RGB model) at ``values (P,)`` of ``param`` and
    ``mu (M,)``; ``error`` the same shape; ``E_avg (P,)`` (``(P, 3)``) and ``E_avg_error``."""

    model: str
    params: dict[str, Any]
    param: str
    values: np.ndarray
    mu: np.ndarray
    E: np.ndarray
    error: np.ndarray
    E_avg: np.ndarray
    E_avg_error: np.ndarray
    log: bool = False
    rgb: bool = False
    unit: str = field(default="")

    @property
    def one_minus_E(self) -> np.ndarray:
        """Kulla–Conty's missing energy ``1 − E(μ)``."""
        return 1.0 - self.E

    @property
    def one_minus_E_avg(self) -> np.ndarray:
        """Kulla–Conty's ``1 − E_avg``."""
        return 1.0 - self.E_avg

    @property
    def error_bound(self) -> float:
        """The largest error estimate of any entry (E or E_avg)."""
        return float(max(np.max(self.error, initial=0.0), np.max(self.E_avg_error, initial=0.0)))


def sweep_param(model: Model, name: str) -> Param:
    """The parameter ``name`` of ``model``, if a table can run over it (a real number);
    ``ValueError`` with the reason otherwise."""
    p = model.param(name)  # unknown: ValueError with a close match
    if p.kind != "float":
        what = {"choice": "a choice", "rgb": "an RGB colour", "path": "a file"}.get(p.kind, p.kind)
        raise ValueError(f"{model.name}: {name} is {what}, not a number: an energy table runs "
                         "over one real parameter")
    return p


def param_grid(lo: float, hi: float, n: int, log: bool = False) -> np.ndarray:
    """``n`` values from ``lo`` to ``hi``, both ends included: linear, or geometric with
    ``log`` (``lo > 0``).  ``n = 1`` gives ``[lo]``."""
    if n == 1:
        return np.array([float(lo)])
    if log:
        g = np.geomspace(lo, hi, n)
    else:
        g = np.linspace(lo, hi, n)
    g[0], g[-1] = lo, hi  # the ends exactly as given (geomspace rounds them)
    return g


def mu_grid(m: int) -> np.ndarray:
    """``m`` values of μ = cos θi from 0 (grazing) to 1 (normal), both included."""
    return np.linspace(0.0, 1.0, m) if m > 1 else np.array([1.0])


def theta_of_mu(mu: np.ndarray) -> np.ndarray:
    """θi in degrees for μ = cos θi, in [0, 90] (arccos of 0 is 90° up to rounding: clipped)."""
    return np.clip(np.degrees(np.arccos(np.clip(mu, 0.0, 1.0))), 0.0, 90.0)


def check_table(model: Model, name: str, lo: float, hi: float, n: int, mu_n: int,
                log: bool) -> Param:
    """Validate a table's request before anything is allocated; ``ValueError`` names the
    problem (one line)."""
    p = sweep_param(model, name)
    for what, k in (("--n", n), ("--mu-n", mu_n)):
        if not 1 <= k <= MAX_N:
            raise ValueError(f"{what} = {k} is out of range: expected 1 to {MAX_N}")
    if n * mu_n > MAX_CELLS:
        raise ValueError(f"the table would have {n * mu_n} entries: at most {MAX_CELLS}")
    if not (np.isfinite(lo) and np.isfinite(hi)):
        raise ValueError(f"range {lo:g}:{hi:g} is not finite")
    if lo > hi or (lo == hi and n > 1):
        raise ValueError(f"range {lo:g}:{hi:g} is empty: expected LO < HI (or --n 1)")
    for v in (lo, hi):
        p.validate(v, model.name)  # ValueError with the parameter's range
    if log and lo <= 0.0:
        raise ValueError(f"--log-param needs a range above 0, got {lo:g}:{hi:g}")
    return p


def _avg_panels(e_of: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]],
                first: tuple[np.ndarray, np.ndarray] | None = None):
    """``2∫₀¹ E(μ) μ dμ`` and its error by adaptive K15/G7 over μ; ``e_of(mu)`` gives the albedo
    and its error at the nodes (one batch per round).  ``first``: the albedos at the first
    round's nodes, if already computed."""
    lo, hi = np.array([0.0]), np.array([1.0])
    total, err_total = 0.0, 0.0
    for rnd in range(AVG_MAX_ROUNDS + 1):
        half = (hi - lo) / 2.0
        mid = (hi + lo) / 2.0
        nodes = (mid[:, None] + half[:, None] * X15[None, :])  # (panels, 15)
        if rnd == 0 and first is not None:
            e, de = first
        else:
            e, de = e_of(nodes.ravel())
        e = e.reshape(nodes.shape + e.shape[1:])
        de = de.reshape(e.shape)
        w = 2.0 * nodes  # the weight 2μ
        extra = (slice(None), slice(None)) + (None,) * (e.ndim - 2)
        h = half.reshape((-1,) + (1,) * (e.ndim - 2))
        k = np.einsum("j,pj...->p...", WK15, w[extra] * e) * h
        g = np.einsum("j,pj...->p...", WG15, w[extra] * e) * h
        quad = np.abs(k - g)
        prop = np.einsum("j,pj...->p...", WK15, w[extra] * de) * h
        q = quad if quad.ndim == 1 else quad.max(axis=-1)
        # refining μ below the albedos' own error gains nothing: that error is the floor
        pr = prop if prop.ndim == 1 else prop.max(axis=-1)
        tol = np.maximum(AVG_RTOL * np.abs(k if k.ndim == 1 else k.max(axis=-1)),
                         np.maximum(pr, AVG_ATOL))
        done = (q <= tol) | (rnd == AVG_MAX_ROUNDS)
        total = total + k[done].sum(axis=0)
        err_total = err_total + (quad[done] + prop[done]).sum(axis=0)
        if done.all():
            break
        lo, hi, mid = lo[~done], hi[~done], mid[~done]
        lo, hi = np.concatenate([lo, mid]), np.concatenate([mid, hi])
    return total, err_total


def e_avg_resolved(model: Model, values: Mapping[str, Any], phi_i: float = 180.0):
    """``(E_avg, error)`` at resolved ``values``: floats, or ``(3,)`` for an RGB model."""

    def e_of(mu):
        r = albedo_rule(model, values, theta_of_mu(mu), phi_i)
        return np.asarray(r.value, dtype=float), np.asarray(r.error, dtype=float)

    return _avg_panels(e_of)


def energy_table(model: Model, params: Mapping[str, Any] | None, name: str, lo: float,
                 hi: float, n: int, mu_n: int, *, log: bool = False, phi_i: float = 180.0,
                 progress: Callable[[int, int], None] | None = None) -> EnergyTable:
    """The table ``E(μ, p)`` of ``model`` over ``n`` values of parameter ``name`` in
    ``[lo, hi]`` and ``mu_n`` values of μ in [0, 1] (see the module docstring); ``params``
    (user units) set the other parameters.  ``progress(done, n)`` is called after each
    parameter value.  ``ValueError`` for a bad request (:func:`check_table`)."""
    check_table(model, name, lo, hi, n, mu_n, log)
    base = model.resolve(params)
    values = param_grid(lo, hi, n, log)
    mu = mu_grid(mu_n)
    thetas = theta_of_mu(mu)
    k15 = (0.5 + 0.5 * X15)  # the first round's μ nodes of E_avg: batched with the table's
    t15 = theta_of_mu(k15)
    # every table's parameters first: a violated constraint is reported before any work
    all_vals = [model.resolve({**base, name: v}) for v in values.tolist()]
    rows, errs, avgs, avg_errs = [], [], [], []
    for i, vals in enumerate(all_vals):
        r = albedo_rule(model, vals, np.concatenate([thetas, t15]), phi_i)
        e = np.asarray(r.value, dtype=float)
        de = np.asarray(r.error, dtype=float)
        rows.append(e[:mu_n])
        errs.append(de[:mu_n])

        def e_of(m, vals=vals):
            rr = albedo_rule(model, vals, theta_of_mu(m), phi_i)
            return np.asarray(rr.value, dtype=float), np.asarray(rr.error, dtype=float)

        a, da = _avg_panels(e_of, (e[mu_n:], de[mu_n:]))
        avgs.append(a)
        avg_errs.append(da)
        if progress is not None:
            progress(i + 1, n)
    return EnergyTable(model.name, dict(base), name, values, mu, np.array(rows), np.array(errs),
                       np.array(avgs, dtype=float), np.array(avg_errs, dtype=float), log,
                       model.rgb, model.param(name).unit)
