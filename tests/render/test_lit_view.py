"""The lit sphere and lit plane pictures (``tuibrdf.render.lit_view``), drawn as the viewer and
``tuibrdf render`` draw them: ``render_view`` → the frame → ``panes.extra_pane``."""

from __future__ import annotations

import numpy as np
import pytest
from rich.console import Console

from tuibrdf.core.registry import get_model
from tuibrdf.render.views import render_view

CT = ("cook-torrance", {"kd": 0.0, "f0": 0.04, "m": 0.07})


@pytest.mark.parametrize("kind", ["sphere", "plane"])
@pytest.mark.parametrize("color", ["none", "256", "truecolor"])
def test_lit_view_fits_and_is_deterministic(kind, color):
    m = get_model(CT[0])
    v = m.resolve(CT[1])
    con = Console(width=40, color_system=None if color == "none" else color,
                  force_terminal=color != "none")

    def out():
        with con.capture() as cap:
            con.print(render_view(kind, m, v, 60.0, 40, 12, color=color))
        return cap.get()

    a = out()
    assert a == out()
    assert len(a.splitlines()) == 12
    assert ("lit " + kind) in a.splitlines()[0]


def test_truecolor_picture_is_drawn_on_64_levels_per_channel():
    # quantise_channels: every value one of round(k·255/63), k = 0…63, and within half a step
    # (255/126 ≈ 2.02) of the 8-bit input; 0 and 255 kept
    from tuibrdf.render.halfblock import quantise_channels

    img = np.arange(256, dtype=np.uint8).reshape(16, 16, 1).repeat(3, axis=2)
    q = quantise_channels(img, 64)
    allowed = {round(k * 255 / 63) for k in range(64)}
    assert set(np.unique(q).tolist()) <= allowed
    assert np.max(np.abs(q.astype(int) - img.astype(int))) <= 255 / 126
    assert q[0, 0, 0] == 0 and q[-1, -1, 0] == 255
