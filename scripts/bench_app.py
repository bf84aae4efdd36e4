"""Interactive speed of the viewer under a real pseudo-terminal (issue 6).

Runs ``python -m tuibrdf view ...`` in a pty of the given size, writes key sequences to it and
timestamps the bytes the app writes back:

* **main view**: from writing the key to the last byte of the first output burst larger than
  ``FRAME_MIN`` bytes (the picture update; bursts are chunks < ``GAP_S`` apart, the app's writer
  thread writes a frame in one go; the largest burst when none is that big: a small update).
  Parameter change (``-`` on phong's Kd), θi change (→ only, from θi = 0°: every key
  asks for an albedo never computed before), model change (``m``), and → and ``+`` in turn
  (each key another than the one before it).  p50 / p95 over ``--reps`` keys each.
* **all panes**: key → the last byte before the output stays idle for ``SETTLE_S`` (map, the
  two sections, the status line's albedo and peak from a worker thread), for every key kind;
  with ``pyte``, not before the status line stops saying the frame's numbers are coming
  (``a(θi) …``: a frame slower than the quiet, whose status line went ahead of it).
* **bytes per update**: all bytes written for one 1° θi key, against the minimum for the cells
  that change: the app's own screen before and after the key is replayed through ``pyte`` (a
  terminal emulator) when installed, each changed cell costing its character plus the shortest
  SGR that sets its colours; without pyte the minimum is not reported.
* **CPU per key**: the viewer's CPU time (all threads, ended ones too: :func:`process_cpu`) over
  the keys of each kind, per key: what a loaded machine inflates far less than latency.
* **catch-up**: a key held 2 s (30 repeats/s) while the reader drains the pty at ~1 MB/s;
  the time from the last key until the output stops (idle ``IDLE_S``).
* The pty answers Textual's synchronized-output query (DECRQM 2026) as terminals that have it
  do, so the viewer writes each frame as it does for users of those terminals.
* **startup**: spawn → the first frame containing the map's colour bar unit (``sr⁻¹``); and
  ``tuibrdf --help``.

* **views** (``--views``): key → frame and key → all panes on each of issue 13's views (lit
  sphere, lit plane, θh × θd slice, f(θh), f(θd)): a parameter key and the view's own key.
* **kinds** (``--kinds [--only-views V,V]``): every kind of model the viewer opens (built-in
  scalar and RGB, a MERL material's fit, a ``.brdf``, a ``.py``, a synthetic ``.bsdf`` and a
  synthetic MERL file, :func:`sample_files`) on every main view: key → the screen's last
  change (complete frame) for → and for the first parameter's −, and on the first view a →
  held 2 s at 30/s read at full speed: the longest time without output while held, and how
  long the screen keeps changing after release.  With ``--against REV --both``, REV's viewer
  and this tree's are measured in turn, cell by cell, in one table: a slow spell of a shared
  machine falls on both (separate runs minutes apart differed by up to 2×).

Usage: ``python scripts/bench_app.py [--sizes 80x24,160x48,240x70] [--reps 20] [--views |
--kinds] [--load N] [--write-docs]``; ``--load N`` runs N processes spinning on the CPU meanwhile (a
shared machine).  Prints a Markdown table; ``--write-docs`` also writes it into
docs/benchmarks.md (scripts/benchdoc.py: its own section per ``--views`` and ``--load``, with
the command, the machine and the date).  Numbers depend on the machine: read them as "about".
"""

from __future__ import annotations

import argparse
import contextlib
import fcntl
import math
import os
import pty
import re
import select
import signal
import statistics
import struct
import subprocess
import sys
import tempfile
import termios
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
GAP_S = 0.004
FRAME_MIN = 3000
IDLE_S = 0.25
SETTLE_S = 0.15
#: the viewer's status line while a frame's numbers are coming (app/text.py's status_text:
#: ``a(θi) …``, ``A: a=…``; panes.albedo_text's ``…``; compare mode's ``rel_l2 …``)
PENDING = re.compile(r"a\(θi\)[ =]…|\ba=…|rel_l2 …")
#: Textual asks whether the terminal has synchronized output (DECRQM mode 2026) at start-up;
#: the reply "mode 2026 is set-able, currently reset" is what terminals that have it answer
SYNC_QUERY, SYNC_REPLY = b"\x1b[?2026$p", b"\x1b[?2026;2$y"
#: the end of a synchronized update (one paint of the screen, once the query is answered)
ESU = b"\x1b[?2026l"
KEYS = {"right": b"\x1b[C", "left": b"\x1b[D", "plus": b"+", "minus": b"-", "m": b"m",
        "q": b"q", "v": b"v", "d": b"d", "D": b"D", "x": b"x", "X": b"X", "y": b"y", "Y": b"Y"}
