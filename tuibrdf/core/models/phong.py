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

from ..frame import half_vector
from ..params import Model, Param, sum_at_most_one
from . import common_params
from .diffuse import above

KD = replace(common_params.KD, default=0.2)
KS = Param("ks", "Ks", 0.5, 0.0, 1.0, 0.01, doc="specular reflectance")
N = Param("n", "n", 20.0, 0.0, 10000.0, 1.0, coarse=10.0, relative=True,
          doc="lobe exponent: larger is higher and narrower")


def lobe_power(c: np.ndarray, n: float) -> np.ndarray:
    """``max(0, c)^n`` with ``0^0 = 0`` outside the lobe: for n = 0 the lobe is the half-space
    ``c > 0``, not the whole sphere (numpy's ``0.0 ** 0 == 1``)."""
    c = np.asarray(c, dtype=float)
    out = np.zeros_like(c)
    np.power(c, n, out=out, where=c > 0.0)  # c ≤ 0: outside the lobe; n huge underflows to 0
    return out


def phong(wi: np.ndarray, wo: np.ndarray, kd: float, ks: float, n: float) -> np.ndarray:
    # S·wo with S = (-wi_x, -wi_y, wi_z)
    s_dot_wo = -wi[..., 0] * wo[..., 0] - wi[..., 1] * wo[..., 1] + wi[..., 2] * wo[..., 2]
    f = kd / np.pi + ks * (n + 2.0) / (2.0 * np.pi) * lobe_power(s_dot_wo, n)
    return np.where(above(wi, wo), f, 0.0)


def blinn_phong(wi: np.ndarray, wo: np.ndarray, kd: float, ks: float, n: float) -> np.ndarray:
    h, valid = half_vector(wi, wo)
    # H undefined (wi = -wo on the horizon): treated as outside the lobe
    n_dot_h = np.where(valid, h[..., 2], 0.0)
    f = kd / np.pi + ks * (n + 8.0) / (8.0 * np.pi) * lobe_power(n_dot_h, n)
    return np.where(above(wi, wo), f, 0.0)


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
