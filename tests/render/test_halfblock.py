"""Half-block renderable: exact segments for hand-built images, escapes, runs, colour systems.

Expected values are written out by hand from the definition (fg = top pixel, bg = bottom pixel,
one segment per run of equal cells), never copied from the code's output.
"""

import io

import numpy as np
import pytest
from rich.console import Console
from rich.segment import Segment
from rich.style import Style

from tuibrdf.render.halfblock import (
    ASCII_RAMP,
    TRANSPARENT,
    XTERM,
    HalfBlockImage,
    Mark,
    find_runs,
    to_xterm,
)

RED, GREEN, BLUE, WHITE, BLACK = (255, 0, 0), (0, 255, 0), (0, 0, 255), (255, 255, 255), (0, 0, 0)


def render(renderable, system, width=20):
    buf = io.StringIO()
    console = Console(file=buf, color_system=system, force_terminal=True, width=width,
                      _environ={})
    console.print(renderable)
    return buf.getvalue()


def hex_color(c):
    return None if c is None else "#" + "".join(f"{v:02x}" for v in c)


def rgb_style(fg=None, bg=None):
    return Style(color=hex_color(fg), bgcolor=hex_color(bg))


def test_two_by_two_image_gives_known_segments():
    # pixels: top row red, green; bottom row blue, green → cell 0 '▀' red on blue,
    # cell 1 top == bottom → a space on green
    img = HalfBlockImage(np.array([[0, 1], [2, 1]]), np.array([RED, GREEN, BLUE]))
    assert img.width == 2 and img.height == 1
    assert img.rows("truecolor") == [[Segment("▀", rgb_style(RED, BLUE)),
                                      Segment(" ", rgb_style(None, GREEN))]]


def test_known_colour_gives_known_escape():
    img = HalfBlockImage(np.array([[0], [1]]), np.array([(255, 128, 0), (0, 0, 255)]))
    # SGR 38;2;r;g;b = truecolor foreground, 48;2 = background (ECMA-48 / ITU T.416)
    assert render(img, "truecolor") == "\x1b[38;2;255;128;0;48;2;0;0;255m▀\x1b[0m\n"
    # xterm: (255,128,0) → cube (5,2,0) = 16 + 36·5 + 6·2 = 208; pure blue → 16 + 5 = 21
    assert render(img, "256") == "\x1b[38;5;208;48;5;21m▀\x1b[0m\n"


def test_runs_of_equal_cells_merge_into_one_segment():
    # 6 cells: 3 × (white over black), 2 × black/black, 1 × white over black
    top = [1, 1, 1, 0, 0, 1]
    bot = [0, 0, 0, 0, 0, 0]
    img = HalfBlockImage(np.array([top, bot]), np.array([BLACK, WHITE]))
    assert img.rows("truecolor") == [[
        Segment("▀▀▀", rgb_style(WHITE, BLACK)),
        Segment("  ", rgb_style(None, BLACK)),
        Segment("▀", rgb_style(WHITE, BLACK)),
    ]]


def test_find_runs_covers_each_row():
    codes = np.array([[5, 5, 7, 7, 7], [1, 2, 2, 2, 1]])
    rows, starts, lengths = find_runs(codes)
    assert rows.tolist() == [0, 0, 1, 1, 1]
    assert starts.tolist() == [0, 2, 0, 1, 4]
    assert lengths.tolist() == [2, 3, 1, 3, 1]


def test_transparent_pixels_use_terminal_background():
    idx = np.array([[0, TRANSPARENT, TRANSPARENT], [TRANSPARENT, 0, TRANSPARENT]])
    img = HalfBlockImage(idx, np.array([RED]))
    assert img.rows("truecolor") == [[
        Segment("▀", rgb_style(RED, None)),
        Segment("▄", rgb_style(RED, None)),
        Segment(" ", Style()),
    ]]


