"""The χ² test of a sampler against its own pdf (as Mitsuba's ``ChiSquareTest`` does it).

For an incidence ``wi``, ``N`` samples ``wo`` of the model's sampler
(:mod:`tuibrdf.core.brdf.sampling`) are counted in the pixels of the Lambert azimuthal
equal-area map of the hemisphere (the viewer's map, :mod:`tuibrdf.core.views.hemimap`): every
pixel covers the same solid angle, so ``counts / N`` estimate the pdf's integral over a pixel
with no Jacobian.  The expected count of a pixel is ``N ∫ pdf dω`` over it, integrated by a
``k × k`` midpoint rule in map coordinates (the map is equal-area: ``dω = du dv``); pixels the
horizon cuts count only their sub-points inside the disc.  One more cell holds the samples
the sampler failed to place (below the horizon, pdf 0, not finite), expected
``N (1 − ∫ pdf dω)`` over the hemisphere.

Cells expected to hold fewer than :data:`MIN_EXPECTED` samples are pooled into one (as
Mitsuba's test does), and Pearson's statistic ``Σ (observed − expected)² / expected`` is
compared with the χ² distribution of ``cells − 1`` degrees of freedom: the p-value is the
regularised upper incomplete gamma function ``Q(dof/2, χ²/2)`` (:func:`gamma_q`, written here:
no scipy at run time).  The test fails when p is below ``significance`` after Šidák's
correction for the number of incidences tested.

The sampler's own ``pdf`` return is compared with ``pdf(wi, wo)`` too (``pdf_mismatch``: the
largest relative difference over the samples).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from tuibrdf.core.directions import incident
from tuibrdf.core.numerics import kernel_errstate
from tuibrdf.core.params import Model

SQRT2 = math.sqrt(2.0)
#: Pixels across the map, samples, sub-points per pixel side, and the pooling threshold.
RES = 32
SAMPLES = 200_000
SUB = 6
MIN_EXPECTED = 5.0
#: sub-points per side in a pixel the horizon cuts, as a multiple of those in a whole one
EDGE_FACTOR = 8
SIGNIFICANCE = 0.01
#: incidences tested (θi in degrees, the light at φi = 180°)
THETAS = (30.0, 70.0)


# ---------------------------------------------------------------------------------------------
# the incomplete gamma function


def gamma_q(a: float, x: float) -> float:
    """Regularised upper incomplete gamma ``Q(a, x) = Γ(a, x) / Γ(a)``: the series of
    ``P = 1 − Q`` for ``x < a + 1``, else Lentz's continued fraction (Numerical Recipes §6.2;
    both converge to 1e-15 within a few hundred terms for the a and x of a χ² test)."""
    if a <= 0.0:
        raise ValueError(f"gamma_q: a = {a} must be > 0")
    if x <= 0.0:
        return 1.0
    log_pre = a * math.log(x) - x - math.lgamma(a)  # log of x^a e^{−x} / Γ(a)
    if x < a + 1.0:
        term = total = 1.0 / a
        ap = a
        for _ in range(10_000):
            ap += 1.0
            term *= x / ap
            total += term
            if abs(term) < abs(total) * 1e-16:
                break
        return max(0.0, 1.0 - total * math.exp(log_pre))
    tiny = 1e-300
    b = x + 1.0 - a
    c = 1.0 / tiny
    d = 1.0 / b
    h = d
    for i in range(1, 10_000):
        an = -i * (i - a)
        b += 2.0
        d = an * d + b
        d = tiny if abs(d) < tiny else d  # Lentz: keep the recurrence off 0
        c = b + an / c
        c = tiny if abs(c) < tiny else c
        d = 1.0 / d
        delta = d * c
        h *= delta
        if abs(delta - 1.0) < 1e-16:
            break
    return min(1.0, math.exp(log_pre) * h)


def chi2_sf(stat: float, dof: int) -> float:
    """P(χ²_dof ≥ stat)."""
    return gamma_q(dof / 2.0, stat / 2.0)


# ---------------------------------------------------------------------------------------------
# the map's cells


def _pixel_of(wo: np.ndarray, res: int) -> np.ndarray:
    """Flat pixel index of upper-hemisphere directions on the ``res × res`` map of
    ``[−√2, √2]²`` (u right, v up; row 0 at the top, as the viewer draws)."""
    k = np.sqrt(2.0 / (1.0 + wo[..., 2]))  # 1 + z ≥ 1 above the horizon
    u, v = wo[..., 0] * k, wo[..., 1] * k
    col = np.clip(np.floor((u + SQRT2) / (2 * SQRT2) * res), 0, res - 1).astype(int)
    row = np.clip(np.floor((SQRT2 - v) / (2 * SQRT2) * res), 0, res - 1).astype(int)
    return row * res + col


def _sub_points(res: int, sub: int, pixels: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Directions of the ``sub × sub`` midpoints of each pixel of ``pixels`` (flat indices;
    ``(n, sub², 3)``) and whether each lies inside the disc."""
    step = 2 * SQRT2 / res
    row, col = np.divmod(np.asarray(pixels), res)
    o = ((np.arange(sub) + 0.5) / sub - 0.5) * step
    uu = ((col + 0.5) * step - SQRT2)[:, None, None] + o[None, None, :]  # (n, 1, sub)
    vv = (SQRT2 - (row + 0.5) * step)[:, None, None] - o[None, :, None]  # (n, sub, 1)
    uu, vv = np.broadcast_arrays(uu, vv)
    r2 = uu * uu + vv * vv
    inside = r2 <= 2.0
    s = np.sqrt(np.clip(1.0 - r2 / 4.0, 0.0, None))
    w = np.stack([uu * s, vv * s, 1.0 - r2 / 2.0], axis=-1)
    n = len(row)
    return w.reshape(n, sub * sub, 3), inside.reshape(n, sub * sub)


