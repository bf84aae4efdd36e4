"""Speed against error for the directional albedo (issues 6, 16, 18; docs/reference/accuracy.md).

    PYTHONPATH=. python scripts/bench_accuracy.py                 # ~2-3 minutes
    PYTHONPATH=. python scripts/bench_accuracy.py --before REV    # and the code of git REV
    (--before may be repeated; --quick: the albedo tables only)
    PYTHONPATH=. python scripts/bench_accuracy.py --interleave REV  # default albedos only,
    timed here and in REV in alternating processes, with evaluations and kernel calls
    (--models abc,sgd: those models' defaults instead of the analytic ones)

For every model's defaults and for the hard cases (sharp lobes down to α = m = 0.001,
n = 10⁴, roughness 0) at θi from 0° to 90°, it prints the default albedo
(``quadrature.albedo_estimate_resolved``): the value, its error estimate, its error against
the reference, evaluations and time; then the speed against error of every way of computing it
on a few cases (the default rule at several tolerances, the uniform mesh levels, the adaptive
mesh); the 91-point curve's time per model; MERL data (synthetic file) time and peak memory;
then the map and the formula variants.  With ``--before REV`` the same albedos by the code of
git revision REV (run in a subprocess from ``git archive``), against the same references.

References: the default rule at ``rtol = 1e-13`` (up to 5 million evaluations), itself checked
here against an independent tensor Gauss-Legendre rule over (θo, φo) with panels graded around
θo = θi, the horizon and the mirror azimuth (the "ref check" table;
tests/core/sphere/test_albedo.py checks
more cases, the closed forms and the 1-D integrals).  Times are best of several runs on a
shared machine (noisy); errors and evaluation counts do not depend on the machine.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from revtree import extract

from tuibrdf.core.directions import from_degrees, incident, mirror
from tuibrdf.core.evaluate import evaluate_resolved
from tuibrdf.core.registry import MODELS, get_model
from tuibrdf.core.sphere import albedo as q
from tuibrdf.core.sphere.mesh import hemisphere, interpolate, refine_adaptive
from tuibrdf.core.sphere.peak import find_peaks

THETAS = [0.0, 30.0, 60.0, 75.0, 85.0, 89.0, 89.9, 90.0]
HARD_THETAS = [0.0, 60.0, 85.0, 89.0, 89.9, 90.0]
HARD = [
    ("ggx", {"kd": 0.0, "f0": 1.0, "alpha": 0.001}),
    ("ggx", {"alpha": 0.01}),
    ("cook-torrance", {"kd": 0.0, "f0": 1.0, "m": 0.001}),
    ("cook-torrance", {"m": 0.01}),
    ("phong", {"kd": 0.0, "ks": 1.0, "n": 10000.0}),
    ("blinn-phong", {"kd": 0.0, "ks": 1.0, "n": 10000.0}),
    ("gltf", {"roughness": 0.0, "metallic": 1.0, "base_color": 1.0}),
    ("ue4", {"roughness": 0.0, "metallic": 1.0, "base_color": 1.0}),
]
DEFAULTS = [(n, {}) for n in MODELS if n != "merl"]
REF_RTOL = 1e-13


def ptext(params):
    return ",".join(f"{k}={v:g}" if isinstance(v, float) else f"{k}={v}"
                    for k, v in params.items()) or "defaults"


def timed(fn, *args, repeat=5, **kw):
    best = np.inf
    for _ in range(repeat):
        t = time.perf_counter()
        out = fn(*args, **kw)
        best = min(best, time.perf_counter() - t)
    return out, best


def rel(a, ref):
    a, ref = np.asarray(a, dtype=float), np.asarray(ref, dtype=float)
    return float(np.max(np.abs(a - ref) / np.maximum(np.abs(ref), 1e-300)))


def reference(model, values, th):
    return q.albedo_estimate_resolved(model, values, th, rtol=REF_RTOL, max_evals=5_000_000)


# ---------------------------------------------------------------------------------------------
# independent check of the reference


def _gl(a, b, n):
    x, w = np.polynomial.legendre.leggauss(n)
    return 0.5 * (b - a) * x + 0.5 * (b + a), 0.5 * (b - a) * w


def _composite(breaks, n):
    rules = [_gl(a, b, n) for a, b in zip(breaks[:-1], breaks[1:], strict=True) if b > a]
    return np.concatenate([r[0] for r in rules]), np.concatenate([r[1] for r in rules])


def _graded(centre, lo, hi):
    g = 1e-8 * 2.0 ** np.arange(60)
    g = g[g < hi - lo]
    return np.unique(np.clip(np.concatenate([np.linspace(lo, hi, 17), centre - g, centre + g,
                                             [centre]]), lo, hi))


def tensor_reference(model, values, th, n=20):
    """Tensor Gauss-Legendre in (θo, φo), φo ∈ [0, π] doubled (isotropic models)."""
    ti = math.radians(th)
    tb = np.unique(np.concatenate([_graded(ti, 0, np.pi / 2), _graded(np.pi / 2, 0, np.pi / 2)]))
    pb = np.unique(np.concatenate([_graded(0.0, 0.0, np.pi), [np.pi / 2]]))
    t, wt = _composite(tb, n)
    p, wp = _composite(pb, n)
    wi = from_degrees(th, 180.0)
    total = 0.0
    for s in range(0, len(t), 64):
        tt, ww = t[s:s + 64, None], wt[s:s + 64, None]
        wo = np.stack(np.broadcast_arrays(np.sin(tt) * np.cos(p), np.sin(tt) * np.sin(p),
                                          np.cos(tt)), -1).reshape(-1, 3)
        f = np.asarray(evaluate_resolved(model, values, np.broadcast_to(wi, wo.shape), wo))
        w = (np.cos(tt) * np.sin(tt) * ww * wp).reshape(-1)
        total = total + np.einsum("n,n...->...", w, f)
    return 2.0 * total


# ---------------------------------------------------------------------------------------------
# tables


def albedo_table(title, cases, thetas, refs):
    print(f"\n{title}")
    print(f"{'model':<14} {'params':<30} {'θi':>5} {'albedo':>10} {'est rel':>8} "
          f"{'err rel':>8} {'evals':>7} {'calls':>5} {'ms':>7}")
    rows = []
    for name, params in cases:
        model = get_model(name)
        values = model.resolve(params)
        for th in thetas:
            ref = reference(model, values, th)
            refs[(name, ptext(params), th)] = ref
            est, t = timed(q.albedo_estimate_resolved, model, values, th, repeat=7)
            n, calls = _evaluations(model, values, th)
            e_est = float(np.max(np.asarray(est.error) / np.abs(ref.value).clip(1e-300)))
            e = rel(est.value, ref.value)
            a = float(np.ravel(est.value)[-1 if np.ndim(est.value) == 0 else 1])
            print(f"{name:<14} {ptext(params):<30} {th:5.1f} {a:10.7f} {e_est:8.1e} {e:8.1e} "
                  f"{n:7d} {calls:5d} {t * 1e3:7.2f}")
            rows.append((name, ptext(params), th, e, e_est, n, t))
    return rows


def _evaluations(model, values, th):
    """Evaluations and kernel calls of the default albedo (they do not depend on the
    machine)."""
    _, n, calls = _run_counted(model, values, th, q.DEFAULT_RTOL)
    return n, calls


FITTED = ("abc", "sgd")  # RGB fits of measured data, ~1-1.5 µs per evaluation


def summary(rows, label):
    errs = np.array([r[3] for r in rows])
    ests = np.array([r[4] for r in rows])
    times = np.array([r[6] for r in rows])
    under = sum(1 for r in rows if r[3] > r[4])
    print(f"{label}: max error {errs.max():.1e}, max estimate {ests.max():.1e}, estimate below "
          f"the error in {under} of {len(rows)}; time median {np.median(times) * 1e3:.2f} ms, "
          f"max {times.max() * 1e3:.2f} ms")
    for name, sel in (("analytic models", [r for r in rows if r[0] not in FITTED]),
                      ("abc, sgd", [r for r in rows if r[0] in FITTED])):
        if sel:
            t = np.array([r[6] for r in sel]) * 1e3
            slow = sorted({f"{r[0]} {r[2]:g}°" for r in sel if r[6] > 2e-3})
            print(f"  {name}: ≤ 2 ms in {int((t <= 2.0).sum())} of {len(sel)}, median "
                  f"{np.median(t):.2f} ms, max {t.max():.2f} ms, evaluations median "
                  f"{int(np.median([r[5] for r in sel]))} max {max(r[5] for r in sel)}"
                  + (f"; above 2 ms: {', '.join(slow)}" if slow else ""))


def ref_check(refs):
    print("\nReference check: default rule at rtol 1e-13 against the tensor Gauss-Legendre rule"
          " (orders 20 and 28)")
    print(f"{'model':<14} {'params':<30} {'θi':>5} {'reference':>12} {'|Δ| rel':>9} "
          f"{'tensor conv':>11}")
    for name, params, th in [("ggx", {}, 89.0), ("ggx", {}, 89.9), ("cook-torrance", {}, 75.0),
                             ("oren-nayar", {}, 89.9), ("gltf", {}, 60.0), ("gltf", {}, 89.9),
                             ("abc", {}, 60.0), ("sgd", {}, 89.9),
                             ("ggx", HARD[0][1], 89.0), ("phong", HARD[4][1], 89.0)]:
        model = get_model(name)
        values = model.resolve(params)
        r = reference(model, values, th)
        t20 = tensor_reference(model, values, th, 20)
        t28 = tensor_reference(model, values, th, 28)
        a = float(np.ravel(r.value)[0])
        print(f"{name:<14} {ptext(params):<30} {th:5.1f} {a:12.9f} {rel(r.value, t28):9.1e} "
              f"{rel(t20, t28):11.1e}")


def methods_table(refs):
    print("\nSpeed against error: default rule (rtol), uniform mesh levels, adaptive mesh (tol)")
    print(f"{'model':<14} {'params':<30} {'θi':>5} {'method':<12} {'evals':>8} {'ms':>8} "
          f"{'err rel':>8}")
    cases = [("ggx", {}, 60.0), ("ggx", {}, 89.0), ("cook-torrance", {}, 85.0),
             ("oren-nayar", {}, 60.0), ("ggx", HARD[0][1], 60.0),
             ("cook-torrance", HARD[3][1], 85.0), ("phong", HARD[4][1], 30.0)]
    for name, params, th in cases:
        model = get_model(name)
        values = model.resolve(params)
        ref = refs.get((name, ptext(params), th)) or reference(model, values, th)
        wi = from_degrees(th, 180.0)

        def radiance(wo, m=model, v=values, wi=wi):
            f = np.asarray(evaluate_resolved(m, v, np.broadcast_to(wi, wo.shape), wo))
            return f * (wo[:, 2, None] if f.ndim == 2 else wo[:, 2])

        for rt in (1e-3, 1e-4, 1e-6, 1e-8, 1e-10):
            est, t = timed(q.albedo_estimate_resolved, model, values, th, rtol=rt, repeat=3)
            n, _ = _evaluations_rtol(model, values, th, rt)
            print(f"{name:<14} {ptext(params):<30} {th:5.1f} {'rtol ' + format(rt, 'g'):<12} "
                  f"{n:8d} {t * 1e3:8.2f} {rel(est.value, ref.value):8.1e}")
        for level in (5, 6, 7, 8):
            mesh = hemisphere(level)
            a, t = timed(lambda m=mesh: m.integrate(radiance(m.vertices)), repeat=3)
            print(f"{'':<14} {'':<30} {'':>5} {'level ' + str(level):<12} "
                  f"{len(mesh.vertices):8d} {t * 1e3:8.2f} {rel(a, ref.value):8.1e}")
        for tol in (1e-3, 1e-5):
            ad, t = timed(refine_adaptive, radiance, tol, max_level=q.adaptive_max_level(wi[2]),
                          focus=mirror(wi), repeat=1)
            print(f"{'':<14} {'':<30} {'':>5} {'adapt ' + format(tol, 'g'):<12} "
                  f"{ad.evaluations:8d} {t * 1e3:8.2f} {rel(ad.integrate(), ref.value):8.1e}")


def _evaluations_rtol(model, values, th, rtol):
    old = q.DEFAULT_RTOL
    try:
        q.DEFAULT_RTOL = rtol
        return _evaluations(model, values, th)
    finally:
        q.DEFAULT_RTOL = old


ABLATIONS = [
    ("as is", {}),
    ("halves at the horizon and breaks (END_LEVELS 0)", {"END_LEVELS": 0}),
    ("K15 on small panels too (SMALL_PANEL 0)", {"SMALL_PANEL": 0.0}),
    ("INNER_SHARE 0.5", {"INNER_SHARE": 0.5}),
    ("radial grading ratio 3 (GRADING 3)", {"GRADING": 3.0}),
    ("outer grading ratio 16 (OUTER_GRADING 16)", {"OUTER_GRADING": 16.0}),
    ("no horizon grading (HORIZON_SHARE inf)", {"HORIZON_SHARE": np.inf}),
    ("horizon grading at 0.03 rtol (HORIZON_SHARE)", {"HORIZON_SHARE": 0.03}),
    ("rtol 1e-6", {"rtol": 1e-6}),
    ("rtol 3e-5", {"rtol": 3e-5}),
    ("rtol 1e-4", {"rtol": 1e-4}),
]


def _run_counted(model, values, th, rtol):
    """``(estimate, evaluations, kernel calls)`` of the default rule at ``rtol``."""
    return q.albedo_rule_counted(model, values, th, rtol=rtol)


def ablation_table(refs):
    """Each refinement choice undone (or a constant changed) in turn, on the analytic models'
    defaults (80 cases) and the hard cases (48): evaluations and kernel calls (the same on
    every machine), worst error and estimate, and the summed time (best of 3 each)."""
    from tuibrdf.core.sphere import integrator
    from tuibrdf.core.sphere.integrator import adaptive, geometry, horizon_cut, rules

    # a constant is read in the module that defines it (and albedo reads the ones the package
    # re-exports): a change is set in every module that binds the name
    modules = (integrator, adaptive, geometry, horizon_cut, rules)

    print("\nRefinement choices, one changed at a time: analytic models' defaults (80 cases) | "
          "hard cases (48)")
    print(f"{'variant':<48} {'evals':>7} {'calls':>5} {'max':>3} {'>1':>3} {'max err':>8} "
          f"{'under':>5} {'sum ms':>7} | {'evals':>7} {'calls':>5} {'max err':>8} {'under':>5}")
    cases = [(n, p, th) for n, p, th in _case_list() if n not in FITTED]
    for name, params, th in cases:  # warm-up
        model = get_model(name)
        _run_counted(model, model.resolve(params), th, q.DEFAULT_RTOL)
    for label, change in ABLATIONS:
        rtol = change.get("rtol", q.DEFAULT_RTOL)
        old = {(m, k): getattr(m, k) for k in change if k != "rtol" for m in modules
               if hasattr(m, k)}
        assert {k for _, k in old} == set(change) - {"rtol"}, change  # every name found
        for m, k in old:
            setattr(m, k, change[k])
        try:
            stats = {True: [], False: []}
            for name, params, th in cases:
                model = get_model(name)
                values = model.resolve(params)
                (r, n, c), t = timed(_run_counted, model, values, th, rtol, repeat=3)
                ref = refs[(name, ptext(params), th)]
                e = rel(r.value[0], ref.value)
                est = float(np.max(np.asarray(r.error[0]) / np.abs(ref.value).clip(1e-300)))
                stats[not params].append((n, c, e, est, t))
        finally:
            for (m, k), v in old.items():
                setattr(m, k, v)
        d, h = stats[True], stats[False]
        print(f"{label:<48} {sum(x[0] for x in d):7d} {sum(x[1] for x in d):5d} "
              f"{max(x[1] for x in d):3d} {sum(x[1] > 1 for x in d):3d} "
              f"{max(x[2] for x in d):8.1e} {sum(x[2] > x[3] for x in d):5d} "
              f"{sum(x[4] for x in d) * 1e3:7.1f} | {sum(x[0] for x in h):7d} "
              f"{sum(x[1] for x in h):5d} {max(x[2] for x in h):8.1e} "
              f"{sum(x[2] > x[3] for x in h):5d}")
    print("(evals, calls: totals; max: most calls for one albedo; >1: albedos needing more than "
          "one call; under: estimate below the error)")


def curve_table():
    print("\n91-point albedo curve (θi = 0…90° by 1°, one batch)")
    print(f"{'model':<14} {'params':<30} {'ms':>8} {'max est rel':>11}")
    for name, params in DEFAULTS + [("ggx", {"alpha": 0.01}), ("cook-torrance", {"m": 0.01}),
                                    HARD[0], HARD[2]]:
        model = get_model(name)
        values = model.resolve(params)
        est, t = timed(q.albedo_curve_estimate_resolved, model, values, np.arange(91.0),
                       repeat=3)
        e = float(np.max(np.asarray(est.error) / np.abs(est.value).clip(1e-300)))
        print(f"{name:<14} {ptext(params):<30} {t * 1e3:8.1f} {e:11.1e}")


MERL_CHILD = r"""
import sys, time, json
import numpy as np
from tuibrdf.core.formats import merl
from tuibrdf.core.sphere import albedo as q
f, lookup = sys.argv[1], sys.argv[2]
merl.load_cached(f)
out = []
for th in (0.0, 60.0, 89.0, 90.0):
    t = time.perf_counter()
    est = q.albedo_estimate("merl", {"file": f, "lookup": lookup}, th)
    out.append((th, float(np.ravel(est.value)[1]), float(np.ravel(est.error)[1]),
                time.perf_counter() - t))
