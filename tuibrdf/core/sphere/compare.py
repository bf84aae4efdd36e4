"""How far apart two BRDFs are, at each incidence: the numbers of ``tuibrdf compare`` and of
the viewer's status line in compare mode.

For each θi, with B the reference (the measured side, when one side is data):

- ``albedo_a``, ``albedo_b`` and their error estimates: each side's directional albedo by the
  package's adaptive rule (:func:`tuibrdf.core.sphere.albedo.albedo_rule`, each about its own
  lobe);
- ``rel_l2 = sqrt(∫ (fA − fB)² cos θo dωo / ∫ fB² cos θo dωo)``: both integrals by the same
  adaptive rule (:func:`tuibrdf.core.sphere.integrator.integrate`, in one batch), about the
  sharper of the two lobes (the two hints merged when they share a frame), with an error
  estimate from theirs (the largest the ratio can be within them, less the value);
- ``max_diff``: the largest ``|fA − fB|`` relative to B's peak value, signed (``fA − fB``
  positive: A above B), and its direction ``(θo, φo)``: a search on the function (a
  hemisphere grid, the mirror direction and each side's own grid maximum, then a local
  pattern search), so it does not depend on any picture's size.  (A difference relative to fB
  itself is unbounded where B's lobe has decayed and A's has not: a Beckmann lobe falls as
  ``exp(−tan²θh/m²)``, a Phong lobe only as ``cosⁿ``.)

RGB sides: the luminance (Rec.709, :func:`~tuibrdf.core.conventions.luminance`) gives the main
numbers, and ``channels`` holds the same numbers per R, G, B; a scalar side against an RGB one
is grey (the same value in each channel).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from tuibrdf.core.conventions import REC709
from tuibrdf.core.directions import check_phi_i, check_theta_i, incident, mirror, sincos_deg
from tuibrdf.core.evaluate import evaluate_resolved
from tuibrdf.core.params import Model
from tuibrdf.core.sphere import integrator
from tuibrdf.core.sphere.albedo import ATOL, DEFAULT_RTOL, MAX_EVALS, albedo_rule
from tuibrdf.core.sphere.lobes import Lobe, lobe
from tuibrdf.core.sphere.mesh import hemisphere

#: Relative tolerance of the two rel_l2 integrals (each): rel_l2 is then good to about
#: this much of itself, far finer than any use of it (a fit's verdict, a status line).
L2_RTOL = 1e-4
#: Hemisphere level of the max-difference search's grid (1,281 vertices at level 4).
SEARCH_LEVEL = 4
#: Rounds of the local pattern search about the grid's best point, and its first step
#: (radians: about a level-4 edge) and shrink factor per round.
SEARCH_ROUNDS, SEARCH_STEP, SEARCH_SHRINK = 6, 0.06, 3.0
CHANNELS = ("R", "G", "B")


@dataclass
class Numbers:
    """One incidence's numbers (scalars; luminance for RGB sides, with ``channels`` holding
    ``{"R": {...}, "G": ..., "B": ...}`` of the same keys but θi and the direction)."""

    theta_i: float
    albedo_a: float
    albedo_a_error: float
    albedo_b: float
    albedo_b_error: float
    rel_l2: float | None  # None: B is zero everywhere (no reference to be relative to)
    rel_l2_error: float | None
    max_diff: float | None  # (fA − fB)/max fB at its largest |·|; None: B is zero everywhere
    max_diff_theta_o: float
    max_diff_phi_o: float
    channels: dict[str, dict[str, float | None]] | None = field(default=None)
    #: which side rel_l2 and max_diff are relative to: "b", or "a" when A alone is measured
    reference: str = "b"

    def as_dict(self) -> dict[str, Any]:
        """JSON-ready (floats and None; no NaN or infinity)."""
        d = {k: getattr(self, k) for k in (
            "theta_i", "albedo_a", "albedo_a_error", "albedo_b", "albedo_b_error", "rel_l2",
            "rel_l2_error", "max_diff", "max_diff_theta_o", "max_diff_phi_o")}
        if self.channels is not None:
            d["channels"] = self.channels
        d["reference"] = self.reference
        return d


def reference_side(model_a: Model, model_b: Model) -> str:
    """``"a"`` when A is measured and B is not (the data is the reference), else ``"b"``."""
    return "a" if model_a.measured and not model_b.measured else "b"


def _columns(model: Model, values: Mapping[str, Any], wi, wo, rgb: bool) -> np.ndarray:
    """f at ``wo (n, 3)``: ``(n,)``, or ``(n, 4)`` = R, G, B, Y when ``rgb`` (a scalar side
    is grey)."""
    return _cols_many(model, values, np.broadcast_to(wi, wo.shape), wo, rgb)


def _merged(a: Lobe, b: Lobe) -> Lobe:
    """One hint for an integrand with both lobes: the sharper lobe's frame and width; when
    both use one frame, both sets of kinks, azimuths and rings."""
    sharp, other = (a, b) if a.scale <= b.scale else (b, a)
    if a.frame != b.frame:
        return Lobe(sharp.frame, sharp.scale, sharp.breaks, a.symmetric and b.symmetric,
                    sharp.max_evals, sharp.azimuths, sharp.horizon, sharp.rings)

    def breaks(*args):
        return [*(a.breaks(*args) if a.breaks else []), *(b.breaks(*args) if b.breaks else [])]

    def azimuths(st, ct):
        return sorted({*(a.azimuths(st, ct) if a.azimuths else []),
                       *(b.azimuths(st, ct) if b.azimuths else [])})

    evals = [m for m in (a.max_evals, b.max_evals) if m]
    return Lobe(sharp.frame, sharp.scale, breaks if (a.breaks or b.breaks) else None,
                a.symmetric and b.symmetric, min(evals) if evals else None,
                azimuths if (a.azimuths or b.azimuths) else None, sharp.horizon or other.horizon,
                tuple(sorted({*a.rings, *b.rings})))


def _ratio(num, num_err, den, den_err):
    """sqrt(num/den) and its error: the largest the ratio can be within the integrals' error
    estimates, less the value; (None, None) when den is not above its error (B is zero)."""
    num, num_err = max(float(num), 0.0), float(num_err)
    den, den_err = float(den), float(den_err)
    if not den > den_err:  # B ≈ 0: no reference
        return None, None
    r = float(np.sqrt(num / den))  # den > den_err ≥ 0
    hi = float(np.sqrt((num + num_err) / (den - den_err)))  # den − den_err > 0: tested above
    return r, hi - r


def _search(g, wi: np.ndarray) -> tuple[float, np.ndarray]:
    """The maximum of ``g(wo (n, 3)) → (n,)`` over the upper hemisphere and where: a grid, the
    mirror direction, then a pattern search in (θ, φ) about the best point."""
    cand = np.concatenate([hemisphere(SEARCH_LEVEL).vertices, [mirror(wi)]])
    v = g(cand)
    k = int(np.argmax(v))
    best, at = float(v[k]), cand[k]
    t = float(np.arccos(np.clip(at[2], -1.0, 1.0)))
    p = float(np.arctan2(at[1], at[0]))
    step = SEARCH_STEP
    offs = np.linspace(-1.0, 1.0, 5)
    for _ in range(SEARCH_ROUNDS):
        tt, pp = np.meshgrid(t + step * offs, p + step * offs)
        tt = np.clip(tt.ravel(), 0.0, np.pi / 2)
        pp = pp.ravel()
        w = np.stack([np.sin(tt) * np.cos(pp), np.sin(tt) * np.sin(pp), np.cos(tt)], axis=1)
        vals = g(w)
        j = int(np.argmax(vals))
        if vals[j] > best:
            best, at, t, p = float(vals[j]), w[j], float(tt[j]), float(pp[j])
        step /= SEARCH_SHRINK
    return best, at


def _angles(w: np.ndarray) -> tuple[float, float]:
    t = float(np.degrees(np.arccos(np.clip(w[2], -1.0, 1.0))))
    # rounded before the turn is taken: −1e-12° is 0°, not 360°
    p = round(float(np.degrees(np.arctan2(w[1], w[0]))), 6) % 360.0 if t > 0.0 else 0.0
    return round(t, 6), p


def _max_diff(ma, va, mb, vb, wi, rgb: bool, col: int | None, ref_is_a: bool = False):
    """(signed max difference relative to the reference's peak or None, θo, φo) for column
    ``col`` (the sign is always that of fA − fB)."""

    def pick(f):
        return f if col is None else f[:, col]

    def fb(wo):
        return pick(_columns(mb, vb, wi, wo, rgb))

    def absdiff(wo):
        return np.abs(pick(_columns(ma, va, wi, wo, rgb)) - fb(wo))

    def fa(wo):
        return pick(_columns(ma, va, wi, wo, rgb))

    peak_b, _ = _search(fa if ref_is_a else fb, wi)
    big, at = _search(absdiff, wi)
    at2 = at[None, :]
    signed = float(pick(_columns(ma, va, wi, at2, rgb))[0] - fb(at2)[0])
    theta, phi = _angles(at)
    if not peak_b > 0.0:  # B is zero everywhere: nothing to be relative to
        return None, theta, phi
    return signed / peak_b, theta, phi  # peak_b > 0: tested above


def largest_difference(model_a: Model, values_a: Mapping[str, Any], model_b: Model,
                       values_b: Mapping[str, Any], wi: np.ndarray, cosine: bool = False
                       ) -> tuple[float, float, float]:
    """``(max |fA − fB|, θo, φo)`` over the upper hemisphere for the light at ``wi``: the
    luminance of RGB sides, ``f·cos θo`` with ``cosine`` (the difference map's scale: a
    property of the two functions, not of any picture's pixels)."""
    rgb = bool(model_a.rgb or model_b.rgb)
    wi = np.asarray(wi, dtype=float)

    def g(wo):
        d = _columns(model_a, values_a, wi, wo, rgb) - _columns(model_b, values_b, wi, wo, rgb)
        d = np.abs(d[:, 3] if rgb else d)
        return d * np.maximum(wo[:, 2], 0.0) if cosine else d

    big, at = _search(g, wi)
    return (big, *_angles(at))


def compare(model_a: Model, values_a: Mapping[str, Any], model_b: Model,
            values_b: Mapping[str, Any], thetas_deg: Sequence[float],
            phi_i_deg: float = 180.0, *, rtol: float = L2_RTOL,
            max_evals: int = MAX_EVALS, reference: str = "b") -> list[Numbers]:
    """The numbers at each incidence (module docstring); values are resolved.  ``reference``
    ``"a"`` makes A the reference of rel_l2 and max_diff (:func:`reference_side`: the data
    when A is measured and B is not); max_diff's sign stays that of fA − fB."""
    if reference not in ("a", "b"):
        raise ValueError(f"reference = {reference!r}: expected 'a' or 'b'")
    ref_a = reference == "a"
    thetas = [check_theta_i(float(t)) for t in thetas_deg]
    phi = check_phi_i(phi_i_deg)
    rgb = bool(model_a.rgb or model_b.rgb)
    ea = albedo_rule(model_a, values_a, thetas, phi, rtol=DEFAULT_RTOL, max_evals=max_evals)
    eb = albedo_rule(model_b, values_b, thetas, phi, rtol=DEFAULT_RTOL, max_evals=max_evals)
    hint = _merged(lobe(model_a, values_a, rtol), lobe(model_b, values_b, rtol))

    s, c = sincos_deg(np.append(np.asarray(thetas, dtype=float), phi))
    n = len(thetas)
    r = integrator.integrate(
        lambda wi, wo: _pair(_cols_many(model_a, values_a, wi, wo, rgb),
                             _cols_many(model_b, values_b, wi, wo, rgb), ref_a),
        hint.frame, integrator.cases(s[:-1], c[:-1], np.full(n, s[-1]), np.full(n, c[-1])),
        scale=hint.scale, radial_breaks=hint.breaks, symmetric=hint.symmetric, rtol=rtol,
        atol=ATOL, max_evals=min(max_evals, hint.max_evals or max_evals),
        azimuth_breaks=hint.azimuths, horizon=hint.horizon, rings=hint.rings)
    out = []
    for i, t in enumerate(thetas):
        wi = incident(t, phi)
        val, err = np.asarray(r.value[i]), np.asarray(r.error[i])
        aa, ae = np.atleast_1d(ea.value[i]), np.atleast_1d(ea.error[i])
        ba, be = np.atleast_1d(eb.value[i]), np.atleast_1d(eb.error[i])
        if rgb:
            # albedos per channel (a scalar side: grey) and their luminance
            aa, ae = _with_y(aa), _with_y(ae)
            ba, be = _with_y(ba), _with_y(be)
            cols = [3, 0, 1, 2]  # Y first, then R, G, B
        else:
            cols = [0]
        rows = []
        for j in cols:
            rl, rle = _ratio(val[_k(j, rgb, 0)], err[_k(j, rgb, 0)],
                             val[_k(j, rgb, 1)], err[_k(j, rgb, 1)])
            md, mt, mp = _max_diff(model_a, values_a, model_b, values_b, wi, rgb,
                                   j if rgb else None, ref_a)
            rows.append({"albedo_a": float(aa[j]), "albedo_a_error": float(ae[j]),
                         "albedo_b": float(ba[j]), "albedo_b_error": float(be[j]),
                         "rel_l2": rl, "rel_l2_error": rle, "max_diff": md,
                         "max_diff_theta_o": mt, "max_diff_phi_o": mp})
        main = rows[0]
        channels = ({name: row for name, row in zip(CHANNELS, rows[1:], strict=True)}
                    if rgb else None)
        out.append(Numbers(theta_i=float(t), channels=channels, reference=reference, **main))
    return out


def _with_y(x: np.ndarray) -> np.ndarray:
    """R, G, B (or one grey value) → R, G, B, Y; an error's Y bounds the weighted sum."""
    x = np.repeat(x, 3) if x.size == 1 else x
    return np.append(x, x @ np.asarray(REC709))


def _k(col: int, rgb: bool, which: int) -> int:
    """Index of ∫(fA − fB)² (``which`` 0) or ∫fB² (1) of column ``col`` in the integrand."""
    ncol = 4 if rgb else 1
    return which * ncol + col


def _cols_many(model: Model, values, wi: np.ndarray, wo: np.ndarray, rgb: bool) -> np.ndarray:
    """:func:`_columns` for many ``(wi, wo)`` pairs (the integrator's call)."""
    f = np.asarray(evaluate_resolved(model, values, wi, wo), dtype=float)
    f = np.broadcast_to(f, wo.shape[:1]) if f.ndim == 0 else f
    if not rgb:
        return f
    if f.ndim == 1:
        f = np.repeat(f[:, None], 3, axis=1)
    return np.concatenate([f, (f @ np.asarray(REC709))[:, None]], axis=1)


def _pair(fa: np.ndarray, fb: np.ndarray, ref_a: bool = False) -> np.ndarray:
    """The integrand's columns: (fA − fB)², then f_ref² (each per channel when RGB)."""
    d = fa - fb
    fb = fa if ref_a else fb
    if fa.ndim == 1:
        return np.stack([d * d, fb * fb], axis=1)
    return np.concatenate([d * d, fb * fb], axis=1)
