"""Where each built-in model's lobe is: the hints the albedo quadrature integrates by.

:func:`lobe` gives, for a model and its values, a :class:`Lobe`: the polar frame of
:mod:`~tuibrdf.core.sphere.integrator` (about the half vector for microfacet models, the lobe
then sits at the pole whatever θi; the mirror direction for Phong; the normal for diffuse
models, whose kinks at θo = θi and Δφ = ±90° are coordinate lines there), the lobe's width, the
integrand's known kinks (radial breaks and outer azimuths) and its pole beyond the horizon.
The per-model knowledge is :data:`LOBE_HINTS`; any other model (a user file) gets
:data:`DEFAULT_LOBE`: the half-vector frame with the finest grading and no symmetry assumed.
The albedo itself is :mod:`tuibrdf.core.sphere.albedo`'s; scripts/bench_accuracy.py measures
each hint.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from functools import lru_cache
from typing import Any, NamedTuple

import numpy as np

from tuibrdf.core.brdf.materials import table
from tuibrdf.core.brdf.microfacet import alpha_from_roughness
from tuibrdf.core.params import Model
from tuibrdf.core.registry import registered_name
from tuibrdf.core.sphere import integrator

#: Evaluation budget per incidence for measured data (MERL tables, RGL ``.bsdf`` files): in
#: effect the rule's first round (4,500-8,100 evaluations, ~0.5 µs each: 3-7 ms).  Their
#: interpolated tables are only piecewise smooth, so more rounds buy little: the estimate
#: (honest, larger) says how far the first got.  On MERL tables of a glossy lobe, alum-bronze's
#: fit (also with 2 % noise) and cook-torrance m = 0.1 at θi = 0-85°, the estimate was 2-15×
#: the error (against 400,000 evaluations) and 1e-5-1e-3 of the albedo; 20,000 evaluations
#: cost 8-20 ms for estimates 2-10× smaller
MEASURED_MAX_EVALS = 4_000


class Lobe(NamedTuple):
    """How to integrate a model: the :mod:`~tuibrdf.core.sphere.integrator` frame, the lobe's
    width about its axis (radians), known radial kinks, and whether the model is isotropic
    (even in ψ)."""

    frame: str
    scale: float
    breaks: Callable[..., list[np.ndarray]] | None = None
    symmetric: bool = True
    #: evaluation budget per incidence, if lower than the caller's
    max_evals: int | None = None
    #: azimuths ψ ∈ (0, π) where the inner integral is less smooth (``(sin θi, cos θi) →
    #: list``): outer panel ends
    azimuths: Callable[[float, float], list[float]] | None = None
    #: ``(sin θi, cos θi, cos ψ, ρmax) → (eps, amp)``: the integrand's pole beyond the horizon,
    #: eps (radians of ρ, per outer node; inf: none) and its relative amplitude
    #: (``integrator.integrate``'s ``horizon``): the first round grades the last panels toward it
    horizon: Callable[..., np.ndarray] | None = None
    #: extra radial panel ends (radians, the same at every outer node; not kinks: no graded
    #: cuts toward them), e.g. where a lobe's envelope ends
    rings: tuple[float, ...] = ()
    #: outer panels narrower than this (radians) use K7 (``integrator.integrate(outer_k7=...)``)
    outer_k7: float = 0.0
    #: below this cos θi the integrand has kinks the hint does not place (Oren-Nayar's clamp
    #: near grazing back-scatter): the albedo is integrated again on a second outer layout and
    #: the difference joins the error estimate (None: never)
    second_layout: float | None = None


def _theta_i_break(st, ct, cpsi, rmax):
    """Oren-Nayar: max/min(θi, θo) kink at θo = θi (normal frame: ρ = θo)."""
    return [np.arctan2(st, ct)]


#: Oren-Nayar (full) is clamped at 0 near grazing back-scatter for σ ≳ 1 rad (from this σ in
#: degrees on), where θi is above 80° (this cos θi): its edges are not placed by the hint
ON_CLAMP_SIGMA = 45.0
ON_CLAMP_COS = float(np.cos(np.radians(80.0)))


def _vcavity_breaks(st, ct, cpsi, rmax):
    """Cook-Torrance's V-cavity G = min(1, 2 cos θh cos θo / cos ψ, 2 cos θh cos θi / cos ψ)
    has kinks where the terms cross.  In the half frame (β = atan2(sin θi cos ψ, cos θi)):
    2 cos ρ cos(2ρ − β) = cos(ρ − β) ⇔ cos(3ρ − β) = 0 ⇔ ρ = (π/2 + β)/3 (masking), and
    2 cos ρ cos θi = R cos(ρ − β) ⇔ tan ρ = cos θi / (sin θi cos ψ) ⇔ ρ = π/2 − β
    (shadowing), and where the two crossed terms meet, cos θo = cos θi: R cos(2ρ − β) =
    R cos β ⇔ ρ = β (β > 0; ρ = 0 is the mirror direction itself)."""
    b = np.arctan2(st * cpsi, ct)
    return [(np.pi / 2 + b) / 3.0, np.pi / 2 - b, np.where(b > 0.0, b, rmax)]


def _vcavity_azimuths(st: float, ct: float) -> list[float]:
    """Where :func:`_vcavity_breaks`' kink curves meet each other or the horizon, the inner
    integral is less smooth in ψ: the three meet at β = π/4 (ρ = π/4), and the shadowing one
    leaves the domain at β = π/6 (π/2 − β = ρmax); tan β = tan θi cos ψ."""
    out = []
    for t in (1.0, 1.0 / math.sqrt(3.0)):
        c = t * ct / st if st > 0.0 else 2.0
        if c < 1.0:
            out.append(math.acos(c))
    return out


def _mirror_kink(st, ct, cpsi, rmax):
    """Phong's ``max(0, S·wo)ⁿ`` ends at 90° from S (ρ = π/2 in the mirror frame)."""
    return [np.full(len(st), np.pi / 2)]


