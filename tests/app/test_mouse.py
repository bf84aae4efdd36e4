"""The mouse in the viewer (issue 36): a drag on the lit sphere moves the light, a drag on
the 3D solid orbits it, the wheel zooms the solid and the sections, a click on a picture reads
the value there in the status line, and a click on a section off its axis reads the side
clicked (not its mirror).

Pilot has no drag or wheel helper: the events are Textual's public MouseMove and
MouseScroll* messages, posted the way Pilot posts its own clicks (``_post_mouse_events``).
Expected directions come from the geometry written out in tests/render/test_pick.py and
tests/app/test_probe.py; values from ``tuibrdf.evaluate``."""

from __future__ import annotations

import math

import numpy as np
import pytest
from textual import events

import tuibrdf
from tests.app.test_probe import lambert_inverse, numbers_after, status
from tuibrdf.app.app import BrdfApp
from tuibrdf.render.sections import angle_at
from tuibrdf.state.viewer import Side, ViewerState

WARD = "tests/data/brdf/ward.brdf"


def make(model, view="map", theta=30.0, **params):
    return BrdfApp(ViewerState(sides=[Side.of(model, params)], theta_i=theta, view=view),
                   sync=True)


async def drag(pilot, pane, start, path):
    await pilot.mouse_down(pane, offset=start)
    for cell in path:
        await pilot._post_mouse_events([events.MouseMove], pane, offset=cell, button=1)
    await pilot.mouse_up(pane, offset=path[-1])
    await pilot.pause()


async def test_drag_on_the_lit_sphere_moves_the_light():
    app = make("phong", "sphere")
    async with app.run_test(size=(120, 40)) as pilot:
        await pilot.pause()
        px_w, px_h = app.frame.request.extra_px
        await drag(pilot, "#extra-a", (30, 10), [(20, 12), (15, 8)])
        rad = min(px_w, px_h) / 2
        u, v = (15.5 - px_w / 2) / rad, (px_h / 2 - (2 * 7 + 1)) / rad
        assert app.state.theta_i == pytest.approx(math.degrees(math.asin(math.hypot(u, v))),
                                                  abs=0.06)  # kept to 0.1°
        assert app.state.phi_i == pytest.approx(math.degrees(math.atan2(v, u)) % 360, abs=0.06)
        assert app.frame.request.theta_i == app.state.theta_i  # the picture follows
        assert "N θ=" not in status(app)  # the end of a drag is not a click


async def test_drag_orbits_the_solid_and_the_wheel_zooms_it():
    app = make("phong", "solid")
    async with app.run_test(size=(120, 40)) as pilot:
        await pilot.pause()
        az, el = app.state.azimuth, app.state.elevation
        before = [s.text for s in app.query_one("#solid-a")._strips]
        await drag(pilot, "#solid-a", (30, 15), [(34, 14)])
        assert app.state.azimuth == pytest.approx(az - 12.0)  # 3° a cell
        assert app.state.elevation == pytest.approx(el - 3.0)
        for _ in range(3):
            await pilot._post_mouse_events([events.MouseScrollUp], "#solid-a", offset=(30, 15))
        await pilot.pause()
        assert app.state.zoom == pytest.approx(1.25 ** 3)
        assert [s.text for s in app.query_one("#solid-a")._strips] != before
        await pilot._post_mouse_events([events.MouseScrollDown], "#incidence", offset=(10, 5))
        await pilot.pause()
        assert app.state.zoom == pytest.approx(1.25 ** 2)
        title = "".join(s.text for s in app.query_one("#incidence")._strips[0])
        assert "zoom ×1.56" in title


async def test_click_on_the_sphere_reads_f_in_the_status_line():
    params = {"kd": 0.2, "ks": 0.6, "n": 30}
    app = make("phong", "sphere", 40.0, **params)
    async with app.run_test(size=(120, 40)) as pilot:
        await pilot.pause()
        px_w, px_h = app.frame.request.extra_px
        await pilot.click("#extra-a", offset=(40, 12))
        await pilot.pause()
        rad = min(px_w, px_h) / 2
        u, v = (40.5 - px_w / 2) / rad, (px_h / 2 - 23) / rad
        n = np.array([u, v, math.sqrt(1 - u * u - v * v)])
        light = np.array([-math.sin(math.radians(40)), 0, math.cos(math.radians(40))])
        # Phong depends on the angle between wo and the mirror of wi about n only
        ci, co = n @ light, n[2]
        mirror_dot = 2 * ci * co - light[2]  # (2(n·wi)n − wi)·z
        f = params["kd"] / math.pi + params["ks"] * (params["n"] + 2) / (2 * math.pi) * \
            max(mirror_dot, 0.0) ** params["n"]
        text = status(app)
        assert numbers_after(text, " f")[0] == pytest.approx(f, rel=5e-3)
        assert numbers_after(text, "f·cosθi")[0] == pytest.approx(f * ci, rel=5e-3)


