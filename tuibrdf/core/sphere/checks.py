"""The checks a renderer developer runs on a BRDF before shipping it (``tuibrdf check``).

Each check runs at the given parameters and at each parameter's ends (a real's minimum and
maximum, an RGB colour's all-minimum and all-maximum, a choice's every other value; where an
end breaks a constraint such as ``kd + ks ≤ 1``, the constraint's other parameters are set to
their minimum), on a fixed set of directions :func:`directions`:

``finite``       no NaN or inf, and no floating-point exception under the package's policy
                 (:mod:`tuibrdf.core.numerics`), over every pair of the set;
``positivity``   the smallest value the model returns, raw (a ``.py`` or ``.brdf`` model's
                 value before the clamp to 0 every picture applies), and where;
``reciprocity``  the largest ``|f(i, o) − f(o, i)|`` relative to the local value
                 ``max(|f(i, o)|, |f(o, i)|)`` (floored at 1e-12 of the largest value, below
                 which no renderer sees a difference); fails above :data:`RECIPROCITY_RTOL`;
``energy``       the largest directional albedo less its error estimate over θi
                 (:data:`ENERGY_THETAS`); fails above 1;
``chi2``         for a model with a sampler (:mod:`tuibrdf.core.brdf.sampling`), the χ² test
                 of :mod:`tuibrdf.core.sphere.chi2` at the given parameters.
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from tuibrdf.core.conventions import fmt_number
from tuibrdf.core.directions import from_degrees
from tuibrdf.core.numerics import KERNEL_ERRORS, kernel_errstate
from tuibrdf.core.params import Model
from tuibrdf.core.sphere.albedo import albedo_rule

RECIPROCITY_RTOL = 1e-6
#: values below this fraction of the largest one are compared with it instead (rounding)
RECIPROCITY_FLOOR = 1e-12
ENERGY_THETAS = (0.0, 15.0, 30.0, 45.0, 60.0, 75.0, 85.0, 89.0, 90.0)
#: polar angles and azimuths of the direction grid (degrees): the normal, the horizon, both
#: sides of the plane of incidence, so that wi = wo and the mirror of each are in the set
GRID_THETAS = (0.0, 10.0, 30.0, 45.0, 60.0, 75.0, 85.0, 89.0, 89.99, 90.0)
GRID_PHIS = (0.0, 45.0, 90.0, 135.0, 180.0, 225.0, 270.0, 315.0)
#: seeded random directions added to the grid (uniform in solid angle)
RANDOM_DIRECTIONS = 48
NAMES = ("finite", "positivity", "reciprocity", "energy", "chi2")


@dataclass(frozen=True)
class CheckResult:
    """One check's verdict, its worst value (None when nothing was measured) and where."""

    name: str
    ok: bool
    worst: float | None
    where: str
    detail: str = ""


@functools.lru_cache(maxsize=1)
def directions() -> np.ndarray:
    """The fixed directions ``(n, 3)`` every check evaluates at (module docstring)."""
    t, p = np.meshgrid(GRID_THETAS[1:], GRID_PHIS, indexing="ij")
    grid = from_degrees(t.ravel(), p.ravel())
    rng = np.random.default_rng(20240611)
    z = rng.random(RANDOM_DIRECTIONS)
    phi = 2.0 * np.pi * rng.random(RANDOM_DIRECTIONS)
    s = np.sqrt(1.0 - z * z)
    rand = np.stack([s * np.cos(phi), s * np.sin(phi), z], axis=-1)
    out = np.concatenate([[[0.0, 0.0, 1.0]], grid, rand])
    out.setflags(write=False)
    return out


def describe_direction(w: np.ndarray) -> str:
    """``(θ 30°, φ 180°)``."""
    theta = float(np.degrees(np.arccos(np.clip(w[2], -1.0, 1.0))))
    phi = float(np.degrees(np.arctan2(w[1], w[0]))) % 360.0
    if theta < 1e-9:
        phi = 0.0
    return f"(θ {theta:.4g}°, φ {phi:.4g}°)"


# ---------------------------------------------------------------------------------------------
# configurations


def configurations(model: Model, params: Mapping[str, Any] | None) -> list[tuple[str, dict]]:
    """``(label, resolved values)``: the given parameters, then each parameter's ends
    (module docstring); duplicates dropped."""
    base = model.resolve(params)
    out: list[tuple[str, dict]] = [("the given parameters", base)]
    seen = [base]
    for p in model.params:
        if p.kind == "float":
            ends = [p.min, p.max]
        elif p.kind == "rgb":
            ends = [(p.min,) * 3, (p.max,) * 3]
        elif p.kind == "choice":
            ends = [c for c in p.choices if c != base[p.name]]
        else:
            continue
        for v in ends:
            vals = _satisfy(model, {**base, p.name: v}, p.name)
            if vals is None or vals in seen:
                continue
            seen.append(vals)
            out.append((f"{p.name}={fmt_number(v)}", vals))
    return out


