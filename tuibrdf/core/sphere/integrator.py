"""Directional albedo by nested adaptive Gauss–Kronrod in polar coordinates about the lobe.

``a(wi) = ∫ f(wi, wo) cos θo dωo`` over the upper hemisphere, written in polar coordinates
``(ρ, ψ)`` about an axis chosen so that the model's lobe sits at ``ρ = 0`` and the horizon is a
curve ``ρ = ρmax(ψ)`` known in closed form (so no cell straddles it)::

    a = ∫ dψ ∫₀^ρmax(ψ) g(ρ, ψ) dρ,     g = f(wi, wo(ρ, ψ)) · cos θo · J(ρ, ψ)

Three frames (``wi = sin θi·u + cos θi·N``, ``u`` the horizontal unit vector toward the light,
``v = N × u``):

``normal``  wo about the normal N; ψ from −u (the mirror side).  ρmax = π/2, J = sin ρ.  For
            diffuse models: Oren-Nayar's kinks (θo = θi, Δφ = ±90°) are coordinate lines.
``mirror``  wo about the mirror direction S = −sin θi·u + cos θi·N, ψ from
            e1 = −(cos θi·u + sin θi·N) (beyond the mirror, toward the horizon).  With
            γ = atan2(sin θi cos ψ, cos θi) and R = hypot(sin θi cos ψ, cos θi):
            cos θo = cos θi cos ρ − sin θi cos ψ sin ρ = R cos(ρ + γ), so
            ρmax = π/2 − γ and cos θo = R sin(ρmax − ρ).  J = sin ρ.  For Phong's lobe.
``half``    the half vector h about N, ψ from u; wo = 2(wi·h)h − wi and dωo = 4 (wi·h) dωh
            (Walter et al. 2007, eq. 14).  With β = atan2(sin θi cos ψ, cos θi) and R as
            above: wi·h = R cos(ρ − β), cos θo = 2(wi·h) cos ρ − cos θi = R cos(2ρ − β), so
            ρmax = (π/2 + β)/2 and cos θo = R sin(2(ρmax − ρ)).  J = 4 (wi·h) sin ρ.  A
            microfacet lobe D(h) sits at the pole, round and of width ~α, whatever θi.
            At grazing incidence the horizon passes (π/2 − θi)/2 from the normal; when that
            is within ``TILT_WITHIN`` lobe widths (off by default) the axis A may be tilted
            onto it (A = cos t N − sin t u, E1 = sin t N + cos t u): then
            wi·h = a0 cos ρ + a1 sin ρ and
            cos θo = 2(wi·h)(N·h) − cos θi = P cos²ρ + Q sin ρ cos ρ + S sin²ρ
                   = (P+S)/2 + (K/2) cos(2ρ − φ0),
            so ρmax solves cos(2ρ − φ0) = −(P+S)/K and
            cos θo = K sin(ρmax + ρ − φ0) sin(ρmax − ρ) (t = 0 gives the formulas above).

The distance to the horizon ``d = ρmax − ρ`` is carried separately (from the panel's end), so
``cos θo`` stays accurate to the last bit near the horizon.

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
  ``HORIZON_SHARE·rtol`` cut that way in the first round (:func:`_horizon_cut`), one kernel
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
#: inner rule of panels narrower than :data:`SMALL_PANEL` lobe widths.
X7, WK7, WG7 = _kronrod7()
for _a in (X7, WK7, WG7):
    _a.setflags(write=False)
#: Inner panels narrower than this many lobe widths (nearly polynomial there) use K7 for K15,
#: when at least SMALL_MIN_COUNT of them start in one pass (8 evaluations saved per panel).
SMALL_PANEL = 0.5
SMALL_MIN_COUNT = 48
#: ``1 − x`` of the K15 and K7 nodes (by node count): the nodes' distance from the panel's end
_ONE_MINUS = {15: 1.0 - X15, 7: 1.0 - X7}
for _a in _ONE_MINUS.values():
    _a.setflags(write=False)
_TINY = np.finfo(float).tiny

FRAMES = ("normal", "mirror", "half")
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
#: Smallest panel (radians) the inner or outer refinement will bisect: below this the nodes
#: would differ by a few ulps of π.
MIN_WIDTH = 1e-12
#: Fraction of the tolerance given to the inner integrals (the rest is for the outer one).
INNER_SHARE = 0.7
#: Largest batch of directions handed to a kernel at once (bounds the temporaries' memory).
CHUNK = 1 << 15


@dataclass(frozen=True)
class Cases:
    """The incidences of one batch: ``sin θi``, ``cos θi`` and the horizontal unit vectors
    ``u`` (toward the light) and ``v = N × u``, each ``(c,)`` or ``(c, 3)``."""

    st: np.ndarray
    ct: np.ndarray
    u: np.ndarray
    v: np.ndarray
    #: half frame: the polar axis is tilted by this angle away from the light (0: the normal)
    tilt: np.ndarray | None = None

    #: every ``u = (1, 0, 0)`` and ``v = (0, 1, 0)`` (φi = 0; set by :func:`integrate` for
    #: an isotropic model)
    canonical: bool = False

    @property
    def wi(self) -> np.ndarray:
        return self.st[:, None] * self.u + self.ct[:, None] * np.array([0.0, 0.0, 1.0])


def cases(st: np.ndarray, ct: np.ndarray, sp: np.ndarray, cp: np.ndarray) -> Cases:
    """Incidences from ``sin/cos θi`` and ``sin/cos φi`` (exact components at multiples of 90°
    come from :func:`tuibrdf.core.directions.sincos_deg`)."""
    st, ct, sp, cp = (np.atleast_1d(np.asarray(a, dtype=float)) for a in (st, ct, sp, cp))
    u, v = np.zeros((len(st), 3)), np.zeros((len(st), 3))
    u[:, 0], u[:, 1] = cp, sp
    v[:, 0], v[:, 1] = -sp, cp
    return Cases(st, ct, u, v)


def _rho_max(frame: str, c: Cases, case: np.ndarray, cpsi: np.ndarray):
    """``(ρmax, params)`` per outer node (``case`` its incidence, ``cpsi`` = cos ψ); ``params``
    are what :func:`directions` needs.  Normal and mirror frames: ``(R, R·sin γ)`` with
    ``R cos γ = cos θi``.  Half frame: ``(a0, a1, K, φ0)`` (module docstring)."""
    st, ct = c.st[case], c.ct[case]
    n = len(case)
    if frame == "normal":
        return np.full(n, np.pi / 2), (np.ones(n), np.zeros(n))
    if frame == "mirror":
        rs = st * cpsi
        return np.pi / 2 - np.arctan2(rs, ct), (np.hypot(rs, ct), rs)
    if c.tilt is None:
        # the axis is the normal (t = 0 below: c0 = 1, s0 = 0): the same values, bit for bit,
        # without the products by 1 and 0 — a0 = cos θi, Q = 2·a1, P = cos θi = −S, so
        # P − S = 2 cos θi, P + S = 0 and acos(−(P+S)/K) = π/2
        a1 = cpsi * st
        q = 2.0 * a1
        two_ct = ct + ct
        phi0 = np.arctan2(q, two_ct)
        return np.maximum(0.5 * (phi0 + np.pi / 2), 0.0), (ct, a1, np.hypot(two_ct, q), phi0)
    t = c.tilt[case]
    c0, s0 = np.cos(t), np.sin(t)
    a0 = ct * c0 - st * s0  # wi·A = cos(θi + t)
    a1 = cpsi * (st * c0 + ct * s0)  # wi·(cos ψ E1 + sin ψ E2)
    n1 = cpsi * s0
    # cos θo = 2(wi·h)(N·h) − cos θi = P cos²ρ + Q sinρ cosρ + S sin²ρ
    p = np.where(t > 0.0, 0.0, 2.0 * a0 * c0 - ct)  # a tilted axis lies on the horizon: 0
    q = 2.0 * (a0 * n1 + a1 * c0)
    s = 2.0 * a1 * n1 - ct
    k = np.hypot(p - s, q)
    phi0 = np.arctan2(q, p - s)
    # cos θo = (P+S)/2 + (K/2) cos(2ρ − φ0) first falls through 0 at 2ρ − φ0 = acos(−(P+S)/K)
    ok = k > 0.0
    cosg = np.clip(np.divide(-(p + s), k, out=np.zeros(n), where=ok), -1.0, 1.0)
    # φ0 + γ ≥ 0 in exact arithmetic (untilted: φ0 = β ∈ [−π/2, π/2], γ = π/2; tilted, P = 0:
    # γ = |φ0|, so 0 outward and 2φ0 inward); rounding may give −1e-17.  K = 0 only when
    # cos θi = 0 = P (then ρmax = 0: the node has no domain)
    rmax = np.maximum(0.5 * (phi0 + np.arccos(cosg)), 0.0)
    return rmax, (a0, a1, k, phi0)


def directions(frame: str, c: Cases, case: np.ndarray, cpsi: np.ndarray, spsi: np.ndarray,
               params: tuple, rmax: np.ndarray, rho: np.ndarray, d: np.ndarray):
    """``(wo (p, n, 3), weight (p, n))`` at polar points ``rho (p, n)`` of panels whose outer
    node has incidence ``case (p,)``, ``cos ψ``, ``sin ψ``, :func:`_rho_max`'s ``params`` and
    ``rmax`` ``(p,)``; ``d = ρmax − ρ`` (accurate near the horizon).  weight = cos θo · J
    (module docstring).  wo is built from its components ``(x, y)`` along ``u`` and ``v``;
    when every incidence has ``u = (1, 0, 0)``, ``v = (0, 1, 0)`` (φi = 0, which
    :func:`integrate` uses for an isotropic model) they are wo's own."""
    st = c.st[case][:, None]
    cp, sp = cpsi[:, None], spsi[:, None]
    sr = np.sin(rho)
    if frame == "normal":
        x, y = -cp * sr, sp * sr
        cz = np.sin(d)  # cos θo = sin(π/2 − ρ), exact to the last bit near the horizon
        w = cz * sr
    elif frame == "mirror":
        r, _ = params
        cr = np.cos(rho)
        # S = −sin θi u + cos θi N,  e1 = −(cos θi u + sin θi N)
        x = -(st * cr + (c.ct[case][:, None] * cp) * sr)
        y = sp * sr
        cz = r[:, None] * np.sin(d)
        w = cz * sr
    elif c.tilt is None or not np.any(c.tilt[case]):
        a0, a1, k, _ = params
        cr = np.cos(rho)
        # h = cos ρ N + sin ρ (cos ψ u + sin ψ v); wo = 2(wi·h)h − wi
        two_s = 2.0 * (a0[:, None] * cr + a1[:, None] * sr) * sr  # 2(wi·h) sin ρ ≥ 0
        x, y = two_s * cp - st, two_s * sp
        # cos θo = R cos(2ρ − β) = R sin(2(ρmax − ρ)), K = 2R (module docstring)
        cz = (0.5 * k)[:, None] * np.sin(2.0 * d)
        w = cz * 2.0 * two_s
    else:
        a0, a1, k, phi0 = params
        cr = np.cos(rho)
        t = c.tilt[case]
        c0, s0 = np.cos(t)[:, None], np.sin(t)[:, None]
        # h = cos ρ A + sin ρ (cos ψ E1 + sin ψ E2), A = cos t N − sin t u, E1 = sin t N + cos t u
        wih = a0[:, None] * cr + a1[:, None] * sr  # wi·h ≥ 0 on the domain
        x = 2.0 * wih * (-cr * s0 + sr * cp * c0) - st
        y = 2.0 * wih * sr * sp
        # cos θo = (K/2)(cos(2ρ − φ0) − cos(2ρmax − φ0)) = K sin(ρmax + ρ − φ0) sin(ρmax − ρ)
        cz = (np.maximum(k[:, None] * np.sin(rmax[:, None] + rho - phi0[:, None]), 0.0)
              * np.sin(d))
        w = cz * 4.0 * wih * sr
    wo = np.empty(rho.shape + (3,))
    if c.canonical:
        wo[..., 0] = x
        wo[..., 1] = y
    else:
        u, v = c.u[case], c.v[case]
        wo[..., 0] = x * u[:, None, 0] + y * v[:, None, 0]
        wo[..., 1] = x * u[:, None, 1] + y * v[:, None, 1]
    wo[..., 2] = cz
    return wo, w


