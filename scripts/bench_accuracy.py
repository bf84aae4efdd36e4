"""Speed against error for the hemisphere quadrature (issue 6; docs/accuracy.md).

    python scripts/bench_accuracy.py            # ~1-2 minutes on a shared 2-core machine

For each model family and each hard case it prints, per way of computing the directional
albedo (uniform icosahedral level 2…7, adaptive refinement at several tolerances): the time,
the number of BRDF evaluations and the error against a converged reference.  Then the map
(barycentric interpolation of a mesh level vs exact per-pixel evaluation), and the formula
variants: exact Fresnel vs Schlick, Oren-Nayar full vs simple, float64 vs float32.

References: smooth cases use Richardson extrapolation of uniform levels 8 and 9 (the rule is
second order, so ``(4·a9 − a8)/3``; the ± printed is a9's own error estimate |a9 − a8|/3, a
generous bound); sharp lobes use adaptive refinement at tol 1e-8 down to level 13 (0.008°
edges; 14 at θi = 89°), ± = its change from one level less.  Times are best of 2-3 runs
with the meshes prebuilt; "auto" is what ``albedo()`` does by default; adaptive rows stop at
the quadrature's max level (10, up to 13 at grazing incidence).  Numbers depend on the
machine; errors do not.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from tuibrdf.core.evaluate import evaluate_resolved
from tuibrdf.core.frame import from_degrees, incident, mirror
from tuibrdf.core.mesh import hemisphere, interpolate, refine_adaptive
from tuibrdf.core.models import get_model
from tuibrdf.core.quadrature import (
    DEFAULT_LEVEL,
    DEFAULT_TOL,
    adaptive_max_level,
    albedo_resolved,
    peak_resolved,
)

FAMILIES = [
    ("lambert", {}),
    ("phong", {}),
    ("cook-torrance", {}),
    ("ggx", {}),
    ("oren-nayar", {}),
    ("disney-diffuse", {}),
]
HARD = [
    ("cook-torrance", {"m": 0.01, "f0": 1.0}),
    ("ggx", {"alpha": 0.005, "f0": 1.0}),
    ("phong", {"kd": 0.0, "ks": 1.0, "n": 5000.0}),
]
HARD_THETAS = [0.0, 60.0, 85.0, 89.0]
LEVELS = range(2, 8)
HARD_LEVELS = range(2, 10)  # sharp lobes: uniform up to 1.3 million evaluations
TOLS = [1e-2, 1e-3, 1e-4, 1e-5]


def timed(fn, *args, repeat=1):
    best = np.inf
    for _ in range(repeat):
        t = time.perf_counter()
        out = fn(*args)
        best = min(best, time.perf_counter() - t)
    return out, best


def radiance(model, values, wi, wo):
    f = np.asarray(evaluate_resolved(model, values, np.broadcast_to(wi, wo.shape), wo))
    if f.ndim == 2:  # RGB: the green channel stands for all three here
        f = f[:, 1]
    return f * wo[:, 2]


def uniform_albedo(model, values, wi, level):
    m = hemisphere(level)
    return float(m.integrate(radiance(model, values, wi, m.vertices))), len(m.vertices)


def adaptive_albedo(model, values, wi, tol, max_level=None):
    max_level = max_level or adaptive_max_level(wi[2])
    a = refine_adaptive(lambda w: radiance(model, values, wi, w), tol, max_level=max_level,
                        focus=mirror(wi))
    return float(a.integrate()), a.evaluations


def reference(model, values, wi, sharp):
    """``(reference, uncertainty)``: see the module docstring."""
    if sharp:
        hi = max(13, adaptive_max_level(wi[2]) + 2)
        a_lo = adaptive_albedo(model, values, wi, 1e-8, max_level=hi - 1)[0]
        a_hi = adaptive_albedo(model, values, wi, 1e-8, max_level=hi)[0]
        return a_hi, abs(a_hi - a_lo)
    a8 = uniform_albedo(model, values, wi, 8)[0]
    a9 = uniform_albedo(model, values, wi, 9)[0]
    return (4 * a9 - a8) / 3, abs(a9 - a8) / 3


def auto_albedo(model, values, th):
    a = albedo_resolved(model, values, th)
    return float(a[1]) if np.ndim(a) else a  # RGB: green, as radiance() does


def albedo_table(cases, sharp):
    print(f"{'model':<15} {'params':<22} {'θi':>4}  {'method':<11} {'evals':>8} "
          f"{'time ms':>8} {'|err|':>9}")
    summary = []
    for name, params in cases:
        model = get_model(name)
        values = model.resolve(params)
        thetas = HARD_THETAS if sharp else [30.0, 75.0]
        for th in thetas:
            wi = incident(th)
            ref, unc = reference(model, values, wi, sharp)
            ptxt = ",".join(f"{k}={v:g}" for k, v in params.items()) or "defaults"
            rows = []
            for level in (HARD_LEVELS if sharp else LEVELS):
                (a, n), t = timed(uniform_albedo, model, values, wi, level, repeat=3)
                rows.append((f"level {level}", n, t, abs(a - ref)))
            for tol in TOLS:
                (a, n), t = timed(adaptive_albedo, model, values, wi, tol, repeat=2)
                rows.append((f"tol {tol:g}", n, t, abs(a - ref)))
            a, t = timed(auto_albedo, model, values, th, repeat=2)
            rows.append(("auto", 0, t, abs(a - ref)))
            for label, n, t, err in rows:
                print(f"{name:<15} {ptxt:<22} {th:4.0f}  {label:<11} {n or '':>8} "
                      f"{t * 1e3:8.2f} {err:9.2e}")
            print(f"{'':<15} {'':<22} {'':>4}  {'reference':<11} {'':>8} {'':>8} {ref:9.6f}"
                  f"  ± {unc:.1e}")
            summary.append((name, ptxt, th, rows))
    return summary


def evals_at_equal_error(summary, target):
    """Fewest evaluations reaching |err| ≤ target, uniform vs adaptive, per case."""
    print(f"\nEvaluations to reach |albedo error| ≤ {target:g} (— = not reached by uniform "
          "level 7, 9 for hard cases / adaptive tol 1e-5)")
    print(f"{'model':<15} {'params':<22} {'θi':>4} {'uniform':>9} {'adaptive':>9} {'ratio':>7}")
    for name, ptxt, th, rows in summary:
        uni = [n for lab, n, _, e in rows if lab.startswith("level") and e <= target]
        # tol rows ascend in cost
        ada = [n for lab, n, _, e in rows if lab.startswith("tol") and e <= target]
        u = min(uni) if uni else None
        a = min(ada) if ada else None
        ratio = f"{u / a:7.1f}" if u and a else "      —"
        print(f"{name:<15} {ptxt:<22} {th:4.0f} {u or '—':>9} {a or '—':>9} {ratio}")


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
    wi = incident(30.0)
    cases = FAMILIES[1:4] + [("ggx", {"alpha": 0.05})]
    for name, params in cases:
        model = get_model(name)
        values = model.resolve(params)

        def exact(v=values, m=model):
            return np.asarray(evaluate_resolved(m, v, np.broadcast_to(wi, dirs.shape), dirs))

        ex, t_ex = timed(exact, repeat=3)
        top = ex.max()
        ptxt = ",".join(f"{k}={v:g}" for k, v in params.items()) or "defaults"
        print(f"{name:<15} {ptxt:<16} {'exact':<9} {t_ex * 1e3:8.2f} {0:9.1e} {0:9.1e}")
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
    print("\nFormula variants (albedo at level 7 and peak value; differences are absolute for "
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
            aa = albedo_resolved(ma, va, th, level=7)
            ab = albedo_resolved(mb, vb, th, level=7)
            qa = peak_resolved(ma, va, th).value
            qb = peak_resolved(mb, vb, th).value
            print(f"{label:<44} {th:4.0f} {aa:9.5f} {ab:9.5f} {ab - aa:9.2e} "
                  f"{(qb - qa) / qa:9.2e}")

    print("\nfloat64 vs float32 (directions and kernel arithmetic in float32, sums in float64; "
          "level 7, θi = 60°)")
    print(f"{'model':<15} {'params':<22} {'t64 ms':>8} {'t32 ms':>8} {'Δalbedo rel':>11} "
          f"{'Δmax rel':>9} {'dtype':>8}")
    mesh = hemisphere(7)
    wi = incident(60.0)
    for name, params in FAMILIES[1:] + HARD:
        model = get_model(name)
        values = model.resolve(params)
        v64 = mesh.vertices
        v32 = v64.astype(np.float32)
        w32 = wi.astype(np.float32)

        def run(v, w, m=model, vals=values):
            return np.asarray(evaluate_resolved(m, vals, np.broadcast_to(w, v.shape), v))

        f64, t64 = timed(run, v64, wi, repeat=3)
        try:
            f32, t32 = timed(run, v32, w32, repeat=3)
        except FloatingPointError as e:  # float32 overflows where float64 does not
            print(f"{name:<15} {'':<22} {t64 * 1e3:8.2f} {'—':>8}  float32 raised: {e}")
            continue
        c = mesh.vertices[:, 2]
        c = c[:, None] if f64.ndim == 2 else c
        a64 = mesh.integrate(f64 * c)
        a32 = mesh.integrate(f32.astype(float) * c)
        da = float(np.max(np.abs(a32 - a64) / np.maximum(np.abs(a64), 1e-300)))
        dm = float(np.max(np.abs(f32.max() - f64.max()) / f64.max()))
        ptxt = ",".join(f"{k}={v:g}" for k, v in params.items()) or "defaults"
        print(f"{name:<15} {ptxt:<22} {t64 * 1e3:8.2f} {t32 * 1e3:8.2f} {da:11.1e} {dm:9.1e} "
              f"{str(f32.dtype):>8}")


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--quick", action="store_true", help="hard cases only")
    args = p.parse_args(argv)
    t0 = time.perf_counter()
    for level in range(2, 10):  # build (and cache) the meshes outside the timings
        hemisphere(level)
    print(f"defaults: DEFAULT_LEVEL = {DEFAULT_LEVEL}, DEFAULT_TOL = {DEFAULT_TOL:g}\n")
    print("Directional albedo, model families (θi = 30°, 75°)")
    fam = [] if args.quick else albedo_table(FAMILIES, sharp=False)
    print("\nDirectional albedo, hard cases (sharp lobes; f0 = 1 so Fresnel does not hide them)")
    hard = albedo_table(HARD, sharp=True)
    evals_at_equal_error(fam + hard, 1e-3)
    evals_at_equal_error(hard, 1e-4)
    if not args.quick:
        map_table()
        variants_table()
    print(f"\ntotal time {time.perf_counter() - t0:.1f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
