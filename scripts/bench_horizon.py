"""Time the horizon check of a frame (tuibrdf/core/sphere/horizon.py::assess: the growth test toward
the horizon and the refinement of a peak missed next to it) against the peak search it follows
(find_peaks), for every built-in model's defaults at θi = 30°, 60°, 85° and 89.9°.  Process CPU
time, median of ``--reps``.

    PYTHONPATH=$PWD python scripts/bench_horizon.py [--reps 7]
"""

from __future__ import annotations

import argparse
import statistics
import time

from tuibrdf.core.directions import incident
from tuibrdf.core.material import Material
from tuibrdf.core.registry import MODELS
from tuibrdf.core.sphere.horizon import assess
from tuibrdf.core.sphere.peak import find_peaks

THETAS = (30.0, 60.0, 85.0, 89.9)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--reps", type=int, default=7)
    args = ap.parse_args()
    print("| model | " + " | ".join(f"θi={t:g}°" for t in THETAS) + " |")
    print("|---" * (len(THETAS) + 1) + "|")
    for name, model in MODELS.items():
        if any(p.kind == "path" for p in model.params):
            continue  # data files: not a default to time
        mat = Material(name)
        cells = []
        for t in THETAS:
            wi = incident(t)
            peaks = find_peaks(mat.model, mat.values, wi)
            a, p = [], []
            for k in range(args.reps):
                t0 = time.process_time()
                assess(mat.model, mat.values, wi, peaks)
                a.append(time.process_time() - t0)
                t0 = time.process_time()
                find_peaks(mat.model, mat.values, incident(t - 1e-3 * (k + 1)))  # no cache
                p.append(time.process_time() - t0)
            cells.append(f"{statistics.median(a) * 1e3:.2f} / {statistics.median(p) * 1e3:.1f}")
        print(f"| {name} | " + " | ".join(cells) + " |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
