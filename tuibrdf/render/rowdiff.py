"""What changed in a row of a picture, known where the picture is drawn.

A picture drawn after another in the same place compares their cells as numbers (the
half-block image's colour codes, the braille canvas's characters and colours) and marks each
row it drew again with the cells that differ: :class:`ChangedRow`.  The widget that shows the
rows then repaints those cells without comparing the rows' segments again
(:meth:`tuibrdf.app.widgets.Rows._set`; it falls back to comparing them for any other row).
"""

from __future__ import annotations

import numpy as np
from rich.segment import Segment


class ChangedRow(list):
    """A row of segments (a list) drawn against ``against``, the row object shown before it in
    the same place: the two are the same outside cells ``span = (x0, x1)`` (it may be wider
    than the change, never narrower)."""

    __slots__ = ("against", "span")

    def __init__(self, segments: list[Segment], against: list[Segment],
                 span: tuple[int, int]) -> None:
        super().__init__(segments)
        self.against, self.span = against, span


def spans(diff: np.ndarray) -> list[tuple[int, int]]:
    """Per row of a ``(rows, cells)`` bool array of differing cells, ``(first, last + 1)``
    (``(0, 0)`` for a row without one)."""
    w = diff.shape[1]
    any_ = diff.any(axis=1)
    x0 = np.where(any_, diff.argmax(axis=1), 0)
    x1 = np.where(any_, w - diff[:, ::-1].argmax(axis=1), 0)
    return list(zip(x0.tolist(), x1.tolist(), strict=True))


def kept_rows(old_rows: list[list[Segment]] | None, diff: np.ndarray | None,
              height: int) -> tuple[list[list[Segment]], np.ndarray]:
    """``(out, same)``: ``height`` rows, each without a differing cell (``diff``, ``(rows,
    cells)``; None: every row differs) the row of ``old_rows`` at its place itself, the
    others empty lists to draw; and which rows were kept."""
    same = np.zeros(height, dtype=bool) if diff is None else ~diff.any(axis=1)
    out: list[list[Segment]] = [[] for _ in range(height)]
    for r in np.flatnonzero(same).tolist():
        out[r] = old_rows[r]
    return out, same


def mark_changed(out: list[list[Segment]], old_rows: list[list[Segment]], redrawn: np.ndarray,
                 diff: np.ndarray) -> None:
    """Each row of ``out`` drawn again (``redrawn``) as a :class:`ChangedRow` against the row
    at its place in ``old_rows``, with the span of its differing cells (``diff``)."""
    rows = np.flatnonzero(redrawn).tolist()
    for r, span in zip(rows, spans(diff[rows]), strict=True):
        out[r] = ChangedRow(out[r], old_rows[r], span)
    for row in old_rows:  # their own comparison is used by now: no chain of old rows kept
        if type(row) is ChangedRow:
            row.against = None
