"""One frame of the viewer as numbers: a :class:`FrameRequest` computed once into a
:class:`FrameResult`, from which every pane draws (map, cross-sections, solid, albedo curve,
status line).  numpy only; :mod:`tuibrdf.render.panes` turns a result into pictures.

A request names what the visible panes need: the materials (one, or two in compare mode), θi,
the cosine toggle, the map's pixel grid (when a map is shown), whether the 3D solid or the
albedo curve is shown.  Per material the result holds:

==============  ==================================================================================
``peaks``       :func:`~tuibrdf.core.sphere.peak.find_peaks`: the one peak (``(Y, R, G, B)`` for
RGB),
                put right next to the horizon by :func:`tuibrdf.core.sphere.horizon.assess`
``horizons``    per column, whether the peak is above 89° or unbounded
                (:class:`~tuibrdf.core.sphere.horizon.Horizon`): the pictures' scale is then the
                largest
                value at θ ≤ 89° (:meth:`SideFrame.scale_for`)
``sections``    ``f`` along both planes (θr from −90° to 90°, :data:`SECTION_THETAS`) and, under
                ``"peak"``, along the great circle through :attr:`SideFrame.section_center` (the
                overall peak, the luminance's for RGB; lowered to θ = 89° when it is above 89°)
                at the request's section azimuth (signed angle from the
                centre, the same 181 samples; 0 below the horizon): one kernel call for all three
``probe``       ``(f, f·cos θr)`` at the request's probe direction (floats, or 3-tuples for RGB),
                or None when no probe is shown
``extra``       the arrays of the request's ``extra`` view, or None (:func:`extra_values`):
                ``sphere``/``plane`` → ``(radiance, mask)``, ``slice`` → ``(f, valid, θh, θd)``,
                ``theta-h``/``theta-d`` → ``(x, f, valid)``, ``energy`` → ``(EnergyView,)``
``extra_problem`` why the extra view could not be computed (a kernel failing at another
                incidence or parameter value than the current ones), else None
``map``         the Lambert map's pixels and :class:`~tuibrdf.core.views.hemimap.MapInfo` (or None)
``solid``       ``f`` at the solid's sample directions (:func:`solid_samples`; or None)
``albedo``      ``a(θi) = ∫ f cos θr dω`` (float, or 3 floats for RGB), None until computed
``curve``       ``a`` at :data:`CURVE_THETAS` (the albedo view), None until computed
``*_error``     the quadrature's estimate of the absolute error of ``albedo`` / ``curve``
==============  ==================================================================================

The energy test is :func:`tuibrdf.core.sphere.albedo.exceeds_one` (albedo − error > 1):
:meth:`SideFrame.albedo_exceeds_one` and :meth:`SideFrame.curve_exceeds_one`.

Every value except ``albedo`` and ``curve`` includes the cosine factor when ``cosine`` is set.
The albedo and the curve are slow (up to tens of ms and 0.3 s for sharp lobes): ``compute_frame(r,
slow=False)`` leaves them None unless already cached, so a viewer can show the rest at once
and complete the frame in a worker.  Each part is cached by what it depends on (thread-safe
:class:`~tuibrdf.core.lru.LRU`), the whole result by its request: a repeated frame costs two
dictionary look-ups.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from functools import lru_cache
from typing import TYPE_CHECKING, Any

import numpy as np

from tuibrdf.core.conventions import luminance
from tuibrdf.core.directions import (
    check_phi_i,
    check_theta_i,
    from_degrees,
    incident,
    sincos_deg,
)
from tuibrdf.core.display import DISPLAY
from tuibrdf.core.evaluate import f_cos
from tuibrdf.core.lru import LRU
from tuibrdf.core.material import Material
from tuibrdf.core.numerics import KERNEL_ERRORS
from tuibrdf.core.sphere.albedo import (
    AlbedoEstimate,
    albedo_curve_estimate_resolved,
    albedo_estimate_resolved,
    exceeds_one,
)
from tuibrdf.core.sphere.horizon import HORIZON_DEG, Horizon, PeakScale, assess, drawn_scale
from tuibrdf.core.sphere.peak import Peak, f_or_f_cos, find_peaks
from tuibrdf.core.views.hemimap import MapInfo, map_values

if TYPE_CHECKING:
    from tuibrdf.core.sphere.compare import Numbers

PLANES = ("incidence", "perpendicular")
#: the main views drawn from :func:`extra_values` (beside the map, the solid and the albedo)
EXTRA_VIEWS = ("sphere", "plane", "slice", "theta-h", "theta-d", "energy")
#: samples of the θh and θd line plots over [0°, 90°]
LINE_SAMPLES = 361
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


@dataclass(frozen=True)
class FrameRequest:
    """What one frame shows, as a hashable value (the cache key of its result)."""

    materials: tuple[Material, ...]
    theta_i: float
    cosine: bool = False
    #: ``(px_w, px_h)`` of the map(s), or None when no map is visible
    map_px: tuple[int, int] | None = None
    #: how the map is filled (:data:`tuibrdf.core.views.hemimap.METHODS`)
    map_method: str = "exact"
    solid: bool = False
    curve: bool = False
    #: ψ of the section through the peak (90°: across the peak's vertical plane)
    section_azimuth: float = DISPLAY.section_azimuth.default
    #: one of :data:`EXTRA_VIEWS` when shown, with its pixel grid (sphere, plane, slice) or
    #: ``None`` (line plots); and the fixed angles of the half/difference views
    extra: str | None = None
    extra_px: tuple[int, int] | None = None
    theta_d: float = DISPLAY.theta_d.default
    theta_h: float = DISPLAY.theta_h.default
    phi_d: float = DISPLAY.phi_d.default
    sqrt_h: bool = DISPLAY.sqrt_h
    #: the probe's Lambert coordinates on the map (:mod:`tuibrdf.core.views.hemimap`), or None
    probe: tuple[float, float] | None = None
    #: the light's azimuth (degrees, in [0, 360)); 180° puts it on the −x side
    phi_i: float = 180.0
    #: the parameter the energy view runs over (None: the model's first real parameter)
    energy_param: str | None = None
    #: the light direction at (θi, φi) (:func:`~tuibrdf.core.directions.incident`), made once
    #: here: every part of the frame takes it (read-only; not part of the key)
    wi: np.ndarray = field(init=False, compare=False, repr=False)

    def __post_init__(self) -> None:
        if not 1 <= len(self.materials) <= 2:
            raise ValueError("a frame shows one or two materials")
        t, p = check_theta_i(self.theta_i), check_phi_i(self.phi_i) % 360.0
        object.__setattr__(self, "theta_i", t)
        object.__setattr__(self, "phi_i", p)
        wi = incident(t, p)
        wi.setflags(write=False)
        object.__setattr__(self, "wi", wi)
        if self.extra is not None and self.extra not in EXTRA_VIEWS:
            raise ValueError(f"unknown view {self.extra!r}: expected one of "
                             f"{', '.join(EXTRA_VIEWS)}")
        if self.extra in ("sphere", "plane", "slice") and self.extra_px is None:
            raise ValueError(f"the {self.extra} view needs its pixel grid (extra_px)")

    @property
    def probe_direction(self) -> np.ndarray:
        """The unit direction of the probe (:func:`tuibrdf.core.views.hemimap.uv_to_dir`)."""
        from tuibrdf.core.views.hemimap import uv_to_dir

        return uv_to_dir(np.asarray(self.probe, dtype=float))

    @property
    def probe_angles(self) -> tuple[float, float]:
        """``(θr, φr)`` of the probe in degrees (φr in (−180°, 180°])."""
        from tuibrdf.core.directions import phi_of, theta_of

        w = self.probe_direction
        return float(np.degrees(theta_of(w))), float(np.degrees(phi_of(w)))

    @property
    def extra_key(self) -> tuple:
        """What the extra view's numbers depend on besides the material."""
        e = self.extra
        if e in ("sphere", "plane"):
            return (e, self.theta_i, self.phi_i, self.extra_px)
        if e == "slice":
            return (e, self.extra_px, self.phi_d, self.sqrt_h)
        if e == "theta-h":
            return (e, self.theta_d, self.phi_d)
        if e == "theta-d":
            return (e, self.theta_h, self.phi_d)
        if e == "energy":
            return (e, self.energy_param, self.theta_i, self.phi_i)
        return (e,)


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
    extra: tuple | None = None
    probe: tuple | None = None
    #: per column of ``peaks`` (:mod:`tuibrdf.core.sphere.horizon`); None: every peak is ordinary
    horizons: tuple[Horizon, ...] | None = None
    #: the share of directions where a user model's unclamped value is negative
    #: (:mod:`tuibrdf.core.views.negatives`); 0 for the built-in models
    negative: float = 0.0
    #: why the albedo curve could not be integrated (a kernel failing at another θi than the
    #: current one); None when it is there or not asked for
    curve_problem: str | None = None
    #: why the extra view could not be computed (:func:`or_problem`)
    extra_problem: str | None = None
    #: :meth:`scale_for`'s answers: the map, the sections and the status line each ask
    _scales: dict[tuple[str, str], PeakScale | None] = field(
        default_factory=dict, init=False, compare=False, repr=False)

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

    def horizon(self, column: int = 0) -> Horizon:
        """Where column ``column``'s peak is for the pictures (:class:`Horizon`)."""
        return Horizon() if self.horizons is None else self.horizons[column]

    def _shown(self, rgb_mode: str) -> int:
        """The column of :meth:`peak_for`."""
        if len(self.peaks) == 1 or rgb_mode != "color":
            return 0
        return max(range(1, len(self.peaks)),
                   key=lambda j: (self.horizon(j).kind == "unbounded", self.peaks[j].value))

    def peak_for(self, rgb_mode: str) -> Peak:
        """The peak a picture in ``rgb_mode`` shows: an RGB model in ``"color"`` mode shows
        every channel on one scale, and the largest channel peak (an unbounded one first);
        otherwise the luminance (or the scalar value)."""
        return self.peaks[self._shown(rgb_mode)]

    def peak_horizon(self, rgb_mode: str) -> Horizon:
        """:meth:`horizon` of :meth:`peak_for`'s column."""
        return self.horizon(self._shown(rgb_mode))

    def scale_for(self, rgb_mode: str, view: str = "map") -> PeakScale | None:
        """The top of the colour (or radius) scale of ``view`` (``"map"`` or ``"solid"``, whose
        values the frame holds; the solid in luminance) in ``rgb_mode``: the one number every
        pane shows.  :meth:`peak_for`'s peak when it is at θ ≤ 89° and bounded; otherwise the
        largest value at θ ≤ 89°: what the picture draws there
        (:func:`~tuibrdf.core.sphere.horizon.drawn_scale`, every channel in ``"color"`` mode), or
        the
        peak of a column it shows when that peak is an ordinary one and higher; with the
        peak's kind.  None when that picture is not in the frame."""
        key = rgb_mode, view
        if key not in self._scales:
            self._scales[key] = self._scale(rgb_mode, view)
        return self._scales[key]

    def _scale(self, rgb_mode: str, view: str) -> PeakScale | None:
        mode = "luminance" if view == "solid" else rgb_mode
        pk, hz = self.peak_for(mode), self.peak_horizon(mode)
        if hz.kind == "peak":
            return PeakScale(*pk)
        if view == "map" and self.map is not None:
            from tuibrdf.core.views.hemimap import geometry

            data = self.map[0]
            g = geometry(data.shape[1], data.shape[0])
            v, dirs = data[g.inside], g.dirs
        elif view == "solid" and self.solid is not None:
            dirs = solid_samples()[0]
            v = self.solid[:len(dirs)]
        else:
            return None
        labels, cols = ("",), (0,)  # the columns of ``peaks`` the picture shows
        if v.ndim == 2:
            if mode == "color":
                labels, cols = ("R", "G", "B"), (1, 2, 3)
            else:
                v, labels = luminance(v), ("Y",)
        s = drawn_scale(v, dirs, labels)
        # a column shown whose own peak is an ordinary one (bounded, at θ ≤ 89°: a channel
        # beside the one that grows toward the horizon) is the largest value at θ ≤ 89° in
        # that column, whether or not a pixel falls on it: a scale below it would sit under
        # the lobe the sections show (sgd gold-metallic-paint at θi = 45°: red 0.646 at 46°,
        # the map's pixels 0.622)
        for j in cols:
            p = self.peaks[j]
            if (self.horizon(j).kind == "peak" and p.theta_deg <= HORIZON_DEG
                    and p.value > s.value):
                s = PeakScale(p.value, p.theta_deg, p.phi_deg, p.label)
        return s._replace(kind=hz.kind, toward_deg=hz.toward_deg)

    @property
    def section_center(self) -> tuple[float, float]:
        """:func:`section_center` of the overall peak."""
        return section_center(self.peaks[0])

    @property
    def section_max(self) -> float:
        """The largest value along both cross-sections through the normal (every channel)."""
        return max(float(np.max(self.sections[p])) for p in PLANES)


