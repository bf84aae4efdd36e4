"""What is drawn at a cell of a picture: the mouse's readouts and the light a drag sets.

Each picture's own geometry, inverted for one cell (the picture's first row is its title):

=================  =====================================================================
``sphere``         the lit sphere's normal N at the cell's centre
                   (:func:`tuibrdf.core.views.lit.sphere_geometry`); the light and the
                   view in N's local frame (:func:`~tuibrdf.core.views.lit.tangent_frames`)
``plane``          the lit plane's camera ray (:func:`~tuibrdf.core.views.lit.plane_rays`
                   at θv = θi, turned with φi): wo = −ray, wi the light
``slice``          θh (column) and θd (the cell's upper pixel row) at the slice's φd
                   (:func:`tuibrdf.core.views.halfdiff.directions`)
``theta-h``,       the x axis's angle at the cell's centre, the other angles fixed
``theta-d``
=================  =====================================================================

:func:`reading` evaluates the model at what :func:`pick` found and writes the status line's
text: where (the direction or angles the picture is drawn in), f per channel (one value
when the channels are equal) and f·cos θ of the direction the picture's cosine belongs to
(θi for the lit views: their radiance is f·cos θi·E; θr elsewhere).  The map and the
sections read through the probe
(:meth:`tuibrdf.state.viewer.ViewerState.set_probe`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from tuibrdf.core.evaluate import evaluate_resolved
from tuibrdf.core.views import halfdiff, lit
from tuibrdf.core.views.frame import FrameResult, turn
from tuibrdf.render.halfdiff_view import MARGIN
from tuibrdf.render.text import phi_deg_text


@dataclass(frozen=True)
class Pick:
    """What a cell shows: ``wi`` and ``wo`` in the surface's local frame (unit, ``(3,)``),
    ``where`` the picture's own coordinates as text, ``cos_of`` ``"θi"`` or ``"θr"``."""

    where: str
    wi: np.ndarray
    wo: np.ndarray
    cos_of: str = "θr"


def angles(w: np.ndarray) -> tuple[float, float]:
    """``(θ, φ)`` in degrees of a unit direction (φ in (−180°, 180°])."""
    th = math.degrees(math.acos(max(-1.0, min(1.0, float(w[2])))))
    return th, math.degrees(math.atan2(float(w[1]), float(w[0])))


def dir_text(name: str, w: np.ndarray) -> str:
    th, ph = angles(w)
    return f"{name} θ={th:.1f}° φ={phi_deg_text(ph) if th > 0.05 else '0'}°"


def _disc_xy(x: int, y: int, px: tuple[int, int]) -> tuple[float, float]:
    """Cell ``(x, y)`` of the lit sphere's pane in units of the disc's radius (x right, y up;
    the cell's centre lies between its two half-block pixels)."""
    px_w, px_h = px
    rad = min(px_w, px_h) / 2.0  # ≥ 0.5: a picture has a pixel at least
    return (x + 0.5 - px_w / 2.0) / rad, (px_h / 2.0 - (2.0 * (y - 1) + 1.0)) / rad


def sphere_normal(x: int, y: int, px: tuple[int, int]) -> np.ndarray | None:
    """The lit sphere's normal (world frame) at cell ``(x, y)`` of its pane, None off the
    disc or the title row."""
    px_w, px_h = px
    if y < 1 or not 0 <= x < px_w or 2 * (y - 1) + 1 > px_h:
        return None
    nx, ny = _disc_xy(x, y, px)
    r2 = nx * nx + ny * ny
    if r2 >= 1.0:
        return None
    return np.array([nx, ny, math.sqrt(1.0 - r2)])


def light_at(x: int, y: int, px: tuple[int, int]) -> tuple[float, float]:
    """``(θi, φi)`` that puts the light where the sphere's normal at cell ``(x, y)`` points
    (BRDF Explorer's lit sphere: drag the light over it); off the disc, on the horizon in the
    pointer's direction (θi = 90°)."""
    n = sphere_normal(x, y, px)
    if n is None:
        nx, ny = _disc_xy(x, y, px)
        return 90.0, math.degrees(math.atan2(ny, nx)) % 360.0
    th, ph = angles(n)
    return th, ph % 360.0


