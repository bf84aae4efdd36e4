"""Pictures of the material under one light: a lit sphere and a large lit plane (numpy only).

Both are lit by one *directional* light of irradiance ``E⊥ = π`` on a surface facing it, so a
pixel's radiance is ::

    L = f(wi, wo) · cos θi · π        (cos θi = wi·N, 0 when the light is below the surface)

with ``wi`` toward the light and ``wo`` toward the camera in the surface's local frame: a
white Lambert surface (f = 1/π) facing the light has ``L = 1``, the top of the tone curve at
exposure 1.  Radiance images are ``(H, W, 3)`` linear RGB (scalar models give three equal
channels) with a mask of the pixels that show the surface.

**Lit sphere** (:func:`lit_sphere`): a unit sphere seen by an *orthographic camera along the
normal* of the flat sample (world +z toward the camera, image x to the right, y up), lit from
``incident(θi)`` = ``(−sin θi, 0, cos θi)``: the light is θi from the viewing direction, on the
left.  This is BRDF Explorer's lit-sphere convention (light and view given relative to each
other); the centre of the sphere shows exactly the viewer's sample (N = view), the rest of the
disc every other normal at once.  Each pixel's local frame: N the sphere's normal, tangent
``T = normalise(e_x − (e_x·N) N)`` (the sample's x axis at the centre), ``B = N × T``; the
choice of tangent matters only for anisotropic models.

**Lit plane** (:func:`lit_plane`): an infinite plane z = 0 seen by a *pinhole camera* one unit
above it, looking toward the light's side (−x) and down at ``θv`` from the normal, lit by the
directional light at ``incident(θi)``.  Every pixel's ray ``d`` that meets the plane gives
``wo = −d`` (toward the camera) and the constant ``wi``; the plane's local frame is the world
frame.  The viewer takes ``θv = θi``: the camera looks at the mirror point of the light (the
centre of the image is the mirror direction S), which is a grazing view when the light is
grazing — the case of the gKit2 lesson (a road, the sea at sunset).  Pixels are square: one
pixel is the same angle horizontally and vertically at the image centre.  A lobe that is a
cone around S (modified Phong: f depends on S·wo only) images as a circle (the cone is around
the optical axis); a half-vector lobe (Cook-Torrance) is narrower across by about cos θi (see
``core/views/sections.py``), so its highlight stretches toward the horizon.

**Tone mapping** (:func:`tone_map`): ``v = clamp(exposure · L, 0, 1) ^ (1/γ)``, 8 bits per
channel: a linear exposure scale, a hard clip (no roll-off: what clips is brighter than the
white Lambert reference times 1/exposure), then a pure power-law display gamma (γ = 2.2 by
default; not the piecewise sRGB curve).
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from tuibrdf.core.directions import sincos_deg
from tuibrdf.core.display import DISPLAY
from tuibrdf.core.evaluate import evaluate_resolved
from tuibrdf.core.numerics import snapped_rint
from tuibrdf.core.params import Model

#: irradiance on a surface facing the light: a white Lambert surface then has radiance 1
E_PERP = np.pi
DEFAULT_FOV_DEG = 40.0


def _radiance(model: Model, values: dict, wi: np.ndarray, wo: np.ndarray) -> np.ndarray:
    """``f(wi, wo) · max(wi_z, 0) · E⊥`` as ``(..., 3)`` linear RGB."""
    wi, wo = np.broadcast_arrays(np.asarray(wi, dtype=float), np.asarray(wo, dtype=float))
    f = np.asarray(evaluate_resolved(model, values, wi, wo), dtype=float)
    cos_i = np.maximum(wi[..., 2], 0.0)
    if f.ndim == wi.ndim:  # RGB model: (..., 3)
        return f * (cos_i * E_PERP)[..., None]
    return np.repeat((f * cos_i * E_PERP)[..., None], 3, axis=-1)


def sphere_geometry(px_w: int, px_h: int) -> tuple[np.ndarray, np.ndarray]:
    """``(normals, inside)``: the sphere's unit normal per pixel (world frame, ``(H, W, 3)``;
    the pole (0, 0, 1) outside the disc) and the pixels whose centre lies inside the disc.
    The disc is centred with radius ``min(px_w, px_h) / 2`` pixels (square pixels)."""
    px_w, px_h = int(px_w), int(px_h)
    if px_w < 1 or px_h < 1:
        raise ValueError(f"image size {px_w}×{px_h}: at least 1×1 pixels")
    rad = min(px_w, px_h) / 2.0
    x = (np.arange(px_w) + 0.5 - px_w / 2.0) / rad  # rad ≥ 0.5
    y = (px_h / 2.0 - np.arange(px_h) - 0.5) / rad
    xx, yy = np.meshgrid(x, y)
    r2 = xx * xx + yy * yy
    inside = r2 < 1.0
    z = np.sqrt(np.where(inside, 1.0 - r2, 1.0))
    n = np.stack([np.where(inside, xx, 0.0), np.where(inside, yy, 0.0), z], axis=-1)
    return n, inside


def tangent_frames(n: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(T, B)`` of each normal ``n``: ``T = normalise(e_x − (e_x·N) N)`` and ``B = N × T``.
    For ``N = ±e_x`` (never a pixel centre: those lie strictly inside the disc, where ``N_y``
    or ``N_z`` ≠ 0) T falls back to ``e_y``."""
    n = np.asarray(n, dtype=float)
    t = np.zeros_like(n)
    t[..., 0] = 1.0
    t = t - n[..., :1] * n
    tl = np.sqrt(np.sum(t * t, axis=-1))
    ok = tl > 1e-12
    t = np.where(ok[..., None], t / np.where(ok, tl, 1.0)[..., None],  # tl = 0 only at N = ±e_x
                 np.array([0.0, 1.0, 0.0]))
    return t, np.cross(n, t)