@dataclass(frozen=True)
class FrameResult:
    request: FrameRequest
    sides: tuple[SideFrame, ...]
    #: compare mode: ``(max |fA − fB|, θo, φo)`` of the luminance (f·cos θr with cosine) on
    #: the function (:func:`tuibrdf.core.sphere.compare.largest_difference`), with a map
    diff_max: tuple[float, float, float] | None = None
    #: compare mode: the numbers of :func:`tuibrdf.core.sphere.compare.compare` at θi (a slow
    #: part, with the albedo)
    numbers: Numbers | None = None

    @property
    def complete(self) -> bool:
        """Whether the slow parts the request asks for are there."""
        return all(s.albedo is not None and (s.curve is not None or s.curve_problem is not None
                                             or not self.request.curve)
                   for s in self.sides) and (len(self.sides) < 2 or self.numbers is not None)


# ------------------------------------------------------------------------------ the parts
_PEAKS, _SECTIONS, _MAPS, _SOLIDS = LRU(64), LRU(64), LRU(8), LRU(16)
_ALBEDO, _CURVES, _FRAMES = LRU(256), LRU(32), LRU(32)
_EXTRA, _PROBES = LRU(16), LRU(64)
_DIFFS, _NUMBERS = LRU(32), LRU(64)
CACHES = (_PEAKS, _SECTIONS, _MAPS, _SOLIDS, _ALBEDO, _CURVES, _FRAMES, _EXTRA, _PROBES,
          _DIFFS, _NUMBERS)


