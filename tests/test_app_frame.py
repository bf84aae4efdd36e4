"""The viewer's data flow and robustness (issue 11, issue 17 item 1), driven with Pilot.

Expected numbers come from the core quadrature called here (independent of the app's
workers), the key table's declarations, and Textual's documented return code (1 after an
unhandled exception).
"""

from __future__ import annotations

import dataclasses
import random
import re
from functools import partial

import numpy as np
import pytest
from rich.console import Console
from textual import events

from tests.pilot import wait_for as pilot_wait_for
from tuibrdf.app import keys
from tuibrdf.app.app import BrdfApp
from tuibrdf.app.state import MAIN_VIEWS, Side, ViewerState
from tuibrdf.core import scene
from tuibrdf.core.conventions import fmt_value
from tuibrdf.core.models import MODELS
from tuibrdf.core.quadrature import albedo

#: drives the Textual viewer: not in CI's numeric leg (pyproject.toml's markers, .ci/run)
pytestmark = pytest.mark.app


@pytest.fixture(autouse=True)
def config_home(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path))
    return tmp_path


def status(app) -> str:
    return str(app.query_one("#status").render())


def burst(app, *names: str) -> None:
    """Key events posted all at once, as a terminal delivers keys typed faster than the app
    (Pilot's ``press`` waits between keys)."""
    for name in names:
        char = {"enter": "\r", "tab": "\t", "space": " "}.get(name)
        if char is None and len(name) == 1:
            char = name
        app.post_message(events.Key(name, char))


wait_for = partial(pilot_wait_for, seconds=20.0, step=0.05)


# ------------------------------------------------------------------------- the key table
def test_bindings_footer_help_and_palette_come_from_one_table():
    assert [b.action for b in keys.BINDINGS] == [k.action for k in keys.KEYS]
    assert [b.show for b in keys.BINDINGS] == [k.footer for k in keys.KEYS]
    con = Console(width=300, color_system=None)  # wide: no help line wraps
    with con.capture() as cap:
        con.print(keys.help_text())
    help_lines = cap.get()
    for k in keys.KEYS:
        assert f"{k.shown:<12}{k.help}" in help_lines
    listed = {k.action for k in keys.palette_keys()}
    assert listed == {k.action for k in keys.KEYS} - {"help", "quit"}
    # every state action names a real transition
    for k in keys.KEYS:
        m = re.match(r"state\('(\w+)'", k.action)
        if m:
            assert callable(getattr(ViewerState, m.group(1)))


# ---------------------------------------------------------------- latest state always wins
async def test_held_key_ends_on_the_final_states_albedo():
    # many → presses posted faster than the worker computes a frame (ggx at grazing angles
    # takes tens of ms): the status line must end on θi = 15° and its albedo, computed here
    # by the core quadrature
    scene.clear_caches()
    app = BrdfApp(ViewerState(sides=[Side.of("ggx", {"alpha": 0.1})], theta_i=0.0))
    expected = fmt_value(albedo("ggx", {"alpha": 0.1}, 15.0))
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.pause()
        for _ in range(5):
            burst(app, "right", "right", "right")
            await pilot.pause(0.01)
        assert await wait_for(pilot, lambda: f"a(θi)={expected} " in status(app))
        assert "θi 15°" in status(app) and app.state.theta_i == 15.0
        assert app.frame.request.theta_i == 15.0


async def test_status_follows_parameter_keys_and_compare_mode():
    app = BrdfApp(ViewerState(sides=[Side.of("phong", {"kd": 0.2, "ks": 0.3})]))
    async with app.run_test(size=(120, 36)) as pilot:
        burst(app, *["plus"] * 8)  # kd 0.2 → 0.28
        assert await wait_for(pilot, lambda: app.state.side.values["kd"] == pytest.approx(0.28))
        want = fmt_value(albedo("phong", {"kd": 0.28, "ks": 0.3}, 30.0))
        assert await wait_for(pilot, lambda: f"a(θi)={want} " in status(app))
        burst(app, "c", "minus", "minus")  # compare (keys act on B); B's kd 0.28 → 0.26
        want_b = fmt_value(albedo("phong", {"kd": 0.26, "ks": 0.3}, 30.0))
        assert await wait_for(pilot, lambda: f"A: a={want}" in status(app)
                              and f"B: a={want_b}" in status(app))


async def test_keys_typed_together_act_in_the_order_typed():
    # c turns compare mode on with the keys acting on B (ViewerState.toggle_compare), tab
    # then switches them to A, so both minus keys lower A's kd; a key handled out of order
    # (tab before c: "press c" and nothing switched) would lower B's instead
    app = BrdfApp(ViewerState(sides=[Side.of("phong", {"kd": 0.2, "ks": 0.3})]))
    async with app.run_test(size=(120, 36)) as pilot:
        await pilot.pause()
        burst(app, "c", "tab", "minus", "minus", "greater_than_sign", "left")
        assert await wait_for(pilot, lambda: app.state.theta_i == 29.0)
        a, b = (side.values["kd"] for side in app.state.sides)
        assert (a, b) == (pytest.approx(0.18), pytest.approx(0.2))
        assert app.state.active == 0 and app.state.phi_i == 195.0


async def test_each_visible_pane_is_evaluated_once_per_frame(monkeypatch):
    # wrap both kernels; one θi step must evaluate each side's map and sections once
    scene.clear_caches()
    calls = {}
    for name in ("phong", "cook-torrance"):
        m = MODELS[name]
        calls[name] = []

        def kernel(wi, wo, _m=m, _c=calls[name], **kw):
            _c.append(int(np.prod(np.shape(wo)[:-1])))
            return _m.kernel(wi, wo, **kw)

        monkeypatch.setitem(MODELS, name, dataclasses.replace(m, kernel=kernel))
    n_sections = 3 * len(scene.SECTION_THETAS)  # both planes + the section through the peak
    app = BrdfApp(ViewerState(sides=[Side.of("phong")]), sync=True)
    async with app.run_test(size=(120, 36)) as pilot:
        for mode in ("single", "compare"):
            if mode == "compare":
                await pilot.press("p", "p")  # phong vs cook-torrance
                await pilot.pause()
            for c in calls.values():
                c.clear()
            await pilot.press("right")
            await pilot.pause()
            n_map = int(np.count_nonzero(
                __import__("tuibrdf.core.hemimap", fromlist=["g"]).geometry(
                    *app.frame.request.map_px).inside))
            sides = ["phong"] if mode == "single" else ["phong", "cook-torrance"]
            for name in sides:
                assert calls[name].count(n_map) == 1, (mode, name, calls[name])
                assert calls[name].count(n_sections) == 1, (mode, name)
            # drawing again (a redraw, or a pane resized back) evaluates nothing
            for c in calls.values():
                c.clear()
            app.refresh_frame()
            await pilot.pause()
            assert all(c == [] for c in calls.values())


