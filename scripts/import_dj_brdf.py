"""Write ``tuibrdf/core/brdf/data/abc.tsv`` and ``sgd.tsv`` from the text of ``dj_brdf.h``.

    python scripts/import_dj_brdf.py PATH/TO/dj_brdf.h

The header (public domain, https://github.com/jdupuy/dj_brdf) tabulates the ABC fits (Löw et al.
2012) and the Shifted Gamma Distribution fits (Bagher, Soler, Holzschuch 2012) of the 100 MERL
materials in ``djb::abc::s_data`` and ``djb::sgd::s_data``.  Every number is copied as the
decimal text the header writes (no float round trip), in the header's row order, so the files
are a transcription of the header's tables and nothing else.  ``tuibrdf/core/brdf/materials.py``
parses them; ``tests/core/brdf/test_materials.py`` checks rows against the header's text.
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

DATA = Path(__file__).resolve().parent.parent / "tuibrdf" / "core" / "data"
SOURCE = ("dj_brdf.h, https://github.com/jdupuy/dj_brdf (commit "
          "94cb16a43b16c056e81947be9687eef79ec511a3), public domain")

ABC_COLUMNS = ("name", "kd_r", "kd_g", "kd_b", "a_r", "a_g", "a_b", "b", "c", "eta")
SGD_VECTORS = ("rho_d", "rho_s", "alpha", "p", "f0", "f1", "kappa", "lambda", "c_g", "k",
               "theta0", "error")
SGD_COLUMNS = ("name", "other_name",
               *(f"{v}_{c}" for v in SGD_VECTORS for c in "rgb"))

ABC_HEAD = f"""\
# ABC fits of the 100 MERL materials (Löw, Kronander, Ynnerman, Unger 2012, "BRDF models for
# accurate and efficient rendering of glossy surfaces", ACM TOG 31(1)), per-material parameters
# provided to dj_brdf by J. Kronander.
# Source: table djb::abc::s_data of {SOURCE}.
# Numbers copied as the header writes them (scripts/import_dj_brdf.py); licence: public domain.
# f = kd/pi + F(cos theta_d; eta) A / (1 + b (1 - cos theta_h))^c G / (pi cos theta_i cos theta_o)
"""

SGD_HEAD = f"""\
# Shifted Gamma Distribution fits of the 100 MERL materials (Bagher, Soler, Holzschuch 2012,
# "Accurate fitting of measured reflectances using a Shifted Gamma micro-facet distribution",
# Computer Graphics Forum 31(4)), per-material parameters provided to dj_brdf by the authors.
# Source: table djb::sgd::s_data of {SOURCE}.
# Numbers copied as the header writes them (scripts/import_dj_brdf.py); licence: public domain.
# other_name: the name the SGD paper's data uses, when it differs ("" in the header: none).
"""

NUM = r"\s*([-+0-9.eE]+)\s*"
VEC = r"\{" + ",".join([NUM] * 3) + r"\}"


def table(text: str, decl: str) -> list[str]:
    start = text.index(decl)
    end = text.index("};", start)
    return [ln for ln in text[start:end].splitlines() if ln.strip().startswith('{ "')]


def abc_rows(text: str) -> list[list[str]]:
    pat = re.compile(r'\s*\{ "([^"]+)",\s*' + VEC + r",\s*" + VEC + "," + ",".join([NUM] * 3)
                     + r"\},?\s*$")
    return [list(pat.match(ln).groups()) for ln in table(text, "abc::data abc::s_data[]")]


def sgd_rows(text: str) -> list[list[str]]:
    pat = re.compile(r'\s*\{ "([^"]+)", "([^"]*)",\s*' + r",\s*".join([VEC] * 12)
                     + r"\s*\},?\s*$")
    return [list(pat.match(ln).groups()) for ln in table(text, "sgd::data sgd::s_data[]")]


def write(path: Path, head: str, columns, rows) -> None:
    lines = [head.rstrip("\n"), "\t".join(columns)] + ["\t".join(r) for r in rows]
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")


def main(argv: list[str]) -> int:
    if len(argv) != 1:
        print(__doc__, file=sys.stderr)
        return 2
    text = Path(argv[0]).read_text(encoding="utf-8")
    abc, sgd = abc_rows(text), sgd_rows(text)
    assert len(abc) == len(sgd) == 100, (len(abc), len(sgd))
    write(DATA / "abc.tsv", ABC_HEAD, ABC_COLUMNS, abc)
    write(DATA / "sgd.tsv", SGD_HEAD, SGD_COLUMNS, sgd)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
