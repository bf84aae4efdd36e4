"""Peaks on the horizon: whether a frame's peak is bounded, and the colour scale its pictures
use.  numpy only (the numbers of :mod:`tuibrdf.core.views.frame`'s frame).

A frame's peak (:func:`~tuibrdf.core.sphere.peak.find_peaks`) can lie on the horizon, or within a
hair
of it, where no picture can show it: the map's cells have their centres below 90° (≈ 88.5° at
the viewer's largest pane, ≈ 85° at 40×14), the sections sample every degree.  Two cases:

- **bounded**: a finite but steep maximum (ggx θi = 89°: f ≈ D·F / (2α sin(θi + θo)), 1.08e3 at
  θo = 90° against 513 at 89°).  The number is true; the map cannot show the last fraction of
  a degree;
- **unbounded**: the kernel grows without bound toward the horizon (sgd where G1(90°) > 0: the
  specular term grows like 1/cos θo; a microfacet lobe at θi = 90°), so there is no maximum and
  the finder's value only says how close to 90° its search got.

**The rule** (the one number of every picture): the colour scale is the frame's peak when the
peak lies at θ ≤ :data:`HORIZON_DEG` (89°) and is bounded: every ordinary frame.  Otherwise
(``kind`` ``"capped"`` or ``"unbounded"``) it is the largest value at θ ≤ 89°: what the
picture draws there (:func:`drawn_scale`: the map's pixel centres, the solid's samples), or a
shown column's own peak there when it is an ordinary one and higher
(:meth:`tuibrdf.core.views.frame.SideFrame.scale_for`); values above it, closer to the horizon,
take the top colour ("clipped").  So the lobe next to the horizon fills the colour range at
any pane size, and the scale is a number the pictures show.

**Growth test** (:func:`assess`): along the mirror side's horizon azimuth and the peak's own
azimuth, ``f`` at ``90° − δ`` for ``δ = 10⁰ … 10⁻⁸ degrees`` (one kernel call of 9 directions per
azimuth).  Unbounded when ``f`` grows by at least √10 over each of the last two decades (like
``1/δ^p`` with p ≥ 1/2 down to 10⁻⁸°: the sgd and microfacet cases grow like ``1/δ``, ratio 10;
a bounded smooth ``f`` has a ratio → 1 there).  A sample above the finder's value is a maximum
the finder missed next to the horizon (its plane grid stops at 89°, its 2-D search can climb
the lobe instead: sgd gold-metallic-paint at θi = 60°, R channel: 0.989 at 63° against 1.13 at
89.98°): it is refined along that azimuth (the finder's 1-D plane search) and replaces the peak.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any, NamedTuple

import numpy as np

from tuibrdf.core.params import Model
from tuibrdf.core.sphere.peak import (
    NORMAL,
    PEAK_TOL,
    Peak,
    _plane_refine,
    f_or_f_cos,
    mirror_horizon,
    scores,
)

#: a peak above this polar angle (degrees) is on the horizon for the pictures: their scale is
#: the largest value they draw at θ ≤ this angle, and the section through the peak goes
#: through the peak's direction lowered to it
HORIZON_DEG = 89.0
#: a bounded peak above HORIZON_DEG is on the horizon for the pictures when it exceeds f at
#: 89° below it by more than this factor (a map on the peak's scale would not reach two thirds
#: of its top colour); a gentler rise (oren-nayar's backscatter, ggx at θi = 60°: 1.05) keeps
#: the peak as the scale
HORIZON_RATIO = 1.5
#: the growth test's distances from the horizon, degrees (10⁰ … 10⁻⁸)
GROWTH_DELTAS_DEG = tuple(10.0 ** -k for k in range(9))
#: growth per decade over the last two decades that counts as unbounded (f ~ 1/δ^p, p ≥ 1/2)
GROWTH_MIN = math.sqrt(10.0)
_DELTAS = np.radians(np.array(GROWTH_DELTAS_DEG))
_COS_D, _SIN_D = np.cos(_DELTAS), np.sin(_DELTAS)


class Horizon(NamedTuple):
    """Where a column's peak is, for the pictures: ``kind`` ``"peak"`` (at θ ≤ 89° and
    bounded), ``"capped"`` (finite, above 89°) or ``"unbounded"`` (f → ∞ toward the horizon
    at azimuth ``toward_deg``, degrees in (−180°, 180°])."""

    kind: str = "peak"
    toward_deg: float = 0.0


class PeakScale(NamedTuple):
    """The top of a picture's colour scale and where it is (degrees; φ in (−180°, 180°]):
    the peak (``kind == "peak"``), or the largest value the picture draws at θ ≤ 89° when its
    peak is ``"capped"`` or ``"unbounded"`` (the peak's kind, ``toward_deg`` as in
    :class:`Horizon`)."""

    value: float
    theta_deg: float
    phi_deg: float
    label: str = ""
    kind: str = "peak"
    toward_deg: float = 0.0

    @property
    def capped(self) -> bool:
        """Whether the scale is not the peak (the peak is above 89° or unbounded)."""
        return self.kind != "peak"


def _axes(wi: np.ndarray, phi_i_deg: float, peaks: tuple[Peak, ...]) -> list[np.ndarray]:
    """The horizontal unit vectors to test: the mirror side's horizon, then each peak's azimuth
    where the peak is above HORIZON_DEG and not on the first."""
    out = [mirror_horizon(wi, phi_i_deg)]
    for p in peaks:
        if p.theta_deg <= HORIZON_DEG:
            continue
        a = math.radians(p.phi_deg)
        ax = np.array([math.cos(a), math.sin(a), 0.0])
        if all(float(ax @ b) < 1.0 - 1e-12 for b in out):
            out.append(ax)
    return out


def _phi(axis: np.ndarray) -> float:
    ph = math.degrees(math.atan2(float(axis[1]), float(axis[0])))
    return ph + 360.0 if ph <= -180.0 else ph


def grows(y: np.ndarray) -> np.ndarray:
    """Per column of ``y`` (values at δ = 10⁰ … 10⁻⁸ degrees, rows in that order): whether it
    grows by at least :data:`GROWTH_MIN` over each of the last two decades."""
    a, b, c = y[-3], y[-2], y[-1]
    return (a > 0.0) & (b >= GROWTH_MIN * a) & (c >= GROWTH_MIN * b)


def _classify(model: Model, values: Mapping[str, Any], wi: np.ndarray,
              peaks: tuple[Peak, ...], *, cosine: bool = False, phi_i_deg: float = 180.0
              ) -> tuple[tuple[Peak, ...], list[float | None], list[float]]:
    """The growth test (see the module): ``(peaks, toward, below)`` with a peak the finder
    missed next to the horizon put right, per column the azimuth (degrees) along which f grows
    without bound toward the horizon (None when it is bounded there), and f at 89° on the
    azimuth tested nearest the peak's."""
    axes = _axes(wi, phi_i_deg, peaks)
    n = len(_DELTAS)
    # 90° − δ along each axis: cos δ · axis + sin δ · N (exact distances from the horizon)
    w = np.concatenate([_COS_D[:, None] * ax + _SIN_D[:, None] * NORMAL for ax in axes])
    sc = scores(f_or_f_cos(model, values, wi, w, cosine))  # one call for every axis
    peaks = list(peaks)
    toward: list[float | None] = [None] * len(peaks)
    starts: list[list] = [[] for _ in axes]
    for j, ax in enumerate(axes):
        y = sc[j * n:(j + 1) * n]
        up = grows(y)
        for c in range(len(peaks)):
            if up[c]:
                if toward[c] is None or j > 0:  # the peak's own azimuth first
                    toward[c] = _phi(ax)
                top = float(y[-1, c])
                if top > peaks[c].value:
                    # no maximum; the value kept is the largest reached (at 10⁻⁸° here), so
                    # that the peak stays above every value a picture draws
                    peaks[c] = Peak(top, 90.0 - GROWTH_DELTAS_DEG[-1], _phi(ax), peaks[c].label)
            elif float(y[:, c].max()) > peaks[c].value * (1.0 + PEAK_TOL):
                # a higher value next to the horizon: refine it along this azimuth (t from
                # the normal, ascending: δ descending)
                ts = (0.5 * math.pi - _DELTAS).tolist()
                starts[j].append((c, ts, y[:, c].tolist()))
    for j, ax in enumerate(axes):
        todo = [s for s in starts[j] if toward[s[0]] is None]
        if not todo:
            continue
        val = [p.value for p in peaks]
        for c, v, t in _plane_refine(model, values, wi, cosine, ax, todo, val):
            if v > peaks[c].value * (1.0 + PEAK_TOL):
                peaks[c] = Peak(v, math.degrees(t), _phi(ax), peaks[c].label)
    # f at 89° below each peak above 89° (on the axis of its azimuth), for the ratio test
    below = []
    for p in peaks:
        a = math.radians(p.phi_deg)
        j = max(range(len(axes)), key=lambda j: math.cos(a) * axes[j][0]
                + math.sin(a) * axes[j][1])
        below.append(float(sc[j * n, len(below)]))
    return tuple(peaks), toward, below


