"""tuibrdf — a terminal BRDF viewer.

The public Python API is numpy only (importing it never loads textual or rich)::

    >>> import numpy as np, tuibrdf
    >>> wi = np.array([0.0, 0.0, 1.0])
    >>> float(tuibrdf.evaluate("lambert", {"kd": 0.5}, wi, wi))  # doctest: +ELLIPSIS
    0.159154...
"""

from __future__ import annotations

TYPE_CHECKING = False  # typing is not imported for ``tuibrdf --help`` (≈ 3 ms)
if TYPE_CHECKING:
    from typing import Any

__all__ = ["MODELS", "evaluate", "get_model", "albedo", "picture"]
__version__ = "0.1.0"


def __getattr__(name: str) -> Any:
    """``evaluate``, ``MODELS`` and ``get_model`` are imported on first use (PEP 562), so
    that ``tuibrdf --help`` does not pay for numpy."""
    if name == "evaluate":
        from tuibrdf.core.evaluate import evaluate

        return evaluate
    if name in ("MODELS", "get_model"):
        from tuibrdf.core import registry as models

        return getattr(models, name)
    if name in ("picture", "Picture"):  # Rich and the renderers: only when asked for
        from tuibrdf.render.export import picture as pictures

        return getattr(pictures, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def albedo(model, params=None, theta_i_deg=0.0, **kwargs):
    """Directional albedo ``a(θi) = ∫ f cos θr dω`` (see :mod:`tuibrdf.core.sphere.albedo`)."""
    from tuibrdf.core.sphere.albedo import albedo as _albedo

    return _albedo(model, params, theta_i_deg, **kwargs)
