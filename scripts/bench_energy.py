"""How long ``tuibrdf energy`` takes: the table E(μ, p) with E_avg of a few models, in process
(:func:`tuibrdf.core.sphere.energy.energy_table`), repeated.

    python scripts/bench_energy.py [--runs 3] [--n 32] [--mu-n 32] [--view] [--write-docs]

Prints the median and the minimum per table and the largest error estimate in it.  ``--view``:
the viewer's energy view instead, its table over the parameter's whole range (12 × 16, each
albedo to 1e-3; :func:`tuibrdf.core.sphere.energy.view_table`), which a step of another
parameter computes again, CPU ms (section ``bench_energy-view``);
``--write-docs`` also writes the table into docs/benchmarks.md (scripts/benchdoc.py: its own
section, with the command, the machine and the date).
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from benchdoc import command_line, machine, write_section  # noqa: E402

#: (model, other parameters, swept parameter, range, log)
CASES = [
    ("lambert", {}, "kd", (0.0, 1.0), False),
    ("ggx", {"kd": 0.0, "f0": 1.0}, "alpha", (0.001, 1.0), False),
    ("ggx", {"kd": 0.0, "f0": 1.0}, "alpha", (0.001, 1.0), True),
    ("cook-torrance", {"kd": 0.0, "f0": 1.0}, "m", (0.001, 1.0), False),
    ("oren-nayar", {}, "sigma", (0.0, 90.0), False),
    ("gltf", {"metallic": 1.0, "base_color": 1.0}, "roughness", (0.0, 1.0), False),
]


def main() -> int:
    from tuibrdf.cli.memory import keep_freed_memory
    from tuibrdf.core.registry import get_model
    from tuibrdf.core.sphere.energy import energy_table

    keep_freed_memory()  # as `tuibrdf energy` and the viewer run (tuibrdf/cli/memory.py)

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--n", type=int, default=32)
    ap.add_argument("--mu-n", type=int, default=32)
    ap.add_argument("--view", action="store_true", help="the viewer's energy view's table")
    ap.add_argument("--write-docs", action="store_true",
                    help="also write the table into docs/benchmarks.md (its own section)")
    a = ap.parse_args()
    started = machine()
    if a.view:
        return view(a, started)
    lines = [f"`tuibrdf energy` tables of {a.n} parameter values × {a.mu_n} values of μ, "
             f"E_avg included, {a.runs} runs each:", "",
             "| model | parameter | grid | median s | min s | error bound |",
             "|---|---|---|---|---|---|"]
    for name, params, p, (lo, hi), log in CASES:
        model = get_model(name)
        times, bound = [], 0.0
        for _ in range(a.runs):
            t0 = time.perf_counter()
            table = energy_table(model, params, p, lo, hi, a.n, a.mu_n, log=log)
            times.append(time.perf_counter() - t0)
            bound = table.error_bound
        lines.append(f"| {name} | {p} {lo:g}…{hi:g} | {'geometric' if log else 'linear'} | "
                     f"{statistics.median(times):.2f} | {min(times):.2f} | {bound:.0e} |")
    return report(lines, "bench_energy", a.write_docs, started)


def report(lines: list[str], section: str, write: bool, started: str) -> int:
    """Print the table and, with ``--write-docs``, write it as ``section`` of the docs."""
    print("\n".join(lines))
    if write:
        doc = write_section(section, "\n".join(lines), command_line(), machine_line=started)
        print(f"written into {doc}")
    return 0


def view(a, started: str) -> int:
    """The ``--view`` table (module docstring)."""
    from tuibrdf.core.registry import get_model
    from tuibrdf.core.sphere import energy

    lines = [f"The energy view's table (E over 12 parameter values × 16 values of μ, and each "
             f"row's E_avg) over the parameter's whole range, the other parameters as in the "
             f"`tuibrdf energy` table above; CPU ms, {a.runs} runs each:", "",
             "| model | parameter | median ms | min ms | largest error of E | of E_avg, relative |",
             "|---|---|---|---|---|---|"]
    for name, params, p, _, log in CASES:
        if log:  # (the view takes its own grid: the linear case is the same table)
            continue
        model = get_model(name)
        values = model.resolve(params)
        times = []
        for _ in range(a.runs):
            energy._VIEW_CACHE.clear()  # (the view keeps its last tables)
            t0 = time.process_time()
            t = energy.view_table(model, values, model.param(p))
            times.append(time.process_time() - t0)
        rel = float((t.E_avg_error / abs(t.E_avg).clip(1e-300)).max())
        lines.append(f"| {name} | {p} | {statistics.median(times) * 1e3:.0f} | "
                     f"{min(times) * 1e3:.0f} | {t.error_bound:.0e} | {rel:.0e} |")
    return report(lines, "bench_energy-view", a.write_docs, started)


if __name__ == "__main__":
    sys.exit(main())
