"""The Textual viewer: wiring only.  A key calls one :class:`ViewerState` transition (plain
Python, :mod:`.state`); the panes show one :class:`~tuibrdf.core.scene.FrameResult` through
:mod:`tuibrdf.render.panes`.

Data flow: every change builds the current :class:`~tuibrdf.core.scene.FrameRequest`
(materials, θi, cosine, view, pane sizes).  A request computed before is shown at once (the
core caches results by request); otherwise :meth:`BrdfApp.compute` runs in an exclusive
thread worker (``@work(exclusive=True, thread=True)``): the newest request cancels the older
ones, and a result that is no longer the current request is dropped, so the latest state
always wins and its frame always arrives.  The worker posts the fast part (maps, sections,
peak) at once and the slow part (albedo, albedo curve) when done.  A frame waits while
Textual's output writer still has frames queued (a slow terminal), and each pane is redrawn
only when what it shows changed.
"""

from __future__ import annotations

from functools import partial

from rich.text import Text
from textual import work
from textual.app import App, ComposeResult, SystemCommand
from textual.containers import Container, Horizontal, Vertical
from textual.css.query import NoMatches
from textual.widgets import Footer, Static
from textual.worker import Worker, get_current_worker

from ..core import merl, scene
from ..core.models import MODELS
from ..core.scene import FrameRequest, FrameResult
from ..render import MIN_HEIGHT, MIN_WIDTH, VIEW_TITLES, panes
from ..render.views import map_pixels
from . import keys
from .presets import PresetError, apply_loaded, list_presets, load_preset, preset_dir, save_preset
from .screens import HelpScreen, SafeCommandPalette, SaveScreen
from .state import COMPARE_PRESETS, Side, ViewerState, panel_rows
from .widgets import ParamPanel, Picture, StatusLine

MIN_W, MIN_H = 60, 18
BOTH_PANELS_H = 40  # compare mode shows both parameter panels from this height
RETRY_S = 0.02  # re-check a busy writer after this long
#: colour levels of the maps: 32 keeps a full 160×48 map update near 50 KiB (docs/app.md)
LEVELS = 32
#: what a pane or a worker shows as a message instead of stopping the viewer: bad data
#: (ValueError, OSError) and a floating-point exception from a kernel (the kernels raise on
#: one, core/numerics.py; a picture is not worth losing the session over)
DRAW_ERRORS = (ValueError, OSError, ArithmeticError)
STEADY_PANEL_H = max(len(panel_rows(m)) for m in MODELS.values()) + 2  # rows + border
#: the actions of the viewer itself (not of a modal screen)
VIEWER_ACTIONS = frozenset({"state", "save", "load_next", "help"})
#: pane → (view, side)
PANES = {"map-a": ("map", 0), "map-b": ("map", 1), "diff": ("diff", 0), "solid-a": ("solid", 0),
         "solid-b": ("solid", 1), "albedo": ("albedo", 0), "incidence": ("incidence", 0),
         "perpendicular": ("perpendicular", 0)}

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


def side_files(side: Side) -> list[str]:
    """The data files (``path`` parameters, i.e. MERL files) a side needs in memory."""
    return [str(side.values[p.name]) for p in side.spec.params
            if p.kind == "path" and side.values.get(p.name)]


