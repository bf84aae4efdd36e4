"""Options shared by the subcommands, and the one-line error policy.

Everything here is generated from the model declarations (:mod:`tuibrdf.core.params`): the
parameter names ``-p`` accepts, their ranges, the close match offered for a typo.  Bad input
raises :class:`UsageError` (or argparse's own error) and ends as one line on stderr, exit 2.

``-p NAME=VALUE`` syntax, per parameter kind:

========  ===========================  ==============================================
kind      VALUE                        examples
========  ===========================  ==============================================
float     a finite real in the range   ``-p kd=0.5``, ``-p sigma=20`` (degrees)
rgb       ``R,G,B`` or one grey value  ``-p color=0.9,0.6,0.2``, ``-p color=0.5``
choice    one of the names             ``-p distribution=ggx`` (case-insensitive)
path      an existing file             ``-p file=gold-metallic-paint.binary``
========  ===========================  ==============================================

The same name given twice: the last one wins (as for most command-line options).
"""

from __future__ import annotations

import argparse
import math
import os
import re
import sys
from collections.abc import Callable, Iterable, Mapping, Sequence

from tuibrdf.core.conventions import fmt_number
from tuibrdf.core.display import DISPLAY

TYPE_CHECKING = False  # typing itself costs --help ≈ 3 ms: for annotations only
if TYPE_CHECKING:  # the declarations import dataclasses and difflib: not for --help
    from typing import Any

    from tuibrdf.core.params import Model, Param


class UsageError(Exception):
    """Bad input from the user: printed as one line, exit status 2."""


def terminal_columns() -> int:
    """The width :func:`shutil.get_terminal_size` gives: ``COLUMNS`` when a positive integer,
    else the terminal's, else 80."""
    try:
        columns = int(os.environ.get("COLUMNS", ""))
    except ValueError:
        columns = 0
    if columns <= 0:
        try:
            columns = os.get_terminal_size(sys.__stdout__.fileno()).columns
        except (AttributeError, ValueError, OSError):  # no stdout, or not a terminal
            columns = 0
    return columns if columns > 0 else 80


class Formatter(argparse.HelpFormatter):
    """argparse's help at the width argparse picks (:func:`terminal_columns`, less 2), found
    without importing :mod:`shutil`, which imports bz2, lzma and zlib: ≈ 4 ms of ``--help``."""

    def __init__(self, *args, **kw) -> None:
        if len(args) < 4 and kw.get("width") is None:
            kw["width"] = terminal_columns() - 2
        super().__init__(*args, **kw)


class Parser(argparse.ArgumentParser):
    """argparse with one-line errors: ``tuibrdf eval: error: ... (see 'tuibrdf eval --help')``
    instead of a usage block, so a log keeps one line per mistake; help by :class:`Formatter`."""

    def __init__(self, *args, **kw) -> None:
        kw.setdefault("formatter_class", Formatter)
        super().__init__(*args, **kw)

    def error(self, message: str):  # noqa: D401 — argparse's hook
        from tuibrdf.cli.text import one_line  # a newline typed in an argument stays escaped

        print(f"{self.prog}: error: {one_line(message)} (see '{self.prog} --help')",
              file=sys.stderr)
        raise SystemExit(2)

    def _print_message(self, message, file=None):  # argparse's writer, which hides OSError
        if message:  # --help > /dev/full must fail loudly (main reports it in one line)
            (file or sys.stderr).write(message)


# --------------------------------------------------------------------------- formatting


def print_json(doc: object, ascii: bool = True) -> None:
    """``doc`` as every ``--json`` prints it: indented, and never a NaN or an infinity (not
    JSON; a number that is one is a bug, raised here rather than printed).  json is imported
    here, not for ``--help``."""
    import json

    print(json.dumps(doc, indent=2, ensure_ascii=ascii, allow_nan=False))


def fmt_params(values: Mapping[str, Any]) -> str:
    """``kd=0.5 ks=0.3 n=20`` — the resolved parameters on one line."""
    return " ".join(f"{k}={fmt_number(v)}" for k, v in values.items())


def json_params(values: Mapping[str, Any]) -> dict[str, Any]:
    """Resolved parameters for JSON (tuples become lists)."""
    return {k: list(v) if isinstance(v, tuple) else v for k, v in values.items()}


# --------------------------------------------------------------------------- numbers

#: a number as typed on a command line: ASCII digits, an optional point and exponent, or the
#: words inf / nan (which the range checks then refuse with the range in the message).
#: Python's float() also takes "1_000", "٣" (Arabic-Indic three), full-width digits and
#: surrounding whitespace: none of that is a number a user means to type here.
NUMBER_RE = re.compile(r"[+-]?(?:(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?"
                       r"|(?i:inf|infinity|nan))")
INTEGER_RE = re.compile(r"[+-]?[0-9]+")


