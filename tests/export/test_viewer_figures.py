"""Key ``w`` and the palette's Screenshot write the screen (SVG) and the main view (PNG and
its numbers) into the output directory; read back here with Pillow, numpy and xml."""

from __future__ import annotations

import io
import json
import xml.etree.ElementTree as ET

import numpy as np
import pytest

import tuibrdf
from tuibrdf.app.app import BrdfApp
from tuibrdf.state.viewer import Side, ViewerState

PIL = pytest.importorskip("PIL.Image")


@pytest.fixture(autouse=True)
def config_home(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path / "config"))


def status(app) -> str:
    return str(app.one("status").render())


def make(view="map", **kw) -> BrdfApp:
    state = ViewerState(sides=[Side.of("phong", {"n": 40})], theta_i=30.0, view=view, **kw)
    return BrdfApp(state, sync=True)


async def test_key_w_writes_screen_png_and_npz(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    app = make()
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.press("w")
        await pilot.pause()
        names = sorted(p.name for p in tmp_path.iterdir() if p.is_file())
        assert names == ["tuibrdf-1-map.npz", "tuibrdf-1-map.png", "tuibrdf-1-screen.svg"]
        assert app.message == f"wrote tuibrdf-1-{{screen.svg,map.png,map.npz}} in {tmp_path}"
        assert "wrote tuibrdf-1-{screen.svg,map.png,map.npz}" in status(app)
        ET.parse(tmp_path / "tuibrdf-1-screen.svg")
        with PIL.open(tmp_path / "tuibrdf-1-map.png") as img:
            assert img.size[0] == 512
        z = np.load(io.BytesIO((tmp_path / "tuibrdf-1-map.npz").read_bytes()))
        meta = json.loads(str(z["metadata"]))
        assert meta["theta_i"] == 30.0 and meta["params"]["n"] == 40
        inside = ~np.isnan(z["f"])
        assert np.array_equal(tuibrdf.evaluate("phong", {"n": 40}, z["wi"], z["wo"][inside]),
                              z["f"][inside])
        await pilot.press("w")  # again: new names, nothing overwritten
        await pilot.pause()
        assert (tmp_path / "tuibrdf-2-map.png").exists()


async def test_albedo_view_writes_its_curve_as_csv(tmp_path):
    app = make(view="albedo")
    app.output_dir = tmp_path / "new" / "dir"  # missing: made
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.press("w")
        await pilot.pause()
        names = sorted(p.name for p in app.output_dir.iterdir())
        assert names == ["tuibrdf-1-albedo.csv", "tuibrdf-1-screen.svg"]
        head = (app.output_dir / "tuibrdf-1-albedo.csv").read_text().splitlines()[0]
        assert head == "theta_i,albedo,error"


async def test_palette_screenshot_never_goes_to_downloads(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("HOME", str(tmp_path / "nohome"))  # no ~/Downloads anywhere
    app = make(view="solid")
    async with app.run_test(size=(100, 30)) as pilot:
        app.action_screenshot()
        await pilot.pause()
        names = sorted(p.name for p in tmp_path.iterdir() if p.is_file())
        assert names == ["tuibrdf-1-map.npz", "tuibrdf-1-screen.svg", "tuibrdf-1-solid.png"]
        assert "wrote" in status(app)
        assert not (tmp_path / "nohome").exists()


async def test_an_unwritable_directory_is_a_status_message(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    app = make()
    app.output_dir = blocker / "sub"
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.press("w")
        await pilot.pause()
        assert "figures not written" in status(app)
        assert app.is_running


async def test_under_a_web_driver_the_files_go_to_the_browser(tmp_path, monkeypatch):
    # tuibrdf serve: Textual's delivery (a download in the browser), nothing on the server's disk
    monkeypatch.chdir(tmp_path)
    sent: list[tuple[str, str]] = []
    monkeypatch.setattr(BrdfApp, "is_web", property(lambda self: True))
    monkeypatch.setattr(BrdfApp, "deliver_text", lambda self, f, **kw: sent.append(
        ("text", kw["save_filename"])))
    monkeypatch.setattr(BrdfApp, "deliver_binary", lambda self, f, **kw: sent.append(
        ("binary", kw["save_filename"])))
    app = make()
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.press("w")
        await pilot.pause()
        assert sorted(sent) == [("binary", "tuibrdf-map.npz"), ("binary", "tuibrdf-map.png"),
                                ("text", "tuibrdf-screen.svg")]
        sent.clear()
        app.action_screenshot()  # the palette's Screenshot: Textual's own delivery of the SVG
        await pilot.pause()
        assert len(sent) == 1 and sent[0][0] == "text" and sent[0][1].endswith(".svg")
    assert not any(tmp_path.iterdir())
