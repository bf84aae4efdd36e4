"""3D photometric solid (tuibrdf/render/solid.py; its values and scale from the frame,
tuibrdf/core/views/frame.py)."""

import numpy as np
import pytest

from tuibrdf.core.material import Material
from tuibrdf.core.views.frame import SOLID_SUBDIV, FrameRequest, compute_frame, solid_samples
from tuibrdf.render.halfblock import TRANSPARENT
from tuibrdf.render.solid import SHADE_LEVELS, camera
from tuibrdf.render.solid import solid_image as draw


def solid_image(model, params, theta_i, px_w, px_h, **kw):
    """``(index, palette, peak)`` as the solid pane draws them from a frame."""
    side = compute_frame(FrameRequest((Material(model, params),), theta_i, solid=True),
                         slow=False).sides[0]
    rmax = side.peak.value
    return (*draw(side.solid, theta_i, px_w, px_h, rmax=rmax, **kw), rmax)


def test_camera_is_orthonormal_and_oriented():
    # az = 0, el = 0: looking from +x: right = +y, up = +z
    c = camera(0, 0)
    assert c @ c.T == pytest.approx(np.eye(3))
    assert c[0] == pytest.approx([0, 1, 0]) and c[1] == pytest.approx([0, 0, 1])
    # right-handed screen: right × up = toward the camera
    c = camera(-60, 25)
    assert np.cross(c[0], c[1]) == pytest.approx(c[2])


def test_lambert_top_view_is_a_round_shaded_disc():
    # a constant BRDF gives a hemisphere of radius kd/π; seen from above it is a disc whose
    # centre faces the camera: shade 0.2 + 0.8·(n·l) with n = camera direction and
    # l = normalize(d + 0.5·up − 0.5·right) → n·l = 1/√1.5
    index, pal, rmax = solid_image("lambert", {"kd": 0.5}, 0, 60, 60, elevation_deg=90)
    assert rmax == pytest.approx(0.5 / np.pi)
    expected = int((0.2 + 0.8 / np.sqrt(1.5)) * SHADE_LEVELS)
    near_centre = index[27:33, 27:33].ravel()
    surface = near_centre[near_centre < SHADE_LEVELS]
    # within 3 pixels of the centre (radius ≈ 26 px) the sphere normal tilts by ≤ 7°, which
    # moves n·l by ≤ 0.08·0.8 → ≤ 4 of 64 levels
    assert surface.size and np.abs(surface - expected).max() <= 4
    # z-buffer: the normal axis (drawn up to 1.1·r, nearer than the surface) covers the centre
    assert (near_centre == SHADE_LEVELS).any()
    # round: the covered region is as wide as it is tall
    rows, cols = np.nonzero(index != TRANSPARENT)
    assert abs((rows.max() - rows.min()) - (cols.max() - cols.min())) <= 2


def test_zero_brdf_draws_guides_only():
    # f = 0 everywhere: the surface collapses onto the origin (at most the one pixel there);
    # the guides are drawn at unit scale: the outline circle and the normal (code
    # SHADE_LEVELS) and the light's direction (SHADE_LEVELS + 1).  An empty picture fails.
    index, pal, rmax = solid_image("lambert", {"kd": 0.0}, 30, 40, 30)
    assert rmax == 0.0
    drawn = index[index != TRANSPARENT]
    assert (drawn < SHADE_LEVELS).sum() <= 1
    axes, light = (drawn == SHADE_LEVELS).sum(), (drawn == SHADE_LEVELS + 1).sum()
    # the outline is an ellipse about 40·(2/2.3) px wide: well over 40 pixels with the normal
    assert axes >= 40 and light >= 5
    rows, cols = np.nonzero(index == SHADE_LEVELS)
    assert cols.max() - cols.min() >= 30  # the circle spans most of the width


def test_deterministic():
    v = {"kd": 0.0, "m": 0.1}
    a = solid_image("cook-torrance", v, 60, 50, 40)[0]
    b = solid_image("cook-torrance", v, 60, 50, 40)[0]
    assert (a == b).all()


