"""Benchmark user-file models against their built-in equivalents: the cost of one map.

    python scripts/bench_formats.py [--repeat N]

For each pair, the best-of-N time (ms; the two timed alternately, so both see the same load)
of ``map_values`` (the Lambert equal-area map, exact per-pixel evaluation, as the viewer draws
it) at the main map's pixel size for a 160×48 and an 80×24 terminal (``2·(h − 3)`` pixel rows,
as scripts/bench_render.py), and the ratio file/built-in.  Also the one-off costs: loading
(parsing + compiling) a ``.brdf`` file and loading a synthetic ``.bsdf``.  Prints Markdown
tables (docs/reference/formats.md quotes the ratio).
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))

from tuibrdf.core.directions import incident  # noqa: E402
from tuibrdf.core.formats import userfiles  # noqa: E402
from tuibrdf.core.registry import get_model  # noqa: E402
from tuibrdf.core.views.hemimap import map_values  # noqa: E402

DATA = ROOT / "tests" / "data" / "brdf"
PAIRS = [
    # (file, its parameters, the built-in model, its parameters): the same BRDF
    ("ggx.brdf", {"kd": 0.2, "f0": 0.04, "alpha": 0.2},
     "ggx", {"kd": 0.2, "f0": 0.04, "alpha": 0.2, "fresnel": "exact"}),
    ("orennayar.brdf", {"rho": 0.8, "sigma": 20.0}, "oren-nayar", {"kd": 0.8, "sigma": 20.0}),
    ("lambert.brdf", {"reflectance": (0.8, 0.8, 0.8)}, "lambert", {"kd": 0.8}),
    ("disney.brdf", {}, None, None),
]
SIZES = [(160, 48), (80, 24)]


def ms(fn, repeat: int) -> float:
    fn()  # warm: caches filled, as in the app
    out = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        out.append((time.perf_counter() - t0) * 1e3)
    return min(out)  # best of N: the machine is shared, the minimum is the least disturbed


def ms_pair(fa, fb, repeat: int) -> tuple[float, float]:
    """Best-of-N of two functions timed alternately, so both see the same machine load."""
    fa()
    fb()
    ta, tb = [], []
    for _ in range(repeat):
        for fn, out in ((fa, ta), (fb, tb)):
            t0 = time.perf_counter()
            fn()
            out.append((time.perf_counter() - t0) * 1e3)
    return min(ta), min(tb)


def bench_maps(repeat: int) -> None:
    print("| file | built-in | cells | file ms | built-in ms | ratio |")
    print("|---|---|---|---|---|---|")
    wi = incident(30.0)
    for fname, fparams, bname, bparams in PAIRS:
        fm = get_model(str(DATA / fname))
        fv = fm.resolve(fparams)
        for w, h in SIZES:
            px_w, px_h = w, 2 * (h - 3)
            if bname is None:
                tf = ms(lambda m=fm, v=fv, a=px_w, b=px_h: map_values(m, v, wi, a, b), repeat)
                print(f"| {fname} | — | {w}×{h} | {tf:.2f} | — | — |")
                continue
            bm = get_model(bname)
            bv = bm.resolve(bparams)
            tf, tb = ms_pair(lambda m=fm, v=fv, a=px_w, b=px_h: map_values(m, v, wi, a, b),
                             lambda m=bm, v=bv, a=px_w, b=px_h: map_values(m, v, wi, a, b),
                             repeat)
            print(f"| {fname} | {bname} | {w}×{h} | {tf:.2f} | {tb:.2f} | {tf / tb:.2f} |")


def bench_loading(repeat: int) -> None:
    from rgl_writer import material, write_tensor

    print()
    print("| one-off | ms |")
    print("|---|---|")
    for fname in ("ggx.brdf", "disney.brdf"):
        def load(f=fname):
            userfiles.clear_cache()
            get_model(str(DATA / f))
        print(f"| load + compile {fname} | {ms(load, repeat):.1f} |")
    with tempfile.TemporaryDirectory() as d:
        path = write_tensor(Path(d) / "m.bsdf", material(n_phi=1, n_theta=8, n=32))

        def load_bsdf():
            userfiles.clear_cache()
            get_model(str(path))
        t = ms(load_bsdf, repeat)
        print(f"| load synthetic .bsdf (1×8 incidences, 32×32, RGB) | {t:.1f} |")
        m = get_model(str(path))
        t = ms(lambda: map_values(m, m.defaults(), incident(30.0), 160, 90), repeat)
        print(f"| map of that .bsdf at 160×48 | {t:.1f} |")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=15)
    args = ap.parse_args()
    bench_maps(args.repeat)
    bench_loading(max(3, args.repeat // 3))


if __name__ == "__main__":
    main()
