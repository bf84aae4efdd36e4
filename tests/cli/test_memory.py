"""The commands' C allocator keeps freed memory (tuibrdf/cli/memory.py)."""

from __future__ import annotations

import os
import platform
import subprocess
import sys

import pytest

#: in a fresh interpreter: a numpy expression with eight live temporaries of 177 KB (the size
#: of a .bsdf map's (7392, 3) arrays), repeated; the minor page faults of 50 repeats
CHURN = """
import resource, sys
import numpy as np
from tuibrdf.cli.memory import keep_freed_memory
if sys.argv[1] == "keep":
    assert keep_freed_memory()
a = np.ones((7392, 3))
def step():
    return sum(float(x[0, 0]) for x in [a * k for k in range(8)])
step()
r0 = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
for _ in range(50):
    step()
print(resource.getrusage(resource.RUSAGE_SELF).ru_minflt - r0)
"""


def faults(mode: str) -> int:
    env = {k: v for k, v in os.environ.items()  # glibc's own defaults, whatever the shell's
           if not k.startswith(("MALLOC_", "GLIBC_TUNABLES"))}
    out = subprocess.run([sys.executable, "-c", CHURN, mode], capture_output=True, text=True,
                         check=True, env=env)
    return int(out.stdout)


@pytest.mark.skipif(platform.libc_ver()[0] != "glibc", reason="glibc's allocator only")
def test_numpy_temporaries_reuse_their_pages_once_the_memory_is_kept():
    # glibc's default gives the top of its heap back once 128 KiB of it are free: each repeat
    # then faults its temporaries' pages in again (8 × 44 pages: ≈ 17,000 in 50 repeats); kept,
    # the repeats reuse them (a few faults at most, for Python's own objects)
    assert faults("keep") <= 50
    assert faults("default") >= 50 * 8 * 44 // 2


def test_another_platform_is_left_alone(monkeypatch):
    from tuibrdf.cli import memory

    monkeypatch.setattr(memory.sys, "platform", "darwin")
    assert memory.keep_freed_memory() is False


def test_every_command_keeps_freed_memory(monkeypatch, capsys):
    from tuibrdf import cli

    calls = []
    monkeypatch.setattr(cli, "keep_freed_memory", lambda: calls.append(1))
    assert cli.main(["models"]) == 0
    assert calls == [1]