def clear_caches() -> None:
    for c in CACHES:
        c.clear()


def section_directions(plane: str, thetas_deg: np.ndarray, phi_i_deg: float = 180.0
                       ) -> np.ndarray:
    """Unit directions for signed ``θr`` in ``plane`` (exact at ±90°): incidence
    ``(sin θr, 0, cos θr)``, perpendicular ``(0, sin θr, cos θr)`` for the light at
    φi = 180°; turned by φi − 180° about the normal otherwise (positive θr: the mirror side)."""
    if plane not in PLANES:
        raise ValueError(f"unknown plane {plane!r}: expected one of {', '.join(PLANES)}")
    s, c = sincos_deg(np.asarray(thetas_deg, dtype=float))
    zero = np.zeros_like(s)
    w = np.stack([s, zero, c] if plane == "incidence" else [zero, s, c], axis=-1)
    return turn(w, float(phi_i_deg) - 180.0)


def turn(w: np.ndarray, deg: float) -> np.ndarray:
    """Directions ``w (..., 3)`` turned by ``deg`` about the normal (exact for 0°)."""
    if deg % 360.0 == 0.0:
        return w
    sp, cp = (float(x) for x in sincos_deg(deg))
    return np.stack([cp * w[..., 0] - sp * w[..., 1], sp * w[..., 0] + cp * w[..., 1],
                     w[..., 2]], axis=-1)


