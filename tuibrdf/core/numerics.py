"""Floating-point policy, in one place.

Every model guards its divisions, square roots and powers where the formula breaks (each guard
says why in a comment).  Because of that, the kernels run under a *raising* policy: a division
by zero, an overflow or an invalid operation that slipped past a guard is a bug, and it must be
loud (``FloatingPointError``) rather than a NaN drawn as black on the screen.  Underflow is
benign here (``exp(-tan²θh/m²)`` of a sharp lobe legitimately flushes to 0) and is ignored.

Use :func:`kernel_errstate` around any evaluation of a model; nothing else in the package calls
``np.errstate``.
"""

from __future__ import annotations

import numpy as np

#: The one errstate policy of the package (see module docstring).
ERRSTATE = {"divide": "raise", "over": "raise", "invalid": "raise", "under": "ignore"}


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
