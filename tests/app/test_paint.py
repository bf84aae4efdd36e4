"""The viewer's own way to the terminal (tuibrdf/app/paint.py, ``Rows.render_lines``) and what
a slow frame shows meanwhile (tuibrdf/app/frames.py): the same cells as Textual's own way.

The references are Textual's: its compositor's partial update and its styles cache's lines,
run on the same screen state; the cells the terminal shows are compared through a small
terminal model written here (cursor moves, SGR, text).  No timings.
"""

from __future__ import annotations

import asyncio
import re
import threading
import unicodedata
from functools import partial

import pytest
from rich.color import ColorSystem
from rich.console import Console
from rich.segment import Segment
from rich.style import Style
from textual._compositor import Compositor
from textual.geometry import Region
from textual.strip import Strip
from textual.widget import Widget

from tests.pilot import wait_for
from tuibrdf.app import frames, textual_internals
from tuibrdf.app.app import BrdfApp
from tuibrdf.app.paint import ViewerCompositor, _cells
from tuibrdf.app.widgets import Rows
from tuibrdf.core.views import frame as core_frame
from tuibrdf.state.viewer import Side, ViewerState


@pytest.fixture(autouse=True)
def config_home(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path))


class Terminal:
    """The cells of a terminal as the viewer's output sets them: ``CSI row;col H`` moves the
    cursor, ``CSI … m`` sets the SGR attributes (``0`` or none resets them), ``\\n`` moves a
    line down, OSC strings (links) change no cell, every other character fills its cells
    (two for East Asian wide and full-width ones) with the attributes in force."""

    CSI = re.compile(r"\x1b\[([0-9;?]*)([A-Za-z])")

    def __init__(self, width: int, height: int) -> None:
        self.cells = [[(" ", ())] * width for _ in range(height)]
        self.x = self.y = 0
        self.sgr: tuple[str, ...] = ()

    def feed(self, data: str) -> None:
        i = 0
        while i < len(data):
            c = data[i]
            if data.startswith("\x1b]", i):  # OSC, up to the string terminator
                i = data.index("\x1b\\", i) + 2
                continue
            if c == "\x1b":
                m = self.CSI.match(data, i)
                assert m is not None, f"unexpected escape {data[i:i + 12]!r}"
                params, command = m.groups()
                if command == "H":
                    row, col = params.split(";")
                    self.y, self.x = int(row) - 1, int(col) - 1
                elif command == "m":
                    self.sgr = () if params in ("", "0") else (*self.sgr, params)
                else:
                    raise AssertionError(f"unexpected sequence {m.group(0)!r}")
                i = m.end()
                continue
            if c == "\n":
                self.y += 1
            else:
                wide = unicodedata.east_asian_width(c) in ("W", "F")
                self.cells[self.y][self.x] = (c, self.sgr)
                if wide:
                    self.cells[self.y][self.x + 1] = ("", self.sgr)
                self.x += 2 if wide else 1
            i += 1


def rendered(update, console: Console) -> str:
    return update.render_segments(console)


class Twin:
    """Every paint of the viewer's screen fed to one terminal, and Textual's own update for
    the same dirty regions (its compositor, its styles cache's lines) fed to another."""

    def __init__(self, monkeypatch, width: int, height: int) -> None:
        self.ours, self.ref = Terminal(width, height), Terminal(width, height)
        self.partial = 0  # partial updates compared
        self.console: Console | None = None
        real = ViewerCompositor.render_update
        twin = self

        def render_update(comp, full=False, screen_stack=None, simplify=False):
            full_update = full or comp.size.region in comp._dirty_regions
            regions = set(comp._dirty_regions)
            update = real(comp, full, screen_stack, simplify)
            if update is None:
                return None
            text = rendered(update, twin.console)
            twin.ours.feed(text)
            if full_update:
                twin.ref.feed(text)
                return update
            comp._dirty_regions.update(regions)
            with monkeypatch.context() as m:  # Textual's lines for the rows, too
                m.setattr(Rows, "render_lines", Widget.render_lines)
                reference = Compositor.render_partial_update(comp)
            twin.ref.feed(rendered(reference, twin.console))
            twin.partial += 1
            assert twin.ours.cells == twin.ref.cells, "a cell differs from Textual's paint"
            return update

        monkeypatch.setattr(ViewerCompositor, "render_update", render_update)


