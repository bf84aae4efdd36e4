"""The viewer driven by keys (Textual's Pilot).

Expected values come from the parameter declarations (each Param's step and coarse step, its
range, the kd + ks ≤ 1 constraint) and the key table of issue 4 / SPEC §5, not from the app.
"""

from functools import partial

import pytest

from tests import DATA_DIR
from tests.pilot import wait_for as pilot_wait_for
from tuibrdf.app.app import BrdfApp
from tuibrdf.app.text import visible_panes
from tuibrdf.core.registry import MODELS
from tuibrdf.state.viewer import Side, ViewerState


@pytest.fixture(autouse=True)
def config_home(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path))
    return tmp_path


def make(model="phong", theta=30.0, **params):
    return BrdfApp(ViewerState(sides=[Side.of(model, params)], theta_i=theta), sync=True)


def status(app) -> str:
    return str(app.query_one("#status").render())


async def test_theta_keys_step_by_one_and_ten():
    app = make()
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.press("right")
        assert app.state.theta_i == 31.0
        await pilot.press("shift+left")
        assert app.state.theta_i == 21.0
        await pilot.pause()
        assert "θi 21°" in status(app)


async def test_theta_limit_is_refused_with_a_message():
    app = make(theta=90.0)
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.press("right")
        await pilot.pause()
        assert app.state.theta_i == 90.0
        assert "range 0–90°" in app.message and "0–90°" in status(app)


async def test_param_keys_use_the_declared_steps():
    app = make(kd=0.2, ks=0.3, n=20.0)
    kd = MODELS["phong"].param("kd")
    n = MODELS["phong"].param("n")
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.press("plus")
        assert app.state.side.values["kd"] == pytest.approx(0.2 + kd.step)
        await pilot.press("left_square_bracket", "left_square_bracket")
        assert app.state.side.values["kd"] == pytest.approx(0.2 - kd.step)
        await pilot.press("down", "down")  # third row: n
        await pilot.press("right_curly_bracket")
        assert n.relative  # an exponent: the coarse step doubles it (issue 12 item 7)
        assert app.state.side.values["n"] == pytest.approx(2 * 20.0)
        await pilot.press("r")
        assert app.state.side.values["n"] == n.default


async def test_typed_entry_sets_a_parameter_and_refuses_out_of_range():
    app = make(kd=0.2, ks=0.3, n=20.0)
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.press("down", "down", "equals_sign")  # n: = opens the input
        await pilot.pause()
        assert type(app.screen).__name__ == "ValueScreen"
        await pilot.press("ctrl+u", *"20000", "enter")  # out of [0, 10000]: stays open
        await pilot.pause()
        assert type(app.screen).__name__ == "ValueScreen"
        assert app.state.side.values["n"] == 20.0
        await pilot.press("ctrl+u", *"1000", "enter")
        await pilot.pause()
        assert type(app.screen).__name__ != "ValueScreen"
        assert app.state.side.values["n"] == 1000.0
        await pilot.press("t", "ctrl+u", *"12.5", "enter")  # θi typed
        await pilot.pause()
        assert app.state.theta_i == 12.5
        await pilot.press("enter", "escape")  # Esc cancels: nothing changes
        await pilot.pause()
        assert app.state.side.values["n"] == 1000.0


async def test_choice_picker_filters_the_names():
    from tuibrdf.state.viewer import Side, ViewerState

    app = BrdfApp(ViewerState(sides=[Side.of("abc")]), sync=True)
    p = MODELS["abc"].param("material")
    target = p.choices[-1]
    async with app.run_test(size=(100, 30)) as pilot:
        app.state.side.selected = [r.param.name for r in app.state.side.rows()].index(
            "material")
        await pilot.press("enter")
        await pilot.pause()
        await pilot.press(*target)  # typing the full name leaves it first in the list
        await pilot.pause()
        await pilot.press("enter")
        await pilot.pause()
        assert app.state.side.values["material"] == target


async def test_constraint_refused_and_values_unchanged():
    app = make(kd=0.5, ks=0.5, n=20.0)  # kd + ks = 1: no room
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.press("plus")
        await pilot.pause()
        assert app.state.side.values["kd"] == 0.5
        assert "kd + ks" in app.message


