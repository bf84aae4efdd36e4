"""Benchmark the polar cross-section pane: the braille canvas drawn straight from the frame's
section arrays (``tuibrdf.render.sections``; the plotext pane it replaced is gone,
docs/design.md keeps the comparison that decided it).

    python scripts/bench_plots.py [--repeat N] [--size WxH] [--stat median|min]

Timings per model, the median (or, with ``--stat min``, the fastest: the cost without the other
jobs of a shared machine) of ``--repeat`` runs after one warm-up:

- *plot*: the picture from the frame's curves: ``polar_canvas`` → rows of segments;
- *pane*: ``panes.section_pane`` (title included) printed to an ANSI string, for the plane of
  incidence and for the section through the peak (the frame computed once, cached).

Prints a Markdown table.
"""

from __future__ import annotations

import argparse
import statistics
import time

from rich.console import Console

from tuibrdf.core.material import Material
from tuibrdf.core.views import frame as core_frame
from tuibrdf.render import panes, sections
from tuibrdf.render.curves import channel_curves

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
    print("| model | braille plot (segments) | incidence pane | peak-section pane |")
    print("|---|---|---|---|")
    for name, params, ti in CASES:
        row = bench_case(name, params, ti, w, h, args.repeat)
        print(f"| {name} θi={ti:g} | " + " | ".join(f"{x:.2f}" for x in row) + " |")


def bench_case(name: str, params: dict, ti: float, w: int, h: int, repeat: int) -> list[float]:
    req = core_frame.FrameRequest((Material(name, params),), ti)
    res = core_frame.compute_frame(req, slow=False)
    side = res.sides[0]
    curves = [(lab, core_frame.SECTION_THETAS, v)
              for lab, v in channel_curves(name, side.sections["incidence"])]
    vmax = side.section_max
    look = panes.Look()

    def b_plot():
        canvas, _ = sections.polar_canvas(curves, w, h - 1, theta_i_deg=ti, vmax=vmax)
        return canvas.rows()

    return [
        ms(b_plot, repeat),
        ms(lambda: ansi(panes.section_pane(res, "incidence", w, h, look), w), repeat),
        ms(lambda: ansi(panes.section_pane(res, "perpendicular", w, h, look), w), repeat),
    ]


if __name__ == "__main__":
    main()
