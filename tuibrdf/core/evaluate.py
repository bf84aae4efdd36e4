"""``evaluate``: validated, broadcasting evaluation of a registered model."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from .models import get_model
from .numerics import kernel_errstate
from .params import Model


def as_directions(w: Any, name: str) -> np.ndarray:
    w = np.asarray(w, dtype=float)
    if w.ndim == 0 or w.shape[-1] != 3:
        raise ValueError(f"{name} must have shape (..., 3), got {w.shape}")
    if not np.all(np.isfinite(w)):
        raise ValueError(f"{name} contains NaN or inf")
    return w


def evaluate(
    model: str | Model,
    params: Mapping[str, Any] | None,
    wi: Any,
    wo: Any,
) -> np.ndarray:
    """BRDF value(s) in sr⁻¹ (no cosine factor) for unit directions ``wi`` (toward the light)
    and ``wo`` (toward the viewer), arrays of shape ``(..., 3)`` that broadcast together.

    ``params`` maps parameter names to user-unit values (degrees for angles, a 3-sequence for
    RGB); missing names take their defaults.  Returns shape ``(...)`` for scalar models and
    ``(..., 3)`` for RGB ones.  Raises ``ValueError`` for an unknown model or parameter, a value
    out of its range (the message gives the range) or a violated constraint.
    """
    m = get_model(model)
    values = m.resolve(params)
    wi = as_directions(wi, "wi")
    wo = as_directions(wo, "wo")
    wi, wo = np.broadcast_arrays(wi, wo)
    return evaluate_resolved(m, values, wi, wo)


def evaluate_resolved(m: Model, values: Mapping[str, Any], wi: np.ndarray, wo: np.ndarray):
    """:func:`evaluate` without validation, for callers that resolved ``values`` once
    (renderers, quadrature) and evaluate many times."""
    with kernel_errstate():
        return m.kernel(wi, wo, **m.kernel_params(values))