KEYS = ["right", "right", "minus", "plus", "shift+right", "b", "L", "I", "m", "greater_than_sign",
        "a", "o", "l", "k", "c", "tab", "minus", "right", "question_mark", "escape", "c",
        "v", "right", "v", "v", "x", "g", "v", "y", "v", "d", "v", "d", "v", "left", "v", "v"]


@pytest.mark.parametrize("size", [(160, 48), (100, 30)])
async def test_every_paint_shows_the_cells_textuals_own_paint_shows(monkeypatch, size):
    # keys through every view, compare mode (bordered pictures: Textual's own lines), the
    # help screen over the viewer and back; after each partial paint the terminal fed the
    # viewer's bytes and the one fed Textual's own update for the same regions agree
    assert textual_internals.PARTIAL_PAINT  # the Textual this runs with (8.2)
    twin = Twin(monkeypatch, *size)
    app = BrdfApp(ViewerState(sides=[Side.of("phong")]), color="truecolor")
    twin.console = app.console
    async with app.run_test(size=size) as pilot:
        await pilot.pause(0.3)
        for key in KEYS:
            await pilot.press(key)
            for _ in range(40):  # the key's frame, albedo included
                await pilot.pause(0.02)
                if app.frame is not None and app.frame.request == app.request \
                        and app.frame.complete:
                    break
        assert app.state.view == "map" and app.frames > len(KEYS) // 2
    assert twin.partial >= len(KEYS)


async def test_without_colour_every_paint_shows_textuals_cells(monkeypatch, no_color):
    # NO_COLOR: Textual's Monochrome filter applies to the rows, which then go its own way
    twin = Twin(monkeypatch, 100, 30)
    app = BrdfApp(ViewerState(sides=[Side.of("gltf")]))
    twin.console = app.console
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.pause(0.3)
        for key in ("right", "plus", "right", "c", "minus"):
            await pilot.press(key)
            await pilot.pause(0.3)
    assert twin.partial >= 5


async def test_rows_hand_over_the_lines_textuals_styles_cache_makes():
    # a picture (no padding), the status line (padding at both sides) and, in compare mode,
    # a bordered picture (Textual's own way): the same segments as the styles cache's
    app = BrdfApp(ViewerState(sides=[Side.of("phong")]), color="truecolor")
    async with app.run_test(size=(120, 36)) as pilot:
        await pilot.pause(0.3)
        await pilot.press("right")
        await pilot.pause(0.3)
        checked = []
        for compare in (False, True):
            if compare:
                await pilot.press("c")
                await pilot.pause(0.5)
            for wid in ("map-a", "incidence", "perpendicular", "status"):
                w = app.query_one(f"#{wid}")
                if not w.display:
                    continue
                width, height = w.outer_size
                for crop in (Region(0, 0, width, height), Region(3, 1, width - 5, height - 1)):
                    ours = [list(line) for line in w.render_lines(crop)]
                    w._styles_cache.clear()
                    theirs = [list(line) for line in Widget.render_lines(w, crop)]
                    assert ours == theirs, (wid, compare, crop)
                    checked.append(wid)
        assert {"map-a", "status"} <= set(checked)


def test_a_span_starts_where_it_starts_unless_inside_a_wide_character():
    # cells: a b 漢漢 字字 c d (漢 and 字 two cells each); the reference for the text is
    # Textual's own crop of the strip from the cell returned
    console = Console(color_system="truecolor", force_terminal=True)
    red, blue = Style(color="red"), Style(bgcolor="blue")
    strip = Strip([Segment("ab", red), Segment("漢字", blue), Segment("cd", None)], 8)
    for start, stop, first in [(1, 7, 1), (3, 7, 2), (2, 8, 2), (5, 8, 2), (6, 8, 6),
                               (0, 3, 0), (0, 8, 0)]:
        got_first, text = _cells(strip, start, stop, ColorSystem.TRUECOLOR)
        assert got_first == first, (start, stop)
        assert text == strip.crop(first, stop).render(console), (start, stop)
    assert "漢" in _cells(strip, 3, 5, ColorSystem.TRUECOLOR)[1]  # never split into spaces


