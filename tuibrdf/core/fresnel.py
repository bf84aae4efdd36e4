"""Fresnel reflectance of a dielectric interface, exact and Schlick.

``cos_psi`` is the cosine of the angle between the microfacet normal H and the light (= the
viewer, for a specular facet), clipped to [0, 1].

Exact (unpolarised light, real index; Cook & Torrance 1981, the seed's formula)::

    g² = n² − sin²ψ = n² − 1 + cos²ψ
    rs = (cosψ − g) / (cosψ + g)          rp = (n² cosψ − g) / (n² cosψ + g)
    F  = (rs² + rp²) / 2

with the index recovered from the normal-incidence reflectance, ``n = (1 + √f0)/(1 − √f0)``.

Schlick (1994)::  F = f0 + (1 − f0)(1 − cosψ)⁵

Ends of the range: ``f0 = 0`` means n = 1, no interface: F ≡ 0 (the exact formula is 0/0 at
grazing there).  ``f0 = 1`` means n → ∞, a perfect mirror: F ≡ 1.  For 0 < f0 < 1, F(ψ = 90°) = 1.
"""

from __future__ import annotations

import numpy as np

from .numerics import safe_sqrt


def index_from_f0(f0: float) -> float:
    """Real refractive index with normal-incidence reflectance ``f0`` (0 ≤ f0 < 1)."""
    r = np.sqrt(f0)
    return float((1.0 + r) / (1.0 - r))


def fresnel_exact(cos_psi: np.ndarray, f0: float) -> np.ndarray:
    c = np.clip(np.asarray(cos_psi, dtype=float), 0.0, 1.0)
    if f0 <= 0.0:
        return np.zeros_like(c)  # n = 1: no interface, no reflection (0/0 at grazing)
    if f0 >= 1.0:
        return np.ones_like(c)  # n = ∞: the index diverges; the limit is total reflection
    r = np.sqrt(f0)
    n2 = ((1.0 + r) / (1.0 - r)) ** 2
    # n² − 1 = 4r/(1 − r)², written without the cancellation of n² − 1 (for f0 ≲ 1e-32, n²
    # rounds to 1 and g would be 0 at grazing: 0/0); g > 0 for f0 > 0, so c + g > 0 below
    g = safe_sqrt(4.0 * r / (1.0 - r) ** 2 + c * c)
    rs = (c - g) / (c + g)
    rp = (n2 * c - g) / (n2 * c + g)
    return 0.5 * (rs * rs + rp * rp)


def fresnel_schlick(cos_psi: np.ndarray, f0) -> np.ndarray:
    """Schlick's approximation; ``f0`` may be a scalar or an RGB triple (broadcast last)."""
    c = np.clip(np.asarray(cos_psi, dtype=float), 0.0, 1.0)
    f0 = np.asarray(f0, dtype=float)
    m = (1.0 - c) ** 5
    if f0.ndim:
        m = m[..., None]
    return f0 + (1.0 - f0) * m


def fresnel(cos_psi: np.ndarray, f0: float, kind: str) -> np.ndarray:
    """Dispatch on the ``fresnel`` choice parameter (``exact`` | ``schlick``)."""
    return fresnel_exact(cos_psi, f0) if kind == "exact" else fresnel_schlick(cos_psi, f0)
