"""Is the albedo's error estimate ever below its true error?  A seeded sweep.

Random parameters over each built-in model's range (log-uniform for the widths and exponents,
so sharp lobes are frequent), θi uniform in [0°, 89.99°] or graded toward it (90° − 10^U(−2,
1)°), the default rule (``albedo_estimate``) against a reference: the same adaptive rule at a
relative tolerance of 1e-12 and 20 M evaluations (its own error then ~1e-12, six orders below
the estimates checked; tests/core/sphere/test_albedo.py checks the rule against independent
tensor Gauss–Legendre references).  Prints the cases where ``|value − reference|`` exceeds the
estimate, and the largest ratio.

    PYTHONPATH=$PWD python scripts/albedo_error_sweep.py --cases 2000 --seed 37
"""

from __future__ import annotations

import argparse
import math
import sys
import time

import numpy as np

from tuibrdf.core.registry import MODELS
from tuibrdf.core.sphere.albedo import albedo_estimate

SKIP = {"merl"}  # needs a file


def random_params(model, rng: np.random.Generator) -> dict:
    out = {}
    for p in model.params:
        if p.kind == "choice":
            out[p.name] = str(rng.choice(p.choices))
        elif p.kind == "rgb":
            out[p.name] = tuple(float(x) for x in rng.uniform(p.min, p.max, 3))
        elif p.kind == "path":
            continue
        elif p.relative:
            lo = max(p.min, 1.0 if p.max > 10 else 1e-3)
            out[p.name] = float(math.exp(rng.uniform(math.log(lo), math.log(p.max))))
        else:
            out[p.name] = float(rng.uniform(p.min, p.max))
    if "kd" in out and "ks" in out and out["kd"] + out["ks"] > 1.0:
        s = out["kd"] + out["ks"]
        out["kd"], out["ks"] = out["kd"] / s * 0.999, out["ks"] / s * 0.999
    return out


def cases(n: int, seed: int):
    rng = np.random.default_rng(seed)
    names = [k for k in MODELS if k not in SKIP]
    for i in range(n):
        name = names[i % len(names)]
        params = random_params(MODELS[name], rng)
        if rng.uniform() < 0.5:
            theta = float(rng.uniform(0.0, 89.99))
        else:
            theta = 90.0 - 10.0 ** float(rng.uniform(-2.0, 1.0))
        yield name, params, theta


def check(name, params, theta):
    est = albedo_estimate(name, params, theta)
    ref = albedo_estimate(name, params, theta, rtol=1e-12, max_evals=20_000_000)
    err = np.abs(np.asarray(est.value) - np.asarray(ref.value))
    ratio = float(np.max(err / np.maximum(np.asarray(est.error), 1e-300)))
    return ratio, est, ref


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--cases", type=int, default=2000)
    ap.add_argument("--seed", type=int, default=37)
    args = ap.parse_args(argv)
    worst, bad, t0 = 0.0, 0, time.perf_counter()
    for i, (name, params, theta) in enumerate(cases(args.cases, args.seed)):
        ratio, est, ref = check(name, params, theta)
        worst = max(worst, ratio)
        if ratio > 1.0:
            bad += 1
            print(f"#{i} {name} {params} θi={theta!r}: {est.value} ± {est.error} "
                  f"reference {ref.value} ± {ref.error} ratio {ratio:.3g}", flush=True)
        if (i + 1) % 100 == 0:
            print(f"... {i + 1} cases, {bad} below, worst ratio {worst:.3g}, "
                  f"{time.perf_counter() - t0:.0f} s", file=sys.stderr, flush=True)
    print(f"{args.cases} cases (seed {args.seed}): {bad} with the estimate below the error; "
          f"largest error/estimate {worst:.3g}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
