"""Write ``tuibrdf/core/brdf/data/material_albedo.tsv``: the albedos ``tuibrdf materials`` lists.

    python scripts/gen_material_albedo.py          # rewrite it (about 10 s)
    python scripts/gen_material_albedo.py --check  # exit 1 if it differs from a fresh run

Run it after changing the abc or sgd kernels or the albedo quadrature
(``tuibrdf/core/sphere/albedo.py``); the tests recompute a sample of the entries.
"""

from __future__ import annotations

import sys

from tuibrdf.core.sphere.material_albedo import STORED, stored_text


def main(argv: list[str]) -> int:
    text = stored_text()
    if "--check" in argv:
        if STORED.read_text(encoding="utf-8") != text:
            print(f"{STORED} is out of date: run python scripts/gen_material_albedo.py",
                  file=sys.stderr)
            return 1
        return 0
    STORED.write_text(text, encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
