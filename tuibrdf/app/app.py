"""The Textual viewer: wiring only.  A key calls one :class:`ViewerState` transition (plain
Python, :mod:`.state`); the panes show one :class:`~tuibrdf.core.views.frame.FrameResult` through
:mod:`tuibrdf.render.panes`, delivered by :class:`.frames.FrameDelivery` (the data flow is
described there).
"""

from __future__ import annotations

import gc
import threading
from functools import partial

import numpy as np
from textual.app import App, ComposeResult, SystemCommand
from textual.containers import Container, Horizontal, Vertical
from textual.css.query import NoMatches
from textual.widgets import Static

from tuibrdf.app import keys
from tuibrdf.app.figures import FigureWriter
from tuibrdf.app.frames import FrameDelivery, built_in
from tuibrdf.app.guard import error_text, survives
from tuibrdf.app.layout import CSS, arrange
from tuibrdf.app.loading import MeasuredData
from tuibrdf.app.paint import ViewerScreen
from tuibrdf.app.text import PANES
from tuibrdf.app.textual_internals import (
    HOLD_PAINTS,
    OneLineCrash,
    SafeCommandPalette,
    coalesce_resize_signals,
    guard_input_parsing,
)
from tuibrdf.app.widgets import KeyBar, ParamPanel, Picture, QuietStatic, StatusLine
from tuibrdf.core.conventions import fmt_number
from tuibrdf.core.directions import from_degrees
from tuibrdf.core.material import file_stamp
from tuibrdf.core.numerics import KERNEL_ERRORS
from tuibrdf.core.views.frame import FrameRequest, FrameResult, section_directions
from tuibrdf.core.views.hemimap import dir_to_uv, geometry
from tuibrdf.core.views.sections import great_circle
from tuibrdf.render import panes
from tuibrdf.render.colormap import DEFAULT_LEVELS
from tuibrdf.render.sections import angle_at
from tuibrdf.state.bparams import save_bparams
from tuibrdf.state.presets import (
    PresetError,
    PresetRunsCode,
    apply_loaded,
    list_presets,
    load_preset,
    preset_dir,
    preset_path,
    runs_code,
    save_preset,
)
from tuibrdf.state.viewer import ViewerState

#: after start-up (Textual, numpy, the models: ≈ 10⁵ objects kept for the whole session) the
#: collector stops scanning what exists then: a full collection took 23–48 ms here, a stall
#: of any key it fell on; later ones scan only the objects made since (docs/benchmarks.md)
FREEZE_S = 1.0

FILE_POLL_S = 1.0  # how often a model file's mtime is checked (an edit redraws)
#: the screen is first painted with the first frame (paint.ViewerScreen), or after this long
#: without one (a model file still loading, an error, a terminal too small: what it says)
HOLD_S = 0.25
#: colour levels of the maps: 256, as `render` (32 showed false contours on smooth diffuse
#: lobes); a full truecolor update of a 110×46 map of Oren-Nayar at 60° is ≈ 90 KB instead of
#: ≈ 29 KB (256 colours: ≈ 20 KB either way), measured with render_view on this tree
LEVELS = DEFAULT_LEVELS
#: the actions of the viewer itself (not of a modal screen)
VIEWER_ACTIONS = frozenset({"state", "save", "load_next", "help", "type_value", "type_theta",
                            "write_figures", "checks"})


def freeze_start_up() -> None:
    """Keep the collector off what start-up made (``FREEZE_S``), and turn it back on if
    ``tuibrdf view`` turned it off to start (cli/view.py)."""
    gc.freeze()
    gc.enable()


# (the modal screens, the pointer's readouts and the figures are imported when first used:
# not for the first frame, docs/benchmarks.md "start-up"; the presets are listed at mount)


def _list_presets() -> list[str]:
    try:
        return list_presets()
    except (PresetError, OSError):
        return []


def _read_preset(name: str, allow_code=()):
    """``(θi, sides)`` of a saved preset, or the message saying why it cannot be read (a
    :class:`PresetRunsCode` for one naming a Python file not in ``allow_code``)."""
    try:
        return load_preset(name, allow_code)
    except PresetRunsCode as e:
        return e
    except (PresetError, OSError) as e:
        return str(e)


