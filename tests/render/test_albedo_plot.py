"""Albedo curve view (tuibrdf/render/albedo_plot.py, the pane in tuibrdf/render/panes.py; the
curve from tuibrdf/core/views/frame.py)."""

import numpy as np
import pytest
from rich.console import Console

from tuibrdf.core.material import Material
from tuibrdf.core.registry import MODELS
from tuibrdf.core.views import frame as core_frame
from tuibrdf.render import panes
from tuibrdf.render.views import render_view


def albedo_curve(model, values):
    """The frame's albedo curve (the one the pane draws), at :data:`core_frame.CURVE_THETAS`."""
    req = core_frame.FrameRequest((Material(model, values),), 0.0, curve=True)
    return core_frame.CURVE_THETAS, core_frame.compute_frame(req).sides[0].curve


def albedo_view(model, values, theta_i, w, h, color):
    return render_view("albedo", model, values, theta_i, w, h, color=color)


def text_of(r) -> str:
    con = Console(width=120, color_system=None)
    with con.capture() as cap:
        con.print(r)
    return cap.get()


def test_lambert_curve_is_kd():
    # ∫ kd/π cos θ dω = kd at every incidence (closed form); mesh quadrature to 1e-3
    thetas, a = albedo_curve(MODELS["lambert"], MODELS["lambert"].resolve({"kd": 0.6}))
    assert thetas[0] == 0 and thetas[-1] == 90
    assert a == pytest.approx(0.6, rel=1e-3)


def test_view_title_and_no_flag_for_lambert():
    m = MODELS["lambert"]
    out = text_of(albedo_view(m, m.resolve({"kd": 0.6}), 30, 60, 12, color="none"))
    first = out.split("\n")[0]
    assert first.startswith("lambert  a(θi=30°) = 0.6") and "a>1" not in first
    assert "\x1b" not in out and len(out.rstrip("\n").split("\n")) == 12


def test_flag_when_above_one():
    # a hand-made curve above 1 by more than its error estimate must be flagged with its
    # maximum; one within its error of 1 must not (quadrature.exceeds_one)
    from dataclasses import replace

    res = core_frame.compute_frame(core_frame.FrameRequest((Material("lambert"),), 10, curve=True))
    for top, err, flagged in ((1.2, 0.0, True), (1.0005, 1e-3, False), (1.0005, 1e-5, True)):
        fake = np.linspace(0.9, top, len(core_frame.CURVE_THETAS))
        side = replace(res.sides[0], curve=fake, curve_error=np.full_like(fake, err))
        out = text_of(panes.albedo_pane(replace(res, sides=(side,)), 70, 10,
                                        panes.Look(color="none")))
        first = out.split("\n")[0]
        assert (f"a>1 (max {top:.3g}): not energy-conserving" in first) == flagged, first


def test_rgb_curves():
    m = MODELS["gltf"]
    thetas, a = albedo_curve(m, m.resolve({}))
    assert a.shape == (len(thetas), 3)


def test_sharp_lobe_curve_matches_an_independent_rule():
    # the seed's Cook-Torrance (m = 0.07) against a Gauss-Legendre × midpoint tensor rule
    # (tests/quad.py, 400 × 1600 nodes, independent of the icosahedral mesh).  A uniform
    # level-5 mesh — what the viewer drew before — is off by 10 % at 87° (0.640 vs 0.582)
    from tests.quad import albedo as reference

    p = {"kd": 0, "f0": 0.04, "m": 0.07}
    m = MODELS["cook-torrance"]
    thetas, a = albedo_curve(m, m.resolve(p))
    for t in (0.0, 45.0, 75.0, 87.0):
        k = int(np.flatnonzero(thetas == t)[0])
        assert a[k] == pytest.approx(reference("cook-torrance", p, t, 400, 1600), rel=3e-3)


def cells(text):
    """Every cell of a Rich ``Text`` as (character, style), row by row."""
    con = Console(width=400, color_system="truecolor")
    return [[(ch, seg.style or None) for seg in line.render(con) for ch in seg.text]
            for line in text.split("\n", allow_blank=True)]


_T = core_frame.CURVE_THETAS
_A = 0.5 + 0.2 * np.cos(np.radians(_T))
MARKER_CASES = {  # one curve, one above 1 (the line a = 1 crossed), a legend, crossing curves
    "one": [("x", _A)],
    "above one": [("x", 1.3 - 0.4 * np.sin(np.radians(_T)) ** 2)],
    "compare": [("A: x", _A), ("B: y", 0.6 * _A)],
    "channels": [("R", _A), ("G", 0.9 * _A), ("B", 0.8 * _A)],
    "crossing": [("A", _A), ("B", _A[::-1])],
}


def assert_marker_is_plotexts_own(curves, sizes, thetas, color="truecolor"):
    """The viewer's plot of ``curves`` with its θi marker (drawn on the kept plot) against
    plotext drawing the marker itself: the same cells, character and colour, at every size
    and θi."""
    from tuibrdf.render import albedo_plot as ap

    styles = [ap._curve_style(j, c) for j, c in enumerate(curves)]
    top = ap.nice_top(max(float(np.max(a)) for _, a in curves))
    for w, h in sizes:
        for theta in thetas:
            want = ap.plot_body(ap._build(_T, curves, styles, top, w, h, theta, color), color)
            got = ap.albedo_plot(_T, curves, w, h, theta_i_deg=theta, color=color)
            assert cells(got) == cells(want), (w, h, theta)