#: issue 13's views: how many ``v`` from the map reach each, and the view's own key pair
VIEW_KEYS = {"sphere": (3, ("right", "left")), "plane": (4, ("right", "left")),
             "slice": (5, ("y", "Y")), "theta-h": (6, ("d", "D")), "theta-d": (7, ("d", "D"))}


def process_cpu(pid: int) -> float:
    """CPU seconds process ``pid`` has used so far, every thread, those that have ended too
    (each frame job's thread ends with its frame): its process CPU clock, in nanoseconds
    (``clock_gettime`` of ``MAKE_PROCESS_CPUCLOCK(pid, CPUCLOCK_SCHED)``, Linux's encoding of
    another process's clock id).  Summing ``/proc/PID/task/*/schedstat`` instead misses the
    threads that have ended."""
    try:
        return time.clock_gettime(((~pid) << 3) | 2)
    except OSError:  # the process has ended
        return 0.0


def seen_in(marker: bytes, tail: bytes, data: bytes) -> tuple[bool, bytes]:
    """Whether ``marker`` is in ``tail + data`` (the bytes read before and now), and the new
    tail: the last ``len(marker) - 1`` bytes, a marker split across two reads.  (Searching a
    tail cut to a fixed size lost a marker at the start of a read larger than the cut.)"""
    buf = tail + data
    return marker in buf, buf[max(0, len(buf) - len(marker) + 1):]


