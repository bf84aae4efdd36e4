"""The key table, declared once: Textual's bindings, the footer, the help screen and the
command palette are all generated from :data:`KEYS`.

An action ``state('METHOD', (ARGS…))`` calls :class:`~tuibrdf.state.viewer.ViewerState`'s
transition of that name (``BrdfApp.action_state``); the others (help, save, load a saved
preset, quit) are the app's own.  :data:`RELAYOUT` names the transitions that change which
panes are shown.
"""

from __future__ import annotations

from dataclasses import dataclass

from rich.console import Group
from rich.table import Table
from rich.text import Text
from textual.binding import Binding


@dataclass(frozen=True)
class Key:
    keys: str  # Textual key names, comma-separated
    action: str
    short: str  # footer label
    help: str  # help screen and command palette
    display: str | None = None  # how the key is written (default: the first key name)
    footer: bool = False
    #: keys the footer shows together with one label (``← → θi``): a footer that fits 60
    #: columns whole
    group: str | None = None

    @property
    def key(self) -> str:
        """The first of its keys (the one the footer presses)."""
        return self.keys.split(",")[0]

    @property
    def shown(self) -> str:
        return self.display or self.key


def _s(method: str, *args: object) -> str:
    """``state('METHOD', (ARGS…))``: the arguments as one tuple (Textual passes an action
    only as many arguments as its method declares, so no ``*args`` there)."""
    return f"state({method!r}, {args!r})"


KEYS: tuple[Key, ...] = (
    Key("left", _s("step_theta", -1), "θi−", "θi −1°  (shift+← −10°)", "←", footer=True,
        group="θi"),
    Key("right", _s("step_theta", 1), "θi+", "θi +1°  (shift+→ +10°)", "→", footer=True,
        group="θi"),
    Key("shift+left", _s("step_theta", -10), "θi −10°", "θi −10°", "shift+←"),
    Key("shift+right", _s("step_theta", 10), "θi +10°", "θi +10°", "shift+→"),
    Key("greater_than_sign", _s("step_phi_i", 15), "φi+", "light azimuth φi +15° (default 180°)",
        ">"),
    Key("less_than_sign", _s("step_phi_i", -15), "φi−", "light azimuth φi −15°", "<"),
    Key("up", _s("select", -1), "param ↑", "previous parameter", "↑"),
    Key("down", _s("select", 1), "param ↓", "next parameter", "↓"),
    Key("plus,right_square_bracket", _s("step_param", 1), "inc",
        "selected parameter + step (also ]); roughness, exponents: ×1.1", "+", footer=True,
        group="step"),
    Key("minus,left_square_bracket", _s("step_param", -1), "dec",
        "selected parameter − step (also [); roughness, exponents: ÷1.1", "-", footer=True,
        group="step"),
    Key("enter,equals_sign", "type_value", "type",
        "type a value for the selected parameter (range shown; a list to filter for choices)",
        "="),  # (not in the footer: it fits 60 columns whole)
    Key("t", "type_theta", "type θi", "type θi in degrees"),
    Key("right_curly_bracket", _s("step_param", 1, True), "+coarse",
        "selected parameter + coarse step (×2 for roughness, exponents)", "}"),
    Key("left_curly_bracket,underscore", _s("step_param", -1, True), "−coarse",
        "selected parameter − coarse step (also _)", "{"),
    Key("r", _s("reset_param"), "reset", "reset the selected parameter"),
    Key("m", _s("cycle_model", 1), "model", "next model (θi kept)", footer=True),
    Key("M", _s("cycle_model", -1), "prev model", "previous model"),
    Key("v", _s("cycle_view"), "view", "main view: map → 3D solid → albedo curve → lit sphere "
        "→ lit plane → θh×θd slice → f(θh) → f(θd)", footer=True),
    Key("V", _s("cycle_view", -1), "prev view", "previous main view"),
    Key("comma,ctrl+left", _s("rotate", -10, 0), "rotate ←",
        "3D solid: turn left (also ctrl+←)", ","),
    Key("full_stop,ctrl+right", _s("rotate", 10, 0), "rotate →",
        "3D solid: turn right (also ctrl+→)", "."),
    Key("e,ctrl+up", _s("rotate", 0, 5), "tilt ↑", "3D solid: tilt up (also ctrl+↑)"),
    Key("E,ctrl+down", _s("rotate", 0, -5), "tilt ↓", "3D solid: tilt down (also ctrl+↓)"),
    Key("a", _s("step_section", 15), "ψ+", "section through the peak: azimuth ψ +15° "
        "(90° = across the plane of incidence)"),
    Key("A", _s("step_section", -15), "ψ−", "section through the peak: azimuth ψ −15°"),
    Key("x", _s("scale_exposure", 2.0), "exp×2", "lit sphere / plane: exposure ×2"),
    Key("X", _s("scale_exposure", 0.5), "exp÷2", "lit sphere / plane: exposure ÷2"),
    Key("g", _s("step_gamma", 0.2), "γ+", "lit sphere / plane: gamma +0.2"),
    Key("G", _s("step_gamma", -0.2), "γ−", "lit sphere / plane: gamma −0.2"),
    Key("d", _s("step_fixed", 5), "fixed+", "f(θh): θd +5°; f(θd): θh +5°; slice: φd +5°"),
    Key("D", _s("step_fixed", -5), "fixed−", "f(θh): θd −5°; f(θd): θh −5°; slice: φd −5°"),
    Key("y", _s("step_phi_d", 15), "φd+", "half/difference views: φd +15°"),
    Key("Y", _s("step_phi_d", -15), "φd−", "half/difference views: φd −15°"),
    Key("h", _s("toggle_sqrt_h"), "√θh", "slice: √θh (as MERL's table) / linear θh axis"),
    Key("b", _s("toggle_probe"), "probe", "probe on the map on / off (also: click the map)"),
    Key("J", _s("move_probe", -1, 0), "probe ←", "move the probe left"),
    Key("L", _s("move_probe", 1, 0), "probe →", "move the probe right"),
    Key("I", _s("move_probe", 0, 1), "probe ↑", "move the probe up"),
    Key("K", _s("move_probe", 0, -1), "probe ↓", "move the probe down"),
    Key("l", _s("toggle_log"), "log", "linear / log colour scale"),
    Key("k", _s("cycle_cmap"), "cmap", "next colour map"),
    Key("o", _s("toggle_cosine"), "f·cos", "show f or f·cos θr"),
    Key("C", _s("cycle_channel"), "channel",
        "curves of RGB models: R,G,B → luminance → R → G → B"),
    Key("c", _s("toggle_compare"), "compare", "compare two models (B starts as A)", footer=True),
    Key("tab", _s("switch_side"), "side", "compare: keys act on A or B"),
    Key("p", _s("next_preset"), "preset",
        "next seed comparison (diffuse, specular, then back to your own settings)"),
    Key("s", "save", "save", "save θi and parameters as a preset (TOML file)"),
    Key("P", "load_next", "load preset",
        "load the next saved preset (also: tuibrdf view --preset NAME)"),
    Key("w", "write_figures", "write",
        "write the screen (SVG) and the main view (PNG, its numbers NPZ/CSV) into the current "
        "directory (tuibrdf view --output-dir DIR)"),
    Key("F", "checks", "checks", "check the model: finite, positivity, reciprocity (with its "
        "map at this θi), energy, and the χ² test of a sampler (pdf, histogram, difference)"),
    Key("question_mark", "help", "help", "this screen", "?", footer=True),
    Key("q", "quit", "quit", "quit", footer=True),
    Key("ctrl+c", "interrupt", "quit", "quit with exit status 130 (as Ctrl-C; ctrl+q quits too)",
        "ctrl+c"),
)

