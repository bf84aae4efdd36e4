"""The viewer's data flow and robustness (issue 11, issue 17 item 1), driven with Pilot.

Expected numbers come from the core quadrature called here (independent of the app's
workers), the key table's declarations, and Textual's documented return code (1 after an
unhandled exception).
"""

from __future__ import annotations

import ast
import dataclasses
import random
import re
from functools import partial

import numpy as np
import pytest
from rich.console import Console
from textual import events

from tests import DATA_DIR
from tests.pilot import wait_for as pilot_wait_for
from tuibrdf.app import keys
from tuibrdf.app.app import BrdfApp
from tuibrdf.core.conventions import fmt_value
from tuibrdf.core.registry import MODELS
from tuibrdf.core.sphere.albedo import albedo
from tuibrdf.core.views import frame as core_frame
from tuibrdf.state.viewer import MAIN_VIEWS, Side, ViewerState


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
    assert listed == {k.action for k in keys.KEYS} - {"help", "quit", "interrupt"}
    # every state action names a real transition
    for k in keys.KEYS:
        m = re.match(r"state\('(\w+)'", k.action)
        if m:
            assert callable(getattr(ViewerState, m.group(1)))



@pytest.mark.parametrize("view", ["sphere", "plane", "slice", "theta-h", "theta-d", "map"])
def test_the_status_line_names_the_keys_of_each_view_setting(view):
    """The status line's second line shows a view's settings (``exp 1``) and ends with the
    keys that change them (``x/X exp``): every key named there, pressed, changes the setting
    it names, or refuses with a reason at a limit (the key table's actions, run on the
    state); and every setting shown is named with its keys."""
    from tuibrdf.app.text import settings_keys, settings_text, view_settings

    def shown(state):  # setting name → the text the status line shows for it
        text = settings_text(state)
        out = {name: value for value, name, _ in view_settings(state) if value}
        assert all(f" · {value}" in text for value in out.values())
        return out

    by_shown = {k.shown: k for k in keys.KEYS}
    s = ViewerState(sides=[Side.of("phong")])
    s.view = view
    hints = re.findall(r"((?:\S+/\S+ |h )+)(\S+)", settings_keys(s).plain)
    assert {name for _, name in hints} == set(shown(s)), (settings_keys(s).plain, shown(s))
    for named, name in hints:
        for key in re.split(r"[ /]", named.strip()):
            t = ViewerState(sides=[Side.of("phong")])
            t.view = view
            method, args = re.fullmatch(r"state\('(\w+)', (.*)\)", by_shown[key].action).groups()
            refused = getattr(t, method)(*ast.literal_eval(args))
            assert shown(t)[name] != shown(s)[name] or refused, (view, key, name)