async def test_model_cycling_keeps_theta_and_the_panel_follows():
    app = make(theta=42.0)
    names = list(MODELS)
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.press("m")
        await pilot.pause()
        assert app.state.side.model == names[names.index("phong") + 1]
        assert app.state.theta_i == 42.0
        panel = app.query_one("#panel-a")
        assert panel.border_title == MODELS[app.state.side.model].title
        await pilot.press("M")
        assert app.state.side.model == "phong"


async def test_compare_presets_from_the_seed():
    app = make()
    async with app.run_test(size=(120, 36)) as pilot:
        await pilot.press("p")
        await pilot.pause()
        assert [s.model for s in app.state.sides] == ["lambert", "oren-nayar"]
        assert app.query_one("#map-b").display and app.query_one("#diff").display
        await pilot.press("p")
        a, b = app.state.sides
        assert (a.model, a.values["kd"], a.values["ks"], a.values["n"]) == \
            ("phong", 0.0, 0.08, 70.0)  # seed §8: Phong kd=0, ks=0.08, n=70
        assert (b.model, b.values["kd"], b.values["f0"], b.values["m"]) == \
            ("cook-torrance", 0.0, 0.04, 0.07)  # Cook-Torrance kd=0, f0=0.04, m=0.07
        await pilot.press("tab", "plus")  # keys act on B now
        assert app.state.sides[1].values["kd"] == pytest.approx(0.01)
        assert app.state.sides[0].values["kd"] == 0.0
        await pilot.press("c")
        assert not app.state.compare and not app.query_one("#map-b").display


async def test_preset_round_trip_restores_every_value(config_home):
    app = make("cook-torrance", theta=55.0, kd=0.3, f0=0.2, m=0.15)
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.press("s")
        await pilot.pause()
        await pilot.press(*"mine", "enter")
        await pilot.pause()
        assert "saved" in app.message
    assert (config_home / "tuibrdf" / "presets" / "mine.toml").is_file()
    other = make()
    async with other.run_test(size=(100, 30)):
        assert other.load("mine") is None
        assert other.state.theta_i == 55.0
        s = other.state.side
        assert s.model == "cook-torrance"
        assert (s.values["kd"], s.values["f0"], s.values["m"]) == (0.3, 0.2, 0.15)


async def test_saved_presets_load_from_the_keyboard(config_home):
    # `P` with nothing saved says where presets live; then it cycles the saved ones by name
    app = make("phong", kd=0.1)
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.press("P")
        assert "no saved presets" in app.message
        for name, kd, theta in (("a-first", 0.3, 40.0), ("b-second", 0.4, 50.0)):
            assert app.state.row.param.name == "kd"
            assert app.state.type_value(f"{kd}") is None  # what Enter / = does
            app.state.theta_i = theta
            await pilot.press("s")
            await pilot.pause()
            await pilot.press(*name, "enter")
            await pilot.pause()
        await pilot.press("P")
        assert app.message == "loaded preset a-first"
        assert app.state.theta_i == 40.0 and app.state.side.values["kd"] == 0.3
        await pilot.press("P")
        assert app.state.theta_i == 50.0 and app.state.side.values["kd"] == 0.4
        titles = [c.title for c in app.get_system_commands(app.screen)]
        assert "Load preset a-first" in titles and "Load preset b-second" in titles


async def test_malformed_preset_is_reported(config_home):
    d = config_home / "tuibrdf" / "presets"
    d.mkdir(parents=True)
    (d / "bad.toml").write_text("theta_i = [oops\n")
    app = make()
    async with app.run_test(size=(100, 30)):
        msg = app.load("bad")
        assert msg and "bad.toml" in msg and "TOML" in msg
        assert app.state.side.model == "phong"


