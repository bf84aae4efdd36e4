"""The local shading frame and direction helpers (SPEC §1).

Normal ``N = (0, 0, 1)``; directions point *away* from the surface: ``wi`` toward the light,
``wo`` toward the viewer.  ``dir(θ, φ) = (sin θ cos φ, sin θ sin φ, cos θ)``; the viewer puts
the light at ``φi = 180°`` so the mirror direction ``S`` sits at ``φ = 0``.
"""

from __future__ import annotations

import math

import numpy as np

from tuibrdf.core.numerics import safe_div, safe_sqrt


def from_degrees(theta_deg, phi_deg) -> np.ndarray:
    """Unit direction(s) ``(sin θ cos φ, sin θ sin φ, cos θ)`` from polar angle ``theta_deg``
    and azimuth ``phi_deg`` in degrees (the user-facing unit).

    Multiples of 90° give exact components, so ``θ = 90°`` lies exactly on the horizon
    (``np.cos(np.pi / 2)`` is 6e-17, not 0).
    """
    st, ct = sincos_deg(theta_deg)
    sp, cp = sincos_deg(phi_deg)
    return np.stack(np.broadcast_arrays(st * cp, st * sp, ct), axis=-1)


_EXACT_SIN = (0.0, 1.0, 0.0, -1.0)  # at 0°, 90°, 180°, 270°
_EXACT_COS = (1.0, 0.0, -1.0, 0.0)


def sincos_deg(t) -> tuple[np.ndarray, np.ndarray]:
    """``(sin t, cos t)`` for ``t`` in degrees, exact at multiples of 90°."""
    if type(t) is float and math.isfinite(t):  # one angle (θi, φi): the same numbers without
        quarter = (t % 360.0) / 90.0  # a dozen numpy calls on 0-d arrays (≈ 20 µs each frame)
        k = round(quarter)  # half to even, as np.round
        if quarter == k:
            return np.float64(_EXACT_SIN[k % 4]), np.float64(_EXACT_COS[k % 4])
        r = np.radians(t)
        return np.sin(r), np.cos(r)
    t = np.asarray(t, dtype=float)
    r = np.radians(t)
    s, c = np.sin(r), np.cos(r)
    quarter = np.remainder(t, 360.0) / 90.0
    exact = quarter == np.round(quarter)
    k = np.round(quarter).astype(int) % 4
    s = np.where(exact, np.array(_EXACT_SIN)[k], s)
    c = np.where(exact, np.array(_EXACT_COS)[k], c)
    return s, c


def check_theta_i(theta_i_deg: float) -> float:
    """``θi`` as a float when it is in [0°, 90°], else ``ValueError``: the one range check of
    the light's polar angle, which every entry point taking it makes (the frame request, the
    albedo); :func:`check_phi_i` is its azimuth's."""
    t = float(theta_i_deg)
    if not 0.0 <= t <= 90.0:  # also refuses NaN
        raise ValueError(f"theta_i = {theta_i_deg!r} is invalid: expected in [0, 90]°")
    return t


def check_phi_i(phi_i_deg: float) -> float:
    """``φi`` as a float when it is finite, else ``ValueError`` (any finite angle is one)."""
    p = float(phi_i_deg)
    if not math.isfinite(p):
        raise ValueError(f"phi_i = {phi_i_deg!r} is invalid: expected a finite angle in °")
    return p


