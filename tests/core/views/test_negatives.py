"""A user model's negative values (issue 36): clamped to 0 as before, and now said in one
line.  Expected shares from the solid angle: f = wo_z − c is negative where θo > acos c, a
cap of solid angle 2π·c, the fraction c of the hemisphere; f = wo_x is negative on half of
it.  The mesh's directions are nearly uniform: within 0.03."""

from __future__ import annotations

import numpy as np
import pytest

import tuibrdf
from tuibrdf.cli import main
from tuibrdf.core.directions import incident
from tuibrdf.core.registry import get_model
from tuibrdf.core.views.negatives import negative_note, negative_share

BRDF = """analytic
::begin parameters
float c 0 1 0.8
::end parameters
::begin shader
vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {{ return vec3({expr}); }}
::end shader
"""

PY = """from tuibrdf.core.params import Model, Param
C = Param("c", "c", 0.8, 0.0, 1.0, 0.01)
def kernel(wi, wo, c):
    return wo[..., 0] * 0 + {expr}
MODEL = Model("neg", "Negative", (C,), kernel)
"""


@pytest.fixture(params=["brdf", "py"])
def model_file(request, tmp_path):
    def make(expr_glsl, expr_py):
        if request.param == "brdf":
            path = tmp_path / "m.brdf"
            path.write_text(BRDF.format(expr=expr_glsl))
        else:
            path = tmp_path / "m.py"
            path.write_text(PY.format(expr=expr_py))
        return str(path)
    return make


@pytest.mark.parametrize("c", [0.2, 0.5, 0.8])
def test_share_is_the_cap_beyond_acos_c(model_file, c):
    path = model_file("V.z - c", "wo[..., 2] - c")
    m = get_model(path)
    share = negative_share(m, m.resolve({"c": c}), incident(30.0))
    assert share == pytest.approx(c, abs=0.03)
    # the pictures still get the clamped values
    wo = np.array([np.sqrt(1 - 0.01), 0.0, 0.1])  # θo = 84°: wo_z − c < 0 for every c here
    assert float(np.max(tuibrdf.evaluate(path, {"c": c}, incident(30.0), wo))) == 0.0


def test_share_of_half_the_hemisphere(model_file):
    path = model_file("V.x", "wo[..., 0]")
    m = get_model(path)
    assert negative_share(m, m.resolve({}), incident(45.0)) == pytest.approx(0.5, abs=0.03)


def test_no_note_for_built_in_or_positive_models(model_file):
    m = get_model("phong")
    assert negative_share(m, m.resolve({}), incident(30.0)) == 0.0
    path = model_file("V.z + c", "wo[..., 2] + c")
    pm = get_model(path)
    assert negative_share(pm, pm.resolve({}), incident(30.0)) == 0.0
    assert negative_note(0.0) == ""


def test_note_text():
    assert negative_note(0.12) == "f < 0 in 12 % of directions, clamped to 0"
    assert negative_note(0.001) == "f < 0 in < 1 % of directions, clamped to 0"


def test_render_says_it(model_file, capsys):
    path = model_file("V.z - c", "wo[..., 2] - c")
    assert main(["render", path, "-p", "c=0.5", "--width", "50", "--height", "8",
                 "--color", "none"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[1] in ("f < 0 in 49 % of directions, clamped to 0",
                        "f < 0 in 50 % of directions, clamped to 0",
                        "f < 0 in 51 % of directions, clamped to 0")


async def test_viewer_status_says_it(model_file):
    from tuibrdf.app.app import BrdfApp
    from tuibrdf.state.viewer import Side, ViewerState

    path = model_file("V.z - c", "wo[..., 2] - c")
    app = BrdfApp(ViewerState(sides=[Side.of(path, {"c": 0.5})]), sync=True)
    async with app.run_test(size=(160, 48)) as pilot:
        await pilot.pause()
        assert "% of directions, clamped to 0" in str(app.query_one("#status").render())
