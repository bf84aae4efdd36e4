"""RGL-EPFL ``.bsdf`` measured materials: container validation and evaluation as powitacq.

Synthetic files (tests/rgl_writer.py) have a closed-form value: a linear VNDF density, whose
inverse warp is known in closed form, and rgb slices linear in every interpolated coordinate
(see the writer's docstring); nothing is downloaded.
"""

from __future__ import annotations

import time

import numpy as np
import pytest

import tuibrdf
from tests.core.formats.test_userfiles import sweep
from tests.rgl_writer import expected, material, tensor_bytes, write_tensor
from tuibrdf.cli import main
from tuibrdf.core.formats import rgl_bsdf
from tuibrdf.core.formats.userfiles import UserFileError
from tuibrdf.core.registry import get_model


def pairs(n=2000, seed=3):
    rng = np.random.default_rng(seed)
    d = rng.normal(size=(2, n, 3))
    d[..., 2] = np.abs(d[..., 2]) + 0.05
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    return d[0], d[1]


@pytest.mark.parametrize("jacobian", [True, False])
def test_isotropic_rgb_matches_the_closed_form(tmp_path, jacobian):
    f = write_tensor(tmp_path / "iso.bsdf", material(jacobian=jacobian))
    wi, wo = pairs()
    got = tuibrdf.evaluate(str(f), {}, wi, wo)
    np.testing.assert_allclose(got, expected(wi, wo, jacobian=jacobian), rtol=1e-12)


def test_anisotropic_interpolates_over_phi_i(tmp_path):
    # 5 φi samples over 360° (reduction 1); the value grows linearly with φi (k = 0.1)
    f = write_tensor(tmp_path / "aniso.bsdf", material(n_phi=5, k=0.1))
    wi, wo = pairs()
    got = tuibrdf.evaluate(str(f), {}, wi, wo)
    np.testing.assert_allclose(got, expected(wi, wo, k=0.1), rtol=1e-12)


def test_reduction_turns_into_the_measured_half(tmp_path):
    # φi grid over 180° (−180°…0°): directions with wi.y ≥ 0 are turned by 180° about the
    # normal (x → −x, y → −y, Mitsuba 3's reduction 2), so f(wi, wo) = f(R(wi), R(wo))
    f = write_tensor(tmp_path / "half.bsdf", material(n_phi=3, phi_span=np.pi, k=0.1))
    wi, wo = pairs()
    flip = np.array([-1.0, -1.0, 1.0])
    a = tuibrdf.evaluate(str(f), {}, wi, wo)
    b = tuibrdf.evaluate(str(f), {}, wi * flip, wo * flip)
    np.testing.assert_allclose(a, b, rtol=1e-12)
    lower = wi[:, 1] < 0  # already in the measured half: the closed form holds there
    np.testing.assert_allclose(a[lower], expected(wi[lower], wo[lower], k=0.1), rtol=1e-12)


def test_float32_file_as_published(tmp_path):
    f = write_tensor(tmp_path / "f32.bsdf", material(dtype=np.float32))
    wi, wo = pairs(300)
    got = tuibrdf.evaluate(str(f), {}, wi, wo)
    np.testing.assert_allclose(got, expected(wi, wo), rtol=1e-6)  # float32 storage


def test_spectral_flat_spectrum_is_grey(tmp_path):
    # a spectrally flat value v under D65 through the CIE 1931 observer is the grey (v, v, v)
    # in linear sRGB (D65 is sRGB's white; the conversion is white-balanced to make it exact)
    wl = np.arange(360.0, 1001.0, 10.0)
    f = write_tensor(tmp_path / "spec.bsdf",
                     material(jacobian=False, spectral_values=(wl, np.full(wl.size, 0.5))))
    m = get_model(str(f))
    wi, wo = pairs(50)
    got = tuibrdf.evaluate(str(f), {}, wi, wo)
    want = 0.5 / wo[:, 2]  # the spectra are constant over the square: f·cos θo = 0.5
    np.testing.assert_allclose(got, np.repeat(want[:, None], 3, axis=1), rtol=1e-12)
    assert any("spectral" in n for n in m.notes)


