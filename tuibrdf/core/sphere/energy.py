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
from tuibrdf.core.sphere.albedo import DEFAULT_RTOL, albedo_rule
from tuibrdf.core.sphere.integrator.rules import WG15, WK15, X15
from tuibrdf.core.sphere.lobes import lobe

#: Largest grid the table accepts per axis (validated before anything is allocated).
MAX_N = 4096
#: Largest table (parameter values × values of μ).
MAX_CELLS = 1 << 20
#: Relative tolerance of E_avg's μ quadrature (its |K − G| per panel) when the albedos are
#: integrated to the albedo's default tolerance (1e-5); in proportion to theirs otherwise (the
#: viewer's table: 1e-4); absolute floor below.
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
                first: tuple[np.ndarray, np.ndarray] | None = None, rtol: float = AVG_RTOL):
    """``2∫₀¹ E(μ) μ dμ`` and its error by adaptive K15/G7 over μ to relative tolerance
    ``rtol`` per panel; ``e_of(mu)`` gives the albedo and its error at the nodes (one batch
    per round).  ``first``: the albedos at the first round's nodes, if already computed."""
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
        tol = np.maximum(rtol * np.abs(k if k.ndim == 1 else k.max(axis=-1)),
                         np.maximum(pr, AVG_ATOL))
        done = (q <= tol) | (rnd == AVG_MAX_ROUNDS)
        total = total + k[done].sum(axis=0)
        err_total = err_total + (quad[done] + prop[done]).sum(axis=0)
        if done.all():
            break
        lo, hi, mid = lo[~done], hi[~done], mid[~done]
        lo, hi = np.concatenate([lo, mid]), np.concatenate([mid, hi])
    return total, err_total


def _albedos(model: Model, values: Mapping[str, Any], phi_i: float, rtol: float):
    """``e_of(mu)`` for :func:`_avg_panels`: the albedos and their errors at ``mu``."""

    def e_of(mu):
        r = albedo_rule(model, values, theta_of_mu(mu), phi_i, rtol=rtol)
        return np.asarray(r.value, dtype=float), np.asarray(r.error, dtype=float)

    return e_of


def _avg_rtol(rtol: float) -> float:
    """E_avg's μ tolerance for albedos integrated to ``rtol``: :data:`AVG_RTOL` at the
    albedo's default, in proportion otherwise (refining μ far below the albedos' own error
    gains nothing)."""
    return AVG_RTOL * (rtol / DEFAULT_RTOL)


def e_avg_resolved(model: Model, values: Mapping[str, Any], phi_i: float = 180.0, *,
                   rtol: float = DEFAULT_RTOL):
    """``(E_avg, error)`` at resolved ``values``: floats, or ``(3,)`` for an RGB model; each
    albedo to ``rtol`` (E_avg's μ panels in proportion, :func:`_avg_rtol`)."""
    return _avg_panels(_albedos(model, values, phi_i, rtol), rtol=_avg_rtol(rtol))


def energy_table(model: Model, params: Mapping[str, Any] | None, name: str, lo: float,
                 hi: float, n: int, mu_n: int, *, log: bool = False, phi_i: float = 180.0,
                 progress: Callable[[int, int], None] | None = None,
                 rtol: float = DEFAULT_RTOL) -> EnergyTable:
    """The table ``E(μ, p)`` of ``model`` over ``n`` values of parameter ``name`` in
    ``[lo, hi]`` and ``mu_n`` values of μ in [0, 1] (see the module docstring); ``params``
    (user units) set the other parameters.  ``progress(done, n)`` is called after each
    parameter value; ``rtol`` is each albedo's relative tolerance.  ``ValueError`` for a bad
    request (:func:`check_table`)."""
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
        r = albedo_rule(model, vals, np.concatenate([thetas, t15]), phi_i, rtol=rtol)
        e = np.asarray(r.value, dtype=float)
        de = np.asarray(r.error, dtype=float)
        rows.append(e[:mu_n])
        errs.append(de[:mu_n])
        a, da = _avg_panels(_albedos(model, vals, phi_i, rtol), (e[mu_n:], de[mu_n:]),
                            _avg_rtol(rtol))
        avgs.append(a)
        avg_errs.append(da)
        if progress is not None:
            progress(i + 1, n)
    return EnergyTable(model.name, dict(base), name, values, mu, np.array(rows), np.array(errs),
                       np.array(avgs, dtype=float), np.array(avg_errs, dtype=float), log,
                       model.rgb, model.param(name).unit)


# ---------------------------------------------------------------------------------------------
# the viewer's energy view

#: the viewer's table: values of the parameter and of μ (a heat map of blocks, not a curve)
VIEW_N, VIEW_MU_N = 12, 16
#: and each of its albedos' relative tolerance: blocks of colour and a verdict printed with its
#: error (the estimate is as honest at any tolerance), recomputed at every step of another
#: parameter; E_avg's μ panels follow it (1e-4, :data:`AVG_RTOL`).  Against the albedo's
#: 1e-5 and E_avg's 1e-6, CPU ms per table: gltf over metallic 289 → 161, phong over n 275 →
#: 162, cook-torrance over m 1333 → 232, ggx over α 1201 → 241 (sharp lobes had taken up to 7
#: rounds of E_avg's μ panels a row at 1e-6), with errors up to 1.1e-4 (E) and 3e-4 (E_avg,
#: relative); `tuibrdf energy` keeps 1e-5 and 1e-6.  The view's E_avg at the current value is
#: integrated the same way (CPU ms per step of the table's own parameter: ggx 16 → 6, ggx at
#: α = 0.05 35 → 19, gltf at roughness 0.1 69 → 8)
VIEW_RTOL = 1e-3
_VIEW_CACHE: dict[tuple, tuple[Model, EnergyTable]] = {}
_VIEW_CACHE_SIZE = 8
_AVG_CACHE: dict[tuple, tuple[Model, tuple]] = {}  # E_avg at the material's values