t = time.perf_counter()
q.albedo_curve_resolved(q.get_model("merl"), {"file": f, "lookup": lookup}, np.arange(91.0))
curve = time.perf_counter() - t
# VmHWM: this process's peak resident set (ru_maxrss would include the parent's, kept
# across fork and exec)
hwm = [int(x.split()[1]) for x in open("/proc/self/status") if x.startswith("VmHWM")][0]
print(json.dumps([out, curve, hwm]))
"""


def merl_table():
    sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))
    from merl_writer import table_from_directions, write_merl

    import tuibrdf

    print("\nMERL (synthetic file: cook-torrance m = 0.05, kd = 0.3, f0 = 0.5 sampled on the "
          "MERL grid; green channel)")
    print(f"{'lookup':<10} {'θi':>5} {'albedo':>9} {'est':>8} {'ms':>8}")
    with tempfile.TemporaryDirectory() as d:
        path = Path(d) / "shiny.binary"
        write_merl(path, table_from_directions(
            lambda wi, wo: tuibrdf.evaluate("cook-torrance", {"m": 0.05, "kd": 0.3, "f0": 0.5},
                                            wi, wo)))
        for lookup in ("trilinear", "nearest"):
            res = subprocess.run([sys.executable, "-c", MERL_CHILD, str(path), lookup],
                                 capture_output=True, text=True, check=True, env=os.environ)
            rows, curve, rss = json.loads(res.stdout)
            for th, a, e, t in rows:
                print(f"{lookup:<10} {th:5.1f} {a:9.5f} {e:8.1e} {t * 1e3:8.1f}")
            print(f"{lookup:<10} 91-point curve {curve:.2f} s; process peak memory "
                  f"{rss / 1024:.0f} MB (35 MB of it the file)")


BEFORE_CHILD = r"""
import json, sys, time
import numpy as np
from tuibrdf.core.registry import get_model
from tuibrdf.core.sphere.albedo import albedo_resolved
out = []
for name, params, th in json.loads(sys.stdin.read()):
    try:
        m = get_model(name)
    except Exception:  # not in that revision
        out.append(None)
        continue
    v = m.resolve(params)
    best, spent = float("inf"), 0.0
    for _ in range(7):  # best of 7, or of as many as fit in 0.5 s
        t = time.perf_counter(); a = albedo_resolved(m, v, th)
        best = min(best, time.perf_counter() - t)
        spent += time.perf_counter() - t
        if spent > 0.5:
            break
    out.append([np.atleast_1d(a).tolist(), best])
