"""The viewer's check report (key F): the verdicts of :mod:`tuibrdf.core.sphere.checks`, one
line each, the reciprocity error at the current light as an equal-area map, and for a model
with a sampler the χ² test's maps: the pdf, the histogram of the samples and their difference.
"""

from __future__ import annotations

import numpy as np
from rich.console import Group
from rich.table import Table
from rich.text import Text

from tuibrdf.render.colormap import Scale, colorize
from tuibrdf.render.halfblock import HalfBlockImage

#: blue (histogram below the pdf) – grey – red (above), as the compare view's difference map
DIVERGING = ((59, 76, 192), (221, 221, 221), (180, 4, 38))


def _image(values: np.ndarray, scale: Scale, cmap: str, color: str) -> HalfBlockImage:
    col = colorize(values, cmap, scale=scale)
    return HalfBlockImage(col.index, col.palette, color_system=color)


def _diverging(d: np.ndarray, top: float, color: str) -> HalfBlockImage:
    """Blue (histogram below the pdf) – grey – red (above), symmetric about 0."""
    t = np.clip((d / (top if top > 0 else 1.0) + 1.0) / 2.0, 0.0, 1.0)
    lo, mid, hi = (np.array(c, dtype=float) for c in DIVERGING)
    k = np.rint(np.nan_to_num(t, nan=0.5) * 16).astype(int)
    pal = np.array([lo + (mid - lo) * (j / 8) if j <= 8 else mid + (hi - mid) * ((j - 8) / 8)
                    for j in range(17)])
    index = np.where(np.isfinite(d), k, -1)
    return HalfBlockImage(index, np.rint(pal).astype(np.uint8), color_system=color)


def check_report(title: str, results, recip: np.ndarray | None, chi2=None, *,
                 cmap: str = "viridis", color: str = "truecolor") -> Group:
    """The report: ``results`` (:class:`~tuibrdf.core.sphere.checks.CheckResult`), the
    reciprocity map ``recip`` (relative error, log scale over 10 decades below 1), and the
    χ² result (:class:`~tuibrdf.core.sphere.chi2.Chi2Result`) of the current incidence."""
    parts: list = [Text(title, style="bold")]
    for r in results:
        worst = "—" if r.worst is None else f"{r.worst:.4g}"
        line = Text(f"{r.name:<12}")
        line.append("ok  " if r.ok else "FAIL", style="bold green" if r.ok else "bold red")
        line.append(f"  {worst:>11}  {r.where}")
        parts.append(line)
        if r.detail:
            parts.append(Text(f"{'':<18}{r.detail}", style="dim"))
    maps = Table.grid(padding=(0, 2))
    heads, cells = [], []
    if recip is not None:
        top = float(np.nanmax(recip)) if np.isfinite(recip).any() else 0.0
        heads.append(f"reciprocity error (max {top:.1e})")
        cells.append(_image(np.where(np.isfinite(recip), np.maximum(recip, 1e-16), np.nan),
                            Scale(1.0, True, 16.0), cmap, color))
    if chi2 is not None:
        pdf, hist = chi2.pdf_map, chi2.hist_map
        top = max(float(np.nanmax(pdf)), float(np.nanmax(hist)), 1e-300)
        heads += [f"pdf θi={chi2.theta_i:g}°", "histogram", "histogram − pdf"]
        cells += [_image(pdf, Scale(top), cmap, color), _image(hist, Scale(top), cmap, color),
                  _diverging(hist - pdf, float(np.nanmax(np.abs(hist - pdf))), color)]
    if cells:
        maps.add_row(*(Text(h, style="dim") for h in heads))
        maps.add_row(*cells)
        parts += [Text(""), maps]
    parts.append(Text("F or Esc closes", style="dim"))
    return Group(*parts)
