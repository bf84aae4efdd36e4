"""What the viewer writes besides the pictures, as plain functions of the session state and
the frame on screen (Rich text, no Textual): the visible panes, the status line, the compare
legend."""

from __future__ import annotations

from rich.text import Text

from tuibrdf.app.keys import keys_of
from tuibrdf.core.display import DISPLAY
from tuibrdf.core.views.frame import FrameResult
from tuibrdf.core.views.negatives import negative_note
from tuibrdf.render import VIEW_TITLES, panes
from tuibrdf.render.text import phi_deg_text
from tuibrdf.state.viewer import COMPARE_PRESETS, Side, ViewerState

#: pane → (view, side)
PANES = {"map-a": ("map", 0), "map-b": ("map", 1), "diff": ("diff", 0), "solid-a": ("solid", 0),
         "solid-b": ("solid", 1), "albedo": ("albedo", 0), "incidence": ("incidence", 0),
         "perpendicular": ("perpendicular", 0), "extra-a": ("extra", 0),
         "extra-b": ("extra", 1)}


def visible_panes(s: ViewerState) -> list[str]:
    """The panes of the main view (one per side in compare mode), then the two sections."""
    if s.compare:
        main = {"map": ["map-a", "map-b", "diff"], "solid": ["solid-a", "solid-b"],
                "albedo": ["albedo"]}.get(s.view, ["extra-a", "extra-b"])
    else:
        main = {"map": ["map-a"], "solid": ["solid-a"], "albedo": ["albedo"]}.get(s.view,
                                                                                 ["extra-a"])
    return main + ["incidence", "perpendicular"]


def side_files(side: Side) -> list[str]:
    """The data files (``path`` parameters, i.e. MERL files) a side needs in memory."""
    return [str(side.values[p.name]) for p in side.spec.params
            if p.kind == "path" and side.values.get(p.name)]


#: how many forms of the status line there are, from the full one to the tersest
#: (:func:`status_text`'s ``terse``: each leaves out more, least useful first; the status
#: line shows the first that fits its rows, ``widgets.StatusLine``)
TERSE_FORMS = 4


def status_text(s: ViewerState, frame: FrameResult | None, look: panes.Look,
                loading: dict[str, float], message: str, terse: int = 0, *,
                failed: bool = False) -> Text:
    """θi, then each side's albedo and peak from the frame on screen when it is the current
    state's (else "…" while it is computed, "—" when it ``failed``: the message says why),
    then the view, scale, colour map and the last message.  ``terse``
    (0 … TERSE_FORMS − 1) shortens the numbers for a narrow line, least useful first: 1 the
    probe's f·cos θr left out (f and θr are shown), 2 the peaks' directions too, 3 the peaks
    (each map's title and colour bar show them)."""
    line = Text()
    line.append(f"θi {s.theta_i:g}°", style="bold")
    if s.phi_i != DISPLAY.phi_i.default:
        line.append(f" φi {phi_deg_text(s.phi_i)}°", style="bold")
    materials = tuple(x.material for x in s.sides)
    files = [f for side in s.sides for f in side_files(side) if f in loading]
    if files:
        line.append(f"  loading {files[0]} {loading[files[0]]:.0%}", style="bold yellow")
    elif frame is not None and (frame.request.materials, frame.request.theta_i,
                                frame.request.cosine, frame.request.phi_i) == (
                                    materials, s.theta_i, s.cosine, s.phi_i):
        line.append_text(panes.stats_text(frame, s.view, look, terse=max(0, terse - 1)))
        for k, side in enumerate(frame.sides):  # a user model's sign slip, said once
            note = negative_note(side.negative)
            if note:
                line.append(f"  {'AB'[k] + ': ' if s.compare else ''}{note}", style="bold red")
        line.append_text(probe_text(frame, terse))
        line.append_text(energy_text(frame))
    else:
        mark = "—" if failed else "…"
        for i in range(len(s.sides)):
            line.append(f"  {'AB'[i]}: a={mark}" if s.compare else f"  a(θi) {mark}")
    second = Text()
    scale = "log (3 decades)" if (s.slice_log if s.view == "slice" else s.log) else "linear"
    second.append(f"{VIEW_TITLES[s.view]} · {scale} · {s.cmap}"
                  f"{' · f·cos θr' if s.cosine else ''}{settings_text(s)}", style="dim")
    if s.compare:
        second.append(f" · keys → {'AB'[s.active]}", style="bold")
    if message:
        second.append(f"  {message}", style="bold yellow")
    second.append_text(settings_keys(s))
    return Text("\n").join([line, second])


