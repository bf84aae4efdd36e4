"""``render_view``: one call from (model, resolved values, θi, size) to a Rich renderable.

Views (:data:`VIEWS`):

=================  ================================================================================
``map``            Lambert equal-area map (:mod:`.hemimap`) as half blocks: a title line, the disc
                   (horizon ring, ``×`` on the mirror direction S, ``o`` on the incident direction's
                   Lambert point) and a colour bar with its min / mid / max values
``incidence``      polar cross-section in the plane of incidence (:mod:`.polar`)
``perpendicular``  polar cross-section in the perpendicular plane
``solid``          3D photometric solid (:mod:`.solid`)
``albedo``         directional albedo a(θi) over 0–90° (:mod:`.albedo_plot`)
=================  ================================================================================

``color``: ``truecolor``, ``256`` (quantised to the xterm palette before runs are merged) or
``none`` (plain text: the half-block pictures become the ASCII density ramp ``" .:-=+*#%@"``,
the plots lose their colours), so the output stays readable in a log file.  The output is
deterministic: the same arguments give the same bytes.

RGB models: ``rgb_mode="auto"`` shows the channels in colour with the ``grey`` map and the
Rec.709 luminance through any other map; ``"color"``/``"luminance"`` force one.
"""

from __future__ import annotations

from functools import lru_cache
from typing import Any

import numpy as np
from rich.console import Group, RenderableType
from rich.text import Text

from ..core.frame import incident
from ..core.models import get_model
from ..core.params import Model
from .colormap import CMAPS, DEFAULT_LEVELS, Scale, check_cmap, colorbar, colorize, fmt_value
from .halfblock import COLOR_SYSTEMS, HalfBlockImage, Mark
from .hemimap import DEFAULT_METHOD, MapInfo, dir_to_uv, geometry, map_values
from .text import title

VIEWS: tuple[str, ...] = ("map", "incidence", "perpendicular", "solid", "albedo")
__all__ = ["CMAPS", "VIEWS", "render_view", "map_view", "map_picture", "title_line"]

#: colour of the horizon ring drawn just outside the disc (not in any colour map's range of
#: greys, so "outside" never reads as a value)
RING_RGB = (70, 90, 130)
MIRROR_MARK = dict(glyph="×", ascii="X", rgb=(255, 40, 40))
INCIDENT_MARK = dict(glyph="o", ascii="o", rgb=(40, 220, 255))
MIN_WIDTH, MIN_HEIGHT = 12, 6


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


def render_view(
    view: str,
    model: Model | str,
    values: dict[str, Any],
    theta_i_deg: float,
    width: int,
    height: int,
    *,
    color: str = "truecolor",
    cmap: str = "grey",
    log: bool = False,
    cosine: bool = False,
    levels: int = DEFAULT_LEVELS,
    method: str = DEFAULT_METHOD,
    rgb_mode: str = "auto",
    azimuth_deg: float = -60.0,
    elevation_deg: float = 25.0,
) -> RenderableType:
    """The picture of ``view`` in ``width × height`` terminal cells (title line included).

    ``values`` are resolved (``model.resolve``); ``theta_i_deg`` in [0, 90].  Raises
    ``ValueError`` for an unknown view, colour system or map, or a size below 12×6.
    """
    model = get_model(model)  # a registry name is accepted too
    width, height = int(width), int(height)
    check_common(view, width, height, color, cmap)
    theta_i = float(theta_i_deg)
    if not 0.0 <= theta_i <= 90.0:
        raise ValueError(f"theta_i {theta_i_deg} out of range: expected 0..90 degrees")
    if view == "map":
        return map_view(model, values, theta_i, width, height, color=color, cmap=cmap, log=log,
                        cosine=cosine, levels=levels, method=method, rgb_mode=rgb_mode)
    if view in ("incidence", "perpendicular"):
        from .polar import section_view

        return section_view(view, model, values, theta_i, width, height, color=color, log=log,
                            cosine=cosine)
    if view == "solid":
        from .solid import solid_view

        return solid_view(model, values, theta_i, width, height, color=color, cmap=cmap,
                          cosine=cosine, log=log, azimuth_deg=azimuth_deg,
                          elevation_deg=elevation_deg)
    from .albedo_plot import albedo_view

    return albedo_view(model, values, theta_i, width, height, color=color)


def mark_legend(color: str) -> str:
    """``× mirror  o light`` with the glyphs the picture uses (ASCII ones in plain text)."""
    key = "ascii" if color == "none" else "glyph"
    return f"{MIRROR_MARK[key]} mirror  {INCIDENT_MARK[key]} light"


