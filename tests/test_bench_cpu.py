"""scripts/bench_app.py's CPU time of the viewer counts the threads that have ended too (each
frame job's thread ends with its frame): a sum over the live threads' counters misses them.
And its pseudo-terminal finds a marker wherever the reads cut the output."""

from __future__ import annotations

import subprocess
import sys

import pytest

from tests import ROOT

sys.path.insert(0, str(ROOT / "scripts"))

from bench_app import process_cpu  # noqa: E402

#: a child whose only busy thread spins for SPIN_S of its own CPU time, ends, and then the
#: child waits for its stdin to close: a CPU-time bound, whatever the machine's speed or load
CHILD = """
import sys, threading, time
def spin():
    while time.thread_time() < {spin}:
        pass
t = threading.Thread(target=spin)
t.start()
t.join()
print("spun", flush=True)
sys.stdin.read()
"""
SPIN_S = 0.2


def test_an_ended_threads_cpu_time_is_counted():
    child = subprocess.Popen([sys.executable, "-c", CHILD.format(spin=SPIN_S)],
                             stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    try:
        assert child.stdout.readline() == "spun\n"
        used = process_cpu(child.pid)
        # at least the ended thread's SPIN_S (its thread_time is the same scheduler clock);
        # far less than a minute: a process's clock, not a wall time or another process's
        assert SPIN_S <= used < 60.0
    finally:
        child.stdin.close()
        child.stdout.close()
        child.wait()
    assert process_cpu(child.pid) == 0.0  # ended and reaped: no clock, no error


def test_a_marker_is_found_in_a_large_read_and_across_two():
    # the start-up benchmark waits for a marker in what the app writes: found at the start of
    # a read larger than any fixed tail, and split across two reads
    from bench_app import seen_in

    marker = b"minimal app ready"
    assert seen_in(marker, b"", marker + b"x" * 20_000)[0]
    found, tail = seen_in(marker, b"", b"y" * 9_000 + marker[:5])
    assert not found and len(tail) == len(marker) - 1
    assert seen_in(marker, tail, marker[5:])[0]
    assert not seen_in(marker, tail, b"other bytes")[0]


@pytest.mark.parametrize("compare", [False, True])
def test_the_benchmark_tells_a_pending_status_line_from_a_complete_one(compare):
    # the benchmark's frame is complete once the status line no longer says its numbers are
    # coming: its pattern must match what the viewer writes meanwhile, at every terse form,
    # and nothing the complete frame's status line says
    from bench_app import PENDING

    from tuibrdf.app.text import TERSE_FORMS, status_text
    from tuibrdf.core.material import Material
    from tuibrdf.core.views import frame as core_frame
    from tuibrdf.render import panes
    from tuibrdf.state.viewer import Side, ViewerState

    sides = [Side.of("ggx"), Side.of("phong")][: 1 + compare]
    state = ViewerState(sides=sides, theta_i=30.0)
    req = core_frame.FrameRequest(tuple(Material(s.model, dict(s.values)) for s in sides), 30.0)
    done = core_frame.compute_frame(req)
    look = panes.Look(color="none")
    for k in range(TERSE_FORMS):
        assert PENDING.search(status_text(state, None, look, {}, "", k).plain)
        assert not PENDING.search(status_text(state, done, look, {}, "", k).plain)
