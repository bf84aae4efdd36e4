"""Fit the free parameters of an analytic model to a measured BRDF (MERL, or an RGL ``.bsdf``
file: :class:`ModelTarget`).  numpy only.

**Samples.**  A fixed, deterministic subset of the MERL bins: every ``stride``-th sample along
θh, θd and φd (default ``(1, 3, 15)``: all 90 θh samples — the √ mapping already concentrates
them at the specular peak — 30 θd and 12 φd samples), at each bin's sample position (its centre,
as :mod:`tuibrdf.core.formats.merl` defines it), keeping those where both directions are strictly
above the horizon: 24 772 samples.  The data values are the table entries themselves (no
interpolation), so a file written from a model is matched exactly by that model.  An RGL
``.bsdf`` file has no such bins: its samples are its values (as ``tuibrdf eval`` gives them) at
the same positions (:class:`ModelTarget`).

**Objective** (Löw et al. 2012 "E2"; Ngan et al. 2005 compress the same way with a cube root)::

    E(p) = mean over samples and channels of
           [ log(1 + f_model·cos θi·cos θo) − log(1 + f_data·cos θi·cos θo) ]²

The cosines weight each sample by what it contributes to reflected radiance (grazing samples,
the least reliable measurements, count little); the logarithm compresses the dynamic range so
the specular peak (10³ sr⁻¹ for a sharp metal) does not drown the diffuse part.  Samples are
uniform over bins (as in Ngan et al.), not over solid angle.  The reported ``residual`` is
``√E``, the RMS error in that compressed space.

**Parameters.**  Every ``float`` and ``rgb`` parameter of the model is free unless it is given
in ``fixed`` (``choice`` parameters keep the given value or their default, e.g.
``fresnel=exact``).  Scalar models are fitted to each
channel separately (three parameter sets); RGB models (``gltf``) are fitted to all three
channels at once.  The optimiser works in an unconstrained space ``z ∈ ℝᵏ``: a parameter in
``[lo, hi]`` is ``lo + (hi − lo)·σ(z)`` (σ the logistic function), on a log scale when the
range spans ≥ 2 decades (``m``, ``alpha``: ``lo·(hi/lo)^σ(z)``; ``n`` ∈ [0, 10⁴]:
``expm1(log1p(hi)·σ(z))``), and parameters tied by a ``a + b ≤ 1`` constraint (blinn-phong's
kd, ks) are ``b·softmax(z_a, z_b, 0)`` with ``b`` = 1 minus the fixed members, so every point
the optimiser visits is valid.

**Optimiser.**  A coarse grid (4 values of each z for ≤ 3 free parameters, else 3), then
Nelder–Mead (Nelder & Mead 1965, standard coefficients 1, 2, ½, ½; adaptive ones for k ≥ 4,
Gao & Han 2012) from the two best grid points (for later channels of a scalar model: the best
grid point and the earlier channels' solutions), keeping the best.  Why not scipy: the problem
has ≤ 5 parameters and a cheap objective (2 ms per evaluation), 70 lines of Nelder–Mead do it,
and scipy would add a 40 MB dependency to a package that otherwise needs only numpy for its
core; gradients (for L-BFGS) would need either finite differences (as slow) or derivatives of
every kernel.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from tuibrdf.core.evaluate import evaluate_resolved
from tuibrdf.core.formats.merl import (
    MERL,
    N_PHI_D,
    N_THETA_D,
    N_THETA_H,
    MerlData,
    from_half_diff,
    load_cached,
)
from tuibrdf.core.numerics import kernel_errstate
from tuibrdf.core.params import Model
from tuibrdf.core.registry import get_model
from tuibrdf.core.sphere.albedo import albedo_resolved

#: default sample strides along (θh, θd, φd) bins
STRIDE = (1, 3, 15)
#: incidence angles (degrees) at which data and fit albedos are reported
ALBEDO_THETAS = (0.0, 30.0, 60.0)
CHANNELS = "RGB"
#: the optimiser's box in z: σ(±16) is within 1.2e-7 of 0 or 1, so a parameter can reach its
#: end to 1.2e-7 of its range (log-scaled ones to a factor 1.2e-7·ln(hi/lo) of it)
Z_BOUND = 16.0


# ------------------------------------------------------------------------------ samples


@dataclass(frozen=True)
class Samples:
    """Directions ``wi, wo (M, 3)``, data ``(M, 3)`` in sr⁻¹ and ``cos_io = cos θi cos θo``."""

    wi: np.ndarray
    wo: np.ndarray
    data: np.ndarray
    cos_io: np.ndarray

    def compressed(self, f: np.ndarray) -> np.ndarray:
        """``log(1 + f·cos θi·cos θo)`` for ``f`` of shape (M,) or (M, 3)."""
        w = self.cos_io if f.ndim == 1 else self.cos_io[:, None]
        return np.log1p(f * w)


@dataclass(frozen=True)
class ModelTarget:
    """A measured file read as a model (an RGL ``.bsdf``: :mod:`tuibrdf.core.formats.rgl_bsdf`),
    fitted at the MERL sample positions; ``n_invalid``: none (it has no invalid bins)."""

    path: str
    model: Model
    n_invalid: tuple[int, int, int] = (0, 0, 0)


#: what :func:`fit` fits to: a MERL file's table, or a measured model's values
Target = MerlData | ModelTarget


def load_target(path: str) -> Target:
    """The measured file at ``path``: a ``.bsdf`` as a :class:`ModelTarget`, anything else as
    MERL (:func:`load_cached`); the formats' one-line errors otherwise."""
    if path.lower().endswith(".bsdf"):
        from tuibrdf.core.formats.userfiles import load_model_file

        return ModelTarget(path, load_model_file(path))
    return load_cached(path)