def _smith_ggx_horizon(alpha: float):
    """Height-correlated Smith GGX (ggx, gltf) at grazing incidence: where it sits on the
    horizon and how strong its pole beyond the horizon is (``integrator.integrate(horizon=...)``).

    ``G2/(4 ci co)·co = co/(2 den)``, ``2 den = co Si + ci So`` with ``Si = √(ci² + α² si²)``,
    ``So = √(co² + α² so²)`` (expanding ``ggx_g2_over_cos``'s denominator), is 0 where
    ``co Si = −ci So``, i.e. ``tan θo = −tan θi``: ``cos θo ≈ −cos θi``, just below the
    horizon.  In the half frame ``cos θo = R sin 2d`` (d = ρmax − ρ, module integrator.geometry)
    with
    ``R = hypot(sin θi cos ψ, cos θi)``, so the pole is ``cos θi/(2R)`` beyond the horizon:
    near it the specular integrand goes as ``d/(d + eps)``, a step of width eps that a panel
    of width ~1 rad cannot resolve at θi ≥ 85°.  Its amplitude relative to the node's inner
    integral is the integrand just outside the step over that integral; measured (ψ = 0,
    θi = 89.9°, the defaults otherwise) 0.97 at α = 1, 0.05 at α = 0.2 (gltf's α = 0.25:
    0.10), 5e-3 at α = 0.05, 6e-4 at α = 0.01: about α² (the tail D(π/2)/D(0) = α⁴ over the
    lobe's α²) for α ≥ 0.05.  Below that it is larger than α², but there the ordinary
    refinement handles the pole within the first call (scripts/bench_accuracy.py), and grading it
    would only cost evaluations.  (A first estimate, 4α/π from D(π/2)·(2/α) over the lobe's
    F/2, ignores that F at the horizon end is F(0°), not the lobe's F(90°) = 1: 5–20× too
    high.)  At θi = 90° (cos θi = 0) the pole meets the zero of co and cancels: none."""
    amp = alpha * alpha

    def horizon(st, ct, cpsi, rmax):
        r = np.hypot(st * cpsi, ct)
        # r ≥ cos θi > 0 where ct > 0; at θi = 90° (ct = 0) no pole: inf
        if ct.min() > 0.0:
            return 0.5 * ct / r, amp
        return np.divide(0.5 * ct, r, out=np.full(len(r), np.inf), where=ct > 0.0), amp

    return horizon


def _power_width(n: float) -> float:
    """Width of cosⁿρ ≈ exp(−nρ²/2): 1/√n, at most π/2."""
    return min(np.pi / 2, 1.0 / math.sqrt(max(n, 0.4)))


