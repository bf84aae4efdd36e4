"""Diffuse models: Lambert, Oren-Nayar (full and simplified), Disney diffuse.

**lambert** (J.H. Lambert, *Photometria*, 1760)::

    f = kd / π

**oren-nayar** — the qualitative model of Oren & Nayar (1994), as the seed writes it but with
the paper's C3 (the seed doc writes B there; the paper, Mitsuba 0.6 and BRDF Explorer use
σ²/(σ² + 0.09))::

    α = max(θi, θo), β = min(θi, θo), A = 1 − 0.5 σ²/(σ² + 0.33), B = 0.45 σ²/(σ² + 0.09)
    C1 = A
    C2 = B sin α                    if cos Δφ ≥ 0
         B (sin α − (2β/π)³)        otherwise
    C3 = 0.125 σ²/(σ² + 0.09) (4αβ/π²)²
    f  = kd/π (C1 + C2 cosΔφ tan β + C3 (1 − |cosΔφ|) tan((α + β)/2))
       + 0.17 kd²/π σ²/(σ² + 0.13) (1 − cosΔφ (2β/π)²)

σ (the slope standard deviation) is set in degrees and enters in radians.  At θ = 0, Δφ is
undefined: cos Δφ = 0.  For σ ≳ 1 rad the single-scattering term goes negative near grazing
back-scatter (C2 < 0 with cos Δφ < 0): the result is clamped to 0.

**oren-nayar-simple** — the approximation renderers use::

    f = kd/π (A + B max(0, cos Δφ) sin α tan β)

**disney-diffuse** (Burley 2012, "Physically-Based Shading at Disney")::

    f = base/π (1 + (FD90 − 1)(1 − cos θi)⁵)(1 + (FD90 − 1)(1 − cos θo)⁵)
    FD90 = 0.5 + 2 roughness cos²θd,  θd = angle(wi, H)

Horizon: Lambert and Disney are finite there.  Oren-Nayar's tan β and tan((α+β)/2) are finite
unless *both* directions are on the horizon, where no limit exists: the value there is 0.
All are reciprocal (every term is symmetric in θi, θo and in Δφ).

=========  ======  ===============  ==========  =====================================
name       symbol  default          range       meaning
=========  ======  ===============  ==========  =====================================
kd         Kd      0.8              [0, 1]      diffuse reflectance / facet albedo
sigma      σ       20°              [0°, 90°]   facet slope standard deviation
base_color base    (0.8, 0.8, 0.8)  [0, 1]³     (disney-diffuse) base colour
roughness  rough   0.5              [0, 1]      (disney-diffuse) retro-reflection
=========  ======  ===============  ==========  =====================================
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from tuibrdf.core.brdf.common_params import BASE, KD
from tuibrdf.core.brdf.common_params import ROUGHNESS as _ROUGHNESS
from tuibrdf.core.brdf.fresnel import pow5
from tuibrdf.core.brdf.rgb import rgb
from tuibrdf.core.directions import Geometry, _cos_dphi, xyz
from tuibrdf.core.directions import above as both_above
from tuibrdf.core.numerics import safe_div
from tuibrdf.core.params import Model, Param

SIGMA = Param("sigma", "σ", 20.0, 0.0, 90.0, 1.0, unit="deg",
              doc="facet slope standard deviation (roughness)")
ROUGHNESS = replace(_ROUGHNESS, doc="roughness: raises grazing retro-reflection")


def above(wi: np.ndarray, wo: np.ndarray) -> np.ndarray:
    """Both directions in the closed upper hemisphere (the BRDF is 0 below the horizon)."""
    return both_above(np.asarray(wi)[..., 2], np.asarray(wo)[..., 2])


def lambert(wi: np.ndarray, wo: np.ndarray, kd: float) -> np.ndarray:
    return np.where(above(wi, wo), kd / np.pi, 0.0)


def oren_nayar_ab(sigma: float) -> tuple[float, float]:
    """A and B of the Oren-Nayar model for σ in radians."""
    s2 = sigma * sigma
    return 1.0 - 0.5 * s2 / (s2 + 0.33), 0.45 * s2 / (s2 + 0.09)


class _AlphaBeta:
    """α = max(θi, θo), β = min(θi, θo), cos Δφ, tan β, tan((α+β)/2), sin α, and where they
    are finite.

    The tangents and sin α come from the vectors' components, not from ``tan`` of an ``atan2``
    angle: near the horizon θ = π/2 − ε is rounded to an absolute 2e-16, so ``tan θ ≈ 1/ε``
    would carry a relative error of 2e-16/ε (1e-7 at ε = 1e-9).  With s = sin θ and c = cos θ
    of each direction (normalised by its length, so they are exactly those of ``atan2(s, c)``):

        tan β = min(si/ci, so/co)                      (tan increases on [0, π/2])
        sin α = max(si, so)                            (sin increases on [0, π/2])
        tan((α+β)/2) = (sin α + sin β)/(cos α + cos β) = (si + so)/(ci + co)

    each symmetric in (wi, wo) to the last bit, so the model stays exactly reciprocal.  Each
    direction's terms are computed once (scalars for a single ``wi``).

    Near the horizon the full model's back-scatter C2 = B (sin α − (2β/π)³) cancels (both terms
    ≈ 1) and tan β ≈ 1/δ multiplies the cancellation back, so it is rewritten without either
    difference: with δ = π/2 − β (from the components, see :func:`_polar`) and u = 2δ/π,

        sin α − (1 − u)³ = −cos²α/(1 + sin α) + u (3 − 3u + u²)

    (``c2_back``; sin α − 1 = −cos²α/(1 + sin α) and 1 − (1 − u)³ = 3u − 3u² + u³).
    """

    def __init__(self, wi: np.ndarray, wo: np.ndarray):
        xi, yi, zi = xyz(wi)
        xo, yo, zo = xyz(wo)
        s2i, s2o = xi * xi + yi * yi, xo * xo + yo * yo
        ti, di, si, ci, tan_i = _polar(s2i, zi)
        to, do, so, co, tan_o = _polar(s2o, zo)
        self.alpha = np.maximum(ti, to)
        self.beta = np.minimum(ti, to)
        self.delta_beta = np.maximum(di, do)  # π/2 − β, from the components
        self.cos_alpha = np.minimum(ci, co)
        self.cos_dphi = _cos_dphi(xi, yi, xo, yo, s2i, s2o)
        self._parts = (xi, yi, xo, yo, s2i, s2o)
        # both on the horizon (β rounds to 90°): tan β and tan((α+β)/2) have no limit → value 0
        self.ok = both_above(zi, zo) & (self.beta < np.pi / 2)
        self.tan_beta = np.where(self.ok, np.minimum(tan_i, tan_o), 0.0)
        self.sin_alpha = np.maximum(si, so)
        # ci + co > 0 wherever ``ok`` holds (at least one direction is above the horizon)
        self.tan_mean = safe_div(si + so, ci + co, self.ok)


    def one_minus_abs_cos_dphi(self) -> np.ndarray:
        """1 − |cos Δφ| without its cancellation as Δφ → 0° or 180° (there tan((α+β)/2) ≈ 1/ε
        multiplies it near the horizon): sin²Δφ/(1 + |cos Δφ|) with sin Δφ from the cross
        product of the horizontal components, for |cos Δφ| > 1/2."""
        xi, yi, xo, yo, s2i, s2o = self._parts
        c = np.abs(self.cos_dphi)
        cross = xi * yo - yi * xo
        den = s2i * s2o * (1.0 + c)
        near = c > 0.5  # |Δφ| within 60° of 0° or 180°
        # den = 0 only at the normal (cos Δφ = 0 there, the other branch)
        sin2_over = safe_div(cross * cross, den, near & (den > 0.0))
        return np.where(near, sin2_over, 1.0 - c)


def _polar(sin2: np.ndarray, z: np.ndarray):
    """``(θ, π/2 − θ, sin θ, cos θ, tan θ)`` of a direction from ``x² + y²`` and ``z``: sin
    and cos divided by the length (≥ 0 for z ≥ 0).  θ and its complement come from one
    ``atan2`` of the smaller component over the larger (an angle t ≤ π/4), the other one as
    π/2 − t ≥ π/4: each is within an ulp or two of its own value, so the complement keeps its
    relative precision near the horizon (π/2 − θ from a rounded θ would be off by 2e-16
    absolute, 1e-7 relative at 1e-9 rad).  The length is ``√(s² + z²)`` with s = √(x² + y²)
    rather than ``hypot(s, z)`` (several times the time per element): the components of a
    direction are at most 1, so nothing overflows, an underflowing square is negligible beside
    the other, and ``√(s·s) = s`` exactly in binary64, so near the horizon (z² below half an ulp
    of s²) sin θ = s/s = 1 exactly, as with ``hypot``: the model is ill-conditioned there
    (C2 cancels), and an ulp of sin α would move it by 1e-8."""
    s = np.sqrt(sin2)  # a sum of squares: ≥ 0
    steep = s <= z  # θ ≤ π/4
    t = np.arctan2(np.minimum(s, z), np.maximum(s, z))  # (0, 0) → 0: θ = 0 (below: never read)
    theta = np.where(steep, t, np.pi / 2 - t)
    comp = np.where(steep, np.pi / 2 - t, t)
    # the length of a direction is never 0 (≥ 1e-162 if not 0: a square root of a double);
    # were it, s = z = 0 divided by the floor gives 0
    r = np.maximum(np.sqrt(s * s + z * z), 1e-300)
    sn, cn = s / r, z / r
    # θ < π/2 as a double means c/s ≳ 1e-16, so s/c ≤ ~1e16; θ rounded to π/2 (c = 0 or c
    # tiny): tan θ = ∞, never the smaller tangent where ``ok`` holds
    return theta, comp, sn, cn, safe_div(sn, cn, theta < np.pi / 2, fill=np.inf)


def oren_nayar(wi: np.ndarray, wo: np.ndarray, kd: float, sigma: float) -> np.ndarray:
    ab = _AlphaBeta(wi, wo)
    a, b = oren_nayar_ab(sigma)
    s2 = sigma * sigma
    cphi = ab.cos_dphi
    two_beta_pi = 2.0 * ab.beta / np.pi
    sin_alpha = ab.sin_alpha
    tb2 = two_beta_pi * two_beta_pi
    # C2 = B sin α if cos Δφ ≥ 0, B (sin α − (2β/π)³) otherwise, the latter without its
    # cancellation near the horizon (see _AlphaBeta); 1 + sin α ≥ 1
    u = 2.0 * ab.delta_beta / np.pi
    c2_back = -ab.cos_alpha * ab.cos_alpha / (1.0 + sin_alpha) + u * (3.0 - 3.0 * u + u * u)
    c2 = b * np.where(cphi >= 0.0, sin_alpha, c2_back)
    ab4 = 4.0 * ab.alpha * ab.beta / np.pi**2
    c3 = 0.125 * s2 / (s2 + 0.09) * (ab4 * ab4)
    side = ab.one_minus_abs_cos_dphi()  # 1 − |cos Δφ|
    single = kd / np.pi * (a + c2 * cphi * ab.tan_beta + c3 * side * ab.tan_mean)
    inter = 0.17 * kd * kd / np.pi * s2 / (s2 + 0.13) * (1.0 - cphi * tb2)
    # the qualitative model goes negative near grazing back-scatter for σ ≳ 1 rad: clamp
    return np.where(ab.ok, np.maximum(single + inter, 0.0), 0.0)


def oren_nayar_simple(wi: np.ndarray, wo: np.ndarray, kd: float, sigma: float) -> np.ndarray:
    ab = _AlphaBeta(wi, wo)
    a, b = oren_nayar_ab(sigma)
    f = kd / np.pi * (a + b * np.maximum(0.0, ab.cos_dphi) * ab.sin_alpha * ab.tan_beta)
    return np.where(ab.ok, f, 0.0)


def disney_diffuse(wi: np.ndarray, wo: np.ndarray, base_color, roughness: float) -> np.ndarray:
    g = Geometry(wi, wo, half=False)
    fd90m1 = 0.5 + 2.0 * roughness * (g.cos_d * g.cos_d) - 1.0
    # (1 − cos θ)⁵ with cos θ clipped to [0, 1] (below the horizon the value is replaced by 0)
    ci = np.minimum(np.maximum(g.cos_i, 0.0), 1.0)
    co = np.minimum(np.maximum(g.cos_o, 0.0), 1.0)
    shape = (1.0 + fd90m1 * pow5(1.0 - ci)) * (1.0 + fd90m1 * pow5(1.0 - co))
    return rgb(g.above, (shape,), (np.asarray(base_color, dtype=float),), _disney_channel)


def _disney_channel(shape, base):
    return base / np.pi * shape


LAMBERT = Model(
    "lambert", "Lambert", (KD,), lambert,
    summary="constant BRDF kd/π: an ideal matte surface",
    horizon="kd/π (no cosine in the formula)",
)
OREN_NAYAR = Model(
    "oren-nayar", "Oren-Nayar (full qualitative)", (KD, SIGMA), oren_nayar,
    summary="rough Lambertian facets, V-cavities, with interreflection (paper's C3)",
    horizon="the formula's value; 0 where both θi and θo are 90° (no limit)",
    notes=("C3 uses σ²/(σ²+0.09) as the 1994 paper (the seed doc writes B)",
           "clamped to 0 where the formula goes negative (σ ≳ 1 rad, grazing back-scatter)"),
)
OREN_NAYAR_SIMPLE = Model(
    "oren-nayar-simple", "Oren-Nayar (simplified)", (KD, SIGMA), oren_nayar_simple,
    summary="kd/π (A + B max(0, cosΔφ) sinα tanβ)",
    horizon="the formula's value; 0 where both θi and θo are 90° (no limit)",
)
DISNEY_DIFFUSE = Model(
    "disney-diffuse", "Disney diffuse", (BASE, ROUGHNESS), disney_diffuse, rgb=True,
    summary="Burley 2012 diffuse with grazing retro-reflection FD90",
    horizon="the formula's value (no division by a cosine)",
)