def measured(data: Target) -> tuple[Model, dict[str, Any]]:
    """The measured side as a model and its values (the viewer's, the albedo's)."""
    if isinstance(data, ModelTarget):
        return data.model, {}
    return MERL, MERL.resolve({"file": data.path, "lookup": "trilinear"})


def sample_set(data: Target, stride: tuple[int, int, int] = STRIDE) -> Samples:
    """The fixed sample set of the module docstring."""
    n_h, n_d, n_p = N_THETA_H, N_THETA_D, N_PHI_D
    ih, idd, ip = np.meshgrid(np.arange(0, n_h, stride[0]), np.arange(0, n_d, stride[1]),
                              np.arange(0, n_p, stride[2]), indexing="ij")
    ih, idd, ip = ih.ravel(), idd.ravel(), ip.ravel()
    # each sample's position: its bin's centre t = i + 1/2
    # (theta_h = ((i + 1/2)/90)^2 * 90 deg, theta_d = (i + 1/2) deg, phi_d = (i + 1/2) deg)
    wi, wo = from_half_diff(((ih + 0.5) / n_h) ** 2 * (np.pi / 2), (idd + 0.5) / n_d * (np.pi / 2),
                            (ip + 0.5) / n_p * np.pi)
    keep = (wi[:, 2] > 0) & (wo[:, 2] > 0)
    if isinstance(data, ModelTarget):
        wi, wo = wi[keep], wo[keep]
        with kernel_errstate():
            values = np.asarray(evaluate_resolved(data.model, {}, wi, wo), dtype=float)
        values = values if values.ndim == 2 else np.repeat(values[:, None], 3, axis=1)
        ok = np.isfinite(values).all(axis=1)  # (a measured model gives finite values)
        wi, wo, values = wi[ok], wo[ok], np.maximum(values[ok], 0.0)
        return Samples(wi, wo, np.ascontiguousarray(values), wi[:, 2] * wo[:, 2])
    values = data.table[:, ih[keep], idd[keep], ip[keep]].T
    wi, wo = wi[keep], wo[keep]
    return Samples(wi, wo, np.ascontiguousarray(values), wi[:, 2] * wo[:, 2])


