"""The published fits of the 100 MERL materials: the ABC and Shifted Gamma Distribution models.

The per-material numbers come from the public-domain ``dj_brdf.h`` (jdupuy/dj_brdf, tables
``djb::abc::s_data`` and ``djb::sgd::s_data``), read from ``tuibrdf/core/data/*.tsv`` at first
use (:mod:`tuibrdf.core.materials`).  The formulas below are those the tables were fitted with,
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
in log space; D is 0 where ``exp(−a)`` underflows, and ``a^p`` is taken only where it does not.

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

from ..frame import Geometry
from ..fresnel import pow5
from ..materials import material_aliases, material_names, table
from ..microfacet import HUGE, vcavity_g_over_cos
from ..numerics import safe_div, safe_sqrt
from ..params import Model, Param
from .rgb import rgb

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


def abc(wi, wo, material: str):
    t = _row("abc", material)
    g = Geometry(wi, wo)
    ok = g.above & g.h_valid
    # 1 − cos θh without cancellation near H = N (B up to 8e6 multiplies it); 1 + cos θh ≥ 1
    one_minus = g.sin2_h / (1.0 + np.maximum(g.cos_h, 0.0))
    p = (1.0 + t["b"] * one_minus) ** t["c"]  # D = A/p: base ≥ 1 (B ≥ 0, 1 − cos ≥ 0): p ≥ 1
    f = fresnel_dielectric(g.cos_d, t["eta"])
    # G/(ci co) with its limit where one cosine is 0, 0 where both are (cook-torrance's helper
    # returns G/(4 ci co); ×4 is exact)
    fg = f * np.where(ok, 4.0 * vcavity_g_over_cos(g.cos_h, g.cos_i, g.cos_o, g.cos_d), 0.0)
    return rgb(g.above, (p, fg), (t["kd"], t["a"]), _abc_channel)


def _abc_channel(p, fg, kd, a):
    return (kd + a / p * fg) / np.pi


def _sgd_ndf(tan2, c2, alpha, p, kappa):
    """:func:`sgd_ndf` from ``tan²θh`` (inf on the horizon) and ``cos²θh``, for parameters of
    any shape that broadcasts (one channel's scalars in the kernel)."""
    a = alpha + tan2 / alpha  # α > 0 (checked when the table is read); inf stays inf
    e = np.exp(-a)  # underflows harmlessly to 0 for a sharp lobe
    live = e > 0.0  # a < 746 here: a^p is finite, and cos²θh > 1/(1 + 746α) is far from 0
    ap = np.power(a, p, out=np.ones(np.shape(e)), where=live)
    return safe_div(kappa * e, np.pi * ap * c2 * c2, live)


def _tan2(c2, s2):
    # tan²θh = sin²/cos²: infinite on the horizon, where exp(−a) makes D's limit 0; also where
    # the quotient would reach HUGE (cos²θh ~ 1e-320 from a unit vector with subnormal z: the
    # division overflowed), since exp(−1e300/α) is 0 as well
    return safe_div(s2, c2, c2 > s2 * (1.0 / HUGE), fill=np.inf)


def sgd_ndf(cos_h: np.ndarray, sin2_h: np.ndarray, alpha, p, kappa) -> np.ndarray:
    """``κ·exp(−a)/(π·a^p·cos⁴θh)``, ``a = α + tan²θh/α``; ``(..., 3)`` for RGB parameters."""
    c2 = (cos_h * cos_h)[..., None]
    s2 = np.asarray(sin2_h)[..., None]
    return _sgd_ndf(_tan2(c2, s2), c2, alpha, p, kappa)


def sgd_g1(theta: np.ndarray, lam, c_g, k, theta0) -> np.ndarray:
    """``clamp(1 + Λ(1 − exp(c_g·max(0, θ − θ0)^k)), 0, 1)``, ``(..., 3)``; needs Λ, c_g, k > 0.

    With x = c_g·t^k ≥ 0, G1 = 1 − Λ·expm1(x) reaches the clamp 0 at x = log(1 + 1/Λ); beyond
    it G1 = 0 is returned without computing exp(x) or t^k (which overflow for c_g = 1e38 or
    k = 856), the test being made on logarithms: log c_g + k log t ≥ log log(1 + 1/Λ).
    """
    return _sgd_g1(np.asarray(theta, dtype=float)[..., None], lam, c_g, k, theta0)


def _sgd_g1(theta, lam, c_g, k, theta0):
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


def _theta(sin2, z):
    """Polar angle from ``x² + y²`` and ``z`` (as :func:`~tuibrdf.core.frame.theta_of`)."""
    return np.arctan2(np.sqrt(sin2), z)  # a sum of squares: ≥ 0


def sgd(wi, wo, material: str):
    t = _row("sgd", material)
    g = Geometry(wi, wo)
    c = g.cos_d  # ∈ [0, 1] by construction (Geometry)
    u5 = pow5(1.0 - c)
    c2 = g.cos_h * g.cos_h
    tan2 = _tan2(c2, g.sin2_h)
    cc = g.cos_i * g.cos_o
    # 1/(cos θi cos θo): no limit on the horizon (the term diverges like 1/cos θ): 0 there
    ok = g.above & g.h_valid & (cc > SGD_MIN_COS_PRODUCT)
    grey = (c, u5, tan2, c2, _theta(g.sin2_i, g.cos_i), _theta(g.sin2_o, g.cos_o), cc, ok)
    return rgb(g.above, grey, tuple(t[f] for f in _SGD_PARAMS), _sgd_channel)


_SGD_PARAMS = ("f0", "f1", "rho_s", "rho_d", "alpha", "p", "kappa", "lambda", "c_g", "k",
               "theta0")


def _sgd_channel(c, u5, tan2, c2, ti, to, cc, ok,
                 f0, f1, rho_s, rho_d, alpha, p, kappa, lam, c_g, k, theta0):
    fres = f0 - c * f1 + u5 * (1.0 - f0)
    d = _sgd_ndf(tan2, c2, alpha, p, kappa)
    g1 = _sgd_g1(ti, lam, c_g, k, theta0) * _sgd_g1(to, lam, c_g, k, theta0)
    spec = safe_div(rho_s * fres * d * g1, cc, ok)
    # F < 0 for a few materials: keep the fitted value where the total is ≥ 0, clamp below
    return np.maximum((rho_d + spec) / np.pi, 0.0)


ABC = Model(
    "abc", "ABC fit of a MERL material", (MATERIAL,), abc, rgb=True,
    summary="Löw et al. 2012: kd/π + F·A/(1+B(1−cosθh))^C·G/(π cosθi cosθo), per-material fit",
    horizon="limit where one of θi, θo is 90°; specular 0 where both are",
    notes=("numbers: dj_brdf.h (public domain), table djb::abc::s_data; docs/materials.md",),
)
SGD = Model(
    "sgd", "Shifted Gamma fit of a MERL material", (MATERIAL,), sgd, rgb=True,
    summary="Bagher et al. 2012: (ρd + ρs·F·D_SGD·G1·G1/(cosθi cosθo))/π, per-material fit",
    horizon="diffuse ρd/π; the specular term is 0 there (it diverges toward 90° where G1 > 0)",
    notes=("numbers: dj_brdf.h (public domain), table djb::sgd::s_data; docs/materials.md",
           "F < 0 for a few materials: f = max(0, ...) where the specular term outweighs ρd"),
)
