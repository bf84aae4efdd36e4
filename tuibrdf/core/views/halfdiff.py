"""Any model in Rusinkiewicz's half/difference angles (θh, θd, φd): the coordinates MERL data
is tabulated in, and the views BRDF Explorer draws from them.

``(θh, θd, φd) → (wi, wo)`` is :func:`tuibrdf.core.formats.merl.from_half_diff` (φh = 0: isotropic
models do not depend on it); its inverse is :func:`tuibrdf.core.formats.merl.half_diff`.  θh is the
half vector's angle from the normal, θd the angle between the half vector and each of ``wi``,
``wo``; φd the difference vector's azimuth about the half vector.  A combination can put
``wi`` or ``wo`` below the horizon (large θh + θd): such samples are *invalid* (value 0 and
mask False), drawn as background.  Samples exactly on the horizon are invalid too: there the
models return their documented conventions (a guarded 1/cos θ can be 1e13), not a value to plot.

Scale: near the horizon a microfacet model's 1/(cos θi cos θo) grows without bound (Cook-
Torrance at θh = 5°, θd = 89.9°: 1e32 sr⁻¹), so a plot scaled to its largest value shows
nothing else.  :func:`scale_max` is the largest value over samples with both directions at
most :data:`SCALE_LIMIT_DEG` from the normal; the views clip above it and say so.

Views:

- :func:`slice_image`: ``f`` on a θh × θd grid at fixed φd (BRDF Explorer's "image slice");
  with ``sqrt_h`` the θh axis is uniform in √θh as MERL's bins are (θh = 90°·u², u uniform),
  which spreads the specular peak near θh = 0 over many columns;
- :func:`theta_h_curve`: ``f(θh)`` at fixed θd, φd; :func:`theta_d_curve`: ``f(θd)`` at fixed
  θh, φd (BRDF Explorer's θh and θd plots).

Angles in and out are in degrees.
"""

from __future__ import annotations

import numpy as np

from tuibrdf.core.display import DISPLAY
from tuibrdf.core.evaluate import evaluate_resolved
from tuibrdf.core.formats.merl import from_half_diff
from tuibrdf.core.params import Model

#: the fixed φd of the views by default: 90°, BRDF Explorer's image-slice default
#: (:data:`~tuibrdf.core.display.DISPLAY`)
DEFAULT_PHI_D = DISPLAY.phi_d.default
#: cosines at or below this count as on the horizon
HORIZON_EPS = 1e-12
#: directions farther than this from the normal do not set the views' scale
SCALE_LIMIT_DEG = 85.0


def theta_h_axis(n: int, sqrt_h: bool = True) -> np.ndarray:
    """``n`` θh sample positions (degrees, cell centres) over [0°, 90°]: uniform, or uniform in
    √θh (θh = 90°·u², u the cell centre in [0, 1])."""
    if n < 1:
        raise ValueError(f"need at least one sample, got {n}")
    u = (np.arange(n) + 0.5) / n
    return 90.0 * u * u if sqrt_h else 90.0 * u


def theta_d_axis(n: int) -> np.ndarray:
    """``n`` θd sample positions (degrees, cell centres) over [0°, 90°]."""
    if n < 1:
        raise ValueError(f"need at least one sample, got {n}")
    return 90.0 * (np.arange(n) + 0.5) / n


def directions(theta_h_deg, theta_d_deg, phi_d_deg) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(wi, wo, valid)`` for half/difference angles in degrees (broadcast together); ``valid``
    where both directions are strictly above the horizon."""
    wi, wo = from_half_diff(np.radians(theta_h_deg), np.radians(theta_d_deg),
                            np.radians(phi_d_deg))
    # 1e-12, not 0: an angle of exactly 90° in radians leaves cos = 6e-17 (on the horizon)
    valid = (wi[..., 2] > HORIZON_EPS) & (wo[..., 2] > HORIZON_EPS)
    return wi, wo, valid


def scale_max(f: np.ndarray, theta_h_deg, theta_d_deg, phi_d_deg,
              limit_deg: float = SCALE_LIMIT_DEG) -> float:
    """The largest value of ``f`` (computed at the given angles; any channel) over the samples
    whose ``wi`` and ``wo`` are both within ``limit_deg`` of the normal; 0 if there are none."""
    wi, wo, _ = directions(theta_h_deg, theta_d_deg, phi_d_deg)
    c = np.cos(np.radians(limit_deg))
    inner = (wi[..., 2] >= c) & (wo[..., 2] >= c)
    v = np.asarray(f, dtype=float)
    if v.ndim == inner.ndim + 1:
        v = v.max(axis=-1)
    v = np.broadcast_to(v, inner.shape)[inner]
    return float(v.max()) if v.size else 0.0


def values_at(model: Model, values: dict, theta_h_deg, theta_d_deg,
              phi_d_deg) -> tuple[np.ndarray, np.ndarray]:
    """``(f, valid)``: the model at the angles (shape of the broadcast angles, ``(..., 3)``
    for RGB models); 0 where invalid."""
    wi, wo, valid = directions(theta_h_deg, theta_d_deg, phi_d_deg)
    up = np.array([0.0, 0.0, 1.0])
    # invalid samples are evaluated at (N, N), a valid pair, and then zeroed
    wi = np.where(valid[..., None], wi, up)
    wo = np.where(valid[..., None], wo, up)
    f = np.asarray(evaluate_resolved(model, values, wi, wo), dtype=float)
    mask = valid[..., None] if f.ndim == valid.ndim + 1 else valid
    return np.where(mask, f, 0.0), valid


def slice_image(model: Model, values: dict, phi_d_deg: float = DEFAULT_PHI_D, *,
                n_h: int = 90, n_d: int = 90, sqrt_h: bool = True):
    """``(f, valid, θh, θd)``: ``f`` of shape ``(n_d, n_h)`` (or ``(n_d, n_h, 3)``), row ``k``
    at ``θd[k]`` (increasing), column ``j`` at ``θh[j]``."""
    th = theta_h_axis(n_h, sqrt_h)
    td = theta_d_axis(n_d)
    f, valid = values_at(model, values, th[None, :], td[:, None], float(phi_d_deg))
    return f, valid, th, td


def theta_h_curve(model: Model, values: dict, theta_d_deg: float,
                  phi_d_deg: float = DEFAULT_PHI_D, *, n: int = 181):
    """``(θh, f, valid)``: ``f`` against θh ∈ [0°, 90°] (``n`` points, ends included) at fixed
    θd and φd."""
    th = np.linspace(0.0, 90.0, n)
    f, valid = values_at(model, values, th, float(theta_d_deg), float(phi_d_deg))
    return th, f, valid


def theta_d_curve(model: Model, values: dict, theta_h_deg: float,
                  phi_d_deg: float = DEFAULT_PHI_D, *, n: int = 181):
    """``(θd, f, valid)``: ``f`` against θd ∈ [0°, 90°] at fixed θh and φd."""
    td = np.linspace(0.0, 90.0, n)
    f, valid = values_at(model, values, float(theta_h_deg), td, float(phi_d_deg))
    return td, f, valid
