"""Refresh the command outputs in ``docs/materials.md``.

Every fenced ``text`` block of that file whose first line is ``$ tuibrdf ...`` is replaced by
the command's real output (as ``scripts/gen_docs.py`` does for docs/cli.md); the prose around
the blocks is left alone.

    python scripts/gen_materials_doc.py          # rewrite the blocks
    python scripts/gen_materials_doc.py --check  # exit 1 if a block is out of date (tested)
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from gen_docs import run_cli  # noqa: E402 — the same runner as docs/cli.md

DOC = Path(__file__).resolve().parent.parent / "docs" / "materials.md"
BLOCK = re.compile(r"```text\n\$ (tuibrdf [^\n]*?)(?:  # exit status \d+)?\n.*?```", re.S)


def render(text: str) -> str:
    def block(m: re.Match) -> str:
        line = m.group(1)
        rc, output = run_cli(line)
        status = f"  # exit status {rc}" if rc else ""
        return f"```text\n$ {line}{status}\n{output.rstrip()}\n```"

    return BLOCK.sub(block, text)


def main(argv: list[str]) -> int:
    old = DOC.read_text(encoding="utf-8")
    new = render(old)
    if "--check" in argv:
        if new != old:
            print(f"{DOC.name} out of date: run python scripts/gen_materials_doc.py",
                  file=sys.stderr)
            return 1
        return 0
    DOC.write_text(new, encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