@pytest.mark.parametrize("pane", ["incidence", "perpendicular"])
@pytest.mark.parametrize("side", [-1, 1])
async def test_section_clicks_off_the_axis_read_the_side_clicked(pane, side):
    # Ward anisotropic (αx ≠ αy) with the section turned to ψ = 60°: the two sides of each
    # section differ, so a mirrored angle reads another value than the one drawn
    params = {"alpha_x": 0.1, "alpha_y": 0.5, "Cd": (0.1, 0.2, 0.3), "Cs": (1.0, 0.5, 0.2)}
    state = ViewerState(sides=[Side.of(WARD, params)], theta_i=40.0, section_azimuth=60.0)
    app = BrdfApp(state, sync=True)
    async with app.run_test(size=(140, 40)) as pilot:
        await pilot.pause()
        pic = app.query_one(f"#{pane}")
        w, h = pic.size.width, pic.size.height
        x, y = w // 2 + side * (w // 5), h // 3
        await pilot.click(f"#{pane}", offset=(x, y))
        await pilot.pause()
        t = angle_at(x, y - 1, w, h - 1)
        assert (t > 0) == (side > 0)  # right of the axis: a positive angle
        d = lambert_inverse(*app.state.probe)
        if pane == "incidence":
            # the plane of incidence: positive θ toward the mirror side, φ = 0
            want = np.array([math.sin(math.radians(t)), 0.0, math.cos(math.radians(t))])
        else:
            # the great circle through the section's centre c at ψ = 60° from e_θ toward e_φ
            th, ph = (math.radians(a) for a in app.frame.sides[0].section_center)
            c = np.array([math.sin(th) * math.cos(ph), math.sin(th) * math.sin(ph),
                          math.cos(th)])
            e_t = np.array([math.cos(th) * math.cos(ph), math.cos(th) * math.sin(ph),
                            -math.sin(th)])
            e_p = np.array([-math.sin(ph), math.cos(ph), 0.0])
            u = math.cos(math.radians(60)) * e_t + math.sin(math.radians(60)) * e_p
            want = math.cos(math.radians(t)) * c + math.sin(math.radians(t)) * u
        np.testing.assert_allclose(d, want, atol=1e-9)
        light = np.array([-math.sin(math.radians(40)), 0, math.cos(math.radians(40))])
        f = np.atleast_1d(tuibrdf.evaluate(WARD, params, light, want))
        assert numbers_after(status(app), " f") == pytest.approx(list(f), rel=5e-3)
        # the value read is the curve drawn at that angle (the section's own samples)
        from tuibrdf.core.views.frame import SECTION_THETAS
        key = "incidence" if pane == "incidence" else "peak"
        drawn = app.frame.sides[0].sections[key]
        for c in range(3):
            assert float(np.interp(t, SECTION_THETAS, drawn[:, c])) == pytest.approx(
                f[c], rel=2e-2)


async def test_click_on_the_albedo_curve_reads_a_there():
    # Lambert: a(θi) = kd at every θi (∫ kd/π cos θr dω = kd); the θi read is the column's
    # place between the axis's 0° and 90° ticks as drawn
    app = make("lambert", "albedo", kd=0.6)
    async with app.run_test(size=(120, 40)) as pilot:
        await pilot.pause()
        rows = ["".join(s.text for s in strip) for strip in app.query_one("#albedo")._strips]
        axis = next(r for r in reversed(rows) if "└" in r)
        ticks = [c for c, ch in enumerate(axis) if ch in "┬┴"]
        x = ticks[0] + round(2 / 3 * (ticks[-1] - ticks[0]))  # ≈ 60°
        await pilot.click("#albedo", offset=(x, 5))
        await pilot.pause()
        text = status(app)
        theta = numbers_after(text, "a(θi")[0]
        assert theta == pytest.approx(60.0, abs=90 / (ticks[-1] - ticks[0]))
        assert numbers_after(text, " a")[0] == pytest.approx(0.6, rel=5e-3)
