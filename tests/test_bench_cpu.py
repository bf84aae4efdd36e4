"""scripts/bench_app.py's CPU time of the viewer counts the threads that have ended too (each
frame job's thread ends with its frame): a sum over the live threads' counters misses them.
And its pseudo-terminal finds a marker wherever the reads cut the output."""

from __future__ import annotations

import subprocess
import sys

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
