"""Command line: ``main(argv=None) -> int``.

One module per subcommand, each exposing ``add_args(parser)`` and ``run(args) -> int``
(meshio's layout).  Nothing here imports textual; ``view`` imports the app only to open it.
"""

from __future__ import annotations

import argparse
import os
import sys

from .. import __version__
from ..core.params import unknown_message
from . import albedo as _albedo
from . import eval as _eval
from . import fit as _fit
from . import materials as _materials
from . import models as _models
from . import render as _render
from . import view as _view
from .common import Parser, UsageError

#: (name, module, one-line help) — the order of ``tuibrdf --help``
SUBCOMMANDS = [
    ("models", _models, "list the models and their parameters"),
    ("materials", _materials, "list the 100 MERL materials of the abc and sgd fits"),
    ("eval", _eval, "print BRDF values for given directions"),
    ("albedo", _albedo, "print the directional albedo a(θi)"),
    ("render", _render, "print a picture of the BRDF (deterministic, for docs and tests)"),
    ("fit", _fit, "fit an analytic model to a measured MERL file"),
    ("view", _view, "open the interactive viewer (the default with no arguments)"),
]


def build_parser() -> argparse.ArgumentParser:
    parser = Parser(prog="tuibrdf", description="A terminal BRDF viewer.")
    parser.add_argument("--version", action="version", version=f"tuibrdf {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND",
                                parser_class=Parser)
    for name, module, help_text in SUBCOMMANDS:
        p = sub.add_parser(name, help=help_text, description=help_text)
        module.add_args(p)
        p.set_defaults(run=module.run)
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    argv = sys.argv[1:] if argv is None else list(argv)
    if not argv and sys.stdin.isatty() and sys.stdout.isatty():
        argv = ["view"]  # plain `tuibrdf` in a terminal opens the viewer (else: the help)
    commands = [name for name, _, _ in SUBCOMMANDS]
    first = next((a for a in argv if not a.startswith("-")), None)
    if first is not None and first not in commands:  # a typo gets a close match
        print(f"tuibrdf: error: {unknown_message('unknown command', first, commands)}",
              file=sys.stderr)
        return 2
    try:
        args = parser.parse_args(argv)
    except SystemExit as e:  # --help (0) or a one-line argparse error (2)
        return e.code if isinstance(e.code, int) else 2
    if args.command is None:
        parser.print_help()
        return 0
    try:
        return args.run(args)
    except (UsageError, ValueError) as e:
        print(f"tuibrdf: error: {e}", file=sys.stderr)
        return 2
    except BrokenPipeError:  # `tuibrdf models | head`: the reader left; no traceback
        return _broken_pipe()


def _broken_pipe() -> int:
    # Python flushes stdout again at exit and would print a second BrokenPipeError: point
    # stdout at /dev/null first (the recipe in the `signal` module's documentation)
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, sys.stdout.fileno())
    return 141  # 128 + SIGPIPE, what a C tool killed by the signal reports
