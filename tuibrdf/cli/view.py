"""``tuibrdf view``: open the interactive viewer (also what plain ``tuibrdf`` does).

``tuibrdf view [MODEL | FILE] [-p NAME=VALUE ...] [--theta-i DEG] [--preset NAME]
[--color auto|truecolor|256|none]``.  A ``.binary`` path opens the measured MERL material
(model ``merl`` with ``file=PATH``); a ``.brdf``, ``.bparam``, ``.py`` or ``.bsdf`` file opens
through the model registry (:mod:`tuibrdf.core.userfiles`).  ``--preset NAME`` loads a saved
preset (``s`` in the viewer saves one) or, when no file has that name, one of the seed's
comparisons (``diffuse``, ``specular``).  Everything is validated before Textual is imported,
so bad input is one line on stderr and exit status 2; ``--color`` and ``NO_COLOR`` are handed
to Textual through its environment variables (``TEXTUAL_COLOR_SYSTEM``, ``NO_COLOR``).

``--material NAME`` opens the published fit of a MERL material (``tuibrdf materials`` lists
them): model ``abc`` (Löw et al. 2012), or ``sgd`` (Bagher et al. 2012) with ``--fit sgd``.
Compare mode from the command line: ``--compare-fit`` puts the ABC fit (A) and the SGD fit (B)
of the material side by side; ``--compare-material OTHER`` puts a second material (B, same fit)
next to the first.
"""

from __future__ import annotations

import argparse
import os

from ..core.merl import check_file
from ..core.models import MODELS
from .common import UsageError, add_theta_i, choices_type, parse_params

COLORS = ("auto", "truecolor", "256", "none")
FITS = ("abc", "sgd")


def add_args(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("model", nargs="?", default=None, metavar="MODEL|FILE",
                        help="model name (see 'tuibrdf models') or a file: .brdf, .bparam "
                             "(BRDF Explorer), .py (Python model), .bsdf (RGL), .binary (MERL) "
                             "(default: lambert)")
    parser.add_argument("-p", "--param", action="append", default=[], metavar="NAME=VALUE",
                        help="set a parameter (repeatable); RGB as R,G,B; angles in degrees")
    add_theta_i(parser, default=30.0)
    parser.add_argument("--preset", metavar="NAME",
                        help="load a saved preset, or a seed comparison: diffuse, specular")
    parser.add_argument("--color", type=choices_type("color mode", COLORS), default="auto",
                        metavar="|".join(COLORS),
                        help="colours: auto (Textual detects; NO_COLOR respected), truecolor, "
                             "256, none")
    parser.add_argument("--material", metavar="NAME",
                        help="a MERL material's published fit instead of MODEL (see 'tuibrdf "
                             "materials'): ABC, or SGD with --fit sgd")
    parser.add_argument("--fit", type=choices_type("fit", FITS), default=None,
                        metavar="|".join(FITS), help="with --material: which fit (default abc)")
    parser.add_argument("--compare-fit", action="store_true",
                        help="with --material: the ABC (A) and SGD (B) fits side by side")
    parser.add_argument("--compare-material", metavar="NAME",
                        help="with --material: a second material (B, same fit) side by side")


def material_sides(args: argparse.Namespace):
    """The sides ``--material`` asks for (one, or two in compare mode), or None without it;
    raises UsageError for a bad combination or name."""
    from ..app.state import Side

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
    """The viewer's initial state from the arguments (no Textual); raises UsageError."""
    from ..app.presets import PresetError, apply_loaded, list_presets, load_preset, preset_path
    from ..app.state import COMPARE_PRESETS, Side, ViewerState

    sides = material_sides(args)
    if sides is not None:
        return ViewerState(sides=sides, theta_i=float(args.theta_i))
    name = args.model or "lambert"
    tokens = list(args.param)
    if name.lower().endswith(".binary"):
        if "merl" not in MODELS:
            raise UsageError(f"{name}: MERL files need the 'merl' model, which this build "
                             "does not have yet")
        if not os.path.isfile(name):
            raise UsageError(f"{name}: no such file")
        tokens = [f"file={name}", *tokens]
        name = "merl"
    if name not in MODELS:
        from ..core.models import get_model
        from ..core.params import unknown_message
        from ..core.userfiles import looks_like_path

        if not looks_like_path(name):
            raise UsageError(unknown_message("unknown model", name, list(MODELS)))
        model = get_model(name)  # a user file (.brdf, .bparam, .py, .bsdf): ValueError → exit 2
    else:
        model = MODELS[name]
    values = model.resolve(parse_params(model, tokens))
    state = ViewerState(sides=[Side(model.name, values)], theta_i=float(args.theta_i))
    if args.preset:
        seed = {p.name for p in COMPARE_PRESETS}
        try:
            exists = preset_path(args.preset).is_file()
        except PresetError as e:
            raise UsageError(str(e)) from None
        if exists or args.preset not in seed:
            try:
                theta, sides = load_preset(args.preset)
            except PresetError as e:
                if args.preset not in seed:
                    have = ", ".join(list_presets() + sorted(seed))
                    raise UsageError(f"{e} (available: {have})") from None
                raise UsageError(str(e)) from None
            apply_loaded(state, theta, sides)
        else:
            msg = state.apply_preset(args.preset)
            if msg:
                raise UsageError(msg)
    for side in state.sides:  # a bad MERL file is one line here, not a message in the viewer
        for p in side.spec.params:
            if p.kind == "path":
                check_file(side.values[p.name])
    return state


def run(args: argparse.Namespace) -> int:
    state = build_state(args)
    if args.color == "none":
        os.environ["NO_COLOR"] = "1"
    elif args.color != "auto":
        os.environ["TEXTUAL_COLOR_SYSTEM"] = "truecolor" if args.color == "truecolor" \
            else "256"
    from ..app.app import BrdfApp  # Textual only here

    color = None if args.color == "auto" else args.color
    app = BrdfApp(state, color=color)
    app.run()  # a crash: Textual restores the terminal, prints the error, sets return_code 1
    return app.return_code or 0
