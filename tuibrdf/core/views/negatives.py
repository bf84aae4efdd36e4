"""How much of a user model's output is negative, and so clamped to 0 (numpy only).

A model read from a file (``.brdf``, ``.py``) may return negative values — a sign slip in a
formula — which every picture clamps to 0, so such a material looks merely dark.  This module
measures the share of outgoing directions where the model's *unclamped* kernel
(:attr:`~tuibrdf.core.params.Model.raw_kernel`) is negative in any channel, for the light at
``wi``; the viewer and ``tuibrdf render`` then say so in one line (:func:`negative_note`).

Directions: the 1 321 vertices of the hemisphere mesh of :data:`LEVEL`
(:func:`tuibrdf.core.sphere.mesh.hemisphere`), each weighted by its solid angle (the mesh's
quadrature weights); the share is the weighted fraction."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from tuibrdf.core.numerics import shader_errstate
from tuibrdf.core.params import Model
from tuibrdf.core.sphere.mesh import hemisphere

LEVEL = 4


def negative_share(model: Model, values: Mapping[str, Any], wi: np.ndarray) -> float:
    """The solid-angle fraction of outgoing directions where the unclamped model is below 0
    in any channel; 0 for a model without a raw kernel (the
    built-in ones).  Errors of the user's kernel propagate (the picture reports them)."""
    if model.raw_kernel is None:
        return 0.0
    mesh = hemisphere(LEVEL)
    wo, w = mesh.vertices, mesh.weights  # solid-angle weights, Σ w = 2π
    with shader_errstate():  # the user's arithmetic
        f = np.asarray(model.raw_kernel(np.broadcast_to(wi, wo.shape), wo,
                                        **model.kernel_params(values)), dtype=float)
    neg = f < 0.0
    if neg.ndim == 2:
        neg = neg.any(axis=1)
    return float(np.sum(w[neg]) / np.sum(w))  # Σ w = 2π > 0


def negative_note(share: float) -> str:
    """``f < 0 in 12 % of directions, clamped to 0`` (``< 1 %`` for a small share), or ``""``
    when nothing is negative."""
    if share <= 0.0:
        return ""
    pct = "< 1" if share < 0.005 else f"{100.0 * share:.0f}"
    return f"f < 0 in {pct} % of directions, clamped to 0"
