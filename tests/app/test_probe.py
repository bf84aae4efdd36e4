"""The probe (issue 13 §4): a cursor on the map moved with keys or a click, and clicks on the
sections; the status line reads θr, φr, f per channel and f·cos θr from the frame.

Expected values come from outside the viewer: the direction from the Lambert equal-area
inverse written out here (r² = u² + v², w = (u·s, v·s, 1 − r²/2), s = √(1 − r²/4): Snyder,
*Map Projections — A Working Manual*, 1987, p. 187, the hemisphere scaled to radius √2), the
value from the public ``tuibrdf.evaluate`` at that direction and the light at θi, φi = 180°.
"""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
from rich.text import Text

import tuibrdf
from tuibrdf.app.app import BrdfApp
from tuibrdf.state.viewer import PROBE_STEP, Side, ViewerState


def make(model, theta=30.0, **params):
    return BrdfApp(ViewerState(sides=[Side.of(model, params)], theta_i=theta), sync=True)


def lambert_inverse(u: float, v: float) -> np.ndarray:
    r2 = u * u + v * v
    s = math.sqrt(1.0 - r2 / 4.0)
    return np.array([u * s, v * s, 1.0 - r2 / 2.0])


def light(theta_deg: float) -> np.ndarray:
    t = math.radians(theta_deg)
    return np.array([-math.sin(t), 0.0, math.cos(t)])


def status(app) -> str:
    return str(app.query_one("#status").render())


def one_if_grey(f) -> list[float]:
    """What the status line shows of f: its channels, one value when they are equal."""
    f = list(np.atleast_1d(f))
    return f[:1] if len(set(f)) == 1 else f


def numbers_after(text: str, key: str) -> list[float]:
    """``f=0.31`` → [0.31]; ``f=(0.1,0.2,0.3)`` → [0.1, 0.2, 0.3]."""
    m = re.search(re.escape(key) + r"=\(?([-+0-9.e,]+)\)?", text)
    assert m, (key, text)
    return [float(x) for x in m.group(1).split(",")]


@pytest.mark.parametrize("model,params", [("phong", {"kd": 0.2, "ks": 0.6, "n": 20}),
                                          ("gltf", {})])
async def test_probe_keys_read_f_and_f_cos_at_the_probe(model, params):
    app = make(model, 40.0, **params)
    async with app.run_test(size=(140, 40)) as pilot:
        await pilot.press("b")  # the probe appears at the centre of the map: the normal
        for key in ("L", "L", "L", "L", "L", "L", "I", "I"):
            await pilot.press(key)
        await pilot.pause()
        u, v = 6 * PROBE_STEP, 2 * PROBE_STEP
        assert app.state.probe == pytest.approx((u, v))
        w = lambert_inverse(u, v)
        text = status(app)
        theta = math.degrees(math.acos(w[2]))
        phi = math.degrees(math.atan2(w[1], w[0]))
        assert numbers_after(text, "θr")[0] == pytest.approx(theta, abs=0.06)
        assert numbers_after(text, "φr")[0] == pytest.approx(phi, abs=0.06)
        f = np.atleast_1d(tuibrdf.evaluate(model, params, light(40.0), w))
        shown = numbers_after(text, " f")
        assert shown == pytest.approx(one_if_grey(f), rel=2e-3)  # 3 significant digits shown
        assert numbers_after(text, "f·cosθr") == pytest.approx(one_if_grey(f * w[2]), rel=2e-3)
        # the probe's mark is on the map
        assert "+" in "".join(s.text for s in app.query_one("#map-a")._strips)


async def test_clicking_the_map_moves_the_probe_there():
    # a click on the cell of the mirror mark (×) puts the probe within a cell of the mirror
    # direction θr = θi, φr = 0
    app = make("phong", 50.0)
    async with app.run_test(size=(140, 40)) as pilot:
        await pilot.pause()
        rows = ["".join(s.text for s in line) for line in app.query_one("#map-a")._strips]
        row = next(k for k, r in enumerate(rows) if "×" in r[:60] and k > 0)
        col = rows[row].index("×")
        await pilot.click("#map-a", offset=(col, row))
        await pilot.pause()
        assert app.state.probe is not None
        w = lambert_inverse(*app.state.probe)
        assert math.degrees(math.acos(w[2])) == pytest.approx(50.0, abs=3.0)
        assert abs(math.degrees(math.atan2(w[1], w[0]))) < 5.0
        assert "probe θr=" in status(app)


