"""The adaptive driver: :func:`integrate`, nested adaptive Gauss–Kronrod over ψ and ρ.

Rule: the outer integral over ψ and, for every outer node ψⱼ, the inner integral over ρ are
both adaptive Gauss–Kronrod (7, 15) (the QUADPACK QK15 pair: Piessens et al. 1983).  Each
panel's error estimate is ``|K15 − G7|`` (the 7 Gauss nodes are among the 15 Kronrod ones, so
it is free); a panel is cut while its error is above its share of the tolerance.  The
inner integral starts from panels graded geometrically (ratio 4) from the lobe width ``scale``
out to ρmax, so a lobe at the axis cannot fall between nodes, with the model's known kinks
(``radial_breaks``) as panel ends; the outer one from ψ = 0, ±π/2, ±π, the model's
``azimuth_breaks`` (where kink curves cross) and, at grazing incidence, a grading toward
ψ = ±π/2.  Refinement:

- an inner panel that ends at the horizon or at a radial break is cut graded toward that end
  (``END_LEVELS`` pieces of ratio 4 after a half): at grazing incidence the integrand is nearly
  singular just beyond such ends (a pole at a distance ~cos θi: GGX's Λ(θo), Oren-Nayar's
  tan((θi + θo)/2)), and halving reached it one round (one kernel call) per halving;
- a model that knows where its integrand has a pole just beyond the horizon (``horizon``: the
  Smith GGX masking at grazing incidence, a step of width ~cos θi at the horizon) has the last
  radial panel of the nodes where this rule's own estimate of that pole's term would exceed
  ``HORIZON_SHARE·rtol`` cut that way in the first round (:mod:`.horizon_cut`), one kernel
  call before the refinement would;
- inner panels that start narrower than ``SMALL_PANEL`` lobe widths (the far side at grazing
  incidence, gaps between close kinks) use the K7/G3 pair: 7 evaluations for 15;
- a model may add radial panel ends that are not kinks (``rings``: e.g. where its lobe's
  envelope ends) and ask for K7/G3 on outer panels narrower than ``outer_k7`` (where its
  inner integral is smooth in ψ: no kink curves meet next to ψ = ±π/2);
- the inner errors enter the albedo's error weighted by the outer weights, so an incidence's
  allowance is shared among its nodes by weight (nodes of tiny weight may be coarser);
- the tolerance holds per channel for RGB models.

All panels of a round, inner or outer, of every incidence go to the model in one call.  The
reported error is the sum of the outer ``|K15 − G7|`` and the inner errors integrated over
ψ: for analytic panels the Kronrod value is far more accurate than that estimate, so the
estimate is pessimistic (an upper bound in practice, measured in docs/reference/accuracy.md).

Several incidences are integrated in one batch (one kernel call per refinement round for the
whole albedo curve); evaluations are capped (``max_evals`` per incidence) so that a
discontinuous integrand (measured data, nearest-bin lookup) costs bounded time and memory and
returns an honest, larger error.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from tuibrdf.core.sphere.integrator.geometry import FRAMES, Cases, _Integrand, _rho_max
from tuibrdf.core.sphere.integrator.horizon_cut import _horizon_cut
from tuibrdf.core.sphere.integrator.rules import (
    _ONE_MINUS,
    WG7,
    WG15,
    WK7,
    WK15,
    X7,
    X15,
    _count,
    _grow,
    _ratio,
    _rule,
    _sum_by,
    _times,
)

#: Ratio of the geometric radial grading from the lobe width out to the horizon.
GRADING = 4.0
#: The first radial panel is [0, FIRST_PANEL × lobe width].
FIRST_PANEL = 1.0
#: Half frame: tilt the axis onto the horizon when it is within this many lobe widths.  Off:
#: measured at 89.9° it saved up to 65 % of the evaluations (gltf) but converged to 7e-7 where
#: the normal axis gives 1e-9 for the same tolerance (ggx and gltf defaults).
TILT_WITHIN = 0.0
#: Outer grading toward ψ = ±π/2 at grazing incidence: from OUTER_START·cot θi by
#: OUTER_GRADING up to OUTER_LIMIT (measured: ~25 % fewer evaluations than ratio 4 to π/4).
OUTER_START, OUTER_GRADING, OUTER_LIMIT = 2.0, 8.0, np.pi / 8
#: Smallest panel (radians) the inner or outer refinement will bisect: below this the nodes
#: would differ by a few ulps of π.
MIN_WIDTH = 1e-12
#: Fraction of the tolerance given to the inner integrals (the rest is for the outer one).
INNER_SHARE = 0.7
#: Inner panels narrower than this many lobe widths (nearly polynomial there) use K7 for K15,
#: when at least SMALL_MIN_COUNT of them start in one pass (8 evaluations saved per panel).
SMALL_PANEL = 0.5
SMALL_MIN_COUNT = 48
_TINY = np.finfo(float).tiny


def outer_grading(st: float, ct: float) -> list[float]:
    """The distances ``w`` from ψ = ±π/2 of the outer grading at grazing incidence (0 < cos θi
    < ½ sin θi): OUTER_START·cot θi, times OUTER_GRADING, while below OUTER_LIMIT; empty
    otherwise (the models' hints place their azimuths against it)."""
    out: list[float] = []
    if 0.0 < ct < 0.5 * st:
        w = OUTER_START * ct / st
        while w < OUTER_LIMIT:
            out.append(w)
            w *= OUTER_GRADING
    return out


def radial_grading(scale: float, top: float) -> list[float]:
    """The radial panel ends of the grading: ``scale``·FIRST_PANEL, times GRADING, while
    below ``top``."""
    out: list[float] = []
    g = scale * FIRST_PANEL
    while g < top:
        out.append(g)
        g *= GRADING
    return out


@dataclass
class PolarResult:
    """Per incidence: ``value`` and ``error`` ``(c,)`` or ``(c, k)``; ``evaluations (c,)``."""

    value: np.ndarray
    error: np.ndarray
    evaluations: np.ndarray


#: Graded cuts toward a panel's end (horizon or break) in the inner refinement (_divide).
END_LEVELS = 3
#: The error estimate of a panel that ends at the horizon or at a radial break (``end``) is
#: ``END_SAFETY·|K15 − G7|``: beyond such an end the integrand may have a pole (GGX's Λ at
#: grazing incidence, at a distance δ ~ cos θi), and for δ/(t + δ) on [0, 1] the Kronrod
#: value's own error is 1.3 |K15 − G7| at δ = 1e-4 (0.33 at 1e-3, < 0.003 above 1e-2).
#: Without it the estimate fell below the true error (1.34×: ggx α 0.0071, f0 1 at 89.99°).
END_SAFETY = 4.0

#: A panel whose error is this many times its share is cut in four rather than two: fewer
#: refinement rounds (each a kernel call with its fixed cost) for a few more evaluations.
QUARTER_ABOVE = 1e3


def _divide(lo: np.ndarray, hi: np.ndarray, owner: np.ndarray, excess: np.ndarray,
            end: np.ndarray | None = None, small: np.ndarray | None = None):
    """Children ``(lo, hi, owner, end)`` of panels ``[lo, hi]``: halves, or quarters where
    ``excess`` (error over its share) is above :data:`QUARTER_ABOVE`; a panel flagged ``end``
    (it ends at the horizon or at a radial break, where a nearly singular integrand sits at
    grazing incidence) is cut graded toward that end instead, :data:`END_LEVELS` pieces of
    ratio 4 after a half (only its last child keeps the flag).  ``small`` (the K7 rule) is
    inherited; returned only when given."""
    if end is None or END_LEVELS < 1:  # END_LEVELS = 0: no graded cuts (for comparison)
        end = np.zeros(len(lo), dtype=bool)
    parts = np.where(end, END_LEVELS + 1, np.where(excess > QUARTER_ABOVE, 4, 2))
    k = np.repeat(parts, parts)
    j = np.arange(len(k)) - np.repeat(np.cumsum(parts) - parts, parts)
    a, b = np.repeat(lo, parts), np.repeat(hi, parts)
    w = b - a
    graded = np.repeat(end, parts)
    # graded: ends at b − w/2, b − w/8, b − w/32, ...; else uniform
    off = 0.5 * 0.25 ** np.minimum(j, k - 1)
    right = np.where(graded, b - w * off, a + (j + 1) * (w / k))
    left = np.where(j == 0, a, np.where(graded, b - w * 0.5 * 0.25 ** np.maximum(j - 1, 0),
                                        a + j * (w / k)))
    # the last child ends exactly at hi (no rounding gap before ρmax)
    last = j == k - 1
    out = left, np.where(last, b, right), np.repeat(owner, parts), graded & last
    return out if small is None else (*out, np.repeat(small, parts))


def _initial_panels(vals: np.ndarray, brk: np.ndarray | None, rmax: np.ndarray):
    """Panels ``(lo, hi, node, end)`` from breakpoints ``vals (m, n)`` (or ``(m, 1)``: the same
    for every node), increasing down each node's column, flagged ``brk (m, n)`` (a radial
    break; None: none), cut at ρmax; ``end``: the panel ends at a break or at ρmax.  Level by
    level, node by node within a level (the order of the sums over panels)."""
    m, n = len(vals), len(rmax)
    e = np.empty((m + 2, n))
    e[0] = 0.0
    np.minimum(vals, rmax, out=e[1:-1])
    e[-1] = rmax
    # the end of the last panel before each breakpoint (0 before the first): a breakpoint
    # that does not pass it (one at or beyond ρmax, or a repeat) makes no panel
    prev = np.maximum.accumulate(e[:-1], axis=0)
    e = e[1:]
    keep = e > prev
    end = e >= rmax
    end[-1] = True
    if brk is not None:
        end[:-1] |= brk
    return prev[keep], e[keep], np.nonzero(keep)[1], end[keep]


def _inner(fn: _Integrand, case: np.ndarray, psi: np.ndarray, wpsi: np.ndarray,
           edges: Callable[..., list[np.ndarray]], tol: np.ndarray | None,
           rtol: float, atol: float, budget: np.ndarray, span: float = 2.0 * np.pi,
           small_width: float = 0.0, horizon: Callable[..., tuple] | None = None):
    """Inner integrals ``∫₀^ρmax g dρ`` for the outer nodes ``ψⱼ`` (incidence ``case[j]``,
    outer weight ``wpsi[j]``): ``(value, error, tol)``.

    ``tol (c,)`` or ``(c, k)`` is each incidence's absolute tolerance (per channel) for the
    whole albedo; these nodes' inner errors, weighted by ``wpsi``, may add up to
    ``INNER_SHARE·tol·Σwpsi/span`` (the outer weights of all nodes sum to ``span``: 2π, or π
    for a symmetric integrand).  When None (the first pass), it is set from the first
    round's own total.  ``budget (c,)`` evaluations left per incidence, decremented here; a
    spent incidence is not refined further.  Every panel stays in the pool with its value and
    error (K15/G7, or K7/G3 for panels narrower than ``small_width``); each round cuts
    (:func:`_divide`), per incidence still above its allowance, the panels whose weighted
    error is above the allowance divided by its number of panels (at least the worst one).
    ``horizon``: :func:`integrate`'s, for :func:`_horizon_cut`."""
    n, ncase = len(case), len(budget)
    cpsi, spsi = np.cos(psi), np.sin(psi)
    rmax, params = _rho_max(fn.frame, fn.c, case, cpsi)
    new_lo, new_hi, new_node, new_end = _initial_panels(*edges(case, cpsi, rmax), rmax)
    if len(new_lo) == 0:  # every node has ρmax = 0 (the far side at θi = 90°)
        return np.zeros(n), np.zeros(n), tol if tol is not None else np.full(ncase, atol)
    graded = np.zeros(len(new_lo), dtype=bool)
    if horizon is not None:
        eps, amp = horizon(fn.c.st[case], fn.c.ct[case], cpsi, rmax)
        new_lo, new_hi, new_node, new_end, graded = _horizon_cut(
            new_lo, new_hi, new_node, new_end, rmax, eps, amp, rtol, case, wpsi)
    # panels that start narrower than small_width (and their children) use K7, when there
    # are enough of them to pay for a second group (its directions and rule: ~0.1 ms); not
    # the pieces next to the horizon of a horizon grading (narrow because the integrand is
    # not polynomial there)
    new_small = (new_hi - new_lo < small_width) & ~graded
    if np.count_nonzero(new_small) < SMALL_MIN_COUNT:
        new_small[:] = False
    lo = hi = node = end = small = k_all = e_all = allow = None
    while len(new_lo):
        mid, half = 0.5 * (new_lo + new_hi), 0.5 * (new_hi - new_lo)
        k15, k7 = (X15, WK15, WG15), (X7, WK7, WG7)
        if not new_small.any():
            parts = [(slice(None), k15)]
        elif new_small.all():
            parts = [(slice(None), k7)]
        else:
            parts = [(~new_small, k15), (new_small, k7)]
        groups = []
        for sel, (x, _, _) in parts:
            h, j = half[sel][:, None], new_node[sel]
            cj, rj = case[j], rmax[j]
            rho = mid[sel][:, None] + h * x
            # distance to the horizon from the panel's end: exact in the last panel
            d = (rj - new_hi[sel])[:, None] + h * _ONE_MINUS[len(x)]
            groups.append((cj, cpsi[j], spsi[j], tuple(p[j] for p in params), rj, rho, d))
            budget -= len(x) * _count(cj, ncase)
        values = fn(groups)
        if len(parts) == 1:
            k, e = _rule(values[0], half, *parts[0][1][1:])
        else:
            k, e = (np.empty((len(new_lo),) + values[0].shape[2:]) for _ in range(2))
            for g, (sel, (_, wk, wg)) in zip(values, parts, strict=True):
                k[sel], e[sel] = _rule(g, half[sel], wk, wg)
        if END_SAFETY != 1.0 and new_end.any():
            # a panel against the horizon or a kink: its |K − G| may miss a pole just beyond
            e = e.copy()
            e[new_end] *= END_SAFETY
        lo, hi, node, end, small, k_all, e_all = _grow(
            (lo, hi, node, end, small, k_all, e_all),
            (new_lo, new_hi, new_node, new_end, new_small, k, e))
        if tol is None:
            tot_v = _sum_by(node, k_all, n)
            tol = rtol * np.abs(_sum_by(case, _times(wpsi, tot_v), ncase)) + atol
        pcase = case[node]
        if allow is None:  # tol is fixed from here on: the same allowance every round
            # the inner errors enter the albedo's error weighted by the outer weights: these
            # nodes may add INNER_SHARE·tol in proportion to their share of the outer span,
            # shared among the incidence's panels (nodes of tiny weight, as near ψ = ±π/2 at
            # grazing incidence, may be coarser than heavy ones)
            # > 0: an incidence with no node here has no panel either (its allowance is unused)
            allow = np.maximum(_times(INNER_SHARE * _sum_by(case, wpsi, ncase) / span, tol),
                               _TINY)
        we = _times(wpsi[node], e_all)
        # incidences above their allowance with evaluations left (none: done)
        over = (_ratio(_sum_by(pcase, we, ncase), allow) > 1.0) & (budget > 0)
        if not over.any():
            break
        npan = _count(pcase, ncase).clip(1)
        excess = _ratio(we, _times(1.0 / npan, allow)[pcase])
        split = over[pcase] & (excess > 1.0) & (hi - lo > 2 * MIN_WIDTH)
        if not split.any():
            break
        new_lo, new_hi, new_node, new_end, new_small = _divide(
            lo[split], hi[split], node[split], excess[split], end[split], small[split])
        keep = ~split
        lo, hi, node, end, small = lo[keep], hi[keep], node[keep], end[keep], small[keep]
        k_all, e_all = k_all[keep], e_all[keep]
    return _sum_by(node, k_all, n), _sum_by(node, e_all, n), tol


def _outer_breaks(frame: str, c: Cases, symmetric: bool,
                  azimuth_breaks: Callable[[float, float], list[float]] | None = None):
    """Initial ψ panels ``(lo, hi, case)``: breakpoints at 0, ±π/2, ±π, ``±azimuth_breaks(sin
    θi, cos θi)`` (ψ in [0, π]), and at grazing incidence (half and mirror frames) a geometric
    grading toward ±π/2, where ρmax(ψ) turns over within ~cot θi.  ``symmetric``: only
    ψ ∈ [0, π]."""
    plo, phi_, pcase = [], [], []
    for i in range(len(c.st)):
        br = {-np.pi, -np.pi / 2, 0.0, np.pi / 2, np.pi}
        st, ct = float(c.st[i]), float(c.ct[i])
        tilted = c.tilt is not None and c.tilt[i] > 0.0
        if azimuth_breaks is not None:
            br.update(x for a in azimuth_breaks(st, ct) if 0.0 < a < np.pi for x in (a, -a))
        if frame != "normal" and not tilted:
            for w in outer_grading(st, ct):
                br.update((-np.pi / 2 - w, -np.pi / 2 + w, np.pi / 2 - w, np.pi / 2 + w))
        e = np.array(sorted(x for x in br if x >= 0.0 or not symmetric))
        plo.append(e[:-1])
        phi_.append(e[1:])
        pcase.append(np.full(len(e) - 1, i))
    return np.concatenate(plo), np.concatenate(phi_), np.concatenate(pcase)


def integrate(f: Callable[[np.ndarray, np.ndarray], np.ndarray], frame: str, c: Cases, *,
              scale: float, radial_breaks: Callable[..., list[np.ndarray]] | None = None,
              symmetric: bool = False, rtol: float = 1e-6, atol: float = 1e-13,
              max_evals: int = 400_000,
              azimuth_breaks: Callable[[float, float], list[float]] | None = None,
              horizon: Callable[..., tuple] | None = None,
              rings: tuple[float, ...] = (), outer_k7: float = 0.0) -> PolarResult:
    """``∫ f(wi, wo) cos θo dωo`` for every incidence of ``c`` (the frames: :mod:`.geometry`;
    the rule: the module docstring).

    ``f(wi (n, 3), wo (n, 3))`` returns ``(n,)`` or ``(n, k)``.  ``scale`` is the lobe's
    width about the frame's axis (radians; the radial grading starts there);
    ``radial_breaks(st, ct, cpsi, rmax)`` gives extra radial breakpoints (known kinks) for
    outer nodes (arrays ``(j,)`` each; values outside ``(0, ρmax)`` are ignored), or None.
    ``symmetric``: the integrand is even in ψ (an isotropic model: mirror symmetry about the
    plane of incidence); only ψ ∈ [0, π] is integrated, and doubled.
    ``horizon(st, ct, cpsi, rmax) → (eps, amp)`` per outer node, or None: the integrand has a
    pole ``eps`` (radians of ρ) beyond the horizon, of amplitude ``amp`` relative to the
    node's inner integral (:func:`_horizon_cut`): the first round grades toward it.
    ``rings``: extra radial panel ends (radians, at every outer node; not kinks).
    ``outer_k7``: outer panels narrower than this (radians) use the K7/G3 pair, for an
    integrand whose inner integral is smooth in ψ at that scale (no kink curves meeting there).
    Stops when the error estimate is ≤ ``rtol·|a| + atol`` or once ``max_evals`` evaluations
    per incidence are spent (then the error says how far it got)."""
    if frame not in FRAMES:
        raise ValueError(f"frame = {frame!r} is invalid: expected one of {', '.join(FRAMES)}")
    ncase = len(c.st)
    if frame == "half" and c.tilt is None and radial_breaks is None:
        # the horizon passes (π/2 − θi)/2 from the normal on the far side: when the lobe
        # reaches it, put the axis there (the horizon is then a smooth curve through the axis,
        # tangent to ψ = ±π/2, instead of a near-step of ρmax(ψ) at ψ = ±π/2)
        rho0 = 0.5 * np.arctan2(c.ct, c.st)
        tilt = np.where(rho0 < TILT_WITHIN * scale, rho0, 0.0)
        c = Cases(c.st, c.ct, c.u, c.v, tilt if np.any(tilt) else None)
    if c.tilt is not None and np.any(c.tilt):
        horizon = None  # its eps is measured in the untilted half frame
    if symmetric:
        # isotropic: f is unchanged by a rotation about N, so every incidence is turned to
        # φi = 0 (wo's components along u and v are then its x and y)
        u, v = np.zeros((ncase, 3)), np.zeros((ncase, 3))
        u[:, 0] = v[:, 1] = 1.0
        c = Cases(c.st, c.ct, u, v, c.tilt, canonical=True)
    fn = _Integrand(f, frame, c)
    budget = np.full(ncase, int(max_evals), dtype=np.int64)
    scale = float(min(max(scale, 1e-6), np.pi / 2))
    top = np.pi if frame == "mirror" else np.pi / 2
    grading = sorted(set(radial_grading(scale, top)).union(x for x in rings if 0.0 < x < top))

    grading_col = np.array(grading).reshape(-1, 1)

    def edges(case: np.ndarray, cpsi: np.ndarray, rmax: np.ndarray):
        """Breakpoints ``(m, n)`` of the nodes' radial panels, increasing down each column,
        and which are radial breaks (None: none)."""
        n = len(case)
        extra = [] if radial_breaks is None else list(
            radial_breaks(c.st[case], c.ct[case], cpsi, rmax))
        if not extra:
            return grading_col, None  # (m, 1): the same at every node
        extra = [np.where((x > 0.0) & (x < rmax), x, rmax) for x in extra]
        vals = np.empty((n, len(grading) + len(extra)))
        vals[:, :len(grading)] = grading
        for i, x in enumerate(extra, len(grading)):
            vals[:, i] = x
        brk = np.zeros(vals.shape, dtype=bool)
        brk[:, len(grading):] = True
        order = np.argsort(vals, axis=1, kind="stable")
        vals = np.take_along_axis(vals, order, axis=1)
        brk = np.take_along_axis(brk, order, axis=1)
        return vals.T, brk.T

    new_lo, new_hi, new_pc = _outer_breaks(frame, c, symmetric, azimuth_breaks)
    lo = hi = pc = k_all = e_all = tol = tot_v = tot_e = None
    while len(new_lo):
        mid, half = 0.5 * (new_lo + new_hi), 0.5 * (new_hi - new_lo)
        small = (new_hi - new_lo) < outer_k7
        if not small.any():
            psi = (mid[:, None] + half[:, None] * X15).ravel()
            case = np.repeat(new_pc, 15)
            wpsi = (half[:, None] * WK15).ravel()
            owner = np.repeat(np.arange(len(new_lo)), 15)
        else:  # the K15 panels' nodes, then the K7 ones'
            i15, i7 = np.flatnonzero(~small), np.flatnonzero(small)
            psi = np.concatenate([(mid[i15, None] + half[i15, None] * X15).ravel(),
                                  (mid[i7, None] + half[i7, None] * X7).ravel()])
            case = np.concatenate([np.repeat(new_pc[i15], 15), np.repeat(new_pc[i7], 7)])
            wpsi = np.concatenate([(half[i15, None] * WK15).ravel(),
                                   (half[i7, None] * WK7).ravel()])
            owner = np.concatenate([np.repeat(i15, 15), np.repeat(i7, 7)])
        iv, ie, tol = _inner(fn, case, psi, wpsi, edges, tol, rtol, atol, budget,
                             np.pi if symmetric else 2.0 * np.pi, SMALL_PANEL * scale,
                             horizon)
        if not small.any():
            k, e = _rule(iv.reshape(len(new_lo), 15, *iv.shape[1:]), half)
        else:
            n15 = 15 * len(i15)
            k = np.empty((len(new_lo),) + iv.shape[1:])
            e = np.empty_like(k)
            k[i15], e[i15] = _rule(iv[:n15].reshape(len(i15), 15, *iv.shape[1:]), half[i15])
            k[i7], e[i7] = _rule(iv[n15:].reshape(len(i7), 7, *iv.shape[1:]), half[i7], WK7,
                                 WG7)
        # the inner errors, integrated with the outer weights
        e = e + _sum_by(owner, _times(wpsi, ie), len(new_lo))
        lo, hi, pc, k_all, e_all = _grow((lo, hi, pc, k_all, e_all),
                                         (new_lo, new_hi, new_pc, k, e))
        tot_v, tot_e = _sum_by(pc, k_all, ncase), _sum_by(pc, e_all, ncase)
        tol = rtol * np.abs(tot_v) + atol
        # incidences above their tolerance with evaluations left (none: done)
        over = (_ratio(tot_e, tol) > 1.0) & (budget > 0)
        if not over.any():
            break
        npan = _count(pc, ncase).clip(1)
        excess = _ratio(e_all, _times(1.0 / npan, tol)[pc])
        split = over[pc] & (excess > 1.0) & (hi - lo > 2 * MIN_WIDTH)
        if not split.any():
            break
        new_lo, new_hi, new_pc, _ = _divide(lo[split], hi[split], pc[split], excess[split])
        keep = ~split
        lo, hi, pc, k_all, e_all = lo[keep], hi[keep], pc[keep], k_all[keep], e_all[keep]
        tot_v = tot_e = None
    if tot_v is None:  # the loop ended on an empty round (no final tally)
        tot_v, tot_e = _sum_by(pc, k_all, ncase), _sum_by(pc, e_all, ncase)
    k = 2.0 if symmetric else 1.0
    return PolarResult(k * tot_v, k * tot_e, fn.count)
