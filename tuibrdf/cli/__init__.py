"""Command line: ``main(argv=None) -> int``.

One module per subcommand, each exposing ``add_args(parser)`` and ``run(args) -> int``
(meshio's layout).  Nothing here imports textual; ``view`` imports the app only to open it.
"""

from __future__ import annotations

import argparse
import importlib
import os
import sys
from collections.abc import Collection

from tuibrdf import __version__
from tuibrdf.cli import text
from tuibrdf.cli.common import Parser, UsageError, isatty, unknown
from tuibrdf.cli.memory import keep_freed_memory

#: (name, module, one-line help) — the order of ``tuibrdf --help``; the module is
#: ``tuibrdf.cli.<module>``, imported when its command runs (:func:`build_parser`)
SUBCOMMANDS = [
    ("models", "models", "list the models and their parameters"),
    ("materials", "materials", "list the 100 MERL materials of the abc and sgd fits"),
    ("eval", "eval", "print BRDF values for given directions"),
    ("albedo", "albedo", "print the directional albedo a(θi)"),
    ("energy", "energy", "print the albedo table E(μ, p) for energy compensation"),
    ("check", "check", "check a BRDF: finite, positive, reciprocal, energy, sampling (CI)"),
    ("compare", "compare", "how far apart two BRDFs are: albedos, rel_l2, largest difference"),
    ("render", "render", "print a picture of the BRDF (deterministic, for docs and tests)"),
    ("fit", "fit", "fit an analytic model to a measured MERL file"),
    ("view", "view", "open the interactive viewer (the default with no arguments)"),
    ("serve", "serve", "serve the viewer to a web browser (needs tuibrdf[web])"),
]


def build_parser(commands: Collection[str] | None = None) -> argparse.ArgumentParser:
    """The command line, with the arguments of ``commands`` (None: of every command); the
    others are listed with their help only.  Declaring every command's arguments costs
    ``tuibrdf --help`` ≈ 20 ms (argparse formats and translates each one), and the line
    names one command at most."""
    parser = Parser(prog="tuibrdf", description="A terminal BRDF viewer.")
    parser.add_argument("--version", action="version", version=f"tuibrdf {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND",
                                parser_class=Parser)
    for name, module_name, help_text in SUBCOMMANDS:
        p = sub.add_parser(name, help=help_text, description=help_text)
        if commands is None or name in commands:
            module = importlib.import_module(f"{__name__}.{module_name}")
            module.add_args(p)
            p.set_defaults(run=module.run)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Run the command line; returns the exit status.

    0 success; 2 bad input (one line on stderr, no traceback); 1 the output could not be
    written (closed stdout, full disk: one line); 141 the reader of a pipe left; 130 Ctrl-C;
    70 an internal error (one line; ``TUIBRDF_DEBUG=1`` shows the traceback).
    """
    text.install()  # a Latin-1 or ASCII locale gets ASCII stand-ins, not UnicodeEncodeError
    if sys.stdout is None:  # started with stdout closed (`tuibrdf ... >&-`)
        _error("standard output is closed: nothing can be printed")
        return 1
    try:
        return _main(argv)
    except KeyboardInterrupt:
        return 130
    except BrokenPipeError:  # `tuibrdf models | head`: the reader left; no traceback
        return _broken_pipe()
    except OSError as e:  # writing the output failed (/dev/full, a closed stream)
        where = f"{e.filename}: " if e.filename else "cannot write output: "
        _error(f"{where}{e.strerror or e}")
        _silence_stdout()
        return 1
    except MemoryError:
        _error("out of memory")
        return 1
    except Exception as e:  # a bug: one line here, the traceback on request
        if os.environ.get("TUIBRDF_DEBUG"):
            raise
        _error(f"internal error: {type(e).__name__}: {e} (TUIBRDF_DEBUG=1 shows the "
               "traceback; please report it)")
        return 70


#: the options of ``tuibrdf`` itself; any other before a command belongs to ``view``
TOP_OPTIONS = ("-h", "--help", "--version")


def _main(argv: list[str] | None) -> int:
    argv = sys.argv[1:] if argv is None else list(argv)
    if not argv and isatty(sys.stdin) and isatty(sys.stdout):
        argv = ["view"]  # plain `tuibrdf` in a terminal opens the viewer (else: the help)
    if argv and argv[0].startswith("-") and argv[0] not in TOP_OPTIONS:
        argv = ["view", *argv]  # `tuibrdf --color none`: options of the default command
    commands = [name for name, _, _ in SUBCOMMANDS]
    first = next((a for a in argv if not a.startswith("-")), None)
    if first is not None and first not in commands:  # a typo gets a close match
        _error(unknown("unknown command", first, commands))
        return 2
    parser = build_parser([first] if first is not None else [])
    try:
        args = parser.parse_args(argv)
    except SystemExit as e:  # --help (0) or a one-line argparse error (2)
        code = e.code if isinstance(e.code, int) else 2
        if code == 0:
            sys.stdout.flush()  # a write error of the help is reported here, not at exit
        return code
    if args.command is None:
        parser.print_help()
        sys.stdout.flush()
        return 0
    keep_freed_memory()  # (cli/memory.py: numpy's temporaries reuse their pages)
    try:
        code = args.run(args)
        sys.stdout.flush()
        if _reader_left():
            raise BrokenPipeError  # part of the output never reached the reader: 141
        return code
    except (UsageError, ValueError, OverflowError) as e:
        _error(str(e))
        return 2


def _error(message: str) -> None:
    """``tuibrdf: error: MESSAGE`` on stderr, always one line (control characters escaped)."""
    if sys.stderr is None:
        return
    try:
        print(f"tuibrdf: error: {text.one_line(message)}", file=sys.stderr, flush=True)
    except (OSError, ValueError):  # stderr is gone too: the exit status says it
        pass


def _silence_stdout() -> None:
    # Python flushes stdout again at exit and would print a second error: point stdout at
    # /dev/null first (the recipe in the `signal` module's documentation)
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError, AttributeError):
        pass


def _reader_left() -> bool:
    """stdout is a pipe whose reader has gone (``render | head``).  Checked once the output is
    written, because a large write cut short by the reader leaving can end without an error
    (CPython's buffered writer takes the partial count and drops the rest): POLLERR on the
    pipe's write end says the reader closed it."""
    import select
    import stat

    try:
        fd = sys.stdout.fileno()
        if not hasattr(select, "poll") or not stat.S_ISFIFO(os.fstat(fd).st_mode):
            return False
        poll = select.poll()
        poll.register(fd, select.POLLOUT)
        return any(ev & select.POLLERR for _, ev in poll.poll(0))
    except (OSError, ValueError, AttributeError):  # not a real file (tests), closed
        return False


def _broken_pipe() -> int:
    _silence_stdout()
    return 141  # 128 + SIGPIPE, what a C tool killed by the signal reports
