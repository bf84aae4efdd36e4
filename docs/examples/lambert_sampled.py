"""A Lambertian model with importance sampling, as a tuibrdf Python model file: the sampler
interface `tuibrdf check` tests with its χ² test (docs/reference/formats.md).

    f(wi, wo) = kd/π,   sampled ∝ cos θo:   pdf(wo) = cos θo / π

    tuibrdf check docs/examples/lambert_sampled.py        (finite, positivity, reciprocity,
                                                           energy and the χ² test)

Besides MODEL, the file defines two functions; both take the model's parameters as keyword
arguments (in kernel units, as the kernel does):

    sample(wi, u1, u2, **params) -> (wo, pdf)   wi (N, 3) toward the light, u1 and u2 (N,)
                                                uniform in [0, 1); wo (N, 3) unit vectors and
                                                their density per steradian (N,); a sample
                                                below the horizon or with pdf 0 is a failure
    pdf(wi, wo, **params) -> (N,)               the density of sample() at wo, per steradian
"""

import numpy as np

from tuibrdf.core.params import Model, Param

KD = Param("kd", "Kd", 0.8, 0.0, 1.0, 0.01, doc="diffuse reflectance")


def lambert(wi, wo, kd):
    up = (wi[..., 2] > 0.0) & (wo[..., 2] > 0.0)
    return np.where(up, kd / np.pi, 0.0)


def sample(wi, u1, u2, kd):
    # Malley's method: a uniform point of the unit disc lifted to the hemisphere
    r = np.sqrt(u1)
    phi = 2.0 * np.pi * u2
    wo = np.stack([r * np.cos(phi), r * np.sin(phi), np.sqrt(np.maximum(1.0 - u1, 0.0))],
                  axis=-1)
    return wo, pdf(wi, wo, kd)


def pdf(wi, wo, kd):
    return np.maximum(wo[..., 2], 0.0) / np.pi


MODEL = Model("lambert-sampled", "Lambert (cosine-sampled)", (KD,), lambert,
              summary="kd/π with cosine-weighted sampling", horizon="kd/π")
