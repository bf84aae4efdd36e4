"""``tuibrdf view``: open the interactive viewer (also what plain ``tuibrdf`` does).

``tuibrdf view [MODEL | FILE] [-p NAME=VALUE ...] [--theta-i DEG] [--phi-i DEG] [--preset NAME
[--trust]] [--color auto|truecolor|256|none | --no-color]`` (or ``--material NAME`` instead of
the model, below).  A ``.py`` model file is Python code and runs; a preset that names one loads
only if that file is named on the command line too, or with ``--trust``.  A ``.binary`` path
opens the measured MERL material (model ``merl`` with ``file=PATH``); a ``.brdf``, ``.bparam``,
``.py`` or ``.bsdf`` file opens through the model registry
(:mod:`tuibrdf.core.formats.userfiles`).  ``--preset NAME`` loads a saved preset (``s`` in the
viewer saves one) or, when no file has that name, one of the seed's comparisons (``diffuse``,
``specular``).  Everything is validated before Textual is imported (a MERL file is read whole,
as ``eval`` reads it), so bad input is one line on stderr and exit status 2; so is a missing
terminal (stdin and stdout must both be one; Textual's web driver, as ``tuibrdf serve``
runs the viewer, counts as one).  ``--color`` and ``NO_COLOR`` are handed to
Textual through its environment variables (``TEXTUAL_COLOR_SYSTEM``, ``NO_COLOR``).

``--material NAME`` opens the published fit of a MERL material (``tuibrdf materials`` lists
them): model ``abc`` (Löw et al. 2012), or ``sgd`` (Bagher et al. 2012) with ``--fit sgd``.
Compare mode from the command line: ``--compare-fit`` puts the ABC fit (A) and the SGD fit (B)
of the material side by side; ``--compare-material OTHER`` puts a second material (B, same fit)
next to the first.
"""

from __future__ import annotations

import argparse
import os
import sys
from functools import partial

from tuibrdf.cli.common import (
    UsageError,
    add_phi_i,
    add_theta_i,
    choices_type,
    isatty,
    parse_params,
    unknown,
)
from tuibrdf.core.display import DISPLAY
from tuibrdf.render import VIEWS

COLORS = ("auto", "truecolor", "256", "none")
FITS = ("abc", "sgd")
#: what plain ``tuibrdf`` shows: a glossy lobe over a diffuse base (a flat Lambert disc
#: taught nothing about lobes), with :data:`FIRST_HINT` on the status line
FIRST_MODEL = "phong"
FIRST_HINT = "←/→ move the light · ↑/↓ +/- a parameter · v next view · m next model · ? keys"
#: views the viewer always shows beside the main one (not a --view of their own)
SECTIONS = ("incidence", "perpendicular")


