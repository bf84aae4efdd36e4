"""Directional albedo curve a(θi) over 0–90° (SPEC §4 view 4), drawn with plotext.

The curve, ``a(θi) = ∫ f(wi, wo) cos θr dω`` at every 3°, comes with the frame
(:func:`tuibrdf.core.scene.albedo_curve`, cached per material: moving θi only moves the
marker); the pane with its title is :func:`tuibrdf.render.panes.albedo_pane`.  The line
``a = 1`` is drawn; RGB models get one curve per channel.
"""

from __future__ import annotations

import numpy as np
import plotext as plt

from .polar import GUIDE_COLOR, INCIDENT_COLOR, PLOT_LOCK, curve_color, finish_plot


def albedo_plot(
    thetas: np.ndarray,
    curves: list[tuple[str, np.ndarray]],
    width: int,
    height: int,
    *,
    theta_i_deg: float | None = None,
    color: str = "truecolor",
) -> str:
    """plotext line plot of the curves with the line a = 1 and a marker at ``theta_i_deg``."""
    top = max(1.1, max(float(np.max(a)) for _, a in curves) * 1.05)
    with PLOT_LOCK:
        plt.clf()
        plt.theme("clear")
        plt.plotsize(width, height)
        plt.xlim(0.0, 90.0)
        plt.ylim(0.0, top)
        plt.xticks([0, 30, 60, 90])
        plt.yticks(np.arange(0.0, top, 0.5 if top < 3 else np.ceil(top / 4)).tolist())
        plt.hline(1.0, GUIDE_COLOR)
        if theta_i_deg is not None:
            plt.vline(float(theta_i_deg), INCIDENT_COLOR)
        for j, (label, a) in enumerate(curves):
            plt.plot(thetas.tolist(), np.asarray(a, dtype=float).tolist(), marker="braille",
                     color=curve_color(label, j), label=label if len(curves) > 1 else None)
        return finish_plot(color)
