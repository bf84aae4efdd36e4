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

import math
from functools import lru_cache

import numpy as np


def _clip01(c) -> np.ndarray:
    return np.minimum(np.maximum(np.asarray(c, dtype=float), 0.0), 1.0)


def pow5(u):
    """``u⁵`` as ``u²·u²·u``: three multiplications instead of ``pow`` (about 20× the time per
    element); within two ulps of the correctly rounded power."""
    u2 = u * u
    return u2 * u2 * u


@lru_cache(maxsize=64)
def _index_terms(f0: float) -> tuple[float, float]:
    """``(n², n² − 1)`` for 0 < f0 < 1, n = (1 + √f0)/(1 − √f0).

    n² − 1 = 4r/(1 − r)², written without the cancellation of n² − 1 (for f0 ≲ 1e-32, n²
    rounds to 1 and g would be 0 at grazing: 0/0); it is > 0 for f0 > 0, so g > 0 (no guard
    needed on the root) and c + g > 0, n² c + g > 0 below.  1 − r > 0 for f0 < 1 (no division
    by zero) and n² ≤ 2e33 (no overflow) for the largest double below 1.  1 − r is taken as
    (1 − f0)/(1 + r): 1 − f0 is exact (Sterbenz) where 1 − √f0 would lose the digits of a
    rounded root (a relative error of 2e-4 in n at f0 = 1 − 1e-12)."""
    r = math.sqrt(f0)
    one_minus_r = (1.0 - f0) / (1.0 + r)
    q = (1.0 + r) / one_minus_r
    return q * q, 4.0 * r / (one_minus_r * one_minus_r)


def fresnel_exact(cos_psi: np.ndarray, f0: float, clipped: bool = False) -> np.ndarray:
    """``clipped=True``: the caller promises ``cos_psi`` in [0, 1] (the models' cos θd is)."""
    c = cos_psi if clipped else _clip01(cos_psi)
    if f0 <= 0.0:
        return np.zeros_like(c)  # n = 1: no interface, no reflection (0/0 at grazing)
    if f0 >= 1.0:
        return np.ones_like(c)  # n = ∞: the index diverges; the limit is total reflection
    n2, n2m1 = _index_terms(f0)
    c2 = c * c
    g = np.sqrt(n2m1 + c2)
    # the differences c − g and n²c − g cancel as n → 1 (tiny f0: an error ~ 1/(4√f0) ulp);
    # with g² = n² − 1 + c² they are, exactly,
    #   c − g = −(n² − 1)/(c + g),   n²c − g = (n⁴c² − g²)/(n²c + g)
    #                                        = (n² − 1)((n² + 1)c² − 1)/(n²c + g)
    # (the factor (n² + 1)c² − 1 is rp's own zero at Brewster's angle, not a cancellation of
    # two approximations).  Denominators: c + g ≥ g > 0 and n²c + g > 0 (see _index_terms).
    cg = c + g
    rs = -n2m1 / (cg * cg)
    n2cg = n2 * c + g
    rp = n2m1 * ((n2 + 1.0) * c2 - 1.0) / (n2cg * n2cg)
    return 0.5 * (rs * rs + rp * rp)


def fresnel_schlick(cos_psi: np.ndarray, f0, clipped: bool = False) -> np.ndarray:
    """Schlick's approximation; ``f0`` may be a scalar or an RGB triple (broadcast last).
    ``clipped=True``: the caller promises ``cos_psi`` in [0, 1]."""
    c = cos_psi if clipped else _clip01(cos_psi)
    m = pow5(1.0 - c)
    if isinstance(f0, float | int):
        return f0 + (1.0 - f0) * m
    f0 = np.asarray(f0, dtype=float)
    if f0.ndim:
        m = np.asarray(m)[..., None]
    return f0 + (1.0 - f0) * m


def fresnel(cos_psi: np.ndarray, f0: float, kind: str, clipped: bool = False) -> np.ndarray:
    """Dispatch on the ``fresnel`` choice parameter (``exact`` | ``schlick``)."""
    if kind == "exact":
        return fresnel_exact(cos_psi, f0, clipped)
    return fresnel_schlick(cos_psi, f0, clipped)
