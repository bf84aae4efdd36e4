"""The horizon grading: the first round's cut of the last radial panels toward a pole the
model knows lies just beyond the horizon (``integrate(horizon=...)``), from the K15/G7 pair's
own error estimate of that pole's term (no model evaluation).
"""

from __future__ import annotations

import numpy as np

from tuibrdf.core.sphere.integrator.rules import WG15, WK15, X15

#: Horizon grading (``integrate(horizon=...)``): in the first round, the last radial panel of
#: a node is cut graded toward ρmax where the model's pole beyond the horizon would leave it
#: an error estimate above HORIZON_SHARE·rtol of the node's inner integral, in an incidence
#: where these estimates' mean (weighted by the outer weights) is above HORIZON_GATE·rtol:
#: a half, then pieces of ratio 4, down to a last piece of about HORIZON_LAST times the
#: pole's distance (at most HORIZON_LEVELS cuts: END_LEVELS, the later rounds' graded cut in
#: :mod:`.adaptive`).
#: Measured on ggx α = 0.001…1 and gltf roughness 0.1…1 at θi = 60…89.99° (104 albedos):
#: 414,117 evaluations and 122 kernel calls, against 441,954 and 160 without, and 419,579
#: and 122 at (0.1, 0) (docs/reference/accuracy.md).
HORIZON_SHARE = 0.3
HORIZON_GATE = 0.15
HORIZON_LAST = 8.0
HORIZON_LEVELS = 3


_HALF_1MX = 0.5 * (1.0 - X15)  # t of the K15 nodes on [0, 1], from the far end
_WK_WG = WK15 - WG15


def _ratio_or_0(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """a / b, 0 where b = 0 (an incidence with no outer node in this pass)."""
    return np.divide(a, b, out=np.zeros_like(a), where=b > 0.0)


def _pole_estimate(delta):
    """``|K15 − G7|`` of ``δ/(t + δ)`` over ``t ∈ [0, 1]`` (a pole δ beyond the end of the
    panel, relative to its width), for a float or an array of δ > 0."""
    d = np.asarray(delta, dtype=float)[..., None]
    # einsum, not @: no BLAS call (and no hand-off to its threads) in the quadrature
    return np.abs(np.einsum("...n,n->...", d / (_HALF_1MX + d), _WK_WG)) * 0.5


def _pole_estimate_1(delta: float) -> float:
    """:func:`_pole_estimate` of one δ, in plain floats (cheaper for one value)."""
    return abs(sum(w * delta / (t + delta) for t, w in _T_WKG)) * 0.5


_T_WKG = tuple(zip(_HALF_1MX.tolist(), _WK_WG.tolist(), strict=True))


def _horizon_cut(lo: np.ndarray, hi: np.ndarray, node: np.ndarray, end: np.ndarray,
                 rmax: np.ndarray, eps: np.ndarray, amp: float, rtol: float,
                 case: np.ndarray, wpsi: np.ndarray):
    """The first round's panels ``(lo, hi, node, end)`` with the last panel of some nodes cut
    graded toward ρmax, and a flag for the pieces of the graded half (never on K7).

    The model says (``integrate(horizon=...)``) that near the horizon its integrand, relative
    to the node's inner integral I, is ``amp·(smooth − eps/(d + eps))`` (d = ρmax − ρ): a
    pole ``eps`` beyond the horizon (``eps`` per node, inf: none).  This rule's own error
    estimate (|K15 − G7|) of that term on the panel ``[lo, ρmax]`` is computed here, from its
    15 values (no model evaluation).  Where it is above ``HORIZON_SHARE·rtol``, and the
    incidence's mean of them (weighted by ``wpsi``, the nodes' outer weights; ``case`` their
    incidences) above ``HORIZON_GATE·rtol``, the panel is cut at ``ρmax − w/2, ρmax − w/8,
    …`` (w its width), as the later rounds would cut it (:func:`.adaptive._divide`) one call
    later."""
    flag = np.zeros(len(lo), dtype=bool)
    emin = float(eps.min())
    if not (amp > 0.0 and emin < np.inf):  # no pole
        return lo, hi, node, end, flag
    last = np.flatnonzero(hi >= rmax[node])
    w = hi[last] - lo[last]  # > 0 (a panel)
    # quick exit (most incidences): the estimate is amp·w·B(eps/w), B(δ) = |K15 − G7| of
    # δ/((1 − x)/2 + δ) over 2, at most 2.9e-3 (near δ = 6e-3), decreasing beyond 1e-2
    # (rounding, ≤ 1e-13, beyond 2: tests/core/sphere/test_albedo.py): below amp·wmax·B(emin/wmax)
    wmax = float(w.max())
    if emin > 1e-2 * wmax and amp * wmax * _pole_estimate_1(emin / wmax) <= HORIZON_SHARE * rtol:
        return lo, hi, node, end, flag
    nl = node[last]
    # δ capped at 1e3 (B = 0 to rounding there; eps may be inf: no pole)
    est = (amp * w) * _pole_estimate(np.minimum(eps[nl] / w, 1e3))
    # per node, and per incidence: the estimates' mean weighted by the outer weights (the
    # refinement cuts only where the incidence's weighted total is over its allowance)
    wl = wpsi[nl] * est
    if np.all(case == case[0]):  # one incidence (a single albedo)
        mean_ok = np.full(len(nl), wl.sum() > HORIZON_GATE * rtol * wpsi.sum())
    else:
        nc = int(case.max()) + 1
        mean = _ratio_or_0(np.bincount(case[nl], weights=wl, minlength=nc),
                           np.bincount(case, weights=wpsi, minlength=nc))
        mean_ok = (mean > HORIZON_GATE * rtol)[case[nl]]
    on = (est > HORIZON_SHARE * rtol) & mean_ok
    if not on.any():
        return lo, hi, node, end, flag
    last, w = last[on], w[on]
    e, b = eps[node[last]], hi[last]
    # cuts: the last piece w/2·4^-(k-1) down to about HORIZON_LAST·eps (at least one cut)
    k = np.ceil(np.log(np.maximum(w / (2.0 * HORIZON_LAST * e), 1.0)) * (1.0 / np.log(4.0)))
    k = np.minimum(k + 1.0, HORIZON_LEVELS)
    # the panel becomes [lo, b − w/2]; pieces j = 1…k are [b − w/2·4^-(j-1), b − w/2·4^-j],
    # the last one ending at b exactly
    cuts = b[:, None] - w[:, None] * _CUT_AT  # (p, HORIZON_LEVELS): b − w/2, b − w/8, …
    ends = np.where(_CUT_J < k[:, None], cuts, b[:, None])
    more = _CUT_J < k[:, None]  # piece j + 1 exists
    hi, end = hi.copy(), end.copy()
    hi[last] = cuts[:, 0]
    end[last] = False
    starts = cuts[more]
    stops = np.concatenate([ends[:, 1:], b[:, None]], axis=1)[more]
    count = more.sum(axis=1)
    owner = np.repeat(node[last], count)
    at_end = stops == np.repeat(b, count)
    return (np.concatenate([lo, starts]), np.concatenate([hi, stops]),
            np.concatenate([node, owner]), np.concatenate([end, at_end]),
            np.concatenate([flag, np.ones(len(starts), dtype=bool)]))


#: ``w·_CUT_AT[j]`` from the end: the horizon grading's cuts (a half, then ratio 4)
_CUT_AT = 0.5 * 0.25 ** np.arange(HORIZON_LEVELS)
_CUT_J = np.arange(HORIZON_LEVELS)
