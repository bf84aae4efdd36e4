"""What every front end (viewer, ``tuibrdf render``, the CLI tables) agrees on, declared once.

- The energy test is :func:`tuibrdf.core.sphere.albedo.exceeds_one`: an albedo is flagged "not
  energy-conserving" only when it exceeds 1 by more than its error estimate.
- :func:`luminance`: Rec.709 luminance ``0.2126 R + 0.7152 G + 0.0722 B`` of linear RGB values
  (ITU-R BT.709-6, item 3.3): how an RGB model becomes one number (peak ranking, maps).
- :func:`fmt_value`: the one format of a measured value on screen (3 significant digits).
- :func:`fmt_number`: the one format of a number that was or can be typed (a parameter, an
  option, a table's angle): ``%g``, RGB triples comma-joined.
- :func:`decimals_for`: the decimals of a value with an error estimate (digits following
  the error).
"""

from __future__ import annotations

# numpy is imported inside the functions that need it: the command line's --help and its
# argument errors format numbers with this module (and read its display defaults), and must
# not pay for numpy (≈ 60 ms; tests/cli/test_text.py)

#: most decimals a value with an error estimate is printed with (float64 noise below)
MAX_DECIMALS = 12
#: Rec.709 luminance weights of linear R, G, B (ITU-R BT.709-6, item 3.3)
REC709 = (0.2126, 0.7152, 0.0722)


def luminance(rgb):
    """Rec.709 luminance of linear RGB values ``(..., 3)``."""
    import numpy as np

    return np.asarray(rgb, dtype=float) @ REC709


def fmt_value(v: float) -> str:
    """Short, deterministic number format for titles, ticks and the status line."""
    return f"{float(v):.3g}"


def fmt_number(v) -> str:
    """A number, or a parameter's value, as the texts write it where it was typed or can be
    typed back: ``%g`` (up to 6 significant digits: ``0.2``, ``1e-05``), an RGB triple or a
    list comma-joined (``0.9,0.6,0.2``), anything else (a choice, a file path) as it is.  The
    parameter ranges and errors, the viewer's panel, the CLI's tables and option defaults."""
    if isinstance(v, tuple | list):
        return ",".join(fmt_number(x) for x in v)
    if isinstance(v, float | int) and not isinstance(v, bool):
        return f"{v:g}"
    return str(v)


def decimals_for(error) -> int:
    """Decimals whose last digit is the error's first significant digit (the largest error
    of several channels); :data:`MAX_DECIMALS` for an error of 0."""
    import numpy as np

    e = float(np.max(np.abs(np.asarray(error, dtype=float))))
    if not np.isfinite(e):
        return 0
    if e <= 0.0:  # log10 of 0: an exact value
        return MAX_DECIMALS
    return int(np.clip(-np.floor(np.log10(e)), 0, MAX_DECIMALS))


def fmt_error(error, decimals: int) -> str:
    """The error to print beside a value printed with ``decimals`` decimals: the estimate (the
    largest of several channels) plus the printed value's own rounding, half a unit of its
    last decimal, rounded *up* to one significant digit (``3e-10``), so that the interval
    printed holds whatever the estimate holds (a value cut to 12 decimals is never printed
    with ``± 1e-15``)."""
    import math

    import numpy as np

    e = float(np.max(np.abs(np.asarray(error, dtype=float))))
    if not np.isfinite(e):
        return f"{e}"
    e += 0.5 * 10.0 ** -decimals
    exp = math.floor(math.log10(e))  # e ≥ half a unit of the last decimal > 0
    # the leading digit rounded up, with a margin of 1e-9 against 10**exp's own rounding
    m = math.ceil(e / 10.0 ** exp * (1.0 - 1e-12))
    if m >= 10:
        m, exp = 1, exp + 1
    # 10**exp's rounding could leave m·10**exp an ulp below e: one more unit then
    while m * 10.0 ** exp < e:
        m += 1
        if m >= 10:
            m, exp = 1, exp + 1
    return f"{m}e{exp:+03d}"
