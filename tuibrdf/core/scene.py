"""One frame of the viewer as numbers: a :class:`FrameRequest` computed once into a
:class:`FrameResult`, from which every pane draws (map, cross-sections, solid, albedo curve,
status line).  numpy only; :mod:`tuibrdf.render.panes` turns a result into pictures.

A request names what the visible panes need: the materials (one, or two in compare mode), θi,
the cosine toggle, the map's pixel grid (when a map is shown), whether the 3D solid or the
albedo curve is shown.  Per material the result holds:

==============  ==================================================================================
``peaks``       :func:`tuibrdf.core.peak.find_peaks`: the one peak (``(Y, R, G, B)`` for RGB)
``sections``    ``f`` along both planes (θr from −90° to 90°, :data:`SECTION_THETAS`): one call
``map``         the Lambert map's pixels and :class:`~tuibrdf.core.hemimap.MapInfo` (or None)
``solid``       ``f`` at the solid's sample directions (:func:`solid_samples`; or None)
``albedo``      ``a(θi) = ∫ f cos θr dω`` (float, or 3 floats for RGB), None until computed
``curve``       ``a`` at :data:`CURVE_THETAS` (the albedo view), None until computed
``*_error``     the quadrature's estimate of the absolute error of ``albedo`` / ``curve``
==============  ==================================================================================

The energy test is :func:`tuibrdf.core.quadrature.exceeds_one` (albedo − error > 1):
:meth:`SideFrame.albedo_exceeds_one` and :meth:`SideFrame.curve_exceeds_one`.

Every value except ``albedo`` and ``curve`` includes the cosine factor when ``cosine`` is set.
The albedo and the curve are slow (up to tens of ms and 0.3 s for sharp lobes): ``compute_frame(r,
slow=False)`` leaves them None unless already cached, so a viewer can show the rest at once
and complete the frame in a worker.  Each part is cached by what it depends on (thread-safe
LRUs), the whole result by its request: a repeated frame costs two dictionary look-ups.
"""

from __future__ import annotations

import threading
from collections import OrderedDict
from collections.abc import Callable, Hashable
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

import numpy as np

from .frame import incident, sincos_deg
from .hemimap import MapInfo, map_values
from .material import Material
from .peak import Peak, find_peaks, radiance
from .quadrature import (
    AlbedoEstimate,
    albedo_curve_estimate_resolved,
    albedo_estimate_resolved,
    exceeds_one,
)

PLANES = ("incidence", "perpendicular")
#: signed θr of the cross-sections: the right half is φr = 0° (incidence) / 90°
SECTION_THETAS = np.linspace(-90.0, 90.0, 181)
SECTION_THETAS.setflags(write=False)
CURVE_STEP_DEG = 3.0
#: incidence angles of the albedo curve
CURVE_THETAS = np.arange(0.0, 90.0 + CURVE_STEP_DEG / 2, CURVE_STEP_DEG)
CURVE_THETAS.setflags(write=False)
#: the albedo curve is integrated in this many batches (coarse to fine: every 4th angle first),
#: so that a worker whose request is gone stops within one batch
CURVE_CHUNKS = 4
#: the 3D solid's sampling: hemisphere mesh level and barycentric steps per triangle edge
SOLID_LEVEL, SOLID_SUBDIV = 4, 3


class LRU:
    """A small thread-safe least-recently-used cache: ``get(key, make)``."""

    def __init__(self, size: int) -> None:
        self.size = size
        self.data: OrderedDict[Hashable, Any] = OrderedDict()
        self.lock = threading.Lock()

    def peek(self, key: Hashable) -> Any:
        with self.lock:
            return self.data.get(key)

    def put(self, key: Hashable, value: Any) -> Any:
        with self.lock:
            self.data[key] = value
            self.data.move_to_end(key)
            while len(self.data) > self.size:
                self.data.popitem(last=False)
        return value

    def get(self, key: Hashable, make: Callable[[], Any]) -> Any:
        with self.lock:
            if key in self.data:
                self.data.move_to_end(key)
                return self.data[key]
        return self.put(key, make())  # computed outside the lock: other threads go on

    def clear(self) -> None:
        with self.lock:
            self.data.clear()


@dataclass(frozen=True)
class FrameRequest:
    """What one frame shows, as a hashable value (the cache key of its result)."""

    materials: tuple[Material, ...]
    theta_i: float
    cosine: bool = False
    #: ``(px_w, px_h)`` of the map(s), or None when no map is visible
    map_px: tuple[int, int] | None = None
    #: how the map is filled (:data:`tuibrdf.core.hemimap.METHODS`)
    map_method: str = "exact"
    solid: bool = False
    curve: bool = False

    def __post_init__(self) -> None:
        if not 1 <= len(self.materials) <= 2:
            raise ValueError("a frame shows one or two materials")
        t = float(self.theta_i)
        if not 0.0 <= t <= 90.0:  # also refuses NaN
            raise ValueError(f"theta_i = {self.theta_i!r} is invalid: expected in [0, 90]°")
        object.__setattr__(self, "theta_i", t)