def pick(res: FrameResult, view: str, k: int, x: int, y: int, w: int, h: int) -> Pick | None:
    """What side ``k``'s ``view`` picture shows at cell ``(x, y)`` of its ``w × h`` pane, or
    None where it shows no direction (title, axes, outside the sphere, the plane's sky)."""
    req = res.request
    if view == "sphere" and req.extra_px is not None:
        n = sphere_normal(x, y, req.extra_px)
        if n is None:
            return None
        t, b = lit.tangent_frames(n)
        frame = np.stack([t, b, n])  # rows T, B, N: world → local
        wi, wo = frame @ req.wi, frame @ np.array([0.0, 0.0, 1.0])
        local = f"(θi={angles(wi)[0]:.1f}° θr={angles(wo)[0]:.1f}° there)"
        return Pick(f"{dir_text('N', n)} {local}", wi, wo, "θi")
    if view == "plane" and req.extra_px is not None:
        px_w, px_h = req.extra_px
        row = 2 * (y - 1)  # the cell's upper pixel (the ray through its centre may miss)
        if y < 1 or not 0 <= x < px_w or row + 1 >= px_h:
            return None
        d, hits = lit.plane_rays(px_w, px_h, req.theta_i)
        if not hits[row + 1, x]:
            return None
        ray = 0.5 * (d[row, x] + d[row + 1, x]) if hits[row, x] else d[row + 1, x]
        wo = -turn(ray, req.phi_i - 180.0)
        wo = wo / np.linalg.norm(wo)  # the mean of two unit rays: |·| > 0
        return Pick(dir_text("wo", wo), req.wi.copy(), wo, "θi")
    if view == "slice":
        if res.sides[k].extra is None:  # the slice could not be computed: its pane says why
            return None
        _, _, th, td = res.sides[k].extra
        col, r = x - MARGIN, y - 1
        n_d = len(td)
        if not 0 <= col < len(th) or not 0 <= r < n_d // 2:
            return None
        # the image is drawn θd up: the cell's upper pixel is θd sample n_d − 1 − 2r (the
        # value read is the one drawn there)
        return _halfdiff(float(th[col]), float(td[n_d - 1 - 2 * r]), req.phi_d)
    if view in ("theta-h", "theta-d"):
        plot_w = w - MARGIN
        col = x - MARGIN
        if not 0 <= col < plot_w or not 1 <= y < h - 1:
            return None
        a = 90.0 * (col + 0.5) / plot_w
        if view == "theta-h":
            return _halfdiff(a, req.theta_d, req.phi_d)
        return _halfdiff(req.theta_h, a, req.phi_d)
    return None


def _halfdiff(theta_h: float, theta_d: float, phi_d: float) -> Pick | None:
    wi, wo, valid = halfdiff.directions(theta_h, theta_d, phi_d)
    where = f"θh={theta_h:.1f}° θd={theta_d:.1f}° φd={phi_d:g}°"
    if not bool(valid):
        return Pick(where + " (below the horizon)", wi, wo)
    return Pick(where, wi, wo)


def values_text(v) -> str:
    """``0.31``, or ``(0.1,0.2,0.3)`` for unequal channels (equal ones: one value)."""
    v = np.atleast_1d(np.asarray(v, dtype=float))
    texts = [f"{float(x):.3g}" for x in v]
    return texts[0] if len(set(texts)) == 1 else "(" + ",".join(texts) + ")"


def reading(res: FrameResult, p: Pick) -> str:
    """The status line's readout of ``p`` for every side: where, the two directions, f and
    f·cos θ (per channel)."""
    parts = [p.where]
    cos = float(p.wi[2] if p.cos_of == "θi" else p.wo[2])
    for k, side in enumerate(res.sides):
        m = side.material
        f = np.asarray(evaluate_resolved(m.model, m.values, p.wi, p.wo), dtype=float)
        tag = f"{'AB'[k]}: " if len(res.sides) > 1 else ""
        parts.append(f"{tag}f={values_text(f)} f·cos{p.cos_of}={values_text(f * max(cos, 0.0))}"
                     " sr⁻¹")
    return "  ".join(parts)


def albedo_reading(res: FrameResult, rows: list[str], x: int) -> str | None:
    """A click on the albedo plot at column ``x``: ``a(θi=47°)=0.71`` per side, θi from the
    plot's own x axis as drawn (``rows``: the pane's text; the axis line's first and last
    tick are 0° and 90°), None off the axis's span or before the curve is computed."""
    from tuibrdf.core.views.frame import CURVE_THETAS

    axis = next((r for r in reversed(rows) if "└" in r and "┘" in r), None)
    ticks = [c for c, ch in enumerate(axis or "") if ch in "┬┴"]
    if len(ticks) < 2 or not ticks[0] <= x <= ticks[-1]:
        return None
    theta = 90.0 * (x - ticks[0]) / (ticks[-1] - ticks[0])  # two ticks: a span > 0
    parts = [f"a(θi={theta:.0f}°)"]
    for k, side in enumerate(res.sides):
        if side.curve is None:
            return None
        c = np.asarray(side.curve, dtype=float)
        a = np.interp(theta, CURVE_THETAS, c) if c.ndim == 1 else np.array(
            [np.interp(theta, CURVE_THETAS, c[:, j]) for j in range(c.shape[1])])
        parts.append(f"{'AB'[k] + ': ' if len(res.sides) > 1 else ''}a={values_text(a)}")
    return "  ".join(parts)
