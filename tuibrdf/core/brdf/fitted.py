"""The published fits of the 100 MERL materials: the ABC and Shifted Gamma Distribution models.

The per-material numbers come from the public-domain ``dj_brdf.h`` (jdupuy/dj_brdf, tables
``djb::abc::s_data`` and ``djb::sgd::s_data``), read from ``tuibrdf/core/brdf/data/*.tsv`` at first
use (:mod:`tuibrdf.core.brdf.materials`).  The formulas below are those the tables were fitted with,
as dj_brdf evaluates them (checked against its ``abc::eval`` and ``sgd::eval``); the evaluation
here is written from the formulas.  RGB, per channel; θ angles in radians; ``cos θd = H·wi``.

**abc** (Löw, Kronander, Ynnerman, Unger 2012, "BRDF models for accurate and efficient
rendering of glossy surfaces", ACM TOG 31(1); the microfacet form with the ABC distribution)::

    f = kd/π + F(cos θd; η)·D(θh)·G / (π cos θi cos θo)
    D(θh) = A / (1 + B (1 − cos θh))^C            (A per channel; B, C, η per material)
    G = min(1, 2 cosθh cosθi / cosθd, 2 cosθh cosθo / cosθd)     (V-cavity)
    F = exact unpolarised Fresnel of a dielectric of index η (Cook & Torrance 1981)

D is not normalised (A absorbs the scale), hence ``π`` rather than ``4`` in the denominator.

**sgd** (Bagher, Soler, Holzschuch 2012, "Accurate fitting of measured reflectances using a
Shifted Gamma micro-facet distribution", Computer Graphics Forum 31(4))::

    f = (ρd + ρs·F·D·G1(wi)·G1(wo) / (cos θi cos θo)) / π
    D(θh) = κ·exp(−a) / (π·a^p·cos⁴θh),    a = α + tan²θh / α
    F(c) = f0 − c·f1 + (1 − c)⁵ (1 − f0),   c = cos θd
    G1(w) = clamp(1 + Λ·(1 − exp(c_g·max(0, θ − θ0)^k)), 0, 1),   θ = angle(w, N)

Guards (each at its source, below): ``1 − cos θh`` as ``sin²θh/(1 + cos θh)`` (B reaches 8e6,
cancellation would cost 10 digits near H = N); ``1 − exp(x)`` as ``−expm1(x)`` (Λ reaches 1.5e7:
G1 lives where x < 1/Λ, and ``1 − exp(x)`` keeps no digit of such an x); G1 is set to 0 without
evaluating ``exp`` once ``c_g·t^k ≥ log(1 + 1/Λ)`` (the clamp's threshold; c_g = 1e38 for
black-obsidian would overflow ``exp``, and t^k with k up to 856 would overflow ``pow``), decided
in log space (t is capped just above the threshold, computed once per material; the few t
within 1e-9 of it take the logarithmic test itself); D is 0 where ``exp(−a)`` underflows, and
``a`` is capped at 746 for ``a^p`` (which then cannot overflow; beyond, D = 0).

Cost (``scripts/bench_kernels.py``): sgd computes its three channels as the rows of
``(3, M)`` arrays (one numpy call per operation, each over a contiguous row), and only at the
points where the specular term can be ≠ 0 (ci·co above its floor, exp(−a) > 0 in some channel):
elsewhere the value is ρd/π, as the formula gives there.

Horizon: abc returns the V-cavity limit where one of θi, θo is 90° and specular 0 where both are
(as cook-torrance).  sgd's G1 reaches 0 only through its clamp, which the fits put at or just
below 90° for most materials; where G1(90°) > 0 (89 materials in some channel, near 1 for 10)
the specular term diverges like 1/cos θ toward the horizon: no limit.  On the horizon the
specular term is 0 and the diffuse term ρd/π remains (the limit where G1 reaches 0 first).

Negative values: sgd's F goes below 0 for a few materials (f1 > f0 near cos θd = 1, e.g.
white-fabric2).  The table was fitted with that F, so the model's value is kept where the total is
positive and clamped, ``f = max(0, ·)``, where the negative specular term exceeds the diffuse one.
abc is ≥ 0 by construction.  Both are reciprocal: every factor is symmetric in (wi, wo) (cos θd =
|wi + wo|/2, G1(wi)·G1(wo), the V-cavity min).
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from tuibrdf.core.brdf.fresnel import pow5
from tuibrdf.core.brdf.materials import material_aliases, material_names, table
from tuibrdf.core.brdf.microfacet import HUGE, vcavity_g_over_cos
from tuibrdf.core.directions import Geometry
from tuibrdf.core.numerics import kernel_errstate, safe_div, safe_sqrt
from tuibrdf.core.params import Model, Param

DEFAULT_MATERIAL = "gold-metallic-paint"
#: ``ci·co`` below this is treated as 0 in sgd's 1/(cos θi cos θo): the numerator is ≤ ~1e6,
#: so the quotient stays below 1e296 (finite); the formula has no limit there anyway
SGD_MIN_COS_PRODUCT = 1e-290

MATERIAL = Param(
    "material", "mat", DEFAULT_MATERIAL, kind="choice", choices=material_names(),
    aliases=material_aliases(),
    choices_doc="one of the 100 MERL names (see 'tuibrdf materials')",
    doc="MERL material whose published fit is shown (SGD's other names accepted)",
)


@lru_cache(maxsize=32)
def _row(kind: str, material: str) -> dict:
    """One material's parameters (RGB fields as ``(3,)`` arrays), looked up once per material.
    The arrays are shared: read only."""
    row = table(kind).row(material)
    for v in row.values():
        if isinstance(v, np.ndarray):
            v.flags.writeable = False
    return row


def fresnel_dielectric(cos_d: np.ndarray, eta: float) -> np.ndarray:
    """Exact unpolarised Fresnel reflectance of a dielectric of real index ``eta`` (Cook &
    Torrance 1981, the form dj_brdf uses)::

        g = √(η² − 1 + c²),  F = ½ (g − c)²/(g + c)² · (1 + (c(g + c) − 1)²/(c(g − c) + 1)²)

    ``η² − 1 + c² ≤ 0`` (η < 1, total internal reflection) gives F = 1.  The tables' η are all in
    [1.04, 100], where g > 0 and both denominators are > 0.
    """
    c = np.minimum(np.maximum(cos_d, 0.0), 1.0)
    e2m1 = eta * eta - 1.0
    g2 = e2m1 + c * c
    if e2m1 > 0.0:
        # η > 1: g ≥ √(η² − 1) > 0, so g + c > 0 and c(g − c) + 1 ≥ 1 − c² + cg > 0 (c ≤ 1):
        # no total reflection, both quotients defined everywhere (the tables' case)
        g = np.sqrt(g2)
        gmc, gpc = g - c, g + c
        a = gmc * gmc / (gpc * gpc)
        num, den = c * gpc - 1.0, c * gmc + 1.0
        return 0.5 * a * (1.0 + num * num / (den * den))
    tir = g2 <= 0.0
    g = safe_sqrt(g2)
    # (g + c)² > 0 unless g = c = 0 (η = 1 at grazing: 0/0, F's limit there is 1) or it
    # underflows (c ≲ 1e-154 under total reflection, where F = 1 anyway); c(g − c) + 1 ≥
    # 1 − c² + cg > 0 unless c = 1 and g = 0 (only with total reflection, masked)
    gpc2 = (g + c) ** 2
    a = safe_div((g - c) ** 2, gpc2, gpc2 > 0.0, fill=1.0)
    b = safe_div((c * (g + c) - 1.0) ** 2, (c * (g - c) + 1.0) ** 2, ~tir, fill=1.0)
    return np.where(tir, 1.0, 0.5 * a * (1.0 + b))


class _Abc:
    """One material's ABC parameters: kd and 4A as ``(3, 1)`` columns (the channels are rows
    of ``(3, M)`` arrays), B, C, η and η² − 1 as floats."""

    def __init__(self, material: str):
        t = _row("abc", material)
        # ×4: cook-torrance's helper returns G/(4 ci co); scaling A by 4 instead of G is exact
        # (a power of 2, and 4A/D's base stays a normal number)
        self.kd, self.a4 = (np.array(v, dtype=float).reshape(3, 1) for v in (t["kd"],
                                                                               4.0 * t["a"]))
        self.b, self.c, self.eta = t["b"], t["c"], t["eta"]
        self.e2m1 = self.eta * self.eta - 1.0


@lru_cache(maxsize=32)
def _abc_params(material: str) -> _Abc:
    return _Abc(material)


def _fresnel_abc(c, q: _Abc):
    """:func:`fresnel_dielectric` for ``c`` = cos θd, already in [0, 1] (Geometry), without the
    clip (the same operations otherwise); η > 1 in every table."""
    if q.e2m1 <= 0.0:
        return fresnel_dielectric(c, q.eta)
    # η > 1: g ≥ √(η² − 1) > 0, so g + c > 0 and c(g − c) + 1 ≥ 1 − c² + cg > 0 (c ≤ 1)
    g = np.sqrt(q.e2m1 + c * c)
    gmc, gpc = g - c, g + c
    a = gmc * gmc / (gpc * gpc)
    num, den = c * gpc - 1.0, c * gmc + 1.0
    return 0.5 * a * (1.0 + num * num / (den * den))


def abc(wi, wo, material: str):
    q = _abc_params(material)
    g = Geometry(wi, wo)
    shape = np.shape(g.above)
    # 1 − cos θh without cancellation near H = N (B up to 8e6 multiplies it); 1 + cos θh ≥ 1
    one_minus = g.sin2_h / (1.0 + np.maximum(g.cos_h, 0.0))
    p = (1.0 + q.b * one_minus) ** q.c  # D = A/p: base ≥ 1 (B ≥ 0, 1 − cos ≥ 0): p ≥ 1
    # G/(4 ci co) with its limit where one cosine is 0, 0 where both are (cook-torrance's
    # helper).  H undefined (wi = −wo) with both directions above means both on the horizon,
    # where the helper gives 0 already; below the horizon the value is replaced by 0 below
    fg = _fresnel_abc(g.cos_d, q) * vcavity_g_over_cos(g.cos_h, g.cos_i, g.cos_o, g.cos_d)
    # the channels as the rows of (3, M): (kd + A/p·F·G/(ci co))/π, one call per operation
    out = np.empty(shape + (3,))
    if len(shape) > 1:
        p, fg = _flat(p, shape), _flat(fg, shape)
    np.divide(q.kd + q.a4 / p * fg, np.pi, out=out.reshape(-1, 3).T)
    if not np.all(g.above):
        out[~np.asarray(g.above)] = 0.0
    return out


def _theta(sin2, z):
    """Polar angle from ``x² + y²`` and ``z`` (as :func:`~tuibrdf.core.directions.theta_of`)."""
    return np.arctan2(np.sqrt(sin2), z)  # a sum of squares: ≥ 0


#: ``t`` within this relative distance of the G1 clamp's threshold t* (below) is decided by
#: the logarithmic test itself; the test's rounding moves its threshold by ≲ 1e-13 relative
#: (log c_g + k·log t has |terms| ≤ 200 near t*, so ≤ 1e-13 absolute error, and d(k log t) =
#: k dt/t with k ≥ 5.6), far inside this band
_G1_BAND = 1e-9


class _Sgd:
    """One material's SGD parameters in the channel-major layout: each RGB field as a ``(3, 1)``
    column against grey ``(M,)`` arrays, and the per-material constants of the formula
    (computed once per material)."""

    def __init__(self, material: str):
        t = _row("sgd", material)
        shape = (3, 1)

        def col(v):
            v = np.array(v, dtype=float).reshape(shape)
            v.flags.writeable = False
            return v

        self.f0, self.f1, self.alpha, self.p = (col(t[f]) for f in ("f0", "f1", "alpha", "p"))
        self.lam, self.c_g, self.k, self.theta0 = (
            col(t[f]) for f in ("lambda", "c_g", "k", "theta0"))
        lam, c_g, k = t["lambda"], t["c_g"], t["k"]  # > 0 (checked when the table is read)
        with kernel_errstate():
            self.one_m_f0 = col(1.0 - t["f0"])
            # G1's clamp in log space (see _sgd_g1): x = c_g·t^k reaches log(1 + 1/Λ) where
            # log c_g + k·log t ≥ log log(1 + 1/Λ), i.e. at t* = exp((log log(1 + 1/Λ) −
            # log c_g)/k) ∈ [8e-9, 40] for the tables (Λ ∈ [4.5e-8, 1.5e7], c_g ∈ [3e-8, 1e38],
            # k ≥ 5.6): no overflow; t ≥ t*·(1 + band) is dead for certain, t < t*·(1 − band)
            # live, the band in between is decided by the test as written
            self.log_cg = col(np.log(c_g))
            self.log_thr = col(np.log(np.log1p(1.0 / lam)))
            t_star = np.exp((np.log(np.log1p(1.0 / lam)) - np.log(c_g)) / k)
            self.t_lo = col(t_star * (1.0 - _G1_BAND))
            self.t_hi = col(t_star * (1.0 + _G1_BAND))
            # the specular factor's per-material part: ρs·κ/π
            self.spec = col(t["rho_s"] * t["kappa"] / np.pi)
            self.rho_d = col(t["rho_d"])
            # exp(−a) = 0 in every channel where tan²θh ≥ this (see sgd)
            self.tan2_max = 746.0 * float(np.max(t["alpha"]))
        #: G1 of single directions, by (sin²θ, cos θ) (see _sgd_g1_cached)
        self.g1_cache: dict[tuple[float, float], np.ndarray] = {}


@lru_cache(maxsize=32)
def _sgd_params(material: str) -> _Sgd:
    return _Sgd(material)


def sgd_g1(theta: np.ndarray, lam, c_g, k, theta0) -> np.ndarray:
    """``clamp(1 + Λ(1 − exp(c_g·max(0, θ − θ0)^k)), 0, 1)``, ``(..., 3)``; needs Λ, c_g, k > 0.

    With x = c_g·t^k ≥ 0, G1 = 1 − Λ·expm1(x) reaches the clamp 0 at x = log(1 + 1/Λ); beyond
    it G1 = 0 is returned without computing exp(x) or t^k (which overflow for c_g = 1e38 or
    k = 856), the test being made on logarithms: log c_g + k log t ≥ log log(1 + 1/Λ).
    """
    return _sgd_g1_plain(np.asarray(theta, dtype=float)[..., None], lam, c_g, k, theta0)


def _sgd_g1_plain(theta, lam, c_g, k, theta0):
    """:func:`sgd_g1` as written, for parameters of any shape that broadcasts."""
    t = np.maximum(theta - theta0, 0.0)
    pos = t > 0.0
    log_t = np.log(t, out=np.full(np.shape(t), -np.inf), where=pos)  # t = 0: x = 0, G1 = 1
    lx = np.log(c_g) + k * log_t
    dead = lx >= np.log(np.log1p(1.0 / lam))
    live = pos & ~dead  # here x < log(1 + 1/Λ) ≤ 17 (Λ ≥ 4.5e-8 in the table): no overflow
    x = np.multiply(c_g, np.power(t, k, out=np.zeros(np.shape(t)), where=live),
                    out=np.zeros(np.shape(t)), where=live)
    # 1 − exp(x) as −expm1(x): x is below 1/Λ wherever G1 > 0, far below 1 for Λ up to 1.5e7
    g1 = np.minimum(np.maximum(1.0 - lam * np.expm1(x), 0.0), 1.0)
    return np.where(dead, 0.0, g1)


def _sgd_g1(theta, q: _Sgd):
    """G1 of polar angle(s) ``theta`` (grey, any shape) for the three channels of ``q``:
    ``(3,) + theta.shape``; the values of :func:`_sgd_g1_plain` (the same operations on every
    element whose value is kept, up to the last bits numpy's loops for exp, log and pow give
    on a given CPU and layout; tests/test_fitted_fast.py bounds them).

    No logarithm per element: ``t`` is clipped to [0, t*·(1 + band)] before the power, which
    leaves t = 0 (θ ≤ θ0: x = 0, G1 = 1 as written) and every t below t*(1 + band) unchanged.
    The clipped ones are dead: there x = x*·(1 + band)^k with x* = log(1 + 1/Λ), so
    1 − Λ·expm1(x) ≈ −(1 + Λ)·x*·k·band ≤ −5.6e-9 (since (1 + Λ)·log(1 + 1/Λ) ≥ 1, k ≥ 5.6),
    far below the rounding of the 1e-15: the clamp at 0 gives G1 = 0, as written; x stays
    ≤ 18 (no overflow).  In the band t*(1 ± band) the logarithmic test as written decides."""
    t = theta - q.theta0
    tc = np.minimum(np.maximum(t, 0.0), q.t_hi)
    x = q.c_g * np.power(tc, q.k)
    # 1 − exp(x) as −expm1(x): x is below 1/Λ wherever G1 > 0, far below 1 for Λ up to 1.5e7;
    # x ≥ 0 and Λ > 0, so 1 − Λ·expm1(x) ≤ 1: the clamp at 1 never acts
    g1 = np.maximum(1.0 - q.lam * np.expm1(x), 0.0)
    band = (tc >= q.t_lo) & (tc < q.t_hi)
    if band.any():
        at = np.nonzero(band)
        ch = at[0]
        # the logarithmic test as written (t ≥ t*(1 − band) > 0: log defined)
        dead = q.log_cg.ravel()[ch] + q.k.ravel()[ch] * np.log(t[at]) >= q.log_thr.ravel()[ch]
        g1[tuple(i[dead] for i in at)] = 0.0
    return g1


def _sgd_g1_cached(sin2, z, q: _Sgd):
    """G1 of the direction(s) with ``sin²θ`` and ``cos θ``; for a single direction (scalars:
    the light of a whole call, the same from call to call in the viewer and the quadrature)
    the ``(3, 1)`` column is kept per material, for the last 64 such directions."""
    if np.ndim(sin2) or np.ndim(z):
        return _sgd_g1(_theta(sin2, z), q)
    key = (float(sin2), float(z))
    g1 = q.g1_cache.get(key)
    if g1 is None:
        if len(q.g1_cache) >= 64:
            q.g1_cache.clear()
        g1 = q.g1_cache[key] = _sgd_g1(_theta(sin2, z), q)
        g1.flags.writeable = False
    return g1


def sgd(wi, wo, material: str):
    g = Geometry(wi, wo)
    shape = np.shape(g.above)
    q = _sgd_params(material)
    c2 = g.cos_h * g.cos_h
    # tan²θh = sin²/cos²: on the horizon, and wherever the quotient would reach HUGE (cos²θh ~
    # 1e-320 from a unit vector with subnormal z), the denominator is raised so that it is
    # HUGE: a ≥ HUGE/α is still finite (α ≥ 1.6e-5) and exp(−a) = 0, D's limit; unchanged
    # wherever it is below HUGE.  sin² and cos² are not both 0 (no 0/0).
    tan2 = g.sin2_h / np.maximum(c2, g.sin2_h * (1.0 / HUGE))
    cc = g.cos_i * g.cos_o
    # 1/(ci co): no limit on the horizon (the term diverges like 1/cos θ): the specular term is
    # 0 where ci·co ≤ SGD_MIN_COS_PRODUCT, and where tan²θh ≥ 746·max α, since there exp(−a) =
    # 0 in every channel (a ≥ tan²θh/α ≥ 746 − rounding).  H undefined (wi = −wo) with both
    # directions above means both on the horizon: cc = 0.  Below the horizon: 0 (at the end).
    spec_live = (cc > SGD_MIN_COS_PRODUCT) & (tan2 < q.tan2_max)
    out = np.empty(shape + (3,))
    out_t = out.reshape(-1, 3).T  # (3, M): the channels' rows, a view of out
    n_live = np.count_nonzero(spec_live)
    if n_live == spec_live.size:
        # everywhere (the usual case): the grey arrays flattened to (M,)
        grey = (g.cos_d, tan2, c2, cc, g.sin2_i, g.cos_i, g.sin2_o, g.cos_o)
        if len(shape) > 1:
            grey = [_flat(x, shape) for x in grey]
        _sgd_total(q, *grey, out=out_t)
    else:
        # the diffuse term alone where the specular one is 0, (ρd + 0)/π as written
        out_t[...] = q.rho_d / np.pi
        if n_live:
            at = np.flatnonzero(spec_live)
            grey = [_take(x, shape, at) for x in (g.cos_d, tan2, c2, cc, g.sin2_i, g.cos_i,
                                                  g.sin2_o, g.cos_o)]
            out_t[:, at] = _sgd_total(q, *grey)
    if not np.all(g.above):
        out[~np.asarray(g.above)] = 0.0
    return out


def _flat(x, shape):
    """A grey quantity as a 1-D array over the result's points (a scalar stays a scalar)."""
    if not np.ndim(x):
        return x
    if np.shape(x) != shape:
        x = np.broadcast_to(x, shape)
    return x.reshape(-1)


