"""The viewer never dies from input (issue 31): keys on a model without parameters, typed
text that looks like Rich markup, a malformed escape sequence, key bursts in the command
palette, a model file that breaks while shown, a refused preset name, presets with non-BMP
paths and presets that would run a Python file nobody named.

Expected values are the issue's contract (a message, the dialog open, the file skipped) and
values given by the test itself (the typed text, the path written, θi set)."""

from __future__ import annotations

import os
import shutil

import pytest

from tests import DATA_DIR, ROOT
from tests.pilot import wait_for
from tuibrdf.app.app import BrdfApp
from tuibrdf.state.viewer import Side, ViewerState

EMPTY_BRDF = ("analytic\n::begin parameters\n::end parameters\n::begin shader\n"
              "vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) { return vec3(0.2); }\n"
              "::end shader\n")


@pytest.fixture(autouse=True)
def config_home(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path / "config"))
    return tmp_path / "config"


def status(app) -> str:
    return str(app.query_one("#status").render())


def make(*sides, theta=30.0) -> BrdfApp:
    return BrdfApp(ViewerState(sides=list(sides), theta_i=theta), sync=True)


# -- models without parameters -------------------------------------------------------------
def parameterless(tmp_path) -> list[str]:
    from tests.rgl_writer import material, write_tensor

    empty = tmp_path / "empty.brdf"
    empty.write_text(EMPTY_BRDF)
    return [str(write_tensor(tmp_path / "synthetic.bsdf", material())), str(empty)]


@pytest.mark.parametrize("which", [0, 1], ids=["bsdf", "empty-brdf"])
async def test_parameter_keys_on_a_model_without_parameters_are_refused(tmp_path, which):
    path = parameterless(tmp_path)[which]
    app = make(Side.of(path))
    async with app.run_test(size=(100, 30)) as pilot:
        for key in ("up", "down", "plus", "minus", "equals_sign", "enter", "r",
                    "left_curly_bracket", "right_curly_bracket"):
            await pilot.press(key)
            await pilot.pause()
            assert "has no parameters" in app.message, key
            assert app.screen is app.screen_stack[0]  # no dialog opened
        panel = app.query_one("#panel-a")
        assert "-1" not in str(panel.border_subtitle or "")
        assert "(no parameters)" in str(panel.render())
        await pilot.press("right")
        assert app.state.theta_i == 31.0


# -- typed text is text --------------------------------------------------------------------
@pytest.mark.parametrize("typed", ["[/]", "[bold]x", "[link=file:///]y[/link]", "[/foo]"])
async def test_typed_text_is_shown_literally(typed):
    app = make(Side.of("cook-torrance"))
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.press("equals_sign")  # kd: a number
        await pilot.pause()
        await pilot.press("ctrl+u", *typed, "enter")
        await pilot.pause()
        assert type(app.screen).__name__ == "ValueScreen"  # refused: it stays open
        assert typed in str(app.screen.query_one("#error").render())
        await pilot.press("escape")
        await pilot.press("down", "down", "down")  # the choice parameter (a filtered list)
        await pilot.press("equals_sign")
        await pilot.pause()
        await pilot.press(*typed)
        await pilot.pause()
        assert repr(typed) in str(app.screen.query_one("#error").render())
        await pilot.press("escape")
        await pilot.press("right")
        assert app.state.theta_i == 31.0
    assert app.return_code in (0, None)


async def test_a_file_name_that_looks_like_markup_is_shown_as_is(tmp_path):
    from rich.text import Text

    path = tmp_path / "[bold]x[red].brdf"
    shutil.copy(DATA_DIR / "brdf" / "lambert.brdf", path)
    app = make(Side.of(str(path)))
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.pause()
        title = app.query_one("#panel-a").border_title  # (Textual gives it back as markup)
        assert "[bold]x[red].brdf" in Text.from_markup(title).plain


# -- raw input -------------------------------------------------------------------------------
def test_a_malformed_sequence_is_dropped_and_the_input_goes_on():
    from textual import events

    from tuibrdf.app.textual_internals import SafeXTermParser

    p = SafeXTermParser()
    got = [e.key for e in p.feed("a\x1b[1114112ub\x1b[99999999999999999999uc\x1b[Ad")
           if isinstance(e, events.Key)]
    assert got == ["a", "b", "c", "up", "d"]