@dataclass(frozen=True)
class SideFrame:
    """The numbers of one material in a frame (see the module's table)."""

    material: Material
    peaks: tuple[Peak, ...]
    sections: dict[str, np.ndarray]
    map: tuple[np.ndarray, MapInfo] | None = None
    solid: np.ndarray | None = None
    albedo: float | tuple[float, ...] | None = None
    curve: np.ndarray | None = None
    albedo_error: float | tuple[float, ...] | None = None
    curve_error: np.ndarray | None = None

    def albedo_exceeds_one(self) -> bool:
        """The energy test on the albedo: above 1 by more than its error estimate."""
        return self.albedo is not None and exceeds_one(
            (self.albedo, 0.0 if self.albedo_error is None else self.albedo_error))

    def curve_exceeds_one(self) -> bool:
        """The energy test at any point of the albedo curve."""
        return self.curve is not None and exceeds_one(
            (self.curve, 0.0 if self.curve_error is None else self.curve_error))

    @property
    def peak(self) -> Peak:
        """The scalar peak: the value, or the luminance of an RGB model."""
        return self.peaks[0]

    def peak_for(self, rgb_mode: str) -> Peak:
        """The peak a picture in ``rgb_mode`` is scaled by: an RGB model in ``"color"`` mode
        shows every channel on one scale, topped by the largest channel peak; otherwise the
        luminance (or the scalar value)."""
        if len(self.peaks) == 1 or rgb_mode != "color":
            return self.peaks[0]
        return max(self.peaks[1:], key=lambda p: p.value)

    @property
    def section_max(self) -> float:
        """The largest value along both cross-sections (every channel)."""
        return max(float(np.max(v)) for v in self.sections.values())


@dataclass(frozen=True)
class FrameResult:
    request: FrameRequest
    sides: tuple[SideFrame, ...]

    @property
    def complete(self) -> bool:
        """Whether the slow parts the request asks for are there."""
        return all(s.albedo is not None and (s.curve is not None or not self.request.curve)
                   for s in self.sides)


# ------------------------------------------------------------------------------ the parts
_PEAKS, _SECTIONS, _MAPS, _SOLIDS = LRU(64), LRU(64), LRU(8), LRU(16)
_ALBEDO, _CURVES, _FRAMES = LRU(256), LRU(32), LRU(32)
CACHES = (_PEAKS, _SECTIONS, _MAPS, _SOLIDS, _ALBEDO, _CURVES, _FRAMES)


def clear_caches() -> None:
    for c in CACHES:
        c.clear()


def section_directions(plane: str, thetas_deg: np.ndarray) -> np.ndarray:
    """Unit directions for signed ``θr`` in ``plane`` (exact at ±90°): incidence
    ``(sin θr, 0, cos θr)``, perpendicular ``(0, sin θr, cos θr)``."""
    if plane not in PLANES:
        raise ValueError(f"unknown plane {plane!r}: expected one of {', '.join(PLANES)}")
    s, c = sincos_deg(np.asarray(thetas_deg, dtype=float))
    zero = np.zeros_like(s)
    return np.stack([s, zero, c] if plane == "incidence" else [zero, s, c], axis=-1)


def _sections(m: Material, theta_i: float, cosine: bool) -> dict[str, np.ndarray]:
    wo = np.concatenate([section_directions(p, SECTION_THETAS) for p in PLANES])
    g = radiance(m.model, m.values, incident(theta_i), wo, cosine)  # both planes, one call
    n = len(SECTION_THETAS)
    out = {p: g[k * n:(k + 1) * n] for k, p in enumerate(PLANES)}
    for v in out.values():
        v.setflags(write=False)
    return out


@lru_cache(maxsize=4)
def solid_samples(level: int = SOLID_LEVEL, subdiv: int = SOLID_SUBDIV):
    """``(dirs (S, 3), face of each sample (S,), face corners (F, 3, 3))``: each triangle of
    ``hemisphere(level)`` sampled on a barycentric grid of ``subdiv`` steps per edge."""
    from .mesh import hemisphere

    mesh = hemisphere(level)
    i, j = np.meshgrid(np.arange(subdiv + 1), np.arange(subdiv + 1), indexing="ij")
    keep = i + j <= subdiv
    b = np.stack([i[keep], j[keep], subdiv - i[keep] - j[keep]], axis=1) / subdiv  # (B, 3)
    tri = mesh.vertices[mesh.faces]  # (F, 3, 3)
    pts = np.einsum("bk,fkd->fbd", b, tri).reshape(-1, 3)
    pts /= np.linalg.norm(pts, axis=1, keepdims=True)  # points of a unit-sphere mesh: norm > 0
    face = np.repeat(np.arange(len(mesh.faces)), len(b))
    for arr in (pts, face, tri):
        arr.setflags(write=False)
    return pts, face, tri


