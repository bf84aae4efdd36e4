"""Benchmark the polar cross-section pane: plotext (``tuibrdf.render.polar``) against the braille
canvas drawn straight from numpy (``tuibrdf.render.polar_braille``), for the same picture.

    python scripts/bench_plots.py [--repeat N] [--size WxH] [--stat median|min]

Timings per model, the median (or, with ``--stat min``, the fastest: the cost without the other
jobs of a shared machine) of ``--repeat`` runs after one warm-up:

- *plot*: the picture from ready curves, what a pane pays per frame once the BRDF is
  evaluated: ``polar.polar_plot`` → ANSI text, then (a separate column) that text parsed back
  into Rich segments (``Text.from_ansi``), against ``polar_canvas`` → rows of segments;
- *view*: the whole ``section_view`` (evaluation of the curves and the common scale included),
  printed to an ANSI string.

Prints a Markdown table (docs/render.md quotes it).
"""

from __future__ import annotations

import argparse
import statistics
import time

from rich.console import Console
from rich.text import Text

from tuibrdf.core.models import MODELS
from tuibrdf.render import polar, polar_braille

CASES = [
    ("cook-torrance", {"kd": 0.0, "f0": 0.04, "m": 0.07}, 60.0),  # the seed's example
    ("phong", {"kd": 0.2, "ks": 0.5, "n": 20}, 30.0),
    ("gltf", {}, 30.0),  # RGB: three curves and a legend
]


STAT = {"median": statistics.median, "min": min}
stat = statistics.median


def ms(fn, repeat: int) -> float:
    fn()
    out = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        out.append((time.perf_counter() - t0) * 1e3)
    return stat(out)


def ansi(renderable, width: int) -> str:
    con = Console(width=width, color_system="truecolor", force_terminal=True,
                  legacy_windows=False)
    with con.capture() as cap:
        con.print(renderable)
    return cap.get()


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=30)
    ap.add_argument("--size", default="160x48")
    ap.add_argument("--stat", choices=sorted(STAT), default="median")
    args = ap.parse_args()
    global stat
    stat = STAT[args.stat]
    w, h = (int(v) for v in args.size.split("x"))
    print(f"\n## Polar section pane at {w}×{h}, truecolor ({args.stat} of {args.repeat}, ms)\n")
    print("| model | plotext plot | plotext text → segments | braille plot (segments) "
          "| plotext view | braille view |")
    print("|---|---|---|---|---|---|")
    for name, params, ti in CASES:
        row = bench_case(name, params, ti, w, h, args.repeat)
        print(f"| {name} θi={ti:g} | " + " | ".join(f"{x:.2f}" for x in row) + " |")


def bench_case(name: str, params: dict, ti: float, w: int, h: int, repeat: int) -> list[float]:
    m = MODELS[name]
    v = m.resolve(params)
    curves = polar.section_curves(m, v, ti, "incidence")
    vmax = polar.sections_max(m, v, ti)

    def p_plot():
        return polar.polar_plot(curves, w, h - 1, theta_i_deg=ti, vmax=vmax)

    def b_plot():
        canvas, _ = polar_braille.polar_canvas(curves, w, h - 1, theta_i_deg=ti, vmax=vmax)
        return canvas.rows()

    text, _ = p_plot()
    return [
        ms(p_plot, repeat),
        ms(lambda: Text.from_ansi(text).divide([]), repeat),
        ms(b_plot, repeat),
        ms(lambda: ansi(polar.section_view("incidence", m, v, ti, w, h), w), repeat),
        ms(lambda: ansi(polar_braille.section_view("incidence", m, v, ti, w, h), w), repeat),
    ]


if __name__ == "__main__":
    main()
