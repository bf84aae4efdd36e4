"""The command-line fuzz (issue 17): a few hundred generated argv per run, in-process and as
subprocesses.  Each must end with exit 0 (nothing on stderr) or exit 2 (one line starting with
``tuibrdf``), with no traceback, no warning, no hang, and without opening the viewer.  The
generator and the rules are ``scripts/fuzz_cli.py`` (which runs thousands: docs/reference/cli.md).

The seed changes with the day, so CI explores new command lines over time while any one day is
reproducible: a failure prints its seed and argv (``python scripts/fuzz_cli.py --seed S``).
"""

from __future__ import annotations

import datetime
import sys

from tests import ROOT

sys.path.insert(0, str(ROOT / "scripts"))

import fuzz_cli  # noqa: E402

CASES = 300
SUBPROCESSES = 8


def test_fuzz_cli():
    seed = int(datetime.date.today().strftime("%Y%m%d"))
    r = fuzz_cli.fuzz(CASES, seed, SUBPROCESSES)
    shown = "\n".join(f"[{w}] {k}: {a!r}\n{e[-500:]}" for w, a, k, e in r["failures"][:5])
    assert not r["failures"], f"seed {seed}: {len(r['failures'])} failures\n{shown}"
    # the generator reaches past argparse: both outcomes occur
    assert r["counts"].get("exit 0", 0) > 10 and r["counts"].get("exit 2", 0) > 10


def test_judge_rules():
    """The rules themselves (so a broken judge cannot pass everything)."""
    j = fuzz_cli.judge
    assert j(0, "") == "" and j(2, "tuibrdf: error: x\n") == ""
    assert j(0, "tuibrdf: error: x\n") == "exit 0 with stderr"
    assert j(2, "tuibrdf: error: x\nmore\n") == "exit 2, several lines"
    assert j(2, "error\n") == "exit 2, unprefixed line"
    assert j(1, "tuibrdf: error: x\n") == "exit 1"
    assert j(2, "Traceback (most recent call last):\n") == "traceback"
    assert j(0, "", timed_out=True) == "hang"
    assert j(0, "x.py:1: RuntimeWarning: divide by zero\n") == "warning"
