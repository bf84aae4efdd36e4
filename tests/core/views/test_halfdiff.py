"""Half/difference-angle views' numbers (``tuibrdf.core.views.halfdiff``; the pictures:
tests/render/test_halfdiff_view.py).

Expected values: the inverse map ``merl.half_diff`` (a separate implementation of the
coordinates), closed forms of models that live naturally in these coordinates (normalised
Blinn-Phong depends on θh only; Lambert is constant), the φd = 0 horizon θh + θd = 90° (from
the rotation: wi_z = cos(θh + θd), wo_z = cos(θh − θd)), and MERL's bin layout.
"""

from __future__ import annotations

import numpy as np
import pytest

from tuibrdf.core.formats.merl import N_THETA_H, half_diff
from tuibrdf.core.registry import MODELS, get_model
from tuibrdf.core.views.halfdiff import (
    directions,
    scale_max,
    slice_image,
    theta_d_curve,
    theta_h_axis,
    theta_h_curve,
)

BP = {"kd": 0.1, "ks": 0.6, "n": 50}


def blinn_phong(theta_h_deg):
    # gKit2's normalised Blinn-Phong: kd/π + ks (n+8)/(8π) cos^n θh
    return BP["kd"] / np.pi + BP["ks"] * (BP["n"] + 8) / (8 * np.pi) * np.cos(
        np.radians(theta_h_deg)) ** BP["n"]


def test_round_trip_angles_directions_angles():
    rng = np.random.default_rng(13)
    th = rng.uniform(0, 89, 2000)
    td = rng.uniform(0, 89, 2000)
    pd = rng.uniform(0, 180, 2000)
    wi, wo, valid = directions(th, td, pd)
    assert np.allclose(np.linalg.norm(wi, axis=-1), 1)
    assert np.allclose(np.linalg.norm(wo, axis=-1), 1)
    assert np.array_equal(valid, (wi[:, 2] > 1e-12) & (wo[:, 2] > 1e-12))
    h, d, p, ok = half_diff(wi, wo)
    assert ok.all()
    assert np.allclose(np.degrees(h), th, atol=1e-9)
    assert np.allclose(np.degrees(d), td, atol=1e-9)
    # φd is folded to [0°, 180°] by reciprocity; ours is drawn there already (θd > 0)
    assert np.allclose(np.degrees(p), pd, atol=1e-7)


def test_phi_d_zero_horizon_is_theta_h_plus_theta_d_90():
    f, valid, th, td = slice_image(get_model("lambert"), {"kd": 1.0}, 0.0, n_h=45, n_d=45,
                                   sqrt_h=False)
    assert np.array_equal(valid, th[None, :] + td[:, None] < 90.0)
    # Lambert: kd/π wherever both directions are above the horizon, 0 elsewhere
    assert np.allclose(f[valid], 1 / np.pi) and np.all(f[~valid] == 0.0)


def test_blinn_phong_depends_on_theta_h_only():
    m = get_model("blinn-phong")
    v = m.resolve(BP)
    th, f, valid = theta_h_curve(m, v, 20.0, 90.0)
    assert valid[:-1].all() and not valid[-1]  # θh = 90° puts both directions on the horizon
    assert np.allclose(f[valid], blinn_phong(th[valid]), rtol=1e-12)
    td, g, valid = theta_d_curve(m, v, 12.0, 45.0)
    assert np.allclose(g[valid], blinn_phong(12.0), rtol=1e-12)
    img, valid, th, td = slice_image(m, v, 90.0, n_h=30, n_d=20)
    assert np.allclose(img, np.where(valid, blinn_phong(th)[None, :], 0.0), rtol=1e-12)


def test_sqrt_axis_puts_one_sample_in_each_merl_bin():
    # MERL's θh bin, as BRDFRead.cpp's theta_half_index writes it: int(√(θh/90°)·90)
    th = theta_h_axis(N_THETA_H, sqrt_h=True)
    i_h = np.floor(np.sqrt(th / 90.0) * 90).astype(int)
    assert i_h.tolist() == list(range(N_THETA_H))
    lin = theta_h_axis(4, sqrt_h=False)
    assert lin.tolist() == [11.25, 33.75, 56.25, 78.75]


def test_scale_max_ignores_grazing_values():
    # Cook-Torrance's 1/(cos θi cos θo) grows without bound at grazing θd: the scale is the
    # largest value with both directions within 85° of the normal, which at θh = 5°, φd = 90°
    # (wi_z = wo_z = cos θh cos θd) means cos θd ≥ cos 85°/cos 5°
    m = get_model("cook-torrance")
    v = m.resolve({})
    td, f, valid = theta_d_curve(m, v, 5.0, 90.0, n=901)
    s = scale_max(f, 5.0, td, 90.0)
    inner = np.cos(np.radians(5.0)) * np.cos(np.radians(td)) >= np.cos(np.radians(85.0))
    assert s == pytest.approx(float(np.max(f[inner])))
    assert np.max(f[valid]) > 100 * s


@pytest.mark.parametrize("name", sorted(n for n in MODELS if n != "merl"))
def test_every_model_slice_is_finite(name):
    m = get_model(name)
    f, valid, _, _ = slice_image(m, m.resolve({}), 90.0, n_h=40, n_d=40)
    assert np.all(np.isfinite(f)) and np.all(f >= 0)