def _peaks(m: Material, wi: np.ndarray, cosine: bool, phi_i: float
           ) -> tuple[tuple[Peak, ...], tuple[Horizon, ...]]:
    """The frame's peaks and where they are for the pictures
    (:mod:`tuibrdf.core.sphere.horizon`)."""
    peaks = find_peaks(m.model, m.values, wi, cosine=cosine, phi_i_deg=phi_i)
    return assess(m.model, m.values, wi, peaks, cosine=cosine, phi_i_deg=phi_i)


def section_center(peak: Peak) -> tuple[float, float]:
    """``(θ, φ)`` in degrees of the centre of the section through ``peak``: its direction,
    lowered to θ = 89° when it is above (the section across a peak on the horizon would be
    the horizon itself)."""
    return min(peak.theta_deg, HORIZON_DEG), peak.phi_deg


def _sections(m: Material, wi: np.ndarray, cosine: bool, center: np.ndarray,
              azimuth: float, phi_i: float = 180.0) -> dict[str, np.ndarray]:
    """Both planes through the normal and the great circle through ``center`` at section
    azimuth ``azimuth`` (:func:`tuibrdf.core.views.sections.great_circle`), in one kernel call."""
    from tuibrdf.core.views.sections import fwhm, great_circle

    w, above = great_circle(center, SECTION_THETAS, azimuth)
    w = np.where(above[:, None], w, np.array([0.0, 0.0, 1.0]))  # below: any valid direction
    wo = np.concatenate([section_directions(p, SECTION_THETAS, phi_i) for p in PLANES] + [w])
    g = f_or_f_cos(m.model, m.values, wi, wo, cosine)  # 3 sections, 1 call
    n = len(SECTION_THETAS)
    out = {p: g[k * n:(k + 1) * n] for k, p in enumerate((*PLANES, "peak"))}
    out["peak"] = np.where(above[:, None] if g.ndim == 2 else above, out["peak"], 0.0)

    def scalar(wo):  # the section's values (f or f·cos θr; the luminance for RGB), 0 below
        x = np.asarray(f_or_f_cos(m.model, m.values, wi, wo, cosine), dtype=float)
        x = luminance(x) if x.ndim == 2 else x
        return np.where(wo[:, 2] >= 0.0, x, 0.0)

    peak = out["peak"]
    width = fwhm(scalar, center, azimuth, SECTION_THETAS,
                 luminance(peak) if peak.ndim == 2 else peak)
    # the FWHM across the lobe (degrees; NaN: none), on the function (see fwhm)
    out["fwhm"] = np.array(np.nan if width is None else width)
    for v in out.values():
        v.setflags(write=False)
    return out


