"""tuibrdf — a terminal BRDF viewer.

The public Python API is numpy only (importing it never loads textual or rich)::

    >>> import numpy as np, tuibrdf
    >>> wi = np.array([0.0, 0.0, 1.0])
    >>> float(tuibrdf.evaluate("lambert", {"kd": 0.5}, wi, wi))  # doctest: +ELLIPSIS
    0.159154...
"""

from __future__ import annotations

from .core.evaluate import evaluate
from .core.models import MODELS, get_model

__all__ = ["MODELS", "evaluate", "get_model", "albedo"]
__version__ = "0.1.0"


def albedo(model, params=None, theta_i_deg=0.0, **kwargs):
    """Directional albedo ``a(θi) = ∫ f cos θr dω`` (see :mod:`tuibrdf.core.quadrature`)."""
    from .core.quadrature import albedo as _albedo

    return _albedo(model, params, theta_i_deg, **kwargs)
