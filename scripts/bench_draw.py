"""What drawing one frame costs the viewer's event loop: ``show_frame`` (every visible pane
turned into rows and marked for repaint, the panels and the status line), not the numbers
(computed beforehand) and not Textual's compositor or the terminal (issue 16).

The viewer runs headless at ``--size`` (Textual's ``run_test``); a sequence of frames is
computed first as the keys would make them (``theta``: θi → one degree a key; ``param``: the
first parameter −, −, −, −, +, +, +, +, …; ``model``: m), then the first ``--frames`` of them
are shown one after another and the event loop's thread CPU time per frame is printed.

The machine's load moves that time by ±30–70 % here, so the deterministic measure is the
instruction count of the drawing alone: run the script under valgrind with 5 and with 15
frames and divide the difference by 10 (both runs compute the same frames)::

    valgrind --tool=callgrind --callgrind-out-file=/dev/null python scripts/bench_draw.py \\
        --frames 5      # then --frames 15; "Collected" is the count

Usage: ``python scripts/bench_draw.py [--model phong] [--kind theta] [--frames 30]
[--size 160x48]``.  Not a test (docs/benchmarks.md has the numbers).
"""

from __future__ import annotations

import argparse
import asyncio
import gc
import time

SEQUENCE = 31  # frames computed, whatever --frames is (so two runs differ only in drawing)


async def run(model: str, kind: str, frames: int, size: tuple[int, int]) -> float:
    from tuibrdf.app.app import BrdfApp
    from tuibrdf.core.views import frame as core_frame
    from tuibrdf.state.viewer import Side, ViewerState

    app = BrdfApp(ViewerState(sides=[Side.of(model)]), color="truecolor")
    async with app.run_test(size=size) as pilot:
        await pilot.pause(0.3)
        gc.freeze()  # as the viewer does a second after start-up (app.FREEZE_S)
        st = app.state
        requests = []
        for i in range(SEQUENCE):
            if kind == "theta":
                st.step_theta(1)
            elif kind == "param":
                st.step_param(-1 if i % 8 < 4 else 1)
            else:
                st.cycle_model(1)
            requests.append(app.frame_request())
        results = [core_frame.compute_frame(r) for r in requests]
        start = time.thread_time()
        for res in results[:frames]:
            app.request = res.request
            app.show_frame(res)
        return (time.thread_time() - start) / frames


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--model", default="phong")
    ap.add_argument("--kind", choices=("theta", "param", "model"), default="theta")
    ap.add_argument("--frames", type=int, default=30)
    ap.add_argument("--size", default="160x48")
    a = ap.parse_args()
    if not 1 <= a.frames <= SEQUENCE:
        ap.error(f"--frames must be 1..{SEQUENCE}")
    w, h = (int(v) for v in a.size.split("x"))
    per = asyncio.run(run(a.model, a.kind, a.frames, (w, h)))
    print(f"{a.model} {a.kind} {a.size}: {per * 1e3:.2f} ms of event-loop CPU per frame "
          f"({a.frames} frames)")


if __name__ == "__main__":
    main()
