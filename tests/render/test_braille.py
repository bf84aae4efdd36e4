"""The braille plot canvas (``tuibrdf.render.braille``) and the polar sections drawn with it
(``tuibrdf.render.sections``).

Expected dots come from the Unicode braille layout (dot k of a cell is bit k−1; dots 1-2-3-7
run down the left column, 4-5-6-8 the right one) and from the canvas's documented mapping:
data x0 … x1 over ``2W`` dot columns, y1 … y0 over ``4H`` dot rows, dot centres at integer
coordinates.
"""

from __future__ import annotations

import numpy as np
import pytest
from rich.console import Console

from tuibrdf.core.registry import get_model
from tuibrdf.render.braille import BrailleCanvas, charset_for, legend_sample
from tuibrdf.render.sections import fwhm_text
from tuibrdf.render.views import render_view


def section_view(plane, m, values, theta_i, w, h, **kw):
    """The sections pane through the one frame computation (``tuibrdf render``'s path)."""
    return render_view(plane, m, values, theta_i, w, h, **kw)


def peak_section_view(m, values, theta_i, w, h, *, azimuth_deg=90.0, **kw):
    return render_view("perpendicular", m, values, theta_i, w, h,
                       section_azimuth_deg=azimuth_deg, **kw)


def text_rows(canvas: BrailleCanvas) -> list[str]:
    """The characters of each row, as Rich draws the canvas (its rows of segments)."""
    return ["".join(s.text for s in row) for row in canvas.rows()]


def lit_dots(canvas: BrailleCanvas) -> set[tuple[int, int]]:
    """Decode the characters back into (dot row, dot column): an independent reading of the
    output, through the Unicode layout rather than the canvas's own arrays."""
    bit_of = {(0, 0): 0, (1, 0): 1, (2, 0): 2, (0, 1): 3, (1, 1): 4, (2, 1): 5, (3, 0): 6,
              (3, 1): 7}
    dots = set()
    for r, line in enumerate(text_rows(canvas)):
        for c, ch in enumerate(line):
            code = ord(ch) - 0x2800 if ch != " " else 0
            assert 0 <= code < 256, ch
            for (dr, dc), bit in bit_of.items():
                if code >> bit & 1:
                    dots.add((4 * r + dr, 2 * c + dc))
    return dots


def test_horizontal_line_lights_exactly_its_row():
    # 10 × 3 cells = 20 × 12 dots over x 0..20, y 0..12: dot (row, col) has its centre at
    # x = col + 0.5, y = 12 − row − 0.5.  y = 6.5 is dot row 5 (cell row 1, dot row 1 = dot 2/5,
    # bits 0x02 | 0x10); x from 2.5 to 9.5 are dot columns 2..9
    cv = BrailleCanvas(10, 3, (0.0, 20.0), (0.0, 12.0), color="none")
    cv.polyline(np.array([2.5, 9.5]), np.array([6.5, 6.5]), cv.layer(None))
    assert lit_dots(cv) == {(5, c) for c in range(2, 10)}
    assert text_rows(cv)[1] == " " + "⠒" * 4 + " " * 5
    assert text_rows(cv)[0] == text_rows(cv)[2] == " " * 10


def test_vertical_and_diagonal_lines_are_connected():
    cv = BrailleCanvas(8, 4, (0.0, 16.0), (0.0, 16.0), color="none")
    lid = cv.layer(None)
    cv.polyline(np.array([0.5, 15.5]), np.array([15.5, 0.5]), lid)  # the anti-diagonal
    dots = lit_dots(cv)
    assert dots == {(k, k) for k in range(16)}  # one dot per row and per column, no gaps


def test_circle_dots_lie_within_half_a_dot_of_the_radius():
    # square dots: 40 × 20 cells = 80 × 80 dots over a 80 × 80 data square; centre (40, 40)
    cv = BrailleCanvas(40, 20, (0.0, 80.0), (0.0, 80.0), color="none")
    cv.polyline(*cv.arc_points(40.0, 40.0, 30.0), cv.layer(None))  # as guide_dots draws
    dots = lit_dots(cv)
    rows = np.array([d[0] for d in dots])
    cols = np.array([d[1] for d in dots])
    x, y = cols + 0.5, 80.0 - rows - 0.5  # dot centres in data units (1 unit = 1 dot)
    r = np.hypot(x - 40.0, y - 40.0)
    # rounding a point of the circle to the nearest dot centre moves it ≤ ½ dot in x and in y:
    # ≤ ½·√2 radially in the worst case, ≤ ½ in the direction of the radius along the axes
    assert np.all(np.abs(r - 30.0) <= 0.5 * np.sqrt(2) + 1e-9)
    assert np.mean(np.abs(r - 30.0)) < 0.3
    # closed: every dot column the circle spans (10..69) is lit
    assert set(cols.tolist()) == set(range(10, 70))


