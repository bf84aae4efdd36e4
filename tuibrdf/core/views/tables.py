"""The numbers behind each view, for files (``tuibrdf render --format npz|csv|json``, the
viewer's ``w`` key, :func:`tuibrdf.picture`): numpy only.

Every BRDF value here is :func:`tuibrdf.core.evaluate.evaluate` itself at the directions the
table states (``wi`` and ``wo`` as unit vectors, normalised by ``evaluate``'s own
:func:`~tuibrdf.core.evaluate.as_directions` first, so evaluating the written directions again
gives the written values bit for bit), never a picture's cached or interpolated pixels; the
albedo values are :func:`tuibrdf.core.sphere.albedo.albedo_curve_estimate_resolved`'s, with
its error estimate.  Angles are in degrees; ``f`` in sr⁻¹ (no cosine factor), ``(..., 3)``
for an RGB model.

A table is a :class:`Table`: ordered named arrays (``columns``) and the metadata a reader
needs (model, parameters, θi, φi, ``wi``) as a JSON-ready dict.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from tuibrdf.core.directions import incident, phi_of, theta_of
from tuibrdf.core.evaluate import as_directions, evaluate
from tuibrdf.core.params import Model

#: the views whose numbers are an image (NPZ) and those whose numbers are curves (CSV, JSON)
IMAGE_TABLES = ("map", "slice")
CURVE_TABLES = ("incidence", "perpendicular", "albedo", "theta-h", "theta-d")


@dataclass(frozen=True)
class Table:
    """Named arrays of one view (``columns``, in order) and its metadata."""

    view: str
    columns: dict[str, np.ndarray]
    meta: dict[str, Any] = field(default_factory=dict)


def _json_value(v: Any) -> Any:
    if isinstance(v, tuple | list):
        return [_json_value(x) for x in v]
    if isinstance(v, np.generic):
        return v.item()
    return v


def metadata(model: Model, values: dict[str, Any], theta_i: float, phi_i: float,
             view: str, **extra: Any) -> dict[str, Any]:
    """Model, parameters (user units, defaults filled), θi, φi, ``wi`` and ``view``."""
    wi = as_directions(incident(theta_i, phi_i), "wi")
    return {"model": model.name, "params": {k: _json_value(v) for k, v in values.items()},
            "theta_i": float(theta_i), "phi_i": float(phi_i),
            "wi": [float(x) for x in wi], "view": view, "f_unit": "1/sr", **extra}


def _f(model: Model, values: dict[str, Any], wi: np.ndarray, wo: np.ndarray) -> np.ndarray:
    return np.asarray(evaluate(model, values, wi, wo), dtype=float)


def map_table(model: Model, values: dict[str, Any], theta_i: float, phi_i: float,
              size: int) -> Table:
    """The Lambert map's ``size × size`` pixel grid (:func:`~.hemimap.geometry`): ``theta_r``,
    ``phi_r`` (degrees), ``wo`` ``(size, size, 3)`` and ``f``, NaN outside the disc."""
    from tuibrdf.core.views.hemimap import geometry

    g = geometry(size, size)
    meta = metadata(model, values, theta_i, phi_i, "map", projection="Lambert equal-area",
                    disc_diameter_px=g.diameter, disc_center_px=[g.cx, g.cy])
    wi = np.array(meta["wi"])
    wo = as_directions(g.dirs, "wo")
    f = _f(model, values, wi, wo)

    def grid(a: np.ndarray) -> np.ndarray:
        out = np.full(g.inside.shape + a.shape[1:], np.nan)
        out[g.inside] = a
        return out

    return Table("map", {"theta_r": grid(np.degrees(theta_of(wo))),
                         "phi_r": grid(np.degrees(phi_of(wo))), "wo": grid(wo),
                         "f": grid(f), "wi": wi}, meta)


def _pairs(model: Model, values: dict[str, Any], wi: np.ndarray, wo: np.ndarray,
           valid: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(wi, wo, f)`` normalised; NaN where not ``valid`` (a direction below the horizon)."""
    up = np.array([0.0, 0.0, 1.0])
    wi = as_directions(np.where(valid[..., None], wi, up), "wi")
    wo = as_directions(np.where(valid[..., None], wo, up), "wo")
    f = _f(model, values, wi, wo)
    nan = ~valid
    wi[nan], wo[nan] = np.nan, np.nan
    f[nan] = np.nan
    return wi, wo, f


