"""Time ``tuibrdf --help`` (and an argument error), the start-up a user waits for.

    python scripts/bench_help.py [--repeat N] [--no-site] [--against REV]

Runs each command ``N`` times as a fresh ``python -m tuibrdf`` process and prints the median
and minimum wall time and the median CPU time, next to a bare ``python -c pass`` (the
interpreter's own start-up), and the modules that cost most, from ``python -X importtime``.
The package's bytecode is written first (:func:`fresh_bytecode`), as an install or a first run
writes it.

* ``--no-site``: every command with ``python -S`` and this tree on ``PYTHONPATH``: the
  package's own share, without the ``.pth`` hooks that installed packages (and a sandbox)
  put in ``site``;
* ``--against REV``: the same commands on git revision REV (``git archive``) too, the two
  trees alternating run by run, so a machine's slow spell falls on both.

docs/benchmarks.md has the numbers.
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

from revtree import extract

ROOT = Path(__file__).resolve().parent.parent

COMMANDS = {
    "python -c pass": ["-c", "pass"],
    "tuibrdf --help": ["-m", "tuibrdf", "--help"],
    "tuibrdf eval --help": ["-m", "tuibrdf", "eval", "--help"],
    "tuibrdf eval (argument error)": ["-m", "tuibrdf", "eval", "phong", "--theta-i", "99",
                                      "--theta-r", "0", "--phi-r", "0"],
}


def fresh_bytecode(env: dict | None = None) -> None:
    """Write the bytecode of the tuibrdf that ``python -m tuibrdf`` imports (with ``env``).  A
    user's runs read it; with ``PYTHONDONTWRITEBYTECODE`` set and the bytecode older than the
    sources (a checkout), every timed run would compile every module it imports: ≈ 20 ms of
    ``tuibrdf --help`` on this machine."""
    code = ("import compileall, os, tuibrdf\n"
            "compileall.compile_dir(os.path.dirname(tuibrdf.__file__), quiet=1)")
    # (not from the current directory, whose tuibrdf would come before PYTHONPATH's)
    subprocess.run([sys.executable, "-c", code], check=True, env=env or os.environ,
                   cwd=tempfile.gettempdir())


def run_once(cmd: list[str], env: dict) -> tuple[float, float]:
    """Wall and CPU time (user + system of the child) of one run: on a shared, loaded machine
    the CPU time is the steadier of the two."""
    import time

    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t = time.perf_counter()
    subprocess.run(cmd, capture_output=True, env=env, cwd=tempfile.gettempdir())
    wall = time.perf_counter() - t
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, r1.ru_utime - r0.ru_utime + r1.ru_stime - r0.ru_stime


def top_imports(env: dict, flags: list[str], n: int = 6) -> list[tuple[int, str]]:
    p = subprocess.run([sys.executable, *flags, "-X", "importtime", "-m", "tuibrdf", "--help"],
                       capture_output=True, text=True, env=env, cwd=tempfile.gettempdir())
    rows = []
    for line in p.stderr.splitlines():
        if not line.startswith("import time:") or "cumulative" in line:
            continue
        parts = line.replace("import time:", "").split("|")
        cum, name = int(parts[1]), parts[2].rstrip()
        if not name.startswith("  "):  # top-level imports only
            rows.append((cum, name.strip()))
    return sorted(rows, reverse=True)[:n]


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeat", type=int, default=20)
    ap.add_argument("--no-site", action="store_true")
    ap.add_argument("--against", metavar="REV")
    a = ap.parse_args()
    flags = ["-S"] if a.no_site else []
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    trees = {"this tree": dict(env, PYTHONPATH=str(ROOT))}
    tmp = None
    if a.against:
        tmp = tempfile.TemporaryDirectory()
        trees = {a.against: dict(env, PYTHONPATH=extract(a.against, tmp.name)), **trees}
    for tree_env in trees.values():
        fresh_bytecode(tree_env)
    rows = [(label, tree, [sys.executable, *flags, *args])
            for label, args in COMMANDS.items()
            for tree in (trees if args[0] == "-m" else list(trees)[-1:])]
    times: dict[tuple[str, str], list[tuple[float, float]]] = {(lab, t): [] for lab, t, _ in rows}
    for _ in range(2):  # warm the page cache
        for _label, tree, cmd in rows:
            run_once(cmd, trees[tree])
    for _ in range(a.repeat):  # every row once a round: a slow spell falls on all of them
        for label, tree, cmd in rows:
            times[label, tree].append(run_once(cmd, trees[tree]))
    print(f"| command | tree | wall median ms | wall min ms | CPU median ms |  ({a.repeat} runs "
          f"each{', python -S' if a.no_site else ''})")
    print("|---|---|---|---|---|")
    for (label, tree), got in times.items():
        wall, cpu = [w for w, _ in got], [c for _, c in got]
        print(f"| `{label}` | {tree if label != 'python -c pass' else '—'} | "
              f"{1000 * statistics.median(wall):.0f} | {1000 * min(wall):.0f} | "
              f"{1000 * statistics.median(cpu):.0f} |")
    print("\nslowest top-level imports of `tuibrdf --help`, this tree (python -X importtime, µs):")
    for cum, name in top_imports(trees["this tree"], flags):
        print(f"  {cum:>8}  {name}")
    if tmp is not None:
        tmp.cleanup()
    return 0


if __name__ == "__main__":
    sys.exit(main())
