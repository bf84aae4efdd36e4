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

from . import scene
from .presets import PresetError, apply_loaded, load_preset, save_preset
from .state import COMPARE_PRESETS, VIEW_TITLES, ViewerState
from .widgets import ParamPanel, Picture, StatusLine

MIN_W, MIN_H = 60, 18
RETRY_S = 0.02  # re-check a busy writer after this long

B = Binding
BINDINGS = [
    B("left", "theta(-1)", "θi−", key_display="←"),
    B("right", "theta(1)", "θi+", key_display="→"),
    B("shift+left", "theta(-10)", "θi −10°", show=False),
    B("shift+right", "theta(10)", "θi +10°", show=False),
    B("up", "select(-1)", "param ↑", show=False),
    B("down", "select(1)", "param ↓", show=False),
    B("plus,equals_sign,right_square_bracket", "step(1)", "param+", key_display="+"),
    B("minus,left_square_bracket", "step(-1)", "param−", key_display="-"),
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
#side Picture { height: 1fr; border: round $primary-darken-3; }
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
    "save": "save θi and parameters as a preset (load: tuibrdf --preset NAME)",
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


class BrdfApp(App):
    """``BrdfApp(state, color=None)``; ``color`` ∈ truecolor/256/none overrides detection."""

    CSS = CSS
    BINDINGS = BINDINGS
    TITLE = "tuibrdf"

    def __init__(self, state: ViewerState | None = None, *, color: str | None = None,
                 message: str = "") -> None:
        super().__init__()
        self.state = state or ViewerState()
        self.state.cmaps = scene.CMAPS
        if self.state.cmap not in self.state.cmaps:
            self.state.cmap = self.state.cmaps[0]
        self._color = color
        self.message = message
        self._dirty = False
        self._scheduled = False
        self.rebuilds = 0  # how many heavy rebuilds ran (tests, benchmarks)

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
        yield Footer(compact=True)

    def on_mount(self) -> None:
        self.query_one("#incidence").border_title = "plane of incidence"
        self.query_one("#perpendicular").border_title = "perpendicular plane"
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
        self.query_one("#panel-b").display = s.compare
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
        self._status(cached_only=True)
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
        self.rebuilds += 1
        for pane in self.visible_panes():
            self._draw(pane)
        self._status(cached_only=False)

    def _draw(self, pane: str) -> None:
        s, look = self.state, self.look
        pic = self.query_one(f"#{pane}", Picture)
        w, h = pic.size.width, pic.size.height
        if w < 2 or h < 1:
            return
        t = s.theta_i
        sides = s.sides
        key = (pane, w, h, look, t, tuple(x.key() for x in sides), s.azimuth, s.elevation)
        if pic.shown_for == key:
            return
        if pane in ("map-a", "map-b"):
            side = sides[0 if pane == "map-a" else 1]
            vmax = scene.compare_vmax(sides, t, w, h, look) if s.compare else None
            r, vmax = scene.map_pane(side, t, w, h, look, vmax)
            self._vmax = vmax
        elif pane == "diff":
            r, m = scene.diff_pane(sides[0], sides[1], t, w, h, look)
            self.query_one("#legend", Static).update(self._legend(m))
        elif pane in ("solid-a", "solid-b"):
            side = sides[0 if pane == "solid-a" else 1]
            r = scene.solid_pane(side, t, w, h, look, s.azimuth, s.elevation)
        elif pane == "albedo":
            r = scene.albedo_pane(sides, t, w, h, look)
        else:
            r = scene.polar_pane(sides, t, pane, w, h, look)
        pic.show(r, key)

    def _legend(self, diff_max: float) -> Text:
        s = self.state
        t = Text()
        for i, side in enumerate(s.sides):
            t.append(f"{'AB'[i]}: ", style="bold " + scene.SIDE_COLORS[i])
            t.append(s.describe(side) + "\n")
        t.append(f"A and B share one colour scale\nA − B: max |Δ| = {diff_max:.3g} sr⁻¹\n"
                 "(red A > B, blue A < B)\n", style="")
        if s.preset:
            title = next(p.title for p in COMPARE_PRESETS if p.name == s.preset)
            t.append(f"preset {title}", style="dim")
        return t

    def _status(self, cached_only: bool) -> None:
        s = self.state
        line = Text()
        line.append(f"θi {s.theta_i:g}°", style="bold")
        for i, side in enumerate(s.sides):
            key = (side.key(), s.theta_i, s.cosine)
            if cached_only and key not in scene._stats_cache.data:
                line.append("  a(θi) …")
                continue
            st = scene.stats(side, s.theta_i, s.cosine)
            tag = f"  {'AB'[i]}" if s.compare else " "
            alb = st.albedo
            alb_txt = f"{alb:.3f}" if isinstance(alb, float) else \
                "(" + ", ".join(f"{a:.3f}" for a in alb) + ")"
            line.append(f"{tag} a(θi)={alb_txt}")
            if st.albedo_max > 1.0 + 1e-9:
                line.append(" >1 not energy-conserving", style="bold red")
            what = "f·cos" if s.cosine else "peak"
            line.append(f"  {what} {st.peak:.3g} at θ={st.peak_theta:.0f}° φ={st.peak_phi:.0f}°")
        second = Text()
        second.append(f"{VIEW_TITLES[s.view]} · {'log' if s.log else 'linear'} · {s.cmap}"
                      f"{' · f·cos θr' if s.cosine else ''}  ", style="dim")
        vmax = getattr(self, "_vmax", None)
        if vmax is not None and s.view == "map":
            second.append_text(scene.colorbar(self.look, vmax, 12))
        if self.message:
            second.append(f"  {self.message}", style="bold yellow")
        self.query_one("#status", StatusLine).update(Text("\n").join([line, second]))

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
        self._do(self.state.switch_side())

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
        for b in BINDINGS:
            if b.action in ("help", "quit"):
                continue
            yield SystemCommand(HELP.get(b.action, b.description),
                                f"key: {b.key_display or b.key.split(',')[0]}",
                                partial(self.run_action, b.action))
