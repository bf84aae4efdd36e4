"""3D photometric solid (SPEC §4 view 3): the surface ``p = f(wi, wo)·wo`` over the hemisphere.

- Directions: :func:`tuibrdf.core.views.frame.solid_samples`, the triangles of a hemisphere mesh,
  each sampled on a barycentric grid, so the surface stays closed where a sharp lobe stretches
  it; the values come with the frame (one kernel call).  RGB models use their Rec.709
  luminance for the radius, and the radius scale is the frame's scale (its peak, or the largest
  value at θ ≤ 89° when the peak is above 89° or unbounded: larger radii are clipped).
- View: orthographic, camera at ``azimuth`` (from +x, the mirror side, toward +y) and
  ``elevation`` above the surface; screen right = ``(−sin az, cos az, 0)``, screen up =
  camera direction × right.
- Surface: the barycentric grid of each mesh triangle is cut into ``subdiv²`` small triangles
  (over the samples), and these are rasterised (every pixel whose centre lies inside, depth
  interpolated), so the surface is closed at any pane size however far a lobe stretches it;
  the samples are also splatted, so a triangle thinner than a pixel still shows.
- Z-buffer: the nearest fragment per pixel wins (depths compared to 1e-9 of a pixel; ties
  broken by fragment order: deterministic).
- Shading: Lambert-like, ``0.2 + 0.8·|n·l|`` with ``n`` the face normal of the *deformed*
  surface (its corners' plane, or where they span none its own small triangles') and ``l`` a
  light over the camera's left shoulder, quantised through the colour map.
- Log (``log=True``): the radius is the decade position ``1 + log10(f / max) / 3`` clipped at 0,
  as in the sections (:func:`.sections.radius`).
- Axes hint: the surface's outline (circle of radius ``max|p|`` in z = 0) and the normal N in
  blue-grey, the incident direction in cyan, also depth-tested.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from tuibrdf.core.conventions import luminance
from tuibrdf.core.directions import incident
from tuibrdf.core.display import DISPLAY
from tuibrdf.core.numerics import snap, snapped_ceil, snapped_floor
from tuibrdf.core.views.frame import SOLID_SUBDIV, solid_samples
from tuibrdf.render.colormap import LOG_DECADES, palette, quantise
from tuibrdf.render.halfblock import TRANSPARENT
from tuibrdf.render.sections import radius
from tuibrdf.render.text import LIGHT_RGB, RING_RGB

SHADE_LEVELS = 64
#: a triangle whose bounding box is wider than this many pixel columns is scanned row by row
#: over its own extent (:func:`rasterise`); a narrower one over its box, which costs less
WIDE_BOX = 4
AXIS_RGB = RING_RGB


def camera(azimuth_deg: float, elevation_deg: float) -> np.ndarray:
    """Rows: screen right, screen up, toward the camera."""
    az, el = np.radians(azimuth_deg), np.radians(elevation_deg)
    d = np.array([np.cos(el) * np.cos(az), np.cos(el) * np.sin(az), np.sin(el)])
    right = np.array([-np.sin(az), np.cos(az), 0.0])
    return np.stack([right, np.cross(d, right), d])


@lru_cache(maxsize=4)
def _grid_triangles(n_faces: int, subdiv: int) -> np.ndarray:
    """``(n_faces·subdiv², 3)`` sample indices of the small triangles of every face's
    barycentric grid, the samples listed face by face as
    :func:`~tuibrdf.core.views.frame.solid_samples` lists them (``(i, j)`` row-major, ``i + j ≤
    n``)."""
    i, j = np.meshgrid(np.arange(subdiv + 1), np.arange(subdiv + 1), indexing="ij")
    keep = i + j <= subdiv
    local = np.full((subdiv + 1, subdiv + 1), -1, dtype=np.int64)
    local[i[keep], j[keep]] = np.arange(keep.sum())
    tris = []
    for a in range(subdiv):
        for b in range(subdiv - a):
            tris.append((local[a, b], local[a + 1, b], local[a, b + 1]))  # "up"
            if a + b <= subdiv - 2:
                tris.append((local[a + 1, b], local[a + 1, b + 1], local[a, b + 1]))  # "down"
    out = (np.arange(n_faces)[:, None, None] * int(keep.sum()) + np.array(tris)[None])
    out = out.reshape(-1, 3)
    out.setflags(write=False)
    return out


def face_normals(corners: np.ndarray, pts: np.ndarray, tris: np.ndarray) -> np.ndarray:
    """Unit normals ``(F, 3)`` of the deformed faces: the plane of each face's corners
    ``corners (F, 3, 3)``; where they span none, the direction of the face's own surface, the
    sum of its small triangles' cross products (``tris``, face by face as
    :func:`_grid_triangles` lists them, into the sample points ``pts``).  Two corners at 0
    with the samples between them not (a lobe rising to the horizon, where f is 0): without
    that, those faces were drawn in the darkest shade among their neighbours.  A face of no
    area at all (f = 0) keeps n = 0."""
    n = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    flat = np.flatnonzero(~np.any(n, axis=1))
    if len(flat):
        p0, p1, p2 = (pts[tris.reshape(len(n), -1, 3)[flat][..., k]] for k in range(3))
        n[flat] = np.cross(p1 - p0, p2 - p0).sum(axis=1)
    nn = np.linalg.norm(n, axis=1)
    return n / np.where(nn > 0, nn, 1.0)[:, None]


def rasterise(x: np.ndarray, y: np.ndarray, depth: np.ndarray, px_w: int, px_h: int):
    """Fragments ``(pixel id, depth, triangle)`` of triangles with corners ``x, y (T, 3)``
    (pixel units, x to the right, y down) and corner depths ``(T, 3)``: every pixel whose
    centre lies inside a triangle or on its edges, all triangles at once (no Python loop),
    triangle by triangle, each one's row by row (the z-buffer's order)."""
    x0, x1, x2 = x.T
    y0, y1, y2 = y.T
    # first and last pixel centres (c + 0.5) inside each triangle's bounding box, on screen,
    # decided on the snapped corners (core.numerics.snap): a corner on the axis of an odd
    # width lies on a pixel centre, and the matrix product that projects it rounds by CPU
    lo_x = np.maximum(snapped_ceil(np.minimum(np.minimum(x0, x1), x2) - 0.5), 0).astype(np.int64)
    hi_x = np.minimum(snapped_floor(np.maximum(np.maximum(x0, x1), x2) - 0.5), px_w - 1)
    y_lo, y_hi = np.minimum(np.minimum(y0, y1), y2), np.maximum(np.maximum(y0, y1), y2)
    lo_y = np.maximum(snapped_ceil(y_lo - 0.5), 0).astype(np.int64)
    hi_y = np.minimum(snapped_floor(y_hi - 0.5), px_h - 1)
    nx = np.maximum(hi_x.astype(np.int64) - lo_x + 1, 0)
    ny = np.maximum(hi_y.astype(np.int64) - lo_y + 1, 0)
    # the box's rows of each triangle that has a pixel centre in its box (most triangles of a
    # small solid have none)
    hit = np.nonzero(nx * ny)[0]
    tri, iy = _spread(hit, lo_y[hit], ny[hit])
    # on each row of a box wider than WIDE_BOX columns, only its columns within a pixel of the
    # triangle's own extent along the row's centre line: a sliver's box (a lobe clipped at
    # the scale stretches triangles across the picture) holds 30 times the centres its rows
    # do.  The edge test below decides, as it does in the box; the extent is only a bound, a
    # pixel wide of it
    first, last = lo_x[tri], hi_x[tri].astype(np.int64)
    wide = np.flatnonzero(nx[tri] > WIDE_BOX)
    if len(wide):
        t = tri[wide]
        xl, xr = _row_extent(x[t], y[t], np.clip(iy[wide] + 0.5, y_lo[t], y_hi[t]))
        first[wide] = np.maximum(first[wide], np.ceil(xl - 0.5).astype(np.int64) - 1)
        last[wide] = np.minimum(last[wide], np.floor(xr - 0.5).astype(np.int64) + 1)
    row, ix = _spread(np.arange(len(tri)), first, np.maximum(last - first + 1, 0))
    tri, iy = tri[row], iy[row]
    cx, cy = ix + 0.5, iy + 0.5
    ax, bx, qx = x0[tri] - cx, x1[tri] - cx, x2[tri] - cx
    ay, by, qy = y0[tri] - cy, y1[tri] - cy, y2[tri] - cy
    # edge functions: w_k is twice the signed area of the triangle opposite corner k
    w0 = bx * qy - qx * by
    w1 = qx * ay - ax * qy
    w2 = ax * by - bx * ay
    area = w0 + w1 + w2
    # either winding; a small tolerance so the shared edge of two triangles leaves no crack
    eps = 1e-9 * np.maximum(np.abs(area), 1.0)
    inside = (area != 0) & (
        ((w0 >= -eps) & (w1 >= -eps) & (w2 >= -eps))
        | ((w0 <= eps) & (w1 <= eps) & (w2 <= eps)))
    # a degenerate triangle (area 0) has no inside: its corners are splatted by the caller
    tri, area = tri[inside], area[inside]
    z = (w0[inside] * depth[tri, 0] + w1[inside] * depth[tri, 1]
         + w2[inside] * depth[tri, 2]) / area  # area ≠ 0 for every kept fragment
    return iy[inside] * px_w + ix[inside], z, tri


def _spread(owner: np.ndarray, start: np.ndarray, count: np.ndarray):
    """``(owner, value)`` for each of ``count[k]`` consecutive integers from ``start[k]``,
    ``owner[k]`` repeated alongside, in order of k."""
    own = np.repeat(owner, count)
    offset = np.arange(len(own)) - np.repeat(np.cumsum(count) - count, count)
    return own, np.repeat(start, count) + offset


def _row_extent(x: np.ndarray, y: np.ndarray, yc: np.ndarray):
    """Least and greatest x of triangles ``x, y (n, 3)`` on the lines ``y = yc (n,)``, each
    within its triangle's y-range: where the line crosses an edge.  A horizontal edge on the
    line counts as its first end (t = 0); its other end is where the next edge starts."""
    xl = np.full(len(yc), np.inf)
    xr = np.full(len(yc), -np.inf)
    for a, b in ((0, 1), (1, 2), (2, 0)):
        xa, xb, ya, yb = x[:, a], x[:, b], y[:, a], y[:, b]
        on = (np.minimum(ya, yb) <= yc) & (yc <= np.maximum(ya, yb))
        dy = yb - ya
        t = np.divide(yc - ya, dy, out=np.zeros(len(yc)), where=dy != 0.0)
        at = xa + t * (xb - xa)
        xl = np.where(on, np.minimum(xl, at), xl)
        xr = np.where(on, np.maximum(xr, at), xr)
    return xl, xr


def solid_image(
    values: np.ndarray,
    theta_i_deg: float,
    px_w: int,
    px_h: int,
    *,
    rmax: float,
    cmap: str = DISPLAY.cmap,
    log: bool = False,
    azimuth_deg: float = DISPLAY.azimuth.default,
    elevation_deg: float = DISPLAY.elevation.default,
    phi_i_deg: float = DISPLAY.phi_i.default,
    zoom: float = 1.0,
) -> tuple[np.ndarray, np.ndarray]:
    """``(index (px_h, px_w), palette)`` of the shaded solid (the light's guide at θi, φi),
    magnified ``zoom`` times about the picture's centre (what leaves it is clipped).

    ``values``: :func:`tuibrdf.core.views.frame.solid_values` (at the samples, then at the face
    corners; RGB values are drawn by their luminance); ``rmax``: the radius scale, the frame's
    scale (its peak, or the largest value at θ ≤ 89°: larger values are clipped to it), so the
    solid's size and its title agree with every other pane."""
    dirs, face, corner_dirs = solid_samples()
    f = np.asarray(values, dtype=float)
    if f.ndim == 2:
        f = luminance(f)
    f, fv = f[: len(dirs)], f[len(dirs):].reshape(corner_dirs.shape[:2])
    top = rmax if rmax > 0 else 1.0
    # a scale below the peak (the peak above 89° or unbounded, core/sphere/horizon.py): the
    # radius is clipped at it, as the map's colours are
    f, fv = np.minimum(f, top), np.minimum(fv, top)
    if log:  # radius = decade position in [0, 1], as in the sections
        f = radius(f, top, True, LOG_DECADES)
        fv = radius(fv, top, True, LOG_DECADES)
    pts = f[:, None] * dirs
    # an all-zero BRDF is drawn as the guides alone; log radii lie in [0, 1]
    scale_r = 1.0 if (log or rmax <= 0) else rmax
    tris = _grid_triangles(len(corner_dirs), SOLID_SUBDIV)
    n = face_normals(corner_dirs * fv[..., None], pts, tris)
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
    xyz = allp @ cam.T  # (screen x, screen y, depth); the surface's samples come first
    # fit the guides' extent (hemisphere of radius scale_r, normal to 1.1·scale_r), so the
    # scale stays put while the view rotates: base circle y ∈ ±r|sin el|, normal tip 1.1·r·cos el
    se, ce = abs(np.sin(np.radians(elevation_deg))), np.cos(np.radians(elevation_deg))
    lo, hi = min(-se, 1.1 * ce) * scale_r, max(se, 1.1 * ce) * scale_r
    k = zoom * min(px_w / (2.3 * scale_r), px_h / (1.05 * (hi - lo)))
    cols = snapped_floor(px_w / 2 + xyz[:, 0] * k).astype(np.int64)
    rows = snapped_floor(px_h / 2 - (xyz[:, 1] - (lo + hi) / 2) * k).astype(np.int64)
    ok = (cols >= 0) & (cols < px_w) & (rows >= 0) & (rows < px_h)
    # the small triangles over each face's samples, in pixel units (x right, y down)
    sx = px_w / 2 + xyz[: len(dirs), 0] * k
    sy = px_h / 2 - (xyz[: len(dirs), 1] - (lo + hi) / 2) * k
    t_pid, t_z, t_id = rasterise(sx[tris], sy[tris], xyz[: len(dirs), 2][tris], px_w, px_h)
    pid = np.concatenate([t_pid, (rows * px_w + cols)[ok]])
    z = np.concatenate([t_z, xyz[ok, 2]])
    frag = np.concatenate([code[tris[t_id, 0]], code[ok]])  # a triangle shades as its face
    index = np.full(px_w * px_h, TRANSPARENT, dtype=np.int64)
    hit, won = nearest_fragments(pid, snap(z * k), px_w * px_h)
    index[hit] = frag[won]
    return index.reshape(px_h, px_w), np.concatenate([pal, guide_pal])


def nearest_fragments(pid: np.ndarray, depth: np.ndarray, n_pixels: int):
    """The z-buffer: ``(pixels, fragments)``, each pixel that fragments ``pid`` cover and the
    fragment that wins it, the one with the largest ``depth`` (toward the camera; depths
    compared as given: the caller snaps them, so two fragments of one point tie whatever the
    last bits of the projection), a tie going to the first in fragment order.  Two unbuffered
    reductions (``np.maximum.at``, ``np.minimum.at``) instead of a sort of the fragments: a
    fifth of the picture's time."""
    if not len(pid):
        return pid, pid
    best = np.full(n_pixels, -np.inf)
    np.maximum.at(best, pid, depth)
    tied = np.flatnonzero(depth == best[pid])  # the nearest fragments of each pixel
    first = np.full(n_pixels, len(pid))
    np.minimum.at(first, pid[tied], tied)
    hit = np.flatnonzero(first < len(pid))
    return hit, first[hit]
