"""Minnaert's BRDF (Minnaert 1941, "The reciprocity principle in lunar photometry"), as a
tuibrdf Python model file.

    f(wi, wo) = albedo/π · (cos θi · cos θo)^(k − 1)

k = 1 is Lambert; k < 1 brightens toward grazing angles (the Moon's limb), k > 1 darkens
them.  The directional albedo at normal incidence is 2·albedo/(k + 1).

Open it as any model:  tuibrdf view docs/examples/minnaert.py -p k=0.7
                       tuibrdf eval docs/examples/minnaert.py --theta-i 30 --theta-r 60 --phi-r 0
                       tuibrdf.evaluate("docs/examples/minnaert.py", {"k": 0.7}, wi, wo)

The declaration is the one the built-in models use (tuibrdf/core/params.py): each parameter
once, with its range, step and documentation; the CLI's -p, the viewer's panel and validation
come from it.  The kernel receives unit directions wi (toward the light) and wo (toward the
viewer) of shape (..., 3) and the parameters as keyword arguments; it returns f in sr⁻¹
(no cosine factor), shape (...) — or (..., 3) for a model declared rgb=True.  It runs under
numpy's raising errstate: guard every division and power where the formula breaks.
"""

import numpy as np

from tuibrdf.core.params import Model, Param

ALBEDO = Param("albedo", "ρ", 0.8, 0.0, 1.0, 0.01, doc="reflectance scale (albedo at k = 1)")
K = Param("k", "k", 0.8, 0.5, 1.5, 0.01, doc="Minnaert exponent (1: Lambert)")


def minnaert(wi, wo, albedo, k):
    c = wi[..., 2] * wo[..., 2]
    up = c > 0.0
    # (cos θi cos θo)^(k − 1) divides by 0 on the horizon when k < 1: evaluate the power only
    # above it; on the horizon the value is 0 (the limit for k > 1, none for k < 1)
    p = np.power(np.where(up, c, 1.0), k - 1.0)
    return np.where(up, albedo / np.pi * p, 0.0)


MODEL = Model(
    "minnaert", "Minnaert", (ALBEDO, K), minnaert,
    summary="albedo/π (cos θi cos θo)^(k−1): lunar limb darkening (k < 1 brightens grazing)",
    horizon="0",
)