class Term:
    """The app in a pty; ``rate`` limits reading (bytes/s, None = as fast as possible)."""

    def __init__(self, w: int, h: int, color: str, args: list[str],
                 root: str | Path = ROOT, command: list[str] | None = None) -> None:
        """``root``: the tree whose viewer runs (``tuibrdf/`` in it); ``command``: another
        program to run instead of the viewer (``args`` and ``color`` are then unused)."""
        env = dict(os.environ, TERM="xterm-256color", PYTHONPATH=str(root))
        env.pop("NO_COLOR", None)
        if color == "truecolor":
            env["COLORTERM"] = "truecolor"
        else:
            env.pop("COLORTERM", None)
        self.t0 = time.perf_counter()
        pid, fd = pty.fork()
        if pid == 0:  # child
            os.chdir(root)
            argv = command or [sys.executable, "-m", "tuibrdf", "view", *args, "--color", color]
            os.execvpe(argv[0], argv, env)
        self.pid, self.fd = pid, fd
        fcntl.ioctl(fd, termios.TIOCSWINSZ, struct.pack("HHHH", h, w, 0, 0))
        self.buf = bytearray()
        self.screen = None  # a pyte screen fed with everything read (bytes per update)
        self.unfed: list[bytes] = []  # read but not yet fed to it
        try:
            import pyte
        except ImportError:
            pyte = None
        if pyte is not None:
            self.screen = pyte.Screen(w, h)
            self.stream = pyte.ByteStream(self.screen)

    def read(self, timeout: float, limit: int = 65536) -> tuple[float, bytes] | None:
        r, _, _ = select.select([self.fd], [], [], timeout)
        if not r:
            return None
        try:
            data = os.read(self.fd, limit)
        except OSError:
            return None
        t = time.perf_counter()
        if SYNC_QUERY in data:  # answer as a terminal with synchronized output does: Textual
            os.write(self.fd, SYNC_REPLY)  # then wraps each frame in BSU … ESU, as users see it
        self.sent_since_key = getattr(self, "sent_since_key", 0) + len(data)
        if self.screen is not None:  # fed to the emulator later: pyte costs ~1 ms per KB, and
            self.unfed.append(data)  # feeding here delayed the next read (and its time stamp)
        return t, data

    def cpu(self) -> float:
        """CPU seconds the viewer has used so far, every thread, ended ones too: a cost a
        loaded machine inflates far less than latency (:func:`process_cpu`)."""
        return process_cpu(self.pid)

    def _feed(self) -> None:
        for data in self.unfed:
            self.stream.feed(data)
        self.unfed.clear()

    def waiting(self) -> bool:
        """Whether the viewer's status line says the frame's numbers are still coming
        (:data:`PENDING`): the pictures and numbers of that frame are not on screen yet,
        however long the screen has been quiet (False without pyte: not known)."""
        if self.screen is None:
            return False
        self._feed()
        return any(PENDING.search(line) for line in self.screen.display)

    def cells(self) -> dict:
        """The emulated screen: (row, col) → (char, fg, bg, bold, reverse)."""
        self._feed()
        out = {}
        for y in range(self.screen.lines):
            row = self.screen.buffer[y]
            for x in range(self.screen.columns):
                c = row[x]
                out[y, x] = (c.data, c.fg, c.bg, c.bold, c.reverse)
        return out

    def until(self, marker: bytes, timeout: float = 20.0) -> float:
        end = time.perf_counter() + timeout
        tail = b""
        while time.perf_counter() < end:
            got = self.read(0.05)
            if got:
                seen, tail = seen_in(marker, tail, got[1])
                if seen:
                    return got[0]
        raise TimeoutError(f"no {marker!r} within {timeout} s")

    def drain(self, idle: float = IDLE_S) -> float:
        """Read until nothing arrives for ``idle`` seconds; time of the last byte."""
        last = time.perf_counter()
        while True:
            got = self.read(idle)
            if got is None:
                return last
            last = got[0]

    def key_to_frame(self, key: bytes, timeout: float = 10.0) -> tuple[float, int, float]:
        """(seconds from the key to the end of the first burst over ``FRAME_MIN`` bytes — or
        of the largest burst when none is that big: a small update —, the bytes of that
        burst, seconds to the last byte before ``SETTLE_S`` of quiet with the status line no
        longer waiting for the frame: :meth:`waiting`)."""
        self._feed()  # what came before the key: not while its frame is timed (no pyte: none)
        t_key = time.perf_counter()
        self.sent_since_key = 0
        os.write(self.fd, key)
        end = t_key + timeout
        bursts: list[tuple[float, int]] = []  # (end, bytes)
        size, last = 0, None
        while time.perf_counter() < end:
            got = self.read(GAP_S if size else (SETTLE_S if bursts else 1.0))
            if got is None:
                if size:
                    bursts.append((last, size))
                    size = 0
                    continue
                # quiet, but the status line may say the frame is still coming (it goes
                # ahead of a slow frame): complete only once its numbers are on screen
                if bursts and not self.waiting():
                    break
                continue
            t, data = got
            size += len(data)
            last = t
        if not bursts:
            raise TimeoutError("no frame")
        big = [b for b in bursts if b[1] >= FRAME_MIN]
        main = big[0] if big else max(bursts, key=lambda b: b[1])
        return main[0] - t_key, main[1], bursts[-1][0] - t_key

    def close(self) -> None:
        try:
            os.write(self.fd, KEYS["q"])
            self.drain(0.3)
        except OSError:
            pass
        try:
            os.kill(self.pid, signal.SIGTERM)
        except ProcessLookupError:
            pass
        os.waitpid(self.pid, 0)
        os.close(self.fd)


def _sgr(cell: tuple) -> int:
    """Bytes of the shortest SGR setting a cell's colours and attributes."""
    parts = ["0"]
    for col, base in ((cell[1], 38), (cell[2], 48)):
        if col != "default":
            if len(col) == 6 and all(ch in "0123456789abcdef" for ch in col):
                r, g, b = (int(col[i:i + 2], 16) for i in (0, 2, 4))
                parts.append(f"{base};2;{r};{g};{b}")
            else:
                parts.append(str(base - 8 + 1))  # a named colour: ≈ 2 digits
    parts += ["1"] * bool(cell[3]) + ["7"] * bool(cell[4])
    return len("\x1b[") + len(";".join(parts)) + 1  # ESC [ params m