def solid_values(m: Material, theta_i: float, cosine: bool = False) -> np.ndarray:
    """``f`` at the samples then at the face corners, in one kernel call: ``(S + 3F, ...)``."""
    pts, _, tri = solid_samples()
    wo = np.concatenate([pts, tri.reshape(-1, 3)])
    g = radiance(m.model, m.values, incident(theta_i), wo, cosine)
    g.setflags(write=False)
    return g


def _plain(a) -> float | tuple[float, ...]:
    a = np.asarray(a, dtype=float)
    return float(a) if a.ndim == 0 else tuple(float(x) for x in a)


def _albedo(m: Material, theta_i: float) -> AlbedoEstimate:
    """``(albedo, error)`` as floats (or tuples of 3 for RGB)."""
    e = albedo_estimate_resolved(m.model, m.values, theta_i)
    return AlbedoEstimate(_plain(e.value), _plain(e.error))


def _curve(m: Material, check: Callable[[], bool] | None = None) -> AlbedoEstimate | None:
    """The albedo and its error at every :data:`CURVE_THETAS` (arrays); None when ``check``
    says stop.  Integrated in :data:`CURVE_CHUNKS` batches (each one batch of the quadrature),
    so a worker whose request is gone stops after at most one batch."""
    n = len(CURVE_THETAS)
    value, error = None, None
    for c in range(CURVE_CHUNKS):
        if check is not None and not check():
            return None
        idx = np.arange(c, n, CURVE_CHUNKS)  # every 4th angle: the first batch spans 0–90°
        e = albedo_curve_estimate_resolved(m.model, m.values, CURVE_THETAS[idx])
        v, err = np.asarray(e.value, dtype=float), np.asarray(e.error, dtype=float)
        if value is None:
            value = np.empty((n,) + v.shape[1:])
            error = np.empty((n,) + v.shape[1:])
        value[idx], error[idx] = v, err
    value.setflags(write=False)
    error.setflags(write=False)
    return AlbedoEstimate(value, error)


def _side(req: FrameRequest, m: Material, slow: bool,
          check: Callable[[], bool] | None) -> SideFrame | None:
    t, cos = req.theta_i, req.cosine
    peaks = _PEAKS.get((m, t, cos), lambda: find_peaks(m.model, m.values, t, cosine=cos))
    sections = _SECTIONS.get((m, t, cos), lambda: _sections(m, t, cos))
    mp = None
    if req.map_px is not None:
        px = req.map_px
        how = req.map_method
        mp = _MAPS.get((m, t, cos, px, how), lambda: map_values(
            m.model, m.values, t, px[0], px[1], cosine=cos, method=how))
    solid = _SOLIDS.get((m, t, cos), lambda: solid_values(m, t, cos)) if req.solid else None
    if slow:
        albedo = _ALBEDO.get((m, t), lambda: _albedo(m, t))
        curve = None
        if req.curve:
            curve = _CURVES.peek(m)
            if curve is None:
                curve = _curve(m, check)
                if curve is None:
                    return None  # abandoned
                _CURVES.put(m, curve)
    else:
        albedo = _ALBEDO.peek((m, t))
        curve = _CURVES.peek(m) if req.curve else None
    a, a_err = albedo if albedo is not None else (None, None)
    c, c_err = curve if curve is not None else (None, None)
    return SideFrame(m, peaks, sections, mp, solid, a, c, a_err, c_err)


def compute_frame(req: FrameRequest, *, slow: bool = True,
                  check: Callable[[], bool] | None = None) -> FrameResult | None:
    """The numbers of ``req`` (cached).  ``slow=False``: the albedo and curve only when
    cached already.  ``check`` (a worker's "still wanted?") is asked before each material and
    each point of the albedo curve; when it answers False the work stops, the answer is None."""
    done = _FRAMES.peek(req)
    if done is not None and (done.complete or not slow):
        return done
    sides = []
    for m in req.materials:
        if check is not None and not check():
            return None
        side = _side(req, m, slow, check)
        if side is None:
            return None
        sides.append(side)
    return _FRAMES.put(req, FrameResult(req, tuple(sides)))


def cached_frame(req: FrameRequest) -> FrameResult | None:
    """The result of ``req`` if it was computed already (no work), else None."""
    return _FRAMES.peek(req)


def albedo_curve(m: Material) -> np.ndarray:
    """``a`` at :data:`CURVE_THETAS` (cached): ``(n,)`` or ``(n, 3)``."""
    return _CURVES.get(m, lambda: _curve(m)).value


def albedo_curve_estimate(m: Material) -> AlbedoEstimate:
    """``(a, error)`` at :data:`CURVE_THETAS` (cached)."""
    return _CURVES.get(m, lambda: _curve(m))