def test_patterns_differ_and_survive_plain_text():
    # two parallel lines, solid and dotted: in plain text (no colours) the dotted one has half
    # the dots of the solid one
    cv = BrailleCanvas(20, 2, (0.0, 40.0), (0.0, 8.0), color="none")
    a, b = cv.layer("red", "solid"), cv.layer("cyan", "dotted")
    cv.polyline(np.array([0.5, 39.5]), np.array([7.5, 7.5]), a)
    cv.polyline(np.array([0.5, 39.5]), np.array([0.5, 0.5]), b)
    dots = lit_dots(cv)
    top = sorted(c for r, c in dots if r == 0)
    bottom = sorted(c for r, c in dots if r == 7)
    assert top == list(range(40)) and bottom == list(range(0, 40, 2))
    assert legend_sample("solid", "braille", "*") != legend_sample("dotted", "braille", "o")


def test_colours_per_curve_and_none_has_no_styles():
    cv = BrailleCanvas(10, 2, (0.0, 20.0), (0.0, 8.0), color="truecolor")
    a, b = cv.layer("red"), cv.layer("cyan")
    cv.polyline(np.array([0.5, 9.5]), np.array([7.5, 7.5]), a)  # cells 0..4 of row 0
    cv.polyline(np.array([10.5, 19.5]), np.array([7.5, 7.5]), b)  # cells 5..9 of row 0
    row = cv.rows()[0]
    assert [(s.text, s.style.color.name if s.style.color else None) for s in row] == [
        ("⠉" * 5, "red"), ("⠉" * 5, "cyan")]
    cv.color = "none"
    assert all(s.style.color is None for s in cv.rows()[0])


def test_ascii_fallback_uses_markers_per_layer():
    cv = BrailleCanvas(10, 2, (0.0, 20.0), (0.0, 8.0), color="none", charset="ascii")
    g, a = cv.layer("color(244)", "sparse", "."), cv.layer("red", "solid", "*")
    cv.polyline(np.array([0.5, 19.5]), np.array([0.5, 0.5]), g)
    cv.polyline(np.array([0.5, 9.5]), np.array([7.5, 7.5]), a)
    # sparse: 1 dot in 4 along the path, dots 0, 4, 8, 12, 16 → every 2nd cell
    assert text_rows(cv) == ["*****     ", ". . . . . "]
    assert all(ord(ch) < 128 for line in text_rows(cv) for ch in line)


def test_text_overlay_and_non_finite_points():
    cv = BrailleCanvas(10, 2, (0.0, 20.0), (0.0, 8.0), color="none")
    lid = cv.layer(None)
    # a NaN breaks the line: the two halves are drawn, nothing joins them
    cv.polyline(np.array([0.5, 3.5, np.nan, 16.5, 19.5]), np.full(5, 7.5), lid)
    cv.text(1, 2, "hello, world")  # cropped at the right edge
    assert text_rows(cv) == ["⠉⠉      ⠉⠉", "  hello, w"]


def test_charset_for_encoding():
    assert charset_for("utf-8") == "braille"
    assert charset_for("ascii") == "ascii"
    assert charset_for("latin-1") == "ascii"
    assert charset_for(None) == "braille"  # io.StringIO: text, written as UTF-8


def test_bad_canvas_arguments():
    with pytest.raises(ValueError):
        BrailleCanvas(0, 3, (0, 1), (0, 1))
    with pytest.raises(ValueError):
        BrailleCanvas(3, 3, (1, 1), (0, 1))
    with pytest.raises(ValueError):
        BrailleCanvas(3, 3, (0, 1), (0, 1), charset="ebcdic")
    with pytest.raises(ValueError):
        BrailleCanvas(3, 3, (0, 1), (0, 1)).layer("red", "wavy")


# -- polar views -------------------------------------------------------------------------------
def render(renderable, width: int) -> list[str]:
    con = Console(width=width, color_system=None, file=None, record=False, force_terminal=False)
    with con.capture() as cap:
        con.print(renderable)
    return cap.get().splitlines()


SEED_CT = {"kd": 0.0, "f0": 0.04, "m": 0.07}


