"""Diffuse models: Lambert.

Lambert (J.H. Lambert, *Photometria*, 1760)::

    f(wi, wo) = kd / π

====  ======  =======  ======  ==============================
name  symbol  default  range   meaning
====  ======  =======  ======  ==============================
kd    Kd      0.8      [0, 1]  diffuse reflectance (= albedo)
====  ======  =======  ======  ==============================
"""

from __future__ import annotations

import numpy as np

from ..params import Model, Param

KD = Param("kd", "Kd", 0.8, 0.0, 1.0, 0.01, doc="diffuse reflectance")


def above(wi: np.ndarray, wo: np.ndarray) -> np.ndarray:
    """Both directions in the closed upper hemisphere (the BRDF is 0 below the horizon)."""
    return (wi[..., 2] >= 0.0) & (wo[..., 2] >= 0.0)


def lambert(wi: np.ndarray, wo: np.ndarray, kd: float) -> np.ndarray:
    return np.where(above(wi, wo), kd / np.pi, 0.0)


LAMBERT = Model(
    "lambert",
    "Lambert",
    (KD,),
    lambert,
    summary="constant BRDF kd/π: an ideal matte surface",
    horizon="kd/π (no cosine in the formula)",
)
