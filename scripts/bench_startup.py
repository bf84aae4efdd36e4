"""The viewer's start-up: spawn → its first frame (the map's colour bar unit ``sr⁻¹``) and →
its complete screen (the last byte before the terminal stays quiet: whatever comes after
the picture) in a pseudo-terminal, as ``scripts/bench_app.py`` measures it, repeated.

    python scripts/bench_startup.py [--runs 12] [--size 160x48] [--against REV] [--rate B/S]
                                    [--write-docs]

Beside it, in every round, a minimal Textual app (one ``Static``, its text the marker waited
for): the floor any Textual program starts from on this machine, and the ratio to it; and
the same app importing numpy first: the floor of a Textual program that computes with
numpy, as the viewer's first frame does.
``--rate B/S`` reads the terminal at that many bytes a second (a slow link: 125000 is
1 Mbit/s), each read then waiting for its bytes to pass, and adds the bytes read per program.
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
import time

from bench_app import IDLE_S, ROOT, Term, seen_in
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
#: the floor of a program that needs numpy for its first screen
NUMPY_APP = "import numpy  # noqa: F401\n" + MINIMAL_APP


def timed(term: Term, marker: bytes, rate: float | None = None
          ) -> tuple[float, float, int]:
    """Seconds from the spawn to ``marker`` and to the complete screen (the last byte
    before :data:`bench_app.IDLE_S` of quiet: what comes after the picture), and the bytes
    read; the terminal read at ``rate`` bytes a second (None: as fast as they come)."""
    try:
        if rate is None:
            seen = term.until(marker)
            return seen - term.t0, max(seen, term.drain()) - term.t0, term.sent_since_key
        seen, last, tail = None, term.t0, b""
        while (got := term.read(IDLE_S if seen else 20.0, 4096)) is not None:
            time.sleep(len(got[1]) / rate)  # the bytes passing the link
            last = time.perf_counter()
            if seen is None:
                found, tail = seen_in(marker, tail, got[1])
                if found:
                    seen = last
        if seen is None:
            raise TimeoutError(f"no {marker!r}")
        return seen - term.t0, last - term.t0, term.sent_since_key
    finally:
        term.close()


def minimal_frame(script: str, w: int, h: int, rate: float | None = None
                  ) -> tuple[float, float, int]:
    return timed(Term(w, h, "truecolor", [], command=[sys.executable, script]),
                 b"minimal app ready", rate)


def first_frame(tree: str, w: int, h: int, rate: float | None = None
                ) -> tuple[float, float, int]:
    return timed(Term(w, h, "truecolor", ["phong", "--theta-i", "0"], root=tree),
                 "sr⁻¹".encode(), rate)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=12)
    ap.add_argument("--size", default="160x48")
    ap.add_argument("--against", metavar="REV")
    ap.add_argument("--rate", type=float, metavar="B/S",
                    help="read the terminal at this many bytes a second (a slow link)")
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
        floor, with_numpy = "a minimal Textual app", "the same, importing numpy first"
        scripts = {}
        for name, text in ((floor, MINIMAL_APP), (with_numpy, NUMPY_APP)):
            scripts[name] = os.path.join(tmp, f"app{len(scripts)}.py")
            with open(scripts[name], "w", encoding="utf-8") as f:
                f.write(text)
        times: dict[str, list[tuple[float, float]]] = {name: [] for name in [*scripts, *trees]}
        for _ in range(a.runs):
            for name, script in scripts.items():
                times[name].append(minimal_frame(script, w, h, a.rate))
            for name, tree in trees.items():
                times[name].append(first_frame(tree, w, h, a.rate))
    base = [statistics.median(t[k] for t in times[floor]) for k in (0, 1)]
    link = (f", the terminal read at {8 * a.rate / 1e6:g} Mbit/s" if a.rate else "")
    lines = [f"start-up, {w}×{h}{link}, {a.runs} runs each: ms from the spawn to the first "
             "frame (the picture's marker) and to the complete screen (then quiet for "
             f"{1e3 * IDLE_S:.0f} ms), median (min), and the bytes written:", "",
             "| program | first frame | / minimal app's | complete screen | / minimal app's "
             "| kB |", "|---|---|---|---|---|---|"]
    for name, t in times.items():
        cells = []
        for k in (0, 1):
            m = statistics.median(x[k] for x in t)
            cells += [f"{1e3 * m:.0f} ({1e3 * min(x[k] for x in t):.0f})", f"{m / base[k]:.2f}"]
        cells.append(f"{statistics.median(x[2] for x in t) / 1e3:.1f}")
        lines.append(f"| {name} | " + " | ".join(cells) + " |")
    print("\n".join(lines))
    if a.write_docs:
        section = "bench_startup" + ("-slow-link" if a.rate else "")
        doc = write_section(section, "\n".join(lines), command_line(),
                            machine_line=started)
        print(f"written into {doc}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