def probe_values(m: Material, wi: np.ndarray, w: np.ndarray) -> tuple:
    """``(f, f·cos θr)`` at the unit direction ``w`` (floats, or 3-tuples for RGB)."""
    f = np.asarray(f_or_f_cos(m.model, m.values, wi, w[None, :], False))[0]

    def out(x):
        return float(x) if np.ndim(x) == 0 else tuple(float(y) for y in x)

    return out(f), out(f_cos(f, w))


def extra_values(m: Material, req: FrameRequest) -> tuple:
    """The arrays of ``req.extra`` for material ``m`` (see the module's table)."""
    from tuibrdf.core.views import halfdiff, lit

    e, model, values = req.extra, m.model, m.values
    if e in ("sphere", "plane"):
        px_w, px_h = req.extra_px
        if e == "sphere":
            return lit.lit_sphere(model, values, req.wi, px_w, px_h)
        return lit.lit_plane(model, values, req.wi, px_w, px_h, view_deg=req.theta_i,
                             phi_i_deg=req.phi_i)
    if e == "slice":
        return halfdiff.slice_image(model, values, req.phi_d, n_h=req.extra_px[0],
                                    n_d=req.extra_px[1], sqrt_h=req.sqrt_h)
    if e == "theta-h":
        return halfdiff.theta_h_curve(model, values, req.theta_d, req.phi_d, n=LINE_SAMPLES)
    if e == "theta-d":
        return halfdiff.theta_d_curve(model, values, req.theta_h, req.phi_d, n=LINE_SAMPLES)
    if e == "energy":
        from tuibrdf.core.sphere.energy import energy_view

        # its E is the frame's albedo at (θi, φi): computed here once, for the status line too
        t, pi = req.theta_i, req.phi_i
        a = _ALBEDO.get((m, t, pi), lambda: _albedo_estimate(m, t, pi))
        return (energy_view(model, values, t, req.energy_param, pi, albedo=a),)
    raise ValueError(f"unknown view {e!r}")


def or_problem(work: Callable[[], Any]) -> Any:
    """``work()``, or why it failed (:data:`~tuibrdf.core.numerics.KERNEL_ERRORS`, as text):
    for the parts that run over other incidences (the albedo curve, the lit views' local
    frames, the θh/θd views) or parameter values (the energy table) than the current ones.  A
    kernel failing there (a NaN at grazing light, a floating-point error) is that pane's
    message, kept with the part, while the panes at the current values draw."""
    try:
        return work()
    except KERNEL_ERRORS as err:
        return str(err)


