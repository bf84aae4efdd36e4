"""Where a key's time goes in the running viewer: a timeline of each key's phases.

    python scripts/timeline_keys.py [--model phong] [--view map] [--key right] [--keys 40]
                                    [--size 160x48] [--load N]

``--key right,-`` sends the keys in turn (→, −, →, …).

The viewer runs in a pty as a user sees it (truecolor); inside it, a few of its methods and
Textual's are wrapped to note a timestamp (``time.perf_counter``, the same monotonic clock in
both processes) when they start and end.  The driver sends one key every 150 ms, reads the pty
and prints, per phase, the time from the key being written to the phase (p50 / p95 / min over
the keys, the first two left out as warm-up):

* ``key``: the key event reaches the app; ``update>``: the coalesced state update runs;
* ``compute>`` / ``compute<``: the worker's ``compute_frame`` calls, from the first's start
  (maps, sections, peak) to the last's end (the albedo); ``fast<``: the first call's end (the
  frame without its albedo); ``ready>``: the worker's result reaches the event loop
  (``on_frame_computed``; absent when the frame is computed on the loop);
* ``show>`` / ``show<``: ``show_frame`` draws every pane, the panels and the status line;
* ``paint>`` / ``paint<``: the screen's compositor turns the dirty regions into output
  (``Screen._compositor_refresh``: Textual's compositor, or the viewer's screen's);
* ``flush``: Textual's writer thread flushes it; ``read``: the last byte reaches the driver.

Then the steps between some of them, timed key by key (``show → paint``: from the frame
drawn to the compositor's start), and the
viewer's CPU time per key over the keys (its process CPU clock): all its threads,
and its main thread (the event loop) alone: what a loaded machine inflates far less than the
times above.

Not a test: timings depend on the machine (docs/benchmarks.md has the numbers and their command).
"""

from __future__ import annotations

import argparse
import fcntl
import os
import pty
import select
import struct
import sys
import tempfile
import termios
import time

KEYS = {"right": b"\x1b[C", "left": b"\x1b[D", "+": b"+", "-": b"-", "m": b"m"}
PHASES = ("key", "update>", "compute>", "fast<", "ready>", "compute<", "show>", "show<",
          "paint>", "paint<", "flush", "read")


def child(out: str, argv: list[str]) -> None:
    """In the pty: wrap the phases' methods, run the viewer, write the marks at exit."""
    import atexit

    import textual.drivers._writer_thread as writer
    import textual.message_pump as pump
    import textual.screen as screen

    from tuibrdf.app import app as viewer
    from tuibrdf.app import frames
    from tuibrdf.core.views import frame as core_frame

    marks: list[tuple[float, str]] = []
    clock = time.perf_counter

    def wrap(owner, name: str, tag: str) -> None:
        original = getattr(owner, name)

        def wrapped(*a, **k):
            marks.append((clock(), tag + ">"))
            try:
                return original(*a, **k)
            finally:
                marks.append((clock(), tag + "<"))

        setattr(owner, name, wrapped)

    wrap(viewer.BrdfApp, "_update", "update")
    wrap(frames.FrameDelivery, "show_frame", "show")
    wrap(frames.FrameDelivery, "on_frame_computed", "ready")
    wrap(screen.Screen, "_compositor_refresh", "paint")
    wrap(core_frame, "compute_frame", "compute")

    dispatch = pump.MessagePump._dispatch_message

    async def dispatched(self, message):
        if type(message).__name__ == "Key" and self is self.app:
            marks.append((clock(), "key"))
        return await dispatch(self, message)

    pump.MessagePump._dispatch_message = dispatched

    run = writer.WriterThread.run

    def run_marked(self):
        file = self._file

        class Marked:
            def flush(self):
                file.flush()
                marks.append((clock(), "flush"))

            def __getattr__(self, name):
                return getattr(file, name)

        self._file = Marked()
        return run(self)

    writer.WriterThread.run = run_marked

    def dump() -> None:
        with open(out, "w") as f:
            f.writelines(f"{t:.6f} {tag}\n" for t, tag in marks)

    atexit.register(dump)
    from tuibrdf.cli import main

    sys.argv = ["tuibrdf", "view", *argv]
    main()


def cpu_seconds(pid: int) -> tuple[float, float]:
    """CPU seconds used so far by every thread of ``pid`` (ended ones too: the frame jobs'
    threads end with their frames) and by its main thread."""
    from bench_app import process_cpu  # (not at the top: this file also runs as the viewer)

    try:
        with open(f"/proc/{pid}/task/{pid}/schedstat") as f:
            main = int(f.read().split()[0]) * 1e-9
    except (OSError, ValueError, IndexError):  # the process has ended
        main = 0.0
    return process_cpu(pid), main


