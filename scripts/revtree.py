"""``extract(rev, dest)``: the package ``tuibrdf`` of git revision ``rev`` written under
``dest`` (from ``git archive``), for the benchmarks that run an older revision beside this
tree (``--rev`` / ``--before``)."""

from __future__ import annotations

import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def extract(rev: str, dest: str) -> str:
    """``dest`` (created if missing), now holding ``tuibrdf/`` as it was at ``rev``."""
    Path(dest).mkdir(parents=True, exist_ok=True)
    tar = subprocess.run(["git", "-C", str(ROOT), "archive", rev, "tuibrdf"],
                         capture_output=True, check=True).stdout
    subprocess.run(["tar", "-x", "-C", dest], input=tar, check=True)
    return dest
