"""3D photometric solid (tuibrdf/render/solid.py; its values and scale from the frame,
tuibrdf/core/views/frame.py)."""

import numpy as np
import pytest

from tuibrdf.core.material import Material
from tuibrdf.core.views.frame import FrameRequest, compute_frame
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
