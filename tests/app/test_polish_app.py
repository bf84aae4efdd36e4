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
