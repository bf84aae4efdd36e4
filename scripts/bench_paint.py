"""The compositor's cost per frame: Textual's own paint against the viewer's (tuibrdf/app/paint.py
and ``Rows.render_lines``), in one process, runs alternating.

    python scripts/bench_paint.py [--model phong] [--frames 60] [--size 160x48] [--runs 3]

The viewer runs headless (Textual's test harness); θi steps 0.5° a frame from 1°, every frame
computed beforehand, then shown (``show_frame``) and painted.  Per frame: the CPU time of the
paint (``Screen._compositor_refresh``: the compositor and turning its update into text, the
event loop's thread) and the characters of text it makes.  *textual*: Textual's compositor,
its styles cache's lines and its update timer; *viewer*: the viewer's screen.  Not a test:
the numbers depend on the machine (docs/benchmarks.md has them and their command).
"""

from __future__ import annotations

import argparse
import asyncio
import dataclasses
import os
import statistics
import time


async def run(model: str, frames: int, w: int, h: int, viewer: bool) -> tuple[list, list]:
    from textual.screen import Screen
    from textual.widget import Widget

    from tuibrdf.app import textual_internals
    from tuibrdf.app.app import BrdfApp
    from tuibrdf.app.widgets import Rows
    from tuibrdf.core.views import frame as core_frame
    from tuibrdf.state.viewer import Side, ViewerState

    saved = Rows.render_lines, Screen._compositor_refresh, textual_internals.PARTIAL_PAINT
    if not viewer:  # Textual's compositor and its styles cache's lines
        textual_internals.PARTIAL_PAINT = False
        Rows.render_lines = Widget.render_lines
    cpu: list[float] = []
    chars: list[int] = []
    refresh = Screen._compositor_refresh

    def timed(screen) -> None:
        t = time.thread_time()
        refresh(screen)
        cpu.append(time.thread_time() - t)

    Screen._compositor_refresh = timed
    try:
        app = BrdfApp(ViewerState(sides=[Side.of(model)]), color="truecolor")
        async with app.run_test(size=(w, h)) as pilot:
            await pilot.pause(0.5)

            def display(screen, update) -> None:  # headless: make the text as a terminal's
                if update is not None:
                    chars.append(len(update.render_segments(app.console)))

            app._display = display
            req = app.frame_request()
            results = [core_frame.compute_frame(dataclasses.replace(req, theta_i=1 + 0.5 * i))
                       for i in range(frames)]
            cpu.clear()
            chars.clear()
            for res in results:
                app.state.theta_i, app.request = res.request.theta_i, res.request
                app.show_frame(res)
                await pilot.pause()
    finally:
        Rows.render_lines, Screen._compositor_refresh, textual_internals.PARTIAL_PAINT = saved
    return cpu, chars


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--model", default="phong")
    ap.add_argument("--frames", type=int, default=60)
    ap.add_argument("--size", default="160x48")
    ap.add_argument("--runs", type=int, default=3)
    args = ap.parse_args()
    os.environ.pop("NO_COLOR", None)
    w, h = (int(v) for v in args.size.split("x"))
    print(f"{args.model}, {args.frames} θi frames, {w}×{h}, truecolor; per frame: paint CPU ms "
          "p50 / p95, characters written")
    for i in range(args.runs):
        for viewer in (False, True):
            cpu, chars = asyncio.run(run(args.model, args.frames, w, h, viewer))
            ms = sorted(t * 1e3 for t in cpu)
            print(f"run {i + 1} {'viewer ' if viewer else 'textual'}  paints {len(ms):3d}  "
                  f"{statistics.median(ms):5.2f} / {ms[int(0.95 * (len(ms) - 1))]:5.2f} ms  "
                  f"{statistics.median(chars):7.0f} chars")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
