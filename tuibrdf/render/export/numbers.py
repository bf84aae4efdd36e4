"""A :class:`~tuibrdf.core.views.tables.Table` as a file: CSV, JSON or NPZ bytes.

- CSV: a header row of the column names, then one row per sample; every number written with
  Python's ``repr`` (the shortest text that reads back as the same float64), ``nan`` where a
  direction is below the horizon.
- JSON: a list of objects, one per row, keyed by the column names (NaN → ``null``); floats
  with the same round-trip precision (``json`` writes ``repr``).
- NPZ (``numpy.savez_compressed``): the table's arrays under their names, and ``metadata``,
  a JSON string (model, parameters, θi, φi, ``wi``, …).  NPZ members carry a fixed time stamp
  (:mod:`zipfile`'s, from ``numpy``), so the same table gives the same bytes.
"""

from __future__ import annotations

import io
import json

import numpy as np

from tuibrdf.core.views.tables import Table


def _row_arrays(table: Table) -> tuple[list[str], list[np.ndarray]]:
    names = [k for k, v in table.columns.items() if np.ndim(v) == 1]
    return names, [np.asarray(table.columns[k], dtype=float) for k in names]


def to_csv(table: Table) -> str:
    names, cols = _row_arrays(table)
    lines = [",".join(names)]
    for row in zip(*(c.tolist() for c in cols), strict=True):
        lines.append(",".join(repr(x) for x in row))
    return "\n".join(lines) + "\n"


def to_json(table: Table) -> str:
    names, cols = _row_arrays(table)
    rows = [{k: (None if x != x else x) for k, x in zip(names, row, strict=True)}  # NaN → null
            for row in zip(*(c.tolist() for c in cols), strict=True)]
    return json.dumps(rows, indent=1, allow_nan=False) + "\n"


def to_npz(table: Table) -> bytes:
    buf = io.BytesIO()
    meta = json.dumps(table.meta, sort_keys=True, allow_nan=False)
    np.savez_compressed(buf, **{k: np.asarray(v) for k, v in table.columns.items()},
                        metadata=np.array(meta))
    return buf.getvalue()