def _barycentric(subdiv: int) -> np.ndarray:
    """``(B, 3)`` integer weights ``(i, j, subdiv − i − j)`` of a triangle's barycentric grid,
    ``(i, j)`` row-major."""
    i, j = np.meshgrid(np.arange(subdiv + 1), np.arange(subdiv + 1), indexing="ij")
    keep = i + j <= subdiv
    return np.stack([i[keep], j[keep], subdiv - i[keep] - j[keep]], axis=1)


@lru_cache(maxsize=4)
def solid_samples(level: int = SOLID_LEVEL, subdiv: int = SOLID_SUBDIV):
    """``(dirs (S, 3), face of each sample (S,), face corners (F, 3, 3))``: each triangle of
    ``hemisphere(level)`` sampled on a barycentric grid of ``subdiv`` steps per edge."""
    from tuibrdf.core.sphere.mesh import hemisphere

    mesh = hemisphere(level)
    b = _barycentric(subdiv) / subdiv  # (B, 3)
    tri = mesh.vertices[mesh.faces]  # (F, 3, 3)
    pts = np.einsum("bk,fkd->fbd", b, tri).reshape(-1, 3)
    pts /= np.linalg.norm(pts, axis=1, keepdims=True)  # points of a unit-sphere mesh: norm > 0
    face = np.repeat(np.arange(len(mesh.faces)), len(b))
    for arr in (pts, face, tri):
        arr.setflags(write=False)
    return pts, face, tri


