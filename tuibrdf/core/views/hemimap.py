"""Lambert azimuthal equal-area map of the upper hemisphere (SPEC §4 view 1): the numbers.

Projection: ``u = 2 sin(θ/2) cos φ``, ``v = 2 sin(θ/2) sin φ``; the hemisphere becomes a disc of
radius √2 (``r = 2 sin(θ/2)``, ``r = √2`` on the horizon).  ``u`` points right (φ = 0, the
mirror side), ``v`` up (φ = 90°), so the light (φ = 180°) is on the left, as in the seed's figures.
The projection is equal-area: its Jacobian is 1, so every pixel of the disc covers the same
solid angle, ``(2√2 / D)²`` sr for a disc ``D`` pixels across.

Inverse, per pixel centre (no trigonometry): ``r² = u² + v²``, ``s = √(1 − r²/4)``,
``w = (u·s, v·s, 1 − r²/2)``.

Pixel grid: ``px_w × px_h`` pixels, ``px_h = 2 ×`` cell rows for half blocks, so pixels are
about square; the disc diameter is ``min(px_w, px_h) − 3`` pixels (one-pixel margin for the
horizon ring drawn by :mod:`tuibrdf.render.panes`), its centre on a pixel centre so the plane of
incidence is one pixel row and the perpendicular plane one column.

Two ways to fill it (``method``):

``exact``  inverse projection of every pixel centre inside the disc, one vectorised
           ``evaluate_resolved`` call.
``mesh``   evaluate at the vertices of ``tuibrdf.core.sphere.mesh.hemisphere(level)`` (the level
           chosen from the pixel count, :func:`mesh_level_for`) and interpolate linearly inside
           its triangles (``tuibrdf.core.sphere.mesh.locate``: triangle and barycentric weights per
           pixel, computed once per size and level and cached).

``scripts/bench_render.py`` measures the speed and error of both (docs/reference/accuracy.md);
``exact`` is the default.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from typing import Any

import numpy as np

from tuibrdf.core.conventions import luminance
from tuibrdf.core.directions import mirror
from tuibrdf.core.evaluate import evaluate_resolved, f_cos
from tuibrdf.core.numerics import snapped_floor
from tuibrdf.core.params import Model

METHODS: tuple[str, ...] = ("exact", "mesh")
DEFAULT_METHOD = "exact"
SQRT2 = float(np.sqrt(2.0))


# ---------------------------------------------------------------------------------------------
# projection


def dir_to_uv(w: np.ndarray) -> np.ndarray:
    """Lambert coordinates ``(..., 2)`` of unit directions ``(..., 3)`` (z ≥ 0):
    ``(u, v) = (x, y)·√(2 / (1 + z))`` (= 2 sin(θ/2)·(cos φ, sin φ))."""
    w = np.asarray(w, dtype=float)
    k = np.sqrt(2.0 / (1.0 + w[..., 2]))  # 1 + z ≥ 1 on the upper hemisphere
    return w[..., :2] * k[..., None]


def uv_to_dir(uv: np.ndarray) -> np.ndarray:
    """Inverse of :func:`dir_to_uv` for ``u² + v² ≤ 2``."""
    uv = np.asarray(uv, dtype=float)
    r2 = (uv**2).sum(axis=-1)
    s = np.sqrt(np.clip(1.0 - r2 / 4.0, 0.0, None))  # r² ≤ 2 inside the disc: argument ≥ 1/2
    return np.concatenate([uv * s[..., None], (1.0 - r2 / 2.0)[..., None]], axis=-1)


@dataclass(frozen=True)
class MapGrid:
    """The map's pixel grid: where the disc sits in ``px_w × px_h`` pixels, and the direction
    of each pixel centre inside it (not :class:`tuibrdf.core.directions.Geometry`, the angles
    of a pair of directions)."""

    px_w: int
    px_h: int
    diameter: float  # pixels
    cx: float  # disc centre, pixel coordinates (x right, y down)
    cy: float
    inside: np.ndarray  # (px_h, px_w) bool
    dirs: np.ndarray  # (n_inside, 3) directions of the pixel centres inside, row-major
    uv: np.ndarray  # (n_inside, 2)

    @property
    def pixel_sr(self) -> float:
        """Solid angle of one pixel: the disc's area per pixel, ``(2√2 / D)²``."""
        return (2.0 * SQRT2 / self.diameter) ** 2

    def to_pixel(self, uv: np.ndarray) -> tuple[int, int]:
        """``(row, col)`` of the pixel containing Lambert point ``uv``."""
        k = self.diameter / 2.0 / SQRT2
        # decided on the snapped coordinate (numerics.snap): a point on the horizon lies on a
        # pixel boundary when the diameter is odd
        col = int(snapped_floor(self.cx + uv[0] * k))
        row = int(snapped_floor(self.cy - uv[1] * k))
        return min(max(row, 0), self.px_h - 1), min(max(col, 0), self.px_w - 1)

    def nearest_inside(self, uv: np.ndarray) -> tuple[int, int]:
        """``(row, col)`` of the pixel containing ``uv``, or of the nearest pixel centre inside
        the disc when that pixel's centre lies outside (a point on the horizon)."""
        row, col = self.to_pixel(uv)
        if self.inside[row, col] or not self.uv.shape[0]:
            return row, col
        k = int(np.argmin(((self.uv - uv) ** 2).sum(axis=1)))
        rows, cols = np.nonzero(self.inside)
        return int(rows[k]), int(cols[k])

    def to_uv(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        """Lambert coordinates of pixel-space points ``(x, y)``."""
        k = SQRT2 / (self.diameter / 2.0)
        return np.stack([(x - self.cx) * k, (self.cy - y) * k], axis=-1)


@lru_cache(maxsize=16)
def geometry(px_w: int, px_h: int) -> MapGrid:
    """The disc in a ``px_w × px_h`` grid (cached per size)."""
    px_w, px_h = int(px_w), int(px_h)
    if px_w < 4 or px_h < 4:
        raise ValueError(f"map needs at least 4×4 pixels, got {px_w}×{px_h}")
    diameter = float(max(min(px_w, px_h) - 3, 1))
    cx = px_w // 2 + 0.5
    cy = px_h // 2 - 0.5
    ys, xs = np.mgrid[0:px_h, 0:px_w] + 0.5
    g = MapGrid(px_w, px_h, diameter, cx, cy, np.zeros((px_h, px_w), bool), np.empty((0, 3)),
                 np.empty((0, 2)))
    uv = g.to_uv(xs, ys)
    inside = (uv**2).sum(axis=-1) <= 2.0
    for a in (inside, uv):
        a.setflags(write=False)
    dirs = uv_to_dir(uv[inside])
    dirs.setflags(write=False)
    return MapGrid(px_w, px_h, diameter, cx, cy, inside, dirs, uv[inside])


# ---------------------------------------------------------------------------------------------
# mesh interpolation


def mesh_level_for(n_pixels: int) -> int:
    """Coarsest hemisphere level with at least one vertex per 4 pixels (vertex spacing about
    two pixels: not finer than the picture needs), between 1 and 7."""
    level = 1
    while level < 7 and 5 * 4**level < n_pixels / 4:  # ≈ 5·4ᴸ vertices on the hemisphere
        level += 1
    return level


@lru_cache(maxsize=8)
def _mesh_weights(px_w: int, px_h: int, level: int) -> tuple[np.ndarray, np.ndarray, Any]:
    """Per inside pixel: the 3 vertex ids of its mesh triangle and barycentric weights
    (``tuibrdf.core.sphere.mesh.locate``), computed once per size and level."""
    from tuibrdf.core.sphere.mesh import hemisphere, locate

    mesh = hemisphere(level)
    ids, bary, _ = locate(mesh, geometry(px_w, px_h).dirs)  # every pixel is above the horizon
    for arr in (ids, bary):
        arr.setflags(write=False)
    return ids, bary, mesh


# ---------------------------------------------------------------------------------------------
# the map


@dataclass(frozen=True)
class MapInfo:
    """What a map shows besides its pixels: ``mirror_px`` ``(row, col)`` of the pixel holding
    the mirror direction S, ``incident_px`` of the light's Lambert point (the nearest pixel
    inside the disc), ``pixel_sr`` the solid angle of one pixel, ``vmin``/``vmax`` the smallest
    and largest pixel value (the luminance for RGB models), ``method`` and the mesh ``level``.
    The peak is not here: it is the frame's, found over the whole hemisphere
    (:mod:`tuibrdf.core.sphere.peak`), not among the pixels."""

    mirror_px: tuple[int, int]
    incident_px: tuple[int, int]
    pixel_sr: float
    vmin: float
    vmax: float
    method: str
    level: int | None = None


def map_values(
    model: Model,
    values: dict[str, Any],
    wi: np.ndarray,
    px_w: int,
    px_h: int,
    *,
    method: str = DEFAULT_METHOD,
    cosine: bool = False,
    level: int | None = None,
) -> tuple[np.ndarray, MapInfo]:
    """The BRDF (or ``f·cos θr`` when ``cosine``) over the map's pixels, the light at ``wi``
    (:func:`~tuibrdf.core.directions.incident`).

    Returns an array ``(px_h, px_w)`` (``(px_h, px_w, 3)`` for RGB models) with NaN outside the
    disc, and its :class:`MapInfo`.  ``values`` are resolved (``Model.resolve``).
    """
    if method not in METHODS:
        raise ValueError(f"map method {method!r}: expected one of {', '.join(METHODS)}")
    g = geometry(px_w, px_h)
    n = g.dirs.shape[0]
    used_level = None
    if method == "exact":
        f = np.asarray(evaluate_resolved(model, values, wi, g.dirs), dtype=float)
        if cosine:
            f = f_cos(f, g.dirs)
    else:
        used_level = level if level is not None else mesh_level_for(n)
        idx, wts, mesh = _mesh_weights(g.px_w, g.px_h, used_level)
        fv = np.asarray(evaluate_resolved(model, values, wi, mesh.vertices), dtype=float)
        if cosine:
            fv = f_cos(fv, mesh.vertices)
        f = np.einsum("nk,nk...->n...", wts, fv[idx])
    shape = (g.px_h, g.px_w) + f.shape[1:]
    out = np.full(shape, np.nan)
    out[g.inside] = f
    scalar = luminance(f) if f.ndim == 2 else f
    mirror_px = g.nearest_inside(dir_to_uv(mirror(wi)))
    incident_px = g.nearest_inside(dir_to_uv(wi))
    vmin = float(np.min(scalar)) if n else 0.0
    vmax = float(np.max(scalar)) if n else 0.0
    return out, MapInfo(mirror_px, incident_px, g.pixel_sr, vmin, vmax, method, used_level)