def view_settings(s: ViewerState) -> list[tuple[str, str, str]]:
    """The settings of the view shown, as ``(shown, name, transition)``:
    ``("exp 1", "exp", "scale_exposure")`` (shown ``""``: another transition of the setting
    before it); ψ only when it is not its default (90°)."""
    out = []
    if s.view in ("sphere", "plane"):
        out += [(f"exp {s.exposure:g}", "exp", "scale_exposure"),
                (f"γ {s.gamma:g}", "γ", "step_gamma")]
    elif s.view == "slice":
        out += [(f"φd {s.phi_d:g}°", "φd", "step_fixed"), ("", "φd", "step_phi_d"),
                ("√θh" if s.sqrt_h else "linear θh", "√θh", "toggle_sqrt_h")]
    elif s.view in ("theta-h", "theta-d"):
        fixed = f"θd {s.theta_d:g}°" if s.view == "theta-h" else f"θh {s.theta_h:g}°"
        out += [(fixed, fixed[:2], "step_fixed"), (f"φd {s.phi_d:g}°", "φd", "step_phi_d")]
    if s.section_azimuth != DISPLAY.section_azimuth.default:
        out.append((f"section ψ {s.section_azimuth:g}°", "ψ", "step_section"))
    return out


def settings_text(s: ViewerState) -> str:
    """`` · exp 1 · γ 2.2``: the view's settings, as the status line shows them."""
    return "".join(f" · {shown}" for shown, _, _ in view_settings(s) if shown)


def settings_keys(s: ViewerState) -> Text:
    """``x/X exp  g/G γ``: the keys that change the view's settings, in bold (the status
    line ends with them: on a full line they are what is cut, after a message)."""
    named: dict[str, list[str]] = {}  # a setting two transitions change: its keys together
    for _, name, method in view_settings(s):
        named.setdefault(name, []).append(keys_of(method))
    out = Text()
    for name, keys in named.items():
        out.append("  ")
        out.append(" ".join(keys), style="bold")
        out.append(f" {name}", style="dim")
    return out


def energy_text(frame: FrameResult) -> Text:
    """The energy view's white-furnace verdict per side (``loses 23 % at α = 1, θi = 0°``)."""
    t = Text()
    if frame.request.extra != "energy":
        return t
    for k, side in enumerate(frame.sides):
        view = side.extra[0] if side.extra else None
        if view is None:
            continue
        tag = f"  {'AB'[k]}: " if len(frame.sides) > 1 else "  "
        t.append(tag + view.verdict, style="bold red" if view.gains else "green")
    return t


def probe_text(frame: FrameResult, terse: int = 0) -> Text:
    """``probe θr=40° φr=10°  f=0.31 f·cosθr=0.24 sr⁻¹`` per side, from the frame;
    ``terse`` as :func:`status_text`'s."""
    t = Text()
    req = frame.request
    if req.probe is None or any(side.probe is None for side in frame.sides):
        return t
    th, ph = req.probe_angles
    t.append(f"  probe θr={th:.1f}° φr={ph:.1f}°", style="bold cyan")
    for k, side in enumerate(frame.sides):
        f, fc = side.probe
        tag = f"  {'AB'[k]}:" if len(frame.sides) > 1 else " "
        cos = "" if terse >= 1 else f" f·cosθr={panes.albedo_text(fc)}"
        t.append(f"{tag} f={panes.albedo_text(f)}{cos} sr⁻¹")
    return t


def legend_text(s: ViewerState) -> Text:
    """Compare mode: both materials in full, the shared scale, the preset, the tab key."""
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