def test_a_paste_that_never_ends_is_dropped_and_keys_are_keys_again(monkeypatch):
    import time

    from textual import events

    from tuibrdf.app.textual_internals import SafeXTermParser

    p = SafeXTermParser()
    p.PASTE_S = 0.2
    assert [e.key for e in p.feed("a\x1b[200~pasted, never ended")] == ["a"]
    time.sleep(0.3)
    list(p.tick())  # (the driver ticks the parser every 0.1 s)
    got = [e.key for e in p.feed("b\x1b[Ac") if isinstance(e, events.Key)]
    assert got == ["b", "up", "c"]
    whole = list(SafeXTermParser().feed("\x1b[200~hi\x1b[201~q"))  # a whole paste: as before
    assert isinstance(whole[0], events.Paste) and whole[0].text == "hi"
    assert whole[1].key == "q"


@pytest.mark.parametrize("driver", ["linux_driver", "web_driver"])
def test_the_viewer_installs_the_guarded_parser_in_its_driver(driver, monkeypatch):
    # the terminal's driver, or the web's (tuibrdf serve sets TEXTUAL_DRIVER)
    import importlib

    from textual import constants
    from textual._xterm_parser import XTermParser

    from tuibrdf.app.textual_internals import SafeXTermParser

    module = importlib.import_module(f"textual.drivers.{driver}")
    cls = "WebDriver" if driver == "web_driver" else "LinuxDriver"
    monkeypatch.setattr(constants, "DRIVER", f"textual.drivers.{driver}:{cls}")
    monkeypatch.setattr(module, "XTermParser", XTermParser)  # Textual's own (restored after)
    BrdfApp(ViewerState())
    assert module.XTermParser is SafeXTermParser


@pytest.mark.parametrize("keys", [("ctrl+p", "enter", "enter"),
                                  ("ctrl+p", "enter", "enter", "enter"),
                                  ("question_mark", "escape", "escape"),
                                  ("s", "escape", "escape")])
async def test_a_dialog_asked_to_close_twice_never_closes_the_viewer(keys):
    from textual import events

    app = make(Side.of("phong"))
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.pause()
        for k in keys:  # in one burst, as a terminal delivers them
            app.post_message(events.Key(k, None))
        await pilot.pause(0.3)
        assert app.return_code is None and app._exception is None
        while len(app.screen_stack) > 1:
            await pilot.press("escape")
        await pilot.press("right")
        assert app.state.theta_i == 31.0


# -- a model file that breaks while shown ----------------------------------------------------
@pytest.mark.parametrize("src,broken", [
    (DATA_DIR / "brdf" / "lambert.brdf", "analytic\n::begin shader\nvec3 BRDF( {\n"),
    (ROOT / "docs" / "examples" / "minnaert.py", "def (:\n")], ids=["brdf", "py"])
async def test_a_shown_file_that_breaks_disappears_and_returns(tmp_path, src, broken):
    path = tmp_path / f"live{src.suffix}"
    shutil.copy(src, path)
    good = path.read_text()
    app = make(Side.of(str(path)))
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.pause()
        shown = app.frame.request.materials  # the last good picture's
        stamp = [os.stat(path).st_mtime_ns]

        def rewrite(text: str) -> None:
            path.write_text(text)
            stamp[0] += 10**9  # a new mtime, whatever the file system's resolution
            os.utime(path, ns=(stamp[0], stamp[0]))

        for step in ("broken", "removed", "back", "broken", "good"):
            if step == "broken":
                rewrite(broken)
            elif step == "removed":
                path.unlink()
            else:
                rewrite(good + "\n" * (1 + (step == "good")))
            app._check_files()
            await pilot.pause()
            if step in ("broken", "removed"):
                assert "cannot be read" in app.message, step
                assert app.frame.request.materials == shown  # the last good picture stays
            else:
                assert "redrawn" in app.message, step
                assert app.frame.request.materials != shown  # re-read, drawn again
                shown = app.frame.request.materials
            assert app.is_running
        await pilot.press("right")
        assert app.state.theta_i == 31.0


# -- user kernels: never on the event loop ----------------------------------------------------
THREAD_PROBE = '''
import threading
import numpy as np
from tuibrdf.core.params import Model, Param

KD = Param("kd", "Kd", 0.4, 0.0, 1.0, 0.1, doc="diffuse reflectance")
SEEN = []


def kernel(wi, wo, kd):
    SEEN.append(threading.current_thread() is threading.main_thread())
    return np.full(np.broadcast_shapes(wi.shape, wo.shape)[:-1], kd / np.pi)


MODEL = Model("probe", "Probe", (KD,), kernel)
'''