async def test_every_view_and_toggle_renders_without_error():
    app = make()
    async with app.run_test(size=(100, 30)) as pilot:
        from tuibrdf.state.viewer import MAIN_VIEWS

        n = len(MAIN_VIEWS)
        keys = ("v", "v", "v", "l", "k", "o", "ctrl+left", *["v"] * (n - 3), "c",
                *["v"] * n)
        seen = set()
        for key in keys:
            await pilot.press(key)
            await pilot.pause()
            seen.add((app.state.view, app.state.compare))
            for pane in visible_panes(app.state):  # every pane drew a picture, no message
                text = "".join(s.text for s in app.query_one(f"#{pane}")._strips)
                assert "cannot" not in text and "too small" not in text, (pane, text[:80])
        assert {v for v, _ in seen} == set(MAIN_VIEWS)
        assert {v for v, c in seen if c} == set(MAIN_VIEWS)
        assert app.state.view == "map" and app.state.log and app.state.cosine
        assert app.frames > 0


async def test_too_small_shows_a_message():
    app = make()
    async with app.run_test(size=(50, 15)) as pilot:
        await pilot.pause()
        assert app.screen.has_class("small")
        assert "at least" in str(app.query_one("#toosmall").render())


async def test_no_color_draws_the_plain_picture(no_color):
    app = make()
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.press("right")
        await pilot.pause()
        assert app.color_system() == "none"
        lines = [app.query_one("#map-a").render_line(y).text for y in range(24)]
        assert any("@" in line for line in lines)  # the ASCII ramp's brightest glyph


def test_view_command_line_is_validated_before_textual(capsys):
    from tuibrdf.cli import build_parser, main
    from tuibrdf.cli.view import build_state

    assert main(["view", "nope"]) == 2
    assert "unknown model" in capsys.readouterr().err
    assert main(["view", "phong", "-p", "kd=0.9", "-p", "ks=0.5"]) == 2  # kd + ks > 1
    assert main(["view", "--preset", "missing"]) == 2
    assert "diffuse" in capsys.readouterr().err  # the seed comparisons are offered
    args = build_parser().parse_args(["view", "phong", "--theta-i", "12", "--preset",
                                      "specular"])
    state = build_state(args)
    assert state.compare and state.theta_i == 12.0
    assert [s.model for s in state.sides] == ["phong", "cook-torrance"]


def test_view_checks_a_measured_file_before_textual(capsys, tmp_path):
    from tuibrdf.cli import main

    bad = tmp_path / "short.binary"
    bad.write_bytes(b"\x5a\x00\x00\x00" * 3 + b"\x00" * 80)  # header (90,90,90): wrong
    for argv, expected in ((["view", str(bad)], "wrong header"),
                           (["view", str(tmp_path / "none.binary")], "no such file"),
                           (["view", "merl"], "no file given")):
        assert main(argv) == 2
        err = capsys.readouterr().err
        assert expected in err and err.count("\n") == 1 and "Traceback" not in err


async def test_command_palette_runs_an_action():
    app = make()
    async with app.run_test(size=(100, 30)) as pilot:
        before = app.state.cmap
        await pilot.press("ctrl+p")
        await pilot.pause()
        await pilot.press(*"next colour map")
        from textual.command import CommandList

        for _ in range(100):  # the palette searches asynchronously: poll, up to ≈ 5 s
            if app.screen.query(CommandList) and app.screen.query_one(CommandList).option_count:
                break
            await pilot.pause(0.05)
        await pilot.press("enter")
        for _ in range(100):
            if app.state.cmap != before:
                break
            await pilot.pause(0.05)
        assert app.state.cmap != before


def test_plain_tuibrdf_without_a_terminal_prints_help(capsys):
    from tuibrdf.cli import main

    assert main([]) == 0  # pytest captures stdout: not a terminal, so no viewer
    assert "view" in capsys.readouterr().out


# -- measured data ------------------------------------------------------------------------
def constant_merl(path, value=0.1, nan=False):
    """A MERL file whose every bin holds ``value`` sr⁻¹ (one NaN bin when ``nan``)."""
    import numpy as np

    from tests.merl_writer import write_merl

    table = np.full((3, 90, 90, 180), value)
    if nan:
        table[1, 10, 20, 30] = np.nan
    return write_merl(path, table)