def test_odd_height_pads_a_transparent_bottom_row():
    img = HalfBlockImage(np.array([[0, 0], [0, 0], [0, 0]]), np.array([RED]))
    assert img.height == 2
    assert img.rows("truecolor")[1] == [Segment("▀▀", rgb_style(RED, None))]


def test_256_colours_merge_neighbours_that_land_on_one_index():
    # (250,0,0) and (255,6,0) are distinct truecolours but both nearest to xterm 196 (255,0,0)
    img = HalfBlockImage(np.array([[0, 1], [0, 1]]), np.array([(250, 0, 0), (255, 6, 0)]))
    assert len(img.rows("truecolor")[0]) == 2
    assert img.rows("256") == [[Segment("  ", Style(bgcolor="color(196)"))]]


def test_xterm_nearest_maps_every_palette_colour_to_itself():
    # the 240 colours 16..255 are pairwise distinct, so each is its own nearest neighbour
    assert to_xterm(XTERM[16:]).tolist() == list(range(16, 256))
    # the cube levels are 0,95,135,175,215,255: 47 is nearer 0 than 95 → the grey ramp wins
    # (38 at index 235 is nearer than 0 at 16)
    assert int(to_xterm(np.array([47, 47, 47]))) == 232 + 4  # grey 8 + 10·4 = 48


def test_plain_fallback_uses_the_density_ramp():
    # black → ramp[0], white → ramp[-1]; (white over black) averages to luma 0.5 → ramp[4.5→4]
    img = HalfBlockImage(np.array([[0, 1, 1], [0, 1, 0]]), np.array([BLACK, WHITE]))
    (row,) = img.rows("none")
    text = "".join(s.text for s in row)
    assert text == ASCII_RAMP[0] + ASCII_RAMP[-1] + ASCII_RAMP[4]
    assert render(img, None) == text + "\n"
    assert img.plain() == text


@pytest.mark.parametrize("system", ["truecolor", "256", "none"])
def test_every_segment_has_a_style_and_rows_are_full_width(system):
    rng = np.random.default_rng(1)
    idx = rng.integers(-1, 4, size=(7, 9))
    img = HalfBlockImage(idx, np.array([RED, GREEN, BLUE, BLACK]),
                         marks=[Mark(1, 2)])
    rows = img.rows(system)
    assert len(rows) == 4
    for row in rows:
        assert sum(s.cell_length for s in row) == 9
        assert all(s.style is not None for s in row)


def test_mark_splits_runs_and_draws_its_glyph():
    img = HalfBlockImage(np.zeros((2, 3), int), np.array([BLACK]),
                         marks=[Mark(0, 1, "×", "X", WHITE)])
    assert img.rows("truecolor") == [[
        Segment(" ", rgb_style(None, BLACK)),
        Segment("×", rgb_style(WHITE, BLACK)),
        Segment(" ", rgb_style(None, BLACK)),
    ]]
    assert img.plain() == " X "


@pytest.mark.parametrize("system", ["truecolor", "256", "none"])
def test_a_cell_is_drawn_by_its_colours_whatever_the_palette(system):
    """Two pictures of the same pixels with their palettes in another order (an RGB picture's
    palette is its own colours, in another order each frame) draw the same rows, and the
    second reuses the first's rows where its cells are the same (the same list objects); a
    mark over other colours at the same palette indices is drawn over those colours."""
    pixels = np.array([[RED, GREEN, BLUE], [BLUE, BLUE, WHITE]], dtype=np.uint8)
    a = HalfBlockImage.from_rgb(np.concatenate([pixels, pixels]), color_system=system)
    order = [3, 1, 0, 2]  # the palette of b lists a's colours in this order
    pal_b = a.palette[order]
    b = HalfBlockImage(np.argsort(order)[a.index], pal_b, color_system=system)
    assert not np.array_equal(a.palette, b.palette)
    rows_a, rows_b = a.rows(system), b.rows(system, like=a)
    assert rows_a == rows_b
    assert all(rb is ra for ra, rb in zip(rows_a, rows_b, strict=True))  # kept, not drawn
    # a mark's look follows the colours under it, not their palette indices
    index = np.array([[0], [1]])
    one = HalfBlockImage(index, np.array([BLACK, WHITE]), marks=[Mark(0, 0, "×", "X", RED)])
    two = HalfBlockImage(index, np.array([WHITE, WHITE]), marks=[Mark(0, 0, "×", "X", RED)])
    if system == "truecolor":
        mid = (128, 128, 128)  # the mean of black and white, rounded
        assert one.rows(system) == [[Segment("×", rgb_style(RED, mid))]]
        assert two.rows(system) == [[Segment("×", rgb_style(RED, WHITE))]]


