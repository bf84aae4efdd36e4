"""``tuibrdf.evaluate`` against its bare kernel on 10⁶ direction pairs.

    PYTHONPATH=$PWD python scripts/bench_evaluate.py [--n 1000000] [--repeat 7] [--write-docs]

For each model: the best of ``--repeat`` calls (taken in turns) of
``tuibrdf.evaluate(model, {}, wi, wo)`` (validating and, where needed, normalising the
directions) and of the kernel behind it,
``evaluate_resolved`` with the parameters resolved once, in one piece (as a bare numpy
expression would be); ``evaluate`` checks and evaluates a block at a time, so the ratio is the
price of the checks less what the blocks save.
``wi`` and ``wo`` are random unit vectors of the upper hemisphere (float64, C order), as a
caller's own array usually is, and the same vectors ×2 (not unit: the normalising path).
``--write-docs`` writes the table into docs/benchmarks.md (section ``bench_evaluate``).
Not a test: the numbers are the machine's.
"""

from __future__ import annotations

import argparse
import timeit

import numpy as np
from benchdoc import command_line, write_section

from tuibrdf.core.evaluate import evaluate, evaluate_resolved
from tuibrdf.core.registry import get_model

MODELS = ("lambert", "phong", "cook-torrance", "ggx", "oren-nayar", "gltf")


def unit_vectors(rng: np.random.Generator, n: int) -> np.ndarray:
    v = rng.normal(size=(n, 3))
    v[:, 2] = np.abs(v[:, 2])
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def best(fns, repeat: int) -> list[float]:
    """The best time of each of ``fns`` over ``repeat`` rounds, the calls taken in turns (so a
    burst of load on a shared machine slows all of them, not one)."""
    times = [[] for _ in fns]
    for _ in range(repeat):
        for t, fn in zip(times, fns, strict=True):
            t.append(timeit.timeit(fn, number=1))
    return [min(t) for t in times]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--n", type=int, default=10**6)
    ap.add_argument("--repeat", type=int, default=7)
    ap.add_argument("--write-docs", action="store_true")
    a = ap.parse_args()
    rng = np.random.default_rng(1)
    wi, wo = unit_vectors(rng, a.n), unit_vectors(rng, a.n)
    wi2, wo2 = 2.0 * wi, 2.0 * wo
    rows = ["| model | kernel ms | `evaluate` ms | ratio | `evaluate`, vectors ×2, ms | ratio |",
            "|---|---|---|---|---|---|"]
    for name in MODELS:
        m = get_model(name)
        values = m.resolve({})
        t_k, t_api, t_2 = best([lambda: evaluate_resolved(m, values, wi, wo),  # noqa: B023
                                lambda: evaluate(name, {}, wi, wo),  # noqa: B023
                                lambda: evaluate(name, {}, wi2, wo2)], a.repeat)  # noqa: B023
        rows.append(f"| {name} | {t_k * 1e3:.1f} | {t_api * 1e3:.1f} | {t_api / t_k:.2f} | "
                    f"{t_2 * 1e3:.1f} | {t_2 / t_k:.2f} |")
        print(rows[-1], flush=True)
    if a.write_docs:
        write_section("bench_evaluate", "\n".join(rows), command_line())


if __name__ == "__main__":
    main()