def test_log_of_constant_brdf_is_the_same_hemisphere():
    # a constant f sits at the top decade (radius 1) in log mode, and the picture is fitted to
    # its radius in both modes: the two pictures coincide
    v = {"kd": 0.3}
    lin = solid_image("lambert", v, 20, 40, 30)[0]
    log = solid_image("lambert", v, 20, 40, 30, log=True)[0]
    assert (lin == log).all()


def _holes(index: np.ndarray) -> int:
    """Uncovered pixels strictly inside the surface's outline.

    The solid of a constant BRDF is a hemispherical dome whose projection is that of a
    half-ball (every ray from the base disc toward a camera above it meets the dome): a convex
    set.  A pixel with surface pixels at least 2 px away on both sides in its row *and* in its
    column is inside it, and must be drawn (by the surface, or a guide in front of it); the
    2 px keep out the half-pixel staircase of the outline itself."""
    surf = (index != TRANSPARENT) & (index < SHADE_LEVELS)
    h, w = index.shape
    r, c = np.nonzero(surf)
    inf = 10 ** 6
    left, right = np.full(h, inf), np.full(h, -inf)
    np.minimum.at(left, r, c)
    np.maximum.at(right, r, c)
    top, bottom = np.full(w, inf), np.full(w, -inf)
    np.minimum.at(top, c, r)
    np.maximum.at(bottom, c, r)
    rr, cc = np.mgrid[0:h, 0:w]
    inside = ((cc >= left[:, None] + 2) & (cc <= right[:, None] - 2)
              & (rr >= top[None, :] + 2) & (rr <= bottom[None, :] - 2))
    return int((inside & (index == TRANSPARENT)).sum())


@pytest.mark.parametrize("px_w, px_h", [(40, 30), (120, 80), (240, 138), (480, 300)])
@pytest.mark.parametrize("elevation", [25.0, 90.0])
def test_lambert_solid_is_closed_at_every_pane_size(px_w, px_h, elevation):
    # constant f: points kd/π·wo fill a dome; no uncovered pixel inside its convex outline,
    # at the largest panes too, where the samples are sparser than the pixels
    index = solid_image("lambert", {"kd": 0.8}, 30, px_w, px_h, elevation_deg=elevation)[0]
    # the dome is drawn, and large
    assert ((index != TRANSPARENT) & (index < SHADE_LEVELS)).sum() > 0.05 * px_w * px_h
    assert _holes(index) == 0


def _components(mask: np.ndarray) -> int:
    """Number of 4-connected components of ``mask`` (a plain flood fill, for the test)."""
    seen = np.zeros_like(mask, dtype=bool)
    n = 0
    h, w = mask.shape
    for r0, c0 in zip(*np.nonzero(mask), strict=True):
        if seen[r0, c0]:
            continue
        n += 1
        stack = [(r0, c0)]
        seen[r0, c0] = True
        while stack:
            r, c = stack.pop()
            for rr, cc in ((r + 1, c), (r - 1, c), (r, c + 1), (r, c - 1)):
                if 0 <= rr < h and 0 <= cc < w and mask[rr, cc] and not seen[rr, cc]:
                    seen[rr, cc] = True
                    stack.append((rr, cc))
    return n


@pytest.mark.parametrize("px_w, px_h", [(160, 94), (240, 138)])
def test_sharp_lobe_is_one_connected_surface(px_w, px_h):
    # cook-torrance m = 0.07 at θi = 60°: a long thin lobe toward the mirror direction.  Its
    # surface is connected, so its pixels form one 4-connected region, not scattered dots.
    # Seen from the side (az 90°, el 10°), away from the guides that could cut it.
    index = solid_image("cook-torrance", {"kd": 0.0, "m": 0.07}, 60, px_w, px_h,
                        azimuth_deg=90.0, elevation_deg=10.0)[0]
    lobe = (index != TRANSPARENT) & (index < SHADE_LEVELS)
    assert lobe.sum() > 100  # the lobe is many pixels long and wide at this size
    assert _components(lobe) == 1


