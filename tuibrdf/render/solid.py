"""3D photometric solid (SPEC §4 view 3): the surface ``p = f(wi, wo)·wo`` over the hemisphere.

- Directions: :func:`tuibrdf.core.scene.solid_samples`, the triangles of a hemisphere mesh,
  each sampled on a barycentric grid, so the surface stays closed where a sharp lobe stretches
  it; the values come with the frame (one kernel call).  RGB models use their Rec.709
  luminance for the radius, and the radius scale is the frame's peak.
- View: orthographic, camera at ``azimuth`` (from +x, the mirror side, toward +y) and
  ``elevation`` above the surface; screen right = ``(−sin az, cos az, 0)``, screen up =
  camera direction × right.
- Z-buffer: the nearest sample per pixel wins (ties broken by sample order: deterministic).
- Shading: Lambert-like, ``0.2 + 0.8·|n·l|`` with ``n`` the triangle normal of the *deformed*
  surface and ``l`` a light over the camera's left shoulder, quantised through the colour map.
- Log (``log=True``): the radius is the decade position ``1 + log10(f / max) / 3`` clipped at 0,
  as in the polar plots.
- Axes hint: the surface's outline (circle of radius ``max|p|`` in z = 0) and the normal N in
  blue-grey, the incident direction in cyan, also depth-tested.
"""

from __future__ import annotations

import numpy as np

from ..core.conventions import luminance
from ..core.frame import incident
from ..core.scene import solid_samples
from .colormap import LOG_DECADES, palette, quantise
from .halfblock import TRANSPARENT
from .polar import radius
from .text import LIGHT_RGB, RING_RGB

SHADE_LEVELS = 64
AXIS_RGB = RING_RGB


def camera(azimuth_deg: float, elevation_deg: float) -> np.ndarray:
    """Rows: screen right, screen up, toward the camera."""
    az, el = np.radians(azimuth_deg), np.radians(elevation_deg)
    d = np.array([np.cos(el) * np.cos(az), np.cos(el) * np.sin(az), np.sin(el)])
    right = np.array([-np.sin(az), np.cos(az), 0.0])
    return np.stack([right, np.cross(d, right), d])


def solid_image(
    values: np.ndarray,
    theta_i_deg: float,
    px_w: int,
    px_h: int,
    *,
    rmax: float,
    cmap: str = "grey",
    log: bool = False,
    azimuth_deg: float = -60.0,
    elevation_deg: float = 25.0,
    phi_i_deg: float = 180.0,
) -> tuple[np.ndarray, np.ndarray]:
    """``(index (px_h, px_w), palette)`` of the shaded solid (the light's guide at θi, φi).

    ``values``: :func:`tuibrdf.core.scene.solid_values` (at the samples, then at the face
    corners; RGB values are drawn by their luminance); ``rmax``: the radius scale, the frame's
    peak, so the solid's size and its title agree with every other pane."""
    dirs, face, corner_dirs = solid_samples()
    f = np.asarray(values, dtype=float)
    if f.ndim == 2:
        f = luminance(f)
    f, fv = f[: len(dirs)], f[len(dirs):].reshape(corner_dirs.shape[:2])
    top = rmax if rmax > 0 else 1.0
    if log:  # radius = decade position in [0, 1], as in the polar plots
        f = radius(f, top, True, LOG_DECADES)
        fv = radius(fv, top, True, LOG_DECADES)
    pts = f[:, None] * dirs
    # an all-zero BRDF is drawn as the guides alone; log radii lie in [0, 1]
    scale_r = 1.0 if (log or rmax <= 0) else rmax
    # triangle normals of the deformed surface, from the values at the face corners
    corners = corner_dirs * fv[..., None]
    n = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    nn = np.linalg.norm(n, axis=1)
    n = n / np.where(nn > 0, nn, 1.0)[:, None]  # a collapsed face (f = 0) keeps n = 0
    cam = camera(azimuth_deg, elevation_deg)
    light = cam[2] + 0.5 * cam[1] - 0.5 * cam[0]
    light /= np.linalg.norm(light)
    shade = 0.2 + 0.8 * np.abs(n @ light)
    # guides: outline circle, normal and incident direction, as dense point lines
    t = np.linspace(0.0, 2 * np.pi, 4 * max(px_w, px_h), endpoint=False)
    circle = np.stack([np.cos(t), np.sin(t), np.zeros_like(t)], axis=1) * scale_r
    s = np.linspace(0.0, 1.1, 2 * max(px_w, px_h))[:, None] * scale_r
    normal = s * np.array([0.0, 0.0, 1.0])
    light_line = s * incident(theta_i_deg, phi_i_deg)
    pal = palette(cmap, SHADE_LEVELS)
    guide_pal = np.array([AXIS_RGB, LIGHT_RGB], dtype=np.uint8)
    allp = np.concatenate([pts, circle, normal, light_line])
    code = np.concatenate([
        quantise(shade[face], SHADE_LEVELS),
        np.full(len(circle) + len(normal), SHADE_LEVELS),
        np.full(len(light_line), SHADE_LEVELS + 1),
    ])
    xyz = allp @ cam.T  # (screen x, screen y, depth)
    # fit the guides' extent (hemisphere of radius scale_r, normal to 1.1·scale_r), so the
    # scale stays put while the view rotates: base circle y ∈ ±r|sin el|, normal tip 1.1·r·cos el
    se, ce = abs(np.sin(np.radians(elevation_deg))), np.cos(np.radians(elevation_deg))
    lo, hi = min(-se, 1.1 * ce) * scale_r, max(se, 1.1 * ce) * scale_r
    k = min(px_w / (2.3 * scale_r), px_h / (1.05 * (hi - lo)))
    cols = np.floor(px_w / 2 + xyz[:, 0] * k).astype(np.int64)
    rows = np.floor(px_h / 2 - (xyz[:, 1] - (lo + hi) / 2) * k).astype(np.int64)
    ok = (cols >= 0) & (cols < px_w) & (rows >= 0) & (rows < px_h)
    pid = (rows * px_w + cols)[ok]
    order = np.lexsort((-xyz[ok, 2], pid))  # by pixel, nearest first
    first_pid, first = np.unique(pid[order], return_index=True)
    index = np.full(px_w * px_h, TRANSPARENT, dtype=np.int64)
    index[first_pid] = code[ok][order][first]
    return index.reshape(px_h, px_w), np.concatenate([pal, guide_pal])