print(json.dumps(out))
"""


TIMING_CHILD = r"""
import json, sys, time
import numpy as np
from tuibrdf.core.sphere import albedo as q
from tuibrdf.core.registry import get_model
cases, repeat = json.loads(sys.stdin.read())
# a fresh process's heap gives the temporaries back to the system after every call (glibc
# trims above 128 KB) and page-faults them in again on the next: up to 3x the kernel's time
# per point (scripts/bench_kernels.py).  Freeing one large block raises glibc's thresholds,
# as happens early in any long-running process (the viewer; the main table here, after its
# references)
warm = np.ones(2**21)
del warm
count = [0, 0]
plain = q.evaluate_resolved


def counted(model, values, wi, wo):
    count[0] += 1
    count[1] += len(wo)
    return plain(model, values, wi, wo)


out = []
for name, params, th in cases:
    m = get_model(name)
    v = m.resolve(params)
    q.evaluate_resolved = counted
    count[:] = [0, 0]
    q.albedo_estimate_resolved(m, v, th)
    calls, evals = count
    q.evaluate_resolved = plain
    best = float("inf")
    for _ in range(repeat):
        t = time.perf_counter(); q.albedo_estimate_resolved(m, v, th)
        best = min(best, time.perf_counter() - t)
    out.append([evals, calls, best])
