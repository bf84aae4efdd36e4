"""render_view: every view, every model, plain fallback, determinism (tuibrdf/render/views.py)."""

import re

import numpy as np
import pytest
from rich.console import Console

from tuibrdf.core.registry import MODELS
from tuibrdf.render.views import CMAPS, VIEWS, render_view

MODELS_NO_FILE = [n for n, m in MODELS.items() if all(p.kind != "path" for p in m.params)]
DONE_VIEWS = VIEWS


def to_text(renderable, system=None, width=200) -> str:
    con = Console(width=width, color_system=system, force_terminal=system is not None,
                  record=False, legacy_windows=False)
    with con.capture() as cap:
        con.print(renderable)
    return cap.get()


def test_views_and_cmaps_tuples():
    assert VIEWS == ("map", "incidence", "perpendicular", "solid", "albedo", "sphere", "plane",
                     "slice", "theta-h", "theta-d", "energy")
    # the renderer and the frame computation know the same extra views
    from tuibrdf.core.views.frame import EXTRA_VIEWS as CORE_EXTRA
    from tuibrdf.render import EXTRA_VIEWS

    assert EXTRA_VIEWS == CORE_EXTRA
    assert "grey" in CMAPS and "viridis" in CMAPS and "inferno" in CMAPS


def test_the_module_docstring_lists_every_view():
    # the table of views in tuibrdf/render/views.py's docstring, one row per view, in order
    import tuibrdf.render.views as views

    rows = re.findall(r"^``([a-z-]+)``  ", views.__doc__, flags=re.M)
    assert tuple(rows) == VIEWS


@pytest.mark.parametrize("view", DONE_VIEWS)
@pytest.mark.parametrize("name", MODELS_NO_FILE)
def test_every_model_every_view_plain(view, name):
    m = MODELS[name]
    for theta_i in (0, 45, 89, 90):
        out = to_text(render_view(view, m, m.resolve({}), theta_i, 40, 14, color="none"))
        lines = out.rstrip("\n").split("\n")
        assert len(lines) <= 14, (view, name, theta_i)
        assert all(len(s) <= 40 for s in lines)
        assert "nan" not in out.lower() and "inf" not in out.lower()
        assert "\x1b" not in out


def test_map_plain_shows_marks_and_title():
    m = MODELS["phong"]
    out = to_text(render_view("map", m, m.resolve({"kd": 0, "ks": 1, "n": 500}), 45, 40, 14,
                              color="none"))
    lines = out.split("\n")
    # title: model, θi and the exact mirror peak (n+2)/(2π)·ks = 79.9
    # (40 cells: θi gives way to the numbers, see test_titles_keep_numbers)
    assert lines[0].startswith("phong  f peak 79.9") and "θ=45° φ=0°" in lines[0]
    body = "\n".join(lines[1:12])
    assert "X" in body and "o" in body  # mirror and light marks
    # the light mark is left of the centre column, the mirror mark right of it
    row_x = next(s for s in lines if "X" in s)
    assert row_x.index("o") < 20 < row_x.index("X")


@pytest.mark.parametrize("color", ["truecolor", "256"])
def test_deterministic_bytes(color):
    m = MODELS["cook-torrance"]
    v = m.resolve({"kd": 0, "f0": 0.04, "m": 0.07})
    a = to_text(render_view("map", m, v, 60, 50, 16, color=color, cmap="inferno"), "truecolor")
    b = to_text(render_view("map", m, v, 60, 50, 16, color=color, cmap="inferno"), "truecolor")
    assert a == b
    if color == "256":
        assert "38;2;" not in a and "48;5;" in a
    else:
        assert "48;2;" in a


def test_rgb_model_colour_map_shows_channels():
    m = MODELS["gltf"]
    v = m.resolve({"base_color": (1.0, 0.0, 0.0), "roughness": 1.0})
    out = to_text(render_view("map", m, v, 0, 40, 14), "truecolor")
    # a red base colour: some diffuse cell is pure-ish red (green and blue channels lower)
    cols = [tuple(map(int, t)) for t in re.findall(r"48;2;(\d+);(\d+);(\d+)", out)]
    assert any(r > 100 and g < r / 2 and b < r / 2 for r, g, b in cols)


