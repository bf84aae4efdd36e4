"""Lambert equal-area map geometry and values (tuibrdf/core/views/hemimap.py)."""

import numpy as np
import pytest

from tuibrdf.core.directions import incident
from tuibrdf.core.registry import MODELS
from tuibrdf.core.views.hemimap import dir_to_uv, geometry, map_values, uv_to_dir


def _sph_tri_area(a, b, c):
    """Solid angle of a spherical triangle (Van Oosterom & Strackee 1983), independent of the
    projection's Jacobian."""
    num = np.abs(np.einsum("...i,...i", a, np.cross(b, c)))
    den = 1 + np.einsum("...i,...i", a, b) + np.einsum("...i,...i", b, c)
    den = den + np.einsum("...i,...i", c, a)
    return 2 * np.arctan2(num, den)


def test_projection_round_trip_and_radius():
    # r = 2 sin(θ/2): the horizon maps to √2, the pole to 0; φ = 0 → +u, φ = 90° → +v
    th, ph = np.radians([0, 30, 60, 90, 90]), np.radians([0, 0, 90, 180, 270])
    w = np.stack([np.sin(th) * np.cos(ph), np.sin(th) * np.sin(ph), np.cos(th)], axis=-1)
    uv = dir_to_uv(w)
    assert np.hypot(uv[:, 0], uv[:, 1]) == pytest.approx(2 * np.sin(th / 2))
    assert uv[1] == pytest.approx([2 * np.sin(np.radians(15)), 0])
    assert uv[2] == pytest.approx([0, 2 * np.sin(np.radians(30))])
    assert uv_to_dir(uv) == pytest.approx(w, abs=1e-12)


@pytest.mark.parametrize("size", [(80, 48), (161, 97)])
def test_equal_area_every_pixel_same_solid_angle(size):
    # map each interior pixel's four corners back to the sphere; its solid angle (two
    # spherical triangles, ~ exact for small cells) must equal (2√2/D)² for every pixel
    g = geometry(*size)
    rows, cols = np.nonzero(g.inside)
    corners = [g.to_uv(cols + dx, rows + dy) for dx, dy in ((0, 0), (1, 0), (1, 1), (0, 1))]
    r2 = np.max([(c**2).sum(-1) for c in corners], axis=0)
    keep = r2 <= 2.0  # pixels wholly inside the disc
    a, b, c, d = (uv_to_dir(k[keep]) for k in corners)
    omega = _sph_tri_area(a, b, c) + _sph_tri_area(a, c, d)
    expected = (2 * np.sqrt(2) / g.diameter) ** 2
    assert omega == pytest.approx(expected, rel=1e-3)
    assert g.pixel_sr == pytest.approx(expected)
    # the whole disc: pixel count × pixel solid angle → 2π (boundary pixels make the error)
    assert g.inside.sum() * g.pixel_sr == pytest.approx(2 * np.pi, rel=4 / g.diameter)


def test_layout_disc_round_and_centred():
    g = geometry(80, 48)
    rows, cols = np.nonzero(g.inside)
    # diameter min(80, 48) − 3 = 45 pixels both ways: round in pixels (pixels ≈ square)
    assert cols.max() - cols.min() + 1 == rows.max() - rows.min() + 1 == 45
    assert (rows.min() >= 1) and (rows.max() <= 46)  # one-pixel margin for the ring


def test_incidence_side_left_mirror_side_right():
    # the phong lobe at θi = 45° is on the right half (u > 0), the left half is dimmer
    m = MODELS["phong"]
    v = m.resolve({"kd": 0.0, "ks": 0.5, "n": 50})
    a, info = map_values(m, v, incident(45), 80, 48)
    g = geometry(80, 48)
    right = np.nansum(a[:, int(g.cx) + 1 :])
    left = np.nansum(a[:, : int(g.cx)])
    assert right > 100 * left
    assert info.mirror_px[1] > g.cx and info.mirror_px[0] == int(g.cy)


