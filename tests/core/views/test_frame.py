"""One frame, one truth (issue 11): the one peak finder, the frame request/result, and the
panes that all draw from it (tuibrdf/core/sphere/peak.py, core/views/frame.py,
render/panes.py); the material value is tests/core/test_material.py's.

Expected values come from outside the code under test: closed forms (Lambert kd/π, Phong's
mirror value (n+2)/(2π)·ks), an independent brute-force search over a dense (θ, φ) grid written
here, and the registry's own declarations (ranges, constraints).
"""

from __future__ import annotations

import dataclasses
import re

import numpy as np
import pytest
from rich.console import Console

from tuibrdf.core.conventions import fmt_value, luminance
from tuibrdf.core.directions import from_degrees, incident
from tuibrdf.core.evaluate import evaluate
from tuibrdf.core.material import Material
from tuibrdf.core.registry import MODELS
from tuibrdf.core.sphere.peak import find_peaks
from tuibrdf.core.views import frame as core_frame
from tuibrdf.core.views.hemimap import geometry
from tuibrdf.render import panes
from tuibrdf.render.views import map_pixels

# ------------------------------------------------------------------------------------ peak


def dense_max(model: str, params: dict, theta_i: float, channel=None) -> tuple[float, float]:
    """Brute force, independent of the finder: f on a (θ, φ) grid of 0.05° × 0.5° plus the
    horizon (θ = 90° exactly); returns the largest value and its θ."""
    th = np.concatenate([np.arange(0.0, 90.0, 0.05), [90.0]])
    ph = np.arange(-180.0, 180.0, 0.5)
    wo = from_degrees(th[:, None], ph[None, :]).reshape(-1, 3)
    f = np.asarray(evaluate(model, params, incident(theta_i), wo))
    if f.ndim == 2:
        f = luminance(f) if channel is None else f[:, channel]
    k = int(np.argmax(f))
    return float(f[k]), float(th[k // len(ph)])


@pytest.mark.parametrize("model,params,theta_i", [
    ("cook-torrance", {"kd": 0.0, "f0": 0.04, "m": 0.07}, 80.0),  # the seed lobe
    ("ggx", {"alpha": 0.05}, 85.0),  # the two-finders case: the horizon
    ("cook-torrance", {"kd": 0.0, "f0": 0.04, "m": 0.07}, 60.0),  # off-specular
    ("oren-nayar", {}, 60.0),  # back-scattering: peak on the light's side
    ("disney-diffuse", {}, 85.0),  # RGB, grazing
    ("phong", {}, 30.0),
    ("cook-torrance", {}, 37.0),  # the search from the mirror climbs a lower local maximum
    ("gltf", {}, 37.0),
])
def test_peak_is_at_least_the_dense_grid_maximum(model, params, theta_i):
    m = MODELS[model]
    pk = find_peaks(m, m.resolve(params), incident(theta_i))[0]
    ref, ref_theta = dense_max(model, params, theta_i)
    # the finder optimises off the grid: never below the grid's best, and not above the
    # function's value at its own direction
    assert pk.value >= ref * (1 - 1e-9)
    at = np.asarray(evaluate(model, params, incident(theta_i), from_degrees(pk.theta_deg,
                                                                            pk.phi_deg)))
    assert (luminance(at) if at.ndim else at) == pytest.approx(pk.value, rel=1e-9)
    assert pk.theta_deg == pytest.approx(ref_theta, abs=0.5)


def test_peak_closed_forms():
    # Phong's lobe peaks on the mirror direction with (n+2)/(2π)·ks (+ kd/π)
    pk = find_peaks(MODELS["phong"], MODELS["phong"].resolve({"kd": 0, "ks": 1, "n": 2000}),
                    incident(40))[0]
    assert pk.value == pytest.approx(2002 / (2 * np.pi), rel=1e-9)
    assert (pk.theta_deg, pk.phi_deg) == pytest.approx((40.0, 0.0), abs=1e-4)
    # Lambert: kd/π; f·cos θr peaks at the normal with kd/π
    lam = MODELS["lambert"]
    assert find_peaks(lam, lam.resolve({"kd": 0.5}), incident(30))[0].value == pytest.approx(
        0.5 / np.pi)
    pk = find_peaks(lam, lam.resolve({"kd": 0.5}), incident(30), cosine=True)[0]
    assert pk.value == pytest.approx(0.5 / np.pi) and pk.theta_deg < 1e-3


def test_rgb_peaks_luminance_and_each_channel():
    params = {"base_color": (0.9, 0.2, 0.05), "metallic": 1.0, "roughness": 0.3}
    m = MODELS["ue4"]
    peaks = find_peaks(m, m.resolve(params), incident(50))
    assert [p.label for p in peaks] == ["Y", "R", "G", "B"]
    for p, ch in zip(peaks, (None, 0, 1, 2), strict=True):
        ref, _ = dense_max("ue4", params, 50, ch)
        assert p.value >= ref * (1 - 1e-9)
    assert peaks[1].value > peaks[2].value > peaks[3].value  # a red base colour


# ----------------------------------------------------------------------- one evaluation


def counting(monkeypatch, name: str) -> list[int]:
    """Wrap a registered model's kernel; returns the list of row counts of every call."""
    calls: list[int] = []
    m = MODELS[name]

    def kernel(wi, wo, **kw):
        calls.append(int(np.prod(np.shape(wo)[:-1])))
        return m.kernel(wi, wo, **kw)

    monkeypatch.setitem(MODELS, name, dataclasses.replace(m, kernel=kernel))
    return calls


def test_each_pane_is_evaluated_once_and_a_repeated_frame_is_free(monkeypatch):
    core_frame.clear_caches()
    calls = counting(monkeypatch, "phong")
    mat = Material("phong", {"kd": 0.1, "ks": 0.5, "n": 40})
    px = map_pixels(60, 20)
    req = core_frame.FrameRequest((mat,), 33.0, map_px=px, solid=True)
    core_frame.compute_frame(req, slow=False)
    n_map = int(geometry(*px).inside.sum())
    n_sections = 3 * len(core_frame.SECTION_THETAS)  # both planes and the peak section: one call
    n_solid = len(core_frame.solid_directions()[0])
    assert calls.count(n_map) == 1 and calls.count(n_sections) == 1
    assert calls.count(n_solid) == 1
    calls.clear()
    assert core_frame.compute_frame(req, slow=False) is core_frame.compute_frame(req, slow=False)
    assert calls == []  # cached by request


def test_the_request_makes_wi_once_and_every_part_takes_it(monkeypatch):
    # the light's direction is the request's: read-only, not part of the key (a function of
    # θi and the normalised φi), and no part of the frame turns θi into wi again
    import sys

    req = core_frame.FrameRequest((Material("ggx"),), 41.0, phi_i=-30.0, map_px=(40, 30),
                             solid=True, probe=(0.3, -0.2), extra="sphere", extra_px=(20, 16))
    assert req.phi_i == 330.0 and np.array_equal(req.wi, incident(41.0, 330.0))
    assert not req.wi.flags.writeable
    assert req == dataclasses.replace(req) and hash(req) == hash(dataclasses.replace(req))

    def no_conversion(*a, **kw):
        raise AssertionError("θi turned into wi again")

    for name, mod in list(sys.modules.items()):
        if name.startswith("tuibrdf.") and getattr(mod, "incident", None) is incident:
            monkeypatch.setattr(mod, "incident", no_conversion)
    core_frame.clear_caches()
    side = core_frame.compute_frame(req, slow=False).sides[0]
    monkeypatch.undo()
    assert side.map is not None and side.solid is not None and side.extra is not None
    assert side.probe[0] == pytest.approx(float(evaluate("ggx", {}, incident(41.0, 330.0),
                                                         req.probe_direction)), rel=1e-12)


# ----------------------------------------------------------------- every pane agrees


def text(renderable, width=200) -> str:
    con = Console(width=width, color_system=None)
    with con.capture() as cap:
        con.print(renderable)
    return cap.get()


#: the number of a scale that is not the peak (core/horizon.py), long or short wording
SCALE_RE = r"scale(?::? max θ≤89°)? ([0-9.e+-]+)"


def numbers(res, view, look, w, h):
    """(title peak, colour bar top, status peak, status albedo) as printed; when the
    picture's scale is not its peak (the peak above 89° or unbounded), the scale's number in
    the title and the status line instead of the peak's."""
    out = text(panes.pane(view, res, 0, w, h, look), w).rstrip("\n").split("\n")
    what = SCALE_RE if panes.shown_scale(res.sides[0], view, look).capped \
        else r"peak ([0-9.e+-]+)"
    title = re.search(what, out[0]).group(1)
    bar = re.findall(r"([0-9.e+-]+) sr⁻¹", out[-1])[-1] if view == "map" else None
    stats = text(panes.stats_text(res, view, look))
    status = re.search(what, stats).group(1)
    albedo = re.search(r"a\(θi\)=(\S+)", stats).group(1)
    return title, bar, status, albedo


@pytest.mark.parametrize("model,params,theta_i,size", [
    ("cook-torrance", {"kd": 0.0, "f0": 0.04, "m": 0.07}, 80.0, (88, 46)),  # seed, 160×48
    ("ggx", {}, 90.0, (44, 22)),  # grazing light, 80×24
    ("ggx", {"alpha": 0.05}, 85.0, (88, 46)),  # a sharp lobe at grazing incidence
    ("ue4", {"base_color": (0.9, 0.2, 0.05)}, 45.0, (60, 20)),  # RGB: which peak is said
])
@pytest.mark.parametrize("cmap", ["grey", "viridis"])
def test_title_colour_bar_and_status_show_one_peak(model, params, theta_i, size, cmap):
    mat = Material(model, params)
    w, h = size
    req = core_frame.FrameRequest((mat,), theta_i, map_px=map_pixels(w, h), solid=True)
    res = core_frame.compute_frame(req)
    look = panes.Look(color="none", cmap=cmap, levels=32)
    expected = fmt_value(panes.shown_scale(res.sides[0], "map", look).value)
    title, bar, status, albedo = numbers(res, "map", look, w, h)
    assert title == bar == status == expected
    # the albedo shown is the core quadrature's at this θi
    from tuibrdf.core.sphere.albedo import albedo as quad_albedo

    a = np.atleast_1d(quad_albedo(model, params, theta_i))
    assert albedo.strip("()").split(",") == [fmt_value(x) for x in a]
    # the solid says the same peak (the luminance for RGB models, labelled)
    sol_title, _, sol_status, _ = numbers(res, "solid", look, w, h)
    assert sol_title == sol_status == fmt_value(panes.shown_scale(res.sides[0], "solid",
                                                                  look).value)
    # the sections say "section max", never "peak", and never more than the peak
    sec = text(panes.pane("incidence", res, 0, w, h, look), w).split("\n")[0]
    # ("max" alone where the radial scale needs the room, issue 36)
    assert re.search(r"\b(section )?max\b", sec) and "peak" not in sec
    assert res.sides[0].section_max <= max(p.value for p in res.sides[0].peaks) * (1 + 1e-12)


def test_rgb_screen_says_which_peak():
    mat = Material("ue4", {"base_color": (0.9, 0.2, 0.05)})
    res = core_frame.compute_frame(core_frame.FrameRequest((mat,), 45.0, map_px=map_pixels(60, 20)))
    grey = text(panes.stats_text(res, "map", panes.Look(cmap="grey")))
    lum = text(panes.stats_text(res, "map", panes.Look(cmap="viridis")))
    assert "(red)" in grey and "(Y)" in lum  # channels in colour: the red channel tops the bar


def test_compare_colour_bar_tops_at_the_larger_peak_and_says_whose():
    # the case: specular compare at 80×24 drew a bar topped at 0.621 beside a peak of
    # 6.14; both maps now share the scale of the larger peak, and the bar says it is B's
    a = Material("phong", {"kd": 0.0, "ks": 0.08, "n": 70.0})
    b = Material("cook-torrance", {"kd": 0.0, "f0": 0.04, "m": 0.07})
    req = core_frame.FrameRequest((a, b), 60.0, map_px=map_pixels(22, 9))
    res = core_frame.compute_frame(req, slow=False)
    look = panes.Look(color="none", levels=32)
    pb = res.sides[1].peak.value
    assert pb > res.sides[0].peak.value
    for k in (0, 1):
        bar = text(panes.pane("map", res, k, 40, 9, look), 40).rstrip("\n").split("\n")[-1]
        assert f"{fmt_value(pb)} sr⁻¹ (B peak)" in bar


def test_energy_test_is_the_quadratures_one():
    # one energy test in the package: albedo − error > 1 (quadrature.exceeds_one); the
    # fixed-tolerance test of conventions is gone and the frame's flags use the estimate
    from dataclasses import replace

    from tuibrdf.core import conventions

    assert not hasattr(conventions, "ENERGY_TOL") and not hasattr(conventions, "exceeds_one")
    res = core_frame.compute_frame(core_frame.FrameRequest((Material("lambert"),), 10, curve=True))
    side = res.sides[0]
    # lambert kd = 0.8 (the default): ∫ kd/π cos θ dω = kd, and the error estimate is tiny
    assert side.albedo == pytest.approx(0.8, abs=1e-12) and 0 <= side.albedo_error < 1e-9
    assert side.curve_error.shape == side.curve.shape and np.all(side.curve_error >= 0)
    for a, err, flagged in ((1.0005, 1e-3, False), (1.002, 1e-3, True), (1.0005, 1e-5, True),
                            ((0.5, 1.01, 0.2), (0.0, 0.02, 0.0), False),
                            ((0.5, 1.01, 0.2), (0.0, 0.001, 0.0), True)):
        fake = replace(side, albedo=a, albedo_error=err)
        assert fake.albedo_exceeds_one() == flagged
        line = panes.stats_text(replace(res, sides=(fake,)), "map", panes.Look()).plain
        assert ("NOT energy-conserving" in line) == flagged, line


@pytest.mark.parametrize("theta_i", [0.0, 85.0, 88.0, 89.0, 89.9, 90.0])
def test_sharp_conserving_lobe_is_never_flagged(theta_i):
    # ggx α = 0.001, f0 = 1, kd = 0: a perfect mirror's microfacet lobe; with F = 1 and the
    # Smith masking-shadowing ≤ 1 its albedo is at most 1 at every incidence (issue 18: the old
    # mesh quadrature gave 1.89 at 85° and 18.6 at 90°)
    m = Material("ggx", {"alpha": 0.001, "f0": 1.0, "kd": 0.0})
    side = core_frame.compute_frame(core_frame.FrameRequest((m,), theta_i)).sides[0]
    assert side.albedo - side.albedo_error <= 1.0 and not side.albedo_exceeds_one()
    line = panes.stats_text(core_frame.compute_frame(core_frame.FrameRequest((m,), theta_i)), "map",
                            panes.Look()).plain
    assert "NOT energy-conserving" not in line


def test_model_gaining_energy_is_flagged():
    # ggx with kd = 1: its Lambert term alone reflects exactly 1 (∫ 1/π cos θ dω = 1) and the
    # specular (f0 = 0.5, α = 0.2) adds a positive amount on top, so the truth is > 1
    m = Material("ggx", {"kd": 1.0, "f0": 0.5})
    for theta_i in (0.0, 60.0):
        res = core_frame.compute_frame(core_frame.FrameRequest((m,), theta_i, curve=True))
        side = res.sides[0]
        assert side.albedo_exceeds_one() and side.curve_exceeds_one()
        assert "NOT energy-conserving" in panes.stats_text(res, "map", panes.Look()).plain


ANGLES = [0.0, -0.0, 90.0, 180.0, 270.0, 360.0, 720.0, -90.0, -180.0, -270.0, -360.0, 45.0,
          30.0, 60.0, 89.9, 89.999999, 90.000001, -1e-20, 1e-300, 1e-20, 1234.5678, -987.654,
          1e15, 0.5, 359.9999999]


@pytest.mark.parametrize("t", ANGLES + list(np.random.default_rng(5).uniform(-720, 720, 40)))
def test_sincos_deg_of_one_angle_is_the_array_path_to_the_bit(t):
    """One float takes a path without numpy's 0-d arrays (θi and φi every frame); it must give
    the numbers the array path gives for the same angle, to the last bit, exact at multiples
    of 90° (independent check: the values at those angles, written here)."""
    from tuibrdf.core.directions import sincos_deg

    s1, c1 = sincos_deg(float(t))
    s2, c2 = sincos_deg(np.array([t]))
    assert np.float64(s1).tobytes() == s2[0].tobytes()
    assert np.float64(c1).tobytes() == c2[0].tobytes()
    if float(t) % 90.0 == 0.0:
        k = round(float(t) % 360.0 / 90.0) % 4
        assert (float(s1), float(c1)) == ((0.0, 1.0), (1.0, 0.0), (0.0, -1.0), (-1.0, 0.0))[k]


def test_the_solid_is_evaluated_once_at_each_distinct_direction():
    # a barycentric grid of s = SOLID_SUBDIV steps on each triangle of the mesh: its corners
    # are the V vertices, each of the E edges has s − 1 points inside, each of the F faces
    # (s − 1)(s − 2)/2 inside; the face corners repeat vertices.  Every sample and corner is
    # one of those directions to within a few ulps (the same point made from two triangles)
    from tuibrdf.core.sphere.mesh import hemisphere

    mesh = hemisphere(core_frame.SOLID_LEVEL)
    s = core_frame.SOLID_SUBDIV
    faces = np.sort(mesh.faces, axis=1)
    edges = {tuple(e) for f in faces.tolist() for e in ((f[0], f[1]), (f[1], f[2]), (f[0], f[2]))}
    want = len(mesh.vertices) + (s - 1) * len(edges) + (s - 1) * (s - 2) // 2 * len(faces)
    distinct, take = core_frame.solid_directions()
    assert len(distinct) == want
    pts, _, tri = core_frame.solid_samples()
    every = np.concatenate([pts, tri.reshape(-1, 3)])
    assert take.shape == (len(every),)
    assert np.max(np.abs(distinct[take] - every)) <= 4 * 2.0**-52
    mat = Material("ggx", {"alpha": 0.3})
    f = core_frame.solid_values(mat, incident(40.0), False)
    assert np.allclose(f, evaluate("ggx", {"alpha": 0.3}, incident(40.0), every), rtol=1e-12,
                       atol=0.0)