def test_horizon_and_invalid_and_negative(tmp_path):
    fields = material()
    fields["rgb"] = fields["rgb"] - 0.5  # some channels go negative: clamped to 0
    fields["valid"][0, 0, 0, :3] = 0
    f = write_tensor(tmp_path / "neg.bsdf", fields)
    m = get_model(str(f))
    assert any("3 invalid entries" in n for n in m.notes)
    wi = np.array([[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.6, 0.0, 0.8]])
    wo = np.array([[0.0, 0.0, 1.0], [0.0, 0.0, 1.0], [-1.0, 0.0, 0.0]])
    got = tuibrdf.evaluate(str(f), {}, wi, wo)
    assert np.all(got >= 0) and np.all(np.isfinite(got))
    assert got[1].tolist() == [0, 0, 0]  # the light on the horizon
    raw = rgl_bsdf.evaluate(rgl_bsdf.load(f), wi[:1], wo[:1], clamp=False)
    assert raw[0, 0] < 0 and got[0, 0] == 0.0


def test_stability_sweep(tmp_path):
    f = write_tensor(tmp_path / "stab.bsdf", material(n_phi=5, k=0.1))
    assert sweep(get_model(str(f))) > 0


def test_cli_eval_and_render(tmp_path, capsys):
    f = write_tensor(tmp_path / "cli.bsdf", material())
    rc = main(["eval", str(f), "--theta-i", "30", "--theta-r", "30", "--phi-r", "0", "--json"])
    out, _ = capsys.readouterr()
    import json

    assert rc == 0
    v = json.loads(out)["values"][0]["f"]
    wi = np.array([-0.5, 0.0, np.sqrt(0.75)])
    wo = np.array([0.5, 0.0, np.sqrt(0.75)])
    np.testing.assert_allclose(v, expected(wi, wo), rtol=1e-12)
    rc = main(["render", str(f), "--width", "20", "--height", "8", "--no-color"])
    assert rc == 0


# --------------------------------------------------------------------------- malformed files


def good_bytes():
    return tensor_bytes(material(n=3, n_theta=2))


def bsdf_error(tmp_path, data: bytes, capsys=None) -> str:
    f = tmp_path / "bad.bsdf"
    f.write_bytes(data)
    with pytest.raises(UserFileError) as e:
        get_model(str(f))
    msg = str(e.value)
    assert "\n" not in msg and msg.startswith(str(f)), msg
    return msg


def test_good_bytes_load(tmp_path):
    (tmp_path / "ok.bsdf").write_bytes(good_bytes())
    assert get_model(str(tmp_path / "ok.bsdf")).rgb


@pytest.mark.parametrize("cut", [0, 5, 13, 17, 20, 40, 100])
def test_truncated_header(tmp_path, cut):
    msg = bsdf_error(tmp_path, good_bytes()[:cut])
    assert "truncated header" in msg or "wrong magic" in msg or "runs past the end" in msg


def test_truncated_data(tmp_path):
    data = good_bytes()
    msg = bsdf_error(tmp_path, data[:len(data) - 10])
    assert "runs past the end of the file" in msg


@pytest.mark.parametrize("kw,what", [
    ({"magic": b"tensor_fiel\0"}, "wrong magic"),
    ({"version": (2, 0)}, "unknown version 2.0"),
    ({"codes": {"ndf": 42}}, "unknown type code 42"),
    ({"offsets": {"rgb": 10**12}}, "runs past the end"),
    ({"shapes": {"vndf": (10**6, 10**6, 10**6, 10**6)}}, "runs past the end"),  # 8e24 bytes
    ({"shapes": {"ndf": (3, 10**9)}}, "runs past the end"),
])
def test_bad_header_fields(tmp_path, kw, what):
    t0 = time.perf_counter()
    msg = bsdf_error(tmp_path, tensor_bytes(material(n=3, n_theta=2), **kw))
    assert what in msg, msg
    assert time.perf_counter() - t0 < 5  # no giant allocation happened (generous bound)


def fields_with(**changes):
    f = material(n=3, n_theta=2)
    for k, v in changes.items():
        if v is None:
            del f[k]
        else:
            f[k] = v
    return f


@pytest.mark.parametrize("changes,what", [
    ({"rgb": None}, "missing field 'rgb'"),
    ({"vndf": None}, "missing field 'vndf'"),
    ({"jacobian": None}, "missing field 'jacobian'"),
    ({"ndf": np.ones((3, 3), dtype=np.int32)}, "type int32"),
    ({"ndf": np.ones(3)}, "has 1 dimensions, expected 2"),
    ({"vndf": np.ones((1, 3, 3, 3))}, "field 'vndf' has shape"),
    ({"rgb": np.ones((1, 2, 4, 3, 3))}, "4 channels, expected 3"),
    ({"rgb": np.ones((1, 2, 3, 5, 5))}, "field 'rgb' has shape"),
    ({"jacobian": np.array([1, 1], dtype=np.uint8)}, "'jacobian' must be one uint8"),
    ({"theta_i": np.array([0.5, 0.1])}, "strictly increasing"),
    ({"sigma": np.full((3, 3), np.nan)}, "9 NaN or infinite values"),
    ({"vndf": -np.ones((1, 2, 3, 3))}, "negative values"),
    ({"vndf": np.zeros((1, 2, 3, 3))}, "zero everywhere"),
    ({"rgb": None, "spectra": np.ones((1, 2, 4, 3, 3)),
      "wavelengths": np.array([400.0, 500, 600])}, "must list the 4 wavelengths"),
    ({"rgb": None, "spectra": np.ones((1, 2, 2, 3, 3)),
      "wavelengths": np.array([1000.0, 1100])}, "no wavelength in the visible range"),
])
def test_bad_fields(tmp_path, changes, what):
    msg = bsdf_error(tmp_path, tensor_bytes(fields_with(**changes)))
    assert what in msg, msg


