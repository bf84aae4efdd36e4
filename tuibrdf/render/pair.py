"""``render_pair``: the picture of two BRDFs compared (``tuibrdf render A --compare B``), from
one :class:`~tuibrdf.core.views.frame.FrameRequest` of both materials, as the viewer's compare
mode draws it: each side's map and the A − B map, both sections' curves in one plot, both
solids on one scale, both albedo curves; then the numbers line (albedos, ``rel_l2``, the
largest difference: :mod:`tuibrdf.core.sphere.compare`).
"""

from __future__ import annotations

from typing import Any

from rich.console import Group, RenderableType
from rich.text import Text

from tuibrdf.core.display import DISPLAY
from tuibrdf.core.material import Material
from tuibrdf.core.params import Model
from tuibrdf.core.views.frame import compute_frame
from tuibrdf.render.colormap import DEFAULT_LEVELS
from tuibrdf.render.panes import Look, albedo_text, compare_text, pane
from tuibrdf.render.views import check_common, request_for

#: the panes of each view in compare mode: (pane, side)
PAIR_PANES = {"map": (("map", 0), ("map", 1), ("diff", 0)), "solid": (("solid", 0), ("solid", 1)),
              "incidence": (("incidence", 0),), "perpendicular": (("perpendicular", 0),),
              "albedo": (("albedo", 0),)}


def numbers_line(res, width: int) -> Text:
    """``A: a=0.04  B: a=0.09  rel_l2 0.802 (vs B) · max Δ …``: the frame's compare numbers,
    shortened (:func:`.panes.compare_text`'s terse forms) to fit ``width`` when it can."""
    for albedos, terse in ((True, 0), (True, 1), (False, 1)):
        line = Text(f"θi={res.request.theta_i:g}°")
        for k, side in enumerate(res.sides if albedos else ()):
            line.append(f"  {'AB'[k]}: a={albedo_text(side.albedo, side.albedo_error)}")
        line.append_text(compare_text(res.numbers, terse))
        if line.cell_len <= width:
            return line
    n = res.numbers  # the narrowest: rel_l2 alone
    rel = "—" if n is None or n.rel_l2 is None else albedo_text(n.rel_l2, n.rel_l2_error)
    return Text(f"θi={res.request.theta_i:g}° rel_l2 {rel}")


def render_pair(view: str, a: tuple[Model | str, dict[str, Any]],
                b: tuple[Model | str, dict[str, Any]], theta_i_deg: float, width: int,
                height: int, *, color: str = "truecolor", cmap: str = DISPLAY.cmap,
                log: bool = False, cosine: bool = False, levels: int = DEFAULT_LEVELS,
                rgb_mode: str = "auto", azimuth_deg: float = DISPLAY.azimuth.default,
                elevation_deg: float = DISPLAY.elevation.default, charset: str = "braille",
                exposure: float = DISPLAY.exposure.default,
                gamma: float = DISPLAY.gamma.default,
                section_azimuth_deg: float = DISPLAY.section_azimuth.default,
                theta_d_deg: float = DISPLAY.theta_d.default,
                theta_h_deg: float = DISPLAY.theta_h.default,
                phi_d_deg: float = DISPLAY.phi_d.default, sqrt_h: bool = DISPLAY.sqrt_h,
                phi_i_deg: float = DISPLAY.phi_i.default) -> RenderableType:
    """The panes of ``view`` for sides ``a`` and ``b`` (model, resolved values), each
    ``width × height`` cells, one below the other, and the numbers line; the options as
    :func:`.views.render_view`'s."""
    width, height = int(width), int(height)
    check_common(view, width, height, color, cmap)
    mats = (Material(*a), Material(*b))
    req = request_for(view, mats, float(theta_i_deg), width, height, cosine=cosine,
                      section_azimuth=float(section_azimuth_deg), theta_d=float(theta_d_deg),
                      theta_h=float(theta_h_deg), phi_d=float(phi_d_deg), sqrt_h=bool(sqrt_h),
                      phi_i=float(phi_i_deg))
    res = compute_frame(req, slow=True)
    look = Look(color, cmap, log, levels, rgb_mode, azimuth_deg, elevation_deg, exposure, gamma,
                charset)
    panes = PAIR_PANES.get(view) or (("extra", 0), ("extra", 1))
    out: list[RenderableType] = []
    for i, (name, k) in enumerate(panes):
        if i:
            out.append(Text(""))
        out.append(pane(name, res, k, width, height, look))
    out += [Text(""), numbers_line(res, width)]
    return Group(*out)


__all__ = ["PAIR_PANES", "render_pair"]
