"""Key storms (issue 31): seeded random terminal input of every kind (tests/app/storm.py) over
every kind of model and every main view; the viewer must be alive at the end and quit with
status 0 on q.  The input goes through Textual's terminal parser as the viewer installs it, so
raw and malformed sequences are part of the storm."""

from __future__ import annotations

import pytest

from tests.app.storm import events, storm
from tuibrdf.app.app import BrdfApp
from tuibrdf.state.viewer import MAIN_VIEWS, Side, ViewerState

#: robustness runs: CI's Python 3.13 leg skips them (pyproject.toml, markers)
pytestmark = pytest.mark.slow

ROOT_DATA = __import__("tests").DATA_DIR


@pytest.fixture(autouse=True)
def config_home(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path / "config"))
    monkeypatch.chdir(tmp_path)  # (the palette's screenshot command writes here)
    return tmp_path


class StormApp(BrdfApp):
    """The viewer without the palette's quit command (a storm types into the palette: "q"
    then Enter would quit on purpose)."""

    def get_system_commands(self, screen):
        for cmd in super().get_system_commands(screen):
            if "quit" not in cmd.title.lower():
                yield cmd


def files(tmp_path) -> dict[str, list[Side]]:
    import numpy as np

    from tests.merl_writer import write_merl
    from tests.rgl_writer import material, write_tensor

    bsdf = write_tensor(tmp_path / "synthetic.bsdf", material())
    merl = write_merl(tmp_path / "grey.binary", np.full((3, 90, 90, 180), 0.1))
    empty = tmp_path / "empty.brdf"
    empty.write_text("analytic\n::begin parameters\n::end parameters\n::begin shader\n"
                     "vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) { return vec3(0.2); }\n"
                     "::end shader\n")
    py = __import__("tests").ROOT / "docs" / "examples" / "minnaert.py"
    return {
        "scalar": [Side.of("phong")],
        "rgb": [Side.of("gltf")],
        "bsdf": [Side.of(str(bsdf))],
        "brdf": [Side.of(str(ROOT_DATA / "brdf" / "disney.brdf"))],
        "empty-brdf": [Side.of(str(empty))],
        "py": [Side.of(str(py))],
        "merl": [Side.of("merl", {"file": str(merl)})],
        "material": [Side.of("abc", {"material": "gold-metallic-paint"})],
        "compare": [Side.of("phong"), Side.of(str(bsdf))],
    }


async def run_storm(sides, views, seed, n=400, sync=True):
    """``n`` storm keys on each of ``views`` in turn, in one viewer: between two storms the
    modal screens are closed and ``v`` brings the next view."""
    app = StormApp(ViewerState(sides=sides, view=views[0]), sync=sync)
    async with app.run_test(size=(100, 30)) as pilot:
        for k, view in enumerate(views):
            await close_screens(pilot, app)
            for _ in range(len(MAIN_VIEWS)):
                if app.state.view == view:
                    break
                await pilot.press("v")
                await pilot.pause()
            assert app.state.view == view, (view, app.message)
            for i, event in enumerate(events(storm(seed + k, n))):
                app.post_message(event)
                if i % 25 == 24:
                    await pilot.pause()
            await pilot.pause()
        # alive: the viewer's screen underneath, and it still answers a key
        await close_screens(pilot, app)
        theta = app.state.theta_i
        await pilot.press("t")
        await pilot.pause()
        await pilot.press("ctrl+u", *"17", "enter")
        await pilot.pause()
        assert app.state.theta_i == 17.0, (theta, app.message)
        await pilot.press("q")
        await pilot.pause()
    assert app.return_code in (0, None)


async def close_screens(pilot, app) -> None:
    while len(app.screen_stack) > 1:
        await pilot.press("escape")
        await pilot.pause()


KINDS = ["scalar", "rgb", "bsdf", "brdf", "empty-brdf", "py", "merl", "material", "compare"]


@pytest.mark.parametrize("kind", KINDS)
async def test_storm_over_every_kind_of_model_and_view(kind, tmp_path):
    await run_storm(files(tmp_path)[kind], MAIN_VIEWS, seed=1000 * KINDS.index(kind), n=100)


@pytest.mark.parametrize("kind", ["py", "compare", "merl"])
async def test_storm_with_frames_computed_in_threads(kind, tmp_path):
    # as the viewer runs (not sync): a user file's frames in threads, the keys meanwhile
    sides = files(tmp_path)[kind]
    await run_storm(sides, ["map"], seed=7000 + KINDS.index(kind), n=300, sync=False)