def test_the_z_buffer_keeps_the_nearest_fragment_and_the_first_of_a_tie():
    """``nearest_fragments`` against the z-buffer written as a loop: each pixel keeps its
    largest depth (toward the camera), a tie goes to the first fragment; depths on a coarse
    grid make ties common."""
    from tuibrdf.render.solid import nearest_fragments

    rng = np.random.default_rng(5)
    for n_frag, n_pix in [(0, 4), (1, 4), (50, 7), (5000, 300)]:
        pid = rng.integers(0, n_pix, n_frag)
        depth = rng.integers(-4, 5, n_frag) * 0.25
        want: dict[int, int] = {}
        for i, (p, d) in enumerate(zip(pid.tolist(), depth.tolist(), strict=True)):
            if p not in want or d > depth[want[p]]:
                want[p] = i
        hit, won = nearest_fragments(pid, depth, n_pix)
        assert dict(zip(hit.tolist(), won.tolist(), strict=True)) == want
        assert hit.tolist() == sorted(want)


def _rasterise_by_loop(x, y, depth, px_w, px_h):
    """:func:`rasterise`'s contract as a loop: triangle by triangle, every pixel centre of its
    bounding box (decided on the snapped corners) row by row, kept where the three edge
    functions agree in sign to 1e-9 of the doubled area (at least 1e-9)."""
    from tuibrdf.core.numerics import snap

    pid, zs, tris = [], [], []
    for t in range(len(x)):
        (x0, x1, x2), (y0, y1, y2) = x[t].tolist(), y[t].tolist()
        lo_x = max(int(np.ceil(snap(min(x0, x1, x2) - 0.5))), 0)
        hi_x = min(int(np.floor(snap(max(x0, x1, x2) - 0.5))), px_w - 1)
        lo_y = max(int(np.ceil(snap(min(y0, y1, y2) - 0.5))), 0)
        hi_y = min(int(np.floor(snap(max(y0, y1, y2) - 0.5))), px_h - 1)
        for iy in range(lo_y, hi_y + 1):
            for ix in range(lo_x, hi_x + 1):
                cx, cy = ix + 0.5, iy + 0.5
                ax, bx, qx = x0 - cx, x1 - cx, x2 - cx
                ay, by, qy = y0 - cy, y1 - cy, y2 - cy
                w0, w1, w2 = bx * qy - qx * by, qx * ay - ax * qy, ax * by - bx * ay
                area = w0 + w1 + w2
                eps = 1e-9 * max(abs(area), 1.0)
                if area != 0 and (min(w0, w1, w2) >= -eps or max(w0, w1, w2) <= eps):
                    pid.append(iy * px_w + ix)
                    zs.append((w0 * depth[t, 0] + w1 * depth[t, 1] + w2 * depth[t, 2]) / area)
                    tris.append(t)
    return np.array(pid, dtype=np.int64), np.array(zs), np.array(tris, dtype=np.int64)


KINDS = ["any", "slivers", "on centres", "ninths", "flat edges", "tiny"]