# ---------------------------------------------------------- hostile key bursts (issue 17)
async def test_save_dialog_survives_enter_enter_in_one_burst():
    app = BrdfApp(ViewerState(sides=[Side.of("phong")]), sync=True)
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.pause()
        burst(app, "s", "enter", "enter")
        await pilot.pause(0.3)
        burst(app, "s", "a", "enter", "enter")
        await pilot.pause(0.3)
        assert app.return_code is None and app._exception is None
        # where each Enter lands depends on when the dialog gets the focus (as in a terminal):
        # it answers the dialog, or reaches the viewer, which ignores it; never a crash
        if len(app.screen_stack) > 1:
            await pilot.press("escape")
        assert app.screen is app.screen_stack[0]
        await pilot.press("right")
        assert app.state.theta_i == 31.0


async def test_palette_survives_pageup_before_its_list_is_laid_out():
    app = BrdfApp(ViewerState(sides=[Side.of("phong")]), sync=True)
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.pause()
        burst(app, "ctrl+p", "pageup", "pagedown", "home", "end")
        await pilot.pause(0.3)
        assert app.return_code is None and app._exception is None
        await pilot.press("escape")
        await pilot.press("right")
        assert app.state.theta_i == 31.0


class Crashing(BrdfApp):
    def action_state(self, method, args=()):
        if method == "toggle_log":
            raise RuntimeError("boom from a test")
        super().action_state(method, args)


async def test_a_crash_sets_a_nonzero_return_code():
    app = Crashing(ViewerState(), sync=True)
    with pytest.raises(RuntimeError, match="boom"):  # run_test re-raises it on exit
        async with app.run_test(size=(100, 30)) as pilot:
            await pilot.press("l")
            await pilot.pause()
    assert app.return_code == 1 and "boom from a test" in str(app._exception)


@pytest.mark.parametrize("inline_s", [0.0, 10.0], ids=["worker", "event-loop"])
async def test_a_crash_in_the_frame_worker_stops_the_app(monkeypatch, inline_s):
    # a bug in the core while a frame is computed (not bad data: a RuntimeError) ends the app
    # with exit status 1 and its message, in the frame worker as on the event loop (a fast
    # frame is computed there: frames.INLINE_S); bad data (ValueError) is a message in the
    # panes instead
    from tuibrdf.app import frames
    from tuibrdf.core import scene

    monkeypatch.setattr(frames, "INLINE_S", inline_s)
    real = scene.compute_frame

    def compute(req, **kw):
        if req.theta_i == 31.0:
            raise RuntimeError("boom in the frame worker")
        if req.theta_i == 32.0:
            raise ValueError("bad data from a test")
        return real(req, **kw)

    monkeypatch.setattr(scene, "compute_frame", compute)
    app = BrdfApp(ViewerState(theta_i=33.0))
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.pause(0.3)
        await pilot.press("left")  # θi 32: bad data
        for _ in range(40):
            await pilot.pause(0.05)
            if "bad data from a test" in status(app):
                break
        assert "bad data from a test" in status(app)
        assert app.is_running
    app = BrdfApp(ViewerState(theta_i=32.0))
    with pytest.raises(Exception, match="boom in the frame worker"):  # Textual's WorkerFailed
        async with app.run_test(size=(100, 30)) as pilot:
            await pilot.pause(0.3)
            await pilot.press("left")  # θi 31: a bug
            for _ in range(40):
                await pilot.pause(0.05)
    assert app.return_code == 1


async def test_a_fast_frame_is_computed_on_the_event_loop_a_slow_one_in_the_worker(
        monkeypatch):
    # a frame whose kind took less than INLINE_S lately is computed where the key is handled
    # (no thread to start and wait for); the first of a kind, a slow kind and a new albedo
    # curve go to the worker.  The times the viewer notes are a clock of the test's: real
    # time (every frame far below the INLINE_S set here, however busy the machine) plus
    # twice INLINE_S for each frame the test makes slow
    import threading
    import time
    import types

    from tuibrdf.app import frames
    from tuibrdf.core import scene

    monkeypatch.setattr(frames, "INLINE_S", 5.0)
    monkeypatch.setattr(frames, "PREDICTED", frozenset())  # no frame computed ahead of a key
    extra = [0.0]
    monkeypatch.setattr(frames, "time", types.SimpleNamespace(
        perf_counter=lambda: time.perf_counter() + extra[0], monotonic=time.monotonic))
    scene.clear_caches()
    where: list[tuple[float, bool, bool]] = []  # (θi, curve, on the event loop)
    real = scene.compute_frame
    slow_from = [90.0]

    def compute(req, **kw):
        where.append((req.theta_i, req.curve, threading.current_thread() is
                      threading.main_thread()))
        if req.theta_i >= slow_from[0]:
            extra[0] += 2 * frames.INLINE_S
        return real(req, **kw)

    monkeypatch.setattr(scene, "compute_frame", compute)
    app = BrdfApp(ViewerState(sides=[Side.of("phong")], theta_i=30.0))
    async with app.run_test(size=(120, 36)) as pilot:
        async def frame_of(theta):
            assert await wait_for(pilot, lambda: app.frame is not None
                                  and app.frame.request.theta_i == theta
                                  and app.frame.complete)

        await frame_of(30.0)
        assert where and not any(loop for _, _, loop in where)  # the first: the worker
        theta = 30.0
        for _ in range(frames.INLINE_KEEP + 1):  # the first of a kind is the slowest (cold)
            theta += 1.0
            await pilot.press("right")
            await frame_of(theta)
        assert [loop for t, _, loop in where if t == theta] == [True]
        slow_from[0] = theta + 1.0  # from here: twice INLINE_S
        await pilot.press("right")  # known fast: on the loop, and now known slow
        await frame_of(theta + 1.0)
        assert [loop for t, _, loop in where if t == theta + 1.0] == [True]
        await pilot.press("right")
        await frame_of(theta + 2.0)
        assert not any(loop for t, _, loop in where if t == theta + 2.0)
        app.state.view = "albedo"  # the albedo curve, never computed: the worker
        app._changed("", relayout=True)
        assert await wait_for(pilot, lambda: app.frame.request.curve and app.frame.complete)
        assert not any(loop for _, curve, loop in where if curve)