# ------------------------------------------------------------------------------ parameter space


@dataclass(frozen=True)
class Space:
    """Map between an unconstrained ``z ∈ ℝᵏ`` and a model's user values (module docstring)."""

    model: Model
    fixed: dict[str, Any]
    #: (name, channel or None) of each free scalar, in z order
    slots: tuple[tuple[str, int | None], ...]
    #: groups of slot indices tied by a sum ≤ 1 constraint, and the budget each group shares
    #: (1 minus the fixed members)
    groups: tuple[tuple[int, ...], ...] = field(default=())
    budgets: tuple[float, ...] = field(default=())

    @classmethod
    def of(cls, model: Model, fixed: Mapping[str, Any]) -> Space:
        """``fixed``: user values (already validated) of the parameters that are not fitted;
        ``choice`` parameters not in it keep their defaults, continuous ones are free."""
        slots: list[tuple[str, int | None]] = []
        values = {}
        for p in model.params:
            if p.name in fixed:
                values[p.name] = fixed[p.name]
            elif p.kind == "float":
                slots.append((p.name, None))
            elif p.kind == "rgb":
                slots.extend((p.name, c) for c in range(3))
            else:
                values[p.name] = p.default
        if not slots:
            raise ValueError(f"fit: {model.name} has no free continuous parameter to fit")
        groups, budgets = [], []
        for c in model.constraints:
            members = [i for i, (n, _) in enumerate(slots) if n in c.names]
            unit = all(model.param(n).min == 0.0 and model.param(n).max == 1.0 for n in c.names)
            if c.text != " + ".join(c.names) + " ≤ 1" or not unit:
                raise ValueError(f"fit: constraint {c.text} of {model.name} is not supported")
            budget = 1.0 - sum(float(values[n]) for n in c.names if n in values)
            if budget < -1e-9:
                raise ValueError(f"fit: the fixed values violate {c.text}")
            if members:
                groups.append(tuple(members))
                budgets.append(max(budget, 0.0))
        return cls(model, values, tuple(slots), tuple(groups), tuple(budgets))

    @property
    def k(self) -> int:
        return len(self.slots)

    def scalars(self, z: np.ndarray) -> np.ndarray:
        """Free scalars (user units) for ``z``."""
        u = 0.5 * (1.0 + np.tanh(0.5 * z))  # logistic σ(z), without exp overflow
        x = np.empty(self.k)
        grouped = {i for g in self.groups for i in g}
        for i, (name, _) in enumerate(self.slots):
            if i in grouped:
                continue
            p = self.model.param(name)
            lo, hi = float(p.min), float(p.max)
            if lo > 0.0 and hi / lo >= 100.0:
                x[i] = lo * (hi / lo) ** u[i]
            elif lo == 0.0 and hi >= 100.0:
                x[i] = math.expm1(math.log1p(hi) * u[i])
            else:
                x[i] = lo + (hi - lo) * u[i]
            x[i] = min(max(x[i], lo), hi)  # rounding of the maps must not leave the range
        for g, budget in zip(self.groups, self.budgets, strict=True):
            zg = np.append(z[list(g)], 0.0)
            e = np.exp(zg - zg.max())  # softmax, shifted so exp cannot overflow
            x[list(g)] = budget * (e / e.sum())[:-1]
        return x

    def values(self, z: np.ndarray) -> dict[str, Any]:
        """Complete user values for ``z`` (valid by construction: ranges and constraints)."""
        out: dict[str, Any] = dict(self.fixed)
        x = self.scalars(z)
        for (name, channel), v in zip(self.slots, x, strict=True):
            if channel is None:
                out[name] = float(v)
            else:
                rgb = list(out.get(name, (0.0, 0.0, 0.0)))
                rgb[channel] = float(v)
                out[name] = tuple(rgb)
        return {p.name: out[p.name] for p in self.model.params}  # declaration order


