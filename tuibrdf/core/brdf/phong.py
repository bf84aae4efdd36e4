"""Phong-type lobes: modified Phong (Lewis 1993) and normalised Blinn-Phong.

Modified Phong (the seed's « Blinn-Phong modifié »; Phong 1975, Lewis 1993)::

    f = kd/π + ks (n+2)/(2π) max(0, S·wo)^n,      S = mirror of wi about N

The factor (n+2)/(2π) makes the lobe's albedo at normal incidence exactly ks, so kd + ks ≤ 1
conserves energy.  S·wo = S·wo' for swapped directions, so it is reciprocal.

Normalised Blinn-Phong (gKit2 light lesson)::

    f = kd/π + ks (n+8)/(8π) max(0, N·H)^n

====  ======  =======  ==========  ==========================
name  symbol  default  range       meaning
====  ======  =======  ==========  ==========================
kd    Kd      0.2      [0, 1]      diffuse reflectance
ks    Ks      0.5      [0, 1]      specular reflectance
n     n       20       [0, 10000]  lobe exponent (sharper →)
====  ======  =======  ==========  ==========================

Constraint: kd + ks ≤ 1.  Both are finite on the horizon (no division by a cosine).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from tuibrdf.core.brdf import common_params
from tuibrdf.core.directions import above, xyz
from tuibrdf.core.numerics import safe_div
from tuibrdf.core.params import Model, Param, sum_at_most_one

KD = replace(common_params.KD, default=0.2)
KS = Param("ks", "Ks", 0.5, 0.0, 1.0, 0.01, doc="specular reflectance")
N = Param("n", "n", 20.0, 0.0, 10000.0, 1.0, coarse=10.0, relative=True,
          doc="lobe exponent: larger is higher and narrower")


#: Integer exponents up to this are taken by repeated squaring (see :func:`lobe_power`)
INT_POWER_MAX = 64
#: ... and only for arrays of more than this many elements (for fewer, one ``pow`` call costs less
#: than the several products)
INT_POWER_MIN_SIZE = 256
#: The smallest normal double: below it a product keeps fewer than 53 bits
_TINY = float(np.finfo(float).tiny)


def lobe_power(c: np.ndarray, n: float) -> np.ndarray:
    """``max(0, c)^n`` with ``0^0 = 0`` outside the lobe: for n = 0 the lobe is the half-space
    ``c > 0``, not the whole sphere (numpy's ``0.0 ** 0 == 1``).

    An integer ``n ≤ INT_POWER_MAX`` is taken by repeated squaring, a few multiplications
    instead of ``pow`` (about 15 ns per element): each product adds at most half an ulp and an
    error in ``c^k`` is raised to at most the ``n/k``-th power, so the result is within
    ``n·2⁻⁵³ ≤ 7e-15`` relative of the correctly rounded power, as long as no product is
    subnormal; since the products of a base ≤ 1 decrease, that holds wherever the result is
    normal, and the few elements below the normal range are recomputed with ``pow``.
    """
    if n == 0.0:
        return np.where(c > 0.0, 1.0, 0.0)
    # c ≤ 0: outside the lobe, 0^n = 0 for n > 0 (n ≥ 0 is the parameter's range: no
    # division); a huge n underflows to 0
    c = np.maximum(c, 0.0)  # a new array (or a scalar): squared and overwritten below
    k = int(n)
    if k != n or k > INT_POWER_MAX or np.size(c) <= INT_POWER_MIN_SIZE:
        return np.power(c, n)  # a few elements: one call beats several
    out = None
    base = c
    while True:
        if k & 1:
            out = base if out is None else out * base
        k >>= 1
        if not k:
            break
        base = base * base
    np.power(c, n, out=out, where=out < _TINY)  # subnormal products lost bits: pow there
    return out


#: Above this exponent the lobe is taken as ``exp(n·log1p(−(1 − c)))`` from a 1 − c computed
#: without cancellation (see :func:`sharp_lobe`)
SHARP_N = INT_POWER_MAX


def sharp_lobe(c: np.ndarray, one_minus_c: np.ndarray, n: float) -> np.ndarray:
    """``max(0, c)^n`` for a large n, from ``1 − c`` given without cancellation.

    A rounded c near 1 carries an absolute error of an ulp, which ``c^n`` multiplies by n
    (2e-12 relative at n = 10⁴, where the lobe lives at 1 − c ~ 1/n); ``exp(n·log1p(−(1 −
    c)))`` with an accurate 1 − c keeps it at a few ulp times the exponent n(1 − c).  For
    c ≤ 1/2 the log of c itself is the better conditioned one (c is accurate relatively there,
    and c^n ≤ 2⁻⁶⁴ of the peak).  c ≤ 0: outside the lobe, 0 (the logs see 1 there)."""
    inside = c > 0.0
    near = one_minus_c < 0.5  # ⇒ log1p(−x) of x < 1/2: finite
    log_c = np.where(near, np.log1p(-np.where(near, one_minus_c, 0.0)),
                     np.log(np.where(inside, c, 1.0)))  # log of a positive number
    return np.where(inside, np.exp(n * log_c), 0.0)  # n·log c ≤ 0: no overflow


def phong(wi: np.ndarray, wo: np.ndarray, kd: float, ks: float, n: float) -> np.ndarray:
    xi, yi, zi = xyz(wi)
    xo, yo, zo = xyz(wo)
    s_dot_wo = -xi * xo - yi * yo + zi * zo  # S·wo with S = (-wi_x, -wi_y, wi_z)
    if n > SHARP_N:
        # 1 − S·wo = |S − wo|²/2 for unit vectors: no cancellation near the lobe's axis
        dx, dy, dz = xi + xo, yi + yo, zi - zo  # S − wo, negated in x, y (squared below)
        lobe = sharp_lobe(s_dot_wo, 0.5 * (dx * dx + dy * dy + dz * dz), n)
    else:
        lobe = lobe_power(s_dot_wo, n)
    f = kd / np.pi + ks * (n + 2.0) / (2.0 * np.pi) * lobe
    return np.where(above(zi, zo), f, 0.0)


def blinn_phong(wi: np.ndarray, wo: np.ndarray, kd: float, ks: float, n: float) -> np.ndarray:
    xi, yi, zi = xyz(wi)
    xo, yo, zo = xyz(wo)
    sx, sy, sz = xi + xo, yi + yo, zi + zo
    n2 = sx * sx + sy * sy + sz * sz
    valid = n2 > 0.0
    # N·H = sz/|wi + wo|; H undefined (wi = -wo on the horizon, or |wi + wo|² underflows to 0)
    # is treated as outside the lobe; 1/1 there instead of 1/0
    inv_len = 1.0 / np.where(valid, np.sqrt(n2), 1.0)
    n_dot_h = np.where(valid, sz * inv_len, 0.0)
    if n > SHARP_N:
        # 1 − N·H = (|h| − hz)/|h| = (hx² + hy²)/(|h| (|h| + hz)) with h = wi + wo: no
        # cancellation; |h| + hz > 0 where N·H > 0 (the only place it is read)
        h_len = np.where(valid, np.sqrt(n2), 1.0)
        one_minus = safe_div(sx * sx + sy * sy, h_len * (h_len + sz), n_dot_h > 0.0, fill=1.0)
        lobe = sharp_lobe(n_dot_h, one_minus, n)
    else:
        lobe = lobe_power(n_dot_h, n)
    f = kd / np.pi + ks * (n + 8.0) / (8.0 * np.pi) * lobe
    return np.where(above(zi, zo), f, 0.0)


PHONG = Model(
    "phong",
    "Modified Phong",
    (KD, KS, N),
    phong,
    constraints=(sum_at_most_one("kd", "ks"),),
    summary="kd/π + ks(n+2)/(2π)·max(0,S·wo)^n — Lewis 1993",
    horizon="the formula's value (no division by a cosine)",
)

BLINN_PHONG = Model(
    "blinn-phong",
    "Normalised Blinn-Phong",
    (KD, KS, N),
    blinn_phong,
    constraints=(sum_at_most_one("kd", "ks"),),
    summary="kd/π + ks(n+8)/(8π)·max(0,N·H)^n — gKit2",
    horizon="the formula's value; 0 lobe where wi = -wo (H undefined)",
)
