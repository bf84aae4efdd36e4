"""The viewer's start-up: spawn → its first frame (the map's colour bar unit ``sr⁻¹``) in a
pseudo-terminal, as ``scripts/bench_app.py`` measures it, repeated.

    python scripts/bench_startup.py [--runs 12] [--size 160x48] [--against REV] [--write-docs]

Beside it, in every round, a minimal Textual app (one ``Static``, its text the marker waited
for): the floor any Textual program starts from on this machine, and the ratio to it.
``--against REV`` starts git revision REV's viewer (``git archive``) too, the two trees one
after the other in every round, so a slow spell of the machine falls on both.  The package's
bytecode is written first (as an install or a first run writes it).  Prints the median and the
minimum per tree; ``--write-docs`` also writes that table into docs/benchmarks.md
(scripts/benchdoc.py: its own section, with the command, the machine and the date).
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import tempfile

from bench_app import ROOT, Term
from bench_help import fresh_bytecode
from benchdoc import command_line, machine, write_section
from revtree import extract

#: the floor: a Textual app showing one line of text
MINIMAL_APP = """
from textual.app import App
from textual.widgets import Static


class Minimal(App):
    def compose(self):
        yield Static("minimal app ready")


Minimal().run()
"""


def minimal_frame(script: str, w: int, h: int) -> float:
    term = Term(w, h, "truecolor", [], command=[sys.executable, script])
    try:
        return term.until(b"minimal app ready") - term.t0
    finally:
        term.close()


def first_frame(tree: str, w: int, h: int) -> float:
    term = Term(w, h, "truecolor", ["phong", "--theta-i", "0"], root=tree)
    try:
        return term.until("sr⁻¹".encode()) - term.t0
    finally:
        term.close()


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=12)
    ap.add_argument("--size", default="160x48")
    ap.add_argument("--against", metavar="REV")
    ap.add_argument("--write-docs", action="store_true",
                    help="also write the table into docs/benchmarks.md (its own section)")
    a = ap.parse_args()
    started = machine()
    w, h = (int(v) for v in a.size.split("x"))
    with tempfile.TemporaryDirectory() as tmp:
        trees = {"this tree": str(ROOT)}
        if a.against:
            trees = {a.against: extract(a.against, tmp), **trees}
        for tree in trees.values():
            fresh_bytecode({k: v for k, v in os.environ.items()
                            if k != "PYTHONDONTWRITEBYTECODE"} | {"PYTHONPATH": tree})
        script = os.path.join(tmp, "minimal_app.py")
        with open(script, "w", encoding="utf-8") as f:
            f.write(MINIMAL_APP)
        floor = "a minimal Textual app"
        times: dict[str, list[float]] = {name: [] for name in [floor, *trees]}
        for _ in range(a.runs):
            times[floor].append(minimal_frame(script, w, h))
            for name, tree in trees.items():
                times[name].append(first_frame(tree, w, h))
    base = statistics.median(times[floor])
    lines = [f"start-up to the first frame, {w}×{h}, {a.runs} runs each:", "",
             "| program | median ms | min ms | median / minimal app's |", "|---|---|---|---|"]
    lines += [f"| {name} | {1e3 * statistics.median(t):.0f} | {1e3 * min(t):.0f} | "
              f"{statistics.median(t) / base:.2f} |" for name, t in times.items()]
    print("\n".join(lines))
    if a.write_docs:
        doc = write_section("bench_startup", "\n".join(lines), command_line(),
                            machine_line=started)
        print(f"written into {doc}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