def assess(model: Model, values: Mapping[str, Any], wi: np.ndarray,
           peaks: tuple[Peak, ...], *, cosine: bool = False, phi_i_deg: float = 180.0
           ) -> tuple[tuple[Peak, ...], tuple[Horizon, ...]]:
    """``(peaks, horizons)``: the frame's peaks (``find_peaks`` of the light ``wi``; a peak
    missed next to the horizon put right, see the module) and per column where it is for the
    pictures (:class:`Horizon`).  ``phi_i_deg`` as ``find_peaks`` takes it.  One kernel call
    of 9 directions per azimuth tested (one or two), and a 1-D search where the finder missed
    a peak next to the horizon."""
    peaks, toward, below = _classify(model, values, wi, peaks, cosine=cosine,
                                     phi_i_deg=phi_i_deg)
    out = tuple(Horizon("unbounded", t) if t is not None
                else Horizon("capped") if (p.theta_deg > HORIZON_DEG
                                           and p.value > HORIZON_RATIO * b) else Horizon()
                for p, t, b in zip(peaks, toward, below, strict=True))
    return peaks, out


#: cos θ at HORIZON_DEG: a drawn direction counts toward the scale when its z is at least this
_Z_MIN = math.sin(math.radians(90.0 - HORIZON_DEG))