async def test_clicking_a_section_reads_it():
    # the incidence section's top centre is the normal (θr ≈ 0); the value is f there
    app = make("phong", 30.0, kd=0.3, ks=0.5, n=10)
    async with app.run_test(size=(140, 40)) as pilot:
        await pilot.pause()
        pic = app.query_one("#incidence")
        w, h = pic.size.width, pic.size.height
        await pilot.click("#incidence", offset=(w // 2, 2))
        await pilot.pause()
        assert app.state.probe is not None
        d = lambert_inverse(*app.state.probe)
        assert math.degrees(math.acos(d[2])) < 3.0  # straight up: near the normal
        assert abs(d[1]) < 1e-12  # in the plane of incidence
        f = float(tuibrdf.evaluate("phong", {"kd": 0.3, "ks": 0.5, "n": 10}, light(30.0), d))
        assert numbers_after(status(app), " f")[0] == pytest.approx(f, rel=2e-3)
        assert h > 3


async def test_phi_i_keys_turn_the_map_and_keep_an_isotropic_albedo():
    # > turns the light by 15°: the map is redrawn (its light mark moves), the status says φi,
    # and an isotropic model's albedo is unchanged (issue 13 §5)
    app = make("phong", 40.0, kd=0.2, ks=0.6, n=30)
    async with app.run_test(size=(140, 40)) as pilot:
        await pilot.pause()
        before = ["".join(s.text for s in line) for line in app.query_one("#map-a")._strips]
        a0 = app.frame.sides[0].albedo
        for _ in range(6):  # 180° + 90° = 270°: the light at the bottom of the map
            await pilot.press("greater_than_sign")
        await pilot.pause()
        assert app.state.phi_i == 270.0 and app.frame.request.phi_i == 270.0
        after = ["".join(s.text for s in line) for line in app.query_one("#map-a")._strips]
        assert before != after
        row_o = next(k for k, r in enumerate(after) if "o" in r[:70] and k > 0)
        row_x = next(k for k, r in enumerate(after) if "×" in r[:70] and k > 0)
        assert row_o > row_x  # the light below the mirror direction (φ = 270° is down)
        assert "φi -90°" in status(app)  # 270° written in (−180°, 180°]
        assert app.frame.sides[0].albedo == pytest.approx(a0, rel=1e-4)


async def test_section_azimuth_key_turns_the_section_through_the_peak():
    # ψ = 90° + 15°: the title says so; at ψ = 0 (six A presses from 90°) the section through
    # the peak lies in the plane of incidence, so its maximum is the incidence section's
    app = make("cook-torrance", 60.0, kd=0.0, f0=0.04, m=0.07)
    async with app.run_test(size=(160, 48)) as pilot:
        await pilot.pause()

        def title():
            return "".join(s.text for s in app.query_one("#perpendicular")._strips[0])

        assert "perp. through peak θ=62° φ=0°" in title() and "section max 6.14" in title()
        await pilot.press("a")
        await pilot.pause()
        assert "ψ=105° through peak" in title()
        await pilot.press(*["A"] * 7)
        await pilot.pause()
        assert app.state.section_azimuth == 0.0
        assert "ψ=0° through peak" in title() and "FWHM 13.8°" in title()  # issue 13's 13.8°


def shown_status_rows(app) -> list[str]:
    """The status line's rows as drawn (its strips), not the text it was given."""
    return ["".join(s.text for s in strip).rstrip() for strip in app.query_one("#status")._strips]


@pytest.mark.parametrize("a,b", [
    (("phong", {"kd": 0.0, "ks": 0.08, "n": 70.0}), ("cook-torrance", {"kd": 0.0, "m": 0.07})),
    (("gltf", {}), ("gltf", {"base_color": (0.2, 0.3, 0.9), "roughness": 0.3})),
], ids=["scalar", "rgb"])
async def test_compare_probe_at_80x24_shows_both_sides(a, b):
    # at 80×24 the 3-row status cut the probe's B part (the numbers wrapped to a fourth row):
    # both sides' f at the probe must be on screen, each equal to the public evaluate() at the
    # probe's direction (Lambert inverse written above), and the view's row kept
    state = ViewerState(sides=[Side.of(*a), Side.of(*b)], theta_i=30.0)
    app = BrdfApp(state, sync=True)
    async with app.run_test(size=(80, 24)) as pilot:
        for key in ("b", "J", "L", "I", "K", "L", "L", "I"):
            await pilot.press(key)
        await pilot.pause()
        u, v = 2 * PROBE_STEP, PROBE_STEP
        assert app.state.probe == pytest.approx((u, v))
        rows = shown_status_rows(app)
        assert 1 <= len(rows) <= 3 and all(len(r) <= 78 for r in rows)
        shown = " ".join(rows)
        w = lambert_inverse(u, v)
        for side, (model, params) in zip("AB", (a, b), strict=True):
            f = np.atleast_1d(tuibrdf.evaluate(model, params, light(30.0), w))
            # 3 significant digits shown: within half a unit of the third, ≤ 0.5 %
            assert numbers_after(shown, f"{side}: f") == pytest.approx(one_if_grey(f), rel=5e-3)
        assert "equal-area map" in rows[-1]  # the view's row is still there
        assert not shown.endswith("…")  # nothing cut: a shorter form fitted


async def test_status_line_that_cannot_fit_says_so():
    # every form too long for three rows: the tersest is shown cut after its third row, which
    # ends in "…" (an explicit cut), never more rows than three
    from textual.app import App

    from tuibrdf.app.widgets import StatusLine

    long = Text(" ".join(f"word{i}" for i in range(60)) + "\nview row")
    forms = [long, Text(" ".join(f"w{i}" for i in range(60)) + "\nview row")]

    class One(App):
        def compose(self):
            yield StatusLine(id="status")

    app = One()
    async with app.run_test(size=(40, 10)) as pilot:
        line = app.query_one("#status")
        line.show_forms(lambda k: forms[k], 2)
        await pilot.pause()
        rows = shown_status_rows(app)
        assert len(rows) == 3 and rows[-1].endswith("…")
        assert rows[0].startswith("w0 w1")  # the terser form
        # a short text: shown whole, no "…"
        line.show_forms(lambda k: Text("θi 30°\nview row"), 1)
        await pilot.pause()
        assert shown_status_rows(app) == ["θi 30°", "view row"]
