"""Microfacet distributions and shadowing-masking, composed by the specular models.

All functions take squared sines/cosines of polar angles measured from the normal: a sharp lobe
near the horizon needs ``sin²θ = x² + y²`` rather than ``1 − cos²θ`` (cancellation), and the
horizon (cos θ = 0, tan θ = ∞) needs explicit limits rather than ``tan²``.

Beckmann (Cook-Torrance's D)::

    D(h) = exp(−tan²θh / m²) / (π m² cos⁴θh)

GGX / Trowbridge-Reitz (Heitz 2014, eq. 71), and Smith's Λ for it (eq. 72)::

    D(h) = α² / (π (cos²θh (α² − 1) + 1)²) = α² / (π (α² cos²θh + sin²θh)²)
    Λ(w) = (−1 + √(1 + α² tan²θ)) / 2

Both D are normalised: ∫ D(h) cos θh dω = 1 (tested).  Height-correlated Smith
``G2 = 1/(1 + Λ(wi) + Λ(wo))`` (eq. 99).  V-cavity G (Cook & Torrance 1981)::

    G = max(0, min(1, 2 cosθh cosθi / cosψ, 2 cosθh cosθo / cosψ))
"""

from __future__ import annotations

import numpy as np

from tuibrdf.core.numerics import safe_div

#: A quotient at or above this counts as infinite.  Cosines a few hundred decades below 1 (a
#: direction given as (1, 0, 1e-310): a valid unit vector, on the horizon to the last bit)
#: make 1/cos overflow; guarding ``den > num / HUGE`` divides only where the quotient is finite
#: and below HUGE, so that products with D (≤ 1/(π·ALPHA_MIN²) ≈ 3e5) stay finite too.
HUGE = 1e300

#: Smallest distribution width; a roughness of 0 (a perfect mirror, a Dirac lobe that no
#: mesh or pixel can show) is clamped to this, as pbrt-v4 and Mitsuba 3 clamp theirs.
ALPHA_MIN = 1e-3


def alpha_from_roughness(roughness) -> float:
    """The glTF / UE4 / Disney mapping ``α = roughness²``, floored at :data:`ALPHA_MIN`."""
    return max(float(roughness) ** 2, ALPHA_MIN)


def beckmann_d(cos2_h: np.ndarray, sin2_h: np.ndarray, m: float) -> np.ndarray:
    """Beckmann D of a direction H given by ``cos²θh`` and ``sin²θh`` (summing to 1)."""
    m2 = m * m
    # tan²θh/m² = sin²/(m² cos²): on the horizon (cos = 0) and wherever it would reach HUGE
    # (cos²θh ~ 1e-320 from a subnormal z), the denominator is raised so the quotient is
    # HUGE: exp(-HUGE) = 0, D's limit (exp wins); the quotient is unchanged wherever it is
    # below HUGE.  sin² and cos² are not both 0 for a direction (no 0/0).
    x = sin2_h / np.maximum(m2 * cos2_h, sin2_h * (1.0 / HUGE))
    e = np.exp(-x)
    # exp(-x) underflows harmlessly to 0 for a sharp lobe.  Where it is > 0, x < 746, so
    # cos²θh > 1/(1 + 746 m²) ≥ 1.3e-3 (m ≤ 1) and cos⁴ is far from 0; where it is 0, cos⁴
    # may underflow to 0 and the floor 1e-300 (never reached where e > 0) gives 0/1e-300 = 0
    return e / np.maximum(np.pi * m2 * cos2_h * cos2_h, 1e-300)


def ggx_d(cos2_h: np.ndarray, sin2_h: np.ndarray, alpha: float) -> np.ndarray:
    a2 = alpha * alpha
    t = a2 * cos2_h + sin2_h  # ≥ min(α², 1)·(cos² + sin²) > 0: never zero for α > 0
    return a2 / (np.pi * t * t)


def ggx_lambda_cos(cos_t: np.ndarray, sin2_t: np.ndarray, alpha: float) -> np.ndarray:
    """``cos θ · Λ(θ)``, finite on the horizon (limit α·sinθ/2 as cos θ → 0).

    ``cos Λ = (√(cos² + α² sin²) − cos)/2``, written without cancellation as
    ``α² sin² / (2(cos + √(cos² + α² sin²)))``.  At the normal (sin = 0) it is exactly 0.
    """
    a2s2 = alpha * alpha * sin2_t
    root = np.sqrt(cos_t * cos_t + a2s2)  # sin² ≥ 0 (module contract): a sum of squares
    den = 2.0 * (cos_t + root)
    return safe_div(a2s2, den, den > 0.0)  # den = 0 only if sin = cos = 0: not a direction


def ggx_g2_over_cos(
    cos_i: np.ndarray, sin2_i: np.ndarray, cos_o: np.ndarray, sin2_o: np.ndarray, alpha: float
) -> np.ndarray:
    """Height-correlated ``G2 / (4 cos θi cos θo)``, with its limit on the horizon.

    ``(1 + Λi + Λo) ci co = ci co + co·(ci Λi) + ci·(co Λo)`` stays finite; where one direction
    is on the horizon the limit is finite (1 / (4·α sinθ/2·cos of the other)); where both are,
    the denominator is 0 and the value is 0 (no limit exists: documented).
    """
    den = cos_i * cos_o + cos_o * ggx_lambda_cos(cos_i, sin2_i, alpha) + cos_i * ggx_lambda_cos(
        cos_o, sin2_o, alpha
    )
    # den ≥ cos_other·α sinθ/2 with α ≥ 1e-3: below 0.25/HUGE only when both directions are on
    # the horizon to ~1e-297 (e.g. z = 1e-310 and z = 0): the "both on the horizon" case, 0;
    # dividing there would overflow
    return safe_div(0.25, den, den > 0.25 / HUGE)


def vcavity_g_over_cos(cos_h, cos_i, cos_o, cos_psi):
    """``G / (4 cos θi cos θo)`` with its limit on the horizon.

    ``G/(ci co) = min(1/(ci co), 2ch/(cψ co), 2ch/(cψ ci))``: where one cosine is 0 the other
    terms stay finite (the limit); where both are 0 every term is infinite and the value is 0.
    For H in the upper hemisphere (ch ≥ 0, as wherever both directions are) the smaller of
    the last two is ``2ch/(cψ·max(ci, co))``, one division instead of two (the same quotient
    to the last bit); elsewhere the value is finite and of no use (the models return 0 there).
    """
    ci_co = cos_i * cos_o
    # each quotient only where it is below HUGE; at or above it counts as HUGE, which min()
    # passes over: the horizon limit, now also for cosines like 1e-310 that overflow 1/x
    a = safe_div(1.0, ci_co, ci_co > 1.0 / HUGE, fill=HUGE)
    two_h = 2.0 * cos_h
    p = cos_psi * np.maximum(cos_i, cos_o)
    b = safe_div(two_h, p, p > np.abs(two_h) * (1.0 / HUGE), fill=HUGE)  # |·|: H may point down
    g = np.minimum(a, b)
    # both at HUGE: no limit, the value is 0 (a product with a 0/1 mask: HUGE·0 = 0)
    return 0.25 * g * (g < HUGE)