@lru_cache(maxsize=8)
def _sphere(px_w: int, px_h: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(frames, inside, view)`` of a sphere picture, the same for every frame of a pane
    size: the per-pixel world → local matrices ``(H, W, 3, 3)`` (rows T, B, N), the disc, and
    the view direction (0, 0, 1) in each local frame."""
    n, inside = sphere_geometry(px_w, px_h)
    t, b = tangent_frames(n)
    frames = np.stack([t, b, n], axis=-2)
    view = np.ascontiguousarray(frames[..., 2])  # the world z component of T, B and N
    for arr in (frames, inside, view):
        arr.setflags(write=False)
    return frames, inside, view


def lit_sphere(model: Model, values: dict, wi: np.ndarray, px_w: int,
               px_h: int) -> tuple[np.ndarray, np.ndarray]:
    """``(radiance, inside)``: the sphere under the light at ``wi`` (see the module docstring);
    radiance ``(px_h, px_w, 3)``, 0 outside the disc."""
    frames, inside, wo = _sphere(int(px_w), int(px_h))
    wi = frames @ wi  # in each pixel's local frame
    # the model returns 0 where either direction is below the local horizon
    rad = _radiance(model, values, wi, wo)
    return np.where(inside[..., None], rad, 0.0), inside


def plane_rays(px_w: int, px_h: int, view_deg: float,
               fov_deg: float = DEFAULT_FOV_DEG) -> tuple[np.ndarray, np.ndarray]:
    """``(d, hits)``: the unit ray direction of each pixel ``(H, W, 3)`` of the camera looking
    toward −x and down at ``view_deg`` from the normal (vertical field of view ``fov_deg``,
    square pixels), and the pixels whose ray meets the plane (``d_z < 0``)."""
    px_w, px_h = int(px_w), int(px_h)
    if px_w < 1 or px_h < 1:
        raise ValueError(f"image size {px_w}×{px_h}: at least 1×1 pixels")
    if not 0.0 < fov_deg < 180.0:
        raise ValueError(f"field of view {fov_deg}°: expected between 0 and 180")
    s, c = sincos_deg(float(view_deg))
    s, c = float(s), float(c)
    forward = np.array([-s, 0.0, -c])  # −S for a light at θi = view_deg
    right = np.array([0.0, 1.0, 0.0])
    up = np.array([-c, 0.0, s])  # right × forward... = up on screen (z at a level camera)
    focal = (px_h / 2.0) / np.tan(np.radians(fov_deg) / 2.0)  # 0 < fov < 180°
    u = np.arange(px_w) + 0.5 - px_w / 2.0
    v = px_h / 2.0 - np.arange(px_h) - 0.5
    uu, vv = np.meshgrid(u, v)
    d = focal * forward + uu[..., None] * right + vv[..., None] * up
    d = d / np.sqrt(np.sum(d * d, axis=-1))[..., None]  # |d| ≥ focal > 0
    return d, d[..., 2] < 0.0


def lit_plane(model: Model, values: dict, wi: np.ndarray, px_w: int, px_h: int, *,
              view_deg: float, phi_i_deg: float = 180.0,
              fov_deg: float = DEFAULT_FOV_DEG) -> tuple[np.ndarray, np.ndarray]:
    """``(radiance, hits)``: the plane under the light at ``wi`` seen by the camera of
    :func:`plane_rays` at ``view_deg`` from the normal (the viewer's: ``θi``, so the image
    centre is the mirror direction), turned with the light's azimuth ``phi_i_deg``; radiance
    ``(px_h, px_w, 3)``, 0 above the horizon."""
    d, hits = plane_rays(px_w, px_h, view_deg, fov_deg)
    # φi ≠ 180°: the light and the camera turn together about the normal (the picture of an
    # isotropic surface does not change; an anisotropic one shows its other azimuth)
    sp, cp = sincos_deg(float(phi_i_deg) - 180.0)
    d = np.stack([cp * d[..., 0] - sp * d[..., 1], sp * d[..., 0] + cp * d[..., 1], d[..., 2]],
                 axis=-1)
    wo = np.where(hits[..., None], -d, np.array([0.0, 0.0, 1.0]))  # sky: any valid direction
    rad = _radiance(model, values, wi, wo)
    return np.where(hits[..., None], rad, 0.0), hits


def tone_map(radiance: np.ndarray, exposure: float = DISPLAY.exposure.default,
             gamma: float = DISPLAY.gamma.default) -> np.ndarray:
    """``uint8`` display values: ``round(255 · clamp(exposure · L, 0, 1) ^ (1/γ))``."""
    if not (np.isfinite(exposure) and exposure >= 0):
        raise ValueError(f"exposure {exposure}: expected a finite value ≥ 0")
    if not (np.isfinite(gamma) and gamma > 0):
        raise ValueError(f"gamma {gamma}: expected a finite value > 0")
    v = np.clip(np.asarray(radiance, dtype=float) * exposure, 0.0, 1.0)
    # the rounding decided on the snapped value (numerics.snap): pow's last bits vary by CPU
    return snapped_rint(255.0 * v ** (1.0 / gamma)).astype(np.uint8)  # gamma > 0 checked