async def test_a_python_kernel_never_runs_on_the_event_loop(tmp_path, monkeypatch):
    # INLINE_S large: a built-in model's frames would all be computed on the loop; a .py
    # model's, however quick, never are (first frame and after keys alike)
    import sys

    from tuibrdf.app import frames

    monkeypatch.setattr(frames, "INLINE_S", 100.0)
    path = tmp_path / "probe.py"
    path.write_text(THREAD_PROBE)
    app = BrdfApp(ViewerState(sides=[Side.of(str(path))]))
    async with app.run_test(size=(100, 30)) as pilot:
        for theta in (31.0, 32.0):
            await pilot.press("right")
            assert await wait_for(pilot, lambda t=theta: app.frame is not None
                                  and app.frame.request.theta_i == t and app.frame.complete)
    seen = [m for m in sys.modules.values() if getattr(m, "SEEN", None) is not None
            and getattr(m, "__file__", "") == str(path)]
    assert seen and seen[0].SEEN and not any(seen[0].SEEN)


async def test_a_click_on_a_python_models_picture_reads_it_off_the_event_loop(tmp_path):
    # a click's readout (f at the directions under the pointer) evaluates the kernel, which
    # may never return: in a thread too, then shown (f = kd/π everywhere)
    import math
    import sys

    from tests.app.test_probe import numbers_after, status

    path = tmp_path / "probe.py"
    path.write_text(THREAD_PROBE)
    app = BrdfApp(ViewerState(sides=[Side.of(str(path))], theta_i=40.0, view="sphere"))
    async with app.run_test(size=(120, 40)) as pilot:
        assert await wait_for(pilot, lambda: app.frame is not None and app.frame.complete)
        seen = [m for m in sys.modules.values() if getattr(m, "SEEN", None) is not None
                and getattr(m, "__file__", "") == str(path)][0].SEEN
        seen.clear()
        await pilot.click("#extra-a", offset=(40, 12))
        assert await wait_for(pilot, lambda: " f=" in status(app))
        assert seen and not any(seen)
        # (printed to 3 digits: 0.127, within half a unit of its last digit)
        assert numbers_after(status(app), " f")[0] == pytest.approx(0.4 / math.pi, abs=5e-4)



async def test_an_edited_python_model_file_is_read_again_off_the_event_loop(tmp_path):
    # re-reading a .py model file runs its module again (a slow import, a loop at its top
    # level): in a thread, and the viewer then draws the new model
    import os
    import sys

    path = tmp_path / "probe.py"
    path.write_text(THREAD_PROBE)
    app = BrdfApp(ViewerState(sides=[Side.of(str(path))]))
    async with app.run_test(size=(100, 30)) as pilot:
        assert await wait_for(pilot, lambda: app.frame is not None and app.frame.complete)
        path.write_text("import threading\nREAD_ON_MAIN = threading.current_thread() is "
                        "threading.main_thread()\n" + THREAD_PROBE.replace("0.4, 0.0", "0.3, 0.0"))
        st = os.stat(path)
        os.utime(path, ns=(st.st_atime_ns, st.st_mtime_ns + 10**9))
        app._check_files()
        assert await wait_for(pilot, lambda: "redrawn" in app.message)
        assert app.state.side.material.model.params[0].default == 0.3  # the new file's
    read = [m.READ_ON_MAIN for m in sys.modules.values()
            if getattr(m, "__file__", "") == str(path) and hasattr(m, "READ_ON_MAIN")]
    assert read and not any(read)

# -- presets -----------------------------------------------------------------------------------
async def test_a_refused_preset_name_keeps_the_dialog_open(config_home):
    app = make(Side.of("phong"))
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.press("s")
        await pilot.pause()
        await pilot.press(*"bad name!", "enter")
        await pilot.pause()
        assert type(app.screen).__name__ == "SaveScreen"
        assert "invalid" in str(app.screen.query_one("#error").render())
        model, gamma = app.state.side.model, app.state.gamma
        await pilot.press("m", "y", "g", "x")  # typed into the dialog, not viewer keys
        await pilot.pause()
        assert (app.state.side.model, app.state.gamma) == (model, gamma)
        await pilot.press("ctrl+u", *"good", "enter")
        await pilot.pause()
        assert app.screen is app.screen_stack[0]
        assert await wait_for(pilot, lambda: "saved" in app.message)
    assert (config_home / "tuibrdf" / "presets" / "good.toml").is_file()


def test_a_preset_round_trips_a_path_with_non_bmp_characters(tmp_path, config_home):
    from tuibrdf.state.presets import load_preset, save_preset

    d = tmp_path / "😀 dir"
    d.mkdir()
    path = d / "lamb😀ert.brdf"
    shutil.copy(DATA_DIR / "brdf" / "lambert.brdf", path)
    save_preset(ViewerState(sides=[Side.of(str(path))], theta_i=20.0), "emoji")
    theta, sides, _look = load_preset("emoji")
    assert theta == 20.0 and sides[0].model == str(path)


def _py_preset(tmp_path, name="code") -> str:
    from tuibrdf.state.presets import save_preset

    py = tmp_path / "mine.py"
    shutil.copy(ROOT / "docs" / "examples" / "minnaert.py", py)
    save_preset(ViewerState(sides=[Side.of(str(py))], theta_i=20.0), name)
    return str(py)


