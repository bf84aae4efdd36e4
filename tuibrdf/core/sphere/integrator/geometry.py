"""Polar coordinates about the lobe: the incidences of a batch (:class:`Cases`), the horizon
``ρmax(ψ)`` and the directions and weights at polar points, and the integrand
``g = f·cos θo·J`` at the nodes of panels, evaluated in bounded batches.

The integral (:mod:`tuibrdf.core.sphere.integrator`)::

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
            is within ``TILT_WITHIN`` lobe widths (:mod:`.adaptive`; off by default) the axis
            A may be tilted onto it (A = cos t N − sin t u, E1 = sin t N + cos t u): then
            wi·h = a0 cos ρ + a1 sin ρ and
            cos θo = 2(wi·h)(N·h) − cos θi = P cos²ρ + Q sin ρ cos ρ + S sin²ρ
                   = (P+S)/2 + (K/2) cos(2ρ − φ0),
            so ρmax solves cos(2ρ − φ0) = −(P+S)/K and
            cos θo = K sin(ρmax + ρ − φ0) sin(ρmax − ρ) (t = 0 gives the formulas above).

The distance to the horizon ``d = ρmax − ρ`` is carried separately (from the panel's end), so
``cos θo`` stays accurate to the last bit near the horizon.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from tuibrdf.core.sphere.integrator.rules import _count

#: the polar axes (the module docstring)
FRAMES = ("normal", "mirror", "half")
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

    #: every ``u = (1, 0, 0)`` and ``v = (0, 1, 0)`` (φi = 0; set by
    #: :func:`.adaptive.integrate` for an isotropic model)
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
    :func:`.adaptive.integrate` uses for an isotropic model) they are wo's own."""
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
