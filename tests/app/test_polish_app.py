"""Viewer polish (issue 36): the panel of a parameterless model, the first screen."""

from __future__ import annotations

import pytest

from tuibrdf.app.app import BrdfApp
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


async def test_footer_and_help_fit_60x18():
    # the footer fits 60 columns whole (no key cut mid-word), and the help screen is no
    # wider than the terminal
    from textual.widgets import Footer

    app = BrdfApp(ViewerState(sides=[Side.of("phong")]), sync=True)
    async with app.run_test(size=(60, 18)) as pilot:
        await pilot.pause()
        footer = app.query_one(Footer)
        right = max(w.region.right for w in footer.query("*") if w.region.width)
        assert right <= 60
        labels = " ".join(str(w.render()) for w in footer.query("FooterKey"))
        assert "help" in labels and "quit" in labels
        await pilot.press("question_mark")
        await pilot.pause()
        box = app.screen.query_one("VerticalScroll")
        assert box.region.x >= 0 and box.region.right <= 60


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