def slice_table(model: Model, values: dict[str, Any], phi_d: float, n_h: int, n_d: int,
                sqrt_h: bool) -> Table:
    """The θh × θd slice (:func:`~.halfdiff.slice_image`'s axes): ``theta_h`` (n_h,),
    ``theta_d`` (n_d,), ``wi``, ``wo`` ``(n_d, n_h, 3)`` and ``f`` ``(n_d, n_h[, 3])``, NaN
    where a direction is below the horizon."""
    from tuibrdf.core.views.halfdiff import directions, theta_d_axis, theta_h_axis

    th, td = theta_h_axis(n_h, sqrt_h), theta_d_axis(n_d)
    wi, wo, valid = directions(th[None, :], td[:, None], float(phi_d))
    wi, wo, f = _pairs(model, values, wi, wo, valid)
    meta = {"model": model.name, "params": {k: _json_value(v) for k, v in values.items()},
            "view": "slice", "phi_d": float(phi_d), "sqrt_theta_h": bool(sqrt_h),
            "f_unit": "1/sr"}
    return Table("slice", {"theta_h": th, "theta_d": td, "wi": wi, "wo": wo, "f": f}, meta)


def section_table(model: Model, values: dict[str, Any], theta_i: float, phi_i: float,
                  plane: str, section_azimuth: float = 90.0, cosine: bool = False) -> Table:
    """A cross-section at the frame's 181 signed angles (negative on the light's side):
    ``incidence`` and ``perpendicular`` through the normal, or ``peak`` … as the viewer's
    ``perpendicular`` view draws it: the great circle through the lobe's peak."""
    from tuibrdf.core.directions import from_degrees
    from tuibrdf.core.sphere.horizon import assess
    from tuibrdf.core.sphere.peak import find_peaks
    from tuibrdf.core.views.frame import SECTION_THETAS, section_center, section_directions
    from tuibrdf.core.views.sections import great_circle

    meta = metadata(model, values, theta_i, phi_i, plane)
    wi = np.array(meta["wi"])
    t = np.array(SECTION_THETAS)
    if plane == "incidence":
        wo, valid = section_directions("incidence", t, phi_i), np.ones(t.shape, bool)
    else:
        peaks, _ = assess(model, values, wi,
                          find_peaks(model, values, wi, cosine=cosine, phi_i_deg=phi_i),
                          cosine=cosine, phi_i_deg=phi_i)
        center = section_center(peaks[0])
        wo, valid = great_circle(from_degrees(*center), t, section_azimuth)
        meta.update(center_theta=center[0], center_phi=center[1],
                    section_azimuth=float(section_azimuth))
    wis, wo, f = _pairs(model, values, np.broadcast_to(wi, wo.shape), wo, valid)
    return Table(plane, {"theta": t, **_direction_columns(wis, wo), **_f_columns(f)}, meta)


def _direction_columns(wi: np.ndarray, wo: np.ndarray) -> dict[str, np.ndarray]:
    """Each row states its directions: ``f`` is ``evaluate`` at exactly these."""
    return {"wi_x": wi[:, 0], "wi_y": wi[:, 1], "wi_z": wi[:, 2],
            "wo_x": wo[:, 0], "wo_y": wo[:, 1], "wo_z": wo[:, 2]}


def _f_columns(f: np.ndarray) -> dict[str, np.ndarray]:
    if f.ndim == 2:
        return {"f_r": f[:, 0], "f_g": f[:, 1], "f_b": f[:, 2]}
    return {"f": f}