print(json.dumps(out))
"""


def interleaved_table(rev, rounds=6, repeat=5, models=None):
    """The 80 default analytic albedos (or those of ``models``) timed in this tree and in
    revision REV's, in alternating subprocesses (``rounds`` each, best of ``repeat`` per round,
    best over the rounds: both trees see the same load), with each one's evaluations and
    kernel calls (counted in the child by wrapping the evaluation: the same on every
    machine)."""
    names = [n for n, _ in DEFAULTS if n not in FITTED] if models is None else models
    cases = [(n, {}, th) for n in names for th in THETAS]
    payload = json.dumps([cases, repeat])
    best = {"now": None, rev: None}
    with tempfile.TemporaryDirectory() as d:
        extract(rev, d)
        here = str(Path(__file__).resolve().parent.parent)
        for _ in range(rounds):
            for label, path in (("now", here), (rev, d)):
                env = dict(os.environ, PYTHONPATH=path)
                res = subprocess.run([sys.executable, "-c", TIMING_CHILD], input=payload,
                                     capture_output=True, text=True, check=True, env=env,
                                     cwd=path)
                got = json.loads(res.stdout)
                best[label] = got if best[label] is None else [
                    [a[0], a[1], min(a[2], b[2])] for a, b in zip(best[label], got,
                                                                   strict=True)]
    print(f"\nDefault albedos of {'the analytic models' if models is None else ', '.join(names)}"
          f", interleaved with {rev} ({rounds} alternating rounds, best of {repeat} each)")
    print(f"{'model':<18} {'θi':>5} {'evals':>7} {'calls':>5} {'ms':>6} | {'evals':>7} "
          f"{'calls':>5} {'ms':>6}   (before | now)")
    for (name, _, th), b, a in zip(cases, best[rev], best["now"], strict=True):
        mark = "  *" if (a[0], a[1]) != (b[0], b[1]) else ""
        print(f"{name:<18} {th:5.1f} {b[0]:7d} {b[1]:5d} {b[2] * 1e3:6.2f} | {a[0]:7d} "
              f"{a[1]:5d} {a[2] * 1e3:6.2f}{mark}")
    for label in (rev, "now"):
        r = best[label]
        t = np.array([x[2] for x in r]) * 1e3
        slow = [f"{c[0]} {c[2]:g}° {x[2] * 1e3:.2f} ms" for c, x in zip(cases, r, strict=True)
                if x[2] > 2e-3]
        print(f"{label}: ≤ 2 ms in {int((t <= 2.0).sum())} of {len(t)}, median "
              f"{np.median(t):.2f} ms, max {t.max():.2f} ms; evaluations {sum(x[0] for x in r)}, "
              f"kernel calls {sum(x[1] for x in r)} (albedos needing more than one: "
              f"{sum(x[1] > 1 for x in r)})" + (f"; above 2 ms: {', '.join(slow)}" if slow else ""))
    print("(*: evaluations or calls changed)")


def before_table(rev, refs, after_rows):
    cases = [(n, p, th) for (n, p, th) in _case_list()]
    with tempfile.TemporaryDirectory() as d:
        extract(rev, d)
        env = dict(os.environ, PYTHONPATH=d)
        res = subprocess.run([sys.executable, "-c", BEFORE_CHILD],
                             input=json.dumps(cases), capture_output=True, text=True,
                             check=True, env=env, cwd=d)
    got = json.loads(res.stdout)
    after = {(r[0], r[1], r[2]): r for r in after_rows}
    print(f"\nBefore ({rev}) and after: default albedo, error against the same references")
    print(f"{'model':<14} {'params':<30} {'θi':>5} {'before err':>10} {'ms':>8} "
          f"{'after err':>10} {'ms':>8}")
    above = 0
    times = []
    for (name, params, th), res in zip(cases, got, strict=True):
        r = after[(name, ptext(params), th)]
        if res is None:
            print(f"{name:<14} {ptext(params):<30} {th:5.1f} {'-':>10} {'-':>8} "
                  f"{r[3]:10.1e} {r[6] * 1e3:8.2f}")
            continue
        a, t = res
        times.append((name, params, th, t))
        ref = refs[(name, ptext(params), th)]
        ev = np.asarray(ref.value, dtype=float)
        a = np.asarray(a, dtype=float).reshape(ev.shape)
        if np.any(a > 1.0 + 1e-9) and np.all(ev <= 1.0 + 1e-9):  # truth 1 to rounding
            above += 1
        print(f"{name:<14} {ptext(params):<30} {th:5.1f} {rel(a, ev):10.1e} {t * 1e3:8.2f} "
              f"{r[3]:10.1e} {r[6] * 1e3:8.2f}")
    print(f"before: {above} cases above 1 (by > 1e-9) where the reference is ≤ 1")
    dflt = [t * 1e3 for name, params, th, t in times if not params and name not in FITTED]
    if dflt:
        print(f"before, analytic models' defaults: ≤ 2 ms in {sum(x <= 2.0 for x in dflt)} of "
              f"{len(dflt)}, median {np.median(dflt):.2f} ms, max {max(dflt):.2f} ms")


def _case_list():
    return ([(n, p, th) for n, p in DEFAULTS for th in THETAS]
            + [(n, p, th) for n, p in HARD for th in HARD_THETAS])


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--before", metavar="REV", action="append", default=[],
                    help="also run the albedo of git revision REV (may be repeated)")
    ap.add_argument("--quick", action="store_true", help="albedo tables only")
    ap.add_argument("--interleave", metavar="REV",
                    help="only time the 80 default analytic albedos here and in REV, "
                         "alternating (evaluations, calls, times)")
    ap.add_argument("--models", metavar="NAMES",
                    help="with --interleave: these models' defaults instead (comma-separated, "
                         "e.g. abc,sgd)")
    args = ap.parse_args(argv)
    if args.models and not args.interleave:
        ap.error("--models goes with --interleave")
    if args.interleave:
        models = None
        if args.models:
            models = [x.strip() for x in args.models.split(",") if x.strip()]
            for n in models:
                get_model(n)  # a typo fails here, with the registry's suggestion
        interleaved_table(args.interleave, models=models)
        return 0
    t0 = time.perf_counter()
    print(f"defaults: DEFAULT_RTOL = {q.DEFAULT_RTOL:g}, MAX_EVALS = {q.MAX_EVALS}")
    refs: dict = {}
    rows = albedo_table("Default albedo at every model's defaults (error: max over channels, "
                        "relative to the reference)", DEFAULTS, THETAS, refs)
    summary(rows, "defaults")
    hard = albedo_table("Default albedo on the hard cases", HARD, HARD_THETAS, refs)
    summary(hard, "hard cases")
    for rev in args.before:
        before_table(rev, refs, rows + hard)
    if not args.quick:
        ablation_table(refs)
        ref_check(refs)
        methods_table(refs)
        curve_table()
        merl_table()
        map_table()
        variants_table()
        precision_table()
    print(f"\ntotal time {time.perf_counter() - t0:.1f} s")
    return 0


# ---------------------------------------------------------------------------------------------
# map and formula variants (unchanged from issue 6)


def equal_area_grid(px):
    """Directions at the pixel centres of a ``px × px`` equal-area (Lambert azimuthal) disc."""
    c = (np.arange(px) + 0.5) / px * 2 - 1
    x, y = np.meshgrid(c, c)
    r = np.hypot(x, y)
    inside = r <= 1.0
    theta = 2 * np.degrees(np.arcsin(np.minimum(r, 1.0) / np.sqrt(2)))
    phi = np.degrees(np.arctan2(y, x))
    return from_degrees(theta[inside], phi[inside])


def map_table():
    print("\nMap: barycentric interpolation of mesh vertex values vs exact per-pixel evaluation, "
          "160×160 equal-area disc, θi = 30°;\nerror relative to the map's peak (one grey level "
          "of 256 = 3.9e-3)")
    print(f"{'model':<15} {'params':<16} {'method':<9} {'time ms':>8} {'max err':>9} "
          f"{'mean err':>9}")
    dirs = equal_area_grid(160)
    wi = from_degrees(30.0, 180.0)
    for name, params in [("phong", {}), ("cook-torrance", {}), ("ggx", {}),
                         ("ggx", {"alpha": 0.05})]:
        model = get_model(name)
        values = model.resolve(params)

        def exact(v=values, m=model):
            return np.asarray(evaluate_resolved(m, v, np.broadcast_to(wi, dirs.shape), dirs))

        ex, t_ex = timed(exact, repeat=3)
        top = ex.max()
        print(f"{name:<15} {ptext(params):<16} {'exact':<9} {t_ex * 1e3:8.2f} {0:9.1e} "
              f"{0:9.1e}")
        for level in range(3, 8):
            mesh = hemisphere(level)

            def via_mesh(mesh=mesh, v=values, m=model):
                vals = evaluate_resolved(m, v, np.broadcast_to(wi, mesh.vertices.shape),
                                         mesh.vertices)
                return interpolate(mesh, vals, dirs)

            got, t = timed(via_mesh, repeat=3)
            err = np.abs(got - ex) / top
            print(f"{'':<15} {'':<16} {'level ' + str(level):<9} {t * 1e3:8.2f} "
                  f"{err.max():9.1e} {err.mean():9.1e}")


def variants_table():
    print("\nFormula variants (default albedo and peak value; differences are absolute for "
          "albedo, relative for the peak)")
    print(f"{'variant':<44} {'θi':>4} {'albedo A':>9} {'albedo B':>9} {'Δalbedo':>9} "
          f"{'Δpeak rel':>9}")
    pairs = []
    for name in ("cook-torrance", "ggx"):
        for f0 in (0.04, 0.5):
            pairs.append((f"{name} f0={f0:g}: exact vs schlick Fresnel",
                          (name, {"f0": f0, "fresnel": "exact"}),
                          (name, {"f0": f0, "fresnel": "schlick"})))
    for sigma in (20.0, 60.0):
        pairs.append((f"oren-nayar σ={sigma:g}°: full vs simple",
                      ("oren-nayar", {"sigma": sigma}), ("oren-nayar-simple", {"sigma": sigma})))
    for label, (na, pa), (nb, pb) in pairs:
        ma, mb = get_model(na), get_model(nb)
        va, vb = ma.resolve(pa), mb.resolve(pb)
        for th in (0.0, 60.0, 85.0):
            aa = q.albedo_resolved(ma, va, th)
            ab = q.albedo_resolved(mb, vb, th)
            qa = find_peaks(ma, va, incident(th))[0].value
            qb = find_peaks(mb, vb, incident(th))[0].value
            print(f"{label:<44} {th:4.0f} {aa:9.5f} {ab:9.5f} {ab - aa:9.2e} "
                  f"{(qb - qa) / qa:9.2e}")


def precision_table():
    print("\nfloat32 vs float64 input: 160×160 equal-area disc at θi = 60°, each model's defaults "
          "(best of 5); the kernels'\nfloat64 constants promote float32 input part-way, so the "
          "output stays float64; the input rounding alone moves f by 'max rel'\n(of the map's "
          "peak)")
    print(f"{'model':<18} {'out dtype':>9} {'f64 ms':>8} {'f32 ms':>8} {'max rel':>9}")
    dirs = equal_area_grid(160)
    wi = np.broadcast_to(from_degrees(60.0, 180.0), dirs.shape)
    wi32, dirs32 = wi.astype(np.float32), dirs.astype(np.float32)
    for name in ("phong", "cook-torrance", "ggx", "oren-nayar", "gltf"):
        model = get_model(name)
        values = model.resolve({})
        f64, t64 = timed(lambda m=model, v=values: np.asarray(evaluate_resolved(m, v, wi, dirs)))
        f32, t32 = timed(lambda m=model, v=values: np.asarray(
            evaluate_resolved(m, v, wi32, dirs32)))
        top = float(np.max(f64))
        err = float(np.max(np.abs(f32.astype(float) - f64))) / top
        print(f"{name:<18} {str(f32.dtype):>9} {t64 * 1e3:8.2f} {t32 * 1e3:8.2f} {err:9.1e}")


if __name__ == "__main__":
    raise SystemExit(main())
