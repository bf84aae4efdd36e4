"""What the generated code calls: the runtime helpers ``rt_*`` (vectorised: each takes scalars
or arrays), with the results docs/reference/formats.md gives where GLSL leaves them undefined
(``x / 0``, ``pow`` of a negative, ``sqrt`` and ``log`` outside their domain, ...), and
:data:`RUNTIME`, the namespace the generated source runs in (``np`` and the short names it
calls them by)."""

from __future__ import annotations

import numpy as np


def _zeros_like(*xs):
    shape = np.broadcast_shapes(*(np.shape(x) for x in xs))
    return np.zeros(shape) if shape else 0.0


def rt_div(a, b):
    """``a / b``, 0 where ``b == 0`` (GLSL leaves it undefined; a GPU gives ±inf/NaN)."""
    if np.ndim(b) == 0:
        return a / b if b != 0 else _zeros_like(a)
    out = np.zeros(np.broadcast_shapes(np.shape(a), np.shape(b)))
    np.divide(a, b, out=out, where=b != 0)
    return out


def rt_sel(c, a, b):
    """``c ? a : b`` lane by lane; a uniform (scalar) condition picks without ``where``."""
    if np.ndim(c) == 0:
        return a if c else b
    return np.where(c, a, b)


def rt_sqrt(x):
    return np.sqrt(np.maximum(x, 0.0))  # sqrt of x < 0 is undefined in GLSL: as of 0


def rt_inversesqrt(x):
    return rt_div(1.0, rt_sqrt(x))


def rt_pow(x, y):
    """``x^y`` for ``x > 0``, else 0 (GLSL: undefined for x < 0, and for x = 0, y ≤ 0).
    Lanes with ``x ≤ 0`` may compute NaN/inf before being replaced (shader errstate)."""
    pos = np.greater(x, 0.0)
    if np.ndim(pos) == 0 and np.ndim(y) == 0:
        return np.power(np.float64(x), y) if pos else 0.0
    if np.ndim(y) == 0 and y in (2.0, 3.0, 4.0, 5.0):  # small integer powers: products
        p = x * x
        if y >= 4.0:
            p = p * p
        if y in (3.0, 5.0):
            p = p * x
        return np.where(pos, p, 0.0)
    return np.where(pos, np.power(x, y), 0.0)


def rt_log(x, fn=np.log):
    pos = np.greater(x, 0.0)  # log of x ≤ 0 is undefined in GLSL: 0
    if np.ndim(pos) == 0:
        return fn(np.float64(x)) if pos else 0.0
    return np.where(pos, fn(np.where(pos, x, 1.0)), 0.0)


def rt_log2(x):
    return rt_log(x, np.log2)


def rt_asin(x):
    return np.arcsin(np.clip(x, -1.0, 1.0))  # |x| > 1 is undefined in GLSL: clamped


def rt_acos(x):
    return np.arccos(np.clip(x, -1.0, 1.0))


def rt_fract(x):
    return x - np.floor(x)


def rt_mod(x, y):
    return x - y * np.floor(rt_div(x, y))


def rt_step(edge, x):
    return np.where(np.less(x, edge), 0.0, 1.0) + 0.0


def rt_smoothstep(e0, e1, x):
    t = np.clip(rt_div(np.subtract(x, e0), np.subtract(e1, e0)), 0.0, 1.0)
    same = np.equal(e0, e1)  # undefined in GLSL: a step at the edge
    return np.where(same, rt_step(e0, x), t * t * (3.0 - 2.0 * t)) + 0.0


def rt_sign(x):
    return np.sign(x) + 0.0


def rt_and(a, b):
    return np.logical_and(a, b)


def rt_or(a, b):
    return np.logical_or(a, b)


def rt_xor(a, b):
    return np.logical_xor(a, b)


def rt_not(a):
    return np.logical_not(a)


RUNTIME = {
    "np": np, "_div": rt_div, "_sel": rt_sel, "_sqrt": rt_sqrt, "_isqrt": rt_inversesqrt,
    "_pow": rt_pow, "_log": rt_log, "_log2": rt_log2, "_asin": rt_asin, "_acos": rt_acos,
    "_fract": rt_fract, "_mod": rt_mod, "_step": rt_step, "_smooth": rt_smoothstep,
    "_sign": rt_sign, "_and": rt_and, "_or": rt_or, "_xor": rt_xor, "_not": rt_not,
}