@dataclass
class PolarResult:
    """Per incidence: ``value`` and ``error`` ``(c,)`` or ``(c, k)``; ``evaluations (c,)``."""

    value: np.ndarray
    error: np.ndarray
    evaluations: np.ndarray


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


class _Integrand:
    """``g = f·cos θo·J`` at the 15 points of panels, chunked, counting evaluations per
    incidence."""

    def __init__(self, f: Callable[[np.ndarray, np.ndarray], np.ndarray], frame: str, c: Cases):
        self.f, self.frame, self.c = f, frame, c
        self.wi = c.wi
        self.count = np.zeros(len(c.st), dtype=np.int64)

    def __call__(self, groups: list[tuple]) -> list[np.ndarray]:
        """Values ``(p, n)`` or ``(p, n, k)`` for each group of panels ``(case, cos ψ, sin ψ,
        params, ρmax, ρ (p, n), d (p, n))``.  The directions of all groups go to the model
        together, in batches of at most :data:`CHUNK` points (one call while they fit): the
        directions are made batch by batch, so memory stays bounded."""
        one = len(self.c.st) == 1
        # pieces (group, first panel, last panel) of at most CHUNK points, packed into batches
        pieces, batches, size = [], [[]], 0
        for gi, grp in enumerate(groups):
            n = grp[5].shape[1]
            step = max(CHUNK // n, 1)
            self.count += _count(grp[0], len(self.count)) * n
            for s0 in range(0, len(grp[5]), step):
                s1 = min(s0 + step, len(grp[5]))
                if size + (s1 - s0) * n > CHUNK and batches[-1]:
                    batches.append([])
                    size = 0
                batches[-1].append(len(pieces))
                pieces.append((gi, s0, s1))
                size += (s1 - s0) * n
        values: list = [None] * len(pieces)
        for batch in batches:
            wos, ws, wis = [], [], []
            for pi in batch:
                gi, s0, s1 = pieces[pi]
                case, cpsi, spsi, params, rmax, rho, d = groups[gi]
                sl = slice(s0, s1)
                wo, w = directions(self.frame, self.c, case[sl], cpsi[sl], spsi[sl],
                                   tuple(x[sl] for x in params), rmax[sl], rho[sl], d[sl])
                wos.append(wo.reshape(-1, 3))
                ws.append(w)
                if not one:
                    wis.append(np.repeat(self.wi[case[sl]], rho.shape[1], axis=0))
            wo = wos[0] if len(wos) == 1 else np.concatenate(wos)
            wi = np.broadcast_to(self.wi[0], wo.shape) if one else np.concatenate(wis)
            fv = np.asarray(self.f(wi, wo), dtype=float)
            at = 0
            for pi, w in zip(batch, ws, strict=True):
                v = fv[at:at + w.size].reshape(w.shape + fv.shape[1:])
                at += w.size
                values[pi] = v * (w if v.ndim == 2 else w[..., None])
        out = []
        for gi in range(len(groups)):
            mine = [values[pi] for pi, p in enumerate(pieces) if p[0] == gi]
            out.append(mine[0] if len(mine) == 1 else np.concatenate(mine))
        return out


#: Graded cuts toward a panel's end (horizon or break) in the inner refinement (_divide).
END_LEVELS = 3

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


#: Horizon grading (``integrate(horizon=...)``): in the first round, the last radial panel of
#: a node is cut graded toward ρmax where the model's pole beyond the horizon would leave it
#: an error estimate above HORIZON_SHARE·rtol of the node's inner integral, in an incidence
#: where these estimates' mean (weighted by the outer weights) is above HORIZON_GATE·rtol:
#: a half, then pieces of ratio 4, down to a last piece of about HORIZON_LAST times the
#: pole's distance (at most HORIZON_LEVELS cuts: END_LEVELS, the later rounds' graded cut).
#: Measured on ggx α = 0.001…1 and gltf roughness 0.1…1 at θi = 60…89.99° (104 albedos):
#: 414,117 evaluations and 122 kernel calls, against 441,954 and 160 without, and 419,579
#: and 122 at (0.1, 0) (scripts/bench_accuracy.py).
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
    …`` (w its width), as the later rounds would cut it (:func:`_divide`) one call later."""
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
    """``∫ f(wi, wo) cos θo dωo`` for every incidence of ``c`` (see the module docstring).

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
