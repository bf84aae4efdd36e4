"""3D photometric solid (SPEC §4 view 3): the surface ``p = f(wi, wo)·wo`` over the hemisphere.

- Directions: the triangles of ``tuibrdf.core.mesh.hemisphere(LEVEL)``; each triangle is
  sampled on a barycentric grid (:data:`SUBDIV` steps per edge), so the surface stays closed
  where a sharp lobe stretches it.  RGB models use their Rec.709 luminance for the radius.
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

from functools import lru_cache
from typing import Any

import numpy as np
from rich.console import Group

from ..core.evaluate import evaluate_resolved
from ..core.frame import incident
from ..core.params import Model
from .colormap import LOG_DECADES, fmt_value, luminance, palette, quantise
from .halfblock import TRANSPARENT, HalfBlockImage
from .polar import radius
from .views import RING_RGB, title_line

LEVEL = 4
SUBDIV = 3
SHADE_LEVELS = 64
AXIS_RGB = RING_RGB
LIGHT_RGB = (40, 220, 255)


@lru_cache(maxsize=4)
def _samples(level: int, subdiv: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Sample directions ``(S, 3)``, the face of each sample ``(S,)`` and the face corner
    directions ``(F, 3, 3)``."""
    from ..core.mesh import hemisphere

    mesh = hemisphere(level)
    i, j = np.meshgrid(np.arange(subdiv + 1), np.arange(subdiv + 1), indexing="ij")
    keep = i + j <= subdiv
    b = np.stack([i[keep], j[keep], subdiv - i[keep] - j[keep]], axis=1) / subdiv  # (B, 3)
    tri = mesh.vertices[mesh.faces]  # (F, 3, 3)
    pts = np.einsum("bk,fkd->fbd", b, tri).reshape(-1, 3)
    pts /= np.linalg.norm(pts, axis=1, keepdims=True)  # points of a unit-sphere mesh: norm > 0
    face = np.repeat(np.arange(len(mesh.faces)), len(b))
    for arr in (pts, face, tri):
        arr.setflags(write=False)
    return pts, face, tri


def camera(azimuth_deg: float, elevation_deg: float) -> np.ndarray:
    """Rows: screen right, screen up, toward the camera."""
    az, el = np.radians(azimuth_deg), np.radians(elevation_deg)
    d = np.array([np.cos(el) * np.cos(az), np.cos(el) * np.sin(az), np.sin(el)])
    right = np.array([-np.sin(az), np.cos(az), 0.0])
    return np.stack([right, np.cross(d, right), d])


def solid_image(
    model: Model,
    values: dict[str, Any],
    theta_i_deg: float,
    px_w: int,
    px_h: int,
    *,
    cmap: str = "grey",
    cosine: bool = False,
    log: bool = False,
    azimuth_deg: float = -60.0,
    elevation_deg: float = 25.0,
) -> tuple[np.ndarray, np.ndarray, float]:
    """``(index (px_h, px_w), palette, max radius)`` of the shaded solid."""
    dirs, face, corner_dirs = _samples(LEVEL, SUBDIV)
    wi = incident(theta_i_deg)
    f = np.asarray(evaluate_resolved(model, values, wi, dirs), dtype=float)
    if f.ndim == 2:
        f = luminance(f)
    if cosine:
        f = f * dirs[:, 2]
    rmax = float(np.max(f))
    if log:  # radius = decade position in [0, 1], as in the polar plots
        f = radius(f, rmax if rmax > 0 else 1.0, True, LOG_DECADES)
    pts = f[:, None] * dirs
    # an all-zero BRDF is drawn as the guides alone; log radii lie in [0, 1]
    scale_r = 1.0 if (log or rmax <= 0) else rmax
    # triangle normals of the deformed surface, from the samples at the face corners
    fv = np.asarray(evaluate_resolved(model, values, wi, corner_dirs), dtype=float)
    if fv.ndim == 3:
        fv = luminance(fv)
    if cosine:
        fv = fv * corner_dirs[..., 2]
    if log:
        fv = radius(fv, rmax if rmax > 0 else 1.0, True, LOG_DECADES)
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
    light_line = s * wi
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
    return index.reshape(px_h, px_w), np.concatenate([pal, guide_pal]), rmax


def solid_view(
    model: Model,
    values: dict[str, Any],
    theta_i_deg: float,
    width: int,
    height: int,
    *,
    color: str = "truecolor",
    cmap: str = "grey",
    cosine: bool = False,
    log: bool = False,
    azimuth_deg: float = -60.0,
    elevation_deg: float = 25.0,
) -> Group:
    """Title line and the solid as half blocks (``height − 1`` rows)."""
    index, pal, rmax = solid_image(model, values, theta_i_deg, width, 2 * (height - 1),
                                   cmap=cmap, cosine=cosine, log=log, azimuth_deg=azimuth_deg,
                                   elevation_deg=elevation_deg)
    what = "f·cosθr·wo" if cosine else "f·wo"
    if log:
        what += f" (log, {LOG_DECADES:g} decades)"
    title = title_line(model, theta_i_deg, f"solid {what}, max {fmt_value(rmax)}", width,
                       f"az {azimuth_deg:g}° el {elevation_deg:g}°")
    return Group(title, HalfBlockImage(index, pal, color_system=color))