def min_bytes(before: dict, after: dict) -> tuple[int, int]:
    """(changed cells, the least bytes that redraw them): per run of changed cells in a row a
    cursor move, per cell its character and, when its style differs from the previous cell's,
    an SGR."""
    changed = sorted(k for k in after if after[k] != before.get(k))
    total, prev_key, prev_style = 0, None, None
    for y, x in changed:
        cell = after[y, x]
        if prev_key != (y, x - 1):
            total += len(f"\x1b[{y + 1};{x + 1}H")
            prev_style = None
        style = cell[1:]
        if style != prev_style:
            total += _sgr(cell)
        total += len(cell[0].encode())
        prev_key, prev_style = (y, x), style
    return len(changed), total


@contextlib.contextmanager
def loaded(n: int):
    """``n`` other processes spinning on the CPU meanwhile (``--load N``): a machine shared
    with other jobs, reproducibly.  On this 2-core machine ``--load 1`` leaves the viewer one
    core for its threads, ``--load 2`` less than a core each."""
    spin = [subprocess.Popen([sys.executable, "-c", "while True: pass"]) for _ in range(n)]
    try:
        yield
    finally:
        for p in spin:
            p.kill()
            p.wait()


def pct(xs: list[float], q: float) -> float:
    xs = sorted(xs)
    return xs[min(len(xs) - 1, round(q * (len(xs) - 1)))]


def latency(w: int, h: int, color: str, reps: int, root: str | Path = ROOT,
            model: str = "phong") -> dict:
    term = Term(w, h, color, [model, "--theta-i", "0"], root=root)
    out: dict = {}
    try:
        out["startup"] = term.until("sr⁻¹".encode()) - term.t0
        term.drain()
        # "-" from Kd = 0.2 in steps of 0.01 and → from θi = 0°: a material or an incidence
        # never seen before at every key (no albedo from the cache); then → and + in turn
        # (each key another than the one before, still never seen before)
        # (a model without parameters, a measured file: "-" and "+" change nothing)
        from tuibrdf.core.registry import get_model

        stepped = bool(get_model(model).params)
        for name, seq in (("param", ("minus",)), ("theta", ("right",)),
                          ("mixed", ("right", "plus")), ("model", ("m",))):
            if not stepped and name in ("param", "mixed"):
                continue
            times, sizes = [], []
            settled = []
            ratios = []
            cpu0 = term.cpu()
            for i in range(reps):
                before = term.cells() if term.screen is not None else None
                dt, n, done = term.key_to_frame(KEYS[seq[i % len(seq)]])
                times.append(dt)
                settled.append(done)
                n_all = n
                if before is not None:
                    n_all = term.sent_since_key
                    _, least = min_bytes(before, term.cells())
                    if least:
                        ratios.append((n_all, least))
                sizes.append(n_all)
            out[name] = (statistics.median(times), pct(times, 0.95), statistics.median(sizes),
                         statistics.median(settled), pct(settled, 0.95),
                         (statistics.median(a for a, _ in ratios),
                          statistics.median(b for _, b in ratios)) if ratios else None,
                         (term.cpu() - cpu0) / reps)
    finally:
        term.close()
    return out


def catch_up(w: int, h: int, color: str, rate: float = 1e6, hold_s: float = 2.0,
             root: str | Path = ROOT, model: str = "phong") -> float:
    """Seconds the screen keeps changing after a held → is released, reader at ``rate`` B/s."""
    term = Term(w, h, color, [model, "--theta-i", "0"], root=root)
    try:
        term.until("sr⁻¹".encode())
        term.drain()
        t_next = time.perf_counter()
        t_end = t_next + hold_s
        last_key = t_next
        while time.perf_counter() < t_end:
            if time.perf_counter() >= t_next:  # key repeat at 30 Hz
                os.write(term.fd, KEYS["right"])
                last_key = time.perf_counter()
                t_next += 1 / 30
            got = term.read(0.001, 4096)  # drain at `rate`: a chunk, then its transfer time
            if got:
                time.sleep(len(got[1]) / rate)
        last = last_key
        while True:  # after release: keep draining at `rate` until idle
            got = term.read(IDLE_S, 4096)
            if got is None:
                break
            last = got[0]
            time.sleep(len(got[1]) / rate)
        return max(0.0, last - last_key)
    finally:
        term.close()