@lru_cache(maxsize=1)
def solid_directions() -> tuple[np.ndarray, np.ndarray]:
    """``(distinct (U, 3), take (S + 3F,))``: the solid's samples then its face corners
    (:func:`solid_samples`) as ``distinct[take]``.  Neighbouring triangles share their edges'
    and corners' samples, and every corner is a sample too: 11,641 directions instead of
    33,280 (a measured ``.bsdf``'s solid took 12.3 ms a θi, about as many times more).  A
    sample is named by the mesh vertices it is made of and their integer weights (the same
    name from every triangle that shares it, whatever the bits of its coordinates on this
    CPU); the first sample of a name stands for all."""
    from tuibrdf.core.sphere.mesh import hemisphere

    pts, _, tri = solid_samples()
    faces = hemisphere(SOLID_LEVEL).faces  # (F, 3)
    w = np.broadcast_to(_barycentric(SOLID_SUBDIV), (len(faces), len(pts) // len(faces), 3))
    ids = np.where(w > 0, faces[:, None, :], -1)  # a vertex of weight 0 is not part of it
    corners = np.zeros(faces.shape + (2, 3), dtype=np.int64)  # (F, 3, [ids, weights], 3)
    corners[..., 0, :2], corners[..., 0, 2] = -1, faces
    corners[..., 1, 2] = SOLID_SUBDIV
    order = np.argsort(ids, axis=-1, kind="stable")
    name = np.concatenate([np.take_along_axis(ids, order, -1).reshape(-1, 3),
                           np.take_along_axis(w, order, -1).reshape(-1, 3)], axis=1)
    name = np.concatenate([name, corners.reshape(-1, 6)])
    _, first, take = np.unique(name, axis=0, return_index=True, return_inverse=True)
    distinct = np.concatenate([pts, tri.reshape(-1, 3)])[first]
    take = take.reshape(-1)
    for arr in (distinct, take):
        arr.setflags(write=False)
    return distinct, take


def solid_values(m: Material, wi: np.ndarray, cosine: bool = False) -> np.ndarray:
    """``f`` at the samples then at the face corners, ``(S + 3F, ...)``, from one kernel call
    at their distinct directions (:func:`solid_directions`)."""
    distinct, take = solid_directions()
    g = np.asarray(f_or_f_cos(m.model, m.values, wi, distinct, cosine))[take]
    g.setflags(write=False)
    return g


def _plain(a) -> float | tuple[float, ...]:
    a = np.asarray(a, dtype=float)
    return float(a) if a.ndim == 0 else tuple(float(x) for x in a)


def _albedo_estimate(m: Material, theta_i: float, phi_i: float = 180.0) -> AlbedoEstimate:
    """``(albedo, error)`` as floats (or tuples of 3 for RGB)."""
    e = albedo_estimate_resolved(m.model, m.values, theta_i, phi_i)
    return AlbedoEstimate(_plain(e.value), _plain(e.error))


def _curve(m: Material, check: Callable[[], bool] | None = None,
           phi_i: float = 180.0) -> AlbedoEstimate | None:
    """The albedo and its error at every :data:`CURVE_THETAS` (arrays); None when ``check``
    says stop.  Integrated in :data:`CURVE_CHUNKS` batches (each one batch of the quadrature),
    so a worker whose request is gone stops after at most one batch."""
    n = len(CURVE_THETAS)
    value, error = None, None
    for c in range(CURVE_CHUNKS):
        if check is not None and not check():
            return None
        idx = np.arange(c, n, CURVE_CHUNKS)  # every 4th angle: the first batch spans 0–90°
        e = albedo_curve_estimate_resolved(m.model, m.values, CURVE_THETAS[idx], phi_i)
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
    t, cos, pi, wi = req.theta_i, req.cosine, req.phi_i, req.wi
    # the parts are cached by (θi, φi), which wi is a function of
    peaks, horizons = _PEAKS.get((m, t, pi, cos), lambda: _peaks(m, wi, cos, pi))
    az = req.section_azimuth
    ctr = section_center(peaks[0])
    sections = _SECTIONS.get((m, t, pi, cos, ctr, az),
                             lambda: _sections(m, wi, cos, from_degrees(*ctr), az, pi))
    mp = None
    if req.map_px is not None:
        px = req.map_px
        how = req.map_method
        mp = _MAPS.get((m, t, pi, cos, px, how), lambda: map_values(
            m.model, m.values, wi, px[0], px[1], cosine=cos, method=how))
    solid = (_SOLIDS.get((m, t, pi, cos), lambda: solid_values(m, wi, cos))
             if req.solid else None)
    extra = None
    if req.extra is not None:
        extra = _EXTRA.get((m, req.extra_key), lambda: or_problem(lambda: extra_values(m, req)))
    probe = None
    if req.probe is not None:
        probe = _PROBES.get((m, t, pi, req.probe),
                            lambda: probe_values(m, wi, req.probe_direction))
    if slow:
        albedo = _ALBEDO.get((m, t, pi), lambda: _albedo_estimate(m, t, pi))
        curve = None
        if req.curve:
            curve = _CURVES.peek((m, pi))
            if curve is None:
                curve = or_problem(lambda: _curve(m, check, pi))  # (over every θi)
                if curve is None:
                    return None  # abandoned
                _CURVES.put((m, pi), curve)
    else:
        albedo = _ALBEDO.peek((m, t, pi))
        curve = _CURVES.peek((m, pi)) if req.curve else None
    a, a_err = albedo if albedo is not None else (None, None)
    problem = curve if isinstance(curve, str) else None
    c, c_err = curve if curve is not None and problem is None else (None, None)
    extra_problem = extra if isinstance(extra, str) else None
    from tuibrdf.core.views.negatives import negative_share

    return SideFrame(m, peaks, sections, mp, solid, a, c, a_err, c_err,
                     None if extra_problem else extra, probe, horizons,
                     negative_share(m.model, m.values, req.wi), problem, extra_problem)


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
    diff, numbers = None, None
    if len(sides) == 2:  # compare mode: the numbers that say how far apart the sides are
        from tuibrdf.core.sphere import compare as sphere_compare  # (compare mode only)

        (a, b), t, pi = req.materials, req.theta_i, req.phi_i
        if req.map_px is not None:
            diff = _DIFFS.get((a, b, t, pi, req.cosine), lambda: sphere_compare.largest_difference(
                a.model, a.values, b.model, b.values, req.wi, req.cosine))
        if slow:
            numbers = _NUMBERS.get((a, b, t, pi), lambda: sphere_compare.compare(
                a.model, a.values, b.model, b.values, [t], pi,
                reference=sphere_compare.reference_side(a.model, b.model))[0])
        else:
            numbers = _NUMBERS.peek((a, b, t, pi))
    return _FRAMES.put(req, FrameResult(req, tuple(sides), diff, numbers))


def cached_frame(req: FrameRequest) -> FrameResult | None:
    """The result of ``req`` if it was computed already (no work), else None."""
    return _FRAMES.peek(req)


def needs_curve(req: FrameRequest) -> bool:
    """``req`` shows an albedo curve not computed yet (91 albedos: the slow part of a frame
    whatever the model)."""
    return req.curve and any(_CURVES.peek((m, req.phi_i)) is None for m in req.materials)