@pytest.mark.parametrize("case", MARKER_CASES)
@pytest.mark.parametrize("color", ["truecolor", "none"])
def test_marker_drawn_on_the_kept_plot_is_plotexts_own(case, color):
    # the θi marker is drawn on a copy of the plot plotext drew without it; the reference is
    # plotext drawing the marker itself: the same cells (character and colour) at every size
    # and θi, including the legend's corner (θi near 0) and points off the θi grid
    assert_marker_is_plotexts_own(
        MARKER_CASES[case], ((70, 20), (40, 8), (121, 41)),
        (0.0, 0.5, 1.0, 2.0, 14.7, 29.99, 30.0, 45.25, 60.0, 89.5, 90.0), color)


@pytest.mark.parametrize("case", ["compare", "channels"])
def test_marker_beside_the_legend_is_plotexts_own(case):
    # θi from 0° to 15.5° by 0.5° puts the marker's line in every column of the legend's box
    # and just past it (the legend is drawn last: it hides the line and the points)
    assert_marker_is_plotexts_own(MARKER_CASES[case], ((70, 20),), np.arange(0.0, 16.0, 0.5))


def test_theta_key_builds_no_plot(monkeypatch):
    # a new θi on the same curves moves the marker on the kept plot: plotext is not asked
    from tuibrdf.render import albedo_plot as ap

    built = []
    build = ap._build
    monkeypatch.setattr(ap, "_build", lambda *a: built.append(a[6]) or build(*a))
    curves = [("x", 0.9 * _A)]  # not drawn by another test: not kept yet
    for theta in (10.0, 11.0, 12.5):
        ap.albedo_plot(_T, curves, 66, 18, theta_i_deg=theta)
    assert built == [None]  # the plot without its marker, once


#: a model file fine up to θi = 84°, NaN beyond (cos θi < 0.1)
NAN_AT_GRAZING = '''
import numpy as np
from tuibrdf.core.params import Model, Param

KD = Param("kd", "kd", 0.5, 0.0, 1.0, 0.01)


def f(wi, wo, kd):
    shape = np.broadcast_shapes(wi.shape, wo.shape)[:-1]
    return np.where(np.broadcast_to(wi[..., 2], shape) < 0.1, np.nan, np.full(shape, kd / np.pi))


MODEL = Model("nan_grazing", "NaN at grazing light", (KD,), f, summary="NaN for θi > 84°")
'''


def test_a_kernel_failing_at_another_incidence_leaves_this_one(tmp_path):
    # the albedo curve runs over θi = 0–90°, where this kernel returns NaN beyond 84°; at
    # θi = 30° it is f = kd/π: the albedo pane says why it has no curve, the frame is
    # complete with the albedo at 30° (kd = 0.5: a = 0.5) and the sections
    from tests.render.test_views import to_text
    from tuibrdf.core.formats.userfiles import load_model_file

    path = tmp_path / "nan_grazing.py"
    path.write_text(NAN_AT_GRAZING)
    m = Material(load_model_file(path), {"kd": 0.5})
    req = core_frame.FrameRequest((m,), 30.0, curve=True)
    res = core_frame.compute_frame(req)
    side = res.sides[0]
    assert res.complete and not core_frame.needs_curve(req)
    assert abs(side.albedo - 0.5) <= side.albedo_error + 1e-12
    assert abs(side.section_max - 0.5 / np.pi) <= 1e-15
    assert side.curve is None and "NaN" in side.curve_problem
    text = " ".join(to_text(panes.pane("albedo", res, 0, 60, 20, panes.Look(color="none")),
                            width=60).split())
    assert "no albedo curve" in text and "returned NaN" in text


@pytest.mark.parametrize("view", ["sphere", "slice", "theta-h", "theta-d"])
def test_an_extra_view_failing_elsewhere_leaves_the_panes_at_this_incidence(tmp_path, view):
    # each of these views runs over other incidences than the current one (the lit sphere's
    # local frames, the θh × θd plane): this kernel's NaN beyond θi = 84° is the pane's
    # message, and the frame at θi = 30° (a = kd = 0.5) still comes
    from tests.render.test_views import to_text
    from tuibrdf.core.formats.userfiles import load_model_file
    from tuibrdf.render import VIEW_TITLES
    from tuibrdf.render.views import extra_pixels

    path = tmp_path / "nan_grazing.py"
    path.write_text(NAN_AT_GRAZING)
    m = Material(load_model_file(path), {"kd": 0.5})
    res = core_frame.compute_frame(core_frame.FrameRequest(
        (m,), 30.0, extra=view, extra_px=extra_pixels(view, 60, 20)))
    side = res.sides[0]
    assert res.complete and abs(side.albedo - 0.5) <= side.albedo_error + 1e-12
    assert side.extra is None and "NaN" in side.extra_problem
    text = " ".join(to_text(panes.pane("extra", res, 0, 60, 20, panes.Look(color="none")),
                            width=60).split())
    assert f"no {VIEW_TITLES[view]}" in text and "returned NaN" in text
    if view == "slice":  # and a click on its pane reads nothing (there is no slice to read)
        from tuibrdf.render.pick import pick

        assert pick(res, "slice", 0, 20, 5, 60, 20) is None