async def test_P_skips_a_preset_that_would_run_a_python_file(tmp_path, config_home):
    from tuibrdf.state.presets import save_preset

    _py_preset(tmp_path, "a-code")
    save_preset(ViewerState(sides=[Side.of("phong")], theta_i=40.0), "b-plain")
    app = make(Side.of("lambert"))
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.press("P")
        assert await wait_for(pilot, lambda: "loaded preset b-plain" in app.message)
        assert "skipped a-code" in app.message and app.state.theta_i == 40.0
        await pilot.press("P")  # only the plain one is left to load
        assert await wait_for(pilot, lambda: app.state.side.model == "phong"
                              and "skipped a-code" in app.message)


def test_view_preset_naming_a_python_file_needs_the_file_or_trust(tmp_path, config_home,
                                                                  capsys):
    from tuibrdf.cli import build_parser, main
    from tuibrdf.cli.common import UsageError
    from tuibrdf.cli.view import build_state

    py = _py_preset(tmp_path)
    parser = build_parser(["view"])
    with pytest.raises(UsageError, match="--trust"):
        build_state(parser.parse_args(["view", "--preset", "code"]))
    for argv in (["view", py, "--preset", "code"], ["view", "--preset", "code", "--trust"]):
        state = build_state(parser.parse_args(argv))
        assert state.side.model == py and state.theta_i == 20.0
    assert main(["view", "--preset", "code"]) == 2
    assert "--trust" in capsys.readouterr().err


def test_render_preset_reads_a_saved_preset_and_needs_trust_for_python(tmp_path, config_home,
                                                                      capsys):
    """``render --preset NAME`` draws a saved preset's sides (its look is the viewer's), and
    one naming a ``.py`` file only with ``--trust``, as ``view --preset``."""
    from tuibrdf.cli import main
    from tuibrdf.state.presets import save_preset

    save_preset(ViewerState(sides=[Side.of("phong"), Side.of("ggx")], theta_i=40.0), "pair")
    assert main(["render", "--preset", "pair", "--view", "map", "--width", "60", "--height",
                 "18", "--color", "none"]) == 0
    out = capsys.readouterr().out
    assert "phong" in out and "ggx" in out
    _py_preset(tmp_path)
    assert main(["render", "--preset", "code", "--width", "60", "--height", "18"]) == 2
    assert "--trust" in capsys.readouterr().err
    assert main(["render", "--preset", "code", "--trust", "--width", "60", "--height", "18",
                 "--color", "none"]) == 0


# -- a huge terminal ---------------------------------------------------------------------------
async def test_a_huge_pane_draws_a_bounded_picture_centred_with_a_note():
    from tuibrdf.app.widgets import MAX_PANE

    app = make(Side.of("phong"))
    async with app.run_test(size=(MAX_PANE[0] + 200, MAX_PANE[1] + 60)) as pilot:
        await pilot.pause()
        pic = app.query_one("#map-a")
        pw, ph = pic.size.width, pic.size.height
        assert ph > MAX_PANE[1]
        cw, ch = min(pw, MAX_PANE[0]), MAX_PANE[1]
        w, h = app.frame.request.map_px  # the frame's pixels: of the bounded picture
        assert w <= cw and h <= 2 * ch
        rows = ["".join(seg.text for seg in row) for row in pic._lines]
        assert len(rows) == ph and all(len(r) == pw for r in rows)
        top = (ph - (ch + 1)) // 2  # the picture and its note, centred
        assert all(not r.strip() for r in rows[:top])
        assert "(drawn at" in rows[top + ch] and f"this pane is {pw}×{ph}" in rows[top + ch]


def test_every_handler_of_the_viewer_survives_its_errors():
    """Each place Textual calls the viewer's code (``action_*``, ``on_*``, the pictures'
    mouse callbacks ``picture_*``) in every class of tuibrdf.app is wrapped by
    ``guard.survives``: an error there is a status message, not the end of the viewer.  A
    handler added without it fails here."""
    import importlib
    import inspect
    import pkgutil

    import tuibrdf.app as pkg

    bare = []
    for info in pkgutil.iter_modules(pkg.__path__):
        mod = importlib.import_module(f"tuibrdf.app.{info.name}")
        for _, cls in inspect.getmembers(mod, inspect.isclass):
            if cls.__module__ != mod.__name__:
                continue
            for name, fn in vars(cls).items():
                if callable(fn) and name.startswith(("action_", "on_", "_on_", "picture_")) \
                        and not getattr(fn, "__survives__", False):
                    bare.append(f"{cls.__module__}.{cls.__name__}.{name}")
    assert not bare, bare
