"""Floating-point policy, in one place.

Every model guards its divisions, square roots and powers where the formula breaks (each guard
says why in a comment).  Because of that, the kernels run under a *raising* policy: a division
by zero, an overflow or an invalid operation that slipped past a guard is a bug, and it must be
loud (``FloatingPointError``) rather than a NaN drawn as black on the screen.  Underflow is
benign here (``exp(-tan²θh/m²)`` of a sharp lobe legitimately flushes to 0) and is ignored.

Use :func:`kernel_errstate` around any evaluation of a model; nothing else in the package calls
``np.errstate`` but the two named exceptions below (:func:`check_errstate`,
:func:`shader_errstate`).
"""

from __future__ import annotations

import numpy as np

#: The one errstate policy of the package (see module docstring).
ERRSTATE = {"divide": "raise", "over": "raise", "invalid": "raise", "under": "ignore"}


#: What a model's failure arrives as: ``ValueError`` (a user kernel's NaN, inf or exception,
#: named with its file; a value out of range) and ``ArithmeticError`` (the raising policy's
#: ``FloatingPointError``, a ``ZeroDivisionError``).
KERNEL_ERRORS = (ValueError, ArithmeticError)


def kernel_errstate() -> np.errstate:
    """Context manager applying :data:`ERRSTATE`."""
    return np.errstate(**ERRSTATE)


def safe_div(num: np.ndarray, den: np.ndarray, where: np.ndarray, fill: float = 0.0) -> np.ndarray:
    """``num / den`` where ``where`` holds, ``fill`` elsewhere, without evaluating the rest.

    ``np.where(mask, a / b, 0)`` evaluates ``a / b`` everywhere and would raise under our policy;
    this divides only the selected elements.  Scalars (a kernel's quantities of a single
    direction) take a branch instead of an array: a numpy scalar, divided only if ``where``.
    """
    shape = getattr(den, "shape", ())
    s_num, s_where = getattr(num, "shape", ()), getattr(where, "shape", ())
    if (s_num and s_num != shape) or s_where != shape:
        shape = np.broadcast_shapes(s_num, shape, s_where)
    if not shape:
        # scalars: float64 scalars obey the errstate policy as arrays do; divided only if where
        return np.float64(num) / np.float64(den) if where else np.float64(fill)
    if fill == 0.0:
        out = np.zeros(shape)  # float64: the package computes in float64 only
    else:
        out = np.empty(shape)
        out.fill(fill)
    np.divide(num, den, out=out, where=where)
    return out


def safe_sqrt(x: np.ndarray) -> np.ndarray:
    """``sqrt(max(x, 0))``: rounding can push a quantity that is ≥ 0 in exact arithmetic
    (``1 - cos²``, ``n² - sin²``) a few ulps below zero."""
    return np.sqrt(np.maximum(x, 0.0))


#: User shaders (BRDF Explorer ``.brdf`` files) were written for a GPU's IEEE arithmetic: both
#: sides of a branch run on every direction and a formula may overflow on directions whose value
#: is then discarded.  Their translated code runs under this policy (no exception, no warning);
#: the shader model replaces any NaN, ±inf or negative result by 0 (core/formats/brdf_explorer.py).
SHADER_ERRSTATE = {"divide": "ignore", "over": "ignore", "invalid": "ignore", "under": "ignore"}


def shader_errstate() -> np.errstate:
    """Context manager applying :data:`SHADER_ERRSTATE` (translated user shaders only)."""
    return np.errstate(**SHADER_ERRSTATE)


#: Pictures decide things by comparing numbers with thresholds: the dot or pixel a point falls
#: in, the pixel centres a triangle's box holds, a colour level, the nearer of two fragments.
#: The numbers come from sin, exp, pow, matmul …, which numpy computes in SIMD or scalar loops
#: that differ by CPU and numpy version in the last bits, and a picture's geometry puts many of
#: them exactly on a threshold (x = 0 in a symmetric window is a dot boundary, a horizon row a
#: half-integer).  So every such decision is taken on :func:`snap`'s value, in the decision's
#: own unit (a dot, a pixel, a level): within 2⁻³¹ ≈ 4.7e-10 of a multiple of this, a number
#: becomes that multiple exactly, so one that is on a threshold in exact arithmetic is on it
#: whatever its last bits, and the tie goes one fixed way.  Any other number moves by at most
#: 4.7e-10 of a unit: nothing drawn shows it.
SNAP = 2.0**-30
_SNAP_ABOVE = 2.0**22  # from here on every float is a multiple of SNAP already (ulp ≥ 2⁻³⁰)


def snap(v) -> np.ndarray:
    """``v`` rounded to the nearest multiple of :data:`SNAP` (ties to even), as a float array.

    Exact: scaling by a power of two and rounding to an integer below 2⁵² round nothing else.
    Magnitudes ≥ 2²² (multiples of SNAP already), ±inf and NaN come back as they are, with no
    floating-point warning."""
    v = np.asarray(v, dtype=float)
    if v.size and -_SNAP_ABOVE < v.min() and v.max() < _SNAP_ABOVE:  # False for NaN
        # every element small (a picture's coordinates): the same rounding in three passes
        out = np.multiply(v, 1.0 / SNAP, out=np.empty_like(v))  # an array, 0-d too
        np.rint(out, out=out)
        out *= SNAP
        return out
    small = np.abs(v) < _SNAP_ABOVE  # False for NaN
    return np.where(small, np.rint(np.where(small, v, 0.0) * (1.0 / SNAP)) * SNAP, v)


def snapped_floor(v) -> np.ndarray:
    """``⌊v⌋`` decided on :func:`snap`'s value (a float array)."""
    return np.floor(snap(v))


def snapped_ceil(v) -> np.ndarray:
    """``⌈v⌉`` decided on :func:`snap`'s value (a float array)."""
    return np.ceil(snap(v))


def snapped_rint(v) -> np.ndarray:
    """The nearest integer, halves to even (``np.rint``), decided on :func:`snap`'s value."""
    return np.rint(snap(v))


#: The API's check of its directions (:func:`tuibrdf.core.evaluate.as_directions`) squares
#: every component in one pass: a component beyond 1.3e154 overflows to inf, one below 1.5e-154
#: underflows, and either sends that input to the exact, scaled path, which decides.  Those two
#: are expected there; a division by zero or an invalid operation is still a bug.
CHECK_ERRSTATE = {"divide": "raise", "over": "ignore", "invalid": "raise", "under": "ignore"}


def check_errstate() -> np.errstate:
    """Context manager applying :data:`CHECK_ERRSTATE` (the directions' one-pass check only)."""
    return np.errstate(**CHECK_ERRSTATE)