wait_for = partial(pilot_wait_for, seconds=4.0)


async def test_measured_file_loads_in_the_background_then_draws(tmp_path):
    from tuibrdf.core.formats import merl

    merl.clear_cache()
    path = str(constant_merl(tmp_path / "grey.binary", 0.1))
    app = make("merl", file=path)
    async with app.run_test(size=(100, 30)) as pilot:
        # the loader runs in a worker; when it is done the map is drawn from the data:
        # a constant BRDF of 0.1 sr⁻¹ in every channel gives the albedo 0.1·π at any θi
        assert await wait_for(pilot, lambda: not app._loading and app.frames > 0)
        assert await wait_for(pilot, lambda: "a(θi)=(0.314,0.314,0.314)" in status(app))
        assert app.state.side.model == "merl" and f"loaded {path}" in app.message


async def test_a_bad_measured_file_is_a_message_not_a_crash(tmp_path):
    from tuibrdf.core.formats import merl

    merl.clear_cache()
    # header and size are right (what `tuibrdf view` checks up front); a NaN inside is only
    # found by the full read in the viewer
    path = str(constant_merl(tmp_path / "nan.binary", nan=True))
    app = make("merl", file=path)
    async with app.run_test(size=(100, 30)) as pilot:
        assert await wait_for(pilot, lambda: app.state.side.model == "lambert")
        await pilot.pause()
        assert "NaN value in channel G" in app.message and "showing lambert" in app.message
        await pilot.press("right")  # still running, keys work
        assert app.state.theta_i == 31.0


async def test_albedo_curve_is_computed_off_the_loop_then_drawn(monkeypatch):
    # while the curve is computed the pane says so at once, then shows the curve; the
    # quadrature is held back by an event here, so the test sees the pane while it works
    import threading

    from tuibrdf.core.material import Material
    from tuibrdf.core.views import frame as core_frame

    core_frame.clear_caches()
    release = threading.Event()
    real = core_frame.albedo_curve_estimate_resolved

    def held(*args, **kw):
        release.wait(10.0)
        return real(*args, **kw)

    monkeypatch.setattr(core_frame, "albedo_curve_estimate_resolved", held)

    app = BrdfApp(ViewerState(sides=[Side.of("cook-torrance", {"m": 0.05, "kd": 0.1})]))
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.press("v", "v")
        assert app.state.view == "albedo"
        pane = app.query_one("#albedo")

        def shown() -> str:
            return "\n".join(pane.render_line(y).text for y in range(pane.size.height))

        assert "computing" in shown()
        release.set()
        m = Material("cook-torrance", {"m": 0.05, "kd": 0.1})
        assert await wait_for(pilot, lambda: core_frame._CURVES.peek((m, 180.0)) is not None,
                              seconds=10.0)  # (500 rounds of 0.02 s)
        drawn = lambda: "a(θi=30°) = " in shown() and "computing" not in shown()  # noqa: E731
        assert await wait_for(pilot, drawn, seconds=10.0)
        await pilot.press("right")  # keys still work
        assert app.state.theta_i == 31.0


async def test_a_failing_picture_is_a_message_not_a_crash(monkeypatch):
    # kernels raise on a floating-point exception (core/numerics.py); should one ever escape,
    # the pane says so and the viewer keeps running
    from tuibrdf.render import panes

    def broken(*args, **kw):
        raise FloatingPointError("overflow encountered in multiply")

    monkeypatch.setattr(panes, "map_pane", broken)
    app = make()
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.pause()
        pane = app.query_one("#map-a")
        text = "\n".join(pane.render_line(y).text for y in range(pane.size.height))
        assert "cannot draw map-a: overflow" in text
        await pilot.press("right")
        assert app.state.theta_i == 31.0


