"""Command line: ``main(argv=None) -> int``.

One module per subcommand, each exposing ``add_args(parser)`` and ``run(args) -> int``
(meshio's layout).  Nothing here imports textual; ``view`` imports the app only to open it.
"""

from __future__ import annotations

import argparse
import sys

from . import models as _models

#: (name, module, one-line help) — the order of ``tuibrdf --help``
SUBCOMMANDS = [
    ("models", _models, "list the models and their parameters"),
]


class UsageError(Exception):
    """Bad input from the user: printed as one line, exit status 2."""


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="tuibrdf", description="A terminal BRDF viewer.")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for name, module, help_text in SUBCOMMANDS:
        p = sub.add_parser(name, help=help_text, description=help_text)
        module.add_args(p)
        p.set_defaults(run=module.run)
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if args.command is None:
        parser.print_help()
        return 0
    try:
        return args.run(args)
    except (UsageError, ValueError) as e:
        print(f"tuibrdf: error: {e}", file=sys.stderr)
        return 2