#: abc's hint leaves out the V-cavity azimuths inside the integrator's first outer grading panel
#: only
#: where that panel (2 cot θi wide) is narrower than this (θi > 84.3°; at 80.5–81°, 0.32 rad,
#: the estimate fell below the error for 5 of the 100 materials: K15 − G7 over a panel that
#: wide misses the inner integral's kinks; at 82–90° it held for all, scripts/bench_accuracy.py) ...
ABC_DROP_WIDTH = np.pi / 16
#: ... and at tolerances from this up: the drop moves the albedo by up to 1e-11 (measured),
#: which the estimate no longer covers below rtol 1e-10
ABC_DROP_RTOL = 1e-8


def _abc_azimuths(st: float, ct: float, drop: bool = True) -> list[float]:
    """abc's outer panel ends: :func:`_vcavity_azimuths`, except (``drop``) where the integrator's
    outer grading toward ψ = π/2 starts less than ABC_DROP_WIDTH from it (its first panel,
    2 cot θi wide, holds both meeting points, at cot θi and cot θi/√3 from π/2, whose two
    extra panels cost 30 outer nodes for an outer weight below 2 cot θi); and at θi = 90°,
    where that grading is empty, one light-side end π/16 from π/2.

    At θi = 90° (cos θd = cos ψ sin ρ in the half frame) the inner integral follows the
    exact Fresnel factor F(cos θd) up to F(0) = 1 as ψ → π/2: it nearly doubles over the last
    ~0.3 rad, and one K15 panel over [0, π/2] missed it by 25 times its share (a second kernel
    call for 30 of the 100 materials).  Below 90° the integrator's grading always has a light-side
    end
    between π/64 and π/8 from π/2 (its coarsest: from 2 cot θi by 8 up to π/8); π/16 stands
    in for it at 90°."""
    if ct <= 0.0:
        return [np.pi / 2 - np.pi / 16]
    out = _vcavity_azimuths(st, ct)
    grading = integrator.outer_grading(st, ct)  # the integrator's outer grading, from π/2 − w
    if drop and grading and grading[0] < ABC_DROP_WIDTH:
        out = [a for a in out if np.pi / 2 - a > grading[0]]
    return out


def _abc_lobe(v: Mapping[str, Any], rtol: float) -> Lobe:
    """abc: D = A/(1 + B(1 − cos θh))^C ≈ A/(1 + B θh²/2)^C is halved within θh ~ √(2/B)
    (B = 11…8e6 over the 100 materials); the V-cavity G is cook-torrance's (same kinks); the
    azimuths of :func:`_abc_azimuths` (the drop from ``ABC_DROP_RTOL`` up)."""
    b = float(table("abc").row(v["material"])["b"])
    drop = rtol >= ABC_DROP_RTOL
    return Lobe("half", math.sqrt(2.0 / b) if b > 0.0 else np.pi / 2, _vcavity_breaks,
                azimuths=lambda st, ct: _abc_azimuths(st, ct, drop))


#: cook-torrance's far side is graded to ψ = π (:func:`_cook_torrance_far`) where the horizon
#: at ψ = π, (π/2 − θi)/2 from the pole, is within this many lobe widths m
CT_FAR_LOBE = 1.0


def _cook_torrance_far(st: float, ct: float, m: float) -> list[float]:
    """cook-torrance's far-side outer panel ends, ψ − π/2 (radians), where the horizon cuts
    the lobe.

    On the far side (ψ = π/2 + w) ρmax = atan(cot θi / sin w)/2 falls from π/4 to
    ρmax(π) = (π/2 − θi)/2; once it is below the lobe's width the horizon cuts the lobe and
    the inner integral falls about as a power of ρmax ∝ cot θi / sin w: a scale-free tail
    with its singularity ~cot θi from π/2 (in the complex plane), which needs outer panels
    graded geometrically in w, as the integrator's grading does from 2 cot θi by OUTER_GRADING, but
    only up to OUTER_LIMIT.  Its last far panel [π/2 + w, π] is up to 32 times wider than w
    (4.5 at 80°, 9 at 85°, 30 at 88.5°), and its |K15 − G7| was 4.7 times its share at 85°
    (the defaults, m = 0.2), 12 times at 75° where the grading is empty (θi < 78.9°: one
    panel [π/2, π]).  Here, where ρmax(π) < CT_FAR_LOBE·m, the far side is graded on to π:
    from the integrator's last break (or from 2 cot θi itself where the integrator has none, as
    sgd's hint
    does) with pieces of ratio at most OUTER_GRADING, evenly in log w."""
    # st > 0: at normal incidence there is no far side (and 2 cot θi is infinite)
    if not (ct > 0.0 and st > 0.0 and 0.5 * math.atan2(ct, st) < CT_FAR_LOBE * m):
        return []
    grading = integrator.outer_grading(st, ct)
    out = []
    if grading:  # polar grades: its last break
        w = grading[-1]
    elif (w := integrator.OUTER_START * ct / st) < np.pi / 2:
        # polar does not grade: its first break, on the far side only
        out.append(w)
    else:
        return []
    r = (np.pi / 2) / w  # > 1
    n = math.ceil(math.log(r) / math.log(integrator.OUTER_GRADING) - 1e-9) - 1  # pieces ≤ ratio
    return out + [w * r ** (j / (n + 1)) for j in range(1, n + 1)]