# ------------------------------------------------------------------------------ optimiser


def nelder_mead(fun: Callable[[np.ndarray], float], x0: np.ndarray, *, step: float = 0.6,
                xtol: float = 1e-4, ftol: float = 1e-12, frtol: float = 1e-9,
                max_evals: int = 2000, bound: float = math.inf):
    """Minimise ``fun`` from ``x0``; returns ``(x, f, evaluations)``.

    Stops when the simplex is smaller than ``xtol`` in every coordinate and its values differ by
    less than ``ftol + frtol·|f|``, or after ``max_evals`` evaluations.  Every trial point is
    clipped to ``[-bound, bound]``: where the optimum is at a parameter's end (σ(z) → 0 or 1)
    the simplex then collapses onto the box face instead of drifting off to infinity.
    """
    def clipped(x: np.ndarray) -> float:  # clips x in place, so the simplex stores it clipped
        np.clip(x, -bound, bound, out=x)
        return fun(x)

    n = len(x0)
    if n >= 4:  # adaptive coefficients (Gao & Han 2012) keep high dimensions from stalling
        rho, chi, psi, sigma = 1.0, 1.0 + 2.0 / n, 0.75 - 1.0 / (2 * n), 1.0 - 1.0 / n
    else:
        rho, chi, psi, sigma = 1.0, 2.0, 0.5, 0.5
    sim = np.vstack([x0, x0 + step * np.eye(n)])
    fs = np.array([clipped(x) for x in sim])
    evals = n + 1
    while evals < max_evals:
        order = np.argsort(fs, kind="stable")
        sim, fs = sim[order], fs[order]
        if (np.max(np.abs(sim[1:] - sim[0])) <= xtol
                and fs[-1] - fs[0] <= ftol + frtol * abs(fs[0])):
            break
        centroid = sim[:-1].mean(axis=0)
        xr = centroid + rho * (centroid - sim[-1])
        fr = clipped(xr)
        evals += 1
        if fr < fs[0]:
            xe = centroid + chi * (xr - centroid)
            fe = clipped(xe)
            evals += 1
            sim[-1], fs[-1] = (xe, fe) if fe < fr else (xr, fr)
        elif fr < fs[-2]:
            sim[-1], fs[-1] = xr, fr
        else:
            outside = fr < fs[-1]
            xc = centroid + psi * ((xr if outside else sim[-1]) - centroid)
            fc = clipped(xc)
            evals += 1
            if fc < (fr if outside else fs[-1]):
                sim[-1], fs[-1] = xc, fc
            else:  # shrink toward the best vertex
                sim[1:] = sim[0] + sigma * (sim[1:] - sim[0])
                fs[1:] = [clipped(x) for x in sim[1:]]
                evals += n
    best = int(np.argmin(fs))
    return sim[best], float(fs[best]), evals


# ------------------------------------------------------------------------------ fitting


@dataclass(frozen=True)
class Fit:
    """A fitted model.  ``params`` holds one complete value mapping per entry of ``channels``:
    ``("R", "G", "B")`` for a scalar model fitted per channel, ``("RGB",)`` for an RGB model,
    ``("mean",)`` for a scalar model fitted to the mean of the channels (one parameter set that
    can be shown as it is, e.g. in the app's compare mode)."""

    model: Model
    channels: tuple[str, ...]
    params: tuple[dict[str, Any], ...]
    residual: float
    evaluations: int
    seconds: float
    n_samples: int