#: transitions after which the set of visible panes may change
RELAYOUT = frozenset({"cycle_model", "cycle_view", "toggle_compare", "switch_side",
                      "next_preset"})

#: the viewer's keys are priority bindings: the app acts on a key when it first reaches
#: it, not after Textual has forwarded it to the screen and it has bubbled back (≈ 0.5 ms a
#: key, docs/benchmarks.md), and keys typed together act in the order typed (a priority key no
#: longer overtakes the ones still bubbling).  While a modal screen is open
#: ``BrdfApp.check_action`` refuses them and the key goes on to that screen as before; quit
#: stays an ordinary binding (q closes the help screen, and types a q in a text field).
BINDINGS = [Binding(k.keys, k.action, k.short, show=k.footer, key_display=k.display,
                    priority=k.action != "quit",
                    group=Binding.Group(k.group, compact=True) if k.group else None)
            for k in KEYS]


def footer_items() -> list[tuple[tuple[Key, ...], str]]:
    """What the footer shows, in the table's order: the keys of a group together with the
    group's name (``←→ θi``), every other footer key with its own label."""
    items: list[tuple[tuple[Key, ...], str]] = []
    for k in KEYS:
        if not k.footer:
            continue
        if k.group and items and items[-1][1] == k.group:
            items[-1] = (items[-1][0] + (k,), k.group)
        else:
            items.append(((k,), k.group or k.short))
    return items


#: the help screen's key column
KEY_COLUMN = 12


def help_text() -> Group:
    """The help screen: every key with its help line, a long one wrapped under its own
    column (not under the keys)."""
    grid = Table.grid()
    grid.add_column(width=KEY_COLUMN, no_wrap=True, style="bold")
    grid.add_column(ratio=1)
    for k in KEYS:
        grid.add_row(k.shown, k.help)
    return Group(Text("tuibrdf — keys\n", style="bold"), grid,
                 Text("\nEsc or ? closes this screen; ctrl+p opens the command palette.",
                      style="dim"))


def keys_of(method: str) -> str:
    """The keys of the state transition ``method``, as written, in the table's order
    (``keys_of("scale_exposure") == "x/X"``): the status line names them beside the setting
    they change."""
    return "/".join(k.shown for k in KEYS if k.action.startswith(f"state({method!r},"))


def palette_keys() -> list[Key]:
    """The keys the command palette lists (Textual adds its own help and quit)."""
    return [k for k in KEYS if k.action not in ("help", "quit", "interrupt")]