def _cook_torrance_lobe(v: Mapping[str, Any], rtol: float) -> Lobe:
    """Beckmann lobe of width m; the V-cavity kinks as radial breaks, and where they cross
    (:func:`_vcavity_azimuths`) as outer ones once the lobe reaches them (m ≥ 0.3: below it
    exp(−tan²ρ/m²) is ≤ 2.5e-2 of the peak at ρ = π/6 and they cost evaluations for nothing;
    measured by scripts/bench_accuracy.py); the far side graded where the horizon cuts the lobe
    (:func:`_cook_torrance_far`)."""
    m = float(v["m"])
    # beyond tan²ρ = 45 m², D/D(0) = exp(−tan²ρ/m²)/cos⁴ρ < exp(−45)(1 + 45 m²)² ≤ 6e-17
    # (m ≤ 1): the specular term, and its kinks, are nil there; only the smooth diffuse
    # term is left, and a break would cost a panel at every outer node for nothing
    cut = math.atan(math.sqrt(45.0) * m)

    def breaks(st, ct, cpsi, rmax):
        return [np.where(b < cut, b, rmax) for b in _vcavity_breaks(st, ct, cpsi, rmax)]

    def azimuths(st: float, ct: float) -> list[float]:
        near = _vcavity_azimuths(st, ct) if m >= 0.3 else []
        return near + [np.pi / 2 + w for w in _cook_torrance_far(st, ct, m)]

    return Lobe("half", m, breaks, azimuths=azimuths)


#: sgd's first radial panel, in half widths of its lobe (:func:`_sgd_shape`): ggx's α is
#: 1.55 times its D's half width at half maximum (α·√(√2 − 1)), cook-torrance's m 1.2 times.
SGD_WIDTH = 1.5
#: The end of sgd's envelope exp(−tan²θh/α): tan θh = 5√α (e^−25, below any tolerance) ...
SGD_ENVELOPE_END = 5.0
#: ... added as a panel end unless the integrator's grading has one where tan θh/√α is in this range
#: (the envelope at e^−6…e^−49: the lobe's end already falls on a panel end)
SGD_ENVELOPE_COVERED = (2.5, 7.0)
#: A G1 clamp θ* so close to the horizon that s·δ² (G1's slope at θ* times the square of its
#: distance to 90°) is at most this share of rtol is not a panel end (see :func:`_sgd_shape`)
SGD_CLAMP_SHARE = 1e-2
#: Far-side outer grading for sgd up to this (see :func:`_sgd_azimuths`)
SGD_FAR_LIMIT = np.pi / 4
#: sgd's outer panels narrower than this use K7 (see :func:`_sgd_lobe`)
SGD_OUTER_K7 = 0.05