def test_view_command_exits_nonzero_and_prints_the_error(monkeypatch, capsys):
    # the real `tuibrdf view` path, headless: the crash ends the app, the message is printed
    # and the exit status is not 0
    import tuibrdf.app.app as app_module
    from tuibrdf.cli import main

    class Headless(Crashing):
        def run(self, **kw):
            async def crash(pilot):
                await pilot.press("l")

            return super().run(headless=True, auto_pilot=crash)

    import tuibrdf.cli.view as view_module

    monkeypatch.setattr(app_module, "BrdfApp", Headless)
    monkeypatch.setattr(view_module, "check_terminal", lambda: None)  # pytest has no terminal
    rc = main(["view", "phong"])
    captured = capsys.readouterr()
    assert rc == 1
    assert "boom from a test" in captured.out + captured.err


# ------------------------------------------------------------------------------ key mash
async def test_key_mash_leaves_a_live_app_and_a_valid_state():
    # a seeded storm of table keys and printable characters (into the save dialog too);
    # quit keys left out, since quitting is what they do
    rng = random.Random(11)
    table = [name for k in keys.KEYS if k.action != "quit" for name in k.keys.split(",")]
    printable = list("abcxyz0123._-") + ["enter", "escape", "backspace"]
    pool = table + printable
    app = BrdfApp(ViewerState(sides=[Side.of("phong")]))
    async with app.run_test(size=(80, 24)) as pilot:
        for _ in range(10):  # 2000 keys
            burst(app, *(rng.choice(pool) for _ in range(200)))
            await pilot.pause(0.01)
        for _ in range(5):  # close whatever dialog is open
            burst(app, "escape")
            await pilot.pause(0.05)
        assert app.return_code is None and app._exception is None
        s = app.state
        assert 0.0 <= s.theta_i <= 90.0 and s.view in MAIN_VIEWS and 1 <= len(s.sides) <= 2
        for side in s.sides:
            side.spec.resolve(side.values)  # still valid
        # and it still answers: the final state's frame arrives
        await pilot.press("right" if s.theta_i < 90 else "left")
        want = app.frame_request()
        assert await wait_for(pilot, lambda: app.frame is not None and
                              app.frame.request == want, seconds=30)


async def test_the_lit_plane_is_evaluated_once_per_frame_and_exposure_evaluates_nothing(
        monkeypatch):
    # the new views draw from the frame too: one θi step on the lit plane in compare mode
    # evaluates each side's plane image once (its pixel count) and the sections once; the
    # exposure and gamma keys change only the drawing (no kernel call)
    scene.clear_caches()
    calls = {}
    for name in ("phong", "cook-torrance"):
        m = MODELS[name]
        calls[name] = []

        def kernel(wi, wo, _m=m, _c=calls[name], **kw):
            _c.append(tuple(np.shape(wo)[:-1]))  # the plane's call: an (H, W) image
            return _m.kernel(wi, wo, **kw)

        monkeypatch.setitem(MODELS, name, dataclasses.replace(m, kernel=kernel))
    n_sections = (3 * len(scene.SECTION_THETAS),)
    app = BrdfApp(ViewerState(sides=[Side.of("phong")]), sync=True)
    async with app.run_test(size=(120, 36)) as pilot:
        await pilot.press("p", "p", "v", "v", "v", "v")  # the lit plane, side by side
        await pilot.pause()
        assert app.frame.request.extra == "plane"
        for c in calls.values():
            c.clear()
        await pilot.press("right")
        await pilot.pause()
        px_w, px_h = app.frame.request.extra_px
        for name in ("phong", "cook-torrance"):
            assert calls[name].count((px_h, px_w)) == 1, (name, calls[name])
            assert calls[name].count(n_sections) == 1, name
        for c in calls.values():
            c.clear()
        await pilot.press("x", "g", "X")
        await pilot.pause()
        assert app.state.exposure == 1.0 and app.state.gamma == pytest.approx(2.4)
        assert all(c == [] for c in calls.values())


def test_changed_span_is_what_differs_between_two_rows():
    # by hand: "ab|cd|ef" against "ab|XY|ef" (| = segment boundaries) differ in cells 2–3
    # only; equal rows differ nowhere; "aB" differs in cell 1 only; one segment "abcdef"
    # against "abcdeF" in cell 5 only; a style change counts as a change of every cell it
    # covers ("cd" bold)
    from rich.segment import Segment
    from rich.style import Style

    from tuibrdf.app.widgets import changed_span

    def row(*texts, bold=()):
        return [Segment(t, Style(bold=t in bold)) for t in texts]

    assert changed_span(row("ab", "cd", "ef"), row("ab", "XY", "ef"), 6) == (2, 4)
    x0, x1 = changed_span(row("ab", "cd", "ef"), row("ab", "cd", "ef"), 6)
    assert x1 <= x0
    assert changed_span(row("ab", "cd", "ef"), row("aB", "cd", "ef"), 6) == (1, 2)
    assert changed_span(row("abcdef"), row("abcdeF"), 6) == (5, 6)
    assert changed_span(row("ab", "cd", "ef"), row("ab", "cd", "ef", bold=("cd",)), 6) == (2, 4)
    # segments cut differently: "abc|def" against "ab|cdXf": only cell 4 differs; the span
    # starts after the common start "ab" of the first segments and ends before the common
    # end "f" of the last ones (cell 2 is equal too, but not seen as such: conservative)
    assert changed_span(row("abc", "def"), row("ab", "cdXf"), 6) == (2, 5)