def _take(x, shape, at):
    return x if not np.ndim(x) else _flat(x, shape)[at]


def _sgd_total(q: _Sgd, c, tan2, c2, cc, sin2_i, cos_i, sin2_o, cos_o, out=None):
    """``max((ρd + specular)/π, 0)`` as ``(3, M)`` from grey 1-D arrays (or scalars) of the
    points where the specular term may be ≠ 0 (both directions strictly above the horizon:
    ci·co > SGD_MIN_COS_PRODUCT).  The channels are rows: one numpy call per operation for
    all three, each running over the contiguous last axis (fast per element), the parameters
    as (3, 1) columns."""
    u5 = pow5(1.0 - c)  # c = cos θd ∈ [0, 1] by construction (Geometry)
    fres = q.f0 - c * q.f1 + u5 * q.one_m_f0
    a = tan2 / q.alpha + q.alpha  # α > 0 (checked when the table is read)
    e = np.exp(-a)  # underflows harmlessly to 0 for a sharp lobe: D = 0
    # a^p only matters where exp(−a) > 0, i.e. a < 746: the cap keeps a^p finite elsewhere
    # (a = HUGE/α on the horizon); a ≥ α ≥ 1.6e-5 and 0 < p ≤ 1.8 give 0 < a^p ≤ 1.3e5
    ap = np.power(np.minimum(a, 746.0), q.p)
    # 1/(cos⁴θh·ci·co): ci·co > SGD_MIN_COS_PRODUCT here, and where D > 0 in a channel
    # cos²θh > 1/(1 + 746α) ≥ 1.5e-3, so the product is > 2e-296 and the floor 1e-300 changes
    # nothing there; where D = 0 it keeps the factor finite (≤ 1e300) and the term 0
    w = 1.0 / np.maximum(c2 * c2 * cc, 1e-300)
    # specular = ρs·F·D·G1(wi)·G1(wo)/(ci co), D = κ e^(−a)/(π a^p cos⁴θh), as
    # (ρs κ/π)·e/a^p·F·(G1(wi)·G1(wo))·w: the factors before w are bounded, w last (the
    # product is as large as the term, ≤ 1e296 as SGD_MIN_COS_PRODUCT says); every factor is
    # symmetric in (wi, wo), so the value is reciprocal to the last bit
    g11 = _sgd_g1_cached(sin2_i, cos_i, q) * _sgd_g1_cached(sin2_o, cos_o, q)
    spec = q.spec * e / ap * fres * g11 * w
    # F < 0 for a few materials: keep the fitted value where the total is ≥ 0, clamp below
    return np.maximum((q.rho_d + spec) / np.pi, 0.0, out=out)


ABC = Model(
    "abc", "ABC fit of a MERL material", (MATERIAL,), abc, rgb=True,
    summary="Löw et al. 2012: kd/π + F·A/(1+B(1−cosθh))^C·G/(π cosθi cosθo), per-material fit",
    horizon="limit where one of θi, θo is 90°; specular 0 where both are",
    notes=("numbers: dj_brdf.h (public domain), table djb::abc::s_data; "
           "docs/reference/materials.md",),
)
SGD = Model(
    "sgd", "Shifted Gamma fit of a MERL material", (MATERIAL,), sgd, rgb=True,
    summary="Bagher et al. 2012: (ρd + ρs·F·D_SGD·G1·G1/(cosθi cosθo))/π, per-material fit",
    horizon="diffuse ρd/π; the specular term is 0 there (it diverges toward 90° where G1 > 0)",
    notes=("numbers: dj_brdf.h (public domain), table djb::sgd::s_data; "
           "docs/reference/materials.md",
           "F < 0 for a few materials: f = max(0, ...) where the specular term outweighs ρd"),
)