def _name_refused(name: str) -> str | None:
    """Why ``name`` cannot be a preset's name (the save dialog then stays open), or None."""
    try:
        preset_path(name)
    except PresetError as e:
        return str(e)
    return None


def _reread(materials: list) -> list:
    """``(material, the material again or re-read, or why it cannot be read)`` for each
    (:meth:`~tuibrdf.core.material.Material.refreshed`; in a thread)."""
    out = []
    for m in materials:
        try:
            out.append((m, m.refreshed()))
        except ValueError as e:
            out.append((m, str(e)))
    return out


def _reading(res: FrameResult, got) -> str:
    """The status line's readout of a click (:func:`tuibrdf.render.pick.reading`), or why
    there is none: a user's kernel failing at the directions clicked."""
    from tuibrdf.render import pick

    try:
        return pick.reading(res, got)
    except KERNEL_ERRORS as e:
        return "cannot read there: " + " ".join(str(e).split())


class BrdfApp(OneLineCrash, FigureWriter, FrameDelivery, MeasuredData, App):
    """``BrdfApp(state, color=None)``; ``color`` ∈ truecolor/256/none overrides detection.
    ``sync=True`` (tests) computes every frame on the event loop, deterministically."""

    CSS = CSS
    BINDINGS = keys.BINDINGS
    TITLE = "tuibrdf"

    def __init__(self, state: ViewerState | None = None, *, color: str | None = None,
                 message: str = "", sync: bool = False) -> None:
        super().__init__()
        guard_input_parsing(self.driver_class)  # a bad escape sequence is dropped, not fatal
        self.sync = sync
        self.state = state or ViewerState()
        self._color = color
        self.message = message
        self.frame: FrameResult | None = None  # the result on screen
        self.request: FrameRequest | None = None  # the result wanted
        self.frames = 0  # how many results were shown (tests, benchmarks)
        self._loading: dict[str, float] = {}  # measured-data file → fraction read so far
        self._loaded = ""  # the saved preset `P` loaded last
        #: recent computing times of each kind of frame (frames.FrameDelivery._quick)
        self._costs: dict[tuple, list[float]] = {}
        #: and of their slow part (the albedo) alone (frames.HOLD_S)
        self._slow_costs: dict[tuple, list[float]] = {}
        self._jobs: list = []  # the frame jobs whose thread has not ended (frames.FrameJob)
        self._changes = 0  # changes so far; only the last one queued updates the screen
        self._relayout = False  # a change since the last update may show other panes
        self._preset_names: list[str] = []  # the saved presets, for the command palette
        self._widgets: dict[str, object] = {}  # id → widget (BrdfApp.one)
        self._failed_request: FrameRequest | None = None  # the last one that could not be drawn
        self._hold_timer = None  # the timer that ends the screen's hold (hold_screen)
        self._rereading = False  # model files are being checked for edits (_check_files)

    # -- layout ------------------------------------------------------------------------------
    def get_default_screen(self) -> ViewerScreen:
        return ViewerScreen(id="_default")

    def compose(self) -> ComposeResult:
        with Vertical(id="root"):
            with Horizontal(id="body"):
                with Container(id="main"):
                    for pane in ("map-a", "map-b", "diff", "solid-a", "solid-b", "albedo",
                                 "extra-a", "extra-b"):
                        yield Picture(pane, id=pane)
                    yield Static(id="legend")
                with Vertical(id="side"):
                    yield ParamPanel(id="panel-a")
                    yield ParamPanel(id="panel-b")
                    yield Picture("incidence", id="incidence")
                    yield Picture("perpendicular", id="perpendicular")
            yield StatusLine(id="status")
        yield QuietStatic(id="toosmall")
        yield KeyBar()

    def _viewer_screen(self) -> ViewerScreen | None:
        screen = self.screen_stack[0] if self.screen_stack else None
        return screen if isinstance(screen, ViewerScreen) else None

    def hold_screen(self) -> None:
        """Paint nothing of the viewer's screen until its frame is drawn (a new layout:
        :meth:`release_screen`), or :data:`HOLD_S` at most."""
        screen = self._viewer_screen()
        if screen is None or not HOLD_PAINTS:
            return
        screen.held = True
        if self._hold_timer is not None:  # (a hold's own timer: never an earlier one's)
            self._hold_timer.stop()
        self._hold_timer = self.set_timer(HOLD_S, self.release_screen)

    def release_screen(self) -> None:
        """Paint the viewer's screen from now on, what the held paints did not write with
        it: its frame is drawn, or what it shows instead (a message, a terminal too small),
        or :data:`HOLD_S` passed without one."""
        if self._hold_timer is not None:
            self._hold_timer.stop()
            self._hold_timer = None
        screen = self._viewer_screen()
        if screen is not None and screen.held:
            screen.release()

    @survives
    def on_mount(self) -> None:
        self.hold_screen()  # (held since it was made: the first paint is the first frame's)
        self._changed(self.message, relayout=True)
        self.set_interval(FILE_POLL_S, self._check_files)
        self.app_resume_signal.subscribe(self, self._resumed)
        coalesce_resize_signals()  # a flood of window changes nests no handler in another
        self.background(_list_presets, self._listed)
        if not self.sync:
            self.set_timer(FREEZE_S, freeze_start_up)

    @survives
    def on_resize(self, event) -> None:
        self._changed(self.message, relayout=True)

    @survives
    def _check_files(self) -> None:
        """A model file edited on disk (mtime or size changed): re-read, redraw.  The stat
        here, the re-read off the event loop (a Python model file's module runs again, and may
        take as long as it likes), and only for a file whose stamp changed: no thread a second
        for files that do not change."""
        materials = [m for m in (side.material for side in self.state.sides)
                     if m.stamp and file_stamp(m.name) != m.stamp]
        if materials and not self._rereading:
            self._rereading = True
            self.background(partial(_reread, materials), self._reread_done)

    @survives
    def _reread_done(self, results: list) -> None:
        """:func:`_reread`'s answers, for the sides still showing the material checked."""
        self._rereading = False
        for old, new in results:
            for side in self.state.sides:
                if side.material is not old:
                    continue
                if isinstance(new, str):
                    self._changed(f"{old.label} changed on disk and cannot be read: {new}")
                elif new is not old:
                    side.material = new
                    self._changed(f"{new.label} changed on disk: redrawn")

    @property
    def look(self) -> panes.Look:
        s = self.state
        return panes.Look(self.color_system(), s.cmap, s.log, LEVELS, "auto", s.azimuth,
                          s.elevation, s.exposure, s.gamma, channel=s.channel, zoom=s.zoom,
                          slice_log=s.slice_log)

    def color_system(self) -> str:
        if self._color:
            return self._color
        if self.no_color:
            return "none"
        cs = self.console.color_system
        return "truecolor" if cs == "truecolor" else ("none" if cs is None else "256")

    def one(self, wid: str):
        """The viewer's widget ``#wid``, looked up once (a query walks the whole DOM: 6 % of
        a key's time when every draw asked again)."""
        w = self._widgets.get(wid)
        if w is None:
            if not self.screen_stack:  # closing: no screen left
                raise NoMatches(f"#{wid}: the viewer has closed")
            w = self._widgets[wid] = self.screen_stack[0].query_one(f"#{wid}")
        return w

    # -- one frame ---------------------------------------------------------------------------
    def _changed(self, message: str | None = None, relayout: bool = False) -> None:
        """After any change: the screen follows once the events already queued are handled
        (a burst of keys costs one update, for the last state)."""
        self.message = message or ""
        self._relayout = self._relayout or relayout
        self._changes += 1
        self.call_later(self._update, self._changes)

    @survives
    def _update(self, change: int) -> None:
        """The layout if the change asked for it, then the frame (:meth:`refresh_frame`: the
        panels and the status line go with it, so one key costs one paint)."""
        if change != self._changes:
            return  # a newer change is queued behind this one
        try:
            if self._relayout:
                self._relayout = False
                self.hold_screen()  # the new panes are painted with their frame, not empty
                shown = self._displayed()
                arrange(self)
                # other panes, or the panels moving them: drawn at their sizes after the
                # layout, once
                if self._panels_move() or self._displayed() != shown:
                    self._status()  # (its height shapes the panes too)
                    self.call_after_refresh(self._update, change)
                    return
            self.refresh_frame()
        except NoMatches:  # keys still queued while the app closes: no widgets left
            pass

    def _displayed(self) -> list[str]:
        """The panes on screen."""
        return [p for p in PANES if self.one(p).display]

    def _panels_move(self) -> bool:
        """Draw the panels; whether one of them takes another height (a model with another
        number of parameters, below :data:`layout.BOTH_PANELS_H`), which moves the panes: a
        frame drawn before the layout would be drawn again at their new sizes, so
        :meth:`_update` draws it after the layout (unless a newer change, a pane's resize say,
        has come by then)."""
        self._panels()
        return any(self.one(p).moving for p in ("panel-a", "panel-b")
                   if self.one(p).display)

    @survives
    async def run_action(self, action, default_namespace=None) -> bool:
        """Textual's, but an error in the action is a message and the viewer goes on
        (every key, palette command and binding of a dialog comes through here)."""
        return await super().run_action(action, default_namespace)

    def report_error(self, error: Exception, where: str) -> None:
        """An error in the viewer's own code (:mod:`.guard`): a message on the status line;
        the last picture stays and the viewer goes on."""
        self.message = f"error in {where}: {error_text(error)} (the viewer goes on)"
        try:
            self._status()
        except Exception:  # (no status line: closing, or the error is in drawing it)
            pass

    def check_action(self, action: str, parameters: tuple[object, ...]) -> bool | None:
        """While a modal screen (help, save, palette) is open, the viewer's keys wait."""
        return not (action in VIEWER_ACTIONS and len(self.screen_stack) > 1)

    @survives
    def picture_clicked(self, pane: str, x: int, y: int) -> None:
        """A click at cell ``(x, y)`` of ``pane``: on a map or a section the probe goes to
        the direction drawn there (the status line then reads it)."""
        res = self.frame
        if res is None or pane not in PANES:
            return
        view, _ = PANES[pane]
        uv = None
        if view == "map" and res.request.map_px is not None and y >= 1:
            g = geometry(*res.request.map_px)
            uv = g.to_uv(np.array(x + 0.5), np.array(2.0 * (y - 1) + 1.0))  # cell centre
        elif view in ("incidence", "perpendicular") and y >= 1:
            pic = self.one(pane)
            t = angle_at(x, y - 1, pic.size.width, pic.size.height - 1)
            if t is not None:
                if view == "incidence":
                    w = section_directions("incidence", np.array([t]), res.request.phi_i)[0]
                else:
                    # the section's own centre (the peak, lowered to 89° on the horizon)
                    w, above = great_circle(from_degrees(*res.sides[0].section_center),
                                            np.array([t]), res.request.section_azimuth)
                    w = w[0] if above[0] else None
                if w is not None:
                    uv = dir_to_uv(w)
        if uv is None:
            self._read(pane, view, x, y)
            return
        self._changed(self.state.set_probe(float(uv[0]), float(uv[1])))

    def _read(self, pane: str, view: str, x: int, y: int) -> None:
        """A click on any other picture: its readout in the status line."""
        from tuibrdf.render import pick

        res = self.frame
        if view == "extra":
            view = res.request.extra or ""
        pic = self.one(pane)
        if view == "albedo":
            text = pick.albedo_reading(res, ["".join(seg.text for seg in strip)
                                             for strip in pic._strips], x)
            if text is not None:
                self._changed(text)
            return
        got = pick.pick(res, view, PANES[pane][1], x, y, pic.size.width, pic.size.height)
        if got is None:
            return
        if all(built_in(s.material) for s in res.sides):
            self._changed(_reading(res, got))
        else:  # a user's kernel (it may never return) or measured data: off the event loop
            self.background(partial(_reading, res, got), partial(self._read_done, res))

    @survives
    def _read_done(self, res: FrameResult, text: str) -> None:
        """A readout computed off the event loop: shown while its frame still is."""
        if self.frame is res:
            self._changed(text)

    @survives
    def picture_dragged(self, pane: str, x: int, y: int, dx: int, dy: int) -> None:
        """A drag: on the lit sphere the light goes where the sphere's normal under the
        pointer points; on the lit plane right/left turns φi and up/down θi; on the 3D
        solid the camera orbits (azimuth, elevation), 3° a cell."""
        from tuibrdf.render import pick

        res, s = self.frame, self.state
        if res is None or pane not in PANES:
            return
        view = PANES[pane][0]
        if view == "extra" and s.view == "sphere" and res.request.extra_px is not None:
            self._changed(s.set_light(*pick.light_at(x, y, res.request.extra_px)))
        elif view == "extra" and s.view == "plane":
            self._changed(s.set_light(s.theta_i - 2.0 * dy, s.phi_i + 2.0 * dx))
        elif view == "solid":
            self._changed(s.rotate(-3.0 * dx, 3.0 * dy))

    @survives
    def picture_scrolled(self, pane: str, steps: int) -> None:
        """The wheel on the 3D solid or a section: zoom in (up) or out, ×1.25 a notch."""
        if PANES.get(pane, ("",))[0] in ("solid", "incidence", "perpendicular"):
            self._changed(self.state.zoom_by(1.25 ** steps))

    # -- actions -----------------------------------------------------------------------------
    @survives
    def action_state(self, method: str, args: tuple = ()) -> None:
        """A :class:`ViewerState` transition named in the key table."""
        message = getattr(self.state, method)(*args)
        self._changed(message, relayout=method in keys.RELAYOUT)

    @survives
    def action_interrupt(self) -> None:
        """ctrl+c: quit with exit status 130, as Ctrl-C ends the other commands."""
        self.exit(return_code=130)

    def _resumed(self, app=None) -> None:
        """Back from a suspension (SIGTSTP, then SIGCONT: ctrl+z and fg in a shell): the
        terminal's screen was left, so everything is painted again."""
        coalesce_resize_signals()  # (the driver installed its own handler again)
        self.screen.refresh(repaint=True)
        self.refresh(repaint=True, layout=True)

    @survives
    def action_help(self) -> None:
        from tuibrdf.app.screens import HelpScreen

        self.push_screen(HelpScreen())

    @survives
    def action_checks(self) -> None:
        """F: the checks of the active side's model (off the event loop), then the report."""
        from tuibrdf.app.checks import check_work

        material, look = self.state.side.material, self.look
        self._changed(f"checking {material.label} …")
        self.background(partial(check_work, material, self.state.theta_i, self.state.phi_i,
                                look.cmap, look.color), self._checked)

    @survives
    def _checked(self, result) -> None:
        if isinstance(result, str):  # why the checks could not run
            self._changed(result)
            return
        from tuibrdf.app.screens import ReportScreen

        self._changed("checks done (F or Esc closes the report)")
        self.push_screen(ReportScreen(result))

    @survives
    def action_type_value(self) -> None:
        """Enter or =: type the selected parameter's value (a filtered list for choices)."""
        from tuibrdf.app.screens import ValueScreen

        s = self.state
        if (why := s.no_params()) is not None:
            self._changed(why)
            return
        row = s.row
        p = row.param
        current = fmt_number(s.row_value(row))
        prompt = f"{s.side.spec.title} {row.label} ({p.doc or p.name})\n" \
                 f"now {current}; {p.range_text()}"
        if p.kind == "choice":
            prompt += "\ntype to filter, ↑/↓, Enter applies, Esc cancels"
        else:
            prompt += "\nEnter applies, Esc cancels"
        self.push_screen(ValueScreen(prompt, current, s.type_value, p.choices),
                         partial(self._typed, row.label))

    @survives
    def action_type_theta(self) -> None:
        from tuibrdf.app.screens import ValueScreen

        s = self.state
        prompt = f"θi (angle of incidence, degrees)\nnow {s.theta_i:g}°; in [0, 90]°" \
                 "\nEnter applies, Esc cancels"
        self.push_screen(ValueScreen(prompt, f"{s.theta_i:g}", s.type_theta),
                         partial(self._typed, "θi"))

    @survives
    def _typed(self, label: str, text: str | None) -> None:
        self._changed(f"{label} = {text}" if text is not None else f"{label} unchanged",
                      relayout=True)

    def background(self, work, done) -> None:
        """``done(work())`` on the event loop, ``work`` in a daemon thread: disk I/O (presets,
        data files) never blocks a key, and a read stuck on a slow disk or a FIFO does not keep
        the process alive after q (a pool thread would: Python joins those at exit).  In sync
        mode (tests) both run here."""
        if self.sync:
            done(work())
            return

        def run() -> None:
            try:
                result = work()
            except Exception as e:  # (else Python would print it over the screen)
                call, args = self.report_error, (e, "background")
            else:
                call, args = done, (result,)
            try:
                self.call_from_thread(call, *args)
            except RuntimeError:  # the app has closed meanwhile
                pass

        threading.Thread(target=run, name="tuibrdf-io", daemon=True).start()

    @survives
    def action_save(self) -> None:
        from tuibrdf.app.screens import SaveScreen

        state = self.state

        def write(name: str) -> str:
            try:
                path = save_preset(state, name)
                return f"saved {path}" + save_bparams(state, path)
            except (PresetError, OSError) as e:
                return f"not saved: {e}"

        def done(name: str | None) -> None:
            if not name:
                self._changed("save cancelled")
                return
            self._changed(f"saving preset {name} …")
            self.background(partial(write, name), self._saved)

        self.push_screen(SaveScreen(_name_refused), done)

    @survives
    def _saved(self, message: str) -> None:
        self._changed(message)
        self.background(_list_presets, self._listed)

    @survives
    def _listed(self, names: list[str]) -> None:
        self._preset_names = names

    def _named_code(self) -> list[str]:
        """The Python model files the user named this session (on the command line, or shown
        since): a preset may load those; any other would run code nobody named."""
        s = self.state
        return [m for m in [*s.files, *(x.model for x in s.sides)] if runs_code(m)]

    @survives
    def action_load_next(self) -> None:
        """P: the next saved preset, skipping those that would run a Python file the user
        did not name (with a message saying so)."""
        loaded, allowed = self._loaded, self._named_code()

        def work() -> tuple[str, object, str]:
            names = _list_presets()
            if not names:
                return "", f"no saved presets in {preset_dir()} (s saves one)", ""
            i = names.index(loaded) if loaded in names else -1
            skipped = []
            for k in range(1, len(names) + 1):
                name = names[(i + k) % len(names)]
                got = _read_preset(name, allowed)
                if not isinstance(got, PresetRunsCode):
                    break
                skipped.append(name)
            else:
                return "", (f"skipped {', '.join(skipped)}: each would run a Python file you "
                            "did not name (tuibrdf view --preset NAME --trust loads one)"), ""
            note = (f"; skipped {', '.join(skipped)}: would run a Python file you did not "
                    "name (tuibrdf view --preset NAME --trust)") if skipped else ""
            return name, got, note

        self.background(work, self._show_loaded)

    @survives
    def load_and_show(self, name: str) -> None:
        allowed = self._named_code()
        self.background(lambda: (name, _read_preset(name, allowed), ""), self._show_loaded)

    @survives
    def _show_loaded(self, result: tuple[str, object, str]) -> None:
        name, got, note = result
        if not isinstance(got, tuple):  # why it cannot be loaded
            self._changed(str(got) + note)
            return
        apply_loaded(self.state, *got)
        self._loaded = name
        self._changed(f"loaded preset {name}{note}", relayout=True)

    def load(self, name: str) -> str | None:
        """Load a saved preset into the viewer now; a message if it cannot be."""
        got = _read_preset(name, self._named_code())
        if not isinstance(got, tuple):
            return str(got)
        apply_loaded(self.state, *got)
        return None

    @survives
    def action_command_palette(self) -> None:
        if self.use_command_palette and not SafeCommandPalette.is_open(self):
            self.push_screen(SafeCommandPalette(id="--command-palette"))

    def get_system_commands(self, screen):
        yield from super().get_system_commands(screen)
        for name in self._preset_names:  # listed off the event loop (on mount, on save)
            yield SystemCommand(f"Load preset {name}", f"{preset_dir() / name}.toml",
                                partial(self.load_and_show, name))
        for k in keys.palette_keys():
            yield SystemCommand(k.help, f"key: {k.shown}", partial(self.run_action, k.action))
