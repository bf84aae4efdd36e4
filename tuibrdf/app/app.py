"""The Textual viewer: keys call :class:`ViewerState` transitions; panes show
:mod:`.scene` renderables.

Responsiveness: a key updates the state, the parameter panel and the status line at once; the
heavy panes (maps, plots) are marked dirty and rebuilt by one coalesced callback that runs after
the keys already queued, so at most one rebuild per frame and the latest state wins.  A rebuild
waits while Textual's output writer still has frames queued (a slow terminal), so a held key
never leaves a backlog of stale pictures.  Only visible panes are computed.
"""

from __future__ import annotations

from functools import partial

from rich.text import Text
from textual.app import App, ComposeResult, SystemCommand
from textual.binding import Binding
from textual.containers import Container, Horizontal, Vertical, VerticalScroll
from textual.screen import ModalScreen
from textual.widgets import Footer, Input, Static

from ..core import merl
from ..core.models import MODELS
from ..render import views
from . import scene
from .presets import PresetError, apply_loaded, list_presets, load_preset, preset_dir, save_preset
from .state import COMPARE_PRESETS, VIEW_TITLES, Side, ViewerState, panel_rows
from .widgets import ParamPanel, Picture, StatusLine

MIN_W, MIN_H = 60, 18
BOTH_PANELS_H = 40  # compare mode shows both parameter panels from this height
RETRY_S = 0.02  # re-check a busy writer after this long
#: what a pane or a worker shows as a message instead of stopping the viewer: bad data
#: (ValueError, OSError) and a floating-point exception from a kernel (the kernels raise on
#: one, core/numerics.py; the stability suite has never seen one, but a picture is not worth
#: losing the session over)
DRAW_ERRORS = (ValueError, OSError, ArithmeticError)
STEADY_PANEL_H = max(len(panel_rows(m)) for m in MODELS.values()) + 2  # rows + border

B = Binding
BINDINGS = [
    B("left", "theta(-1)", "θi−", key_display="←"),
    B("right", "theta(1)", "θi+", key_display="→"),
    B("shift+left", "theta(-10)", "θi −10°", show=False),
    B("shift+right", "theta(10)", "θi +10°", show=False),
    B("up", "select(-1)", "param ↑", show=False),
    B("down", "select(1)", "param ↓", show=False),
    B("plus,equals_sign,right_square_bracket", "step(1)", "inc", key_display="+"),
    B("minus,left_square_bracket", "step(-1)", "dec", key_display="-"),
    B("right_curly_bracket", "step(1, True)", "+coarse", show=False, key_display="}"),
    B("left_curly_bracket,underscore", "step(-1, True)", "−coarse", show=False,
      key_display="{"),
    B("r", "reset", "reset", show=False),
    B("m", "model(1)", "model"),
    B("M", "model(-1)", "prev model", show=False),
    B("v", "view", "view"),
    B("ctrl+left", "rotate(-10, 0)", "rotate ←", show=False),
    B("ctrl+right", "rotate(10, 0)", "rotate →", show=False),
    B("ctrl+up", "rotate(0, 5)", "tilt ↑", show=False),
    B("ctrl+down", "rotate(0, -5)", "tilt ↓", show=False),
    B("l", "log", "log", show=False),
    B("k", "cmap", "cmap", show=False),
    B("o", "cosine", "f·cos", show=False),
    B("c", "compare", "compare"),
    B("tab", "side", "side", priority=True, show=False),
    B("p", "preset", "preset"),
    B("s", "save", "save", show=False),
    B("P", "load_next", "load preset", show=False),
    B("question_mark", "help", "help", key_display="?"),
    B("q", "quit", "quit"),
]

CSS = """
Screen { layout: vertical; }
#root { height: 1fr; }
#body { height: 1fr; }
#main { width: 55%; height: 1fr; }
#main.compare-map { layout: grid; grid-size: 2 2; }
#main.compare-solid { layout: horizontal; }
#side { width: 1fr; height: 1fr; }
#side Picture { height: 1fr; }
Picture { border-title-color: $text-muted; }
#main Picture { border: none; }
#main.compare-map Picture, #main.compare-solid Picture { border: round $primary-darken-3; }
#legend { padding: 0 1; }
#toosmall { width: 1fr; height: 1fr; content-align: center middle; display: none; }
Screen.small #toosmall { display: block; }
Screen.small #root { display: none; }
"""


