"""3D photometric solid (tuibrdf/render/solid.py; its values and scale from the frame,
tuibrdf/core/scene.py)."""

import numpy as np
import pytest

from tuibrdf.core.material import Material
from tuibrdf.core.scene import FrameRequest, compute_frame
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
