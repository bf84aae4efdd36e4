"""How the stored albedos of the fitted materials compare with the mesh quadrature, and what
each costs.

    python scripts/bench_material_albedo.py

Prints the time of all 400 albedos (100 materials × abc, sgd × θi = 0°, 60°) by
``tuibrdf.albedo`` (mesh quadrature, defaults) and by the half-vector rule of
``tuibrdf/core/material_albedo.py`` (the stored table's nodes), and their largest differences
from the stored table.  Numbers in docs/materials.md.
"""

from __future__ import annotations

import time

import numpy as np

import tuibrdf
from tuibrdf.core import material_albedo as ma
from tuibrdf.core.materials import material_names


def main() -> None:
    data = ma.stored()
    jobs = [(n, m, k, t) for n in material_names() for m in ("abc", "sgd")
            for k, t in enumerate(ma.THETAS)]
    for label, fn in (
        ("half-vector rule", lambda n, m, t: ma.albedo(m, n, t, n_s=ma.STORED_NODES[0],
                                                       n_phi=ma.STORED_NODES[1])),
        ("mesh quadrature (tuibrdf.albedo)", lambda n, m, t: tuibrdf.albedo(
            m, {"material": n}, t)),
    ):
        wall, cpu = time.perf_counter(), time.process_time()
        diffs = []
        for n, m, k, t in jobs:
            a = np.asarray(fn(n, m, t))
            d = float(np.max(np.abs(a - data[n][m][k])))
            diffs.append((d, d / max(float(np.max(data[n][m][k])), 1e-3), m, n, t))
        wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
        diffs.sort()
        d, rel, m, n, t = diffs[-1]
        print(f"{label}: 400 albedos in {wall:.1f} s wall, {cpu:.1f} s CPU; vs stored: "
              f"median |Δ| {np.median([x[0] for x in diffs]):.2g}, "
              f"max |Δ| {d:.2g} ({rel:.2g} relative; {m} {n} at {t:g}°), "
              f"{sum(x[0] > 1e-3 for x in diffs)} above 1e-3")


if __name__ == "__main__":
    main()