# ---------------------------------------------------------------- latest state always wins
async def test_held_key_ends_on_the_final_states_albedo():
    # many → presses posted faster than the worker computes a frame (ggx at grazing angles
    # takes tens of ms): the status line must end on θi = 15° and its albedo, computed here
    # by the core quadrature
    core_frame.clear_caches()
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
    core_frame.clear_caches()
    calls = {}
    for name in ("phong", "cook-torrance"):
        m = MODELS[name]
        calls[name] = []

        def kernel(wi, wo, _m=m, _c=calls[name], **kw):
            _c.append(int(np.prod(np.shape(wo)[:-1])))
            return _m.kernel(wi, wo, **kw)

        monkeypatch.setitem(MODELS, name, dataclasses.replace(m, kernel=kernel))
    n_sections = 3 * len(core_frame.SECTION_THETAS)  # both planes + the section through the peak
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
                __import__("tuibrdf.core.views.hemimap", fromlist=["g"]).geometry(
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


async def test_an_error_in_an_action_is_a_message_and_the_viewer_goes_on():
    app = Crashing(ViewerState(), sync=True)
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.press("l")
        await pilot.pause()
        assert "boom from a test" in status(app)
        await pilot.press("right")
        assert app.state.theta_i == 31.0
    assert app.return_code in (0, None) and app._exception is None


class CrashingAtStart(BrdfApp):
    def compose(self):
        raise RuntimeError("boom from a test")
        yield


@pytest.mark.parametrize("inline_s", [0.0, 10.0], ids=["worker", "event-loop"])
async def test_an_error_computing_a_frame_is_a_message_and_the_viewer_goes_on(monkeypatch,
                                                                             inline_s):
    # a bug in the core while a frame is computed (a RuntimeError) or bad data (ValueError):
    # a message on the status line, in the frame's thread as on the event loop (a fast frame
    # is computed there: frames.INLINE_S); the viewer goes on (issue 31)
    from tuibrdf.app import frames
    from tuibrdf.core.views import frame as core_frame

    monkeypatch.setattr(frames, "INLINE_S", inline_s)
    real = core_frame.compute_frame

    def compute(req, **kw):
        if req.theta_i == 31.0:
            raise RuntimeError("boom in the frame worker")
        if req.theta_i == 32.0:
            raise ValueError("bad data from a test")
        return real(req, **kw)

    monkeypatch.setattr(core_frame, "compute_frame", compute)
    core_frame.clear_caches()
    app = BrdfApp(ViewerState(theta_i=33.0))
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.pause(0.3)
        for key, text in (("left", "bad data from a test"),
                          ("left", "boom in the frame worker")):
            await pilot.press(key)
            for _ in range(100):
                await pilot.pause(0.05)
                if text in status(app):
                    break
            assert text in status(app)
            assert app.is_running
        await pilot.press("left")
        assert await wait_for(pilot, lambda: app.frame is not None
                              and app.frame.request.theta_i == 30.0)
    assert app.return_code in (0, None)


async def test_a_fast_frame_is_computed_on_the_event_loop_a_slow_one_in_the_worker(
        monkeypatch):
    # a frame of registered models is computed where the key is handled (no thread to start
    # and wait for) unless a frame of its kind took INLINE_S of CPU time or more lately; then,
    # and for a new albedo curve, the worker.  The CPU times the viewer notes are a clock of
    # the test's: the thread's CPU time (every frame far below the INLINE_S set here, however
    # busy the machine) plus twice INLINE_S for each frame the test makes slow
    import threading
    import time
    import types

    from tuibrdf.app import frames
    from tuibrdf.core.views import frame as core_frame

    monkeypatch.setattr(frames, "INLINE_S", 5.0)
    extra = [0.0]
    monkeypatch.setattr(frames, "time", types.SimpleNamespace(
        thread_time=lambda: time.thread_time() + extra[0]))
    core_frame.clear_caches()
    where: list[tuple[float, bool, bool]] = []  # (θi, curve, on the event loop)
    real = core_frame.compute_frame
    slow_from = [90.0]

    def compute(req, **kw):
        where.append((req.theta_i, req.curve, threading.current_thread() is
                      threading.main_thread()))
        if req.theta_i >= slow_from[0]:
            extra[0] += 2 * frames.INLINE_S
        return real(req, **kw)

    monkeypatch.setattr(core_frame, "compute_frame", compute)
    app = BrdfApp(ViewerState(sides=[Side.of("phong")], theta_i=30.0))
    async with app.run_test(size=(120, 36)) as pilot:
        async def frame_of(theta):
            assert await wait_for(pilot, lambda: app.frame is not None
                                  and app.frame.request.theta_i == theta
                                  and app.frame.complete)

        await frame_of(30.0)
        assert where and all(loop for _, _, loop in where)  # the first of a kind too
        await pilot.press("right")
        await frame_of(31.0)
        assert [loop for t, _, loop in where if t == 31.0] == [True]
        slow_from[0] = 32.0  # from here: twice INLINE_S
        await pilot.press("right")  # not known slow: on the loop, and now known slow
        await frame_of(32.0)
        assert [loop for t, _, loop in where if t == 32.0] == [True]
        await pilot.press("right")
        await frame_of(33.0)
        assert where and not any(loop for t, _, loop in where if t == 33.0)
        app.state.view = "albedo"  # the albedo curve, never computed: the worker
        app._changed("", relayout=True)
        assert await wait_for(pilot, lambda: app.frame.request.curve and app.frame.complete)
        assert not any(loop for _, curve, loop in where if curve)


def test_view_command_exits_nonzero_and_prints_the_error(monkeypatch, capsys):
    # the real `tuibrdf view` path, headless: an error outside the viewer's handlers (here in
    # building the screen) ends the app with exit status 1 and one line, not a traceback
    import tuibrdf.app.app as app_module
    from tuibrdf.cli import main

    class Headless(CrashingAtStart):
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
    said = captured.out + captured.err
    assert "boom from a test" in said and "Traceback" not in said
    assert len([ln for ln in said.splitlines() if ln.strip()]) == 1, said


# ------------------------------------------------------------------------------ key mash
async def test_key_mash_leaves_a_live_app_and_a_valid_state():
    # a seeded storm of table keys and printable characters (into the save dialog too);
    # quit keys left out, since quitting is what they do
    rng = random.Random(11)
    table = [name for k in keys.KEYS if k.action not in ("quit", "interrupt")
             for name in k.keys.split(",")]
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
    core_frame.clear_caches()
    calls = {}
    for name in ("phong", "cook-torrance"):
        m = MODELS[name]
        calls[name] = []

        def kernel(wi, wo, _m=m, _c=calls[name], **kw):
            _c.append(tuple(np.shape(wo)[:-1]))  # the plane's call: an (H, W) image
            return _m.kernel(wi, wo, **kw)

        monkeypatch.setitem(MODELS, name, dataclasses.replace(m, kernel=kernel))
    n_sections = (3 * len(core_frame.SECTION_THETAS),)
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
    from tuibrdf.state.viewer import Side, ViewerState

    # a coloured base (the default is grey, whose channels read as one value: issue 36)
    app = BrdfApp(ViewerState(sides=[Side.of("gltf", {"base_color": (0.9, 0.5, 0.2)})]),
                  sync=True)
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


async def test_a_model_files_frames_are_never_computed_on_the_event_loop(monkeypatch, tmp_path):
    # a model read from a user's file (a .brdf here; a .py model or a .bsdf the same way) runs
    # the user's kernel: every one of its frames is computed in the worker, however quick
    # (INLINE_S: ten seconds), so the keys, q among them, never wait for it on the event loop.
    # A registered model's quick frames are computed on the loop (the control)
    import shutil
    import threading

    from tuibrdf.app import frames

    monkeypatch.setattr(frames, "INLINE_S", 10.0)
    path = tmp_path / "mine.brdf"
    shutil.copy(DATA_DIR / "brdf" / "lambert.brdf", path)
    core_frame.clear_caches()
    where: list[tuple[str, bool]] = []  # (model, on the event loop)
    real = core_frame.compute_frame

    def compute(req, **kw):
        on_loop = threading.current_thread() is threading.main_thread()
        where.extend((m.name, on_loop) for m in req.materials)
        return real(req, **kw)

    monkeypatch.setattr(core_frame, "compute_frame", compute)
    for model in (str(path), "lambert"):
        where.clear()
        app = BrdfApp(ViewerState(sides=[Side.of(model)], theta_i=30.0))
        async with app.run_test(size=(120, 36)) as pilot:
            for theta in (31.0, 32.0, 33.0, 34.0):
                await pilot.press("right")
                assert await wait_for(pilot, lambda t=theta, a=app: a.frame is not None
                                      and a.frame.request.theta_i == t and a.frame.complete)
        assert {name for name, _ in where} == {model}
        assert any(loop for _, loop in where) == (model == "lambert"), where


async def test_a_pane_is_drawn_again_only_when_what_it_shows_changed(monkeypatch):
    # the section's azimuth (a) changes the sections' pictures, not the map's; the same frame
    # shown again draws nothing
    from tuibrdf.app import widgets

    drawn: list[str] = []
    show = widgets.Picture.show

    def spy(self, renderable, key=None):
        drawn.append(self.pane)
        return show(self, renderable, key)

    monkeypatch.setattr(widgets.Picture, "show", spy)
    app = BrdfApp(ViewerState(sides=[Side.of("phong")], theta_i=30.0), sync=True)
    async with app.run_test(size=(160, 48)) as pilot:
        await pilot.pause()
        drawn.clear()
        await pilot.press("right")  # θi: every picture
        assert {"map-a", "incidence", "perpendicular"} <= set(drawn)
        drawn.clear()
        await pilot.press("a")
        assert app.frame.request.section_azimuth == app.state.section_azimuth
        assert drawn and "map-a" not in drawn
        drawn.clear()
        app.refresh_frame()
        await pilot.pause()
        assert drawn == []


async def test_the_objects_of_start_up_are_frozen_out_of_the_collector(monkeypatch):
    # FREEZE_S after start-up the viewer calls gc.freeze(): later collections do not scan
    # Textual, numpy and the models again
    import gc

    from tuibrdf.app import app as app_module

    monkeypatch.setattr(app_module, "FREEZE_S", 0.05)
    gc.unfreeze()
    gc.disable()  # as `tuibrdf view` starts (cli/view.py): the collector comes back with it
    try:
        app = BrdfApp(ViewerState(sides=[Side.of("phong")]))
        async with app.run_test(size=(100, 30)) as pilot:
            assert gc.get_freeze_count() == 0 and not gc.isenabled()
            assert await wait_for(pilot, lambda: gc.get_freeze_count() > 0)
            assert gc.isenabled()
    finally:
        gc.enable()
        gc.unfreeze()


def test_view_turns_the_collector_back_on_when_it_ends(monkeypatch):
    # `tuibrdf view` starts with the collector off (start-up makes objects that live for the
    # session); however the viewer ends, before the app froze them or not, it is on again
    import gc

    from tuibrdf.cli import view

    seen = []

    def fake_run(args):
        seen.append(gc.isenabled())
        raise RuntimeError("the viewer failed")

    monkeypatch.setattr(view, "_run", fake_run)
    with pytest.raises(RuntimeError):
        view.run(None)
    assert seen == [False] and gc.isenabled()


def _fresh_rows(app, pane: str) -> list[list[tuple[str, object]]]:
    """``pane``'s rows drawn from nothing from the frame on screen (the pictures' own way,
    which tests/render/test_lines.py checks against Rich)."""
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


@pytest.mark.parametrize("seed", [3, 8])
async def test_after_any_keys_every_picture_is_what_drawing_it_gives(monkeypatch, seed):
    # a seeded walk over the keys a user presses again and again, their opposites and keys
    # that change the look, the panes or the side, with pauses of random length (a frame
    # caught on its way: computing, its fast part shown, done): once each key's frame is
    # complete, every visible picture is cell for cell what drawing it from that frame gives,
    # whether it was kept from the frame before (nothing it shows changed) or drawn at the key
    from tuibrdf.app.text import visible_panes

    core_frame.clear_caches()
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


async def test_a_held_key_on_a_threaded_model_shows_frames_while_held(monkeypatch, tmp_path):
    # a model file's frames are computed in the worker; here each takes 40 ms of wall time
    # (a sleep in the test's compute_frame: the scheduling, not the machine's speed, decides)
    # and → comes every 10 ms for 0.6 s.  The viewer must not cancel every frame for the next
    # key (nothing was shown until the key was released) nor start a thread per key (they
    # share one interpreter): one job at a time, each finished job's pictures shown, and the
    # final state's complete frame last
    import shutil
    import threading
    import time

    path = tmp_path / "mine.brdf"
    shutil.copy(DATA_DIR / "brdf" / "lambert.brdf", path)
    core_frame.clear_caches()
    real = core_frame.compute_frame
    running, most = [0], [0]
    lock = threading.Lock()

    def compute(req, **kw):
        with lock:
            running[0] += 1
            most[0] = max(most[0], running[0])
        try:
            time.sleep(0.04)
            return real(req, **kw)
        finally:
            with lock:
                running[0] -= 1

    monkeypatch.setattr(core_frame, "compute_frame", compute)
    app = BrdfApp(ViewerState(sides=[Side.of(str(path))], theta_i=0.0))
    async with app.run_test(size=(120, 36)) as pilot:
        assert await wait_for(pilot, lambda: app.frame is not None and app.frame.complete)
        shown = app.frames
        for _ in range(60):
            burst(app, "right")
            await pilot.pause(0.01)
        during = app.frames - shown
        assert app.state.theta_i == 60.0
        assert await wait_for(pilot, lambda: app.frame.request.theta_i == 60.0
                              and app.frame.complete)
        assert "θi 60°" in status(app) and "a(θi) …" not in status(app)
    # 0.6 s of keys, ≥ 40 ms a frame: at most 15 frames; a cancelled-at-every-key viewer
    # showed none before the last key
    assert during >= 3, during
    assert most[0] == 1, most[0]


@pytest.mark.parametrize("hold", [True, False])
async def test_a_threaded_frame_whose_albedo_is_quick_is_shown_in_one_piece(monkeypatch,
                                                                             tmp_path, hold):
    # each message from the worker is a paint, and Textual holds a second paint until its next
    # 1/60 s tick: when the slow part (the albedo) of a kind of frame was quick lately
    # (HOLD_S), the pictures wait for it and come with it; else (HOLD_S = 0, the control) the
    # pictures come first and the albedo after
    import shutil

    from tuibrdf.app import frames

    monkeypatch.setattr(frames, "HOLD_S", 1e9 if hold else 0.0)
    path = tmp_path / "mine.brdf"
    shutil.copy(DATA_DIR / "brdf" / "lambert.brdf", path)
    core_frame.clear_caches()
    app = BrdfApp(ViewerState(sides=[Side.of(str(path))], theta_i=10.0))
    shown: list[tuple[float, bool]] = []
    real_show = app.show_frame

    def show(res, passed=False):
        shown.append((res.request.theta_i, res.complete))
        return real_show(res, passed)

    monkeypatch.setattr(app, "show_frame", show)
    async with app.run_test(size=(120, 36)) as pilot:
        assert await wait_for(pilot, lambda: app.frame is not None and app.frame.complete)
        for theta in (11.0, 12.0, 13.0):
            await pilot.press("right")
            assert await wait_for(pilot, lambda t=theta: app.frame.request.theta_i == t
                                  and app.frame.complete)
    # the first frame has no history (pictures first); the next ones follow HOLD_S
    later = [c for t, c in shown if t >= 12.0]
    assert later.count(True) == 2
    assert later.count(False) == (0 if hold else 2), shown


async def test_the_first_frame_is_computed_once_at_the_panes_laid_out_size(monkeypatch):
    """Start-up computes one frame, at the map's size after the first layout: not one
    before it (the panes have no size yet: a frame without a map, drawn and painted for
    nothing, ~15 ms of the first screen), and not one at a size the panels' first rows then
    change (they are filled before the layout's end)."""
    core_frame.clear_caches()
    asked: list = []
    real = core_frame.compute_frame

    def compute(req, **kw):
        asked.append(req.map_px)
        return real(req, **kw)

    monkeypatch.setattr(core_frame, "compute_frame", compute)
    app = BrdfApp(ViewerState(sides=[Side.of("phong")], theta_i=30.0))
    async with app.run_test(size=(120, 36)) as pilot:
        assert await wait_for(pilot, lambda: app.frame is not None and app.frame.complete)
        await pilot.pause(0.3)  # any later resize of the panes would ask again
        assert len(asked) == 1 and asked[0] is not None, asked
        assert asked[0] == app.frame.request.map_px