def _cells(res: int) -> tuple[np.ndarray, np.ndarray]:
    """Flat indices of the pixels wholly inside the disc, and of those the horizon cuts."""
    step = 2 * SQRT2 / res
    e = np.arange(res + 1) * step - SQRT2  # pixel edges
    far = np.maximum(np.abs(e[:-1]), np.abs(e[1:]))  # farthest edge from the centre per axis
    near = np.where(e[:-1] * e[1:] <= 0, 0.0, np.minimum(np.abs(e[:-1]), np.abs(e[1:])))
    whole = (far[:, None] ** 2 + far[None, :] ** 2) <= 2.0
    touch = (near[:, None] ** 2 + near[None, :] ** 2) < 2.0
    return np.flatnonzero(whole), np.flatnonzero(touch & ~whole)


@dataclass(frozen=True)
class Chi2Result:
    """One incidence's test: the maps (``res × res``, NaN outside the disc) of the expected
    pdf integral and the histogram, both as densities (per sr, so comparable with the pdf),
    the statistic, its degrees of freedom and p-value, the fraction of failed samples, and the
    largest relative mismatch between the pdf ``sample`` returned and ``pdf(wi, wo)``;
    ``resolved`` is False when the pdf varies too fast within a pixel for the midpoint rule
    (a lobe narrower than a pixel): the statistic then measures the rule, not the sampler."""

    theta_i: float
    pdf_map: np.ndarray
    hist_map: np.ndarray
    stat: float
    dof: int
    p_value: float
    lost: float
    pdf_mismatch: float
    resolved: bool = True


