"""Reference quadrature for tests, independent of :mod:`tuibrdf.core.sphere.mesh`.

Gauss-Legendre in ``u = cos θ`` (or in a mapped polar angle) times the midpoint rule in φ: a
tensor rule whose accuracy is classical, so a test of a model's integral does not lean on the
icosahedral mesh that the quadrature tests check separately.
"""

from __future__ import annotations

import numpy as np

import tuibrdf
from tuibrdf.core.directions import incident


def gauss(a: float, b: float, n: int) -> tuple[np.ndarray, np.ndarray]:
    x, w = np.polynomial.legendre.leggauss(n)
    return 0.5 * (b - a) * x + 0.5 * (b + a), 0.5 * (b - a) * w


def hemisphere_rule(n_u: int = 96, n_phi: int = 192) -> tuple[np.ndarray, np.ndarray]:
    """Directions ``(n_u·n_phi, 3)`` and solid-angle weights over the upper hemisphere."""
    u, wu = gauss(0.0, 1.0, n_u)
    phi = (np.arange(n_phi) + 0.5) * (2 * np.pi / n_phi)
    s = np.sqrt(1.0 - u * u)
    d = np.stack(
        [np.outer(s, np.cos(phi)), np.outer(s, np.sin(phi)), np.outer(u, np.ones(n_phi))], -1
    )
    w = np.outer(wu, np.full(n_phi, 2 * np.pi / n_phi))
    return d.reshape(-1, 3), w.reshape(-1)


def albedo(model: str, params: dict, theta_i_deg: float, n_u: int = 96, n_phi: int = 192):
    """a(θi) = ∫ f(wi, wo) cos θo dωo with the tensor rule."""
    wo, w = hemisphere_rule(n_u, n_phi)
    f = tuibrdf.evaluate(model, params, incident(theta_i_deg), wo)
    weights = w * wo[:, 2]
    return np.tensordot(weights, f, axes=(0, 0))