def _satisfy(model: Model, values: dict, fixed: str) -> dict | None:
    """``values`` resolved, with the other parameters of a broken constraint at their
    minimum; None if that does not help."""
    try:
        return model.resolve(values)
    except ValueError:
        pass
    for c in model.constraints:
        if fixed in c.names and not c.holds(values):
            for n in c.names:
                if n != fixed:
                    values[n] = model.param(n).min
    try:
        return model.resolve(values)
    except ValueError:
        return None


# ---------------------------------------------------------------------------------------------
# raw values


def raw_kernel(model: Model) -> Callable[..., Any]:
    """The model's kernel before any clamp (:attr:`Model.raw_kernel`: a ``.py`` file's values
    checked for shape and finiteness, a ``.brdf`` shader's with NaN, inf and negatives kept);
    a built-in's kernel as it is."""
    return model.raw_kernel or model.kernel


def _call(model: Model, kernel, kw: dict, wi: np.ndarray, wo: np.ndarray) -> np.ndarray:
    f = np.asarray(kernel(wi, wo, **kw), dtype=float)
    shape = wi.shape[:-1] + ((3,) if model.rgb else ())
    return np.broadcast_to(f, shape)


def _first_raising(model, kernel, kw, wi, wo) -> tuple[int, str] | None:
    """The first pair whose evaluation raises under the package's errstate (bisection), and
    what it raised."""
    try:
        with kernel_errstate():
            _call(model, kernel, kw, wi, wo)
        return None
    except (FloatingPointError, ArithmeticError, ValueError) as e:
        msg = f"{type(e).__name__}: {e}"
    lo, hi = 0, len(wi)
    while hi - lo > 1:
        mid = (lo + hi) // 2
        try:
            with kernel_errstate():
                _call(model, kernel, kw, wi[lo:mid], wo[lo:mid])
            lo = mid
        except (FloatingPointError, ArithmeticError, ValueError) as e:
            hi, msg = mid, f"{type(e).__name__}: {e}"
    return lo, msg


# ---------------------------------------------------------------------------------------------
# the checks


def _where(label: str, wi=None, wo=None, theta=None) -> str:
    parts = [f"at {label}"]
    if wi is not None:
        parts.append(f"wi {describe_direction(wi)}")
    if wo is not None:
        parts.append(f"wo {describe_direction(wo)}")
    if theta is not None:
        parts.append(f"θi {fmt_number(theta)}°")
    return ", ".join(parts)


def reciprocity_map(f: np.ndarray) -> np.ndarray:
    """``|f(i,o) − f(o,i)| / max(|f(i,o)|, |f(o,i)|, floor)`` for values ``f (n, n[, 3])`` on
    all pairs of a set of directions (the largest over channels): ``(n, n)``."""
    ft = np.swapaxes(f, 0, 1)
    top = float(np.max(np.abs(f), initial=0.0))
    den = np.maximum(np.maximum(np.abs(f), np.abs(ft)), RECIPROCITY_FLOOR * top)
    with np.errstate(all="ignore"):
        r = np.where(den > 0, np.abs(f - ft) / np.where(den > 0, den, 1.0), 0.0)
    return r.max(axis=-1) if r.ndim == 3 else r


def run_checks(model: Model, params: Mapping[str, Any] | None = None, *,
               chi2: bool = True) -> list[CheckResult]:
    """Every check of the module docstring, in :data:`NAMES` order (``chi2`` only when the
    model has a sampler and ``chi2``)."""
    configs = configurations(model, params)
    dirs = directions()
    n = len(dirs)
    wi = np.repeat(dirs, n, axis=0)  # pair (a, b): wi = dirs[a], wo = dirs[b]
    wo = np.tile(dirs, (n, 1))
    kernel = raw_kernel(model)
    opposite = np.sum((dirs[:, None, :] + dirs[None, :, :]) ** 2, axis=-1) < 1e-12
    fin = [True, 0.0, "every configuration"]
    pos = [np.inf, ""]
    rec = [0.0, ""]
    raised = None
    for label, vals in configs:
        kw = model.kernel_params(vals)
        bad = _first_raising(model, kernel, kw, wi, wo)
        if bad is not None and raised is None:
            k, msg = bad
            raised = f"{msg} {_where(label, wi[k], wo[k])}"
        with np.errstate(all="ignore"):
            f = np.array(_call(model, kernel, kw, wi, wo))
        finite = np.isfinite(f)
        if not finite.all():
            k = int(np.flatnonzero(~finite.reshape(n * n, -1).all(axis=-1))[0])
            if fin[0]:
                kind = "NaN" if np.isnan(f.reshape(n * n, -1)[k]).any() else "inf"
                fin = [False, float(np.sum(~finite)), f"{kind} {_where(label, wi[k], wo[k])}"]
            f = np.where(finite, f, 0.0)
        flat = f.reshape(n * n, -1).min(axis=-1)
        k = int(np.argmin(flat))
        if flat[k] < pos[0]:
            pos = [float(flat[k]), _where(label, wi[k], wo[k])]
        r = reciprocity_map(f.reshape((n, n) + f.shape[1:]))
        r[opposite] = 0.0  # wi = −wo (both on the horizon): H is undefined, no value to compare
        k = int(np.argmax(r))
        if r.flat[k] > rec[0]:
            a, b = divmod(k, n)
            rec = [float(r.flat[k]), _where(label, dirs[a], dirs[b])]
    out = []
    if raised is not None and fin[0]:
        fin = [False, None, raised]
    out.append(CheckResult("finite", fin[0], fin[1] if not fin[0] else None, fin[2],
                           f"{len(configs)} configurations × {n * n} direction pairs"))
    out.append(CheckResult("positivity", pos[0] >= 0.0, pos[0], pos[1], "smallest raw value"))
    out.append(CheckResult("reciprocity", rec[0] <= RECIPROCITY_RTOL, rec[0], rec[1] or
                           "everywhere", "largest relative |f(i,o) − f(o,i)|"))
    out.append(_energy(model, configs))
    if chi2 and model.sampler is not None:
        out.append(_chi2(model, configs[0][1]))
    return out


