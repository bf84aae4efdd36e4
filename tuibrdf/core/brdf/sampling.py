"""Importance sampling: the interface a model's sampler follows, and the built-in GGX's.

A sampler is an object with two methods, both taking the model's parameters as keywords in
kernel units (as the kernel does):

``sample(wi, u1, u2, **params) -> (wo, pdf)``
    ``wi (N, 3)`` unit directions toward the light, ``u1, u2 (N,)`` uniform numbers in
    [0, 1); returns the sampled ``wo (N, 3)`` (unit vectors; one below the horizon, or with
    ``pdf`` 0, is a sample the sampler failed to place) and its density ``pdf (N,)`` per unit
    solid angle.
``pdf(wi, wo, **params) -> (N,)``
    the density of ``sample`` at ``wo`` per unit solid angle.

The χ² test (:mod:`tuibrdf.core.sphere.chi2`) checks that the two agree.  A ``.py`` model file
provides one by defining module-level functions ``sample`` and ``pdf``
(docs/reference/formats.md).

:data:`GGX_VNDF` samples the built-in ``ggx``: the distribution of visible normals (Heitz 2018,
"Sampling the GGX distribution of visible normals", JCGT 7(4)) reflected about the normal
found, mixed with cosine-weighted sampling of the diffuse term when ``kd > 0``.  Its density
is ``G1(wi) D(h) / (4 cos θi)`` (the visible-normal density ``G1(wi) max(0, wi·h) D(h) / cos θi``
times the reflection's Jacobian ``1 / (4 wi·h)``).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from tuibrdf.core.brdf.microfacet import ggx_d, ggx_lambda_cos
from tuibrdf.core.numerics import safe_div

#: Share of the samples given to the diffuse term when ``kd > 0``.
DIFFUSE_SHARE = 0.5


class Sampler(NamedTuple):
    """A model's ``sample(wi, u1, u2, **params) -> (wo, pdf)`` and ``pdf(wi, wo, **params)``."""

    sample: object
    pdf: object


def _normalize(v: np.ndarray) -> np.ndarray:
    n = np.sqrt(np.sum(v * v, axis=-1, keepdims=True))
    return safe_div(v, n, n > 0.0)  # a zero vector stays zero (no direction: pdf 0 below)


def cosine_sample(u1: np.ndarray, u2: np.ndarray) -> np.ndarray:
    """Cosine-weighted directions (Malley's method: the unit disc lifted to the hemisphere)."""
    r = np.sqrt(u1)
    phi = 2.0 * np.pi * u2
    z = np.sqrt(np.maximum(1.0 - u1, 0.0))
    return np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=-1)


def ggx_vndf_sample(wi: np.ndarray, u1: np.ndarray, u2: np.ndarray, alpha: float) -> np.ndarray:
    """Visible normals of GGX seen from ``wi`` (Heitz 2018, listing 1, isotropic α)."""
    vh = _normalize(wi * np.array([alpha, alpha, 1.0]))
    lensq = vh[..., 0] ** 2 + vh[..., 1] ** 2
    inv = safe_div(1.0, np.sqrt(lensq), lensq > 0.0)
    t1v = np.where((lensq > 0.0)[..., None],
                   np.stack([-vh[..., 1] * inv, vh[..., 0] * inv, np.zeros_like(inv)], axis=-1),
                   np.array([1.0, 0.0, 0.0]))
    t2v = np.cross(vh, t1v)
    r = np.sqrt(u1)
    phi = 2.0 * np.pi * u2
    t1 = r * np.cos(phi)
    t2 = r * np.sin(phi)
    s = 0.5 * (1.0 + vh[..., 2])
    t2 = (1.0 - s) * np.sqrt(np.maximum(1.0 - t1 * t1, 0.0)) + s * t2
    nh = (t1[..., None] * t1v + t2[..., None] * t2v
          + np.sqrt(np.maximum(1.0 - t1 * t1 - t2 * t2, 0.0))[..., None] * vh)
    return _normalize(np.stack([alpha * nh[..., 0], alpha * nh[..., 1],
                                np.maximum(nh[..., 2], 0.0)], axis=-1))


def _ggx_spec_pdf(wi: np.ndarray, wo: np.ndarray, alpha: float) -> np.ndarray:
    """``G1(wi) D(h) / (4 cos θi)`` with ``h = (wi + wo)/|wi + wo|``; 0 where ``h`` is below
    the horizon or undefined, or ``wi`` is on or below it."""
    h = _normalize(wi + wo)
    ci = wi[..., 2]
    sin2_i = wi[..., 0] ** 2 + wi[..., 1] ** 2
    cos2_h = h[..., 2] ** 2
    sin2_h = h[..., 0] ** 2 + h[..., 1] ** 2
    d = ggx_d(cos2_h, sin2_h, alpha)
    # G1(wi)/(4 cos θi) = 1/(4 (cos θi + cos θi Λ(wi))): finite for cos θi > 0
    den = 4.0 * (ci + ggx_lambda_cos(np.maximum(ci, 0.0), sin2_i, alpha))
    ok = (h[..., 2] > 0.0) & (ci > 0.0) & (den > 0.0)
    return np.where(ok, d * safe_div(1.0, den, ok), 0.0)


def ggx_sample(wi, u1, u2, kd: float, f0: float, alpha: float, fresnel: str):
    """Samples of the built-in ``ggx`` (see the module docstring): ``(wo, pdf)``."""
    wi = np.asarray(wi, dtype=float)
    u1 = np.asarray(u1, dtype=float)
    u2 = np.asarray(u2, dtype=float)
    share = DIFFUSE_SHARE if kd > 0.0 else 0.0
    diffuse = u1 < share
    # reuse u1 for the lobe chosen: rescaled to [0, 1) within its share
    u_spec = safe_div(u1 - share, 1.0 - share, np.ones_like(u1, bool)) if share else u1
    u_diff = safe_div(u1, share, np.ones_like(u1, bool)) if share else u1
    h = ggx_vndf_sample(wi, np.clip(u_spec, 0.0, 1.0), u2, alpha)
    spec_wo = 2.0 * np.sum(wi * h, axis=-1, keepdims=True) * h - wi
    wo = np.where(diffuse[..., None], cosine_sample(np.clip(u_diff, 0.0, 1.0), u2), spec_wo)
    wo = _normalize(wo)
    return wo, ggx_pdf(wi, wo, kd, f0, alpha, fresnel)


def ggx_pdf(wi, wo, kd: float, f0: float, alpha: float, fresnel: str):
    """Density of :func:`ggx_sample` at ``wo`` per unit solid angle."""
    wi = np.asarray(wi, dtype=float)
    wo = np.asarray(wo, dtype=float)
    share = DIFFUSE_SHARE if kd > 0.0 else 0.0
    spec = _ggx_spec_pdf(wi, wo, alpha)
    if not share:
        return spec
    return (1.0 - share) * spec + share * np.maximum(wo[..., 2], 0.0) / np.pi


#: The built-in ``ggx``'s sampler.
GGX_VNDF = Sampler(ggx_sample, ggx_pdf)