@lru_cache(maxsize=32)
def _sgd_shape(material: str) -> tuple[float, tuple[float, ...], tuple[float, ...],
                                       tuple[tuple[float, float], ...]]:
    """sgd's lobe, per material: ``(scale, rings, kinks, clamps)`` (radians).

    D ∝ exp(−a)/a^p/cos⁴θh, a = α + tan²θh/α: a core (1 + tan²θh/α²)^−p of width ~α in an
    envelope exp(−tan²θh/α) of width ~√α.  The scale is SGD_WIDTH times the half width at
    half maximum of the narrowest channel's core × envelope (t²/α + p·log(1 + t²/α²) = log 2
    for t = tan θh, by bisection: the left side increases with t; p < 0 is read as 0, none in
    the table): the core when p is large, the envelope when p ≈ 0 (p is 2e-14 for a tenth of
    the materials, where α alone put the first panels deep inside a flat top).  Where polar's
    grading from there (ratio 4) has no panel end while the envelope falls through
    e^−6…e^−49, one is added where it ends (tan θh = 5√α).

    G1(θo) = clamp(1 − Λ·expm1(c_g (θo − θ0)^k), 0, 1) has kinks at θ0 (0 < θ0 < π/2: the
    shift starts; k ≥ 5.6, so it is at least C⁵ there): ``kinks``; and at θ* where the clamp
    reaches 0: ``clamps``, pairs (θ*, s·δ²) with s = |G1'(θ*)| = (1 + Λ)·k·log(1 + 1/Λ)/(θ* −
    θ0) and δ = π/2 − θ*.  All 145 θ* of the tables below 90° are within 3.4e-6 rad of it
    (the fits put the clamp at the horizon): there the clamp changes G1 by at most s·δ, over a
    band of θo δ wide next to the horizon where f·cos θo itself vanishes like G1, so the
    albedo by ~s·δ² (≤ 1.4e-9 in the tables; measured for the default material, s·δ² =
    9e-12: 3e-12); as a panel end it costs a sliver panel at every outer node (a quarter of
    the evaluations at θi ≤ 60° for the default material).  :func:`_sgd_lobe` keeps those
    with s·δ² above SGD_CLAMP_SHARE·rtol."""
    t = table("sgd").row(material)
    alpha, p = np.asarray(t["alpha"], dtype=float), np.maximum(np.asarray(t["p"], float), 0.0)
    # half width: h(x) = x²/α + p·log1p(x²/α²) − log 2 is < 0 at 0 and ≥ 0 at √(α log 2)
    lo, hi = np.zeros(3), np.sqrt(alpha * math.log(2.0))
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        below = mid * mid / alpha + p * np.log1p((mid / alpha) ** 2) < math.log(2.0)
        lo, hi = np.where(below, mid, lo), np.where(below, hi, mid)
    scale = SGD_WIDTH * math.atan(float(np.min(hi)))
    # polar's radial grading (integrate): scale·FIRST_PANEL·GRADING^j below π/2, in units
    # of the narrowest envelope √α
    a0 = float(np.min(alpha))
    grading = [math.tan(g) / math.sqrt(a0) for g in integrator.radial_grading(scale, np.pi / 2)]
    lo_c, hi_c = SGD_ENVELOPE_COVERED
    rings = () if any(lo_c <= x <= hi_c for x in grading) else (
        math.atan(SGD_ENVELOPE_END * math.sqrt(a0)),)
    # the clamp: c_g·t^k reaches log(1 + 1/Λ) at t* = θ* − θ0, solved in logarithms (c_g up
    # to 1e38, k up to 856 overflow otherwise); Λ, c_g, k > 0 (the table); t* capped at
    # e^5 (beyond π anyway)
    lam, cg, k, th0 = (np.asarray(t[f], dtype=float) for f in ("lambda", "c_g", "k", "theta0"))
    x_star = np.log1p(1.0 / lam)
    t_star = np.exp(np.minimum((np.log(x_star) - np.log(cg)) / k, 5.0))  # > 0
    theta_star = th0 + t_star
    slope = (1.0 + lam) * k * x_star / t_star  # |dG1/dθ| at θ*: Λ·e^x*·k·x*/t*
    inside = (theta_star > 0.0) & (theta_star < np.pi / 2)
    clamps = tuple((float(a), float(s * (np.pi / 2 - a) ** 2))
                   for a, s in zip(theta_star[inside], slope[inside], strict=True))
    # sorted, each once, in plain floats (not np.unique: without its index outputs it imports
    # numpy.ma, a one-off 8–30 ms in the first sgd frame's worker)
    kinks = tuple(sorted({float(x) for x in th0[(th0 > 0.0) & (th0 < np.pi / 2)]}))
    return scale, rings, kinks, clamps


def _sgd_azimuths(st: float, ct: float) -> list[float]:
    """sgd's far side: polar grades ψ toward π/2 from 2 cot θi (``OUTER_START``) only while
    that is below π/8 (θi > 79°); on the far side ρmax(ψ) falls from π/4 to (π/2 − θi)/2
    within ~cot θi of π/2, where the horizon cuts through sgd's envelope (up to ~1 rad wide),
    and one K15 panel over [π/2, π] missed that by up to 6 times its share at 70–78° (the
    default material at 75°: a second and third kernel call).  The same first break, on the
    far side only, up to SGD_FAR_LIMIT (θi ≥ 68.5°)."""
    if not 0.0 < ct < 0.5 * st:
        return []
    w = integrator.OUTER_START * ct / st
    return [np.pi / 2 + w] if integrator.OUTER_LIMIT <= w < SGD_FAR_LIMIT else []