def parse_float(text: str) -> float:
    """``text`` as a float, ASCII syntax only; ``ValueError`` otherwise."""
    if not isinstance(text, str) or not NUMBER_RE.fullmatch(text):
        raise ValueError(f"not a number: {text!r}")
    return float(text)


def parse_int(text: str) -> int:
    """``text`` as an int, ASCII digits only (at most 30 of them); ``ValueError`` otherwise."""
    if not isinstance(text, str) or not INTEGER_RE.fullmatch(text) or len(text) > 30:
        raise ValueError(f"not an integer: {text!r}")
    return int(text)


# --------------------------------------------------------------------------- argparse types


def bounded(name: str, lo: float, hi: float, unit: str = "°") -> Callable[[str], float]:
    """An argparse ``type`` for a finite real in ``[lo, hi]``, with the range in its error."""
    rng = f"[{lo:g}, {hi:g}]{unit}"

    def parse(text: str) -> float:
        try:
            v = parse_float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(
                f"{name} = {text!r} is not a number: expected a value in {rng}"
            ) from None
        if not (math.isfinite(v) and lo <= v <= hi):
            raise argparse.ArgumentTypeError(f"{name} = {text} is out of range: expected {rng}")
        return v

    parse.__name__ = name
    return parse


def setting_type(name: str, setting) -> Callable[[str], float]:
    """:func:`bounded` to a display setting's range (:data:`~tuibrdf.core.display.DISPLAY`):
    the range the viewer's keys keep it in."""
    return bounded(name, setting.lo, setting.hi, setting.unit)


def add_setting(parser: argparse.ArgumentParser, flag: str, setting, metavar: str,
                help: str) -> None:
    """``flag`` for a display setting: its range, and its default in the help."""
    parser.add_argument(flag, type=setting_type(flag[2:], setting), default=setting.default,
                        metavar=metavar, help=f"{help} (default {fmt_number(setting.default)}, "
                                              f"range {setting.range_text()})")


def int_in(name: str, lo: int, hi: int) -> Callable[[str], int]:
    """An argparse ``type`` for an integer in ``[lo, hi]`` (a size: the upper end keeps a typo
    like ``--width 80000`` from allocating gigabytes)."""

    def parse(text: str) -> int:
        try:
            v = parse_int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(
                f"{name} = {text!r} is not an integer: expected {lo} to {hi}"
            ) from None
        if not lo <= v <= hi:
            raise argparse.ArgumentTypeError(f"{name} = {v} is out of range: expected {lo} "
                                             f"to {hi}")
        return v

    parse.__name__ = name
    return parse


#: θr of a viewing direction in the upper hemisphere, in degrees
theta_r_deg = bounded("theta_r", 0.0, 90.0)
#: φr of a viewing direction in degrees (the kernels are periodic; one turn either way)
phi_r_deg = bounded("phi_r", -360.0, 360.0)


# --------------------------------------------------------------------------- shared options


def add_model_args(parser: argparse.ArgumentParser, optional: bool = False) -> None:
    """``MODEL`` (``optional``: may be left out) and ``-p/--param NAME=VALUE`` (repeatable)."""
    parser.add_argument("model", metavar="MODEL", **({"nargs": "?"} if optional else {}),
                        help="model name (see 'tuibrdf models') or a file: .brdf, .bparam, "
                             ".py, .bsdf, .binary")
    parser.add_argument(
        "-p", "--param", action="append", default=[], metavar="NAME=VALUE",
        help="set a parameter (repeatable); RGB as R,G,B or one grey value; "
             "angles in degrees; unset parameters take their defaults",
    )


def resolve(args: argparse.Namespace) -> tuple[Model, dict[str, Any]]:
    """The model named by ``args.model`` and its validated parameters (defaults filled)."""
    model = find_model(args.model)
    return model, model.resolve(parse_params(model, args.param))


def unknown(what: str, name: str, valid: Sequence[str]) -> str:
    """:func:`~tuibrdf.core.params.unknown_message`, whose close match also tries the name
    case-insensitively (``-p M=0.1`` → did you mean 'm'?; difflib alone finds no match for
    a one-letter name in the wrong case)."""
    folded = [v for v in valid if v.casefold() == name.casefold()]
    if folded:
        return f"{what} {name!r} (did you mean {folded[0]!r}?); valid: {', '.join(valid)}"
    from tuibrdf.core.params import unknown_message

    return unknown_message(what, name, valid)


def find_model(name: str) -> Model:
    """The registered model ``name``; :class:`UsageError` with a close match otherwise."""
    from tuibrdf.core.registry import MODELS, get_model  # numpy: only once a command runs

    if isinstance(name, str) and name not in MODELS:
        folded = [m for m in MODELS if m.casefold() == name.casefold()]
        if folded:
            raise UsageError(unknown("unknown model", name, list(MODELS)))
    return get_model(name)


