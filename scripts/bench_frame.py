"""The core's cost of one viewer frame, per model: what a key asks of the numbers before
anything is drawn (issue 16).

The request is the one the viewer makes at 160×48 on the map view: the 88×84-pixel Lambert
map, both cross-sections, the peak and the albedo with its error estimate
(``core_frame.compute_frame``).  Every model's defaults at θi = 30°, 60°, 85° and 89.9°; each
repetition asks for a θi never asked before (θi − k·0.001°, so no cache answers).  Process
CPU time, median of ``--reps`` after a first round that warms imports, caches and the heap.
``--rev REV`` runs the same in a subprocess on git revision REV (``git archive``).  ``--idle S``
sleeps S seconds before each timed frame, as between two keys of a user: a frame computed
after the process was idle takes longer than one computed right after another (the CPU's
caches hold other work by then; docs/benchmarks.md).

Usage: ``python scripts/bench_frame.py [--reps 15] [--rev b3f6b82] [--idle 0.15]``.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

from revtree import extract

ROOT = Path(__file__).resolve().parent.parent
THETAS = (30.0, 60.0, 85.0, 89.9)
CHILD = r"""
import json, statistics, sys, time
from tuibrdf.core.views import frame as core_frame
from tuibrdf.core.material import Material
from tuibrdf.core.registry import MODELS
reps, idle = int(sys.argv[1]), float(sys.argv[3])
out = {}
for rnd in range(2):  # the first round warms imports, caches and the heap; the second counts
    for name, model in MODELS.items():
        if any(p.kind == "path" for p in model.params):
            continue  # data files: not a default to time
        m = Material(name, None)
        for th in json.loads(sys.argv[2]):
            ts = []
            for k in range(reps):
                req = core_frame.FrameRequest((m,), th - 0.001 * (k + rnd * reps), map_px=(88, 84))
                if idle and rnd:
                    time.sleep(idle)
                t = time.process_time()
                core_frame.compute_frame(req)
                ts.append(time.process_time() - t)
            out[f"{name} {th:g}"] = statistics.median(ts)
print(json.dumps(out))
"""


def run(tree: str, reps: int, idle: float = 0.0) -> dict:
    env = dict(os.environ, PYTHONPATH=tree)
    res = subprocess.run([sys.executable, "-c", CHILD, str(reps), json.dumps(THETAS), str(idle)],
                         capture_output=True, text=True, check=True, env=env, cwd=tree)
    return json.loads(res.stdout)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--reps", type=int, default=15)
    ap.add_argument("--rev", default=None, help="also time git revision REV")
    ap.add_argument("--idle", type=float, default=0.0, help="seconds asleep before each frame")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as d:
        old = extract(args.rev, d) if args.rev else None
        after = run(str(ROOT), args.reps, args.idle)
        before = run(old, args.reps, args.idle) if old else {}
    cols = [f"θi={t:g}°" for t in THETAS]
    head = "| model | " + " | ".join(cols) + " |"
    print(f"one frame at 160×48 (map, sections, peak, albedo), CPU ms median of {args.reps}"
          + (f"; {args.rev} → this tree" if args.rev else "")
          + (f"; {args.idle:g} s idle before each" if args.idle else ""))
    print(head)
    print("|---" * (len(cols) + 1) + "|")
    for name in dict.fromkeys(k.rsplit(" ", 1)[0] for k in after):
        cells = []
        for t in THETAS:
            key = f"{name} {t:g}"
            now = f"{after[key] * 1e3:.1f}"
            cells.append(f"{before[key] * 1e3:.1f} → {now}" if key in before else now)
        print(f"| {name} | " + " | ".join(cells) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
