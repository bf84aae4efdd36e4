"""Colour maps, scales, quantisation and the colour bar (tuibrdf/render/colormap.py)."""

import numpy as np
import pytest

from tuibrdf.render.colormap import (
    CMAPS,
    Scale,
    colorbar,
    colorize,
    palette,
    quantise,
    sample,
    tick_line,
)
from tuibrdf.render.halfblock import TRANSPARENT

# matplotlib 3.x _cm_listed.py, _viridis_data / _inferno_data entries 0, 127, 128 and 255
PUBLISHED = {
    "viridis": {
        0: (0.267004, 0.004874, 0.329415),
        127: (0.128729, 0.563265, 0.551229),
        128: (0.127568, 0.566949, 0.550556),
        255: (0.993248, 0.906157, 0.143936),
    },
    "inferno": {
        0: (0.001462, 0.000466, 0.013866),
        127: (0.729909, 0.212759, 0.333861),
        128: (0.735683, 0.215906, 0.330245),
        255: (0.988362, 0.998364, 0.644924),
    },
}


def test_cmaps_listed():
    assert CMAPS == ("grey", "viridis", "inferno")


@pytest.mark.parametrize("name", ["viridis", "inferno"])
def test_endpoints_equal_published_values(name):
    for i in (0, 255):
        assert sample(name, np.array(i / 255)) == pytest.approx(PUBLISHED[name][i], abs=1e-6)


@pytest.mark.parametrize("name", ["viridis", "inferno"])
def test_interpolated_entries_within_one_8bit_step(name):
    # 127 and 128 are not anchors (anchors are every 5th entry): interpolation must stay
    # within one 8-bit step of the published table
    for i in (127, 128):
        got = sample(name, np.array(i / 255))
        assert np.abs(got - PUBLISHED[name][i]).max() < 1 / 255


def test_palette_ends_and_grey():
    # 8-bit rounding of the published ends: viridis 0 → (68, 1, 84), 255 → (253, 231, 37)
    v = palette("viridis", 256)
    assert tuple(v[0]) == (68, 1, 84) and tuple(v[-1]) == (253, 231, 37)
    g = palette("grey", 32)
    assert tuple(g[0]) == (0, 0, 0) and tuple(g[-1]) == (255, 255, 255)
    assert len(g) == 32


@pytest.mark.parametrize("levels", [31, 257])
def test_levels_out_of_range(levels):
    with pytest.raises(ValueError, match="32..256"):
        palette("grey", levels)


def test_unknown_cmap():
    with pytest.raises(ValueError, match="viridis"):
        palette("jet")


def test_quantisation_edges():
    # level k holds [k/L, (k+1)/L) of t·L snapped to 2⁻³⁰ (core.numerics.snap): 1e-8 below a
    # boundary (3.2e-7 of a level) is below it, 1e-13 below (3.2e-12 of a level, a few
    # ulps: the last bits of a CPU's exp or pow) is on it; t = 1 falls in the top level;
    # NaN → transparent
    L = 32
    t = np.array([0.0, 1 / L - 1e-8, 1 / L - 1e-13, 1 / L, 1 / L + 1e-13, 0.5, 1 - 1e-8,
                  1.0, np.nan])
    assert quantise(t, L).tolist() == [0, 0, 1, 1, 1, 16, 31, 31, TRANSPARENT]


def test_linear_scale_zero_to_max():
    s = Scale.for_values(np.array([0.0, 2.0, np.nan]))
    assert s.vmax == 2.0 and s.vmin == 0.0
    assert s.normalise(np.array([0.0, 1.0, 2.0])).tolist() == [0.0, 0.5, 1.0]
    assert s.ticks() == (0.0, 1.0, 2.0)


def test_all_zero_picture_gets_lowest_colour():
    c = colorize(np.zeros((2, 2)), levels=32)
    assert (c.index == 0).all()


def test_log_scale_decades():
    # 3 decades: max → 1, max/10 → 2/3, max/1000 and below (and 0) → 0
    s = Scale(2.0, log=True, decades=3)
    t = s.normalise(np.array([2.0, 0.2, 0.002, 1e-9, 0.0, np.nan]))
    assert t[:5] == pytest.approx([1.0, 2 / 3, 0.0, 0.0, 0.0])
    assert np.isnan(t[5])
    lo, mid, hi = s.ticks()
    assert (lo, hi) == pytest.approx((0.002, 2.0)) and mid == pytest.approx(2.0 * 10**-1.5)


def test_nan_is_background_distinct_from_zero():
    c = colorize(np.array([[0.0, np.nan]]), "inferno", levels=64)
    assert c.index.tolist() == [[0, TRANSPARENT]]


def test_rgb_color_mode_common_scale():
    # channels share the maximum (1.0): (1, 0.5, 0) → (255, 128?, 0) at 256 levels:
    # 0.5 → level 128 → 128·255/255 = 128
    c = colorize(np.array([[[1.0, 0.5, 0.0], [np.nan] * 3]]), levels=256)
    assert c.index[0, 1] == TRANSPARENT
    assert tuple(c.palette[c.index[0, 0]]) == (255, 128, 0)


def test_rgb_luminance_mode():
    # pure green (0, 1, 0) has Rec.709 luminance 0.7152; pure white 1 is the max
    c = colorize(np.array([[[0.0, 1.0, 0.0], [1.0, 1.0, 1.0]]]), "grey", levels=256,
                 rgb_mode="luminance")
    assert c.index.tolist() == [[int(0.7152 * 256), 255]]


def test_tick_line_layout():
    assert tick_line(11, "0", "5", "10") == "0    5   10"
    # mid dropped when it would touch a neighbour, right kept
    assert tick_line(6, "0", "555", "10") == "0   10"


def test_colorbar_plain_ramp_and_ticks():
    from rich.console import Console

    con = Console(width=40, color_system=None, record=True)
    con.print(colorbar(Scale(1.0), "grey", 10, color_system="none"))
    bar, ticks = con.export_text().splitlines()
    # grey ramp at cell centres t = 0.05 … 0.95: dark at the left, bright at the right
    assert len(bar) == 10 and bar[0] == " " and bar[-1] == "@"
    assert list(bar) == sorted(bar, key=" .:-=+*#%@".index)  # monotone ramp
    assert ticks.startswith("0") and ticks.endswith("1 sr⁻¹")
