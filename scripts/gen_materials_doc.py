"""Refresh the command outputs in ``docs/reference/materials.md``.

Every fenced ``text`` block of that file whose first line is ``$ tuibrdf ...`` is replaced by
the command's real output, as ``scripts/gen_docs.py`` does for every doc it refreshes (it
refreshes this one too); the prose around the blocks is left alone.

    python scripts/gen_materials_doc.py          # rewrite the blocks
    python scripts/gen_materials_doc.py --check  # exit 1 if a block is out of date (tested)
"""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from gen_docs import REFERENCE, refresh  # noqa: E402 — the same runner as every generated doc

DOC = REFERENCE / "materials.md"


def main(argv: list[str]) -> int:
    old = DOC.read_text(encoding="utf-8")
    new = refresh(old)
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