def fit(data: Target, model: str | Model, *, fixed: Mapping[str, Any] | None = None,
        stride: tuple[int, int, int] = STRIDE, mean: bool = False,
        progress: Callable[[str, int, int], None] | None = None) -> Fit:
    """Fit ``model``'s free parameters to ``data`` (module docstring).  ``fixed`` maps names to
    user values that are kept, not fitted (e.g. ``{"kd": 0}``, ``{"fresnel": "schlick"}``);
    unnamed ``choice`` parameters keep their defaults.  ``mean`` fits a scalar model once, to
    the mean of R, G and B, instead of once per channel.  ``progress(channel, i, n)`` is called
    before each of the ``n`` channel fits (``i`` from 1)."""
    m = get_model(model)
    if m is MERL or any(p.kind == "path" for p in m.params):
        raise ValueError(f"fit: {m.name} is not an analytic model")
    space = Space.of(m, {k: m.param(k).validate(v, m.name) for k, v in (fixed or {}).items()})
    samples = sample_set(data, stride)
    start = time.perf_counter()
    if m.rgb:
        channels, targets = ("RGB",), [samples.compressed(samples.data)]
    elif mean:
        channels, targets = ("mean",), [samples.compressed(samples.data.mean(axis=1))]
    else:
        target = samples.compressed(samples.data)
        channels, targets = tuple(CHANNELS), [target[:, c] for c in range(3)]
    evaluations = 0
    params = []
    errors = []
    warm: list[np.ndarray] = []  # earlier channels' solutions: extra starting points
    for i, want in enumerate(targets):
        if progress is not None:
            progress(channels[i], i + 1, len(targets))

        def objective(z, want=want):
            with kernel_errstate():
                f = evaluate_resolved(m, space.values(z), samples.wi, samples.wo)
            return float(np.mean((samples.compressed(f) - want) ** 2))

        z, err, n = _minimise(objective, space.k, warm)
        warm.append(z)
        evaluations += n
        params.append(space.values(z))
        errors.append(err)
    return Fit(m, channels, tuple(params), math.sqrt(float(np.mean(errors))), evaluations,
               time.perf_counter() - start, len(samples.cos_io))


def _minimise(objective: Callable[[np.ndarray], float], k: int, warm=()):
    """Coarse grid, then Nelder–Mead from the two best grid points, or from the best one and
    ``warm`` (the solutions of the channels fitted before: a channel's optimum is usually near
    its neighbour's, and a start there avoids a local minimum one channel fell into)."""
    levels = np.array([-2.4, -0.8, 0.8, 2.4]) if k <= 3 else np.array([-2.0, 0.0, 2.0])
    grid = np.stack(np.meshgrid(*([levels] * k), indexing="ij"), axis=-1).reshape(-1, k)
    values = np.array([objective(z) for z in grid])
    evaluations = len(grid)
    best = None
    order = np.argsort(values, kind="stable")
    starts = [grid[i] for i in order[:1 if warm else 2]] + list(warm)
    for z0 in starts:
        z, err, n = nelder_mead(objective, z0, bound=Z_BOUND)
        evaluations += n
        if best is None or err < best[1]:
            best = (z, err)
    return best[0], best[1], evaluations


# ------------------------------------------------------------------------------ judgement

#: a fitted value within this fraction of its range from an end is "at the bound": the
#: optimiser pushed it there (the model wants a value past the end), so the fit is limited
BOUND_FRACTION = 1e-3
#: fit / data albedo outside [1 / R, R] at any θi and channel flags a poor fit: 25 % more or
#: less reflected energy is visible at a glance in the viewer (a design choice,
#: docs/reference/formats.md)
POOR_ALBEDO_RATIO = 1.25