def test_from_rgb_builds_palette_and_mask():
    rgb = np.array([[RED, BLUE], [RED, GREEN]], dtype=np.uint8)
    img = HalfBlockImage.from_rgb(rgb, mask=np.array([[True, True], [True, False]]))
    assert img.rows("truecolor") == [[Segment(" ", rgb_style(None, RED)),
                                      Segment("▀", rgb_style(BLUE, None))]]


@pytest.mark.parametrize("bad", [np.array([[0, 3]]), np.array([[-2, 0]]),
                                 np.array([[0.0, 1.0]])])
def test_rejects_out_of_palette_or_float_index(bad):
    with pytest.raises(ValueError):
        HalfBlockImage(bad, np.array([RED, GREEN, BLUE]))


def test_console_colour_system_is_followed():
    img = HalfBlockImage(np.array([[0], [0]]), np.array([WHITE]))
    assert render(img, "truecolor") == "\x1b[48;2;255;255;255m \x1b[0m\n"
    assert render(img, "256") == "\x1b[48;5;231m \x1b[0m\n"  # cube (5,5,5) = 231


def _ring_cells_form_a_closed_loop(plain: str, ring_char: str) -> bool:
    """The cells showing ``ring_char`` form one 8-connected set in which every cell has at
    least two ring neighbours (a loop with no loose end and no gap).  Written here, not taken
    from the renderer: a flood fill over the characters."""
    grid = [[ch == ring_char for ch in line] for line in plain.split("\n")]
    cells = {(r, c) for r, row in enumerate(grid) for c, on in enumerate(row) if on}
    if not cells:
        return False

    def around(r, c):
        return [(r + dr, c + dc) for dr in (-1, 0, 1) for dc in (-1, 0, 1)
                if (dr or dc) and (r + dr, c + dc) in cells]

    if any(len(around(r, c)) < 2 for r, c in cells):
        return False
    seen, todo = set(), [next(iter(cells))]
    while todo:
        cell = todo.pop()
        if cell not in seen:
            seen.add(cell)
            todo.extend(around(*cell))
    return seen == cells


@pytest.mark.parametrize("px_w", [20, 33, 40, 64, 81, 120])
@pytest.mark.parametrize("px_h", [12, 17, 30, 31, 44, 60])
def test_plain_horizon_ring_is_a_closed_loop(px_w, px_h):
    # --color none drew the ring with a gap at the top centre of the disc: where the disc's
    # top edge is flat the ring is one pixel row, all of it in cells whose other half is data,
    # and such a cell showed the data alone.  The disc and its ring come from the map's own
    # geometry (hemimap.geometry's inside mask); the ring is computed here as the pixels
    # outside the disc that touch it (8-neighbourhood), the definition in docs/design.md.  Data
    # pixels are black, so a cell that shows data is a blank: only ring cells are "~".
    from tuibrdf.core.views.hemimap import geometry
    from tuibrdf.render.halfblock import RING_CHAR

    inside = geometry(px_w, px_h).inside
    padded = np.pad(inside, 1)
    touch = np.zeros_like(inside)
    for dr in (-1, 0, 1):
        for dc in (-1, 0, 1):
            touch |= padded[1 + dr:1 + dr + px_h, 1 + dc:1 + dc + px_w]
    ring = touch & ~inside
    index = np.where(inside, 0, np.where(ring, 1, TRANSPARENT))
    img = HalfBlockImage(index, np.array([BLACK, (72, 72, 160)], dtype=np.uint8), ring=1)
    plain = img.plain()
    assert _ring_cells_form_a_closed_loop(plain, RING_CHAR), plain
    # only the ring's cells changed to "~": no cell without a ring pixel shows it
    top, bottom = ring[0::2], np.vstack([ring[1::2], np.zeros((px_h % 2, px_w), bool)])
    shown = np.array([[ch == RING_CHAR for ch in line] for line in plain.split("\n")])
    assert not (shown & ~(top | bottom)).any()