async def test_preset_io_runs_off_the_event_loop_in_a_daemon_thread(config_home, monkeypatch):
    # issue 17: a preset read stuck on a slow disk must not freeze the keys, and the thread
    # doing it must be a daemon (a pool thread is joined at exit: q would hang)
    import threading

    from tuibrdf.app import app as app_module

    release, seen = threading.Event(), {}

    def slow_load(name, allow_code=False):
        seen["daemon"] = threading.current_thread().daemon
        release.wait(10)
        return 10.0, [Side.of("lambert")]

    monkeypatch.setattr(app_module, "list_presets", lambda: ["slow"])
    monkeypatch.setattr(app_module, "load_preset", slow_load)
    app = BrdfApp(ViewerState(sides=[Side.of("phong")], theta_i=30.0))  # not sync
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.press("P")
        await pilot.pause()
        await pilot.press("right")  # the key is handled while the preset is still read
        await pilot.pause()
        assert app.state.theta_i == 31.0 and app.state.side.model == "phong"
        assert seen.get("daemon") is True
        release.set()
        for _ in range(100):
            await pilot.pause(0.05)
            if app.state.side.model == "lambert":
                break
        assert app.state.theta_i == 10.0 and app.message == "loaded preset slow"


async def test_a_long_message_does_not_wrap_the_status_line():
    # issue 12 item 10: a bad preset name wrapped the status line to a third row
    app = make()
    async with app.run_test(size=(80, 24)) as pilot:
        app._changed("x" * 300)
        await pilot.pause()
        await pilot.pause()
        assert app.query_one("#status").size.height == 2


async def test_compare_mode_below_its_minimum_says_so_and_c_returns():
    app = make()
    async with app.run_test(size=(60, 18)) as pilot:
        await pilot.press("c")
        await pilot.pause()
        assert app.screen.has_class("small")
        assert "compare mode needs at least 80×24" in str(app.query_one("#toosmall").render())
        await pilot.press("c")
        await pilot.pause()
        assert not app.screen.has_class("small")
        # at 18 rows one section is shown, with the rows both would share
        assert app.query_one("#incidence").display and not app.query_one("#perpendicular").display


async def test_panel_columns_line_up_with_long_labels():
    """A .brdf file's parameters have long names (baseColor.r, clearcoatGloss): every row's
    value must still start in the same column (they were padded to 7 cells only, so each
    long name pushed its own row's value right)."""

    path = str(DATA_DIR / "brdf" / "disney.brdf")
    app = BrdfApp(ViewerState(sides=[Side(path)]), sync=True)
    async with app.run_test(size=(160, 48)) as pilot:
        await pilot.pause()
        lines = str(app.query_one("#panel-a").render()).splitlines()
        assert len(lines) >= 10
        labels = [r.label for r in app.state.side.rows()]
        assert max(len(x) for x in labels) > 7  # the case this is about
        width = min(max(len(x) for x in labels), 16)
        # "▶ " or "  ", the label column, then the value right-aligned in 8 cells
        ends = {len(line[:2 + width + 8].rstrip()) for line in lines}
        assert ends == {2 + width + 8}, lines


async def test_a_frame_that_cannot_be_computed_says_its_albedo_will_not_come(tmp_path):
    # a user's kernel that returns NaN: every pane and the status line say why, and the
    # albedo is "—" (not computed), not "…" (still computing); the next good frame shows it
    path = tmp_path / "half_nan.py"
    path.write_text(
        "import numpy as np\n"
        "from tuibrdf.core.params import Model, Param\n"
        "A = Param('a', 'a', 0.5, 0.0, 1.0, 0.1, doc='NaN from 0.55 on')\n"
        "def f(wi, wo, a):\n"
        "    return np.where(a > 0.55, np.nan, a / np.pi) + 0.0 * wo[..., 2]\n"
        "MODEL = Model('half-nan', 'Half NaN', (A,), f)\n", encoding="utf-8")
    app = make(str(path))
    async with app.run_test(size=(120, 36)) as pilot:
        await pilot.pause()
        assert "a(θi)=0.5" in status(app)  # a/π: albedo a
        await pilot.press("plus")  # a = 0.6: NaN
        await pilot.pause()
        assert "cannot compute this frame" in status(app) and "a(θi) —" in status(app)
        assert "…" not in status(app).split("\n")[0]
        await pilot.press("minus")
        await pilot.pause()
        assert "a(θi)=0.5" in status(app)