def halfdiff_table(model: Model, values: dict[str, Any], view: str, fixed: float,
                   phi_d: float, n: int) -> Table:
    """``theta-h`` (f against θh at θd = ``fixed``) or ``theta-d`` (against θd at θh =
    ``fixed``), ``n`` points over [0°, 90°], with both directions; NaN where a direction is
    below the horizon."""
    from tuibrdf.core.views.halfdiff import directions

    x = np.linspace(0.0, 90.0, n)
    th, td = (x, float(fixed)) if view == "theta-h" else (float(fixed), x)
    wi, wo, valid = directions(th, td, float(phi_d))
    wi, wo, f = _pairs(model, values, *np.broadcast_arrays(wi, wo), np.broadcast_to(valid,
                                                                                    x.shape))
    name = "theta_h" if view == "theta-h" else "theta_d"
    meta = {"model": model.name, "params": {k: _json_value(v) for k, v in values.items()},
            "view": view, "phi_d": float(phi_d),
            ("theta_d" if view == "theta-h" else "theta_h"): float(fixed), "f_unit": "1/sr"}
    return Table(view, {name: x, **_direction_columns(wi, wo), **_f_columns(f)}, meta)


def albedo_table(model: Model, values: dict[str, Any], phi_i: float,
                 thetas: np.ndarray | None = None) -> Table:
    """``theta_i``, ``albedo`` and ``error`` (the quadrature's estimate of the absolute error)
    at the albedo view's incidences (every 3°, 0–90°); ``_r/_g/_b`` columns for RGB."""
    from tuibrdf.core.sphere.albedo import albedo_curve_estimate_resolved
    from tuibrdf.core.views.frame import CURVE_THETAS

    t = np.array(CURVE_THETAS if thetas is None else thetas, dtype=float)
    e = albedo_curve_estimate_resolved(model, values, t, float(phi_i))
    a, err = np.asarray(e.value, dtype=float), np.asarray(e.error, dtype=float)
    meta = {"model": model.name, "params": {k: _json_value(v) for k, v in values.items()},
            "view": "albedo", "phi_i": float(phi_i)}
    if a.ndim == 2:
        cols = {f"albedo_{c}": a[:, k] for k, c in enumerate("rgb")}
        cols.update({f"error_{c}": err[:, k] for k, c in enumerate("rgb")})
        return Table("albedo", {"theta_i": t, **cols}, meta)
    return Table("albedo", {"theta_i": t, "albedo": a, "error": err}, meta)


def for_view(view: str, model: Model, values: dict[str, Any], theta_i: float,
             phi_i: float = 180.0, *, size: int = 512, section_azimuth: float = 90.0,
             theta_d: float = 0.0, theta_h: float = 0.0, phi_d: float = 90.0,
             sqrt_h: bool = True, cosine: bool = False) -> Table:
    """The numbers of ``view`` (one of :data:`IMAGE_TABLES` or :data:`CURVE_TABLES`); the map
    on a ``size × size`` grid, the slice ``size`` θh by ``size // 2`` θd samples.  The solid,
    the lit sphere and the lit plane are drawn from the BRDF over the hemisphere at this light:
    their numbers are the map's."""
    from tuibrdf.core.views.frame import LINE_SAMPLES

    if view in ("map", "solid", "sphere", "plane"):
        return map_table(model, values, theta_i, phi_i, size)
    if view == "slice":
        return slice_table(model, values, phi_d, size, max(size // 2, 2), sqrt_h)
    if view in ("incidence", "perpendicular"):
        return section_table(model, values, theta_i, phi_i, view, section_azimuth,
                             cosine=cosine)
    if view == "albedo":
        return albedo_table(model, values, phi_i)
    if view in ("theta-h", "theta-d"):
        fixed = theta_d if view == "theta-h" else theta_h
        return halfdiff_table(model, values, view, fixed, phi_d, LINE_SAMPLES)
    raise ValueError(f"view {view!r} has no table of numbers: the views with one are "
                     f"{', '.join(IMAGE_TABLES + CURVE_TABLES)}")
