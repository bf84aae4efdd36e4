"""3D photometric solid (tuibrdf/render/solid.py)."""

import numpy as np
import pytest

from tuibrdf.core.models import MODELS
from tuibrdf.render.halfblock import TRANSPARENT
from tuibrdf.render.solid import SHADE_LEVELS, camera, solid_image


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
    m = MODELS["lambert"]
    index, pal, rmax = solid_image(m, m.resolve({"kd": 0.5}), 0, 60, 60, elevation_deg=90)
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
    m = MODELS["lambert"]
    index, pal, rmax = solid_image(m, m.resolve({"kd": 0.0}), 30, 40, 30)
    assert rmax == 0.0
    drawn = index[index != TRANSPARENT]
    assert drawn.size and (drawn >= SHADE_LEVELS).all() or (drawn < SHADE_LEVELS).sum() < 4


def test_deterministic():
    m = MODELS["cook-torrance"]
    v = m.resolve({"kd": 0.0, "m": 0.1})
    a = solid_image(m, v, 60, 50, 40)[0]
    b = solid_image(m, v, 60, 50, 40)[0]
    assert (a == b).all()


def test_log_of_constant_brdf_is_the_same_hemisphere():
    # a constant f sits at the top decade (radius 1) in log mode, and the picture is fitted to
    # its radius in both modes: the two pictures coincide
    m = MODELS["lambert"]
    v = m.resolve({"kd": 0.3})
    lin = solid_image(m, v, 20, 40, 30)[0]
    log = solid_image(m, v, 20, 40, 30, log=True)[0]
    assert (lin == log).all()
