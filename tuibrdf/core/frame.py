"""The local shading frame and direction helpers (SPEC §1).

Normal ``N = (0, 0, 1)``; directions point *away* from the surface: ``wi`` toward the light,
``wo`` toward the viewer.  ``dir(θ, φ) = (sin θ cos φ, sin θ sin φ, cos θ)``; the viewer puts
the light at ``φi = 180°`` so the mirror direction ``S`` sits at ``φ = 0``.
"""

from __future__ import annotations

import numpy as np

from .numerics import safe_sqrt


def from_angles(theta: np.ndarray, phi: np.ndarray) -> np.ndarray:
    """Unit direction(s) from polar angle ``theta`` and azimuth ``phi`` in radians."""
    theta = np.asarray(theta, dtype=float)
    phi = np.asarray(phi, dtype=float)
    s = np.sin(theta)
    return np.stack(np.broadcast_arrays(s * np.cos(phi), s * np.sin(phi), np.cos(theta)), axis=-1)


def from_degrees(theta_deg, phi_deg) -> np.ndarray:
    """:func:`from_angles` with angles in degrees (the user-facing unit).

    Multiples of 90° give exact components, so ``θ = 90°`` lies exactly on the horizon
    (``np.cos(np.pi / 2)`` is 6e-17, not 0).
    """
    st, ct = sincos_deg(theta_deg)
    sp, cp = sincos_deg(phi_deg)
    return np.stack(np.broadcast_arrays(st * cp, st * sp, ct), axis=-1)


def sincos_deg(t) -> tuple[np.ndarray, np.ndarray]:
    """``(sin t, cos t)`` for ``t`` in degrees, exact at multiples of 90°."""
    t = np.asarray(t, dtype=float)
    r = np.radians(t)
    s, c = np.sin(r), np.cos(r)
    quarter = np.remainder(t, 360.0) / 90.0
    exact = quarter == np.round(quarter)
    k = np.round(quarter).astype(int) % 4
    s = np.where(exact, np.array([0.0, 1.0, 0.0, -1.0])[k], s)
    c = np.where(exact, np.array([1.0, 0.0, -1.0, 0.0])[k], c)
    return s, c


def incident(theta_i_deg: float, phi_i_deg: float = 180.0) -> np.ndarray:
    """The light direction ``wi`` at ``θi``, ``φi`` in degrees (the viewer's default
    ``φi = 180°``: the light on the −x side): the one place (θi, φi) becomes ``wi``.

    Built from exact components so that ``θi = 90°`` lies exactly on the horizon (cos = 0),
    which ``np.cos(np.pi / 2) = 6e-17`` would not give, and φi = 180° gives ``(−sin θi, 0,
    cos θi)`` exactly.
    """
    s, c = sincos_deg(float(theta_i_deg))
    sp, cp = sincos_deg(float(phi_i_deg))
    return np.array([float(s) * float(cp), float(s) * float(sp), float(c)])


def mirror(w: np.ndarray) -> np.ndarray:
    """Mirror of ``w`` about the normal: ``(-x, -y, z)``."""
    w = np.asarray(w, dtype=float)
    return w * np.array([-1.0, -1.0, 1.0])


def cos_theta(w: np.ndarray) -> np.ndarray:
    return np.asarray(w)[..., 2]


def sin2_theta(w: np.ndarray) -> np.ndarray:
    """``sin²θ = x² + y²`` — accurate near the normal, where ``1 - cos²θ`` cancels."""
    w = np.asarray(w)
    return w[..., 0] ** 2 + w[..., 1] ** 2


def cos_dphi(wi: np.ndarray, wo: np.ndarray) -> np.ndarray:
    """``cos(φo - φi)``; 0 where either direction is the normal (Δφ undefined there, SPEC §2)."""
    num = wi[..., 0] * wo[..., 0] + wi[..., 1] * wo[..., 1]
    den = np.sqrt(sin2_theta(wi) * sin2_theta(wo))
    out = np.zeros(np.broadcast_shapes(num.shape, den.shape))
    np.divide(num, den, out=out, where=den > 0)  # den = 0 only at the normal: Δφ undefined
    return np.clip(out, -1.0, 1.0)


def half_vector(wi: np.ndarray, wo: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(H, valid)``: the normalised half vector and where it is defined.

    ``wi + wo = 0`` (light and viewer opposite on the horizon) has no half vector; there ``H``
    is set to the normal and ``valid`` is False so models can return their documented value.
    """
    s = np.asarray(wi, dtype=float) + np.asarray(wo, dtype=float)
    n2 = np.sum(s * s, axis=-1)
    valid = n2 > 0.0
    inv = np.zeros_like(n2)
    np.divide(1.0, np.sqrt(n2), out=inv, where=valid)  # |wi+wo| = 0: H undefined
    h = s * inv[..., None]
    h = np.where(valid[..., None], h, np.array([0.0, 0.0, 1.0]))
    return h, valid


def theta_of(w: np.ndarray) -> np.ndarray:
    """Polar angle in radians, accurate everywhere (``atan2(sin, cos)`` rather than ``acos``)."""
    return np.arctan2(safe_sqrt(sin2_theta(w)), cos_theta(w))


def phi_of(w: np.ndarray) -> np.ndarray:
    """Azimuth in radians in (-π, π]."""
    w = np.asarray(w)
    return np.arctan2(w[..., 1], w[..., 0])


class Geometry:
    """The angular quantities every model needs, computed once per evaluation.

    Attributes (arrays broadcast over the leading axes of ``wi``/``wo``): ``cos_i``, ``cos_o``,
    ``sin2_i``, ``sin2_o``; the half vector ``h`` and where it is defined (``h_valid``);
    ``cos_h``, ``sin2_h`` (of θh) and ``cos_d`` = H·wi = H·wo (cos ψ, cos θd; 0 where H is
    undefined, the limit as wo → −wi); ``above``: both directions in the closed upper hemisphere.
    """

    __slots__ = ("cos_i", "cos_o", "sin2_i", "sin2_o", "h", "h_valid", "cos_h", "sin2_h",
                 "cos_d", "above")

    def __init__(self, wi: np.ndarray, wo: np.ndarray):
        self.cos_i = cos_theta(wi)
        self.cos_o = cos_theta(wo)
        self.sin2_i = sin2_theta(wi)
        self.sin2_o = sin2_theta(wo)
        self.above = (self.cos_i >= 0.0) & (self.cos_o >= 0.0)
        self.h, self.h_valid = half_vector(wi, wo)
        self.cos_h = cos_theta(self.h)
        self.sin2_h = sin2_theta(self.h)
        # H·wi = H·wo = |wi + wo|/2 for unit vectors: this form is symmetric in (wi, wo) to the
        # last bit (so every model using it stays reciprocal) and free of cancellation when wi
        # and wo are nearly opposite; 0 where H is undefined (wi = −wo)
        s = np.asarray(wi, dtype=float) + np.asarray(wo, dtype=float)
        self.cos_d = np.minimum(0.5 * np.sqrt(np.sum(s * s, axis=-1)), 1.0)