def title_line(model: Model, theta_i_deg: float, what: str, width: int,
               extra: str = "") -> Text:
    """``phong  θi=30°  <what>  <extra>`` fitted to ``width``: ``extra`` goes first, then
    θi, then the model name; ``what`` (the numbers) stays."""
    return title([(model.name, 2), (f"θi={theta_i_deg:g}°", 3), (what, 0), (extra, 4)], width)


@lru_cache(maxsize=16)
def ring_mask(px_w: int, px_h: int) -> np.ndarray:
    """Pixels outside the disc that touch it (8-neighbourhood): the horizon ring."""
    inside = geometry(px_w, px_h).inside
    grown = inside.copy()
    grown[1:] |= inside[:-1]
    grown[:-1] |= inside[1:]
    g2 = grown.copy()
    g2[:, 1:] |= grown[:, :-1]
    g2[:, :-1] |= grown[:, 1:]
    ring = g2 & ~inside
    ring.setflags(write=False)
    return ring


def map_view(
    model: Model,
    values: dict[str, Any],
    theta_i_deg: float,
    width: int,
    height: int,
    *,
    color: str = "truecolor",
    cmap: str = "grey",
    log: bool = False,
    cosine: bool = False,
    levels: int = DEFAULT_LEVELS,
    method: str = DEFAULT_METHOD,
    rgb_mode: str = "auto",
) -> Group:
    """Title, half-block map (``height − 3`` rows) and colour bar."""
    data, info = map_values(model, values, theta_i_deg, width, 2 * (height - 3), method=method,
                            cosine=cosine)
    return map_picture(data, info, theta_i_deg, width, label=model.name, color=color,
                       cmap=cmap, log=log, cosine=cosine, levels=levels, rgb_mode=rgb_mode)


def map_picture(
    data: np.ndarray,
    info: MapInfo,
    theta_i_deg: float,
    width: int,
    *,
    label: str,
    color: str = "truecolor",
    cmap: str = "grey",
    log: bool = False,
    cosine: bool = False,
    levels: int = DEFAULT_LEVELS,
    rgb_mode: str = "auto",
    scale: Scale | None = None,
) -> Group:
    """Title, disc and colour bar from :func:`~.hemimap.map_values`' output (``data`` is
    ``width`` pixels wide).  ``scale`` imposes a colour scale (compare mode: two maps on one
    scale); by default the data's own."""
    px_h, px_w = data.shape[:2]
    if rgb_mode == "auto":
        rgb_mode = "color" if cmap == "grey" else "luminance"
    col = colorize(data, cmap, levels=levels, log=log, rgb_mode=rgb_mode, scale=scale)
    ring_index = len(col.palette)
    index = np.where(ring_mask(px_w, px_h), ring_index, col.index)
    pal = np.concatenate([col.palette, np.array([RING_RGB], dtype=np.uint8)])
    marks = [Mark(info.mirror_px[0] // 2, info.mirror_px[1], **MIRROR_MARK)]
    wi_uv = dir_to_uv(incident(theta_i_deg))
    r, c = geometry(px_w, px_h).nearest_inside(wi_uv)
    if (r // 2, c) != (marks[0].row, marks[0].col):
        marks.append(Mark(r // 2, c, **INCIDENT_MARK))
    image = HalfBlockImage(index, pal, marks, color_system=color)
    what = "f·cosθr" if cosine else "f"
    unit = "sr⁻¹"  # f·cos θr is in sr⁻¹ too (the cosine has no unit)
    uniform = info.vmin >= info.peak_value * (1.0 - 1e-12)  # Lambert: no "the" peak
    if uniform:
        peak, where = f"{what} = {fmt_value(info.peak_value)} {unit}", "everywhere"
    else:  # ints: never "φ=-0°"
        th, ph = round(info.peak_theta_deg), round(info.peak_phi_deg)
        ph = ph + 360 if ph <= -180 else ph  # one convention: φ in (−180°, 180°]
        peak, where = f"{what} peak {fmt_value(info.peak_value)} {unit}", f"at θ={th}° φ={ph}°"
    bar_cmap = "grey" if (data.ndim == 3 and rgb_mode == "color") else cmap
    bar = colorbar(col.scale, bar_cmap, width, levels=levels, unit=unit, color_system=color)
    head = title([(label, 2), (f"θi={theta_i_deg:g}°", 3), (peak, 0),
                  (where, 1), (mark_legend(color), 4)], width)
    return Group(head, image, bar)
