"""``evaluate``: validated, broadcasting evaluation of a registered model.

Input contract of the directions (docs/design.md, "The API's input contract"):

* ``wi`` and ``wo`` are float arrays of shape ``(..., 3)`` that broadcast together; anything
  else is a ``ValueError`` naming the argument and the shape;
* every component is finite: NaN or ±inf is a ``ValueError`` naming the argument and the
  first bad index;
* a direction is a direction: any non-zero vector is **normalised** first, so ``(0, 0, 2)``,
  ``(0, 0, 1e200)`` and ``(0, 0, 1e-310)`` all mean the normal.  The length is computed
  without overflow or underflow (the vector is scaled by the power of two of its largest
  component first, where its squares would overflow or underflow), and a
  unit vector moves by at most a few ulps.  The zero vector has no direction:
  ``ValueError`` with its index;
* float64 vectors that are already unit (``| |w|² − 1 | ≤`` :data:`UNIT_TOL`, a few ulps) pass
  unchanged and uncopied: the check is one pass over the input, and normalising them would
  move them by no more than that;
* directions below the horizon (z < 0) are allowed and give 0 (the BRDF is defined on the
  upper hemisphere).

The kernels themselves (:func:`evaluate_resolved`) assume unit vectors and do not check.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from tuibrdf.core.numerics import check_errstate, kernel_errstate
from tuibrdf.core.params import Model
from tuibrdf.core.registry import BROADCAST_KERNELS, get_model


def _first(mask: np.ndarray) -> str:
    """The index of the first True in ``mask``, as text (``""`` for a single vector)."""
    if mask.ndim == 0:
        return ""
    return str(tuple(int(i) for i in np.argwhere(mask)[0]))


#: how far ``|w|²`` may be from 1 for ``w`` to count as a unit vector and pass unchanged: 8 ulps
#: of 1 covers a normalised vector's own rounding (each of its three squares and two sums adds
#: at most ½ ulp) and the rounding of the check's sum; unnormalised, such a vector differs from
#: its normalised self by at most 4 ulps
UNIT_TOL = 8 * 2.0**-52
#: where ``|w|²`` of the check can normalise ``w`` directly: its squares stay normal numbers
#: (a component below 1e-145 squares to a subnormal and keeps fewer bits: 1e-290 bounds the
#: largest one's square from below) and its sum stays finite (components up to 1e150); the
#: scaled path gives the same bits there
SQUARES_EXACT = (1e-290, 1e300)


def _squared_norm(w: np.ndarray) -> np.ndarray:
    """``x² + y² + z²`` of ``w (..., 3)``, summed in that order: elementwise ufuncs, so the same
    bits on every CPU (einsum's 3-term sum took another order, and twice the time: 8.6 against
    4.2 ms for 10⁶ vectors).  The squares in one pass over ``w`` as it lies in memory (a
    fifth less time than three strided ones)."""
    s = w * w
    return s[..., 0] + s[..., 1] + s[..., 2]


def _as_array(w: Any, name: str) -> np.ndarray:
    """``w`` as a float array of shape ``(..., 3)`` (uncopied when it is one), else a
    ``ValueError`` naming ``name``."""
    try:
        w = np.asarray(w, dtype=float)
    except (TypeError, ValueError, OverflowError):
        raise ValueError(f"{name} must be an array of numbers of shape (..., 3)") from None
    if w.ndim == 0 or w.shape[-1] != 3:
        raise ValueError(f"{name} must have shape (..., 3), got {w.shape}")
    return w


def as_directions(w: Any, name: str) -> np.ndarray:
    """``w`` as unit vectors of shape ``(..., 3)``, validated (see the module docstring)."""
    w = _as_array(w, name)
    if w.size:
        # the usual input, finite unit vectors, in one pass: |w|² then its range (a NaN makes
        # min and max NaN, an inf makes max inf: both fail the test and take the checks below)
        with check_errstate():  # an overflow or underflow here takes the scaled path
            n2 = _squared_norm(w)
        lo, hi = n2.min(), n2.max()
        if 1.0 - UNIT_TOL <= lo and hi <= 1.0 + UNIT_TOL:
            return w
        if SQUARES_EXACT[0] <= lo and hi <= SQUARES_EXACT[1]:
            # finite, non-zero, and |w|² neither overflowed nor lost bits to underflow: one
            # square root and one division (the scaled path below gives the same bits)
            return w / np.sqrt(n2)[..., None]
    # |w| without overflow (1e200² = inf) or underflow (1e-310² = 0): scale by the largest
    # component first (a subnormal vector keeps only the bits it has).  np.maximum propagates
    # NaN and inf, so the largest component is also the finiteness check.
    a = np.abs(w)
    big = np.maximum(np.maximum(a[..., 0], a[..., 1]), a[..., 2])
    finite = np.isfinite(big)
    if not finite.all():
        at = _first(~finite)
        raise ValueError(f"{name}{at and '[' + at[1:-1].rstrip(',') + ']'} contains NaN or inf")
    zero = big == 0.0
    if zero.any():
        at = _first(zero)
        raise ValueError(f"{name}{at and '[' + at[1:-1].rstrip(',') + ']'} is the zero vector: "
                         "a direction must be non-zero")
    # scaled by a power of two (exact: the same bits as the direct division above, where both
    # apply) that puts the largest component in [1, 2): never lower, where a unit vector's
    # subnormal component would round (halving 5e-324 gives 0)
    s = np.ldexp(w, 1 - np.frexp(big)[1][..., None])  # big > 0 checked above
    n = np.sqrt(_squared_norm(s))  # in [1, 2√3)
    return s / n[..., None]


def evaluate(
    model: str | Model,
    params: Mapping[str, Any] | None,
    wi: Any,
    wo: Any,
) -> np.ndarray:
    """BRDF value(s) in sr⁻¹ (no cosine factor) for directions ``wi`` (toward the light) and
    ``wo`` (toward the viewer), arrays of shape ``(..., 3)`` that broadcast together.  Each
    direction is normalised first; NaN, inf or the zero vector is a ``ValueError`` (see the
    module docstring for the whole contract).

    ``params`` maps parameter names to user-unit values (degrees for angles, a 3-sequence for
    RGB); missing names take their defaults.  Returns shape ``(...)`` for scalar models and
    ``(..., 3)`` for RGB ones.  Raises ``ValueError`` for an unknown model or parameter, a value
    out of its range (the message gives the range) or a violated constraint.
    """
    m = get_model(model)
    values = m.resolve(params)
    wi, wo = _as_array(wi, "wi"), _as_array(wo, "wo")
    shape = np.broadcast_shapes(wi.shape, wo.shape)
    inner = math.prod(shape[1:-1])  # pairs per row of the first axis (0: an empty input)
    if m.kernel in BROADCAST_KERNELS and len(shape) > 1 and inner:
        blocks = shape[0] // max(1, BLOCK // inner)
        if blocks >= 2:
            out = _in_blocks(m, values, wi, wo, shape, blocks)
            if out is not None:
                return out
    wi, wo = np.broadcast_arrays(as_directions(wi, "wi"), as_directions(wo, "wo"))
    return evaluate_resolved(m, values, wi, wo)


#: :func:`evaluate` takes large inputs about this many direction pairs at a time (along
#: their first axis), so that each block's check, the kernel's temporaries and its values stay
#: in the CPU's cache (2¹⁶ pairs: 3 MiB of directions): the inputs are read from memory once,
#: not once by the check and again by each step of the kernel.  On 10⁶ pairs ggx's took 107
#: ms in one piece and 56 ms in blocks, against 98 ms for its kernel alone in one piece
#: (docs/benchmarks.md, bench_evaluate).  Each step of a built-in kernel is elementwise: the
#: same bits either way (tested)
BLOCK = 1 << 16


def _in_blocks(m: Model, values: Mapping[str, Any], wi: np.ndarray, wo: np.ndarray,
               shape: tuple[int, ...], blocks: int) -> np.ndarray | None:
    """:func:`evaluate` of a built-in kernel over ``shape`` (the broadcast shape of ``wi`` and
    ``wo``) in ``blocks`` near-equal parts of its first axis, each of :data:`BLOCK`/2 pairs or
    more (so none is small enough for a kernel to take another way: phong's power of a few
    elements); None if a direction is not one (the whole input's check then says which)."""
    whole = [w.ndim < len(shape) or w.shape[0] == 1 for w in (wi, wo)]
    try:  # an input broadcast along the first axis is checked once, not per block
        wi, wo = (as_directions(w, n) if k else w for w, n, k in zip((wi, wo), ("wi", "wo"),
                                                                       whole, strict=True))
    except ValueError:
        return None
    out = None
    for j in range(blocks):
        rows = slice(j * shape[0] // blocks, (j + 1) * shape[0] // blocks)
        try:  # (only the checks: what the kernel raises is the caller's)
            a, b = (w if k else as_directions(w[rows], n)
                    for w, n, k in zip((wi, wo), ("wi", "wo"), whole, strict=True))
        except ValueError:
            return None
        f = evaluate_resolved(m, values, *np.broadcast_arrays(a, b))
        if out is None:
            out = np.empty(shape[:1] + f.shape[1:], dtype=f.dtype)
        out[rows] = f
    return out


def f_cos(f: np.ndarray, wo: np.ndarray) -> np.ndarray:
    """``f·cos θo``: BRDF values ``f`` (shape ``(...)``, or ``(..., 3)`` for an RGB model) at
    the outgoing directions ``wo (..., 3)`` times ``cos θo``, 0 below the horizon: the one
    place the viewer's f·cos θr and the albedo's integrand weight ``f`` by the cosine."""
    c = np.maximum(np.asarray(wo)[..., 2], 0.0)
    f = np.asarray(f)
    return f * (c[..., None] if f.ndim > c.ndim else c)


def _one_direction(w: np.ndarray) -> np.ndarray | None:
    """The single direction ``w`` repeats, if it is one vector broadcast along every leading
    axis (all strides 0, as ``np.broadcast_to(wi, wo.shape)`` makes), else None."""
    if w.ndim > 1 and w.size and not any(w.strides[:-1]):
        return w[(0,) * (w.ndim - 1)]
    return None


def evaluate_resolved(m: Model, values: Mapping[str, Any], wi: np.ndarray, wo: np.ndarray):
    """:func:`evaluate` without validation, for callers that resolved ``values`` once
    (renderers, quadrature) and evaluate many times.

    A built-in kernel given one direction broadcast against many (``np.broadcast_to``, zero
    strides) evaluates that direction's terms once rather than once per element: the same
    operations on the same numbers, so the same values (tested)."""
    kw = m.kernel_params(values)
    if (m.kernel in BROADCAST_KERNELS and type(wi) is np.ndarray and type(wo) is np.ndarray
            and wi.shape == wo.shape):
        one_i = _one_direction(wi)
        if one_i is not None:
            wi = one_i
        else:
            one_o = _one_direction(wo)
            if one_o is not None:
                wo = one_o
    with kernel_errstate():
        f = m.kernel(wi, wo, **kw)
    return flush_tiny(f)


#: BRDF values of smaller magnitude are 0 (sr⁻¹): a picture's scale is taken from its maximum
#: (pixels / max, log10(max), a 1-2-5 × 10^k step, max · 10⁻⁸ for the log scale), and these
#: stay finite and normal only for a maximum well above the smallest normal float (2.2e-308):
#: 1e-290 leaves 18 decades for them.  Physically, any such value is 0.
FLUSH_BELOW = 1e-290


def flush_tiny(f):
    """``f`` with values of magnitude under :data:`FLUSH_BELOW` (subnormal ones included) made
    0: `render blinn-phong -p ks=5e-324` (a 1e-323 peak) and `render lambert -p kd=1e-307`
    failed in the sections, the solid and the θh/θd views, whose scales overflowed or
    underflowed.  Every consumer (pictures, albedo, fits, `eval`) gets the same 0."""
    a = np.asarray(f)
    if a.dtype.kind != "f" or not a.size:
        return f
    if a.ndim == 0:  # a scalar: 0 of the same kind
        if 0.0 < abs(float(a)) < FLUSH_BELOW:
            return np.zeros_like(a) if isinstance(f, np.ndarray) else 0.0
        return f
    sub = np.abs(a) < FLUSH_BELOW
    sub &= a != 0.0
    return np.where(sub, 0.0, a) if sub.any() else f
