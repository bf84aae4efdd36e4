"""The published fits of the 100 MERL materials: ABC and Shifted Gamma Distribution tables.

The numbers are those of the public-domain header ``dj_brdf.h`` (Jonathan Dupuy,
https://github.com/jdupuy/dj_brdf, tables ``djb::abc::s_data`` and ``djb::sgd::s_data``),
transcribed as text into ``tuibrdf/core/brdf/data/abc.tsv`` and ``sgd.tsv`` by
``scripts/import_dj_brdf.py``:

* ABC: Löw, Kronander, Ynnerman, Unger 2012, "BRDF models for accurate and efficient rendering
  of glossy surfaces", ACM TOG 31(1).  Row: name, kd (RGB), A (RGB), B, C, η.
* SGD: Bagher, Soler, Holzschuch 2012, "Accurate fitting of measured reflectances using a Shifted
  Gamma micro-facet distribution", Computer Graphics Forum 31(4).  Row: name, other name (the
  name in the SGD data, or empty), then RGB triples ρd, ρs, α, p, f0, f1, κ, Λ, c_g, k, θ0 and
  the fit error.

Each file is read when first needed (the names when the registry is built, the numbers when a
material is first evaluated), every value ``float()`` of the decimal text as written in the
header, so float64 correctly rounded from it.  The tables are package data, not user input, but
a damaged installation still gets one clear line (``ValueError`` naming the file and row).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cache
from pathlib import Path

import numpy as np

DATA_DIR = Path(__file__).resolve().parent / "data"
FILES = {"abc": DATA_DIR / "abc.tsv", "sgd": DATA_DIR / "sgd.tsv"}
N_MATERIALS = 100

SGD_FIELDS = ("rho_d", "rho_s", "alpha", "p", "f0", "f1", "kappa", "lambda", "c_g", "k",
              "theta0", "error")
#: columns after the name(s): (field, width) in file order
_ABC_LAYOUT = (("kd", 3), ("a", 3), ("b", 1), ("c", 1), ("eta", 1))
_SGD_LAYOUT = tuple((f, 3) for f in SGD_FIELDS)
#: fields that must be > 0 for the formulas (and their guards) to hold: powers of a base that
#: must be positive, logarithms taken by the G1 guard, a refractive index
_POSITIVE = {"abc": ("a", "b", "c", "eta"),
             "sgd": ("alpha", "kappa", "lambda", "c_g", "k")}


@dataclass(frozen=True)
class Table:
    """One parsed table: ``names`` in file order, ``other_names`` (SGD; "" where none) and
    ``values[field]`` of shape ``(100, 3)`` (RGB) or ``(100,)``."""

    kind: str
    names: tuple[str, ...]
    other_names: tuple[str, ...]
    values: dict[str, np.ndarray]

    def index(self, name: str) -> int:
        return self.names.index(name)

    def row(self, name: str) -> dict[str, np.ndarray | float]:
        """The parameters of one material: RGB fields as ``(3,)`` arrays, scalars as floats."""
        i = self.index(name)
        return {k: (v[i].copy() if v.ndim == 2 else float(v[i])) for k, v in self.values.items()}


def _lines(kind: str) -> list[tuple[int, list[str]]]:
    """``(line number, cells)`` of the data rows (comments and the column header skipped)."""
    path = FILES[kind]
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as e:
        raise ValueError(f"{path}: cannot read the {kind} material table ({e.strerror})") from None
    rows = []
    header_seen = False
    for no, line in enumerate(text.splitlines(), 1):
        if not line or line.startswith("#"):
            continue
        if not header_seen:
            header_seen = True
            continue
        rows.append((no, line.split("\t")))
    if len(rows) != N_MATERIALS:
        raise ValueError(f"{path}: expected {N_MATERIALS} materials, found {len(rows)}")
    return rows


@cache
def table(kind: str) -> Table:
    """The parsed ``"abc"`` or ``"sgd"`` table (read once, then cached)."""
    path = FILES[kind]
    layout = _ABC_LAYOUT if kind == "abc" else _SGD_LAYOUT
    n_names = 1 if kind == "abc" else 2
    width = n_names + sum(w for _, w in layout)
    names, others, numbers = [], [], []
    for no, cells in _lines(kind):
        if len(cells) != width:
            raise ValueError(f"{path}:{no}: expected {width} columns, found {len(cells)}")
        try:
            nums = [float(c) for c in cells[n_names:]]
        except ValueError:
            raise ValueError(f"{path}:{no}: a value is not a number") from None
        if not all(math.isfinite(x) for x in nums):
            raise ValueError(f"{path}:{no}: a value is not finite")
        names.append(cells[0])
        others.append(cells[1] if kind == "sgd" else "")
        numbers.append(nums)
    if len(set(names)) != len(names):
        raise ValueError(f"{path}: a material name appears twice")
    arr = np.array(numbers, dtype=float)
    values: dict[str, np.ndarray] = {}
    col = 0
    for field, w in layout:
        values[field] = arr[:, col:col + w] if w == 3 else arr[:, col]
        col += w
    for field in _POSITIVE[kind]:
        bad = np.flatnonzero(np.any(values[field].reshape(len(names), -1) <= 0.0, axis=1))
        if bad.size:
            raise ValueError(f"{path}: {field} must be > 0 (material {names[bad[0]]})")
    for v in values.values():
        v.flags.writeable = False
    return Table(kind, tuple(names), tuple(others), values)


@cache
def material_names() -> tuple[str, ...]:
    """The 100 MERL names, sorted (the same set in both tables; checked)."""
    abc = {cells[0] for _, cells in _lines("abc")}
    sgd = {cells[0] for _, cells in _lines("sgd")}
    if abc != sgd:
        raise ValueError(f"{FILES['abc']} and {FILES['sgd']} name different materials: "
                         f"{', '.join(sorted(abc ^ sgd))}")
    return tuple(sorted(abc))


@cache
def material_aliases() -> tuple[tuple[str, str], ...]:
    """``((other name, name), ...)``: the SGD table's other names that differ from the name."""
    out = []
    names = set(material_names())
    for _, cells in _lines("sgd"):
        other = cells[1]
        if other and other != cells[0] and other not in names:
            out.append((other, cells[0]))
    return tuple(sorted(out))