def parse_params(model: Model, tokens: Iterable[str]) -> dict[str, Any]:
    """``["kd=0.5", "color=1,0,0"]`` → ``{"kd": 0.5, "color": (1.0, 0.0, 0.0)}``, each value
    validated against its declaration; :class:`UsageError` names the parameter and its range."""
    names = [p.name for p in model.params]
    out: dict[str, Any] = {}
    for token in tokens:
        name, sep, raw = token.partition("=")
        name = name.strip()
        if not name:
            raise UsageError(f"-p {token!r}: missing parameter name before '='; "
                             f"{model.name} has: {', '.join(names) or '(no parameters)'}")
        if name not in names:
            raise UsageError(unknown(f"{model.name}: unknown parameter", name, names))
        p = model.param(name)
        if not sep:
            raise UsageError(f"-p {token!r}: missing value, expected -p {name}=VALUE with "
                             f"VALUE {p.range_text()}")
        out[name] = parse_value(model, p, raw.strip())
    return out


def parse_value(model: Model, p: Param, raw: str) -> Any:
    """One ``-p`` value, validated: raises :class:`UsageError`."""
    if p.kind == "choice" and p.choice(raw) is None:
        raise UsageError(p.unknown_choice(raw, model.name))
    if p.kind == "path":
        from tuibrdf.core.formats.files import describe

        problem = describe(raw) if raw else "empty file name"
        if problem:  # "no such file", "is a directory, not a regular file", ...
            raise UsageError(f"{model.name}: {p.name} = {raw!r}: {problem}")
    value: Any = raw
    if p.kind in ("float", "rgb"):
        parts = raw.split(",") if p.kind == "rgb" else [raw]
        try:
            nums = [parse_float(x.strip()) for x in parts]
        except ValueError:
            nums = None  # keep the text so the error shows what was typed
        if nums is None:
            grey = " or one grey value" if p.kind == "rgb" else ""
            raise UsageError(f"{model.name}: {p.name} = {raw!r} is invalid: expected "
                             f"{p.range_text()}{grey}")
        # one grey value: validate() repeats a number over R, G, B
        value = nums[0] if len(nums) == 1 else tuple(nums)
    try:
        return p.validate(value, model.name)
    except ValueError as e:
        grey = " or one grey value" if p.kind == "rgb" else ""
        raise UsageError(f"{e}{grey}") from None


def add_phi_i(parser: argparse.ArgumentParser) -> None:
    """``--phi-i DEG``: the light's azimuth (:data:`DISPLAY`: 180°, the seed's, in ±360°)."""
    s = DISPLAY.phi_i
    parser.add_argument("--phi-i", type=setting_type("phi_i", s), default=s.default,
                        metavar="DEG", help=f"light azimuth φi in degrees (default "
                                            f"{fmt_number(s.default)}: the light on the −x "
                                            "side, as in the source document)")


#: the incidences a command that tabulates over θi prints when none are given: every 15°, and
#: 89° for grazing light (90° itself is a limit: no light arrives)
DEFAULT_THETAS = (0.0, 15.0, 30.0, 45.0, 60.0, 75.0, 89.0)


def add_theta_i(parser: argparse.ArgumentParser, *, many: bool = False,
                default: Any = None) -> None:
    """``--theta-i DEG`` (or ``DEG [DEG ...]`` with ``many``), in :data:`DISPLAY`'s range of
    θi, [0, 90]°; without a ``default`` the option is required."""
    s = DISPLAY.theta_i
    kw: dict[str, Any] = {"nargs": "+"} if many else {}
    if default is None:
        kw["required"] = True
    else:
        kw["default"] = default
    rng = f"[{s.lo:g}, {s.hi:g}]"
    parser.add_argument("--theta-i", type=setting_type("theta_i", s), metavar="DEG",
                        help=(f"incidence angles θi in degrees, each in {rng}" if many
                              else f"incidence angle θi in degrees, in {rng}")
                             + ("" if default is None else f" (default: {fmt_number(default)})"),
                        **kw)


def choices_type(name: str, valid: Sequence[str]) -> Callable[[str], str]:
    """An argparse ``type`` for one of ``valid``, with a close match for a typo."""

    def parse(text: str) -> str:
        if text in valid:
            return text
        raise argparse.ArgumentTypeError(unknown(f"unknown {name}", text, list(valid)))

    parse.__name__ = name
    return parse


def isatty(stream: Any) -> bool:
    """Whether ``stream`` is a terminal; ``False`` for ``None``, an object without
    ``isatty`` and a closed or broken stream (which raise rather than answer)."""
    check = getattr(stream, "isatty", None)
    try:
        return bool(check is not None and check())
    except (OSError, ValueError):
        return False
