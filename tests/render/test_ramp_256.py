"""256 colours: a colour map's ramp stays monotone in lightness (issue 36: viridis' low end
went through xterm colour 60, a grey-lilac lighter than its neighbours, a false contour ring
around every lobe in almost the horizon ring's hue).

Lightness is OKLab's L, computed here from Ottosson's published matrices (2020), not by the
code under test; the xterm colours are xterm's documented cube and grey ramp."""

from __future__ import annotations

import numpy as np
import pytest

from tuibrdf.cli import main
from tuibrdf.render.colormap import palette
from tuibrdf.render.halfblock import xterm_indices
from tuibrdf.render.text import RING_RGB


def xterm(i: int) -> tuple[int, int, int]:
    if i >= 232:
        g = 8 + 10 * (i - 232)
        return g, g, g
    lv = (0, 95, 135, 175, 215, 255)
    i -= 16
    return lv[i // 36], lv[i // 6 % 6], lv[i % 6]


def lightness(rgb) -> float:
    c = np.array(rgb, dtype=float) / 255
    lin = np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)
    l_ = 0.4122214708 * lin[0] + 0.5363325363 * lin[1] + 0.0514459929 * lin[2]
    m_ = 0.2119034982 * lin[0] + 0.6806995451 * lin[1] + 0.1073969566 * lin[2]
    s_ = 0.0883024619 * lin[0] + 0.2817188376 * lin[1] + 0.6299787005 * lin[2]
    return 0.2104542553 * np.cbrt(l_) + 0.7936177850 * np.cbrt(m_) - 0.0040720468 * np.cbrt(s_)


@pytest.mark.parametrize("cmap", ["grey", "viridis", "inferno"])
@pytest.mark.parametrize("levels", [32, 256])
def test_ramp_never_gets_darker(cmap, levels):
    xi = xterm_indices(palette(cmap, levels)).tolist()
    L = [lightness(xterm(i)) for i in xi]
    assert all(b >= a - 1e-9 for a, b in zip(L, L[1:], strict=False)), (cmap, xi)
    assert len(set(xi)) >= 10  # still a ramp, not a few steps
    assert 16 <= min(xi) and max(xi) <= 255  # never the themable system colours


@pytest.mark.parametrize("cmap", ["grey", "viridis", "inferno"])
def test_the_horizon_ring_colour_is_in_no_ramp(cmap):
    ring = int(xterm_indices(np.array([RING_RGB], dtype=np.uint8))[0])
    for levels in (32, 64, 256):
        assert ring not in xterm_indices(palette(cmap, levels)).tolist()


def test_viridis_map_in_256_colours_avoids_colour_60(capsys):
    assert main(["render", "phong", "--cmap", "viridis", "--color", "256", "--width", "60",
                 "--height", "20"]) == 0
    out = capsys.readouterr().out
    assert "5;60m" not in out and "5;60;" not in out