def held_compute(monkeypatch, slow_only: bool, held=lambda theta_i: theta_i == 31.0):
    """``core_frame.compute_frame`` held by an event for the θi that ``held`` names (31°; its
    albedo part only, or the whole frame), in the frame worker (every frame goes there: none
    on the event loop)."""
    monkeypatch.setattr(frames, "INLINE_S", 0.0)
    release = threading.Event()
    real = core_frame.compute_frame

    def compute(req, **kw):
        if held(req.theta_i) and (not slow_only or kw.get("slow", True)) and \
                threading.current_thread() is not threading.main_thread():
            release.wait(10.0)
        return real(req, **kw)

    monkeypatch.setattr(core_frame, "compute_frame", compute)
    return release


async def test_a_slow_frame_lets_the_status_line_go_ahead(monkeypatch):
    # the frame of θi 31° is held: after PENDING_S the status line shows θi 31° with its
    # numbers pending ("…") while the pictures still show θi 30°; then the frame arrives
    core_frame.clear_caches()
    release = held_compute(monkeypatch, slow_only=False)
    app = BrdfApp(ViewerState(sides=[Side.of("phong")]), color="truecolor")
    async with app.run_test(size=(120, 36)) as pilot:
        await pilot.pause(0.3)
        await pilot.press("right")
        status = lambda: str(app.query_one("#status").render())  # noqa: E731
        assert await wait_for(pilot, lambda: "θi 31°" in status())
        assert "a(θi) …" in status() and app.frame.request.theta_i == 30.0
        release.set()
        assert await wait_for(pilot, lambda: app.frame.request.theta_i == 31.0
                              and app.frame.complete and "a(θi)=" in status())


async def test_the_status_line_follows_a_held_key_while_the_frames_are_slow(monkeypatch):
    # every frame but θi 30°'s is held (a user's slow kernel, an energy table of a .brdf):
    # keys 10 ms apart, closer than PENDING_S, for 200 ms; the status line shows a newer θi
    # while they come (the timer was put off by every key: θi 30° until the last)
    core_frame.clear_caches()
    release = held_compute(monkeypatch, slow_only=False, held=lambda theta_i: theta_i != 30.0)
    app = BrdfApp(ViewerState(sides=[Side.of("phong")]), color="truecolor")
    async with app.run_test(size=(120, 36)) as pilot:
        assert await wait_for(pilot, lambda: app.frame is not None and app.frame.complete)
        status = lambda: str(app.query_one("#status").render())  # noqa: E731
        seen = []
        for _ in range(20):  # (pilot.press waits for the screen: a held key does not)
            app.simulate_key("right")
            await asyncio.sleep(0.01)
            seen.append(status())
        release.set()
        assert any("θi 30°" not in s for s in seen[:-1]), seen[-3:]
        assert await wait_for(pilot, lambda: app.frame.request.theta_i == 50.0
                              and app.frame.complete)


async def test_a_held_frames_pictures_go_ahead_of_a_slow_albedo(monkeypatch):
    # every job holds its pictures for its slow part (HOLD_S: its kind's albedo was quick
    # lately), and θi 31°'s albedo then blocks: the pictures go ahead after HOLD_WAIT_S,
    # without waiting for it, and the whole frame follows when it comes
    core_frame.clear_caches()
    monkeypatch.setattr(frames, "HOLD_S", 1e9)
    release = held_compute(monkeypatch, slow_only=True)
    app = BrdfApp(ViewerState(sides=[Side.of("phong")]), color="truecolor")
    async with app.run_test(size=(120, 36)) as pilot:
        assert await wait_for(pilot, lambda: app.frame is not None and app.frame.complete)
        await pilot.press("right")
        assert await wait_for(pilot, lambda: app.frame.request.theta_i == 31.0)
        assert not app.frame.complete and not release.is_set()
        release.set()
        assert await wait_for(pilot, lambda: app.frame.complete
                              and app.frame.request.theta_i == 31.0)