class HelpScreen(ModalScreen):
    """Every key, from the same table the footer uses."""

    BINDINGS = [B("escape,question_mark,q", "dismiss", "close")]
    DEFAULT_CSS = """
    HelpScreen { align: center middle; }
    HelpScreen > VerticalScroll { width: 64; max-height: 90%; border: round $accent;
                                  background: $surface; padding: 0 1; height: auto; }
    """

    def compose(self) -> ComposeResult:
        t = Text("tuibrdf — keys\n\n", style="bold")
        for b in BINDINGS:
            keys = b.key_display or b.key
            if "," in b.key and not b.key_display:
                keys = b.key.split(",")[0]
            t.append(f"{keys:<12}", style="bold")
            t.append(f"{HELP.get(b.action, b.description)}\n")
        t.append("\nEsc or ? closes this screen; ctrl+p opens the command palette.", style="dim")
        with VerticalScroll():
            yield Static(t)


HELP = {
    "theta(-1)": "θi −1°  (shift+← −10°)", "theta(1)": "θi +1°  (shift+→ +10°)",
    "theta(-10)": "θi −10°", "theta(10)": "θi +10°",
    "select(-1)": "previous parameter", "select(1)": "next parameter",
    "step(1)": "selected parameter + step (also = and ])",
    "step(-1)": "selected parameter − step (also [)",
    "step(1, True)": "selected parameter + coarse step", "step(-1, True)":
        "selected parameter − coarse step (also _)",
    "reset": "reset the selected parameter", "model(1)": "next model (θi kept)",
    "model(-1)": "previous model", "view": "main view: map → 3D solid → albedo curve",
    "rotate(-10, 0)": "3D solid: turn left", "rotate(10, 0)": "3D solid: turn right",
    "rotate(0, 5)": "3D solid: tilt up", "rotate(0, -5)": "3D solid: tilt down",
    "log": "linear / log colour scale", "cmap": "next colour map",
    "cosine": "show f or f·cos θr", "compare": "compare two models (B starts as A)",
    "side": "compare: keys act on A or B", "preset": "next seed comparison (diffuse, specular)",
    "save": "save θi and parameters as a preset (TOML file)",
    "load_next": "load the next saved preset (also: tuibrdf view --preset NAME)",
    "help": "this screen", "quit": "quit",
}


class SaveScreen(ModalScreen[str | None]):
    BINDINGS = [B("escape", "dismiss(None)", "cancel")]
    DEFAULT_CSS = """
    SaveScreen { align: center middle; }
    SaveScreen > Vertical { width: 50; height: auto; border: round $accent; background: $surface;
                            padding: 0 1; }
    """

    def compose(self) -> ComposeResult:
        with Vertical():
            yield Static("Save preset as (Enter saves, Esc cancels):")
            yield Input(placeholder="name", id="name")

    def on_input_submitted(self, event: Input.Submitted) -> None:
        self.dismiss(event.value.strip() or None)


def side_files(side: Side) -> list[str]:
    """The data files (``path`` parameters, i.e. MERL files) a side needs in memory."""
    return [str(side.values[p.name]) for p in side.spec.params
            if p.kind == "path" and side.values.get(p.name)]