def view_latency(w: int, h: int, color: str, reps: int, view: str,
                 root: str | Path = ROOT) -> dict:
    """Key → frame and key → all panes on one of issue 13's views (phong kd=0.2 ks=0.5 n=20,
    θi = 30°): a parameter key (+/−, every pane changes) and the view's own key pair."""
    n_v, own = VIEW_KEYS[view]
    term = Term(w, h, color, ["phong", "--theta-i", "30"], root=root)
    out: dict = {}
    try:
        term.until("sr⁻¹".encode())
        term.drain()
        for _ in range(n_v):
            os.write(term.fd, KEYS["v"])
            term.drain()
        for name, seq in (("param", ("plus", "minus")), ("own", own)):
            times, settled = [], []
            for i in range(reps):
                dt, _, done = term.key_to_frame(KEYS[seq[i % len(seq)]])
                times.append(dt)
                settled.append(done)
            out[name] = (statistics.median(times), pct(times, 0.95), statistics.median(settled),
                         pct(settled, 0.95))
    finally:
        term.close()
    return out


def sample_files(tmp: str | Path) -> dict[str, tuple[list[str], str | None]]:
    """Every kind of model the viewer opens: label → (the viewer's arguments, the key that
    steps its first parameter, None for a model without parameters).  The files are written
    here by the tests' writers (a synthetic 1×8-incidence 32×32 RGB ``.bsdf``, a synthetic
    MERL table) or taken from the repository (``tests/data/brdf/disney.brdf``,
    ``docs/examples/minnaert.py``)."""
    sys.path.insert(0, str(ROOT / "tests"))
    import numpy as np
    from merl_writer import sample_angles, write_merl
    from rgl_writer import material, write_tensor

    tmp = Path(tmp)
    bsdf = write_tensor(tmp / "synthetic.bsdf", material(n_phi=1, n_theta=8, n=32))
    th, _, _ = sample_angles()
    lobe = 0.1 + 2.0 * np.exp(-(th / 0.1) ** 2)  # a glossy peak about the half vector
    merl = write_merl(tmp / "synthetic.binary",
                      np.broadcast_to(lobe[None], (3, 90, 90, 180)).copy())
    return {
        "phong (built-in)": (["phong"], "minus"),
        "gltf (built-in, RGB)": (["gltf"], "minus"),
        "material alum-bronze (abc)": (["--material", "alum-bronze"], "minus"),
        "disney.brdf": ([str(ROOT / "tests" / "data" / "brdf" / "disney.brdf")], "minus"),
        "minnaert.py": ([str(ROOT / "docs" / "examples" / "minnaert.py")], "minus"),
        "synthetic .bsdf": ([str(bsdf)], None),
        "synthetic MERL": ([str(merl)], None),
    }


def hold(term: Term, key: bytes, hold_s: float = 2.0, rate_hz: float = 30.0
         ) -> tuple[float, float, int, int]:
    """A key held ``hold_s`` seconds (``rate_hz`` repeats), the pty read as fast as it comes:
    (the longest time without output while it is held, after its first 0.1 s; the time from
    the last key to the screen's last change; the paints from the first key to the screen's
    last change, each one synchronized update's end (ESU); the keys sent).  With keys every
    1/rate s, the longest gap cannot be below that interval plus the spread of the frames'
    latencies; paints ≥ keys says that no key's frame was skipped."""
    t_start = t_next = time.perf_counter()
    t_end = t_start + hold_s
    last_key, frames, keys, paints = t_start, [], 0, 0
    while time.perf_counter() < t_end:
        if time.perf_counter() >= t_next:
            os.write(term.fd, key)
            keys += 1
            last_key = time.perf_counter()
            t_next += 1 / rate_hz
        got = term.read(0.001)
        if got:  # the screen changed (a θi key changes the pictures and the status line)
            frames.append(got[0])
            paints += got[1].count(ESU)
    last = last_key
    while True:
        got = term.read(IDLE_S)
        if got is None:
            break
        last = got[0]
        paints += got[1].count(ESU)
    marks = [t_start + 0.1] + [t for t in frames if t > t_start + 0.1] + [t_end]
    return (max(b - a for a, b in zip(marks, marks[1:], strict=False)),
            max(0.0, last - last_key), paints, keys)


