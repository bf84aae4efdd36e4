"""Compare mode tells A from B in every colour mode (issue 12 item 2) and the albedo axis
fits the curves (item 8)."""

import numpy as np

from tuibrdf.render.albedo_plot import nice_top
from tuibrdf.render.curves import SIDE_MARKERS, side_curves
from tuibrdf.render.panes import signed_text


def test_each_side_has_its_own_marker_and_legend_entries():
    # three different channels (equal ones read as one grey curve, issue 36)
    rgb = np.column_stack([np.linspace(0, 1, 5), np.linspace(0, 0.5, 5), np.linspace(0, 0.2, 5)])
    scalar = np.linspace(0, 2, 5)
    # compare mode's default ("rgb") shows an RGB side's luminance: six curves in one plot
    # cannot be read (issue 32)
    assert [c[0] for c in side_curves([("gltf", rgb), ("ggx", scalar)], "rgb")] == [
        "A:gltf (Y)", "B:ggx"]
    curves = side_curves([("gltf", rgb), ("ggx", scalar)], "all")
    labels = [c[0] for c in curves]
    # one legend entry per curve, side named; a channel in words ("A:B" would read as two
    # sides, "B:B" as side B twice)
    assert labels == ["A:red", "A:green", "A:blue", "B:ggx"]
    assert {c[2] for c in curves[:3]} == {SIDE_MARKERS[0]} and curves[3][2] == SIDE_MARKERS[1]
    assert SIDE_MARKERS[0] != SIDE_MARKERS[1]  # the marker survives --color none
    # each side its own hue family, whatever the channel: no colour of A's is one of B's
    assert not {c[3] for c in curves[:3]} & {curves[3][3]}
    # the channel choice: luminance (Rec.709: 0.2126 R + 0.7152 G + 0.0722 B) or one channel
    rgb2 = np.column_stack([np.full(4, 1.0), np.full(4, 0.0), np.full(4, 0.0)])
    lum = side_curves([("a", rgb2), ("b", rgb2)], "lum")
    assert [c[0] for c in lum] == ["A:a (Y)", "B:b (Y)"]
    np.testing.assert_allclose(lum[0][1], 0.2126, rtol=1e-3)
    green = side_curves([("a", rgb2)], "G")
    assert green[0][0] == "G" and np.all(green[0][1] == 0.0)


def test_difference_map_without_colour_says_the_sign():
    # A larger on the left half, B larger on the right, equal in the middle column, outside
    # (NaN) blank: the characters must say which (the colour legend cannot)
    d = np.full((4, 5), np.nan)
    d[:, 0] = 0.5
    d[:, 1] = 0.1
    d[:, 2] = 0.0
    d[:, 3] = -0.1
    d[:, 4] = -0.5
    d[0, :] = np.nan
    rows = signed_text(d).plain.splitlines()
    assert rows == ["#+.-=", "#+.-="]  # row 0 = pixel rows 0–1 (one finite), row 1 = 2–3


def test_albedo_axis_fits_a_specular_albedo():
    # a specular albedo of 0.05 must not be squashed under a fixed 0–1.1 axis: the axis end
    # is within 1.1–1.5 × the maximum (the 1-1.2-1.5-2… rounding); near 1 the axis includes 1
    for peak in (0.04, 0.05, 0.09, 0.3):
        top = nice_top(peak)
        assert 1.1 * peak <= top <= 1.5 * 1.1 * peak
    assert nice_top(0.95) >= 1.0 and nice_top(1.3) >= 1.3 * 1.1
