"""The mouse's readouts (render/pick.py): what a click on the lit sphere, the lit plane, the
θh×θd slice and the f(θh)/f(θd) plots reads, and the light a drag on the sphere sets.

Expected values are computed here from the geometry as the docs state it, not by the code
under test: the sphere's normal from the orthographic disc (core/views/lit.py's docstring),
the half/difference directions from Rusinkiewicz 1998 written out below, the values from the
public ``tuibrdf.evaluate``.  The readout prints 3 significant digits: rel 5e-3."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

import tuibrdf
from tuibrdf.core.material import Material
from tuibrdf.core.views.frame import FrameRequest, compute_frame
from tuibrdf.render import pick
from tuibrdf.render.halfdiff_view import MARGIN
from tuibrdf.render.views import extra_pixels

WARD = "tests/data/brdf/ward.brdf"
ANISO = {"alpha_x": 0.1, "alpha_y": 0.5}


def frame(model, params, view, w, h, theta_i=35.0, phi_i=180.0, **kw):
    req = FrameRequest((Material(model, params),), theta_i, extra=view,
                       extra_px=extra_pixels(view, w, h), phi_i=phi_i, **kw)
    return compute_frame(req)


def incident(theta, phi):
    t, p = math.radians(theta), math.radians(phi)
    return np.array([math.sin(t) * math.cos(p), math.sin(t) * math.sin(p), math.cos(t)])


def shown(text: str, key: str) -> list[float]:
    m = re.search(re.escape(key) + r"=\(?([-+0-9.e,]+)\)?", text)
    assert m, (key, text)
    return [float(x) for x in m.group(1).split(",")]


def normal_at(x, y, px_w, px_h):
    """The disc of radius min(px)/2 centred in the image, the cell's centre between its two
    half-block pixels (y counted from the title row)."""
    rad = min(px_w, px_h) / 2
    u = (x + 0.5 - px_w / 2) / rad
    v = (px_h / 2 - (2 * (y - 1) + 1)) / rad
    return np.array([u, v, math.sqrt(1 - u * u - v * v)])


@pytest.mark.parametrize("cell", [(30, 10), (50, 20), (12, 18), (33, 30), (40, 3)])
@pytest.mark.parametrize("model,params", [("phong", {"kd": 0.2, "ks": 0.6, "n": 30}),
                                          (WARD, ANISO), ("gltf", {"roughness": 0.4})])
def test_click_on_the_sphere_reads_f_there(cell, model, params):
    w, h = 66, 37
    res = frame(model, params, "sphere", w, h, phi_i=150.0)
    got = pick.pick(res, "sphere", 0, *cell, w, h)
    n = normal_at(*cell, w, 2 * (h - 1))
    light = incident(35.0, 150.0)
    # what does not depend on the tangent: the two cosines and the angle between wi and wo
    assert got.wi[2] == pytest.approx(n @ light, abs=1e-12)
    assert got.wo[2] == pytest.approx(n[2], abs=1e-12)
    assert got.wi @ got.wo == pytest.approx(light[2], abs=1e-12)
    # the tangent: the sample's x axis projected (T = normalise(e_x − n_x n))
    t = np.array([1.0, 0, 0]) - n[0] * n
    t /= np.linalg.norm(t)
    assert got.wi[0] == pytest.approx(t @ light, abs=1e-12)
    f = np.atleast_1d(tuibrdf.evaluate(model, params, got.wi, got.wo))
    text = pick.reading(res, got)
    if len(set(f"{v:.3g}" for v in f)) > 1:
        assert shown(text, " f") == pytest.approx(list(f), rel=5e-3)
    else:
        assert shown(text, " f") == pytest.approx([f[0]], rel=5e-3)
    assert shown(text, "f·cosθi") == pytest.approx(list(f * (n @ light)) if len(
        shown(text, "f·cosθi")) > 1 else [f[0] * (n @ light)], rel=5e-3)
    th = math.degrees(math.acos(n[2]))
    assert f"N θ={th:.1f}°" in text


def test_click_off_the_sphere_reads_nothing():
    res = frame("phong", {}, "sphere", 66, 37)
    assert pick.pick(res, "sphere", 0, 0, 1, 66, 37) is None  # a corner
    assert pick.pick(res, "sphere", 0, 33, 0, 66, 37) is None  # the title


@pytest.mark.parametrize("cell", [(33, 18), (10, 18), (60, 18), (33, 3), (33, 34)])
def test_drag_on_the_sphere_puts_the_light_along_the_normal(cell):
    px = (66, 72)
    th, ph = pick.light_at(*cell, px)
    n = normal_at(*cell, *px)
    assert th == pytest.approx(math.degrees(math.acos(n[2])), abs=1e-9)
    assert ph == pytest.approx(math.degrees(math.atan2(n[1], n[0])) % 360.0, abs=1e-9)
    # left of the centre: the light on the −x side (φ near 180°), as the default light
    if cell == (10, 18):
        assert abs(ph - 180.0) < 5.0


def test_drag_off_the_sphere_puts_the_light_on_the_horizon():
    assert pick.light_at(79, 18, (80, 72)) == pytest.approx((90.0, 0.0), abs=2.0)
    th, ph = pick.light_at(33, 1, (66, 72))  # above the top: the light at φ = 90°
    assert th == 90.0 and ph == pytest.approx(90.0, abs=1.0)


@pytest.mark.parametrize("phi_i", [180.0, 300.0, 45.0])
def test_the_lit_plane_centre_reads_the_mirror_direction(phi_i):
    w, h = 80, 30
    res = frame("phong", {"kd": 0.1, "ks": 0.5, "n": 40}, "plane", w, h, 50.0, phi_i)
    got = pick.pick(res, "plane", 0, w // 2, h // 2, w, h)
    light = incident(50.0, phi_i)
    mirror = np.array([-light[0], -light[1], light[2]])
    # the centre cell is within a pixel of the image centre (fov 40° over 58 pixels: 0.7°)
    assert math.degrees(math.acos(min(1.0, got.wo @ mirror))) < 1.5
    np.testing.assert_allclose(got.wi, light, atol=1e-12)
    f = float(tuibrdf.evaluate("phong", {"kd": 0.1, "ks": 0.5, "n": 40}, light, got.wo))
    assert shown(pick.reading(res, got), " f")[0] == pytest.approx(f, rel=5e-3)


def rusinkiewicz(theta_h, theta_d, phi_d):
    """(wi, wo) from half/difference angles with φh = 0: wi = Ry(θh)·d(θd, φd), wo its
    mirror about H = (sin θh, 0, cos θh)."""
    th, td, pd = (math.radians(a) for a in (theta_h, theta_d, phi_d))
    d = np.array([math.sin(td) * math.cos(pd), math.sin(td) * math.sin(pd), math.cos(td)])
    ry = np.array([[math.cos(th), 0, math.sin(th)], [0, 1, 0], [-math.sin(th), 0, math.cos(th)]])
    wi = ry @ d
    hv = np.array([math.sin(th), 0, math.cos(th)])
    return wi, 2 * (hv @ wi) * hv - wi


@pytest.mark.parametrize("cell", [(MARGIN, 1), (MARGIN + 20, 5), (MARGIN + 41, 12)])
def test_click_on_the_slice_reads_the_value_drawn_there(cell):
    w, h = 50, 16
    params = {"kd": 0.0, "f0": 0.04, "m": 0.2}
    res = frame("cook-torrance", params, "slice", w, h, phi_d=90.0)
    got = pick.pick(res, "slice", 0, *cell, w, h)
    f_img, valid, th, td = res.sides[0].extra
    col, row = cell[0] - MARGIN, cell[1] - 1
    k = len(td) - 1 - 2 * row  # θd up: the cell's upper pixel
    assert f"θh={th[col]:.1f}° θd={td[k]:.1f}°" in got.where
    wi, wo = rusinkiewicz(th[col], td[k], 90.0)
    np.testing.assert_allclose(got.wi, wi, atol=1e-12)
    np.testing.assert_allclose(got.wo, wo, atol=1e-12)
    f = float(tuibrdf.evaluate("cook-torrance", params, wi, wo))
    assert f == pytest.approx(float(f_img[k, col]), rel=1e-12)  # the drawn sample
    assert shown(pick.reading(res, got), " f")[0] == pytest.approx(f, rel=5e-3)


@pytest.mark.parametrize("view", ["theta-h", "theta-d"])
def test_click_on_a_line_plot_reads_f_at_that_angle(view):
    w, h = 60, 14
    params = {"kd": 0.1, "ks": 0.6, "n": 50}
    res = frame("blinn-phong", params, view, w, h, theta_d=20.0, theta_h=10.0, phi_d=90.0)
    x = MARGIN + 17
    got = pick.pick(res, view, 0, x, 5, w, h)
    a = 90.0 * (17 + 0.5) / (w - MARGIN)
    wi, wo = rusinkiewicz(a, 20.0, 90.0) if view == "theta-h" else rusinkiewicz(10.0, a, 90.0)
    np.testing.assert_allclose(got.wi, wi, atol=1e-12)
    f = float(tuibrdf.evaluate("blinn-phong", params, wi, wo))
    assert shown(pick.reading(res, got), " f")[0] == pytest.approx(f, rel=5e-3)
    assert pick.pick(res, view, 0, 2, 5, w, h) is None  # the y labels


def test_equal_channels_read_as_one_value():
    assert pick.values_text(np.array([0.25, 0.25, 0.25])) == "0.25"
    assert pick.values_text(np.array([0.25, 0.5, 0.25])) == "(0.25,0.5,0.25)"
