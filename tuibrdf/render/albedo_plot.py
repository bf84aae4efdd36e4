"""Directional albedo curve a(θi) over 0–90° (SPEC §4 view 4), drawn with plotext.

``a(θi) = ∫ f(wi, wo) cos θr dω`` from ``tuibrdf.core.quadrature.albedo_curve_resolved`` (its
accurate default) at every :data:`STEP_DEG` degrees (the curve does not depend on θi, so it is
cached per model and parameter values: moving θi only moves the marker).
The line ``a = 1`` is drawn; the title flags a curve that exceeds it (not energy-conserving).
RGB models get one curve per channel.
"""

from __future__ import annotations

import threading
from collections import OrderedDict
from typing import Any

import numpy as np
import plotext as plt
from rich.console import Group

from ..core.params import Model
from ..core.quadrature import albedo_curve_resolved, albedo_resolved
from .colormap import fmt_value
from .polar import (
    GUIDE_COLOR,
    INCIDENT_COLOR,
    PLOT_LOCK,
    channel_curves,
    curve_color,
    finish_plot,
    plot_body,
)
from .text import title

STEP_DEG = 3.0
#: the incidence angles of the curve
THETAS = np.arange(0.0, 90.0 + STEP_DEG / 2, STEP_DEG)
THETAS.setflags(write=False)
ENERGY_TOL = 1e-3  # quadrature error allowance before a value counts as "> 1"
CACHE_SIZE = 32

_CURVES: OrderedDict[tuple, np.ndarray] = OrderedDict()
_LOCK = threading.Lock()  # the viewer computes curves in a worker thread


def _key(model: Model, values: dict[str, Any]) -> tuple:
    return (model.name, tuple(sorted((k, tuple(v) if isinstance(v, list | tuple) else v)
                                     for k, v in values.items())))


def cached_curve(model: Model, values: dict[str, Any]) -> np.ndarray | None:
    """The curve if it was computed already (no work), else ``None``."""
    with _LOCK:
        return _CURVES.get(_key(model, values))


def albedo_curve(model: Model, values: dict[str, Any]) -> tuple[np.ndarray, np.ndarray]:
    """``(θi degrees, a)`` with ``a`` of shape ``(n,)`` or ``(n, 3)`` (cached per model and
    values: the curve does not depend on the current θi).

    Each point is the default, accurate quadrature (``albedo_resolved``: ≲ 1e-4 on default
    lobes, ≲ 1e-3 on sharp ones).  A uniform level-5 mesh would be 20× faster and wrong by
    0.44 for the seed's Cook-Torrance (m = 0.07): a picture of the wrong curve.  Cost: 10 ms
    (phong n = 70) to 0.4–0.6 s (cook-torrance m = 0.07, ggx α = 0.05) for the 31 points,
    so the viewer computes it in a worker thread.
    """
    key = _key(model, values)
    a = cached_curve(model, values)
    if a is None:
        a = np.asarray(albedo_curve_resolved(model, values, THETAS), dtype=float)
        a.setflags(write=False)
        with _LOCK:
            _CURVES[key] = a
            while len(_CURVES) > CACHE_SIZE:
                _CURVES.popitem(last=False)
    return THETAS, a


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


def albedo_view(
    model: Model,
    values: dict[str, Any],
    theta_i_deg: float,
    width: int,
    height: int,
    *,
    color: str = "truecolor",
) -> Group:
    """Title (a at the current θi, flagged when > 1) and the a(θi) plot."""
    thetas, a = albedo_curve(model, values)
    now = np.atleast_1d(np.asarray(albedo_resolved(model, values, theta_i_deg)))
    curves = channel_curves(model.name, a)
    over = bool(np.max(a) > 1.0 + ENERGY_TOL)
    flag = f"a>1 (max {fmt_value(float(np.max(a)))}): not energy-conserving" if over else ""
    now_s = ",".join(fmt_value(float(x)) for x in now)
    text = albedo_plot(thetas, curves, width, height - 1, theta_i_deg=theta_i_deg, color=color)
    head = title([(model.name, 2), (f"a(θi={theta_i_deg:g}°) = {now_s}", 0), (flag.strip(), 1)],
                 width, style="bold red" if over and color != "none" else "")
    return Group(head, plot_body(text, color))