def test_section_view_matches_polar_geometry():
    # modified Phong kd = 0, ks = 1, n = 200 at θi = 0: the lobe points straight up with peak
    # (n+2)/(2π) = 32.15 and FWHM 2·acos(0.5^(1/200)) = 9.5°: the topmost lit dot of the plot
    # is the peak, on the centre column, at the top of the outer circle
    m = get_model("phong")
    values = m.resolve({"kd": 0.0, "ks": 1.0, "n": 200})
    lines = render(section_view("incidence", m, values, 0.0, 80, 24, color="none"), 80)
    assert len(lines) == 24 and all(len(ln) <= 80 for ln in lines)
    assert "max 32.1" in lines[0] and "circles every 10" in lines[0]
    # the lobe's tip (r = 32.1) reaches above the outer guide circle (r = 30): the topmost
    # lit cell row holds the tip alone, on the centre columns (the plot is 80 cells wide)
    first = next(ln for ln in lines[1:] if ln.strip())
    assert {i for i, ch in enumerate(first) if ch != " "} <= {39, 40}


def test_peak_section_view_title_and_width():
    m = get_model("cook-torrance")
    values = m.resolve(SEED_CT)
    lines = render(peak_section_view(m, values, 60.0, 100, 24, color="none"), 100)
    # issue 13: the width across the lobe at 60° is 6.6°; the peak sits at θ = 62.0°
    assert "perp. through peak θ=62° φ=0°" in lines[0] and "FWHM 6.6°" in lines[0]
    assert "max 6.14" in lines[0]
    lines = render(peak_section_view(m, values, 60.0, 100, 24, azimuth_deg=0.0, color="none"),
                   100)
    assert "ψ=0° through peak" in lines[0] and "FWHM 13.8°" in lines[0]


def test_fwhm_text():
    # the core's width (tests/core/views/test_sections.py), one decimal from 1°, two below
    assert fwhm_text(10.0) == "FWHM 10.0°"
    assert fwhm_text(0.1234) == "FWHM 0.12°"
    assert fwhm_text(float("nan")) == "" and fwhm_text(None) == ""


@pytest.mark.parametrize("charset", ["braille", "ascii"])
def test_rgb_sections_have_a_legend_and_are_deterministic(charset):
    m = get_model("gltf")
    values = m.resolve({"base_color": [0.9, 0.3, 0.1]})
    a = render(section_view("incidence", m, values, 30.0, 60, 16, color="none",
                            charset=charset), 60)
    b = render(section_view("incidence", m, values, 30.0, 60, 16, color="none",
                            charset=charset), 60)
    assert a == b
    assert [ln[4:5] for ln in a[1:4]] == ["R", "G", "B"]
    if charset == "ascii":
        assert all(ord(ch) < 128 for ln in a[1:] for ch in ln)
        assert a[1][:3] == "***" and a[2][:3] == "ooo" and a[3][:3] == "+++"


def test_points_far_outside_are_clipped_not_sampled():
    # a value 1e30 times the axis (a grazing microfacet value) must draw the visible part of
    # its segment, not allocate 1e30 samples: the segment from (0.5, 0.5) to (0.5, 1e30) is
    # the left dot column, all 8 rows of a 1 × 2 cell canvas over 0..2 × 0..8
    cv = BrailleCanvas(1, 2, (0.0, 2.0), (0.0, 8.0), color="none")
    cv.polyline(np.array([0.5, 0.5]), np.array([0.5, 1e30]), cv.layer(None))
    assert lit_dots(cv) == {(r, 0) for r in range(8)}
    # a segment entirely outside draws nothing
    cv2 = BrailleCanvas(1, 2, (0.0, 2.0), (0.0, 8.0), color="none")
    cv2.polyline(np.array([5.0, 9.0]), np.array([1e10, 1e30]), cv2.layer(None))
    assert lit_dots(cv2) == set()



def test_guides_drawn_once_are_the_guides_drawn_each_time():
    """The guide circles are drawn once per window (``guide_dots``, cached) and copied onto
    each canvas: every canvas must carry the guides drawn afresh for its own window (the
    function without its cache), whatever window came before."""
    from tuibrdf.render.sections import guide_dots, plot_window, polar_canvas

    t = np.linspace(-90.0, 90.0, 181)
    drawn = []
    for vmax in (1.0, 1.0, 2.5, 0.37, 1.0):
        curve = [("f", t, vmax * np.cos(np.radians(t)) ** 8)]
        got, caption = polar_canvas(curve, 60, 18, theta_i_deg=30.0)
        step = float(caption.split("every ")[1])
        guides = tuple(step * np.arange(1, int(np.floor(vmax / step + 1e-9)) + 1))
        rmax = max(vmax, guides[-1])
        fresh = guide_dots.__wrapped__(60, 18, *plot_window(60, 18, rmax), rmax, guides)
        covered = got.owner > 0  # the light line and the curve drawn over the guides
        assert np.array_equal(got.owner == 0, (fresh == 0) & ~covered)
        drawn.append(fresh == 0)
    assert not np.array_equal(drawn[0], drawn[3])  # other circles in their window
    assert np.array_equal(drawn[0], drawn[4])