def kinds_table(sizes, colors, reps: int, lines: list[str], root: str | Path = ROOT,
                views: tuple[str, ...] | None = None,
                trees: list[tuple[str, str | Path]] | None = None) -> None:
    """Key → complete frame for every kind of model on every main view: θi (→, a new
    incidence each key) and the first parameter (−, a new value each key), p50 / p95 of the
    time to the screen's last change (``SETTLE_S`` of quiet after it); and on the map a held
    →: the longest wait for a frame while held, the settling after release.  ``trees``:
    ``(label, root)`` of trees measured in turn, cell by cell (a slow spell of the machine
    falls on all of them), with a column saying which."""
    from tuibrdf.state.viewer import MAIN_VIEWS

    views = views or MAIN_VIEWS
    both = trees is not None
    trees = trees or [("", root)]
    emit(lines, "| size | colours | model | view |" + (" tree |" if both else "")
         + " θi p50/p95 ms | parameter p50/p95 ms | held →: longest gap / settles, ms / "
         "paints of keys |")
    emit(lines, "|---|---|---|---|" + ("---|" if both else "") + "---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for label, (argv, param_key) in sample_files(tmp).items():
            for w, h, color, view, (tree, root) in (
                    (w, h, c, v, t) for w, h in sizes for c in colors for v in views
                    for t in trees):
                term = Term(w, h, color, [*argv, "--theta-i", "0", "--view", view],
                            root=root)
                try:
                    term.until(b"\x1b[?1049h")  # the alternate screen: started
                    # the first frame complete: 3 s without output (an energy table
                    # or an albedo curve of a file model can take seconds, and the
                    # partial repaint never sends the status line's text whole)
                    term.drain(3.0)
                    cells = []
                    for key in ("right", param_key):
                        if key is None:
                            cells.append("—")
                            continue
                        done = [term.key_to_frame(KEYS[key])[2] for _ in range(reps)]
                        cells.append(f"{statistics.median(done) * 1e3:.0f} / "
                                     f"{pct(done, 0.95) * 1e3:.0f}")
                    held = "—"
                    if view == views[0]:
                        gap, settle, paints, keys = hold(term, KEYS["right"])
                        held = f"{gap * 1e3:.0f} / {settle * 1e3:.0f} / {paints} of {keys}"
                finally:
                    term.close()
                emit(lines, f"| {w}×{h} | {color} | {label} | {view} | "
                     + (f"{tree} | " if both else "") + f"{cells[0]} | "
                     f"{cells[1]} | {held} |")


def emit(lines: list[str], line: str) -> None:
    """Print a line of the table as soon as it is measured, and keep it."""
    print(line, flush=True)
    lines.append(line)


def views_table(sizes, colors, reps: int, lines: list[str], root: str | Path = ROOT) -> None:
    emit(lines, "| size | colours | view | param p50/p95 ms | param all panes p50/p95 ms "
         "| own key | own p50/p95 ms | own all panes p50/p95 ms |")
    emit(lines, "|---|---|---|---|---|---|---|---|")
    for w, h in sizes:
        for color in colors:
            for view in VIEW_KEYS:
                r = view_latency(w, h, color, reps, view, root)
                cells = []
                for k in ("param", "own"):
                    cells.append(f"{r[k][0] * 1e3:.0f} / {r[k][1] * 1e3:.0f}")
                    cells.append(f"{r[k][2] * 1e3:.0f} / {r[k][3] * 1e3:.0f}")
                own = "/".join(VIEW_KEYS[view][1])
                emit(lines, f"| {w}×{h} | {color} | {view} | {cells[0]} | {cells[1]} | {own} | "
                     f"{cells[2]} | {cells[3]} |")


def help_time(args: tuple[str, ...] = ("-m", "tuibrdf", "--help")) -> float:
    """Median wall time of 5 runs of ``python ARGS`` (``python -c pass``: the interpreter's
    own start-up, which a slow spell of the machine moves as much)."""
    from bench_help import fresh_bytecode

    fresh_bytecode(dict(os.environ, PYTHONPATH=str(ROOT)))
    ts = []
    for _ in range(5):
        t = time.perf_counter()
        subprocess.run([sys.executable, *args], cwd=ROOT, capture_output=True, check=True)
        ts.append(time.perf_counter() - t)
    return statistics.median(ts)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", default="80x24,160x48,240x70")
    ap.add_argument("--model", default="phong",
                    help="the model or file the viewer opens (default phong; its first "
                         "parameter takes the '-' keys)")
    ap.add_argument("--reps", type=int, default=20)
    ap.add_argument("--colors", default="truecolor,256")
    ap.add_argument("--no-catch-up", action="store_true", help="skip the held-key test")
    ap.add_argument("--views", action="store_true",
                    help="key → frame on each of issue 13's views instead")
    ap.add_argument("--kinds", action="store_true",
                    help="every kind of model (built-in, RGB, material, .brdf, .py, .bsdf, "
                         "MERL) on every main view instead")
    ap.add_argument("--only-views", metavar="V,V", help="with --kinds: these views only")
    ap.add_argument("--load", type=int, default=0, metavar="N",
                    help="N other processes spinning on the CPU meanwhile (a shared machine)")
    ap.add_argument("--against", metavar="REV",
                    help="measure git revision REV's viewer instead of this tree's (git archive)")
    ap.add_argument("--both", action="store_true",
                    help="with --kinds --against REV: REV's viewer and this tree's in turn, "
                         "cell by cell, in one table")
    ap.add_argument("--write-docs", action="store_true",
                    help="also write the table into docs/benchmarks.md (its own section)")
    args = ap.parse_args()
    from benchdoc import command_line, machine, write_section

    started = machine()  # (the load average before the spinning processes start)
    with tempfile.TemporaryDirectory() as tmp:
        args.root = ROOT
        if args.against:
            from revtree import extract

            args.root = extract(args.against, tmp)
        with loaded(args.load):
            lines = run(args)
    if args.write_docs:
        import re

        kind = "" if args.model == "phong" else "-" + re.sub(r"[^A-Za-z0-9_.-]", "_",
                                                              Path(args.model).name)
        name = "bench_app" + kind + ("-views" if args.views else "") + (
            "-kinds" if args.kinds else "") + (
            f"-load{args.load}" if args.load else "") + (
            f"-{'vs' if args.both else 'at'}-{args.against}" if args.against else "")
        doc = write_section(name, "\n".join(lines), command_line(), machine_line=started)
        print(f"written into {doc}")
    return 0


def run(args: argparse.Namespace) -> list[str]:
    """Measure and print the table; its lines."""
    sizes = [tuple(int(v) for v in s.split("x")) for s in args.sizes.split(",")]
    colors = args.colors.split(",")
    lines: list[str] = []
    if args.views:
        views_table(sizes, colors, args.reps, lines, args.root)
        return lines
    if args.kinds:
        trees = ([(args.against, args.root), ("this tree", ROOT)]
                 if args.both and args.against else None)
        kinds_table(sizes, colors, args.reps, lines, args.root,
                    tuple(args.only_views.split(",")) if args.only_views else None, trees)
        return lines
    kinds = ("param", "theta", "model", "mixed")
    emit(lines, "| size | colours | startup s | main view p50/p95 ms: param | θi | model | "
         "→ and + | all panes p50/p95 ms: param | θi | model | → and + | bytes per 1° θi / "
         "changed cells' minimum | CPU per key ms: param | θi | model | → and + | catch-up s |")
    emit(lines, "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for w, h in sizes:
        for color in colors:
            r = latency(w, h, color, args.reps, args.root, args.model)
            cu = float("nan") if args.no_catch_up else catch_up(w, h, color, root=args.root,
                                                                 model=args.model)
            r |= {k: (math.nan,) * 7 for k in kinds if k not in r}  # (no parameter to step)
            ms = [f"{r[k][0] * 1e3:.0f} / {r[k][1] * 1e3:.0f}" for k in kinds]
            done = [f"{r[k][3] * 1e3:.0f} / {r[k][4] * 1e3:.0f}" for k in kinds]
            least = r["theta"][5]
            sent = (f"{least[0] / 1e3:.1f} / {least[1] / 1e3:.1f} kB = {least[0] / least[1]:.2f}×"
                    if least else f"{r['theta'][2] / 1e3:.1f} kB / ?")
            cpu = [f"{r[k][6] * 1e3:.1f}" for k in kinds]
            emit(lines, f"| {w}×{h} | {color} | {r['startup']:.2f} | {' | '.join(ms)} | "
                 f"{' | '.join(done)} | {sent} | {' | '.join(cpu)} | {cu:.2f} |")
    emit(lines, "")
    emit(lines, f"`tuibrdf --help`: {help_time() * 1e3:.0f} ms, `python -c pass`: "
         f"{help_time(('-c', 'pass')) * 1e3:.0f} ms (medians of 5)")
    return lines


if __name__ == "__main__":
    sys.exit(main())