class BrdfApp(App):
    """``BrdfApp(state, color=None)``; ``color`` ∈ truecolor/256/none overrides detection.
    ``sync=True`` (tests) computes every frame on the event loop, deterministically."""

    CSS = CSS
    BINDINGS = keys.BINDINGS
    TITLE = "tuibrdf"

    def __init__(self, state: ViewerState | None = None, *, color: str | None = None,
                 message: str = "", sync: bool = False) -> None:
        super().__init__()
        self.sync = sync
        self.state = state or ViewerState()
        self._color = color
        self.message = message
        self.frame: FrameResult | None = None  # the result on screen
        self.request: FrameRequest | None = None  # the result wanted
        self.frames = 0  # how many results were shown (tests, benchmarks)
        self._loading: dict[str, float] = {}  # measured-data file → fraction read so far
        self._loaded = ""  # the saved preset `P` loaded last
        self._worker: Worker | None = None  # the frame worker started last, and its request
        self._worker_for: FrameRequest | None = None
        self._changes = 0  # changes so far; only the last one queued updates the screen
        self._relayout = False  # a change since the last update may show other panes

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
        self._changed(self.message, relayout=True)

    def on_resize(self, event) -> None:
        self._changed(self.message, relayout=True)

    @property
    def look(self) -> panes.Look:
        s = self.state
        return panes.Look(self.color_system(), s.cmap, s.log, LEVELS, "auto", s.azimuth,
                          s.elevation)

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
        # resizes the plots below; short ones keep every row for the plots
        steady = STEADY_PANEL_H if h >= BOTH_PANELS_H else None
        for panel in self.query(ParamPanel):
            panel.styles.min_height = steady
        if s.compare:
            for pane in ("map-a", "map-b", "solid-a", "solid-b"):
                k = PANES[pane][1]
                self.query_one(f"#{pane}").border_title = f"{'AB'[k]}: {s.sides[k].model}"
            self.query_one("#diff").border_title = "A − B"

    # -- one frame ---------------------------------------------------------------------------
    def _changed(self, message: str | None = None, relayout: bool = False) -> None:
        """After any change: the screen follows once the events already queued are handled
        (a burst of keys costs one update, for the last state)."""
        self.message = message or ""
        self._relayout = self._relayout or relayout
        self._changes += 1
        self.call_later(self._update, self._changes)

    def _update(self, change: int) -> None:
        """The panels and the status line now; the frame at once or from the worker."""
        if change != self._changes:
            return  # a newer change is queued behind this one
        try:
            if self._relayout:
                self._relayout = False
                self._layout()
            for i, panel in enumerate(self.query(ParamPanel)):
                if i < len(self.state.sides):
                    panel.show(self.state, i)
            self.refresh_frame()
        except NoMatches:  # keys still queued while the app closes: no widgets left
            pass

    def check_action(self, action: str, parameters: tuple[object, ...]) -> bool | None:
        """While a modal screen (help, save, palette) is open, the viewer's keys wait."""
        return not (action in VIEWER_ACTIONS and len(self.screen_stack) > 1)

    def request_rebuild(self) -> None:
        """A pane was resized: the request (pane sizes) changed."""
        self.refresh_frame()

    def _pane_size(self, pane: str) -> tuple[int, int]:
        size = self.query_one(f"#{pane}", Picture).size
        return size.width, size.height

    def frame_request(self) -> FrameRequest:
        """What the visible panes show, from the state and the pane sizes."""
        s = self.state
        map_px = None
        if s.view == "map":
            sizes = [self._pane_size(p) for p in self.visible_panes() if PANES[p][0] in
                     ("map", "diff")]
            if all(w >= MIN_WIDTH and h >= MIN_HEIGHT for w, h in sizes):
                map_px = map_pixels(min(w for w, _ in sizes), min(h for _, h in sizes))
        return FrameRequest(tuple(x.material for x in s.sides), s.theta_i, cosine=s.cosine,
                            map_px=map_px, solid=s.view == "solid", curve=s.view == "albedo")

    def refresh_frame(self) -> None:
        """Show the current state's frame: at once when computed before, else when the worker
        has computed it."""
        if self.screen.has_class("small"):
            self._status()
            return
        if not self._files_ready():  # measured data still loading: its panes say so
            for pane in self.visible_panes():
                self.query_one(f"#{pane}", Picture).show(
                    Text("loading measured data …", justify="center"), None)
            self._status()
            return
        req = self.request = self.frame_request()
        self._status()
        if self.sync:
            try:
                self.show_frame(scene.compute_frame(req))
            except DRAW_ERRORS as e:
                self._failed(req, e)
            return
        done = scene.cached_frame(req)
        if done is not None:
            self.show_frame(done)
        busy = self._worker is not None and self._worker.is_running
        if (done is None or not done.complete) and not (busy and self._worker_for == req):
            self._worker, self._worker_for = self.compute(req), req

    @work(exclusive=True, thread=True, group="frame")
    def compute(self, req: FrameRequest) -> None:
        """The frame of ``req`` off the event loop: the fast part, then the albedo (and the
        albedo curve); each posted unless a newer request cancelled this worker."""
        worker = get_current_worker()

        def post(callback, *args) -> None:
            if not worker.is_cancelled:
                try:
                    self.call_from_thread(callback, *args)
                except RuntimeError:  # the app has closed meanwhile
                    pass

        if worker.is_cancelled:
            return
        try:
            res = scene.compute_frame(req, slow=False)
            post(self.show_frame, res)
            if not res.complete and not worker.is_cancelled:
                res = scene.compute_frame(req, check=lambda: not worker.is_cancelled)
                if res is not None:
                    post(self.show_frame, res)
        except DRAW_ERRORS as e:  # a data file that vanished or changed on disk
            post(self._failed, req, e)

    def _failed(self, req: FrameRequest, error: Exception) -> None:
        if req == self.request:
            for pane in self.visible_panes():
                self.query_one(f"#{pane}", Picture).show(Text(f"cannot draw: {error}"), None)
            self.message = f"cannot compute this frame: {error}"
            self._status()

    def _writer_busy(self) -> bool:
        """Frames still queued for the terminal (Textual's private writer; guarded)."""
        try:
            return self._driver._writer_thread._queue.qsize() > 0  # type: ignore[union-attr]
        except AttributeError:
            return False

    def show_frame(self, res: FrameResult) -> None:
        """Draw ``res`` if it is still the current request: the main view now, the two
        cross-sections one frame later (plotext, ≈ 8 ms each at 160×48)."""
        if res.request != self.request or not self.is_running:
            return  # a newer request is on its way, or the app is closing
        if self._writer_busy():  # trailing edge: try again when the terminal has caught up
            self.set_timer(RETRY_S, partial(self.show_frame, res))
            return
        self.frame = res
        self.frames += 1
        shown = self.visible_panes()
        for pane in shown[:-2]:
            self._draw(pane, res)
        if self.state.compare and self.state.view == "map":
            self.query_one("#legend", Static).update(self._legend())
        self._status()
        self.call_after_refresh(self._draw_later, res, shown[-2:])

    def _draw_later(self, res: FrameResult, shown: list[str]) -> None:
        if res is self.frame and not self.screen.has_class("small"):
            for pane in shown:
                self._draw(pane, res)

    def _draw(self, pane: str, res: FrameResult) -> None:
        pic = self.query_one(f"#{pane}", Picture)
        w, h = pic.size.width, pic.size.height
        view, k = PANES[pane]
        look, req = self.look, res.request
        if w < MIN_WIDTH or h < MIN_HEIGHT or (view in ("map", "diff") and not req.map_px):
            pic.show(Text(f"{w}×{h}: too small for this pane"), None)
            return
        if view in ("map", "diff"):  # every map of a compare grid on the same pixel grid
            w, h = req.map_px[0], req.map_px[1] // 2 + 3
        what = (req.materials, req.theta_i, req.cosine)
        key = {"map": (what, req.map_px, look), "diff": (what, req.map_px, look.color),
               "solid": (what, look), "albedo": (req.materials, req.theta_i, look.color,
                                                 res.complete)}.get(view)
        key = (pane, w, h, key or (what, look.color, look.log))
        if pic.shown_for == key:
            return
        try:
            pic.show(panes.pane(view, res, k, w, h, look), key)
        except DRAW_ERRORS as e:
            pic.show(Text(f"cannot draw {pane}: {e}"), None)

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

    def _status(self) -> None:
        """θi, then each side's albedo and peak from the frame on screen when it is the
        current state's (else "…"), then the view, scale, colour map and the last message."""
        s = self.state
        line = Text()
        line.append(f"θi {s.theta_i:g}°", style="bold")
        res = self.frame
        materials = tuple(x.material for x in s.sides)
        loading = [f for side in s.sides for f in side_files(side) if f in self._loading]
        if loading:
            line.append(f"  loading {loading[0]} {self._loading[loading[0]]:.0%}",
                        style="bold yellow")
        elif res is not None and (res.request.materials, res.request.theta_i,
                                  res.request.cosine) == (materials, s.theta_i, s.cosine):
            line.append_text(panes.stats_text(res, s.view, self.look))
        else:
            for i in range(len(s.sides)):
                line.append(f"  {'AB'[i]}: a=…" if s.compare else "  a(θi) …")
        second = Text()
        scale = "log (3 decades)" if s.log else "linear"
        second.append(f"{VIEW_TITLES[s.view]} · {scale} · {s.cmap}"
                      f"{' · f·cos θr' if s.cosine else ''}", style="dim")
        if s.compare:
            second.append(f" · keys → {'AB'[s.active]}", style="bold")
        if self.message:
            second.append(f"  {self.message}", style="bold yellow")
        self.query_one("#status", StatusLine).show_text(Text("\n").join([line, second]))

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
                    self.call_later(self._load_failed, path, str(e))
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

    # -- actions -----------------------------------------------------------------------------
    def action_state(self, method: str, args: tuple = ()) -> None:
        """A :class:`ViewerState` transition named in the key table."""
        self._changed(getattr(self.state, method)(*args), relayout=method in keys.RELAYOUT)

    def action_help(self) -> None:
        self.push_screen(HelpScreen())

    def action_save(self) -> None:
        def done(name: str | None) -> None:
            if not name:
                self._changed("save cancelled")
                return
            try:
                path = save_preset(self.state, name)
            except (PresetError, OSError) as e:
                self._changed(f"not saved: {e}")
                return
            self._changed(f"saved {path}")

        self.push_screen(SaveScreen(), done)

    def action_load_next(self) -> None:
        names = list_presets()
        if not names:
            self._changed(f"no saved presets in {preset_dir()} (s saves one)")
            return
        i = names.index(self._loaded) if self._loaded in names else -1
        self.load_and_show(names[(i + 1) % len(names)])

    def load_and_show(self, name: str) -> None:
        msg = self.load(name)
        if msg is None:
            self._loaded = name
        self._changed(msg or f"loaded preset {name}", relayout=True)

    def load(self, name: str) -> str | None:
        """Load a saved preset into the viewer; a message if it cannot be."""
        try:
            theta, sides = load_preset(name)
        except PresetError as e:
            return str(e)
        apply_loaded(self.state, theta, sides)
        return None

    def action_command_palette(self) -> None:
        if self.use_command_palette and not SafeCommandPalette.is_open(self):
            self.push_screen(SafeCommandPalette(id="--command-palette"))

    def get_system_commands(self, screen):
        yield from super().get_system_commands(screen)
        for name in list_presets():
            yield SystemCommand(f"Load preset {name}", f"{preset_dir() / name}.toml",
                                partial(self.load_and_show, name))
        for k in keys.palette_keys():
            yield SystemCommand(k.help, f"key: {k.shown}", partial(self.run_action, k.action))