def test_plain_map_top_of_the_disc_has_no_gap():
    # the case seen on screen: `tuibrdf render phong --width 64 --height 18 --color none`,
    # whose top ring row read "~~~~       ~~~~"; expected: the top row of the disc is one
    # unbroken run of "~"
    from tuibrdf.core.registry import MODELS
    from tuibrdf.render.halfblock import RING_CHAR
    from tuibrdf.render.views import render_view

    m = MODELS["phong"]
    buf = io.StringIO()
    Console(file=buf, width=64, color_system=None, _environ={}).print(
        render_view("map", m, m.resolve({}), 30.0, 64, 18, color="none"))
    first = buf.getvalue().splitlines()[1].strip()
    assert first and set(first) == {RING_CHAR}, first


def test_shades_draw_each_channel_on_evenly_spaced_levels_and_keep_the_palette():
    # shades=64: every drawn channel is round(k·255/63) for the k nearest to the palette's
    # value v (k = round(v·63/255): never a tie, (2k+1)·255/126 is not an integer); the
    # palette itself (what an export reads) is untouched, and without shades the colours
    # are drawn as given
    vals = np.arange(256)
    pal = np.stack([vals, vals[::-1], (vals * 7) % 256], axis=1).astype(np.uint8)
    index = np.arange(256).reshape(2, 128)  # one cell per pair of palette entries
    img = HalfBlockImage(index, pal, shades=64)
    drawn = [(seg.style.color.triplet, seg.style.bgcolor.triplet)
             for row in img.rows("truecolor") for seg in row for _ in seg.text]
    assert len(drawn) == 128
    for c, (top, bottom) in enumerate(drawn):
        for got, want in ((top, pal[c]), (bottom, pal[128 + c])):
            for g, v in zip(got, want.tolist(), strict=True):
                assert g == round(round(v * 63 / 255) * 255 / 63)
    assert np.array_equal(img.palette, pal)
    exact = HalfBlockImage(index, pal).rows("truecolor")
    assert exact[0][0] == Segment("▀", rgb_style(tuple(pal[0]), tuple(pal[128])))
    # neighbours that land on one shade merge into one run; 256 colours ignore shades
    grey = np.array([[100, 101, 102, 103]], dtype=np.uint8).T.repeat(3, axis=1)
    merged = HalfBlockImage(np.array([[0, 1, 2, 3]] * 2), grey, shades=64)
    assert [len(seg.text) for seg in merged.rows("truecolor")[0]] == [4]  # all → 101.19 → 101
    assert (HalfBlockImage(np.array([[0, 1, 2, 3]] * 2), grey, shades=64).rows("256")
            == HalfBlockImage(np.array([[0, 1, 2, 3]] * 2), grey).rows("256"))


def test_rgb_colour_pictures_are_drawn_in_shades_colour_maps_are_not():
    from tuibrdf.render.colormap import colorize
    from tuibrdf.render.halfblock import SHADES

    rgb = np.random.default_rng(3).random((4, 4, 3))
    assert colorize(rgb, "grey", rgb_mode="color").shades == SHADES == 64
    assert colorize(rgb, "grey", rgb_mode="luminance").shades is None
    assert colorize(rgb[..., 0], "viridis").shades is None
