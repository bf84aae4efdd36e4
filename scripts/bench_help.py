"""Time ``tuibrdf --help`` (and an argument error), the start-up a user waits for.

    python scripts/bench_help.py [--repeat N]

Runs each command ``N`` times as a fresh ``python -m tuibrdf`` process (the tuibrdf on
``PYTHONPATH``) and prints the median and minimum wall time, next to a bare ``python -c pass``
(the interpreter's own start-up), and the modules that cost most, from ``python -X importtime``.
The package's bytecode is written first (:func:`fresh_bytecode`), as an install or a first run
writes it.  docs/app.md quotes the numbers.
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import time

COMMANDS = {
    "python -c pass": [sys.executable, "-c", "pass"],
    "tuibrdf --help": [sys.executable, "-m", "tuibrdf", "--help"],
    "tuibrdf eval --help": [sys.executable, "-m", "tuibrdf", "eval", "--help"],
    "tuibrdf eval (argument error)": [sys.executable, "-m", "tuibrdf", "eval", "phong",
                                      "--theta-i", "99", "--theta-r", "0", "--phi-r", "0"],
}


def fresh_bytecode(env: dict | None = None) -> None:
    """Write the bytecode of the tuibrdf that ``python -m tuibrdf`` imports (with ``env``).  A
    user's runs read it; with ``PYTHONDONTWRITEBYTECODE`` set and the bytecode older than the
    sources (a checkout), every timed run would compile every module it imports: ≈ 20 ms of
    ``tuibrdf --help`` on this machine."""
    code = ("import compileall, os, tuibrdf\n"
            "compileall.compile_dir(os.path.dirname(tuibrdf.__file__), quiet=1)")
    subprocess.run([sys.executable, "-c", code], check=True, env=env or os.environ)


def wall(cmd: list[str], repeat: int) -> tuple[list[float], list[float]]:
    """Wall times and CPU times (user + system of the child): on a shared, loaded machine the
    CPU time is the steadier of the two."""
    out, cpu = [], []
    for _ in range(repeat):
        r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
        t = time.perf_counter()
        subprocess.run(cmd, capture_output=True, env=os.environ)
        out.append(time.perf_counter() - t)
        r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu.append(r1.ru_utime - r0.ru_utime + r1.ru_stime - r0.ru_stime)
    return out, cpu


def top_imports(n: int = 6) -> list[tuple[int, str]]:
    p = subprocess.run([sys.executable, "-X", "importtime", "-m", "tuibrdf", "--help"],
                       capture_output=True, text=True, env=os.environ)
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
    a = ap.parse_args()
    fresh_bytecode()
    print(f"| command | wall median ms | wall min ms | CPU median ms |  ({a.repeat} runs each)")
    print("|---|---|---|---|")
    for label, cmd in COMMANDS.items():
        wall(cmd, 2)  # warm the page cache
        t, c = wall(cmd, a.repeat)
        print(f"| `{label}` | {1000 * statistics.median(t):.0f} | {1000 * min(t):.0f} | "
              f"{1000 * statistics.median(c):.0f} |")
    print("\nslowest top-level imports of `tuibrdf --help` (python -X importtime, µs):")
    for cum, name in top_imports():
        print(f"  {cum:>8}  {name}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