def test_changed_span_covers_every_changed_cell():
    # property: every cell outside [x0, x1) is the same in both rows (random rows of random
    # segments, styles from a small set, texts from a small alphabet)
    import random

    from rich.segment import Segment
    from rich.style import Style

    from tuibrdf.app.widgets import changed_span

    rng = random.Random(5)
    styles = [Style(), Style(bold=True), Style(color="red")]

    for _ in range(2000):
        w = rng.randint(1, 12)
        a = [(rng.choice("ab "), rng.choice(styles)) for _ in range(w)]
        b = [c if rng.random() < 0.7 else (rng.choice("ab "), rng.choice(styles)) for c in a]
        ra = [Segment(c, s) for c, s in a]  # one segment per cell, then merged at random
        rb = [Segment(c, s) for c, s in b]
        ra = merge_random(ra, rng)
        rb = merge_random(rb, rng)
        x0, x1 = changed_span(ra, rb, w)
        for x in range(w):
            if not x0 <= x < x1:
                assert a[x] == b[x], (a, b, x0, x1)


def merge_random(row, rng):
    """Join neighbouring one-cell segments of the same style at random."""
    out = [row[0]]
    for seg in row[1:]:
        if seg.style == out[-1].style and rng.random() < 0.6:
            out[-1] = type(seg)(out[-1].text + seg.text, seg.style)
        else:
            out.append(seg)
    return out


async def test_status_line_grows_and_shrinks_with_its_text():
    # the status line re-lays out the screen only when its height may change; numbers that
    # wrap (two RGB sides) must still get their lines (2 lines normally, 3 at most: its CSS
    # max-height) and the line count must come back when they go.  A long message does not
    # wrap: it is cut with "…" (issue 12 item 10)
    from tuibrdf.app.state import Side, ViewerState

    app = BrdfApp(ViewerState(sides=[Side.of("gltf")]), sync=True)
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.pause()
        st = app.query_one("#status")
        assert st.size.height == 2
        app._changed("long " * 60)
        await pilot.pause()
        await pilot.pause()
        assert st.size.height == 2 and "long long" in status(app) and "…" in status(app)
        app.state.toggle_compare()
        app._changed("", relayout=True)
        await pilot.pause()
        await pilot.pause()
        assert st.size.height == 3, status(app)
        app.state.toggle_compare()
        app._changed("short", relayout=True)
        await pilot.pause()
        await pilot.pause()
        assert st.size.height == 2


async def test_a_parameter_key_repaints_one_row_of_the_panel(monkeypatch):
    # the parameter panel draws rows: a new value repaints the cells of its own row (the
    # selected one, Kd: the panel's first), a new model of as many rows or fewer keeps the
    # panel's height where it is steady (tall terminals, layout.STEADY_PANEL_H) and lays the
    # screen out again only where its rows set its height
    from tuibrdf.app.layout import STEADY_PANEL_H
    from tuibrdf.app.widgets import ParamPanel

    calls: list[tuple] = []
    refresh = ParamPanel.refresh

    def spy(self, *regions, **kw):
        calls.append((regions, kw.get("layout", False)))
        return refresh(self, *regions, **kw)

    monkeypatch.setattr(ParamPanel, "refresh", spy)
    app = BrdfApp(ViewerState(sides=[Side.of("phong")]), sync=True)
    async with app.run_test(size=(160, 48)) as pilot:
        await pilot.pause()
        panel = app.query_one("#panel-a")
        assert panel.outer_size.height == STEADY_PANEL_H
        calls.clear()
        await pilot.press("minus")
        await pilot.pause()
        assert app.state.side.material.values["kd"] == pytest.approx(0.19)
        assert calls and all(not layout for _, layout in calls)
        rows = {r.y for regions, _ in calls for r in regions}
        assert rows == {0}, calls  # Kd's row only, never the whole panel (no region)
        assert all(regions for regions, _ in calls)
        line = str(panel.render()).splitlines()[0]
        assert "0.19" in line and line.startswith("▶")
        calls.clear()
        await pilot.press("m")
        await pilot.pause()
        assert not any(layout for _, layout in calls)
        assert panel.outer_size.height == STEADY_PANEL_H
    app = BrdfApp(ViewerState(sides=[Side.of("lambert")]), sync=True)
    async with app.run_test(size=(100, 30)) as pilot:  # below BOTH_PANELS_H: rows set it
        await pilot.pause()
        panel = app.query_one("#panel-a")
        assert panel.outer_size.height == 1 + 2  # Kd and the border
        await pilot.press("m")
        await pilot.pause()
        await pilot.pause()
        assert app.state.side.model == "phong"
        assert panel.outer_size.height == 3 + 2