def add_args(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("model", nargs="?", default=None, metavar="MODEL|FILE",
                        help="model name (see 'tuibrdf models') or a file: .brdf, .bparam "
                             "(BRDF Explorer), .py (Python model: its code runs), .bsdf (RGL), "
                             ".binary (MERL) "
                             "(default: phong, a glossy lobe)")
    parser.add_argument("-p", "--param", action="append", default=[], metavar="NAME=VALUE",
                        help="set a parameter (repeatable); RGB as R,G,B; angles in degrees")
    add_theta_i(parser, default=DISPLAY.theta_i.default)
    add_phi_i(parser)
    parser.add_argument("--view", metavar="NAME", default=None,
                        help="start in this main view (v cycles them): " + ", ".join(
                            v for v in VIEWS if v not in SECTIONS) + " (default: map)")
    parser.add_argument("--preset", metavar="NAME",
                        help="load a saved preset, or a seed comparison: diffuse, specular; "
                             "a preset naming a .py model file runs that file's code, so it "
                             "loads only if that file is also named here or with --trust")
    parser.add_argument("--trust", action="store_true",
                        help="let --preset load a preset that names a .py model file (its "
                             "Python code runs) not named on the command line")
    parser.add_argument("--color", type=choices_type("color mode", COLORS), default="auto",
                        metavar="|".join(COLORS),
                        help="colours: auto (Textual detects; NO_COLOR respected), truecolor, "
                             "256, none")
    parser.add_argument("--no-color", dest="color", action="store_const", const="none",
                        help="no colours, the same as --color none")
    parser.add_argument("--material", metavar="NAME",
                        help="a MERL material's published fit instead of MODEL (see 'tuibrdf "
                             "materials'): ABC, or SGD with --fit sgd")
    parser.add_argument("--fit", type=choices_type("fit", FITS), default=None,
                        metavar="|".join(FITS), help="with --material: which fit (default abc)")
    parser.add_argument("--compare-fit", action="store_true",
                        help="with --material: the ABC (A) and SGD (B) fits side by side")
    parser.add_argument("--output-dir", metavar="DIR", default=None,
                        help="where key w (and the palette's Screenshot) writes the screen "
                             "and the main view (default: the current directory)")
    parser.add_argument("--compare-material", metavar="NAME",
                        help="with --material: a second material (B, same fit) side by side")
    from tuibrdf.cli.sides import add_compare_args

    add_compare_args(parser)


def material_sides(args: argparse.Namespace):
    """The sides ``--material`` asks for (one, or two in compare mode), or None without it;
    raises UsageError for a bad combination or name."""
    from tuibrdf.core.registry import MODELS
    from tuibrdf.state.viewer import Side

    material = getattr(args, "material", None)
    extra = [flag for flag, on in (("--fit", args.fit), ("--compare-fit", args.compare_fit),
                                   ("--compare-material", args.compare_material)) if on]
    if material is None:
        if extra:
            raise UsageError(f"{extra[0]} needs --material NAME")
        return None
    if args.model:
        raise UsageError(f"give a MODEL ({args.model}) or --material, not both")
    if args.preset:
        raise UsageError("--preset and --material both choose what to show: give one")
    if args.compare_fit and args.compare_material:
        raise UsageError("--compare-fit and --compare-material: give one")
    if args.compare_fit and args.fit:
        raise UsageError("--compare-fit shows both fits: drop --fit")
    fit = MODELS[args.fit or "abc"]
    values = fit.resolve(parse_params(fit, [f"material={material}", *args.param]))
    if args.compare_fit:
        other = MODELS["sgd"]
        return [Side(fit.name, values),
                Side(other.name, other.resolve(parse_params(other, [f"material={material}"])))]
    sides = [Side(fit.name, values)]
    if args.compare_material:
        sides.append(Side(fit.name, fit.resolve(
            parse_params(fit, [f"material={args.compare_material}", *args.param]))))
    return sides


def build_state(args: argparse.Namespace):
    """The viewer's initial state from the arguments (no Textual); raises UsageError.
    ``--compare B [-q …]`` adds side B (:mod:`tuibrdf.cli.sides`)."""
    from tuibrdf.cli.sides import compare_side
    from tuibrdf.state.viewer import Side

    other = compare_side(args)
    state = _build_state(args)
    if other is not None:
        from tuibrdf.core.material import Material

        if state.compare:
            raise UsageError("--compare and a comparison already asked for: give one")
        state.sides = [state.sides[0], Side(Material(*other))]
    return state


def _build_state(args: argparse.Namespace):
    from tuibrdf.core.formats.merl import check_file, load_cached
    from tuibrdf.core.registry import MODELS
    from tuibrdf.state.presets import (
        PresetError,
        apply_loaded,
        find_preset,
        list_presets,
        load_preset,
        where_presets_are,
    )
    from tuibrdf.state.viewer import COMPARE_PRESETS, Side, ViewerState

    sides = material_sides(args)
    if sides is not None:
        return with_view(ViewerState(sides=sides, theta_i=float(args.theta_i),
                                     phi_i=float(args.phi_i) % 360.0), args)
    name = args.model or FIRST_MODEL
    tokens = list(args.param)
    if name.lower().endswith(".binary"):
        if "merl" not in MODELS:
            raise UsageError(f"{name}: MERL files need the 'merl' model, which this build "
                             "does not have yet")
        from tuibrdf.core.formats.files import describe

        problem = describe(name)  # "no such file", "is a FIFO (named pipe), ..."
        if problem:
            raise UsageError(f"{name}: {problem}")
        tokens = [f"file={name}", *tokens]
        name = "merl"
    if name not in MODELS:
        from tuibrdf.core.formats.userfiles import looks_like_path
        from tuibrdf.core.registry import get_model

        if not looks_like_path(name):
            raise UsageError(unknown("unknown model", name, list(MODELS)))
        model = get_model(name)  # a user file (.brdf, .bparam, .py, .bsdf): ValueError → exit 2
    else:
        model = MODELS[name]
    values = model.resolve(parse_params(model, tokens))
    state = ViewerState(sides=[Side(model.name, values)], theta_i=float(args.theta_i),
                        phi_i=float(args.phi_i) % 360.0)
    if args.preset:
        seed = {p.name for p in COMPARE_PRESETS}
        try:
            path = find_preset(args.preset)  # the new directory first, then the old one
        except PresetError as e:
            raise UsageError(str(e)) from None
        exists = os.path.lexists(path)  # a FIFO or a directory of that name: say what it is
        if not exists and args.preset not in seed:
            have = ", ".join(list_presets() + sorted(seed))
            raise UsageError(f"no preset named {args.preset!r} in {where_presets_are()} "
                             f"(available: {have})")
        if exists:
            named = [name] if name.lower().endswith(".py") else []  # the user named it
            try:
                loaded = load_preset(args.preset, True if args.trust else named)
            except PresetError as e:
                raise UsageError(str(e)) from None
            apply_loaded(state, *loaded)
        else:
            msg = state.apply_preset(args.preset)
            if msg:
                raise UsageError(msg)
    for side in state.sides:  # a bad MERL file is one line here, not a message in the viewer
        for p in side.spec.params:
            if p.kind == "path":
                check_file(side.values[p.name])  # cheap: kind of file, header, size
                # then the whole file, as `eval` reads it (NaN and inf are found only there);
                # the viewer's own load is then a cache hit
                load_cached(side.values[p.name])
    return with_view(state, args)


def with_view(state, args: argparse.Namespace):
    """``state`` in the main view ``--view`` names (it wins over a preset's); UsageError for a
    name the viewer's ``v`` cycle does not have."""
    from tuibrdf.state.viewer import MAIN_VIEWS

    view = getattr(args, "view", None)
    if view is None:
        return state
    if view in SECTIONS:
        raise UsageError(f"--view {view}: the cross-sections are always shown beside the main "
                         f"view; main views: {', '.join(MAIN_VIEWS)}")
    if view not in MAIN_VIEWS:
        raise UsageError(unknown("--view: unknown view", view, list(MAIN_VIEWS)))
    state.view = view
    return state


def check_terminal(stdin=None, stdout=None) -> None:
    """The viewer needs a terminal on both ends; without one Textual would wait for keys that
    never come (``tuibrdf view < /dev/null``) or draw escape codes into a file."""
    if web_driver():  # served (tuibrdf serve): the streams are textual-serve's pipes
        return
    stdin = sys.stdin if stdin is None else stdin
    stdout = sys.stdout if stdout is None else stdout
    for what, stream in (("standard input", stdin), ("standard output", stdout)):
        if not isatty(stream):  # also a closed stream
            raise UsageError(f"view needs a terminal, and {what} is not one (for a picture "
                             "in a pipe or a file: tuibrdf render)")


def web_driver() -> bool:
    """Whether Textual will use its web driver (textual-serve sets ``TEXTUAL_DRIVER``, which
    Textual's ``App.get_driver_class`` imports): it talks over pipes, not a terminal."""
    module = os.environ.get("TEXTUAL_DRIVER", "").partition(":")[0]
    return module == "textual.drivers.web_driver"


#: the signals that end the viewer: the terminal is restored, then exit status 128 + n
#: (SIGINT: 130, as Ctrl-C); SIGTSTP/SIGCONT are Textual's (suspend, resume: redrawn)
TERMINATING = ("SIGINT", "SIGTERM", "SIGHUP", "SIGQUIT", "SIGUSR1", "SIGUSR2", "SIGALRM")
#: what leaving Textual's application mode writes: the kitty keyboard protocol, mouse
#: tracking, focus events and bracketed paste off, line wrap on, the main screen back, the
#: cursor shown
RESTORE = ("\x1b[<u\x1b[?1000l\x1b[?1003l\x1b[?1015l\x1b[?1006l\x1b[?1004l\x1b[?2004l"
           "\x1b[?7h\x1b[?1049l\x1b[?25h")


def _on_terminating_signal(saved, signum, frame) -> None:
    """Restore the terminal (the modes Textual set, the tty's attributes from before) and
    exit 128 + ``signum`` at once: nothing waits for the app or a frame's thread."""
    try:
        os.write(sys.__stdout__.fileno(), RESTORE.encode())
    except (OSError, ValueError, AttributeError):  # the terminal is gone (SIGHUP)
        pass
    if saved is not None:
        import termios

        try:
            termios.tcsetattr(sys.__stdin__.fileno(), termios.TCSANOW, saved)
        except (termios.error, OSError, ValueError):
            pass
    os._exit(128 + signum)


def catch_terminating_signals() -> dict:
    """From here on, each of :data:`TERMINATING` restores the terminal and exits; returns
    the handlers they had (for :func:`restore_signals`)."""
    import signal

    saved = None
    try:
        import termios
    except ImportError:  # (Windows)
        termios = None
    if termios is not None:
        try:
            saved = termios.tcgetattr(sys.__stdin__.fileno())
        except (termios.error, OSError, ValueError, AttributeError):  # not a tty (tests)
            pass
    before = {}
    for name in TERMINATING:
        if hasattr(signal, name):
            n = getattr(signal, name)
            before[n] = signal.signal(n, partial(_on_terminating_signal, saved))
    return before


def restore_signals(before: dict) -> None:
    import signal

    for n, handler in before.items():
        signal.signal(n, handler if handler is not None else signal.SIG_DFL)


def open_viewer(state, color: str | None, message: str = "",
                output_dir: str | None = None) -> int:
    """Run the Textual app (the only place Textual is imported); its exit status.  A crash:
    Textual restores the terminal, the app prints one line and sets exit status 1.  A frame
    still computing in a thread (a user's kernel that does not return) is not waited for:
    the process ends without it (``os._exit``, after the terminal was restored)."""
    from pathlib import Path

    from tuibrdf.app.app import BrdfApp

    app = BrdfApp(state, color=color, message=message)
    if output_dir is not None:
        app.output_dir = Path(output_dir).absolute()  # a later cd does not move it
    before = catch_terminating_signals()
    try:
        app.run()
    finally:
        restore_signals(before)
    code = app.return_code or 0
    if app.stuck_jobs():
        for stream in (sys.stdout, sys.stderr):
            try:
                stream.flush()
            except (OSError, ValueError):
                pass
        os._exit(code)
    return code


def run(args: argparse.Namespace) -> int:
    import gc

    # start-up's objects (Textual, numpy, the models, the first frame) nearly all live for the
    # whole session: collecting while they are made scans them for nothing (≈ 20 ms of the
    # imports, 9 %).  The app turns the collector back on when it freezes them
    # (app.freeze_start_up); this does if the viewer ends first
    gc.disable()
    try:
        return _run(args)
    finally:
        gc.enable()


def _run(args: argparse.Namespace) -> int:
    from tuibrdf.state import sandbox

    policy = sandbox.install_from_environment()  # served: only the files serve allows
    state = build_state(args)
    if policy is not None:  # the other model files named to serve: `m` cycles to them
        state.files += [m for m in policy.models if m not in state.files]
    if args.output_dir is not None and os.path.exists(args.output_dir) \
            and not os.path.isdir(args.output_dir):
        raise UsageError(f"--output-dir {args.output_dir}: not a directory")
    check_terminal()
    if args.color == "none":
        os.environ["NO_COLOR"] = "1"
    elif args.color != "auto":
        os.environ["TEXTUAL_COLOR_SYSTEM"] = "truecolor" if args.color == "truecolor" \
            else "256"
    first = not (args.model or args.preset or args.material)
    # output_dir only when given: open_viewer(state, color, message) without it
    kw = {} if args.output_dir is None else {"output_dir": args.output_dir}
    return open_viewer(state, None if args.color == "auto" else args.color,
                       FIRST_HINT if first else "", **kw) or 0
