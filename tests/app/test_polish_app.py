"""Viewer polish (issue 36): the panel of a parameterless model, the first screen."""

from __future__ import annotations

import pytest
from textual.app import App

from tuibrdf.app.app import BrdfApp
from tuibrdf.app.widgets import KeyBar
from tuibrdf.state.viewer import Side, ViewerState

FLAT = """analytic
::begin shader
vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) { return vec3(0.25); }
::end shader
"""


@pytest.mark.parametrize("size", [(60, 18), (80, 24), (160, 48)])
async def test_a_parameterless_model_has_no_negative_count(tmp_path, size):
    path = tmp_path / "flat.brdf"
    path.write_text(FLAT)
    app = BrdfApp(ViewerState(sides=[Side.of(str(path))]), sync=True)
    async with app.run_test(size=size) as pilot:
        await pilot.pause()
        panel = app.query_one("#panel-a") if app.query("#panel-a") else None
        texts = [str(w.border_subtitle or "") + str(w.border_title or "")
                 for w in app.query("*") if hasattr(w, "border_subtitle")]
        assert not any("-1" in t or "more" in t for t in texts), texts
        assert panel is None or "(no parameters)" in str(panel.render())


#: the footer as designed: the key table's footer keys, a group's keys with its name, two
#: spaces between items (59 cells: it fits 60 columns whole)
FOOTER = " ←→ θi  +- step  m model  v view  c compare  ? help  q quit"


async def test_footer_and_help_fit_60x18():
    # the footer fits 60 columns whole (no key cut mid-word), and the help screen is no
    # wider than the terminal
    app = BrdfApp(ViewerState(sides=[Side.of("phong")]), sync=True)
    async with app.run_test(size=(60, 18)) as pilot:
        await pilot.pause()
        bar = app.query_one(KeyBar)
        assert bar.region.width == 60 and bar.render().plain == FOOTER
        await pilot.press("question_mark")
        await pilot.pause()
        box = app.screen.query_one("VerticalScroll")
        assert box.region.x >= 0 and box.region.right <= 60
        # while the help is open the viewer's keys wait: the footer shows what acts
        assert bar.render().plain == " q quit"
        await pilot.press("escape")
        await pilot.pause()
        assert bar.render().plain == FOOTER


class _Bar(App):
    def compose(self):
        yield KeyBar()


@pytest.mark.parametrize("width", [1, 10, 24, 30, 31, 32, 59, 200])
async def test_a_narrow_footer_shows_whole_keys_only(width):
    # as many whole items as fit: the line is the designed one cut at an item's end
    async with _Bar().run_test(size=(width, 3)) as pilot:
        await pilot.pause()
        line = pilot.app.query_one(KeyBar).render().plain
    ends = [0] + [i for i in range(1, len(FOOTER) + 1)
                  if i == len(FOOTER) or FOOTER[i:i + 2] == "  "]
    assert line == FOOTER[:max(e for e in ends if e <= width)] or line == " "


async def test_a_click_on_a_footer_key_presses_it():
    app = BrdfApp(ViewerState(sides=[Side.of("phong")]), sync=True)
    async with app.run_test(size=(160, 48)) as pilot:
        await pilot.pause()
        theta = app.state.theta_i
        await pilot.click(KeyBar, offset=(FOOTER.index("→"), 0))
        await pilot.pause()
        assert app.state.theta_i == theta + 1
        await pilot.click(KeyBar, offset=(FOOTER.index("θi"), 0))  # a group's name: no key
        await pilot.pause()
        assert app.state.theta_i == theta + 1
        await pilot.click(KeyBar, offset=(FOOTER.index("model"), 0))  # a single key's label
        await pilot.pause()
        assert app.state.side.model != "phong"
        await pilot.hover(KeyBar, offset=(FOOTER.index("compare"), 0))  # its help line
        assert app.query_one(KeyBar).tooltip == "compare two models (B starts as A)"
        await pilot.hover(KeyBar, offset=(FOOTER.index("θi"), 0))
        assert app.query_one(KeyBar).tooltip is None
        await pilot.click(KeyBar, offset=(FOOTER.index("? help"), 0))
        await pilot.pause()
        assert app.screen.query("VerticalScroll")


async def test_the_map_has_256_levels():
    # Oren-Nayar at θi = 60°: a smooth diffuse lobe; 32 levels drew visible contours.  The map
    # pane draws more than 32 distinct colours now (as `render` does)
    app = BrdfApp(ViewerState(sides=[Side.of("oren-nayar")], theta_i=60.0), color="truecolor",
                  sync=True)
    async with app.run_test(size=(160, 48)) as pilot:
        await pilot.pause()
        colours = {seg.style.bgcolor for strip in app.query_one("#map-a")._strips
                   for seg in strip if seg.style is not None and seg.style.bgcolor is not None}
        assert len(colours) > 40
