"""Evaluating the three channels of an RGB model in the cheaper of two layouts.

An RGB kernel computes grey quantities (angles, D, G: arrays of shape ``(...)``) and combines
them with per-channel parameters.  Two layouts give the same numbers (the same operations on
the same operands, element by element):

* *together*: the grey arrays as ``(..., 1)`` against ``(3,)`` parameters, one numpy call per
  operation for all channels; numpy's inner loop then runs over the last axis of 3, several
  times slower per element (5–13 ns against 0.4–1 ns for a contiguous ``(...)`` operation);
* *per channel*: three passes with scalar parameters over ``(...)`` arrays, written into the
  columns of the result: three times the calls, each fast per element.

Small evaluations (the viewer's peak search, a section) are dominated by the cost per call,
large ones (a map, a mesh) by the cost per element: :data:`TOGETHER_MAX` chooses.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

import numpy as np

#: At or below this many points the channels are computed together (see the module docstring;
#: the crossover measured by scripts/bench_kernels.py lies between 100 and 1000 points)
TOGETHER_MAX = 256


def rgb(above, grey: Sequence, params: Sequence[np.ndarray], channel: Callable) -> np.ndarray:
    """``(..., 3)``: ``channel(*grey, *params)`` for each channel, 0 where ``above`` is False.

    ``above`` has the result's shape ``(...)`` (both directions in the upper hemisphere, so
    every quantity of the two directions broadcasts to it); ``grey`` are arrays (or scalars)
    that broadcast to it; ``params`` are ``(3,)`` arrays.  ``channel`` is called either once
    with ``(..., 1)`` grey arrays and the ``(3,)`` parameters, or three times with the grey
    arrays and the channel's scalars, so it must only use elementwise operations.
    """
    shape = np.shape(above)
    if math.prod(shape) <= TOGETHER_MAX:
        out = channel(*(np.asarray(x)[..., None] for x in grey), *params)
        return np.where(np.asarray(above)[..., None], out, 0.0)
    out = np.empty(shape + (3,))
    for k in range(3):
        out[..., k] = channel(*grey, *(p[k] for p in params))
    out[~np.asarray(above)] = 0.0
    return out