def _sgd_lobe(v: Mapping[str, Any], rtol: float) -> Lobe:
    """sgd: the lobe's scale, envelope end and G1 kinks of :func:`_sgd_shape` (the clamps
    whose s·δ² is above SGD_CLAMP_SHARE·rtol), the far-side azimuth of
    :func:`_sgd_azimuths`.  A G1 kink at θo = θk is, in the half frame (cos θo = R cos(2ρ −
    β), module integrator.geometry), at 2ρ = β ± acos(cos θk / R): radial breaks."""
    scale, rings, kinks, clamps = _sgd_shape(v["material"])
    kinks = sorted(set(kinks).union(a for a, e in clamps if e > SGD_CLAMP_SHARE * rtol))

    def breaks(st, ct, cpsi, rmax):
        # no solution where cos θk > R (then ρmax is returned: ignored)
        b = np.arctan2(st * cpsi, ct)
        r = np.hypot(st * cpsi, ct)
        out = []
        for k in kinks:
            ok = r >= math.cos(k)
            c = np.arccos(np.clip(np.divide(math.cos(k), r, out=np.ones_like(r), where=ok),
                                  -1.0, 1.0))
            out += [np.where(ok, 0.5 * (b - c), rmax), np.where(ok, 0.5 * (b + c), rmax)]
        return out

    return Lobe("half", scale, breaks if kinks else None, azimuths=_sgd_azimuths, rings=rings,
                outer_k7=SGD_OUTER_K7)


#: Registry name → (values, rtol) → :class:`Lobe`, for the built-in models (used only when the
#: model is the registered one: same kernel).  ``rtol`` is the tolerance the albedo is asked
#: for: a hint may leave out a panel end whose effect on the value is far below it.
LOBE_HINTS: dict[str, Callable[[Mapping[str, Any], float], Lobe]] = {
    "lambert": lambda v, rtol: Lobe("normal", np.pi / 2),
    "oren-nayar": lambda v, rtol: Lobe(
        "normal", np.pi / 2, _theta_i_break,
        second_layout=ON_CLAMP_COS if float(v["sigma"]) >= ON_CLAMP_SIGMA else None),
    "oren-nayar-simple": lambda v, rtol: Lobe("normal", np.pi / 2, _theta_i_break),
    "disney-diffuse": lambda v, rtol: Lobe("normal", np.pi / 2),
    "phong": lambda v, rtol: Lobe("mirror", _power_width(float(v["n"])), _mirror_kink),
    "blinn-phong": lambda v, rtol: Lobe("half", _power_width(float(v["n"]))),
    "cook-torrance": _cook_torrance_lobe,
    "ggx": lambda v, rtol: Lobe("half", float(v["alpha"]),
                          horizon=_smith_ggx_horizon(float(v["alpha"]))),
    "gltf": lambda v, rtol: Lobe("half", alpha_from_roughness(v["roughness"]),
                           horizon=_smith_ggx_horizon(alpha_from_roughness(v["roughness"]))),
    "ue4": lambda v, rtol: Lobe("half", alpha_from_roughness(v["roughness"])),
    # measured, isotropic; the specular peak of shiny materials is ~0.5° wide.  The lookups
    # are piecewise constant or linear over 1.46 million bins, so refinement never reaches
    # 1e-6: a smaller budget (the error estimate stays honest: 1e-5…1e-3 measured)
    "abc": _abc_lobe,
    "sgd": _sgd_lobe,
    "merl": lambda v, rtol: Lobe("half", 0.004, max_evals=MEASURED_MAX_EVALS),
}
#: Any other model: the half-vector frame (a specular lobe at the pole for every θi), graded
#: down to the narrowest built-in lobe, no symmetry assumed.
DEFAULT_LOBE = Lobe("half", 1e-3, None, False)


def lobe(model: Model, values: Mapping[str, Any], rtol: float) -> Lobe:
    """The integration hint for ``model`` at relative tolerance ``rtol`` (the albedo's, e.g.
    :data:`tuibrdf.core.sphere.albedo.DEFAULT_RTOL`; see :data:`LOBE_HINTS`)."""
    name = registered_name(model)
    return LOBE_HINTS[name](values, rtol) if name in LOBE_HINTS else DEFAULT_LOBE