async def test_pictures_stop_waiting_for_a_slow_albedo(monkeypatch):
    # the albedo of θi 31° is held: the pictures (maps, sections, peak) are shown without
    # it, then with it when it comes
    core_frame.clear_caches()
    release = held_compute(monkeypatch, slow_only=True)
    app = BrdfApp(ViewerState(sides=[Side.of("phong")]), color="truecolor")
    async with app.run_test(size=(120, 36)) as pilot:
        await pilot.pause(0.3)
        await pilot.press("right")
        assert await wait_for(pilot, lambda: app.frame.request.theta_i == 31.0)
        assert not app.frame.complete
        release.set()
        assert await wait_for(pilot, lambda: app.frame.complete
                              and app.frame.request.theta_i == 31.0)


def frame_done(app: BrdfApp) -> bool:
    """Whether the current request's frame is on screen, albedo included."""
    return app.frame is not None and app.frame.complete and app.frame.request == app.request


class Paints:
    """Every paint the viewer's screen writes: what the terminal then shows (a
    :class:`Terminal` fed each one), how many frames the app had drawn by then, and the cells
    a terminal fed the whole screen at that moment (Textual's full update) shows."""

    def __init__(self, monkeypatch, app: BrdfApp, width: int, height: int) -> None:
        self.shown = Terminal(width, height)
        self.made: list[tuple[int, list, list]] = []  # (frames drawn, shown cells, whole)
        real = ViewerCompositor.render_update

        def render_update(comp, full=False, screen_stack=None, simplify=False):
            update = real(comp, full, screen_stack, simplify)
            if update is not None:
                self.shown.feed(rendered(update, app.console))
                whole = Terminal(width, height)
                whole.feed(rendered(Compositor.render_full_update(comp), app.console))
                self.made.append((app.frames, [list(r) for r in self.shown.cells],
                                  whole.cells))
            return update

        monkeypatch.setattr(ViewerCompositor, "render_update", render_update)


async def test_the_first_paint_is_the_first_frame_on_the_whole_screen(monkeypatch):
    # Textual paints its layout as it starts (empty panes, three times at 160×48) and then
    # the first frame twice; the viewer's screen writes nothing before its first frame, and
    # that paint leaves the terminal showing the whole screen (what a full update shows)
    from tuibrdf.app import app as app_module

    assert textual_internals.HOLD_PAINTS  # the Textual this runs with (8.2)
    monkeypatch.setattr(app_module, "HOLD_S", 60.0)  # released by the frame alone
    app = BrdfApp(ViewerState(sides=[Side.of("phong")]), color="truecolor")
    paints = Paints(monkeypatch, app, 160, 48)
    async with app.run_test(size=(160, 48)) as pilot:
        assert await wait_for(pilot, lambda: app.frame is not None and app.frame.complete)
        await pilot.pause(0.2)
        frames_then, shown, whole = paints.made[0]
        assert frames_then >= 1
        assert shown == whole
        assert any("sr⁻¹" in "".join(c for c, _ in row) for row in shown)
        assert len(paints.made) <= 2  # (the albedo, if it came after the pictures)


async def test_a_screen_whose_frame_is_slow_is_painted_after_hold_s(monkeypatch):
    # the first frame is held (a model file's kernel that does not return): after HOLD_S the
    # screen is painted anyway, its panels and the status line's "…", then the frame
    from tuibrdf.app import app as app_module

    core_frame.clear_caches()
    monkeypatch.setattr(app_module, "HOLD_S", 0.05)
    release = held_compute(monkeypatch, slow_only=False, held=lambda theta_i: True)
    app = BrdfApp(ViewerState(sides=[Side.of("phong")]), color="truecolor")
    paints = Paints(monkeypatch, app, 120, 36)
    try:
        async with app.run_test(size=(120, 36)) as pilot:
            assert await wait_for(pilot, lambda: paints.made)
            frames_then, shown, whole = paints.made[0]
            text = "\n".join("".join(c for c, _ in row) for row in shown)
            assert frames_then == 0 and shown == whole
            assert "Modified Phong" in text and "a(θi) …" in text
            release.set()
            assert await wait_for(pilot, lambda: app.frame is not None and app.frame.complete)
    finally:
        release.set()


