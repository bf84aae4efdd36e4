"""Stand-ins used ONLY until the real pieces land (delete this module then).

* ``tuibrdf.render`` (helper render: hemimap, colormap, polar, solid, albedo_plot, views);
* ``tuibrdf.core.quadrature`` (helper mesh: directional albedo and peak).

Everything here is small and exact but slow-ish: an exact per-pixel equal-area map, a grey /
viridis / inferno ramp from a few control points, plotext polar curves, and a midpoint-rule
(θ, φ) grid for the albedo and the peak.  No Textual.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..core.evaluate import evaluate_resolved
from ..core.frame import incident
from ..core.params import Model

SQRT2 = float(np.sqrt(2.0))


# --------------------------------------------------------------------------- map values
def map_values(model: Model, values: dict[str, Any], theta_i_deg: float, px_w: int, px_h: int,
               *, cosine: bool = False) -> tuple[np.ndarray, dict]:
    """Exact BRDF on a ``px_h × px_w`` equal-area image, NaN outside the disc (centred, as big
    as the smaller side).  Shape ``(px_h, px_w)`` or ``(px_h, px_w, 3)`` for RGB models."""
    side = max(2, min(px_w, px_h))
    y, x = np.mgrid[0:px_h, 0:px_w].astype(float)
    u = (x + 0.5 - px_w / 2) / (side / 2) * SQRT2
    v = -(y + 0.5 - px_h / 2) / (side / 2) * SQRT2
    r2 = u * u + v * v
    inside = r2 <= 2.0
    # inverse Lambert azimuthal equal-area: z = 1 − r²/2, (x, y) = (u, v)·√(1 − r²/4)
    s = np.sqrt(np.clip(1.0 - r2[inside] / 4.0, 0.0, None))  # clip: r² ≤ 2 inside the disc
    wo = np.stack([u[inside] * s, v[inside] * s, np.clip(1.0 - r2[inside] / 2.0, 0.0, 1.0)], -1)
    wi = np.broadcast_to(incident(theta_i_deg), wo.shape)
    f = np.asarray(evaluate_resolved(model, values, wi, wo), dtype=float)
    if cosine:
        f = f * (wo[:, 2:3] if f.ndim == 2 else wo[:, 2])
    shape = (px_h, px_w, 3) if model.rgb else (px_h, px_w)
    out = np.full(shape, np.nan)
    out[inside] = f
    # mirror direction S at φ = 0, θr = θi: radius 2 sin(θi/2) on the u axis
    mu = 2 * np.sin(np.radians(theta_i_deg) / 2)
    info = {"side": side, "mirror_px": (px_w / 2 + mu / SQRT2 * side / 2, px_h / 2)}
    return out, info


# --------------------------------------------------------------------------- colour maps
_STOPS = {
    "grey": [(0, 0, 0), (255, 255, 255)],
    "viridis": [(68, 1, 84), (59, 82, 139), (33, 145, 140), (94, 201, 98), (253, 231, 37)],
    "inferno": [(0, 0, 4), (87, 16, 110), (188, 55, 84), (249, 142, 9), (252, 255, 164)],
    "diverging": [(59, 76, 192), (221, 221, 221), (180, 4, 38)],
}
CMAPS = ("grey", "viridis", "inferno")


def palette(name: str, levels: int) -> np.ndarray:
    stops = np.array(_STOPS.get(name, _STOPS["grey"]), dtype=float)
    t = np.linspace(0, 1, levels)
    k = np.linspace(0, 1, len(stops))
    return np.rint(np.stack([np.interp(t, k, stops[:, c]) for c in range(3)], -1)).astype(int)


# --------------------------------------------------------------------------- polar curves
def plane_curve(model: Model, values: dict[str, Any], theta_i_deg: float, plane: str,
                *, cosine: bool = False, n: int = 181) -> tuple[np.ndarray, np.ndarray]:
    """``(θr in degrees from −90 to 90, f)`` in the plane of incidence (negative θr on the
    φ = 180° side, the light's side) or the perpendicular plane (negative θr at φ = −90°)."""
    t = np.linspace(-90.0, 90.0, n)
    s, c = np.sin(np.radians(t)), np.cos(np.radians(t))
    c = np.clip(c, 0.0, None)
    z = np.zeros_like(t)
    wo = np.stack([s, z, c] if plane == "incidence" else [z, s, c], -1)
    wi = np.broadcast_to(incident(theta_i_deg), wo.shape)
    f = np.asarray(evaluate_resolved(model, values, wi, wo), dtype=float)
    if f.ndim == 2:
        f = f @ np.array([0.2126, 0.7152, 0.0722])  # luminance of an RGB model
    if cosine:
        f = f * c
    return t, f


# --------------------------------------------------------------------------- quadrature
def _grid(n_theta: int):
    dt = np.pi / 2 / n_theta
    t = (np.arange(n_theta) + 0.5) * dt
    n_phi = 2 * n_theta
    dp = 2 * np.pi / n_phi
    p = (np.arange(n_phi) + 0.5) * dp - np.pi
    T, P = np.meshgrid(t, p, indexing="ij")
    wo = np.stack([np.sin(T) * np.cos(P), np.sin(T) * np.sin(P), np.cos(T)], -1)
    w = np.sin(T) * dt * dp  # solid angle of each cell (midpoint rule)
    return wo, w


def albedo_and_peak(model: Model, values: dict[str, Any], theta_i_deg: float,
                    *, n_theta: int = 64, cosine: bool = False):
    """``(albedo, (peak value, θ, φ))``; albedo per channel for RGB models."""
    wo, w = _grid(n_theta)
    wi = np.broadcast_to(incident(theta_i_deg), wo.shape)
    f = np.asarray(evaluate_resolved(model, values, wi, wo), dtype=float)
    cos = wo[..., 2]
    fc = f * (cos[..., None] if f.ndim == 3 else cos)
    wt = w[..., None] if f.ndim == 3 else w
    a = (fc * wt).sum(axis=(0, 1))
    g = fc if cosine else f
    if g.ndim == 3:
        g = g @ np.array([0.2126, 0.7152, 0.0722])
    k = np.unravel_index(int(np.argmax(g)), g.shape)
    th = float(np.degrees(np.arccos(np.clip(wo[k][2], -1, 1))))
    ph = float(np.degrees(np.arctan2(wo[k][1], wo[k][0])))
    return (a if np.ndim(a) else float(a)), (float(g[k]), th, ph)


def albedo_curve(model: Model, values: dict[str, Any], thetas: np.ndarray) -> np.ndarray:
    return np.array([albedo_and_peak(model, values, t, n_theta=32)[0] for t in thetas])