def _energy(model: Model, configs) -> CheckResult:
    worst, where, value, error = -np.inf, "", 0.0, 0.0
    for label, vals in configs:
        try:
            r = albedo_rule(model, vals, ENERGY_THETAS)
        except KERNEL_ERRORS as e:  # a user kernel's NaN or exception
            return CheckResult("energy", False, None, f"at {label}",
                               f"not evaluated: {type(e).__name__}: {e}")
        e = np.asarray(r.value, dtype=float)
        de = np.asarray(r.error, dtype=float)
        low = (e - de).reshape(len(ENERGY_THETAS), -1)
        k, c = np.unravel_index(int(np.argmax(low)), low.shape)
        if low[k, c] > worst:
            worst = float(low[k, c])
            value = float(e.reshape(low.shape)[k, c])
            error = float(de.reshape(low.shape)[k, c])
            where = _where(label, theta=ENERGY_THETAS[k])
    return CheckResult("energy", worst <= 1.0, worst, where,
                       f"largest albedo less its error; E = {value:.6g} ± {error:.1e}")


def _chi2(model: Model, values) -> CheckResult:
    from tuibrdf.core.sphere.chi2 import chi2_test

    try:
        v = chi2_test(model, values)
    except KERNEL_ERRORS as e:  # a user sampler's exception
        return CheckResult("chi2", False, None, "at the given parameters",
                           f"not evaluated: {type(e).__name__}: {e}")
    worst_r = min(v.results, key=lambda r: r.p_value)
    mism = max(r.pdf_mismatch for r in v.results)
    detail = (f"p = {v.p_value:.3g} (threshold {v.threshold:.3g}), χ² = {worst_r.stat:.5g} on "
              f"{worst_r.dof} degrees of freedom; sample()'s pdf vs pdf(): {mism:.1e}")
    if not v.resolved:
        detail += "; inconclusive: the lobe is narrower than the map's pixels"
    where = f"at the given parameters, θi {fmt_number(worst_r.theta_i)}°"
    return CheckResult("chi2", v.ok, v.p_value, where, detail)


def reciprocity_on_map(model: Model, values: Mapping[str, Any], wi: np.ndarray,
                       res: int = 32) -> np.ndarray:
    """The relative reciprocity error ``|f(wi, wo) − f(wo, wi)| / max(|f(wi,wo)|, |f(wo,wi)|)``
    (floored as :func:`reciprocity_map`) over the Lambert equal-area map of ``wo``
    (``res × res`` pixel centres, u right, v up; NaN outside the disc), raw values."""
    step = 2 * np.sqrt(2.0) / res
    c = (np.arange(res) + 0.5) * step - np.sqrt(2.0)
    u, v = np.meshgrid(c, -c)  # row 0 at the top (v up)
    r2 = u * u + v * v
    inside = r2 <= 2.0
    s = np.sqrt(np.clip(1.0 - r2[inside] / 4.0, 0.0, None))
    wo = np.stack([u[inside] * s, v[inside] * s, 1.0 - r2[inside] / 2.0], axis=-1)
    wi_b = np.broadcast_to(np.asarray(wi, dtype=float), wo.shape).copy()
    kernel = raw_kernel(model)
    kw = model.kernel_params(values)
    with np.errstate(all="ignore"):
        a = np.array(_call(model, kernel, kw, wi_b, wo))
        b = np.array(_call(model, kernel, kw, wo, wi_b))
    a = np.where(np.isfinite(a), a, 0.0)
    b = np.where(np.isfinite(b), b, 0.0)
    top = max(float(np.max(np.abs(a), initial=0.0)), float(np.max(np.abs(b), initial=0.0)))
    den = np.maximum(np.maximum(np.abs(a), np.abs(b)), RECIPROCITY_FLOOR * top)
    with np.errstate(all="ignore"):
        r = np.where(den > 0, np.abs(a - b) / np.where(den > 0, den, 1.0), 0.0)
    if r.ndim == 2:
        r = r.max(axis=-1)
    out = np.full((res, res), np.nan)
    out[inside] = r
    return out
