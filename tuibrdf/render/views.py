"""``render_view``: one call from (model, resolved values, θi, size) to a Rich renderable.

Views (:data:`VIEWS`, declared in :mod:`tuibrdf.render`):

=================  ==========================================================================
``map``            Lambert equal-area map (:mod:`~tuibrdf.core.views.hemimap`) as half blocks:
                   a title line with the peak, the disc (horizon ring, ``×`` on the mirror
                   direction S, ``o`` on the incident direction's Lambert point) and a colour
                   bar from 0 (or 3 decades below, in log) to the peak
``incidence``      polar cross-section in the plane of incidence (:mod:`.sections`)
``perpendicular``  polar cross-section through the lobe's peak, across the plane of incidence
                   (turned by ``section_azimuth_deg``)
``solid``          3D photometric solid (:mod:`.solid`)
``albedo``         directional albedo a(θi) over 0–90° (:mod:`.albedo_plot`)
``sphere``         the material on a sphere lit from θi (:mod:`.lit_view`)
``plane``          a large plane lit from θi, seen along the mirror direction
                   (:mod:`.lit_view`)
``slice``          f over θh × θd at fixed φd (:mod:`.halfdiff_view`)
``theta-h``        f against θh at fixed θd and φd (:mod:`.halfdiff_view`)
``theta-d``        f against θd at fixed θh and φd (:mod:`.halfdiff_view`)
``energy``         directional albedo E(μ, p) over μ = cos θi and the first real parameter,
                   with E_avg(p) and the white-furnace verdict (:mod:`.energy_view`)
=================  ==========================================================================

The numbers come from one :class:`~tuibrdf.core.views.frame.FrameRequest` (the same computation the
viewer uses), the picture from :func:`tuibrdf.render.panes.pane`.

``color``: ``truecolor``, ``256`` (quantised to the xterm palette before runs are merged) or
``none`` (plain text: the half-block pictures become the ASCII density ramp ``" .:-=+*#%@"``,
the plots lose their colours), so the output stays readable in a log file.  The output is
deterministic: the same arguments give the same bytes.

RGB models: ``rgb_mode="auto"`` shows the channels in colour with the ``grey`` map and the
Rec.709 luminance through any other map; ``"color"``/``"luminance"`` force one.
"""

from __future__ import annotations

from typing import Any

from rich.console import RenderableType

from tuibrdf.core.display import DISPLAY
from tuibrdf.core.material import Material
from tuibrdf.core.params import Model
from tuibrdf.core.views.frame import FrameRequest, compute_frame
from tuibrdf.core.views.hemimap import DEFAULT_METHOD
from tuibrdf.render import CMAPS, EXTRA_VIEWS, MIN_HEIGHT, MIN_WIDTH, VIEWS
from tuibrdf.render.colormap import DEFAULT_LEVELS, check_cmap
from tuibrdf.render.halfblock import COLOR_SYSTEMS
from tuibrdf.render.panes import Look, pane

__all__ = ["CMAPS", "VIEWS", "MIN_WIDTH", "MIN_HEIGHT", "render_view", "request_for"]


def check_common(view: str, width: int, height: int, color: str, cmap: str) -> None:
    if view not in VIEWS:
        raise ValueError(f"unknown view {view!r}: expected one of {', '.join(VIEWS)}")
    if color not in COLOR_SYSTEMS:
        raise ValueError(f"color {color!r}: expected one of {', '.join(COLOR_SYSTEMS)}")
    check_cmap(cmap)
    if width < MIN_WIDTH or height < MIN_HEIGHT:
        raise ValueError(
            f"view size {width}×{height} too small: at least {MIN_WIDTH}×{MIN_HEIGHT} cells"
        )


def map_pixels(width: int, height: int) -> tuple[int, int]:
    """The map's pixel grid in a ``width × height`` pane: a title line and a two-row colour
    bar leave ``height − 3`` rows of two half-block pixels."""
    return int(width), 2 * (int(height) - 3)