def drawn_scale(values: np.ndarray, dirs: np.ndarray, labels: tuple[str, ...] = ("",)
                ) -> PeakScale:
    """The largest of ``values`` (``(n,)``, or ``(n, c)`` channels labelled ``labels``; NaN:
    not drawn) at the directions ``dirs (n, 3)`` with θ ≤ :data:`HORIZON_DEG`, and where: the
    scale of a picture whose peak is on the horizon (kind left ``"peak"``: the caller says
    which).  0 at the normal when nothing is drawn there."""
    v = np.asarray(values, dtype=float)
    v = v[:, None] if v.ndim == 1 else v
    ok = (np.asarray(dirs)[:, 2] >= _Z_MIN)[:, None] & np.isfinite(v)
    vv = np.where(ok, v, -np.inf)
    if not ok.any():
        return PeakScale(0.0, 0.0, 0.0, labels[0])
    i, c = np.unravel_index(int(np.argmax(vv)), vv.shape)
    w = np.asarray(dirs)[i]
    theta = math.degrees(math.atan2(math.hypot(float(w[0]), float(w[1])), float(w[2])))
    phi = math.degrees(math.atan2(float(w[1]), float(w[0]))) if theta > 0.0 else 0.0
    return PeakScale(float(v[i, c]), theta, phi + 360.0 if phi <= -180.0 else phi,
                     labels[c] if c < len(labels) else "")