@pytest.mark.parametrize("kind", KINDS)
def test_rasterise_covers_what_a_loop_over_each_box_covers(kind):
    """The same fragments, in the same order (the z-buffer's tie-break) and with the same
    depths, as the loop over each triangle's box: slivers across many columns (a lobe clipped
    at the scale; scanned over their own extent on each row), corners and edges on pixel
    centres (and on a grid of thirds, sixths or ninths of a pixel, where an edge's x on a row
    rounds off a centre that lies on it), horizontal edges, triangles of nearly no area."""
    from tuibrdf.render.solid import rasterise

    rng = np.random.default_rng(KINDS.index(kind))
    for _ in range(12):
        n, w, h = int(rng.integers(1, 60)), int(rng.integers(1, 50)), int(rng.integers(1, 50))
        if kind == "any":
            x, y = rng.uniform(-5, w + 5, (n, 3)), rng.uniform(-5, h + 5, (n, 3))
        elif kind == "slivers":  # two corners close, the third far along x or y
            x = rng.uniform(0, w, (n, 1)) + rng.normal(0, 0.05, (n, 3))
            y = rng.uniform(0, h, (n, 1)) + rng.normal(0, 0.05, (n, 3))
            far = rng.uniform(-40, 40, n)
            x[::2, 2] += far[::2]
            y[1::2, 2] += far[1::2]
            x[1::2, 2] += 0.3 * far[1::2]
        elif kind == "on centres":
            x = rng.integers(0, w + 1, (n, 3)) + rng.choice([0.0, 0.5], (n, 3))
            y = rng.integers(0, h + 1, (n, 3)) + rng.choice([0.0, 0.5], (n, 3))
        elif kind == "ninths":  # boxes wider than solid.WIDE_BOX: scanned over the extent
            q = int(rng.choice([3, 6, 9]))
            x, y = rng.integers(0, q * w, (n, 3)) / q, rng.integers(0, q * h, (n, 3)) / q
            x[:, 2] = x[:, 0] + rng.integers(6, 30, n) * rng.choice([-1, 1], n)
            # a few ulps off: a corner that snaps onto a centre's row lies just beyond it
            y[::4] = np.nextafter(y[::4], y[::4] + rng.choice([-1.0, 1.0], (len(y[::4]), 3)))
        elif kind == "flat edges":
            x = rng.integers(-2, w + 2, (n, 3)) + 0.5
            y = rng.integers(-2, h + 2, (n, 3)) + 0.5
            y[:, 1] = y[:, 0]
            x[::3, 2] = x[::3, 0]
        else:
            x = rng.uniform(0, w, (n, 1)) + rng.normal(0, 1e-7, (n, 3))
            y = rng.uniform(0, h, (n, 1)) + rng.normal(0, 1e-7, (n, 3))
            x[::2] = x[::2, :1]  # a vertical segment: no area
        depth = rng.normal(size=(n, 3))
        got, want = rasterise(x, y, depth, w, h), _rasterise_by_loop(x, y, depth, w, h)
        for g, e in zip(got, want, strict=True):
            np.testing.assert_array_equal(g, e)


def test_a_face_with_two_corners_at_zero_has_the_normal_of_its_surface():
    """The solid of f = 1 but 0 on the horizon (a lobe rising to the horizon, where f is 0):
    the outer faces with two corners on the horizon still have samples off it, so they are
    drawn and need a normal, which the plane of their corners (two at the origin) does not
    give.  Theirs is their deformed surface's vector area, which Stokes' theorem gives from
    the boundary alone: ½ Σ p_k × p_k+1 around the face's edge samples; every other face keeps
    its corners' plane."""
    from tuibrdf.render.solid import _grid_triangles, face_normals

    dirs, face, corner_dirs = solid_samples()
    horizon = np.abs(dirs[:, 2]) < 1e-12
    pts = np.where(horizon, 0.0, 1.0)[:, None] * dirs
    n_faces, s = len(corner_dirs), SOLID_SUBDIV
    zero = np.abs(corner_dirs[..., 2]) < 1e-12
    corners = np.where(zero, 0.0, 1.0)[..., None] * corner_dirs
    n = face_normals(corners, pts, _grid_triangles(n_faces, s))
    # a face's samples: (i, j) row-major, i + j ≤ s; its edge from (0,0) along i, then back
    # along the hypotenuse and down j (the small triangles' winding)
    ij = [(i, j) for i in range(s + 1) for j in range(s + 1) if i + j <= s]
    loop = ([(i, 0) for i in range(s)] + [(s - k, k) for k in range(s)]
            + [(0, s - k) for k in range(s)])
    edge = np.array([ij.index(v) for v in loop])
    ring = pts[:n_faces * len(ij)].reshape(n_faces, len(ij), 3)[:, edge]
    area = 0.5 * np.cross(ring, np.roll(ring, -1, axis=1)).sum(axis=1)
    two = zero.sum(axis=1) == 2
    assert two.sum() >= 16  # the outer ring's faces that sit on the horizon
    want = area[two] / np.linalg.norm(area[two], axis=1)[:, None]
    np.testing.assert_allclose(n[two], want, atol=1e-9)
    plane = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])[~two]
    np.testing.assert_allclose(n[~two], plane / np.linalg.norm(plane, axis=1)[:, None],
                               atol=1e-12)
