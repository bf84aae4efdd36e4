"""A reader that leaves early (`tuibrdf models | head -1`) gets no traceback on stderr."""

from __future__ import annotations

import subprocess
import sys


def test_closed_stdout_is_quiet():
    p = subprocess.Popen([sys.executable, "-m", "tuibrdf", "models"],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    p.stdout.close()  # the reader is gone before the first write
    err = p.stderr.read().decode()
    p.stderr.close()
    assert p.wait(timeout=60) in (0, 141)
    assert "Traceback" not in err and "BrokenPipe" not in err, err