def at_bounds(result: Fit, fixed: Mapping[str, Any] | None = None) -> list[dict[str, Any]]:
    """``[{"param": name, "bound": "min"|"max", "value": v, "channels": [...]}, ...]``: the
    fitted (not fixed) continuous parameters that ended at an end of their range."""
    found: dict[tuple[str, str], dict[str, Any]] = {}
    for channel, values in zip(result.channels, result.params, strict=True):
        for p in result.model.params:
            if p.kind not in ("float", "rgb") or p.name in (fixed or {}):
                continue
            v = values[p.name]
            comps = list(v) if p.kind == "rgb" else [v]
            tol = BOUND_FRACTION * (p.max - p.min)
            for c, x in enumerate(comps):
                for which, end in (("min", p.min), ("max", p.max)):
                    if abs(float(x) - end) <= tol:
                        label = channel if p.kind != "rgb" else f"{channel}.{'rgb'[c]}"
                        entry = found.setdefault((p.name, which), {
                            "param": p.name, "bound": which, "value": float(end),
                            "channels": []})
                        entry["channels"].append(label)
    return list(found.values())


def albedo_ratio(rows: list[dict[str, Any]]) -> dict[str, Any]:
    """The worst fit / data albedo ratio of :func:`albedo_table`'s rows (farthest from 1 on a
    log scale): ``{"ratio": r, "theta_i": θ, "channel": c, "poor": bool}``; a data albedo of 0
    (a black channel) is skipped."""
    worst = {"ratio": 1.0, "theta_i": None, "channel": None}
    for row in rows:
        for c, (d, f) in enumerate(zip(row["data"], row["fit"], strict=True)):
            if d <= 0 or f <= 0:  # no ratio of a black channel (guards the division and log)
                continue
            r = f / d
            if abs(math.log(r)) > abs(math.log(worst["ratio"])):
                worst = {"ratio": r, "theta_i": row["theta_i"], "channel": CHANNELS[c]}
    r = worst["ratio"]
    worst["poor"] = not (1 / POOR_ALBEDO_RATIO <= r <= POOR_ALBEDO_RATIO)
    return worst


# ------------------------------------------------------------------------------ albedo


def albedo_table(data: Target, result: Fit, thetas=ALBEDO_THETAS) -> list[dict[str, Any]]:
    """``[{"theta_i": θ, "data": [r, g, b], "fit": [r, g, b]}, ...]``: directional albedos by
    the mesh quadrature (:func:`tuibrdf.core.sphere.albedo.albedo_resolved`, its default level),
    the data through the ``merl`` model (trilinear lookup) or the ``.bsdf`` model."""
    data_model, data_values = measured(data)
    rows = []
    for t in thetas:
        if result.model.rgb:
            fitted = np.asarray(albedo_resolved(result.model, result.params[0], t))
        else:
            fitted = np.array([albedo_resolved(result.model, p, t) for p in result.params])
            fitted = np.resize(fitted, 3)  # a mean fit is grey: its one albedo for R, G, B
        rows.append({"theta_i": float(t),
                     "data": np.asarray(albedo_resolved(data_model, data_values, t)).tolist(),
                     "fit": fitted.tolist()})
    return rows


# ------------------------------------------------------------------------------ published fits


def score(data: Target, model: str | Model, values: Mapping[str, Any],
          stride: tuple[int, int, int] = STRIDE) -> float:
    """The objective's ``√E`` of ``model`` with fixed user ``values`` on ``data``'s sample set
    (what :func:`fit` reports as ``residual``, for a model that is not fitted)."""
    m = get_model(model)
    samples = sample_set(data, stride)
    with kernel_errstate():
        f = evaluate_resolved(m, m.resolve(values), samples.wi, samples.wo)
    f = np.asarray(f)
    if f.ndim == 1:
        f = np.repeat(f[:, None], 3, axis=1)
    return math.sqrt(float(np.mean((samples.compressed(f) - samples.compressed(samples.data))
                                   ** 2)))


def material_of(path: str) -> str | None:
    """The MERL material a file is named after: its stem is a material's name
    (``gold-metallic-paint.binary``) or one of the SGD data's other names; else None."""
    from pathlib import Path

    from tuibrdf.core.brdf.fitted import MATERIAL

    return MATERIAL.choice(Path(path).stem)


