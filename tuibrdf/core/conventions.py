"""What every front end (viewer, ``tuibrdf render``, the CLI tables) agrees on, declared once.

- The energy test is :func:`tuibrdf.core.sphere.albedo.exceeds_one`: an albedo is flagged "not
  energy-conserving" only when it exceeds 1 by more than its error estimate.
- :func:`luminance`: Rec.709 luminance ``0.2126 R + 0.7152 G + 0.0722 B`` of linear RGB values
  (ITU-R BT.709-6, item 3.3): how an RGB model becomes one number (peak ranking, maps).
- :func:`fmt_value`: the one format of a measured value on screen (3 significant digits).
- :func:`decimals_for`: the decimals of a value with an error estimate (digits following
  the error).
"""

from __future__ import annotations

import numpy as np

#: most decimals a value with an error estimate is printed with (float64 noise below)
MAX_DECIMALS = 12
REC709 = np.array([0.2126, 0.7152, 0.0722])
REC709.setflags(write=False)


def luminance(rgb: np.ndarray) -> np.ndarray:
    """Rec.709 luminance of linear RGB values ``(..., 3)``."""
    return np.asarray(rgb, dtype=float) @ REC709


def fmt_value(v: float) -> str:
    """Short, deterministic number format for titles, ticks and the status line."""
    return f"{float(v):.3g}"


def decimals_for(error) -> int:
    """Decimals whose last digit is the error's first significant digit (the largest error
    of several channels); :data:`MAX_DECIMALS` for an error of 0."""
    e = float(np.max(np.abs(np.asarray(error, dtype=float))))
    if not np.isfinite(e):
        return 0
    if e <= 0.0:  # log10 of 0: an exact value
        return MAX_DECIMALS
    return int(np.clip(-np.floor(np.log10(e)), 0, MAX_DECIMALS))