def test_anisotropic_grid_with_a_strange_span(tmp_path):
    f = material(n=3, n_theta=2, n_phi=4, phi_span=2.0)  # 115°: no symmetry reduction
    msg = bsdf_error(tmp_path, tensor_bytes(f))
    assert "spans 114.6°" in msg


def test_cli_error_is_one_line(tmp_path, capsys):
    (tmp_path / "bad.bsdf").write_bytes(b"tensor_file\0\x01\x00")
    rc = main(["view", str(tmp_path / "bad.bsdf")])
    _, err = capsys.readouterr()
    assert rc == 2 and err.count("\n") == 1 and "truncated header" in err


def test_one_light_for_many_views_equals_per_direction(tmp_path):
    # a map evaluates one wi against many wo: the parameter slices are mixed once, which must
    # give what per-direction interpolation gives (every lookup is linear in the slices)
    f = write_tensor(tmp_path / "one.bsdf", material(n_phi=5, n_theta=4, k=0.1))
    data = rgl_bsdf.load(f)
    _, wo = pairs(500)
    wi = np.array([-0.3, 0.2, 0.9])
    wi /= np.linalg.norm(wi)
    one = rgl_bsdf.evaluate(data, wi, wo)
    many = rgl_bsdf.evaluate(data, np.broadcast_to(wi, wo.shape), wo)
    np.testing.assert_allclose(one, many, rtol=1e-13)
    np.testing.assert_allclose(one, expected(np.broadcast_to(wi, wo.shape), wo, k=0.1),
                               rtol=1e-12)


def test_grazing_views_divide_by_at_most_1_over_cos_89_9(tmp_path):
    # f·cos θo is stored; within 0.1° of the horizon cos θo is held at cos 89.9° (the synthetic
    # material's f·cos θo does not vanish there, as noisy grazing measurements need not)
    f = write_tensor(tmp_path / "graze.bsdf", material())
    t = np.radians(89.95)
    wi = np.array([[-0.5, 0.0, np.sqrt(0.75)]])
    wo = np.array([[np.sin(t), 0.0, np.cos(t)]])
    got = tuibrdf.evaluate(str(f), {}, wi, wo)
    want = expected(wi, wo) * np.cos(t) / np.cos(np.radians(89.9))
    np.testing.assert_allclose(got, want, rtol=1e-12)


def test_on_the_horizon_the_value_is_the_limit_from_above(tmp_path):
    # θo = 90° exactly: the held cos θo makes f continuous there, so the closed hemisphere's
    # supremum is a value the kernel gives (the peak finder's searches stop on it); the
    # synthetic f·cos θo is smooth, so 1e-9° above the horizon differs by O(1e-11) relative
    f = write_tensor(tmp_path / "edge.bsdf", material())
    wi = np.array([-0.5, 0.0, np.sqrt(0.75)])
    t = np.radians(90.0 - 1e-9)
    wo = np.array([[1.0, 0.0, 0.0], [np.sin(t), 0.0, np.cos(t)], [1.0, 0.0, -1e-300]])
    got = tuibrdf.evaluate(str(f), {}, np.broadcast_to(wi, wo.shape), wo)
    assert np.all(got[0] > 0)
    np.testing.assert_allclose(got[0], got[1], rtol=1e-9)
    assert got[2].tolist() == [0, 0, 0]  # below the horizon
    # the albedo's f, divided by cos θo itself, has no finite limit: 0 on the horizon
    own = rgl_bsdf.evaluate(rgl_bsdf.load(f), wi, wo[:1], floor=False)
    assert own.tolist() == [[0, 0, 0]]


