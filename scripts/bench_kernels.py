"""Cost of one kernel call, fixed and per point, for every built-in model (issue 16;
its output is the record).

    PYTHONPATH=$PWD python scripts/bench_kernels.py               # before (git main) and after
    PYTHONPATH=$PWD python scripts/bench_kernels.py --rev REV     # before = git revision REV
    PYTHONPATH=$PWD python scripts/bench_kernels.py --rev none    # this tree only
    PYTHONPATH=$PWD python scripts/bench_kernels.py --cold        # a fresh process's heap
    PYTHONPATH=$PWD python scripts/bench_kernels.py --albedo --models abc,sgd   # the albedo

Each model is called as the viewer calls it: ``evaluate_resolved(model, model.defaults(),
incident(40, 180), wo)`` with ``wo`` random unit vectors of the upper hemisphere.  The *fixed*
cost is the time of one call at n = 1, 10 and 100 points (printed as the range), the *per-point*
cost ``(t(10⁴) − t(1)) / (10⁴ − 1)``.  Times are the best of several repeats (the machine is
shared: noisy).  This tree and the revision REV (from ``git archive``) run in subprocesses, in
turns, model by model (``--rounds``, the best of each kept), with the same directions; their
values are compared on several parameter sets and direction layouts (one wi against many wo,
many against many, both sides broadcast), including directions on and below the horizon: the
largest relative difference per model is printed (``rel diff``: ``|new − old| / |old|`` where
old ≠ 0, and new must be exactly 0 where old is); abc and sgd are compared on every material.

``--albedo`` times ``quadrature.albedo_estimate_resolved`` at the model's defaults instead, at
θi = 0, 30, 60, 75, 85, 89, 89.9 and 90° (best of 9 calls after a first one, the trees in turns,
best of the rounds), and prints the albedo's largest relative difference between the trees.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import timeit
from pathlib import Path

import numpy as np
from revtree import extract

ROOT = Path(__file__).resolve().parent.parent
NAMES = ["lambert", "phong", "blinn-phong", "cook-torrance", "oren-nayar", "oren-nayar-simple",
         "ggx", "gltf", "disney-diffuse", "ue4", "abc", "sgd"]
#: parameter sets for the value comparison (besides the defaults)
EXTRA = {
    "phong": [{"n": 0.0}, {"n": 10000.0, "kd": 0.0, "ks": 1.0}],
    "blinn-phong": [{"n": 0.0}, {"n": 10000.0, "kd": 0.0, "ks": 1.0}],
    "cook-torrance": [{"m": 0.001, "kd": 0.5}, {"m": 1.0, "fresnel": "schlick"}, {"f0": 0.0},
                      {"f0": 1.0}],
    "ggx": [{"alpha": 0.001, "kd": 0.5}, {"alpha": 1.0, "fresnel": "schlick"}, {"f0": 1e-40}],
    "gltf": [{"roughness": 0.0, "metallic": 1.0}, {"roughness": 1.0, "metallic": 0.3,
                                                   "base_color": (0.9, 0.2, 0.0)}],
    "ue4": [{"roughness": 0.0, "metallic": 1.0}, {"roughness": 1.0, "metallic": 0.3,
                                                  "base_color": (0.9, 0.2, 0.0)}],
    "oren-nayar": [{"sigma": 0.0}, {"sigma": 90.0, "kd": 1.0}],
    "oren-nayar-simple": [{"sigma": 0.0}, {"sigma": 90.0, "kd": 1.0}],
    "disney-diffuse": [{"roughness": 0.0}, {"roughness": 1.0, "base_color": (1.0, 0.5, 0.0)}],
    "abc": [{"material": "black-obsidian"}, {"material": "white-fabric2"}],
    "sgd": [{"material": "black-obsidian"}, {"material": "white-fabric2"},
            {"material": "chrome"}],
}
SIZES_FIXED = (1, 10, 100)
N_BIG = 10_000

CHILD = r"""
import json, sys
sys.path.insert(0, sys.argv[1])
sys.path.insert(0, sys.argv[2])
import bench_kernels as b
import os
f = b.measure_albedo if os.environ.get("BENCH_KERNELS_ALBEDO") else b.measure
res = f(json.loads(sys.argv[3]), sys.argv[4])
print(json.dumps(res))
"""


def _upper(rng: np.random.Generator, n: int) -> np.ndarray:
    v = rng.normal(size=(n, 3))
    v[:, 2] = np.abs(v[:, 2])
    return v / np.linalg.norm(v, axis=1)[:, None]


def _hard(rng: np.random.Generator, n: int) -> np.ndarray:
    """Random directions of the whole sphere, plus the normal, horizon and near-horizon ones."""
    v = rng.normal(size=(n, 3))
    v /= np.linalg.norm(v, axis=1)[:, None]
    s = [[0, 0, 1], [1, 0, 0], [-1, 0, 0], [0, 1, 0], [0.6, 0.8, 0.0],
         [1, 0, 1e-9], [-1, 0, 1e-9], [1, 0, 1e-300], [1, 0, 1e-310], [0, 0, -1],
         [np.sin(0.3), 0, np.cos(0.3)], [-np.sin(0.3), 0, np.cos(0.3)]]
    s = np.array(s, dtype=float)
    s /= np.linalg.norm(s, axis=1)[:, None]
    return np.concatenate([s, v])


def values(out: str) -> None:
    """Evaluate every model on the comparison cases and save them to ``out`` (.npz)."""
    from tuibrdf.core.brdf.materials import material_names
    from tuibrdf.core.directions import incident
    from tuibrdf.core.evaluate import evaluate_resolved
    from tuibrdf.core.registry import MODELS

    rng = np.random.default_rng(16)
    wo = _hard(rng, 400)
    wis = [incident(t, 180.0) for t in (0.0, 40.0, 85.0, 89.9, 90.0)]
    wi_many = _hard(rng, 60)
    saved = {}
    for name in NAMES:
        m = MODELS[name]
        sets = EXTRA.get(name, [])
        if name in ("abc", "sgd"):  # the fits: every material
            sets = [{"material": n} for n in material_names()]
        for k, params in enumerate([{}, *sets]):
            v = m.resolve(params)
            for j, wi in enumerate(wis):
                saved[f"{name}|{k}|one{j}"] = evaluate_resolved(m, v, wi, wo)
            a, b = np.broadcast_arrays(wi_many[:, None, :], wi_many[None, :, :])
            saved[f"{name}|{k}|pairs"] = evaluate_resolved(m, v, a, b)
            saved[f"{name}|{k}|bcast"] = evaluate_resolved(
                m, v, np.broadcast_to(wis[1], wo.shape), wo)
            saved[f"{name}|{k}|same"] = evaluate_resolved(m, v, wo[::-1].copy(), wo)
    np.savez(out, **{k: np.asarray(x) for k, x in saved.items()})


def measure(names: list[str], dump: str) -> dict[str, list[float]]:
    """``{model: [t(1), t(10), t(100), t(10⁴)]}`` in seconds; values saved to ``dump`` (if
    not empty)."""
    from tuibrdf.core.directions import incident
    from tuibrdf.core.evaluate import evaluate_resolved
    from tuibrdf.core.registry import MODELS

    if dump:
        values(dump)
    # A fresh process's heap gives memory back to the system when a call frees its
    # temporaries (glibc trims above 128 KB), so the next call page-faults them in again:
    # 2–3× the time per point at n = 10⁴.  Freeing one large block raises glibc's thresholds
    # (to its size), as happens early in any long-running process such as the viewer.
    if not os.environ.get("BENCH_KERNELS_COLD"):
        warm = np.ones(2**21)
        del warm
    rng = np.random.default_rng(1)
    wi = incident(40.0, 180.0)
    res = {}
    for name in names:
        m = MODELS[name]
        v = m.defaults()
        times = []
        for n in (*SIZES_FIXED, N_BIG):
            wo = _upper(rng, n)
            evaluate_resolved(m, v, wi, wo)
            number = 200 if n <= 100 else 10
            best = min(timeit.repeat(lambda m=m, v=v, wo=wo: evaluate_resolved(m, v, wi, wo),
                                     number=number, repeat=5))
            times.append(best / number)
        res[name] = times
    return res


ALBEDO_THETAS = (0.0, 30.0, 60.0, 75.0, 85.0, 89.0, 89.9, 90.0)


def measure_albedo(names: list[str], dump: str) -> dict[str, list[float]]:
    """``{model: [seconds per albedo at each of ALBEDO_THETAS]}``; the albedos (RGB) saved to
    ``dump`` (if not empty)."""
    import time

    from tuibrdf.core.registry import MODELS
    from tuibrdf.core.sphere import albedo as quadrature

    if not os.environ.get("BENCH_KERNELS_COLD"):
        warm = np.ones(2**21)
        del warm
    res, saved = {}, {}
    for name in names:
        m = MODELS[name]
        v = m.defaults()
        times = []
        for j, theta in enumerate(ALBEDO_THETAS):
            saved[f"{name}|{j}"] = np.asarray(quadrature.albedo_estimate_resolved(m, v, theta)
                                              .value)
            best = float("inf")
            for _ in range(9):
                t0 = time.perf_counter()
                quadrature.albedo_estimate_resolved(m, v, theta)
                best = min(best, time.perf_counter() - t0)
            times.append(best)
        res[name] = times + [_replayed(m, v, theta) for theta in ALBEDO_THETAS]
    if dump:
        np.savez(dump, **saved)
    return res


def _replayed(m, v, theta: float) -> float:
    """The albedo's time with a kernel that costs nothing: the kernel's outputs of one run
    recorded, then returned in order (the same values, so the same quadrature path)."""
    import time

    from tuibrdf.core import evaluate
    from tuibrdf.core.sphere import albedo as quadrature

    real, rec = m.kernel, []

    def record(wi, wo, **kw):
        rec.append(real(wi, wo, **kw))
        return rec[-1]

    def replay(wi, wo, **kw):
        replay.i += 1
        return rec[replay.i - 1]

    saved = evaluate.BROADCAST_KERNELS
    evaluate.BROADCAST_KERNELS = set(saved) | {record, replay}
    try:
        object.__setattr__(m, "kernel", record)
        quadrature.albedo_estimate_resolved(m, v, theta)
        object.__setattr__(m, "kernel", replay)
        best = float("inf")
        for _ in range(9):
            replay.i = 0
            t0 = time.perf_counter()
            quadrature.albedo_estimate_resolved(m, v, theta)
            best = min(best, time.perf_counter() - t0)
    finally:
        object.__setattr__(m, "kernel", real)
        evaluate.BROADCAST_KERNELS = saved
    return best


def run_tree(tree: str, names: list[str], dump: str) -> dict[str, list[float]]:
    """:func:`measure` (or :func:`measure_albedo` with ``--albedo``) on the package in
    directory ``tree``, in a subprocess."""
    env = {**os.environ, "PYTHONPATH": tree}
    out = subprocess.run([sys.executable, "-c", CHILD, tree, str(ROOT / "scripts"),
                          json.dumps(names), dump],
                         capture_output=True, text=True, check=True, env=env, cwd=tree).stdout
    return json.loads(out.strip().splitlines()[-1])


def best_of(runs: list[dict[str, list[float]]]) -> dict[str, list[float]]:
    return {k: [min(r[k][i] for r in runs) for i in range(len(runs[0][k]))] for k in runs[0]}


def rel_diff(new: np.ndarray, old: np.ndarray) -> float:
    """Largest ``|new − old| / |old|``; inf where old is 0 and new is not, or shapes differ."""
    if new.shape != old.shape:
        return float("inf")
    nz = old != 0.0
    if np.any(new[~nz] != 0.0):
        return float("inf")
    if not nz.any():
        return 0.0
    return float(np.max(np.abs(new[nz] - old[nz]) / np.abs(old[nz])))


def _fixed(t: list[float]) -> str:
    lo, hi = min(t[: len(SIZES_FIXED)]), max(t[: len(SIZES_FIXED)])
    return f"{lo * 1e6:.0f}–{hi * 1e6:.0f}"


def _per_point(t: list[float]) -> float:
    return (t[-1] - t[0]) / (N_BIG - 1) * 1e9


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--rev", default="main",
                    help="git revision to compare with ('none': this tree only)")
    ap.add_argument("--models", default=",".join(NAMES), help="comma-separated model names")
    ap.add_argument("--rounds", type=int, default=3, help="runs of each tree, best kept")
    ap.add_argument("--cold", action="store_true",
                    help="leave glibc's heap thresholds at their start (see measure())")
    ap.add_argument("--albedo", action="store_true",
                    help="time the albedo at the defaults (8 incidences) instead")
    args = ap.parse_args()
    if args.cold:
        os.environ["BENCH_KERNELS_COLD"] = "1"
    if args.albedo:
        os.environ["BENCH_KERNELS_ALBEDO"] = "1"
    names = args.models.split(",")
    with tempfile.TemporaryDirectory() as d:
        after_dump = os.path.join(d, "after.npz")
        before_dump = os.path.join(d, "before.npz")
        old_tree = os.path.join(d, "old")
        if args.rev != "none":
            extract(args.rev, old_tree)
        # the two trees in turns, model by model, best of the rounds: a busy spell of the
        # shared machine then weighs on both rather than on one
        # the values (with --albedo: the albedos, timed and saved in the same run)
        dump_names = names if args.albedo else []
        run_tree(str(ROOT), dump_names, after_dump)
        if args.rev != "none":
            run_tree(old_tree, dump_names, before_dump)
        after_runs, before_runs = [], []
        for _ in range(args.rounds):
            a_run, b_run = {}, {}
            for name in names:
                a_run.update(run_tree(str(ROOT), [name], ""))
                if args.rev != "none":
                    b_run.update(run_tree(old_tree, [name], ""))
            after_runs.append(a_run)
            before_runs.append(b_run)
        after = best_of(after_runs)
        before = diffs = None
        if args.rev != "none":
            before = best_of(before_runs)
            a, b = np.load(after_dump), np.load(before_dump)
            diffs = {}
            for key in b.files:
                name = key.split("|")[0]
                diffs[name] = max(diffs.get(name, 0.0), rel_diff(a[key], b[key]))
    if args.albedo:
        _print_albedo(names, after, before, diffs, args.rev)
        return
    print(f"evaluate_resolved(model, defaults, incident(40°, 180°), wo): fixed µs per call "
          f"(n = 1, 10, 100), per-point ns (n = {N_BIG})")
    if before is None:
        print(f"{'model':18s} {'fixed µs':>10s} {'ns/point':>9s}")
        for n in names:
            print(f"{n:18s} {_fixed(after[n]):>10s} {_per_point(after[n]):9.0f}")
        return
    print(f"before = git {args.rev}, after = this tree; rel diff = largest relative difference "
          "of the values")
    print(f"{'model':18s} {'fixed µs before':>16s} {'after':>9s} {'ns/pt before':>13s} "
          f"{'after':>6s} {'change':>7s} {'rel diff':>9s}")
    for n in names:
        pb, pa = _per_point(before[n]), _per_point(after[n])
        print(f"{n:18s} {_fixed(before[n]):>16s} {_fixed(after[n]):>9s} {pb:13.0f} {pa:6.0f} "
              f"{(pa - pb) / pb:+7.0%} {diffs.get(n, 0.0):9.1e}")


def _print_albedo(names, after, before, diffs, rev) -> None:
    print("albedo_estimate_resolved(model, defaults, θi): ms, best of 9 calls and of the rounds"
          + (f"; before = git {rev}, after = this tree" if before else ""))
    print("free = this tree with the kernel's outputs replayed (the quadrature's own time)")
    print(f"{'model':8s} {'θi':>5s} {'before':>7s} {'after':>7s} {'change':>7s} {'free':>7s}")
    nt = len(ALBEDO_THETAS)
    for n in names:
        for j, theta in enumerate(ALBEDO_THETAS):
            a, free = after[n][j] * 1e3, after[n][nt + j] * 1e3
            if before:
                b = before[n][j] * 1e3
                print(f"{n:8s} {theta:5g} {b:7.2f} {a:7.2f} {(a - b) / b:+7.0%} {free:7.2f}")
            else:
                print(f"{n:8s} {theta:5g} {'':7s} {a:7.2f} {'':7s} {free:7.2f}")
        ok = sum(t <= 2e-3 for t in after[n][:nt])
        line = f"{n}: ≤ 2 ms in {ok} of {len(ALBEDO_THETAS)} after"
        if before:
            line += f", {sum(t <= 2e-3 for t in before[n][:nt])} before; albedo rel diff "
            line += f"{diffs.get(n, 0.0):.1e}"
        print(line)


if __name__ == "__main__":
    main()