@dataclass(frozen=True)
class EnergyView:
    """What the energy view shows: the table over the whole range of ``table.param`` (the
    other parameters the material's), the albedo at the current (μ, p) with its error, and
    the white-furnace verdict."""

    table: EnergyTable
    current: float  # the current value of the parameter
    mu: float  # the current μ = cos θi
    E: float  # the albedo there (the largest channel)
    error: float
    E_avg: float  # E_avg at the current value
    E_avg_error: float
    verdict: str
    gains: bool
    symbol: str = ""


def view_param(model: Model, name: str | None) -> Param | None:
    """The parameter the view runs over: ``name`` if it is a real one, else the model's first
    real parameter; None when it has none."""
    reals = [p for p in model.params if p.kind == "float"]
    for p in reals:
        if p.name == name:
            return p
    return reals[0] if reals else None


def _freeze(v: Any) -> Any:
    return tuple(v) if isinstance(v, list | tuple) else v


def view_table(model: Model, values: Mapping[str, Any], p: Param,
               phi_i: float = 180.0) -> EnergyTable:
    """The view's table of ``p`` over its whole range (geometric for a parameter that steps
    by a factor and starts above 0), the other parameters at ``values``, at the light's
    azimuth ``φi``; the last few are kept (stepping ``p`` itself reuses its table, and so does
    a φi step for a model whose albedo does not depend on it: an isotropic one)."""
    others = tuple((k, _freeze(v)) for k, v in values.items() if k != p.name)
    # an isotropic model's integrand is even in ψ and integrated at φi = 0 whatever φi is
    # (integrator.integrate, symmetric): the same table at every φi
    azimuth = None if lobe(model, values, VIEW_RTOL).symmetric else phi_i
    key = (id(model), p.name, others, azimuth)
    hit = _VIEW_CACHE.get(key)
    if hit is not None and hit[0] is model:
        return hit[1]
    log = bool(p.relative and p.min > 0)
    base = {k: v for k, v in values.items() if k != p.name}
    lo, hi = float(p.min), float(p.max)
    # an end that breaks a constraint (kd + ks ≤ 1) is not drawable: the range stops short
    for end in (lo, hi):
        try:
            model.resolve({**base, p.name: end})
        except ValueError:
            others_sum = sum(float(values[n]) for c in model.constraints if p.name in c.names
                             for n in c.names if n != p.name)
            hi = min(hi, max(lo, 1.0 - others_sum))
    n = VIEW_N if hi > lo else 1
    table = energy_table(model, base, p.name, lo, hi, n, VIEW_MU_N, log=log, phi_i=phi_i,
                         rtol=VIEW_RTOL)
    if len(_VIEW_CACHE) >= _VIEW_CACHE_SIZE:
        _VIEW_CACHE.pop(next(iter(_VIEW_CACHE)))
    _VIEW_CACHE[key] = (model, table)
    return table


def energy_view(model: Model, values: Mapping[str, Any], theta_i: float,
                name: str | None = None, phi_i: float = 180.0, *,
                albedo: tuple | None = None) -> EnergyView | None:
    """The energy view of ``model`` at resolved ``values`` and incidence ``θi`` over
    parameter ``name`` (:func:`view_param`); None for a model without a real parameter.
    ``albedo``: the albedo at (θi, φi) and its error, when the caller has it (the viewer's
    frame: the same number as its status line's, computed once)."""
    from tuibrdf.core.conventions import fmt_number

    p = view_param(model, name)
    if p is None:
        return None
    table = view_table(model, values, p, phi_i)
    if albedo is None:
        r = albedo_rule(model, values, [theta_i], phi_i)
        albedo = (r.value, r.error)
    e = np.max(np.asarray(albedo[0], dtype=float).reshape(-1))  # the largest channel
    de = float(np.max(np.asarray(albedo[1], dtype=float)))
    key = (id(model), phi_i, tuple((k, _freeze(v)) for k, v in values.items()))
    hit = _AVG_CACHE.get(key)
    if hit is None or hit[0] is not model:
        if len(_AVG_CACHE) >= _VIEW_CACHE_SIZE:
            _AVG_CACHE.pop(next(iter(_AVG_CACHE)))
        hit = _AVG_CACHE[key] = (model, e_avg_resolved(model, values, phi_i, rtol=VIEW_RTOL))
    avg, davg = hit[1]
    sym = p.symbol or p.name
    cur = float(values[p.name])
    low = table.E - table.error
    worst = np.unravel_index(int(np.argmax(low)), low.shape)
    gains = bool(low[worst] > 1.0) or e - de > 1.0
    here = f"{sym} = {fmt_number(cur)}, θi = {fmt_number(theta_i)}°"
    if e - de > 1.0:
        verdict = f"gains energy: E = {e:.4g} ± {de:.0e} at {here}"
    else:
        verdict = f"loses {100 * (1 - e):.3g} % at {here}"
        if gains:  # elsewhere in the table
            i, j = worst[0], worst[1]
            th = float(np.degrees(np.arccos(table.mu[j])))
            verdict += (f"; gains energy: E = {table.E[worst]:.4g} ± {table.error[worst]:.0e}"
                        f" at {sym} = {fmt_number(float(table.values[i]))}, θi = {th:.3g}°")
    return EnergyView(table, cur, float(np.cos(np.radians(theta_i))), float(e), de,
                      float(np.max(avg)), float(np.max(davg)), verdict, gains, sym)