def chi2_at(model: Model, values: Mapping[str, Any], theta_i: float, *, samples: int = SAMPLES,
            res: int = RES, sub: int = SUB, seed: int = 0) -> Chi2Result:
    """The χ² test of ``model.sampler`` at incidence ``θi`` (module docstring)."""
    sampler = model.sampler
    kw = model.kernel_params(values)
    wi1 = incident(theta_i, 180.0)
    rng = np.random.default_rng(seed)
    u1, u2 = rng.random(samples), rng.random(samples)
    wi = np.broadcast_to(wi1, (samples, 3))
    with kernel_errstate():
        wo, pdf_s = sampler.sample(wi, u1, u2, **kw)
    wo = np.asarray(wo, dtype=float).reshape(samples, 3)
    pdf_s = np.broadcast_to(np.asarray(pdf_s, dtype=float), (samples,))
    with np.errstate(all="ignore"):  # a sampler's failed samples may hold anything
        ok = np.isfinite(wo).all(axis=-1) & np.isfinite(pdf_s) & (pdf_s > 0.0) & (wo[:, 2] > 0.0)
    wo_ok = wo[ok]
    counts = np.bincount(_pixel_of(wo_ok, res), minlength=res * res).astype(float)
    lost = float(samples - ok.sum())
    # the pdf at the samples, against what sample() returned
    with kernel_errstate():
        pdf_at = np.asarray(sampler.pdf(wi[ok], wo_ok, **kw), dtype=float).reshape(-1)
    den = np.maximum(np.abs(pdf_at), np.abs(pdf_s[ok]))
    mism = float(np.max(np.abs(pdf_at - pdf_s[ok]) / np.where(den > 0, den, 1.0),
                        initial=0.0))
    # expected counts: N ∫ pdf dω per pixel, midpoint rule in (u, v)
    integral, area = _integrate(sampler, kw, wi1, res, sub)
    coarse, _ = _integrate(sampler, kw, wi1, res, max(sub // 2, 1))
    expected = samples * integral
    # the midpoint rule's error, estimated from the rule at half the sub-points: what it
    # would add to the statistic (≈ Σ err²/expected) against the statistic's own spread
    with np.errstate(all="ignore"):
        q_err = np.sum(np.where(expected > 0, (samples * (integral - coarse)) ** 2
                                / np.where(expected > 0, expected, 1.0), 0.0))
    exp_lost = max(samples * (1.0 - float(integral.sum())), 0.0)
    cover = area > 0.0
    obs = np.append(counts[cover], lost)
    exp = np.append(expected[cover], exp_lost)
    stat, dof = pearson(obs, exp)
    pval = chi2_sf(stat, dof) if dof > 0 else 1.0
    with np.errstate(all="ignore"):
        dens_pdf = np.where(cover, integral / np.where(area > 0, area, 1.0), np.nan)
        dens_hist = np.where(cover, counts / samples / np.where(area > 0, area, 1.0), np.nan)
    resolved = bool(q_err <= 0.25 * math.sqrt(2.0 * max(dof, 1)))
    return Chi2Result(theta_i, dens_pdf.reshape(res, res), dens_hist.reshape(res, res), stat,
                      dof, pval, lost / samples, mism, resolved)


def _integrate(sampler, kw, wi1, res: int, sub: int) -> tuple[np.ndarray, np.ndarray]:
    """``∫ pdf dω`` over every pixel (flat, ``res²``) by the midpoint rule in map coordinates:
    ``sub × sub`` points in a pixel wholly inside the disc, :data:`EDGE_FACTOR` times as many
    per side where the horizon cuts the pixel (the points inside count); and each pixel's solid
    angle inside the disc by the same points."""
    whole, edge = _cells(res)
    pix_sr = (2 * SQRT2 / res) ** 2
    integral = np.zeros(res * res)
    area = np.zeros(res * res)
    for pixels, k in ((whole, sub), (edge, sub * EDGE_FACTOR)):
        pts, inside = _sub_points(res, k, pixels)
        flat = pts[inside]
        with kernel_errstate():
            p = np.asarray(sampler.pdf(np.broadcast_to(wi1, flat.shape), flat, **kw),
                           dtype=float)
        grid = np.zeros(inside.shape)
        grid[inside] = np.maximum(p.reshape(-1), 0.0)
        integral[pixels] = grid.sum(axis=1) * (pix_sr / (k * k))
        area[pixels] = inside.sum(axis=1) * (pix_sr / (k * k))
    return integral, area


def pearson(observed: np.ndarray, expected: np.ndarray) -> tuple[float, int]:
    """Pearson's statistic with the cells expected below :data:`MIN_EXPECTED` pooled into one
    (which joins the rest only if it reaches the threshold itself; else it is merged into the
    smallest kept cell), and its degrees of freedom (kept cells − 1)."""
    observed = np.asarray(observed, dtype=float)
    expected = np.asarray(expected, dtype=float)
    low = expected < MIN_EXPECTED
    obs = list(observed[~low])
    exp = list(expected[~low])
    po, pe = float(observed[low].sum()), float(expected[low].sum())
    if low.any():
        if pe >= MIN_EXPECTED or not exp:
            obs.append(po)
            exp.append(pe)
        else:
            k = int(np.argmin(exp))
            obs[k] += po
            exp[k] += pe
    o, e = np.array(obs), np.array(exp)
    keep = e > 0.0
    stat = float(np.sum((o[keep] - e[keep]) ** 2 / e[keep]))
    # observations in cells expected to be empty: impossible under the pdf
    if np.any(o[~keep] > 0):
        stat = math.inf
    return stat, int(keep.sum()) - 1


@dataclass(frozen=True)
class Chi2Verdict:
    """``ok``; ``resolved`` False: inconclusive (some incidence's lobe is narrower than the
    map's pixels; ``ok`` is then True unless the pdfs disagree)."""

    ok: bool
    p_value: float  # the smallest over the incidences
    results: tuple[Chi2Result, ...]
    threshold: float
    resolved: bool = True


def chi2_test(model: Model, values: Mapping[str, Any], thetas: Sequence[float] = THETAS, *,
              significance: float = SIGNIFICANCE, samples: int = SAMPLES, seed: int = 0,
              res: int = RES, sub: int = SUB) -> Chi2Verdict:
    """The test at every incidence of ``thetas``; passes when every p-value is above
    ``significance`` with Šidák's correction, ``1 − (1 − α)^{1/n}``, and the sampler's pdf
    agrees with ``pdf`` to 1e-6 (an unresolved test passes on the pdfs' agreement alone)."""
    rs = tuple(chi2_at(model, values, t, samples=samples, seed=seed + k, res=res, sub=sub)
               for k, t in enumerate(thetas))
    threshold = 1.0 - (1.0 - significance) ** (1.0 / max(len(rs), 1))
    pmin = min(r.p_value for r in rs)
    resolved = all(r.resolved for r in rs)
    agree = all(r.pdf_mismatch <= 1e-6 for r in rs)
    ok = agree and (pmin >= threshold or not resolved)
    return Chi2Verdict(ok, pmin, rs, threshold, resolved)