@pytest.mark.parametrize("theta_i", [30, 60])
def test_mirror_pixel_holds_peak_for_sharp_phong(theta_i):
    m = MODELS["phong"]
    v = m.resolve({"kd": 0.0, "ks": 1.0, "n": 2000})
    a, info = map_values(m, v, incident(theta_i), 160, 96)
    assert a[info.mirror_px] == np.nanmax(a)
    # the brightest pixel is close to the mirror value (n+2)/(2π)·ks (closed form at wo = S)
    assert info.vmax == np.nanmax(a) and info.vmax <= 2002 / (2 * np.pi) * (1 + 1e-12)


def test_lambert_map_constant_and_nan_outside():
    m = MODELS["lambert"]
    a, info = map_values(m, m.resolve({"kd": 0.5}), incident(20), 40, 30)
    g = geometry(40, 30)
    assert np.isnan(a[~g.inside]).all()
    assert a[g.inside] == pytest.approx(0.5 / np.pi)
    # cosine: f·cos θr peaks at the pole with kd/π
    a, info = map_values(m, m.resolve({"kd": 0.5}), incident(20), 40, 30, cosine=True)
    assert np.nanmax(a) == pytest.approx(0.5 / np.pi, rel=1e-2)
    assert np.nanmin(a) >= 0 and np.nanmin(a) < 0.1 * 0.5 / np.pi


SCALAR_OR_RGB = [name for name, m in MODELS.items() if all(p.kind != "path" for p in m.params)]


@pytest.mark.parametrize("name", SCALAR_OR_RGB)
@pytest.mark.parametrize("theta_i", [0, 45, 89, 90])
def test_nan_free_inside_every_model(name, theta_i):
    m = MODELS[name]
    a, info = map_values(m, m.resolve({}), incident(theta_i), 40, 24)
    g = geometry(40, 24)
    inside = a[g.inside]
    assert np.isfinite(inside).all() and (inside >= 0).all()
    assert np.isfinite(info.vmax) and info.vmin <= info.vmax
    if m.rgb:
        assert a.shape == (24, 40, 3)


def test_mesh_method_reproduces_constant_and_converges():
    # barycentric interpolation reproduces a constant exactly (weights sum to 1)
    m = MODELS["lambert"]
    a, info = map_values(m, m.resolve({"kd": 0.5}), incident(30), 40, 30, method="mesh")
    assert a[geometry(40, 30).inside] == pytest.approx(0.5 / np.pi)
    assert info.level is not None
    # a smooth lobe: the mesh map approaches the exact one as the level grows
    m = MODELS["phong"]
    v = m.resolve({"kd": 0.0, "ks": 0.5, "n": 10})
    wi = incident(30)
    exact, _ = map_values(m, v, wi, 60, 40)
    errs = [np.nanmax(np.abs(map_values(m, v, wi, 60, 40, method="mesh", level=lv)[0] - exact))
            for lv in (2, 4)]
    assert errs[1] < errs[0] / 4  # linear interpolation: error ∝ h², h halves per level


@pytest.mark.parametrize("n_pixels", [1201, 5957, 13485])
def test_mesh_level_not_finer_than_the_picture(n_pixels):
    # about one vertex per 4 pixels: the chosen level has enough vertices, the one below not
    from tuibrdf.core.sphere.mesh import hemisphere
    from tuibrdf.core.views.hemimap import mesh_level_for

    lv = mesh_level_for(n_pixels)
    assert len(hemisphere(lv).vertices) >= n_pixels / 4
    assert len(hemisphere(lv - 1).vertices) < n_pixels / 4


def test_horizon_ring_outside_and_touching_the_disc():
    from tuibrdf.render.panes import ring_mask

    g = geometry(50, 40)
    ring = ring_mask(50, 40)
    assert not (ring & g.inside).any()
    rows, cols = np.nonzero(ring)
    # every ring pixel has an inside pixel among its 8 neighbours
    pad = np.pad(g.inside, 1)
    near = np.zeros_like(ring)
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            near |= pad[1 + dy : 41 + dy, 1 + dx : 51 + dx]
    assert near[rows, cols].all()
    # and it closes the disc: every outside pixel touching the disc is a ring pixel
    assert (ring == (near & ~g.inside)).all()
