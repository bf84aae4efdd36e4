"""MERL reader, lookup and fit: time and memory on full-size synthetic files.

    python scripts/bench_merl.py            # prints a table (docs/reference/formats.md quotes it)

Writes two 35 MB files into a temporary directory (removed at the end): one from the ggx model
(alpha 0.2, per-channel f0 and kd) and one from cook-torrance (m 0.3), with -1 (invalid) below
the horizon as in MERL's own files.  Memory of the load is measured twice: numpy's allocations
through ``tracemalloc`` (numpy reports them) and the growth of the process's peak RSS.
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
import time
import tracemalloc
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from merl_writer import table_from_directions, write_merl  # noqa: E402

from tuibrdf.core import fit
from tuibrdf.core.directions import from_degrees  # noqa: E402
from tuibrdf.core.evaluate import evaluate  # noqa: E402
from tuibrdf.core.formats import merl  # noqa: E402

GGX = [{"alpha": 0.2, "f0": 0.9, "kd": 0.1}, {"alpha": 0.2, "f0": 0.6, "kd": 0.2},
       {"alpha": 0.2, "f0": 0.3, "kd": 0.05}]
CT = [{"m": 0.3, "f0": f0, "kd": 0.3} for f0 in (0.9, 0.6, 0.3)]


# VmHWM (peak RSS of this process image) rather than ru_maxrss, which Linux carries over
# from the parent across fork + exec
RSS_CHILD = """
import sys
from tuibrdf.core.formats import merl
def hwm():
    for line in open("/proc/self/status"):
        if line.startswith("VmHWM:"):
            return int(line.split()[1])  # kB
h0 = hwm()
data = merl.load(sys.argv[1])
print(f"{(hwm() - h0) / 1e3:.1f}")
"""


def per_channel(name, params):
    def fn(wi, wo):
        return np.stack([evaluate(name, p, wi, wo) for p in params], axis=-1)
    return fn


def best_of(n, fn):
    times = []
    for _ in range(n):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return min(times)


def main() -> None:
    with tempfile.TemporaryDirectory() as d:
        ggx_path = write_merl(Path(d) / "ggx.binary", table_from_directions(per_channel("ggx",
                                                                                    GGX)))
        ct_path = write_merl(Path(d) / "ct.binary",
                             table_from_directions(per_channel("cook-torrance", CT)))
        # ---- load: memory first; the RSS growth in a fresh process (this one is already big)
        child = subprocess.run(
            [sys.executable, "-c", RSS_CHILD, str(ggx_path)], capture_output=True, text=True,
            check=True, cwd=Path(__file__).resolve().parents[1])
        tracemalloc.start()
        data = merl.load(ggx_path)
        _, peak = tracemalloc.get_traced_memory()
        tracemalloc.stop()
        print(f"file size            {ggx_path.stat().st_size:,} bytes")
        print(f"table                {data.table.nbytes / 1e6:.1f} MB, invalid bins "
              f"{data.n_invalid}")
        print(f"load peak (numpy)    {peak / 1e6:.1f} MB traced by tracemalloc")
        print(f"load peak RSS growth {child.stdout.strip()} MB (VmHWM, fresh process)")
        print(f"load time            {best_of(5, lambda: merl.load(ggx_path)) * 1e3:.0f} ms "
              "(best of 5, warm page cache)")
        merl.clear_cache()
        merl.load_cached(ggx_path)
        hit = best_of(20, lambda: merl.load_cached(ggx_path))
        print(f"cache hit            {hit * 1e6:.0f} µs")
        # ---- lookup
        rng = np.random.default_rng(0)
        n = 1_000_000
        wi = from_degrees(rng.uniform(0, 90, n), rng.uniform(-180, 180, n))
        wo = from_degrees(rng.uniform(0, 90, n), rng.uniform(-180, 180, n))
        for mode in merl.LOOKUPS:
            t = best_of(3, lambda mode=mode: merl.evaluate(data, wi, wo, mode))
            print(f"lookup {mode:<10}    {t * 1e3:.0f} ms per 10^6 direction pairs")
        # accuracy of the lookups against the generating model at random directions
        ref = per_channel("ggx", GGX)(wi[:100_000], wo[:100_000])
        for mode in merl.LOOKUPS:
            got = merl.evaluate(data, wi[:100_000], wo[:100_000], mode)
            err = np.abs(np.log1p(got) - np.log1p(ref))
            print(f"lookup {mode:<10}    |log(1+f) error| vs ggx: median {np.median(err):.2e}, "
                  f"p99 {np.quantile(err, 0.99):.2e}")
        # ---- fits
        print()
        print(f"{'file':<6} {'model':<14} {'seconds':>7} {'evals':>6} {'residual':>10}  params")
        for path, truth_name in ((ggx_path, "ggx"), (ct_path, "cook-torrance")):
            d_ = merl.load(path)
            for name in ("ggx", "cook-torrance", "blinn-phong", "gltf"):
                r = fit.fit(d_, name)
                shown = "; ".join(
                    " ".join(f"{k}={v:.4g}" if isinstance(v, float) else
                             f"{k}=" + ",".join(f"{x:.4g}" for x in v)
                             for k, v in p.items() if k != "fresnel") for p in r.params)
                print(f"{truth_name:<6.6} {name:<14} {r.seconds:7.2f} {r.evaluations:6d} "
                      f"{r.residual:10.3g}  {shown}")


if __name__ == "__main__":
    main()