def drive(model: str, key: str, n: int, w: int, h: int, view: str = "map"
          ) -> tuple[list[float], list, list, tuple[float, float]]:
    out = tempfile.mktemp(suffix=".marks")
    # the viewer of this script's tree (the child's sys.path[0] is scripts/, and an installed
    # tuibrdf would come next): a copy of an older tree times that tree
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    env = dict(os.environ, TERM="xterm-256color", COLORTERM="truecolor", PYTHONPATH=root)
    env.pop("NO_COLOR", None)
    pid, fd = pty.fork()
    if pid == 0:
        os.execvpe(sys.executable, [sys.executable, __file__, "--child", out, model,
                                    "--color", "truecolor", "--view", view], env)
    fcntl.ioctl(fd, termios.TIOCSWINSZ, struct.pack("HHHH", h, w, 0, 0))
    sends: list[float] = []
    reads: list[float] = []

    def drain(seconds: float) -> None:
        end = time.perf_counter() + seconds
        while (left := end - time.perf_counter()) > 0:
            if select.select([fd], [], [], left)[0]:
                try:
                    os.read(fd, 65536)
                except OSError:
                    return
                reads.append(time.perf_counter())

    drain(3.0)
    cpu0 = cpu_seconds(pid)
    cycle = key.split(",")
    for i in range(n):
        sends.append(time.perf_counter())
        os.write(fd, KEYS[cycle[i % len(cycle)]])
        drain(0.15)
    cpu = tuple((b - a) / n for a, b in zip(cpu0, cpu_seconds(pid), strict=True))
    os.write(fd, b"q")
    drain(1.5)
    os.waitpid(pid, 0)
    with open(out) as f:
        marks = [(float(t), tag) for t, tag in (line.split() for line in f)]
    os.unlink(out)
    return sends, marks, reads, cpu


def table(sends: list[float], marks: list, reads: list[float]) -> str:
    per: dict[str, list[float]] = {p: [] for p in PHASES}
    for i, s in enumerate(sends[2:], start=2):
        end = sends[i + 1] if i + 1 < len(sends) else s + 0.15
        seen = [(t - s, tag) for t, tag in marks if s <= t < end]
        for p in PHASES[:-1]:
            ts = [t for t, tag in seen if tag == ("compute<" if p == "fast<" else p)]
            if p == "fast<":
                ts = ts[:1]  # the first call's end
            if ts:  # the first start, the last end
                per[p].append((max if p.endswith("<") or p == "flush" else min)(ts))
        last = [t - s for t in reads if s <= t < end]
        if last:
            per["read"].append(last[-1])
    lines = ["phase       keys  p50 ms  p95 ms  min ms"]
    for p, v in per.items():
        if v:
            v = sorted(x * 1e3 for x in v)
            lines.append(f"{p:10s} {len(v):5d} {v[len(v) // 2]:7.2f} "
                         f"{v[min(len(v) - 1, int(len(v) * 0.95))]:7.2f} {v[0]:7.2f}")
    return "\n".join(lines)


#: the steps between the phases, each timed key by key: (name, from, to)
STEPS = (("key → update", "key", "update>"), ("update → worker", "update>", "compute>"),
         ("albedo → show", "compute<", "show>"), ("show → paint", "show<", "paint>"),
         ("paint", "paint>", "paint<"), ("paint → flush", "paint<", "flush"))


def steps(sends: list[float], marks: list) -> str:
    """The hand-offs and the paint, key by key: p50 / p95 of each step over the keys."""
    per: dict[str, list[float]] = {name: [] for name, _, _ in STEPS}
    for i, s in enumerate(sends[2:], start=2):
        end = sends[i + 1] if i + 1 < len(sends) else s + 0.15
        seen = [(t, tag) for t, tag in marks if s <= t < end]

        def at(tag: str, last: bool = False, seen=seen) -> float | None:
            ts = [t for t, got in seen if got == tag]
            if not ts:
                return None
            return ts[-1] if last else ts[0]

        for name, a, b in STEPS:
            t0, t1 = at(a, last=a == "compute<"), at(b)
            if t0 is not None and t1 is not None and t1 >= t0:
                per[name].append((t1 - t0) * 1e3)
    lines = ["step              keys  p50 ms  p95 ms"]
    for name, v in per.items():
        if v:
            v.sort()
            lines.append(f"{name:16s} {len(v):5d} {v[len(v) // 2]:7.2f} "
                         f"{v[min(len(v) - 1, int(len(v) * 0.95))]:7.2f}")
    return "\n".join(lines)


def main() -> int:
    if len(sys.argv) > 2 and sys.argv[1] == "--child":
        child(sys.argv[2], sys.argv[3:])
        return 0
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--model", default="phong")
    ap.add_argument("--key", default="right",
                    help=f"one of {', '.join(sorted(KEYS))}, or several, comma-separated")
    ap.add_argument("--keys", type=int, default=40)
    ap.add_argument("--size", default="160x48")
    ap.add_argument("--view", default="map", help="the view the viewer opens on")
    ap.add_argument("--load", type=int, default=0, metavar="N",
                    help="N other processes spinning on the CPU meanwhile (a shared machine)")
    args = ap.parse_args()
    if not all(k in KEYS for k in args.key.split(",")):
        ap.error(f"--key: expected keys among {', '.join(sorted(KEYS))}, comma-separated")
    w, h = (int(v) for v in args.size.split("x"))
    print(f"{args.model}, {args.view}, key {args.key!r} × {args.keys}, {w}×{h}, truecolor"
          + (f", {args.load} spinning processes" if args.load else ""))
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from bench_app import loaded

    with loaded(args.load):
        sends, marks, reads, cpu = drive(args.model, args.key, args.keys, w, h, args.view)
    print(table(sends, marks, reads))
    print(steps(sends, marks))
    print("CPU per key ms: all threads {:.2f}, event loop {:.2f}".format(*(t * 1e3 for t in cpu)))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