def test_points_on_the_limits_are_drawn_in_the_edge_dots():
    """The canvas covers the data window with both ends included: f = 0 on a y axis from 0
    and θ = 90° on an x axis to 90° are the bottom row and the last column of dots (they fell
    one dot past the edge and were dropped, so a curve reaching 0 seemed to stop); a point
    beyond the window is still dropped."""
    cv = BrailleCanvas(10, 3, (0.0, 90.0), (0.0, 1.0))
    a = cv.layer("red")
    cv.polyline(np.array([2.25, 87.75]), np.array([0.0, 0.0]), a)  # first to last dot centre
    assert (cv.owner[-1] == a).all()  # the whole bottom row of dots
    cv.polyline(np.array([90.0]), np.array([1.0]), a)  # a lone point
    assert cv.owner[0, -1] == a  # the top-right dot
    b = cv.layer("cyan")
    just_out = 90.0 * (1 + 1e-9)
    # lone points (a NaN between them breaks the line) just beyond the right and bottom edges
    cv.polyline(np.array([just_out, np.nan, 45.0]), np.array([0.5, np.nan, -1e-9]), b)
    assert not (cv.owner == b).any()


def _legend_canvas(height: int, labels: list[str], patterns: list[str]):
    from tuibrdf.render.braille import draw_legend

    c = BrailleCanvas(40, height, (0.0, 1.0), (0.0, 1.0), color="truecolor")
    colours = {"red": "#ff0000", "green": "#00ff00", "blue": "#0000ff"}
    ids = [c.layer(colours[lab.split(":")[-1]], pat, "*" if pat == "solid" else "+")
           for lab, pat in zip(labels, patterns, strict=True)]
    draw_legend(c, [(lab, np.zeros(0), np.zeros(0)) for lab in labels], ids)
    return c


def _cell_colours(row) -> list[str | None]:
    out = []
    for seg in row:
        name = None if seg.style is None or seg.style.color is None else \
            seg.style.color.get_truecolor().hex
        out += [name] * len(seg.text)
    return out


COMPARE_RGB = [f"{s}:{n}" for s in "AB" for n in ("red", "green", "blue")]
COMPARE_PATTERNS = ["solid"] * 3 + ["dotted"] * 3


def test_a_legend_with_more_curves_than_rows_names_every_curve_a_side_a_line():
    # compare mode, two RGB sides in a section of 4 rows: 6 curves, 2 lines, every channel
    # named in its colour after its side's line sample (B:blue was cut before)
    c = _legend_canvas(4, COMPARE_RGB, COMPARE_PATTERNS)
    lines, rows = text_rows(c), c.rows()
    for r, side, pattern in ((0, "A", "solid"), (1, "B", "dotted")):
        sample = legend_sample(pattern, "braille", "")
        assert lines[r].startswith(f"{sample} {side}:red green blue")
        colours = _cell_colours(rows[r])
        for word, hexa in (("red", "#ff0000"), ("green", "#00ff00"), ("blue", "#0000ff")):
            at = lines[r].index(word)
            assert set(colours[at:at + len(word)]) == {hexa}, (side, word)
        assert colours[0] == "#ff0000"  # the sample in the first curve's colour
    assert lines[2].strip() == lines[3].strip() == ""


def test_a_legend_that_fits_keeps_one_line_a_curve():
    c = _legend_canvas(6, COMPARE_RGB, COMPARE_PATTERNS)
    lines = text_rows(c)
    for r, lab in enumerate(COMPARE_RGB):
        assert lines[r].rstrip().endswith(" " + lab)


def test_a_legend_folds_only_curves_of_one_side_drawn_alike():
    # labels with no side, or one side's curves in different patterns, keep a line each
    # (what does not fit is cut, as before)
    c = _legend_canvas(2, ["red", "green", "blue"], ["solid", "dotted", "solid"])
    assert [x.split()[-1] for x in text_rows(c)] == ["red", "green"]
    c = _legend_canvas(2, ["A:red", "A:green", "A:blue"], ["solid", "dotted", "dotted"])
    lines = [x.rstrip() for x in text_rows(c)]
    assert lines[0].endswith(" A:red") and lines[1].endswith(" A:green blue")