def extra_pixels(view: str, width: int, height: int) -> tuple[int, int] | None:
    """The pixel (sample) grid of an extra view in a ``width × height`` pane: the lit views a
    title line above half-block pixels, the slice :func:`.halfdiff_view.slice_pixels`."""
    if view in ("sphere", "plane"):
        return int(width), 2 * (int(height) - 1)
    if view == "slice":
        from tuibrdf.render.halfdiff_view import slice_pixels

        return slice_pixels(width, height)
    return None


def request_for(view: str, materials: tuple[Material, ...], theta_i_deg: float, width: int,
                height: int, *, cosine: bool = False, method: str = DEFAULT_METHOD,
                **extra: Any) -> FrameRequest:
    """The frame request of ``view`` in a ``width × height`` pane; ``extra``: the request's
    section azimuth and fixed angles (:class:`~tuibrdf.core.views.frame.FrameRequest`)."""
    ex = view if view in EXTRA_VIEWS else None
    return FrameRequest(materials, theta_i_deg, cosine=cosine and view != "albedo",
                        map_px=map_pixels(width, height) if view == "map" else None,
                        map_method=method, solid=view == "solid", curve=view == "albedo",
                        extra=ex, extra_px=extra_pixels(view, width, height) if ex else None,
                        **extra)


def render_view(
    view: str,
    model: Model | str,
    values: dict[str, Any],
    theta_i_deg: float,
    width: int,
    height: int,
    *,
    color: str = "truecolor",
    cmap: str = DISPLAY.cmap,
    log: bool = False,
    cosine: bool = False,
    levels: int = DEFAULT_LEVELS,
    method: str = DEFAULT_METHOD,
    rgb_mode: str = "auto",
    azimuth_deg: float = DISPLAY.azimuth.default,
    elevation_deg: float = DISPLAY.elevation.default,
    section_azimuth_deg: float = DISPLAY.section_azimuth.default,
    exposure: float = DISPLAY.exposure.default,
    gamma: float = DISPLAY.gamma.default,
    theta_d_deg: float = DISPLAY.theta_d.default,
    theta_h_deg: float = DISPLAY.theta_h.default,
    phi_d_deg: float = DISPLAY.phi_d.default,
    sqrt_h: bool = DISPLAY.sqrt_h,
    charset: str = "braille",
    phi_i_deg: float = DISPLAY.phi_i.default,
) -> RenderableType:
    """The picture of ``view`` in ``width × height`` terminal cells (title line included).

    ``values`` are validated again (a :class:`~tuibrdf.core.material.Material` is built);
    ``theta_i_deg`` in [0, 90]; the look's defaults are :data:`~tuibrdf.core.display.DISPLAY`'s.
    Raises ``ValueError`` for an unknown view, colour system or map, or a size below 12×6.
    """
    width, height = int(width), int(height)
    check_common(view, width, height, color, cmap)
    theta_i = float(theta_i_deg)
    if not DISPLAY.theta_i.accepts(theta_i):
        raise ValueError(f"theta_i {theta_i_deg} out of range: expected "
                         f"{DISPLAY.theta_i.lo:g}..{DISPLAY.theta_i.hi:g} degrees")
    req = request_for(view, (Material(model, values),), theta_i, width, height, cosine=cosine,
                      method=method, section_azimuth=float(section_azimuth_deg),
                      theta_d=float(theta_d_deg), theta_h=float(theta_h_deg),
                      phi_d=float(phi_d_deg), sqrt_h=bool(sqrt_h), phi_i=float(phi_i_deg))
    res = compute_frame(req, slow=view == "albedo")
    look = Look(color, cmap, log, levels, rgb_mode, azimuth_deg, elevation_deg, exposure, gamma,
                charset)
    return pane("extra" if view in EXTRA_VIEWS else view, res, 0, width, height, look)