@pytest.mark.parametrize("bad,match", [
    (dict(view="nope"), "unknown view"),
    (dict(color="16"), "color"),
    (dict(cmap="jet"), "colour map"),
    (dict(width=5), "too small"),
    (dict(theta_i_deg=91), "0..90"),
])
def test_bad_arguments(bad, match):
    m = MODELS["lambert"]
    kw = dict(view="map", model=m, values=m.resolve({}), theta_i_deg=10, width=40, height=14)
    kw.update(bad)
    with pytest.raises(ValueError, match=match):
        render_view(**kw)


def test_cosine_title():
    m = MODELS["lambert"]
    out = to_text(render_view("map", m, m.resolve({}), 10, 60, 14, color="none", cosine=True))
    assert "f·cosθr" in out.split("\n")[0]
    assert np.isclose(float(re.search(r"peak ([0-9.]+)", out).group(1)), 0.8 / np.pi, rtol=1e-2)


@pytest.mark.parametrize("size", [(12, 6), (300, 100)])
@pytest.mark.parametrize("view", VIEWS)
def test_output_fits_the_requested_cells(view, size):
    from rich.text import Text

    w, h = size
    out = to_text(render_view(view, "gltf", MODELS["gltf"].resolve({}), 45, w, h, color="256"),
                  "256", width=w)
    lines = Text.from_ansi(out).plain.rstrip("\n").split("\n")
    assert len(lines) <= h and max(len(s) for s in lines) <= w


def test_titles_keep_numbers():
    # a narrow pane drops the legend, then θi, then the name; the value and direction stay
    from tuibrdf.render.text import fit_parts

    parts = [("cook-torrance", 2), ("θi=60°", 3), ("f peak 6.14 at θ=62° φ=0°", 0),
             ("× mirror", 4)]
    assert fit_parts(parts, 80) == "cook-torrance  θi=60°  f peak 6.14 at θ=62° φ=0°  × mirror"
    assert fit_parts(parts, 50) == "cook-torrance  θi=60°  f peak 6.14 at θ=62° φ=0°"
    assert fit_parts(parts, 42) == "cook-torrance  f peak 6.14 at θ=62° φ=0°"
    assert fit_parts(parts, 30) == "f peak 6.14 at θ=62° φ=0°"
    assert fit_parts(parts, 6) == "f peak"
    # two parts that must stay: both kept, the line cropped
    assert fit_parts([("incidence", 0), ("(φ 180°|0°)", 4), ("max 6.14 · circles every 2", 0)],
                     30) == "incidence  max 6.14 · circles"


def test_uniform_map_says_everywhere_and_no_negative_zero():
    # Lambert kd=0.8: f = 0.8/π = 0.2546 in every direction, so no direction is "the" peak
    m = MODELS["lambert"]
    head = to_text(render_view("map", m, m.resolve({"kd": 0.8}), 30, 80, 20, color="none"))
    assert "f = 0.255 sr⁻¹  everywhere" in head.split("\n")[0]
    for theta in (0, 30, 60, 89):  # φ of a peak in the plane of incidence is 0, never -0
        m = MODELS["cook-torrance"]
        out = to_text(render_view("map", m, m.resolve({"kd": 0, "m": 0.07}), theta, 80, 20,
                                  color="none"))
        assert "φ=-0°" not in out and "φ=0°" in out.split("\n")[0]


def test_horizon_ring_never_collides_with_a_data_value():
    # issue 12 item 5: in 256 colours viridis's lowest band was xterm 60, the ring's colour;
    # without colour the ring was drawn with ':' and '-', data levels of the ramp.  Expected:
    # the ring's xterm index is none of the indices any colour map quantises to (every level
    # count the viewer allows), and in plain text its character is not in the density ramp.
    from tuibrdf.render.colormap import MAX_LEVELS, MIN_LEVELS, colorize
    from tuibrdf.render.halfblock import ASCII_RAMP, RING_CHAR, to_xterm
    from tuibrdf.render.text import RING_RGB

    ring = int(to_xterm(np.array(RING_RGB)))
    ramp = np.linspace(0.0, 1.0, 2000)[None, :]
    for cmap in CMAPS:
        for levels in range(MIN_LEVELS, MAX_LEVELS + 1):
            for log in (False, True):
                pal = colorize(ramp, cmap, levels=levels, log=log).palette
                assert ring not in set(to_xterm(pal).tolist()), (cmap, levels)
    assert RING_CHAR not in ASCII_RAMP
    m = MODELS["ggx"]
    lines = to_text(render_view("map", m, m.resolve({}), 30.0, 40, 16, color="none")
                    ).splitlines()
    assert any(RING_CHAR in ln for ln in lines[1:-2])  # the ring in the disc rows
