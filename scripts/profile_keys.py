"""CPU profile of the viewer's event loop over a run of keys (in-process, Textual's test
harness; the frame worker's thread is not profiled).

Usage: ``python scripts/profile_keys.py [--keys 20] [--key right] [--size 160x48] [--top 40]``.
Prints the event loop's CPU per key and cProfile's cumulative table; e.g. ``grep
_refresh_layout`` shows whether a key re-lays out the screen.
"""

from __future__ import annotations

import argparse
import asyncio
import cProfile
import os
import pstats
import time


async def profile(n: int, key: str, w: int, h: int, top: int) -> None:
    from tuibrdf.app.app import BrdfApp
    from tuibrdf.state.viewer import ViewerState

    app = BrdfApp(ViewerState(), color="truecolor")
    async with app.run_test(size=(w, h)) as pilot:
        await pilot.pause(0.5)
        prof = cProfile.Profile()
        t = time.process_time()
        prof.enable()
        for _ in range(n):
            await pilot.press(key)
            await pilot.pause(0.05)
        prof.disable()
        print(f"CPU per key (whole process, event loop profiled): "
              f"{(time.process_time() - t) / n * 1e3:.1f} ms")
        pstats.Stats(prof).sort_stats("cumulative").print_stats(top)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--keys", type=int, default=20)
    ap.add_argument("--key", default="right")
    ap.add_argument("--size", default="160x48")
    ap.add_argument("--top", type=int, default=40)
    args = ap.parse_args()
    os.environ.pop("NO_COLOR", None)
    w, h = (int(v) for v in args.size.split("x"))
    asyncio.run(profile(args.keys, args.key, w, h, args.top))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
