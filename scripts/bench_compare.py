"""The numbers of ``tuibrdf compare`` for one θi (:func:`tuibrdf.core.sphere.compare.compare`:
both albedos, rel_l2's two integrals, the largest difference) for pairs of analytic models,
nothing cached: process CPU time, median and maximum of ``--reps`` runs (each at a θi moved
by a millidegree, so no cache of the package answers).  The issue's target: ≤ 50 ms a θi.

    python scripts/bench_compare.py [--reps 9] [--write-docs]

``--write-docs`` also writes the table into docs/benchmarks.md (scripts/benchdoc.py: its own
section, with the command, the machine and the date).
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time

from benchdoc import WRITE_FLAG, command_line, machine, write_section

from tuibrdf.core.material import Material
from tuibrdf.core.sphere.compare import compare

#: (label, A, B): the seed's two comparisons and two more
PAIRS = (
    ("specular: phong vs cook-torrance", ("phong", {"kd": 0.0, "ks": 0.08, "n": 70.0}),
     ("cook-torrance", {"kd": 0.0, "f0": 0.04, "m": 0.07})),
    ("diffuse: lambert vs oren-nayar", ("lambert", {}), ("oren-nayar", {})),
    ("ggx vs blinn-phong", ("ggx", {}), ("blinn-phong", {})),
    ("gltf vs ue4", ("gltf", {}), ("ue4", {})),
)
THETAS = (30.0, 60.0, 85.0)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--reps", type=int, default=9)
    ap.add_argument(WRITE_FLAG, dest="write_docs", action="store_true")
    a = ap.parse_args()
    started = machine()
    lines = [f"`compare` numbers for one θi, CPU ms (median / max of {a.reps}):", "",
             "| pair | " + " | ".join(f"θi={t:g}°" for t in THETAS) + " |",
             "|---" * (len(THETAS) + 1) + "|"]
    for label, (ma, pa), (mb, pb) in PAIRS:
        x, y = Material(ma, pa), Material(mb, pb)
        cells = []
        for t in THETAS:
            times = []
            for k in range(a.reps):
                t0 = time.process_time()
                compare(x.model, x.values, y.model, y.values, [t - 1e-3 * (k + 1)])
                times.append(time.process_time() - t0)
            cells.append(f"{1e3 * statistics.median(times):.1f} / {1e3 * max(times):.1f}")
        lines.append(f"| {label} | " + " | ".join(cells) + " |")
    print("\n".join(lines))
    if a.write_docs:
        doc = write_section("bench_compare", "\n".join(lines), command_line(),
                            machine_line=started)
        print(f"written into {doc}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