# ---------------------------------------------------------------- the garbage of each key
async def test_garbage_is_collected_after_each_frame_and_fully_when_idle(monkeypatch):
    # the young generations after each shown frame's paint, a full collection once frames
    # stop, and the automatic collector's young threshold raised after start-up
    import gc

    from tuibrdf.app import app as app_module
    from tuibrdf.app import frames
    calls = []
    collect = gc.collect
    monkeypatch.setattr(gc, "collect", lambda *a: (calls.append(a), collect(*a))[1])
    monkeypatch.setattr(app_module, "FREEZE_S", 0.05)
    monkeypatch.setattr(app_module, "GC_IDLE_S", 0.5)
    monkeypatch.setattr(frames, "GC_IDLE_S", 0.5)
    monkeypatch.setattr(frames, "PREDICTED", frozenset())  # (its own collection: below)
    threshold = gc.get_threshold()
    gc.set_threshold(700, *threshold[1:])  # Python's default (an earlier viewer raised it)
    try:
        app = BrdfApp(ViewerState(sides=[Side.of("phong")], theta_i=30.0))
        async with app.run_test(size=(120, 36)) as pilot:
            # start-up settled: the last request's frame shown (the layout settles in steps)
            assert await wait_for(pilot, lambda: app.frame is not None and app.frame.complete
                                  and app.frame.request == app.request
                                  and not (app._worker and app._worker.is_running))
            assert await wait_for(pilot, lambda: gc.get_threshold()[0] == frames.GC_YOUNG)
            assert frames.GC_YOUNG > 700
            await pilot.pause(0.1)  # the collections of start-up's frames
            calls.clear()
            shown = app.frames
            for theta in (31.0, 32.0, 33.0):
                await pilot.press("right")
                assert await wait_for(pilot, lambda t=theta: app.frame.request.theta_i == t
                                      and app.frame.complete)
                # its collection, GC_AFTER_S after the frame
                assert await wait_for(pilot, lambda: calls.count((1,)) == app.frames - shown)
            assert app.frames - shown >= 3
            assert () not in calls  # no full collection while frames come
            await pilot.pause(1.6)
            assert calls.count(()) == 1  # idle: one full collection, not one per interval
            # a newer frame on its way: no collection, unless the garbage has grown
            calls.clear()
            app.request = dataclasses.replace(app.request, theta_i=34.0)
            app._collect_young()
            assert calls == []
            junk = [[i] for i in range(frames.GC_YOUNG // 2 + 100)]  # tracked: gen 0 count grows
            app._collect_young()
            assert calls == [(1,)]
            del junk
    finally:
        gc.set_threshold(*threshold)


def _prefetch_log(monkeypatch):
    """compute_frame wrapped: the log of (model names, θi, on the event loop) per call."""
    import threading

    from tuibrdf.app import frames

    monkeypatch.setattr(frames, "PREFETCH_S", 0.01)
    scene.clear_caches()
    log: list[tuple[tuple[str, ...], float, bool]] = []
    real = scene.compute_frame

    def compute(req, **kw):
        log.append((tuple(m.name for m in req.materials), req.theta_i,
                    threading.current_thread() is threading.main_thread()))
        return real(req, **kw)

    monkeypatch.setattr(scene, "compute_frame", compute)
    return log


def _after_in_table(name: str, step: int) -> str:
    names = list(MODELS)  # the registered models in their order (merl: no file, skipped)
    names.remove("merl")
    return names[(names.index(name) + step) % len(names)]


@pytest.mark.parametrize("step,key", [(1, "m"), (-1, "M")])
async def test_a_model_key_prefetches_the_frame_the_same_key_shows_next(monkeypatch, step,
                                                                         key):
    # after m (M), the frame of the model after (before) it is computed in the worker while
    # the viewer is idle; the next m (M) then shows that very result, computed nowhere else
    log = _prefetch_log(monkeypatch)
    app = BrdfApp(ViewerState(sides=[Side.of("phong")], theta_i=30.0))
    first, second = _after_in_table("phong", step), _after_in_table("phong", 2 * step)
    async with app.run_test(size=(120, 36)) as pilot:
        assert await pilot_wait_for(pilot, lambda: app.frame is not None and app.frame.complete)
        await pilot.press(key)
        assert await pilot_wait_for(pilot, lambda: app.frame.complete
                                    and app.frame.request.materials[0].name == first)
        ahead = dataclasses.replace(app.request,
                                    materials=(Side.of(second).material,))
        assert await pilot_wait_for(pilot, lambda: (f := scene.cached_frame(ahead)) is not None
                                    and f.complete)
        prefetched = scene.cached_frame(ahead)
        where = [loop for names, _, loop in log if names == (second,)]
        assert where and not any(where)  # in the worker
        calls = len(log)
        await pilot.press(key)
        assert await pilot_wait_for(pilot, lambda: app.frame.request == ahead)
        assert app.frame is prefetched
        assert [names for names, _, _ in log[calls:]
                if names == (second,)] == []  # nothing computed again for it


async def test_in_compare_mode_the_prefetch_changes_only_the_active_side(monkeypatch):
    # side B active: the frame computed ahead keeps side A's material, and is the one shown
    _prefetch_log(monkeypatch)
    app = BrdfApp(ViewerState(sides=[Side.of("phong"), Side.of("ggx")], active=1,
                              theta_i=30.0))
    first, second = _after_in_table("ggx", 1), _after_in_table("ggx", 2)
    async with app.run_test(size=(160, 48)) as pilot:
        assert await pilot_wait_for(pilot, lambda: app.frame is not None and app.frame.complete)
        await pilot.press("m")
        assert await pilot_wait_for(pilot, lambda: app.frame.complete and [
            m.name for m in app.frame.request.materials] == ["phong", first])
        ahead = dataclasses.replace(app.request, materials=(
            app.request.materials[0], Side.of(second).material))
        assert await pilot_wait_for(pilot, lambda: (f := scene.cached_frame(ahead)) is not None
                                    and f.complete)
        prefetched = scene.cached_frame(ahead)
        assert await pilot_wait_for(pilot, lambda: app._drawn_ahead)  # some drawn while idle
        await pilot.press("m")
        assert await pilot_wait_for(pilot, lambda: app.frame.request == ahead)
        assert app.frame is prefetched
        from tuibrdf.app.text import visible_panes

        for pane in visible_panes(app.state):  # what was drawn ahead, and what was kept
            assert _cells(_shown_rows(app, pane)) == _cells(_fresh_rows(app, pane)), pane


def _drawn_ahead_log(monkeypatch) -> list[bool]:
    """Picture.show wrapped: per call, whether its rows came drawn ahead."""
    from tuibrdf.app import widgets

    given: list[bool] = []
    show = widgets.Picture.show

    def spy(self, renderable, key=None, lines=None):
        given.append(lines is not None)
        return show(self, renderable, key, lines)

    monkeypatch.setattr(widgets.Picture, "show", spy)
    return given


def _fresh_rows(app, pane: str) -> list[list[tuple[str, object]]]:
    """``pane``'s rows drawn from nothing from the frame on screen (the pictures' own way,
    which tests/test_render_lines.py checks against Rich)."""
    from tuibrdf.app.frames import PANES
    from tuibrdf.render import panes
    from tuibrdf.render.lines import pane_lines

    pic = app.query_one(f"#{pane}")
    got = app._pane_key(pane, app.frame)
    key, w, h = got
    view, k = PANES[pane]
    part = panes.pane(view, app.frame, k, w, h, app.look)
    rows = pane_lines(part, app.console, pic.size.width, pic.size.height)
    return [[(s.text, s.style) for s in row] for row in rows]


def _shown_rows(app, pane: str) -> list[list[tuple[str, object]]]:
    return [[(s.text, s.style) for s in strip] for strip in app.query_one(f"#{pane}")._strips]


def _cells(rows) -> list[list[tuple[str, object]]]:
    """Per row, its cells: (character, style) (segments may be cut differently)."""
    return [[(ch, style) for text, style in row for ch in text] for row in rows]


@pytest.mark.parametrize("between", [[], ["l"], ["k"]])
async def test_pictures_drawn_ahead_are_the_pictures_the_key_would_draw(monkeypatch, between):
    # after a model key, the next model's pictures are drawn while idle (frames._draw_ahead)
    # and shown by the next m: cell for cell what drawing them then gives; a look changed in
    # between (log scale, colour map) has them drawn ahead again, in that look
    from tuibrdf.app.text import visible_panes

    _prefetch_log(monkeypatch)
    given = _drawn_ahead_log(monkeypatch)
    app = BrdfApp(ViewerState(sides=[Side.of("phong")], theta_i=35.0))
    names = [_after_in_table("phong", j) for j in (1, 2, 3)]
    async with app.run_test(size=(160, 48)) as pilot:
        assert await pilot_wait_for(pilot, lambda: app.frame is not None and app.frame.complete)
        for j, name in enumerate(names):
            await pilot.press("m")
            assert await pilot_wait_for(pilot, lambda name=name: app.frame.complete and
                                        app.frame.request.materials[0].name == name)
            if j == 0:  # the first m: nothing ahead yet; then wait for the next one's
                assert await pilot_wait_for(pilot, lambda: len(app._drawn_ahead) == len(
                    visible_panes(app.state)))
                for key in between:
                    shown = app.frames
                    await pilot.press(key)  # its frame clears what was drawn ahead
                    assert await pilot_wait_for(pilot, lambda s=shown: app.frames > s and len(
                        app._drawn_ahead) == len(visible_panes(app.state)))
                given.clear()
                continue
            panes_now = visible_panes(app.state)
            for pane in panes_now:
                assert _cells(_shown_rows(app, pane)) == _cells(_fresh_rows(app, pane)), pane
            if j == 1:
                assert given and all(given)
            n = len(panes_now)
            assert await pilot_wait_for(pilot, lambda n=n: len(app._drawn_ahead) == n)
            given.clear()


async def test_other_keys_and_refused_keys_prefetch_nothing(monkeypatch):
    # keys that are not stepped again and again (log scale, colour map, the section's
    # azimuth) and a key refused at a bound (θi already 90°) compute no frame but their own
    import threading

    from tuibrdf.app import frames

    _prefetch_log(monkeypatch)
    asked: list[tuple[float, float, bool]] = []  # (θi, ψ, in the worker)
    real = scene.compute_frame

    def compute(req, **kw):
        asked.append((req.theta_i, req.section_azimuth,
                      threading.current_thread() is not threading.main_thread()))
        return real(req, **kw)

    monkeypatch.setattr(scene, "compute_frame", compute)
    app = BrdfApp(ViewerState(sides=[Side.of("phong")], theta_i=90.0))
    async with app.run_test(size=(120, 36)) as pilot:
        assert await pilot_wait_for(pilot, lambda: app.frame is not None and app.frame.complete)
        for key in ("l", "k", "a", "right"):  # (→ at 90°: refused)
            asked.clear()
            await pilot.press(key)
            assert await pilot_wait_for(pilot, lambda: app.frame.request == app.request
                                        and app.frame.complete)
            await pilot.pause(10 * frames.PREFETCH_S)
            wanted = (app.request.theta_i, app.request.section_azimuth)
            assert {(t, psi) for t, psi, _ in asked} <= {wanted}, key
            assert app._ahead is None or app._ahead.theta_i == 90.0 and (
                app._ahead.section_azimuth == app.request.section_azimuth)


@pytest.mark.parametrize("key,method,args", [("right", "step_theta", (1,)),
                                             ("left", "step_theta", (-1,)),
                                             ("greater_than_sign", "step_phi_i", (15,)),
                                             ("minus", "step_param", (-1,))])
async def test_a_theta_or_parameter_key_prefetches_the_frame_the_same_key_shows_next(
        monkeypatch, key, method, args):
    # → (←, −) again: its frame is the very result computed ahead in the worker, computed
    # nowhere else, and its pictures were drawn ahead
    log = _prefetch_log(monkeypatch)
    given = _drawn_ahead_log(monkeypatch)
    app = BrdfApp(ViewerState(sides=[Side.of("phong")], theta_i=40.0))
    async with app.run_test(size=(120, 36)) as pilot:
        assert await pilot_wait_for(pilot, lambda: app.frame is not None and app.frame.complete)
        await pilot.press(key)
        assert await pilot_wait_for(pilot, lambda: app.frame.complete
                                    and app.frame.request == app.request)
        state = app.state.fork()  # where the same key goes: the state's own transition
        assert getattr(state, method)(*args) is None
        ahead = app.frame_request(state)
        assert ahead != app.request
        assert await pilot_wait_for(pilot, lambda: (f := scene.cached_frame(ahead)) is not None
                                    and f.complete and app._drawn_ahead)
        prefetched = scene.cached_frame(ahead)
        calls, given[:] = len(log), []
        await pilot.press(key)
        assert await pilot_wait_for(pilot, lambda: app.frame.request == ahead)
        assert app.frame is prefetched
        assert all(not on_loop for _, _, on_loop in log[calls:])  # nothing on the loop
        assert given and all(given)  # every picture drawn ahead


async def test_the_key_a_prefetch_is_for_waits_for_it_rather_than_computing_again(
        monkeypatch):
    # m pressed while the worker still computes that frame: the frame comes from that one
    # computation (the worker is neither cancelled nor joined by a second)
    import threading

    log = _prefetch_log(monkeypatch)
    traced = scene.compute_frame
    started, release = threading.Event(), threading.Event()
    ahead_name = _after_in_table("blinn-phong", 1)

    def held(req, **kw):
        if req.materials[0].name == ahead_name and not release.is_set():
            started.set()
            release.wait(10.0)
        return traced(req, **kw)

    monkeypatch.setattr(scene, "compute_frame", held)
    app = BrdfApp(ViewerState(sides=[Side.of("phong")], theta_i=30.0))
    async with app.run_test(size=(120, 36)) as pilot:
        assert await pilot_wait_for(pilot, lambda: app.frame is not None and app.frame.complete)
        await pilot.press("m")  # → blinn-phong; then the prefetch of the next one starts
        assert await pilot_wait_for(pilot, started.is_set)
        ahead = dataclasses.replace(app.request, materials=(Side.of(ahead_name).material,))
        app._costs[app._kind(ahead)] = [0.0]  # a kind known fast: the loop would compute it
        await pilot.press("m")  # the very frame being computed
        await pilot.pause(0.05)
        release.set()
        assert await pilot_wait_for(pilot, lambda: app.frame.complete
                                    and app.frame.request.materials[0].name == ahead_name)
        fresh = [c for c in log if c[0] == (ahead_name,)]
        assert len(fresh) <= 2 and not any(loop for _, _, loop in fresh)  # fast part, albedo


async def test_the_garbage_of_a_frame_drawn_ahead_is_collected_once_it_is_drawn(monkeypatch):
    # the frame prepared ahead leaves its garbage (rows, segments) between two keys: it is
    # collected when its last picture is drawn, not by the automatic collector in the next key
    import gc

    from tuibrdf.app import frames

    monkeypatch.setattr(frames, "PREFETCH_S", 0.05)
    monkeypatch.setattr(frames, "GC_AFTER_S", 0.001)  # the key's own, well before
    marks: list[str] = []
    collect = gc.collect
    monkeypatch.setattr(gc, "collect", lambda *a: (marks.append(f"collect{a}"), collect(*a))[1])
    draw_ahead = frames.FrameDelivery._draw_ahead

    def spy(self, res, todo):
        marks.append(f"ahead {len(todo)}")
        return draw_ahead(self, res, todo)

    monkeypatch.setattr(frames.FrameDelivery, "_draw_ahead", spy)
    app = BrdfApp(ViewerState(sides=[Side.of("phong")], theta_i=30.0))
    async with app.run_test(size=(120, 36)) as pilot:
        assert await wait_for(pilot, lambda: app.frame is not None and app.frame.complete)
        await pilot.pause(0.2)
        marks.clear()
        await pilot.press("right")
        assert await wait_for(pilot, lambda: "ahead 1" in marks
                              and "collect(1,)" in marks[marks.index("ahead 1"):])


async def test_a_slow_kind_of_frame_is_not_prepared_ahead(monkeypatch):
    # frames of a kind that took PREFETCH_MAX_S or more lately (measured data, a slow model
    # file) are not computed ahead of a θi key: the worker would hold the next key up.  The
    # viewer's clock is the test's: real time plus twice PREFETCH_MAX_S per frame computed
    import time
    import types

    from tuibrdf.app import frames

    _prefetch_log(monkeypatch)
    extra = [0.0]
    monkeypatch.setattr(frames, "time", types.SimpleNamespace(
        perf_counter=lambda: time.perf_counter() + extra[0], monotonic=time.monotonic))
    asked: list[float] = []
    real = scene.compute_frame

    def slow(req, **kw):
        asked.append(req.theta_i)
        extra[0] += 2 * frames.PREFETCH_MAX_S
        return real(req, **kw)

    monkeypatch.setattr(scene, "compute_frame", slow)
    app = BrdfApp(ViewerState(sides=[Side.of("phong")], theta_i=40.0))
    async with app.run_test(size=(120, 36)) as pilot:
        assert await pilot_wait_for(pilot, lambda: app.frame is not None and app.frame.complete)
        for theta in (41.0, 42.0):
            await pilot.press("right")
            assert await pilot_wait_for(pilot, lambda t=theta: app.frame.complete
                                        and app.frame.request.theta_i == t)
            await pilot.pause(10 * frames.PREFETCH_S)
        assert set(asked) == {40.0, 41.0, 42.0}  # none of 43°


async def test_pictures_drawn_ahead_for_another_widget_size_are_drawn_again(monkeypatch):
    # a map's key names its pixel grid, not its widget's size: rows drawn ahead for a widget
    # of another size (resized meanwhile) are not shown, the picture is drawn afresh
    from textual.geometry import Size

    _prefetch_log(monkeypatch)
    given = _drawn_ahead_log(monkeypatch)
    app = BrdfApp(ViewerState(sides=[Side.of("phong")], theta_i=40.0))
    async with app.run_test(size=(120, 36)) as pilot:
        assert await pilot_wait_for(pilot, lambda: app.frame is not None and app.frame.complete)
        await pilot.press("right")
        assert await pilot_wait_for(pilot, lambda: app.frame.request.theta_i == 41.0
                                    and len(app._drawn_ahead) >= 3)
        for key, (part, lines, _size) in list(app._drawn_ahead.items()):
            app._drawn_ahead[key] = part, lines, Size(7, 3)  # as if drawn before a resize
        given.clear()
        await pilot.press("right")
        assert await pilot_wait_for(pilot, lambda: app.frame.request.theta_i == 42.0)
        assert given and not any(given)
        from tuibrdf.app.text import visible_panes

        for pane in visible_panes(app.state):
            assert _cells(_shown_rows(app, pane)) == _cells(_fresh_rows(app, pane)), pane


async def test_a_key_then_the_key_back_shows_the_pictures_shown_before(monkeypatch):
    # → then ←: the frame of ← is the one shown before → (the core's cache) and so are its
    # pictures (frames._draw keeps what a frame replaces): none drawn again, each cell for
    # cell what drawing it gives.  Nothing is prepared ahead here (PREFETCH_S: an hour)
    from tuibrdf.app import frames
    from tuibrdf.app.text import visible_panes

    log = _prefetch_log(monkeypatch)
    monkeypatch.setattr(frames, "PREFETCH_S", 3600.0)
    given = _drawn_ahead_log(monkeypatch)
    app = BrdfApp(ViewerState(sides=[Side.of("phong")], theta_i=40.0))
    async with app.run_test(size=(120, 36)) as pilot:
        assert await pilot_wait_for(pilot, lambda: app.frame is not None and app.frame.complete)
        await pilot.pause(0.2)  # (the layout settled)
        assert await pilot_wait_for(pilot, lambda: app.frame.request == app.request)
        first = app.frame
        await pilot.press("right")
        assert await pilot_wait_for(pilot, lambda: app.frame.complete
                                    and app.frame.request.theta_i == 41.0)
        assert not any(given)  # (nothing was drawn ahead)
        calls, given[:] = len(log), []
        await pilot.press("left")
        assert await pilot_wait_for(pilot, lambda: app.frame.request.theta_i == 40.0)
        assert app.frame.request == first.request and len(log) == calls  # (cached)
        assert len(given) == len(visible_panes(app.state)) and all(given)
        for pane in visible_panes(app.state):
            assert _cells(_shown_rows(app, pane)) == _cells(_fresh_rows(app, pane)), pane
        given.clear()  # and → again: the pictures ← replaced
        await pilot.press("right")
        assert await pilot_wait_for(pilot, lambda: app.frame.request.theta_i == 41.0)
        assert given and all(given)
        for pane in visible_panes(app.state):
            assert _cells(_shown_rows(app, pane)) == _cells(_fresh_rows(app, pane)), pane


async def test_the_two_latest_different_keys_are_both_prepared_ahead(monkeypatch):
    # θi →, then a parameter's −: the frames of − again and of → again are both computed in
    # the worker and drawn while idle; → then shows its prepared frame, drawn ahead, cell for
    # cell what drawing it gives
    from tuibrdf.app.text import visible_panes

    log = _prefetch_log(monkeypatch)
    given = _drawn_ahead_log(monkeypatch)
    app = BrdfApp(ViewerState(sides=[Side.of("phong")], theta_i=40.0))
    async with app.run_test(size=(120, 36)) as pilot:
        assert await pilot_wait_for(pilot, lambda: app.frame is not None and app.frame.complete)
        for key in ("right", "minus"):
            await pilot.press(key)
            assert await pilot_wait_for(pilot, lambda: app.frame.complete
                                        and app.frame.request == app.request)
        wanted = []
        for method, args in (("step_param", (-1,)), ("step_theta", (1,))):
            state = app.state.fork()
            assert getattr(state, method)(*args) is None
            wanted.append(app.frame_request(state))
        assert len(set(wanted)) == 2 and app.request not in wanted
        n = len(visible_panes(app.state))
        assert await pilot_wait_for(pilot, lambda: all(
            (f := scene.cached_frame(r)) is not None and f.complete for r in wanted)
            and app._ahead == wanted[1] and len(app._drawn_ahead) >= n + 1)
        prefetched = scene.cached_frame(wanted[1])
        assert not any(on_loop for names, theta, on_loop in log if theta == 42.0)
        calls, given[:] = len(log), []
        await pilot.press("right")
        assert await pilot_wait_for(pilot, lambda: app.frame.request == wanted[1])
        assert app.frame is prefetched and all(not loop for _, _, loop in log[calls:])
        assert given and all(given)
        for pane in visible_panes(app.state):
            assert _cells(_shown_rows(app, pane)) == _cells(_fresh_rows(app, pane)), pane


async def test_a_worker_whose_frame_is_complete_is_not_computing():
    # a thread worker reads as running a moment after it handed over its last result; the
    # prefetch of the next transition does not wait for it (frames._computing): a worker is
    # computing only while its request's complete frame is not in the cache
    import types

    app = BrdfApp(ViewerState(sides=[Side.of("phong")], theta_i=40.0))
    async with app.run_test(size=(120, 36)) as pilot:
        assert await pilot_wait_for(pilot, lambda: app.frame is not None and app.frame.complete)
        done = app.frame.request
        assert scene.cached_frame(done).complete
        app._worker = types.SimpleNamespace(is_running=True)
        app._worker_for = done
        assert not app._computing()
        app._worker_for = dataclasses.replace(done, theta_i=12.5)  # not computed
        assert app._computing()
        app._worker = types.SimpleNamespace(is_running=False)
        assert not app._computing()
        app._worker = None


async def test_a_key_pressed_again_has_only_its_own_frame_prepared(monkeypatch):
    # →, then m twice: the user steps through the models, and only the next model's frame
    # is prepared ahead, not → again's (after → then m alone, both are: the test above)
    from tuibrdf.app.text import visible_panes

    log = _prefetch_log(monkeypatch)
    app = BrdfApp(ViewerState(sides=[Side.of("phong")], theta_i=40.0))
    async with app.run_test(size=(120, 36)) as pilot:
        assert await pilot_wait_for(pilot, lambda: app.frame is not None and app.frame.complete)
        for key in ("right", "m", "m"):
            await pilot.press(key)
            assert await pilot_wait_for(pilot, lambda: app.frame.complete
                                        and app.frame.request == app.request)
        model = app.request.materials[0].name
        ahead = dataclasses.replace(app.request, materials=(
            Side.of(_after_in_table(model, 1)).material,))
        n = len(visible_panes(app.state))
        assert await pilot_wait_for(pilot, lambda: (f := scene.cached_frame(ahead)) is not None
                                    and f.complete and len(app._drawn_ahead) >= n)
        await pilot.pause(0.3)
        assert not [c for c in log if c[:2] == ((model,), 41.0 + 1)]  # → again: not prepared
        assert [c for c in log if c[:2] == ((_after_in_table(model, 1),), 41.0)]


@pytest.mark.parametrize("seed", [3, 8])
async def test_after_any_keys_every_picture_is_what_drawing_it_gives(monkeypatch, seed):
    # a seeded walk over the keys the viewer prepares ahead, their opposites and keys that
    # change the look, the panes or the side, with pauses of random length (the frames ahead
    # caught at every stage: computing, half drawn, done): once each key's frame is complete,
    # every visible picture is cell for cell what drawing it from that frame gives, whether
    # it was drawn ahead, kept from the frame before or drawn at the key
    from tuibrdf.app.text import visible_panes

    _prefetch_log(monkeypatch)
    rng = random.Random(seed)
    pool = ["right", "left", "right", "left", "plus", "minus", "plus", "minus", "m", "M",
            "greater_than_sign", "less_than_sign", "l", "k", "a", "up", "down", "c", "tab",
            "o", "b"]
    app = BrdfApp(ViewerState(sides=[Side.of("phong")], theta_i=40.0))
    async with app.run_test(size=(120, 36)) as pilot:
        assert await pilot_wait_for(pilot, lambda: app.frame is not None and app.frame.complete)
        for step in range(30):
            key = rng.choice(pool)
            await pilot.press(key)
            assert await wait_for(pilot, lambda: app.frame is not None and app.frame.complete
                                  and app.frame.request == app.request
                                  and app.frame_request() == app.request), (step, key)
            for pane in visible_panes(app.state):
                if app._pane_key(pane, app.frame) is not None:
                    assert _cells(_shown_rows(app, pane)) == _cells(
                        _fresh_rows(app, pane)), (step, key, pane)
            await pilot.pause(rng.choice([0.0, 0.005, 0.02, 0.05, 0.1]))