def rough(fields: dict, seed=7) -> dict:
    """The synthetic material with random positive vndf, rgb, ndf and σ tables (same shapes):
    nothing is linear any more, so a wrong corner, slice or weight shows."""
    rng = np.random.default_rng(seed)
    out = dict(fields)
    for name in ("vndf", "rgb", "ndf", "sigma"):
        out[name] = rng.uniform(0.2, 1.5, size=fields[name].shape)
    return out


@pytest.mark.parametrize("kw", [
    dict(n_phi=1, n_theta=4, n=9),
    dict(n_phi=1, n_theta=8, n=32),
    dict(n_phi=2, n_theta=6, n=12, jacobian=False),
    dict(n_phi=3, n_theta=8, n=32, k=0.1),
    dict(n_phi=5, n_theta=3, n=7, k=0.2, phi_span=np.pi),  # reduction 2
    dict(n_phi=4, n_theta=5, n=16, k=0.3, phi_span=np.pi / 2),  # reduction 4
    dict(n_phi=1, n_theta=1, n=5),
])
@pytest.mark.parametrize("make", [material, lambda **kw: rough(material(**kw))],
                         ids=["linear", "rough"])
def test_one_light_fast_path_equals_the_general_path(tmp_path, kw, make):
    # One wi (shape (3,) or (1, 3)) takes the fast path: the (φi, θi) slices mixed once per
    # incidence (and kept), the four corners of a cell gathered per table.  The same wi
    # broadcast to every wo takes the general path: the slices mixed per direction at each
    # corner.  Both are the same linear combinations of the same table entries, at most
    # regrouped: a sum of m terms regrouped moves by ≤ m·2⁻⁵³ of Σ|terms| (m ≤ 16 here: 4
    # cell corners × ≤ 4 slices, ≤ 2e-15 of the largest value); the inverse warp's (x, y), a
    # few such sums and a quotient of them, move by ~1e-14 at most, and the rgb interpolation
    # turns a shift δ of its argument into ≤ 2·max·(n − 1)·δ (n ≤ 32: ~1e-12 of the maximum
    # at the very worst).  Hence 1e-12 of the maximum.  (As written today the two group
    # their sums alike and agree to the bit.)
    f = write_tensor(tmp_path / "fast.bsdf", make(**kw))
    data = rgl_bsdf.load(f)
    wis, wo = pairs(700, seed=11)
    wo = np.concatenate([wo, [[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.6, -0.8, 1e-9]]])
    lights = [*wis[:5], np.array([0.0, 0.0, 1.0]), np.array([-0.8, -0.6, 1e-3]),
              np.array([0.3, 0.4, -0.5])]  # normal, grazing, below the horizon
    for wi in lights:
        for clamp in (True, False):
            general = rgl_bsdf.evaluate(data, np.broadcast_to(wi, wo.shape), wo, clamp=clamp)
            tol = 1e-12 * np.abs(general).max()
            for one in (wi, wi[None]):
                for _ in range(2):  # the second time from the kept incidence
                    fast = rgl_bsdf.evaluate(data, one, wo, clamp=clamp)
                    assert fast.shape == general.shape
                    np.testing.assert_allclose(fast, general, rtol=0, atol=tol)
            np.testing.assert_allclose(rgl_bsdf.evaluate(data, wi, wo[7]), general[7], rtol=0,
                                       atol=tol)


def test_kept_incidences_are_bounded_and_per_file(tmp_path):
    # the slices mixed at an incidence live in the file's own RglData, at most LIGHT_CACHE of
    # them: another file (other values, the same grids) evaluated at the same wi is not
    # answered from this one's
    a = rgl_bsdf.load(write_tensor(tmp_path / "a.bsdf", material(n_phi=3, k=0.1)))
    b = rgl_bsdf.load(write_tensor(tmp_path / "b.bsdf", rough(material(n_phi=3, k=0.1))))
    wis, wo = pairs(50, seed=5)
    for wi in wis[:3 * rgl_bsdf.LIGHT_CACHE]:
        va, vb = rgl_bsdf.evaluate(a, wi, wo), rgl_bsdf.evaluate(b, wi, wo)
        np.testing.assert_allclose(va, expected(np.broadcast_to(wi, wo.shape), wo, k=0.1),
                                   rtol=1e-12)
        np.testing.assert_array_equal(vb, rgl_bsdf.evaluate(b, np.broadcast_to(wi, wo.shape),
                                                            wo))
    assert len(a.lights) == len(b.lights) == rgl_bsdf.LIGHT_CACHE
    light = rgl_bsdf._light(a, 0.1, 0.2)  # kept, and shared read-only
    assert rgl_bsdf._light(a, 0.1, 0.2) is light
    assert not light.vndf.data.flags.writeable and not light.den.flags.writeable
