"""What every front end (viewer, ``tuibrdf render``, the CLI tables) agrees on, declared once.

- :data:`ENERGY_TOL`: a directional albedo ``a(θi) > 1 + ENERGY_TOL`` is flagged "not
  energy-conserving".  The allowance is the quadrature's own error on sharp lobes (≲ 1e-3,
  docs/accuracy.md), so a conserving model is never flagged for rounding.
- :func:`luminance`: Rec.709 luminance ``0.2126 R + 0.7152 G + 0.0722 B`` of linear RGB values
  (ITU-R BT.709-6, item 3.3): how an RGB model becomes one number (peak ranking, maps).
- :func:`fmt_value`: the one format of a measured value on screen (3 significant digits).
"""

from __future__ import annotations

import numpy as np

ENERGY_TOL = 1e-3
REC709 = np.array([0.2126, 0.7152, 0.0722])
REC709.setflags(write=False)


def luminance(rgb: np.ndarray) -> np.ndarray:
    """Rec.709 luminance of linear RGB values ``(..., 3)``."""
    return np.asarray(rgb, dtype=float) @ REC709


def exceeds_one(albedo) -> bool:
    """Whether any channel of an albedo is above ``1 + ENERGY_TOL``."""
    return bool(np.max(np.asarray(albedo, dtype=float)) > 1.0 + ENERGY_TOL)


def fmt_value(v: float) -> str:
    """Short, deterministic number format for titles, ticks and the status line."""
    return f"{float(v):.3g}"
