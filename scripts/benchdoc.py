"""Benchmark tables written into docs/benchmarks.md by the scripts that measure them.

Each table lives in its own marked section, ``<!-- NAME -->`` … ``<!-- /NAME -->``, with the
exact command, the machine (CPU model, cores, Python, numpy, Textual, Rich, the load average
when it started) and the date; writing a section again replaces it, the rest of the file
stays.  A script calls::

    from benchdoc import command_line, write_section
    write_section("bench_app", table, command_line())

Not a test; the numbers are the machine's (docs/benchmarks.md says how to read them).
"""

from __future__ import annotations

import datetime
import os
import platform
import re
import shlex
import sys
from importlib import metadata
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DOC = ROOT / "docs" / "benchmarks.md"
WRITE_FLAG = "--write-docs"


def _cpu_model() -> str:
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine() or "unknown CPU"


def _version(dist: str) -> str:
    try:
        return metadata.version(dist)
    except metadata.PackageNotFoundError:
        return "not installed"


def machine() -> str:
    """One line: the CPU, its cores, the OS, the versions that move the numbers, the load."""
    load = "n/a"
    if hasattr(os, "getloadavg"):
        load = " ".join(f"{x:.2f}" for x in os.getloadavg())
    return (f"{_cpu_model()}, {os.cpu_count()} cores, {platform.system()} "
            f"{platform.release()}; Python {platform.python_version()}, numpy "
            f"{_version('numpy')}, textual {_version('textual')}, rich {_version('rich')}; "
            f"load average at the start {load}")


def command_line(argv: list[str] | None = None) -> str:
    """The command that ran this script, as typed from the repository's root (without
    :data:`WRITE_FLAG`, which changes where the table goes, not what it holds)."""
    argv = sys.argv if argv is None else argv
    script = Path(argv[0]).resolve()
    try:
        script_path = script.relative_to(ROOT).as_posix()
    except ValueError:
        script_path = str(script)
    args = [a for a in argv[1:] if a != WRITE_FLAG]
    return " ".join(["python", script_path, *map(shlex.quote, args)])


def section(name: str, markdown_table: str, command: str, *, machine_line: str | None = None,
            date: str | None = None) -> str:
    """The marked section of ``name``: the command, the machine and the date, the table."""
    when = date or datetime.date.today().isoformat()
    return "\n".join([
        f"<!-- {name} -->",
        f"`{command}`",
        "",
        f"{machine_line or machine()}; {when}.",
        "",
        markdown_table.strip(),
        f"<!-- /{name} -->",
    ])


def write_section(name: str, markdown_table: str, command: str, *, doc: Path = DOC,
                  machine_line: str | None = None, date: str | None = None) -> Path:
    """Put the section of ``name`` into ``doc``: in place of the one there, else at the end."""
    if not re.fullmatch(r"[A-Za-z0-9_.-]+", name):
        raise ValueError(f"section name {name!r}: letters, digits, '_', '.', '-' only")
    block = section(name, markdown_table, command, machine_line=machine_line, date=date)
    text = doc.read_text(encoding="utf-8") if doc.exists() else ""
    marked = re.compile(rf"<!-- {re.escape(name)} -->.*?<!-- /{re.escape(name)} -->",
                        re.DOTALL)
    if marked.search(text):
        text = marked.sub(lambda _: block, text, count=1)
    else:
        text = text.rstrip("\n") + ("\n\n" if text.strip() else "") + block + "\n"
    doc.write_text(text, encoding="utf-8")
    return doc