class BrdfApp(App):
    """``BrdfApp(state, color=None)``; ``color`` ∈ truecolor/256/none overrides detection."""

    CSS = CSS
    BINDINGS = BINDINGS
    TITLE = "tuibrdf"

    def __init__(self, state: ViewerState | None = None, *, color: str | None = None,
                 message: str = "", sync_stats: bool = False) -> None:
        super().__init__()
        self.sync_stats = sync_stats  # tests: albedo and peak on the loop (deterministic)
        self.state = state or ViewerState()
        self.state.cmaps = scene.CMAPS
        if self.state.cmap not in self.state.cmaps:
            self.state.cmap = self.state.cmaps[0]
        self._color = color
        self.message = message
        self._dirty = False
        self._scheduled = False
        self._stats_running = False
        self.rebuilds = 0  # how many heavy rebuilds ran (tests, benchmarks)
        self._loading: dict[str, float] = {}  # measured-data file → fraction read so far
        self._curves_running = False
        self._loaded = ""  # the saved preset `P` loaded last

    # -- layout ------------------------------------------------------------------------------
    def compose(self) -> ComposeResult:
        with Vertical(id="root"):
            with Horizontal(id="body"):
                with Container(id="main"):
                    for pane in ("map-a", "map-b", "diff", "solid-a", "solid-b", "albedo"):
                        yield Picture(pane, id=pane)
                    yield Static(id="legend")
                with Vertical(id="side"):
                    yield ParamPanel(id="panel-a")
                    yield ParamPanel(id="panel-b")
                    yield Picture("incidence", id="incidence")
                    yield Picture("perpendicular", id="perpendicular")
            yield StatusLine(id="status")
        yield Static(id="toosmall")
        yield Footer(compact=True, show_command_palette=False)

    def on_mount(self) -> None:
        self._layout()
        self._changed()

    def on_resize(self, event) -> None:
        self._layout()
        self._changed()

    @property
    def look(self) -> scene.Look:
        s = self.state
        return scene.Look(self.color_system(), s.cmap, s.log, s.cosine)

    def color_system(self) -> str:
        if self._color:
            return self._color
        if self.no_color:
            return "none"
        cs = self.console.color_system
        return "truecolor" if cs == "truecolor" else ("none" if cs is None else "256")

    def visible_panes(self) -> list[str]:
        s = self.state
        if s.compare:
            main = {"map": ["map-a", "map-b", "diff"], "solid": ["solid-a", "solid-b"],
                    "albedo": ["albedo"]}[s.view]
        else:
            main = {"map": ["map-a"], "solid": ["solid-a"], "albedo": ["albedo"]}[s.view]
        return main + ["incidence", "perpendicular"]

    def _layout(self) -> None:
        """Show the panes of the current mode; the too-small message below the minimum."""
        w, h = self.size
        self.screen.set_class(w < MIN_W or h < MIN_H, "small")
        self.query_one("#toosmall", Static).update(
            f"The terminal is {w}×{h}: tuibrdf needs at least {MIN_W}×{MIN_H}.\n"
            "Enlarge the window (q quits).")
        s = self.state
        visible = set(self.visible_panes())
        main = self.query_one("#main")
        main.set_class(s.compare and s.view == "map", "compare-map")
        main.set_class(s.compare and s.view == "solid", "compare-solid")
        for pic in self.query(Picture):
            pic.display = pic.pane in visible
        self.query_one("#legend").display = s.compare and s.view == "map"
        # both panels when there is room; otherwise only the side the keys act on
        both = s.compare and h >= BOTH_PANELS_H
        self.query_one("#panel-a").display = not s.compare or both or s.active == 0
        self.query_one("#panel-b").display = both or (s.compare and s.active == 1)
        # tall terminals: panels as tall as the longest model's, so cycling models never
        # resizes the plots below (a steady picture, and no whole-screen re-layout on `m`);
        # short ones keep every row for the plots
        steady = STEADY_PANEL_H if h >= BOTH_PANELS_H else None
        for panel in self.query(ParamPanel):
            panel.styles.min_height = steady
        if s.compare:
            self.query_one("#map-a").border_title = f"A: {s.sides[0].model}"
            self.query_one("#map-b").border_title = f"B: {s.sides[1].model}"
            self.query_one("#diff").border_title = "A − B"
            self.query_one("#solid-a").border_title = f"A: {s.sides[0].model}"
            self.query_one("#solid-b").border_title = f"B: {s.sides[1].model}"

    # -- updates ---------------------------------------------------------------------------
    def _changed(self, message: str | None = None, relayout: bool = False) -> None:
        """Cheap parts now; heavy panes marked dirty and rebuilt once, later."""
        self.message = message or ""
        if relayout:
            self._layout()
        for i, panel in enumerate(self.query(ParamPanel)):
            if i < len(self.state.sides):
                panel.show(self.state, i)
        self._status()
        self.request_rebuild()

    def request_rebuild(self) -> None:
        """Mark the heavy panes dirty; one coalesced rebuild runs after the queued events."""
        self._dirty = True
        if not self._scheduled:
            self._scheduled = True
            self.call_later(self._rebuild)

    def _writer_busy(self) -> bool:
        """Frames still queued for the terminal (Textual's private writer; guarded)."""
        try:
            return self._driver._writer_thread._queue.qsize() > 0  # type: ignore[union-attr]
        except AttributeError:
            return False

    def _rebuild(self) -> None:
        if not self._dirty:
            self._scheduled = False
            return
        if self._writer_busy():  # trailing edge: try again when the terminal has caught up
            self.set_timer(RETRY_S, self._rebuild)
            return
        self._scheduled = False
        self._dirty = False
        if self.screen.has_class("small"):
            return
        panes = self.visible_panes()
        if not self._files_ready():  # measured data still loading: its panes say so
            for pane in panes:
                pic = self.query_one(f"#{pane}", Picture)
                pic.show(Text("loading measured data …", justify="center"), None)
            return
        self.rebuilds += 1
        main, plots = panes[:-2], panes[-2:]
        for pane in main:
            self._draw(pane)
        if self.state.compare:
            self.query_one("#legend", Static).update(self._legend())
        # the cross-sections (plotext, ≈ 8 ms each at 160×48) go out one frame later, so the
        # main view's frame is not held back by them
        self.call_after_refresh(self._draw_later, plots)

    def _draw_later(self, panes: list[str]) -> None:
        if self._writer_busy():
            self.set_timer(RETRY_S, lambda: self._draw_later(panes))
            return
        visible = self.visible_panes()
        for pane in panes:
            if pane in visible and not self.screen.has_class("small"):
                self._draw(pane)

    def _draw(self, pane: str) -> None:
        s, look = self.state, self.look
        pic = self.query_one(f"#{pane}", Picture)
        w, h = pic.size.width, pic.size.height
        if w < views.MIN_WIDTH or h < views.MIN_HEIGHT:
            pic.show(Text(f"{w}×{h}: too small for this pane"), None)
            return
        t, sides = s.theta_i, s.sides
        key = (pane, w, h, look, t, tuple(x.key() for x in sides), s.azimuth, s.elevation)
        if pic.shown_for == key:
            return
        try:
            r = self._renderable(pane, w, h)
        except DRAW_ERRORS as e:  # e.g. a data file that changed on disk
            pic.show(Text(f"cannot draw {pane}: {e}"), None)
            return
        if r is None:  # computed in a worker, which asks for a redraw when done
            pic.show(Text("computing a(θi) over 0–90° …", justify="center"), None)
            return
        pic.show(r, key)

    def _renderable(self, pane: str, w: int, h: int):
        s, look = self.state, self.look
        t, sides = s.theta_i, s.sides
        k = 1 if pane.endswith("-b") else 0
        if pane in ("map-a", "map-b"):
            r = scene.compare_map(sides, k, t, w, h, look) if s.compare else \
                scene.view_pane("map", sides[0], t, w, h, look)
        elif pane == "diff":
            r = scene.diff_map(sides, t, w, h, look)
        elif pane in ("solid-a", "solid-b"):
            r = scene.view_pane("solid", sides[k], t, w, h, look, s.azimuth, s.elevation)
        elif pane == "albedo":
            if not self.sync_stats and not all(scene.albedo_curve_ready(x) for x in sides):
                self._compute_curves()
                return None  # drawn when the worker is done
            r = scene.albedo_pane(sides, t, w, h, look)
        elif s.compare:
            r = scene.compare_section(sides, t, pane, w, h, look)
        else:
            r = scene.view_pane(pane, sides[0], t, w, h, look)
        return r

    def _legend(self) -> Text:
        s = self.state
        t = Text()
        for i, side in enumerate(s.sides):
            t.append(f"{'AB'[i]}: ", style="bold")
            t.append(s.describe(side) + "\n")
        t.append("A and B share one colour scale.\n", style="dim")
        if s.preset:
            title = next(p.title for p in COMPARE_PRESETS if p.name == s.preset)
            t.append(f"preset {title}\n", style="dim")
        t.append("tab: keys act on the other side", style="dim")
        return t

    def _stats_wanted(self) -> list[tuple]:
        s = self.state
        return [(side, s.theta_i, s.cosine) for side in s.sides]

    def _compute_stats(self) -> None:
        """Albedo and peak of every side (cached), off the event loop; then the status line."""
        wanted = self._stats_wanted()
        try:
            for side, t, cos in wanted:
                scene.stats(side, t, cos)
        except DRAW_ERRORS as e:  # a data file that vanished or changed on disk
            self.call_from_thread(self._do, f"no albedo: {e}")
            return
        self.call_from_thread(self._status)

    def _compute_curves(self) -> None:
        """The albedo curves of the sides (0.01–0.6 s each) in a worker; then a redraw.  (The
        tests' ``sync_stats`` draws them on the loop instead, deterministically.)"""
        if self._curves_running:
            return
        self._curves_running = True
        sides = list(self.state.sides)

        def work() -> None:
            try:
                for side in sides:
                    scene.albedo_curve(side)
            except DRAW_ERRORS as e:
                self.call_from_thread(self._do, f"no albedo curve: {e}")
            finally:
                self._curves_running = False
            self.call_from_thread(self.request_rebuild)

        self.run_worker(work, thread=True, group="curves", exit_on_error=False)

    # -- measured data: read off the event loop, progress on the status line ---------------
    def _files_ready(self) -> bool:
        """Whether every side's data file is in memory; starts a loader for each missing one
        (a worker thread: the 35 MB read never blocks a key) and answers False meanwhile."""
        ready = True
        for side in self.state.sides:
            for path in side_files(side):
                try:
                    if merl.is_loaded(path):
                        continue
                except merl.MerlError as e:
                    self._load_failed(path, str(e))
                    return False
                ready = False
                if path not in self._loading:
                    self._loading[path] = 0.0
                    self.run_worker(partial(self._load_file, path), thread=True,
                                    group="load", exit_on_error=False)
        return ready

    def _load_file(self, path: str) -> None:
        def progress(fraction: float) -> None:
            self.call_from_thread(self._load_progress, path, fraction)

        try:
            merl.load_cached(path, progress)
        except (merl.MerlError, OSError) as e:
            self.call_from_thread(self._load_failed, path, str(e))
            return
        self.call_from_thread(self._load_done, path)

    def _load_progress(self, path: str, fraction: float) -> None:
        if path in self._loading:
            self._loading[path] = fraction
            self._status()

    def _load_done(self, path: str) -> None:
        self._loading.pop(path, None)
        self._changed(f"loaded {path}")

    def _load_failed(self, path: str, error: str) -> None:
        """A side whose file cannot be read shows Lambert instead; the message says why."""
        self._loading.pop(path, None)
        s = self.state
        s.sides = [Side.of("lambert") if path in side_files(x) else x for x in s.sides]
        self._changed(f"{error} — showing lambert", relayout=True)

    def _status(self) -> None:
        s = self.state
        line = Text()
        line.append(f"θi {s.theta_i:g}°", style="bold")
        ready = self._files_ready()  # no stats from a file still being read
        pending = False
        for i, side in enumerate(s.sides):
            tag = f"  {'AB'[i]}:" if s.compare else " "
            files = [f for f in side_files(side) if f in self._loading]
            if files:
                line.append(f"{tag} loading {files[0]} {self._loading[files[0]]:.0%}",
                            style="bold yellow")
                continue
            if scene.stats_key(side, s.theta_i, s.cosine) not in scene.STATS:
                line.append(f"{tag} a(θi) …")
                pending = True
                continue
            st = scene.stats(side, s.theta_i, s.cosine)
            alb = st.albedo
            alb_txt = f"{alb:.3f}" if isinstance(alb, float) else \
                "(" + ",".join(f"{a:.3f}" for a in alb) + ")"
            line.append(f"{tag} a={alb_txt}" if s.compare else f"{tag} a(θi)={alb_txt}")
            if st.albedo_max > 1.0 + 1e-9:
                line.append(" >1 NOT energy-conserving", style="bold red")
            what = "f·cos" if s.cosine else "peak"
            th, ph = round(st.peak_theta), round(st.peak_phi)  # ints: never "-0°"
            where = f"({th}°,{ph}°)" if s.compare else f"at θ={th}° φ={ph}°"
            line.append(f"  {what} {st.peak:.3g} {where}")
        second = Text()
        scale = "log (3 decades)" if s.log else "linear"
        second.append(f"{VIEW_TITLES[s.view]} · {scale} · {s.cmap}"
                      f"{' · f·cos θr' if s.cosine else ''}", style="dim")
        if s.compare:
            second.append(f" · keys → {'AB'[s.active]}", style="bold")
        if self.message:
            second.append(f"  {self.message}", style="bold yellow")
        self.query_one("#status", StatusLine).update(Text("\n").join([line, second]))
        if pending and not ready:
            return  # the stats start when the data is in memory (_load_done)
        if pending and self.sync_stats:
            for side, t, cos in self._stats_wanted():
                scene.stats(side, t, cos)
            self._status()
        elif pending and not self._stats_running:
            self._stats_running = True
            self.run_worker(self._stats_thread, thread=True, exclusive=True, group="stats")

    def _stats_thread(self) -> None:
        try:
            self._compute_stats()
        finally:
            self._stats_running = False

    # -- actions ---------------------------------------------------------------------------
    def _do(self, result: str | None, relayout: bool = False) -> None:
        self._changed(result, relayout)

    def action_theta(self, delta: float) -> None:
        self._do(self.state.step_theta(delta))

    def action_select(self, delta: int) -> None:
        self._do(self.state.select(delta))

    def action_step(self, direction: int, coarse: bool = False) -> None:
        self._do(self.state.step_param(direction, coarse))

    def action_reset(self) -> None:
        self._do(self.state.reset_param())

    def action_model(self, delta: int) -> None:
        self._do(self.state.cycle_model(delta), relayout=True)

    def action_view(self) -> None:
        self._do(self.state.cycle_view(), relayout=True)

    def action_rotate(self, d_az: float, d_el: float) -> None:
        if self.state.view != "solid":
            self._do("ctrl+arrows rotate the 3D solid (press v for that view)")
            return
        self._do(self.state.rotate(d_az, d_el))

    def action_log(self) -> None:
        self._do(self.state.toggle_log())

    def action_cmap(self) -> None:
        self._do(self.state.cycle_cmap())

    def action_cosine(self) -> None:
        self._do(self.state.toggle_cosine())

    def action_compare(self) -> None:
        self._do(self.state.toggle_compare(), relayout=True)

    def action_side(self) -> None:
        self._do(self.state.switch_side(), relayout=True)

    def action_preset(self) -> None:
        self._do(self.state.next_preset(), relayout=True)

    def action_help(self) -> None:
        self.push_screen(HelpScreen())

    def action_save(self) -> None:
        def done(name: str | None) -> None:
            if not name:
                self._do("save cancelled")
                return
            try:
                path = save_preset(self.state, name)
            except (PresetError, OSError) as e:
                self._do(f"not saved: {e}")
                return
            self._do(f"saved {path}")

        self.push_screen(SaveScreen(), done)

    def action_load_next(self) -> None:
        names = list_presets()
        if not names:
            self._do(f"no saved presets in {preset_dir()} (s saves one)")
            return
        i = names.index(self._loaded) if self._loaded in names else -1
        self.load_and_show(names[(i + 1) % len(names)])

    def load_and_show(self, name: str) -> None:
        msg = self.load(name)
        if msg is None:
            self._loaded = name
        self._do(msg or f"loaded preset {name}", relayout=True)

    def load(self, name: str) -> str | None:
        """Load a saved preset into the viewer; a message if it cannot be."""
        try:
            theta, sides = load_preset(name)
        except PresetError as e:
            return str(e)
        apply_loaded(self.state, theta, sides)
        return None

    def get_system_commands(self, screen):
        yield from super().get_system_commands(screen)
        for name in list_presets():
            yield SystemCommand(f"Load preset {name}", f"{preset_dir() / name}.toml",
                                partial(self.load_and_show, name))
        for b in BINDINGS:
            if b.action in ("help", "quit"):
                continue
            yield SystemCommand(HELP.get(b.action, b.description),
                                f"key: {b.key_display or b.key.split(',')[0]}",
                                partial(self.run_action, b.action))
