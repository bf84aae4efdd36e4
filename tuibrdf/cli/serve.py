"""``tuibrdf serve``: the viewer in a web browser, through textual-serve (the ``[web]`` extra).

``tuibrdf serve [MODEL|FILE ...] [-p NAME=VALUE ...] [--host 127.0.0.1] [--port 8000]
[--data-dir DIR] [--allow-python]``.  textual-serve runs one command per browser connection,
here ``python -m tuibrdf view FIRST -p ...`` with Textual's web driver, so each tab has its own
viewer process.  The first MODEL opens (with the ``-p`` values); the other model files are one
``m`` away.  Everything is validated here first, so a bad argument is one line and exit 2 before
anything listens.

textual-serve has no authentication: serve binds to 127.0.0.1 by default (reach it from another
machine through ``ssh -L 8000:localhost:8000 server``) and warns when told to bind elsewhere.  A
served viewer opens only the files named here and those under ``--data-dir``, and no Python
model file unless ``--allow-python`` (:mod:`tuibrdf.state.sandbox`, handed to the viewer
processes in an environment variable).
"""

from __future__ import annotations

import argparse
import ipaddress
import os
import shlex
import sys

from tuibrdf.cli.common import Parser, UsageError

DEFAULT_PORT = 8000


def add_args(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("model", nargs="*", metavar="MODEL|FILE",
                        help="what the viewer opens: a model name or a file, as for 'tuibrdf "
                             "view' (default: lambert); further model files are one 'm' away")
    parser.add_argument("-p", "--param", action="append", default=[], metavar="NAME=VALUE",
                        help="set a parameter of the first MODEL (repeatable)")
    parser.add_argument("--host", default="127.0.0.1",
                        help="address to listen on (default 127.0.0.1: this machine only; "
                             "anything else is reachable without a password)")
    parser.add_argument("--port", type=_port, default=DEFAULT_PORT,
                        help=f"port to listen on (default {DEFAULT_PORT})")
    parser.add_argument("--data-dir", metavar="DIR",
                        help="the viewer may also open files under DIR (default: only the "
                             "files named here)")
    parser.add_argument("--allow-python", action="store_true",
                        help="let the viewer run Python model files (.py): they run code on "
                             "this machine")


def _port(text: str) -> int:
    try:
        port = int(text)
    except ValueError:
        port = -1
    if not 0 < port < 65536:
        raise argparse.ArgumentTypeError(f"port {text!r} is invalid: expected 1 to 65535")
    return port


def loopback(host: str) -> bool:
    if host == "localhost":
        return True
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        return False


def viewer_command(args: argparse.Namespace) -> list[str]:
    """The command textual-serve runs per connection (before shell quoting)."""
    command = [sys.executable, "-m", "tuibrdf", "view"]
    if args.model:
        command.append(os.path.abspath(args.model[0]) if _is_file(args.model[0])
                       else args.model[0])
    for p in args.param:
        command += ["-p", p]
    return command


def _is_file(name: str) -> bool:
    from tuibrdf.core.formats.userfiles import looks_like_path
    from tuibrdf.core.registry import MODELS

    return name not in MODELS and looks_like_path(name)


def policy_for(args: argparse.Namespace):
    """Validate the arguments as ``view`` would (one line, exit 2) and return the policy of
    the served viewers: the files named here, ``--data-dir``, ``--allow-python``."""
    from tuibrdf.cli import view
    from tuibrdf.state.sandbox import Policy

    if args.data_dir is not None and not os.path.isdir(args.data_dir):
        raise UsageError(f"--data-dir {args.data_dir}: not a directory")
    models = args.model or [None]
    files: list[str] = []
    for i, name in enumerate(models):
        if name is not None and _is_file(name):
            if name.lower().endswith(".py") and not args.allow_python:
                raise UsageError(f"{name}: a Python model file runs code in every served "
                                 "viewer: add --allow-python to serve it")
            files.append(name)
        parser = Parser(prog="tuibrdf serve")
        view.add_args(parser)
        argv = [name] if name is not None else []
        if i == 0:
            argv += [f"--param={p}" for p in args.param]
        state = view.build_state(parser.parse_args(argv))  # UsageError, ValueError: exit 2
        files += [str(side.values[p.name]) for side in state.sides for p in side.spec.params
                  if p.kind == "path" and side.values[p.name]]
    others = [os.path.abspath(n) for n in args.model[1:] if _is_file(n)
              and not n.lower().endswith(".binary")]
    return Policy.make(args.data_dir, files, args.allow_python, others)


def run(args: argparse.Namespace) -> int:
    try:
        from textual_serve.server import Server
    except ImportError:
        raise UsageError("serve needs textual-serve: pip install 'tuibrdf[web]'") from None
    from tuibrdf.state.sandbox import ENV

    policy = policy_for(args)
    if not loopback(args.host):
        print(f"tuibrdf: warning: listening on {args.host}: textual-serve has no "
              "authentication, so anyone who can reach this port gets a viewer (the default "
              f"127.0.0.1 and 'ssh -L {args.port}:localhost:{args.port} SERVER' keep it "
              "private)", file=sys.stderr, flush=True)
    os.environ[ENV] = policy.to_json()  # textual-serve passes its environment to each viewer
    server = Server(shlex.join(viewer_command(args)), host=args.host, port=args.port,
                    title="tuibrdf")
    try:
        server.serve()
    except OSError as e:  # the port is taken, the address is not this machine's
        # aiohttp's message repeats the address before the reason: the reason
        why = str(e.strerror or e).rsplit(": ", 1)[-1]
        raise UsageError(f"cannot listen on {args.host}:{args.port}: {why}") from None
    return 0
