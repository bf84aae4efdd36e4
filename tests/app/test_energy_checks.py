"""The energy view and key F in the viewer (Textual's Pilot, sync mode)."""

from __future__ import annotations

import pytest

from tuibrdf.app.app import BrdfApp
from tuibrdf.app.screens import ReportScreen
from tuibrdf.state.viewer import MAIN_VIEWS, Side, ViewerState


@pytest.fixture(autouse=True)
def config_home(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path))
    return tmp_path


def make(model, theta=30.0, **params):
    return BrdfApp(ViewerState(sides=[Side.of(model, params)], theta_i=theta), sync=True)


def status(app) -> str:
    return str(app.query_one("#status").render())


async def test_energy_view_shows_the_furnace_verdict_of_the_selected_parameter():
    # Lambert with kd = 0.6: E = kd at every μ, so it loses 40 % (closed form)
    app = make("lambert", kd=0.6)
    async with app.run_test(size=(120, 36)) as pilot:
        for _ in range(MAIN_VIEWS.index("energy")):
            await pilot.press("v")
        await pilot.pause()
        assert app.state.view == "energy"
        assert "loses 40 % at Kd = 0.6, θi = 30°" in status(app)
        text = "".join(s.text for s in app.query_one("#extra-a")._strips)
        assert "white furnace" in text


async def test_key_f_opens_the_check_report():
    app = make("ggx")
    async with app.run_test(size=(160, 48)) as pilot:
        await pilot.press("F")
        await pilot.pause()
        screen = app.screen
        assert isinstance(screen, ReportScreen)
        body = str(screen.body.renderables[0])
        assert body.startswith("ggx: FAILS energy")  # kd = 1 gains (docs/reference/checks.md)
        await pilot.press("escape")
        await pilot.pause()
        assert not isinstance(app.screen, ReportScreen)
