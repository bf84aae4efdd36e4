"""The energy view: ``E(μ, p)`` (:mod:`tuibrdf.core.sphere.energy`) as a heat map, μ = cos θi
along x (0, grazing, on the left … 1, normal, on the right) and the parameter p along y (its
smallest value at the bottom), one block per table entry; the current (μ, p) marked; beside it a
strip of ``E_avg(p)`` in the same colours; the white-furnace verdict under the title.  An RGB
model shows its largest channel (the one a furnace test fails first).  The colour scale runs
from 0 to 1, or to the largest value when the model gains energy.
"""

from __future__ import annotations

import textwrap

import numpy as np
from rich.console import Group
from rich.text import Text

from tuibrdf.core.conventions import fmt_number
from tuibrdf.render.colormap import DEFAULT_LEVELS, Scale, colorbar, colorize
from tuibrdf.render.halfblock import HalfBlockImage, Mark
from tuibrdf.render.halfdiff_view import MARGIN, LeftLabelled, axis_line
from tuibrdf.render.text import first_fitting

#: the E_avg strip: a gap, then this many columns
STRIP_GAP, STRIP_W = 2, 3
CURRENT_MARK = dict(glyph="●", ascii="O", rgb=(255, 40, 40))


def _largest(a: np.ndarray) -> np.ndarray:
    return a.max(axis=-1) if a.ndim == 3 else a


def energy_picture(name: str, view, width: int, height: int, *, cmap: str = "viridis",
                   levels: int = DEFAULT_LEVELS, color: str = "truecolor") -> Group:
    """The view of :class:`~tuibrdf.core.sphere.energy.EnergyView` ``view`` (None: the model
    has no real parameter) in ``width × height`` cells."""
    if view is None:  # said whole, wrapped to the pane (a compare pane is narrow)
        note = (f"{name}: no real parameter for an energy table E(μ, p); its albedo at θi "
                "is on the status line")
        lines = textwrap.wrap(note, max(int(width), 1), break_long_words=True)
        return Group(*(Text(line) for line in lines[:max(int(height), 1)]))
    t = view.table
    img_w, rows = int(width) - MARGIN - STRIP_GAP - STRIP_W, int(height) - 6
    if img_w < 4 or rows < 2:  # too small for the picture: the verdict alone
        lines = [Text(name), Text(view.verdict, style="bold red" if view.gains else "green")]
        for line in lines:
            line.truncate(int(width), overflow="ellipsis")
        return Group(*lines[: max(1, int(height))])
    E = _largest(t.E)  # (P, M)
    avg = t.E_avg.max(axis=-1) if t.E_avg.ndim == 2 else t.E_avg
    P, M = E.shape
    px_h = 2 * rows
    # each pixel shows the table entry it falls in: blocks, not an interpolation
    col_of = np.minimum((np.arange(img_w) + 0.5) * M / img_w, M - 1).astype(int)
    row_of = np.minimum((np.arange(px_h) + 0.5) * P / px_h, P - 1).astype(int)[::-1]
    pic = np.full((px_h, img_w + STRIP_GAP + STRIP_W), np.nan)
    pic[:, :img_w] = E[row_of][:, col_of]
    pic[:, img_w + STRIP_GAP:] = avg[row_of][:, None]
    top = max(1.0, float(np.nanmax(pic)))
    scale = Scale(top)
    col = colorize(pic, cmap, levels=levels, scale=scale, rgb_mode="luminance")
    # the current (μ, p): the nearest entry's block
    j = int(np.argmin(np.abs(t.mu - view.mu)))
    i = int(np.argmin(np.abs(t.values - view.current)))
    cx = int(np.flatnonzero(col_of == j)[len(np.flatnonzero(col_of == j)) // 2]) \
        if (col_of == j).any() else 0
    ys = np.flatnonzero(row_of == i)
    cy = int(ys[len(ys) // 2]) // 2 if ys.size else 0
    marks = [Mark(cy, cx, **CURRENT_MARK), Mark(cy, img_w + STRIP_GAP + STRIP_W // 2,
                                                 **CURRENT_MARK)]
    image = HalfBlockImage(col.index, col.palette, marks, color_system=color)
    sym = view.symbol
    labels = [""] * rows
    for k in (P - 1, P // 2, 0):  # the parameter's values at a few rows
        r = [rr for rr in range(rows) if k in (row_of[2 * rr], row_of[2 * rr + 1])]
        if r:
            labels[r[len(r) // 2]] = fmt_number(float(f"{t.values[k]:.3g}"))
    labels[0] = labels[0] or sym
    axis = axis_line(img_w, [0.0, 0.5, 1.0], ["0", "0.5", "1"], "μ")
    axis.append(" " * max(0, img_w + MARGIN + STRIP_GAP - axis.cell_len) + "avg", style="dim")
    bar = colorbar(scale, cmap, int(width), levels=levels, unit="", color_system=color)
    verdict = Text(view.verdict, style="bold red" if view.gains else "bold green",
                   no_wrap=True, overflow="ellipsis")
    now = (f"E = {view.E:.4g} ± {view.error:.0e}, E_avg = {view.E_avg:.4g} ± "
           f"{view.E_avg_error:.0e} at {sym} = {fmt_number(view.current)}")
    head = first_fitting([[(name, 2), (f"E(μ, {sym}): white furnace", 0),
                           ("largest channel" if t.rgb else "", 3)]], int(width))
    now_t = Text(now, no_wrap=True, overflow="ellipsis")
    for t_ in (verdict, axis, now_t):
        t_.truncate(int(width), overflow="ellipsis")
    return Group(head, verdict, LeftLabelled(image, labels, color), axis, now_t, bar)