async def test_the_paint_after_a_release_writes_what_the_held_ones_did_not(monkeypatch):
    # while held, a parameter key changes the panel's row and the pictures; after the
    # release a θi key changes the pictures only: its paint writes the panel's row too
    app = BrdfApp(ViewerState(sides=[Side.of("phong")]), color="truecolor")
    paints = Paints(monkeypatch, app, 120, 36)
    async with app.run_test(size=(120, 36)) as pilot:
        done = partial(frame_done, app)
        assert await wait_for(pilot, done)
        screen = app.screen
        screen.held = True
        await pilot.press("minus")
        assert await wait_for(pilot, done)
        await pilot.pause(0.1)
        held = len(paints.made)
        screen.release()
        await pilot.press("right")
        assert await wait_for(pilot, lambda: done() and len(paints.made) > held)
        await pilot.pause(0.1)
        _, shown, whole = paints.made[-1]
        assert shown == whole


@pytest.mark.parametrize("case", ["too small", "loading"])
async def test_a_screen_that_says_why_there_is_no_frame_is_painted_at_once(
        monkeypatch, tmp_path, case):
    # a terminal too small for the panes, or a measured file still loading: what the screen
    # says is painted without waiting for HOLD_S (made here longer than the test)
    from tests.merl_writer import write_merl
    from tuibrdf.app import app as app_module
    from tuibrdf.core.formats import merl

    monkeypatch.setattr(app_module, "HOLD_S", 60.0)
    size = (30, 8) if case == "too small" else (100, 30)
    side = Side.of("phong")
    if case == "loading":
        merl.clear_cache()
        import numpy as np

        path = str(write_merl(tmp_path / "grey.binary", np.full((3, 90, 90, 180), 0.1)))
        side = Side.of("merl", {"file": path})
        gate = threading.Event()
        real = merl.load_cached

        def slow_load(*a, **kw):  # the file is read only once the test has looked
            gate.wait(10.0)
            return real(*a, **kw)

        monkeypatch.setattr(merl, "load_cached", slow_load)
    app = BrdfApp(ViewerState(sides=[side]), color="truecolor")
    paints = Paints(monkeypatch, app, *size)
    try:
        async with app.run_test(size=size) as pilot:
            assert await wait_for(pilot, lambda: paints.made, seconds=5.0)
            frames_then, shown, whole = paints.made[0]
            text = "\n".join("".join(c for c, _ in row) for row in shown)
            assert frames_then == 0 and shown == whole
            assert ("needs at least" if case == "too small" else "loading measured data") \
                in text, text
            if case == "loading":
                gate.set()
                assert await wait_for(pilot, lambda: app.frames > 0)
    finally:
        if case == "loading":
            gate.set()


@pytest.mark.parametrize("key", ["v", "c", "m"])
async def test_a_new_layout_is_painted_with_its_frame_not_empty(monkeypatch, key):
    # another view, compare mode, another model: Textual paints a layout when it is made,
    # the new panes empty, then filled; the viewer's screen writes nothing until the new
    # layout's frame is drawn, and that paint leaves the whole screen right
    from tuibrdf.app import app as app_module

    monkeypatch.setattr(app_module, "HOLD_S", 60.0)  # released by the frame alone
    app = BrdfApp(ViewerState(sides=[Side.of("phong")]), color="truecolor")
    paints = Paints(monkeypatch, app, 120, 36)
    async with app.run_test(size=(120, 36)) as pilot:
        done = partial(frame_done, app)
        assert await wait_for(pilot, done)
        await pilot.pause(0.2)
        before, made = app.frames, len(paints.made)
        await pilot.press(key)  # (v: map → solid; c: map A, B and A − B; m: blinn-phong)
        assert await wait_for(pilot, lambda: done() and app.frames > before
                              and len(paints.made) > made)
        await pilot.pause(0.2)
        after = paints.made[made:]
        # every paint shows the main pane drawn: its title row is not blank
        assert all("".join(c for c, _ in shown[0][:60]).strip() for _, shown, _ in after)
        assert after[-1][1] == after[-1][2]