def published_scores(data: Target, stride: tuple[int, int, int] = STRIDE
                     ) -> dict[str, Any] | None:
    """``{"material": name, "abc": √E, "sgd": √E}`` when the file is named after a MERL
    material: how the tabulated ABC and SGD fits (:mod:`tuibrdf.core.brdf.fitted`) score on
    the objective :func:`fit` minimises; None otherwise."""
    name = material_of(data.path)
    if name is None:
        return None
    return {"material": name,
            **{m: score(data, m, {"material": name}, stride) for m in ("abc", "sgd")}}


def fit_file(path: str, model: str | Model, **kw) -> tuple[Target, Fit]:
    """:func:`load_target` then :func:`fit`."""
    data = load_target(path)
    return data, fit(data, model, **kw)


# ------------------------------------------------------------------------------ rel_l2

#: rel_l2 of the fit against the data above this at any θi of :data:`ALBEDO_THETAS` (and any
#: channel) flags a poor fit: the fit's lobe misses half the data's L2 norm or more (a design
#: choice, as :data:`POOR_ALBEDO_RATIO`; the published ABC and SGD fits of alum-bronze differ
#: from each other by 0.48 at 45°)
POOR_REL_L2 = 0.5
#: evaluations per incidence for the data's integrals (a measured table is piecewise: the
#: adaptive rule would refine to its cap; its error estimate says how far it got)
FIT_MAX_EVALS = 40_000


def rel_l2_table(data: Target, result: Fit, thetas=ALBEDO_THETAS) -> list[dict[str, Any]]:
    """``[{"theta_i": θ, "rel_l2": [r, g, b], "error": [...]}, ...]``: rel_l2 of the fit
    against the data (the reference) per channel (:func:`tuibrdf.core.sphere.compare.compare`;
    a per-channel fit against its own channel, a mean fit against each)."""
    from tuibrdf.core.sphere.compare import compare

    dm, dv = measured(data)
    sets = list(result.params)
    rows = []
    for t in thetas:
        vals, errs = [], []
        done: dict[int, dict] = {}  # one comparison per parameter set (all channels at once)
        for c in range(3):
            k = c if len(sets) == 3 else 0
            if k not in done:
                done[k] = compare(result.model, sets[k], dm, dv, [t],
                                  max_evals=FIT_MAX_EVALS)[0].channels
            if done[k] is None:  # both scalar: not a measured target (never MERL or .bsdf)
                raise ValueError("rel_l2_table: the data must be RGB")
            r = done[k]["RGB"[c]]
            vals.append(r["rel_l2"])
            errs.append(r["rel_l2_error"])
        rows.append({"theta_i": float(t), "rel_l2": vals, "error": errs})
    return rows


def worst_rel_l2(rows: list[dict[str, Any]]) -> dict[str, Any]:
    """The largest rel_l2 of :func:`rel_l2_table`'s rows: ``{"rel_l2": r, "theta_i": θ,
    "channel": c, "poor": bool}`` (a black channel, None, is skipped)."""
    worst = {"rel_l2": 0.0, "theta_i": None, "channel": None}
    for row in rows:
        for c, v in enumerate(row["rel_l2"]):
            if v is not None and v > worst["rel_l2"]:
                worst = {"rel_l2": v, "theta_i": row["theta_i"], "channel": CHANNELS[c]}
    worst["poor"] = worst["rel_l2"] > POOR_REL_L2
    return worst


__all__ = ["ALBEDO_THETAS", "BOUND_FRACTION", "POOR_ALBEDO_RATIO", "POOR_REL_L2", "albedo_ratio",
           "at_bounds", "Fit", "ModelTarget", "Samples", "Space", "Target", "albedo_table", "fit",
           "load_target", "measured", "rel_l2_table", "worst_rel_l2",
           "fit_file", "material_of", "nelder_mead", "published_scores", "sample_set",
           "score"]
