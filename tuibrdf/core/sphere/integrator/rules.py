"""The Gauss–Kronrod pairs of the integrator and the arithmetic of panels.

K15/G7 (QUADPACK's QK15) and K7/G3 on [-1, 1] with their nodes' distances from a panel's
end; a pair's value and error ``|K − G|`` for panels from their values at the nodes; and the
per-panel bookkeeping both adaptive loops share (the panels kept so far, sums and counts by
group, error over tolerance).
"""

from __future__ import annotations

import numpy as np

# QUADPACK QK15 (Piessens, de Doncker-Kapenga, Überhuber, Kahaner 1983): Kronrod abscissae
# (positive half, descending, 0 last), Kronrod weights, and the weights of the 7-point Gauss
# rule on the odd-indexed abscissae.  Checked in tests/core/sphere/test_albedo.py (G7 = numpy's
# leggauss(7),
# K15 exact for polynomials of degree 22).
_XGK = (0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
        0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
        0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
        0.207784955007898467600689403773245, 0.000000000000000000000000000000000)
_WGK = (0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
        0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
        0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
        0.204432940075298892414161999234649, 0.209482141084727828012999174891714)
_WG = (0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
       0.381830050505118944950369775488975, 0.417959183673469387755102040816327)


def _kronrod15() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    x = np.array(_XGK)
    wk = np.array(_WGK)
    wg = np.zeros(8)
    wg[1::2] = _WG
    nodes = np.concatenate([-x[:-1], x[::-1]])  # ascending, 15 nodes
    return (nodes, np.concatenate([wk[:-1], wk[::-1]]), np.concatenate([wg[:-1], wg[::-1]]))


#: K15 nodes on [-1, 1] (ascending), Kronrod weights, Gauss weights (0 off the G7 nodes).
X15, WK15, WG15 = _kronrod15()
for _a in (X15, WK15, WG15):
    _a.setflags(write=False)

# The 7-point Kronrod extension of the 3-point Gauss rule (Kronrod 1965; the values of
# QUADPACK's documentation and of scipy's tables): nodes (positive half, descending), Kronrod
# weights, Gauss weights 5/9 and 8/9 on ±√(3/5) and 0.  Checked in tests/core/sphere/test_albedo.py.
_XGK7 = (0.960491268708020283423507092629080, 0.774596669241483377035853079956480,
         0.434243749346802558002071502844628, 0.0)
_WGK7 = (0.104656226026467265193823857192073, 0.268488089868333440728569280666710,
         0.401397414775962222905051818618432, 0.450916538658474142345110087045571)


def _kronrod7() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    x, wk = np.array(_XGK7), np.array(_WGK7)
    wg = np.array([0.0, 5.0 / 9.0, 0.0, 8.0 / 9.0])
    return (np.concatenate([-x[:-1], x[::-1]]), np.concatenate([wk[:-1], wk[::-1]]),
            np.concatenate([wg[:-1], wg[::-1]]))


#: K7 nodes on [-1, 1] (ascending), Kronrod weights, Gauss weights (0 off the G3 nodes): the
#: inner rule of panels narrower than :data:`.adaptive.SMALL_PANEL` lobe widths.
X7, WK7, WG7 = _kronrod7()
for _a in (X7, WK7, WG7):
    _a.setflags(write=False)
#: ``1 − x`` of the K15 and K7 nodes (by node count): the nodes' distance from the panel's end
_ONE_MINUS = {15: 1.0 - X15, 7: 1.0 - X7}
for _a in _ONE_MINUS.values():
    _a.setflags(write=False)


def _grow(kept: tuple, new: tuple) -> tuple:
    """The panels kept so far (``None`` each before the first pass) with the new ones appended,
    array by array: the bookkeeping both adaptive loops share."""
    if kept[0] is None:
        return new
    return tuple(np.concatenate([a, b]) for a, b in zip(kept, new, strict=True))


def _rule(g: np.ndarray, half: np.ndarray, wk: np.ndarray = WK15,
          wg: np.ndarray = WG15) -> tuple[np.ndarray, np.ndarray]:
    """Kronrod value and |Kronrod − Gauss| of panels from their values ``g (p, n[, k])`` at
    the rule's nodes (K15/G7 by default, or K7/G3)."""
    if g.ndim == 2:
        k = np.einsum("pn,n->p", g, wk) * half
        gg = np.einsum("pn,n->p", g, wg) * half
    else:
        # channel by channel: einsum sums a strided row in order, as it does over "pnc" (the
        # same values, bit for bit: tests/core/sphere/test_albedo.py), in half the time of the 3-D
        # form
        k, gg = np.empty(g.shape[::2]), np.empty(g.shape[::2])
        for i in range(g.shape[2]):
            k[:, i] = np.einsum("pn,n->p", g[:, :, i], wk)
            gg[:, i] = np.einsum("pn,n->p", g[:, :, i], wg)
        k *= half[:, None]
        gg *= half[:, None]
    return k, np.abs(k - gg)


def _ratio(e: np.ndarray, tol: np.ndarray) -> np.ndarray:
    """Per row: error over tolerance (same shapes, tol > 0), ``(p,)``; for RGB rows the worst
    channel (each channel has its own tolerance: a dim channel is as accurate, relatively,
    as a bright one)."""
    r = e / tol
    return r.max(axis=1) if r.ndim == 2 else r


def _sum_by(idx: np.ndarray, x: np.ndarray, n: int) -> np.ndarray:
    """Sum of the rows of ``x (p,)`` or ``(p, k)`` by group ``idx``: ``(n,)`` or ``(n, k)``."""
    if x.ndim == 1:
        return np.bincount(idx, weights=x, minlength=n)
    out = np.empty((n, x.shape[1]))
    for i, xi in enumerate(np.ascontiguousarray(x.T)):  # one copy, not one per channel
        out[:, i] = np.bincount(idx, weights=xi, minlength=n)
    return out


def _count(idx: np.ndarray, n: int) -> np.ndarray:
    """How many of ``idx`` fall in each of ``0 … n − 1`` (``np.bincount``; one group: all)."""
    return np.array([len(idx)]) if n == 1 else np.bincount(idx, minlength=n)


def _times(w: np.ndarray, x: np.ndarray) -> np.ndarray:
    return w * x if x.ndim == 1 else w[:, None] * x