def incident(theta_i_deg: float, phi_i_deg: float = 180.0) -> np.ndarray:
    """The light direction ``wi`` at ``θi``, ``φi`` in degrees (the viewer's default
    ``φi = 180°``: the light on the −x side): the one place (θi, φi) becomes ``wi``.  A frame
    makes it once (:attr:`tuibrdf.core.views.frame.FrameRequest.wi`) and every pane's numbers
    take that ``wi``.  The angles are not checked here (:func:`check_theta_i` and
    :func:`check_phi_i` are).

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


def xyz(w) -> tuple:
    """The components ``(x, y, z)`` of direction(s) ``w``: three float64 scalars for a single
    direction of shape ``(3,)`` (a kernel's terms of that direction then cost scalar
    operations, which obey the errstate policy as arrays do), three views of shape ``(...)``
    otherwise.  Working on components avoids the ``(..., 3)`` temporaries and the slow
    reductions over a last axis of length 3."""
    w = np.asarray(w, dtype=float)
    if w.ndim == 1:
        return w[0], w[1], w[2]
    return w[..., 0], w[..., 1], w[..., 2]


def above(zi, zo):
    """Both directions in the closed upper hemisphere, from their z components (a scalar z of a
    single direction decides without an array operation)."""
    if not np.ndim(zi):
        return zo >= 0.0 if zi >= 0.0 else np.zeros(np.shape(zo), dtype=bool)
    if not np.ndim(zo):
        return zi >= 0.0 if zo >= 0.0 else np.zeros(np.shape(zi), dtype=bool)
    return (zi >= 0.0) & (zo >= 0.0)


def cos_dphi(wi: np.ndarray, wo: np.ndarray) -> np.ndarray:
    """``cos(φo - φi)``; 0 where either direction is the normal (Δφ undefined there, SPEC §2)."""
    xi, yi, _ = xyz(wi)
    xo, yo, _ = xyz(wo)
    return _cos_dphi(xi, yi, xo, yo, xi * xi + yi * yi, xo * xo + yo * yo)


def _cos_dphi(xi, yi, xo, yo, sin2_i, sin2_o):
    num = xi * xo + yi * yo
    den = np.sqrt(sin2_i * sin2_o)  # a product of sums of squares: ≥ 0
    out = safe_div(num, den, den > 0.0)  # den = 0 only at the normal: Δφ undefined
    return np.minimum(np.maximum(out, -1.0), 1.0)  # rounding can leave [-1, 1] by an ulp


def theta_of(w: np.ndarray) -> np.ndarray:
    """Polar angle in radians, accurate everywhere (``atan2(sin, cos)`` rather than ``acos``)."""
    return np.arctan2(safe_sqrt(sin2_theta(w)), cos_theta(w))


def phi_of(w: np.ndarray) -> np.ndarray:
    """Azimuth in radians in (-π, π]."""
    w = np.asarray(w)
    return np.arctan2(w[..., 1], w[..., 0])


#: Up to this many directions :class:`Geometry` works on ``(..., 3)`` arrays, above on components
PACKED_MAX = 256


class Geometry:
    """The angular quantities every model needs, computed once per evaluation.

    Attributes (arrays broadcast over the leading axes of ``wi``/``wo``, or scalars where both
    are single directions): ``cos_i``, ``cos_o``, ``sin2_i``, ``sin2_o`` (computed when first
    read); ``h_valid`` (the half vector H is defined), ``cos_h``, ``sin2_h`` (of θh) and
    ``cos_d`` = H·wi = H·wo (cos ψ, cos θd; 0 where H is undefined, the limit as wo → −wi);
    ``above``: both directions in the closed upper hemisphere.  ``half=False`` computes only
    ``cos_d`` of the half-vector quantities.

    Everything is computed from the components (:func:`xyz`): a single ``wi`` costs scalar
    operations, and no ``(..., 3)`` array or last-axis reduction is made.
    """

    __slots__ = ("_xi", "_yi", "_xo", "_yo", "_sin2_i", "_sin2_o", "_invalid", "_h_valid",
                 "cos_i", "cos_o", "cos_h", "sin2_h", "cos_d", "above")

    def __init__(self, wi: np.ndarray, wo: np.ndarray, half: bool = True):
        xi, yi, zi = xyz(wi)
        xo, yo, zo = xyz(wo)
        self._xi, self._yi, self._xo, self._yo = xi, yi, xo, yo
        self._sin2_i = self._sin2_o = None
        self.cos_i, self.cos_o = zi, zo
        self.above = above(zi, zo)
        # |wi + wo|², summed in np.sum's order; two layouts, the same operations on the same
        # numbers: for a few points (…, 3) arrays (fewer numpy calls), for many the components
        # (numpy's inner loop over a last axis of 3 is several times slower per element)
        wi, wo = np.asarray(wi, dtype=float), np.asarray(wo, dtype=float)
        packed = max(wi.size, wo.size) <= PACKED_MAX * 3
        if packed:
            s = wi + wo
            q = s * s
            n2 = q[..., 0] + q[..., 1] + q[..., 2]
        else:
            sx, sy, sz = xi + xo, yi + yo, zi + zo
            n2 = sx * sx + sy * sy + sz * sz
        r = np.sqrt(n2)
        # H·wi = H·wo = |wi + wo|/2 for unit vectors: this form is symmetric in (wi, wo) to the
        # last bit (so every model using it stays reciprocal) and free of cancellation when wi
        # and wo are nearly opposite; 0 where H is undefined (wi = −wo)
        self.cos_d = np.minimum(0.5 * r, 1.0)
        if not half:
            return
        # |wi + wo| = 0 (n2 ≥ 0): H undefined, set to the normal.  There s = 0, so adding 1 to
        # the length (exactly: r + True) divides s by 1, not 0, and gives hx = hy = hz = 0
        # (sin²θh = 0), and cos θh = 0 + 1; elsewhere r + 0 and hz + 0 are r and hz exactly.
        # An addition costs less than a select.
        self._invalid = invalid = n2 == 0.0
        self._h_valid = None
        inv = 1.0 / (r + invalid)
        if packed:
            h = s * inv[..., None]
            q = h * h
            self.sin2_h = q[..., 0] + q[..., 1]
            self.cos_h = h[..., 2] + invalid
        else:
            hx, hy = sx * inv, sy * inv
            self.sin2_h = hx * hx + hy * hy
            self.cos_h = sz * inv + invalid

    @property
    def h_valid(self):
        """Where the half vector is defined (``wi + wo ≠ 0``)."""
        if self._h_valid is None:
            self._h_valid = ~self._invalid
        return self._h_valid

    @property
    def sin2_i(self):
        """``sin²θi = x² + y²`` (accurate near the normal, where ``1 − cos²`` cancels)."""
        if self._sin2_i is None:
            self._sin2_i = self._xi * self._xi + self._yi * self._yi
        return self._sin2_i

    @property
    def sin2_o(self):
        if self._sin2_o is None:
            self._sin2_o = self._xo * self._xo + self._yo * self._yo
        return self._sin2_o
