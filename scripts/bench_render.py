"""Benchmark the terminal pictures: map building (exact vs mesh, with the mesh's error), colour
mapping + half-block segments, whole views, and ANSI bytes per frame.

    python scripts/bench_render.py [--repeat N]

Prints Markdown tables (docs/reference/accuracy.md quotes the map's error).  Times are medians
of ``--repeat`` warm runs (caches filled by a first call, as in the app, where the size and
mesh level rarely change).
"""

from __future__ import annotations

import argparse
import statistics
import time

import numpy as np
from rich.console import Console

from tuibrdf.core.directions import incident
from tuibrdf.core.registry import MODELS
from tuibrdf.core.views.hemimap import map_values
from tuibrdf.render.colormap import colorize
from tuibrdf.render.halfblock import HalfBlockImage
from tuibrdf.render.views import VIEWS, render_view

SIZES = [(80, 24), (160, 48), (240, 70)]
CASES = [
    ("cook-torrance", {"kd": 0.0, "f0": 0.04, "m": 0.07}, 60.0),  # the seed's example
    ("phong", {"kd": 0.2, "ks": 0.5, "n": 20}, 30.0),
    ("oren-nayar", {}, 45.0),
    ("gltf", {}, 30.0),
]


def ms(fn, repeat: int) -> float:
    fn()  # warm caches
    out = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        out.append((time.perf_counter() - t0) * 1e3)
    return statistics.median(out)


def ansi(renderable, system: str, width: int) -> str:
    con = Console(width=width, color_system=system, force_terminal=True, legacy_windows=False)
    with con.capture() as cap:
        con.print(renderable)
    return cap.get()


def bench_maps(repeat: int) -> None:
    print("\n## Map: exact vs mesh (map only, warm)\n")
    print("| model | cells | pixels in disc | exact ms | mesh level | mesh ms | mesh max err "
          "(rel. to peak) | mesh RMS err |")
    print("|---|---|---|---|---|---|---|---|")
    for name, params, ti in CASES:
        m = MODELS[name]
        v = m.resolve(params)
        for w, h in SIZES:
            px_w, px_h = w, 2 * (h - 3)
            wi = incident(ti)
            exact, info = map_values(m, v, wi, px_w, px_h)
            mesh, minfo = map_values(m, v, wi, px_w, px_h, method="mesh")
            inside = ~np.isnan(exact)
            err = np.abs(mesh - exact)[inside]
            peak = np.nanmax(exact)
            te = ms(lambda m=m, v=v, wi=wi, a=px_w, b=px_h: map_values(m, v, wi, a, b), repeat)
            tm = ms(lambda m=m, v=v, wi=wi, a=px_w, b=px_h: map_values(m, v, wi, a, b,
                                                                       method="mesh"), repeat)
            n_in = int(inside.all(axis=-1).sum() if inside.ndim == 3 else inside.sum())
            print(f"| {name} | {w}×{h} | {n_in} | {te:.2f} | {minfo.level} | {tm:.2f} | "
                  f"{err.max() / peak:.3f} | {np.sqrt((err**2).mean()) / peak:.4f} |")


def bench_segments(repeat: int) -> None:
    print("\n## Colour map + half-block segments, and ANSI bytes per map frame\n")
    print("| cells | levels | colorize ms | segments truecolor ms | segments 256 ms | "
          "bytes truecolor | bytes 256 |")
    print("|---|---|---|---|---|---|---|")
    m = MODELS["cook-torrance"]
    v = m.resolve({"kd": 0.0, "f0": 0.04, "m": 0.2})
    for w, h in SIZES:
        data, _ = map_values(m, v, incident(45), w, 2 * (h - 3))
        for levels in (256, 32):
            tc = ms(lambda d=data, lv=levels: colorize(d, "inferno", levels=lv), repeat)
            col = colorize(data, "inferno", levels=levels)

            def seg(system, col=col):
                HalfBlockImage(col.index, col.palette).rows(system)

            tt = ms(lambda: seg("truecolor"), repeat)
            t2 = ms(lambda: seg("256"), repeat)
            img = HalfBlockImage(col.index, col.palette)
            bt = len(ansi(img, "truecolor", w).encode())
            b2 = len(ansi(img, "256", w).encode())
            print(f"| {w}×{h} | {levels} | {tc:.2f} | {tt:.2f} | {t2:.2f} | {bt} | {b2} |")


def bench_views(repeat: int) -> None:
    print("\n## Whole views (render_view + printing to a string), cook-torrance m=0.2, θi=45\n")
    print("| view | " + " | ".join(f"{w}×{h} ms" for w, h in SIZES) + " | bytes 160×48 truecolor |")
    print("|---|" + "---|" * (len(SIZES) + 1))
    m = MODELS["cook-torrance"]
    v = m.resolve({"kd": 0.0, "f0": 0.04, "m": 0.2})
    for view in VIEWS:
        cells = []
        for w, h in SIZES:
            cells.append(ms(lambda view=view, w=w, h=h: ansi(
                render_view(view, m, v, 45, w, h, cmap="inferno"), "truecolor", w), repeat))
        size = len(ansi(render_view(view, m, v, 45, 160, 48, cmap="inferno"), "truecolor",
                        160).encode())
        print(f"| {view} | " + " | ".join(f"{c:.1f}" for c in cells) + f" | {size} |")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repeat", type=int, default=15)
    args = ap.parse_args()
    bench_maps(args.repeat)
    bench_segments(args.repeat)
    bench_views(args.repeat)


if __name__ == "__main__":
    main()
