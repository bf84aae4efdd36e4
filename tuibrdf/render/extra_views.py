"""The views of issue 13 behind one call, for ``tuibrdf render`` (and, later, the viewer).

=================  ================================================================================
``perpendicular``  section through the lobe's peak across the plane of incidence (or at any section
                   azimuth ψ; :mod:`.polar_braille`), replacing the plane through the normal
``sphere``         lit sphere (:mod:`.lit_view`)
``plane``          lit plane at the mirror view (:mod:`.lit_view`)
``slice``          θh × θd image at fixed φd (:mod:`.halfdiff_view`)
``theta-h``        f(θh) at fixed θd, φd
``theta-d``        f(θd) at fixed θh, φd
=================  ================================================================================

:func:`render_extra` takes the common arguments of ``views.render_view`` plus each view's own
(its fixed angles, exposure and gamma, section azimuth); arguments a view does not use are
ignored (``cosine`` for the lit and half/difference views, whose quantities are fixed: radiance,
and f in MERL's coordinates).
"""

from __future__ import annotations

from typing import Any

from rich.console import RenderableType

from ..core.halfdiff import DEFAULT_PHI_D
from ..core.lit import DEFAULT_EXPOSURE, DEFAULT_GAMMA
from ..core.models import get_model
from ..core.params import Model
from ..core.sections import PERPENDICULAR

EXTRA_VIEWS: tuple[str, ...] = ("perpendicular", "sphere", "plane", "slice", "theta-h",
                                "theta-d")
DEFAULT_THETA_D = 30.0
DEFAULT_THETA_H = 0.0


def render_extra(
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
    section_azimuth_deg: float = PERPENDICULAR,
    exposure: float = DEFAULT_EXPOSURE,
    gamma: float = DEFAULT_GAMMA,
    theta_d_deg: float = DEFAULT_THETA_D,
    theta_h_deg: float = DEFAULT_THETA_H,
    phi_d_deg: float = DEFAULT_PHI_D,
    sqrt_h: bool = True,
    charset: str = "braille",
) -> RenderableType:
    """The picture of ``view`` (one of :data:`EXTRA_VIEWS`) in ``width × height`` cells."""
    model = get_model(model)
    if view == "perpendicular":
        from .polar_braille import peak_section_view

        return peak_section_view(model, values, theta_i_deg, width, height,
                                 azimuth_deg=section_azimuth_deg, color=color, log=log,
                                 cosine=cosine, charset=charset)
    if view in ("sphere", "plane"):
        from .lit_view import lit_view

        return lit_view(view, model, values, theta_i_deg, width, height, exposure=exposure,
                        gamma=gamma, color=color)
    if view == "slice":
        from .halfdiff_view import slice_view

        return slice_view(model, values, width, height, phi_d_deg=phi_d_deg, sqrt_h=sqrt_h,
                          log=log, cmap=cmap, color=color)
    if view == "theta-h":
        from .halfdiff_view import theta_h_view

        return theta_h_view(model, values, width, height, theta_d_deg=theta_d_deg,
                            phi_d_deg=phi_d_deg, log=log, color=color, charset=charset)
    if view == "theta-d":
        from .halfdiff_view import theta_d_view

        return theta_d_view(model, values, width, height, theta_h_deg=theta_h_deg,
                            phi_d_deg=phi_d_deg, log=log, color=color, charset=charset)
    raise ValueError(f"unknown view {view!r}: expected one of {', '.join(EXTRA_VIEWS)}")
