"""The lit sphere and the lit plane as half-block pictures (:mod:`tuibrdf.core.views.lit`).

:func:`lit_picture` draws the frame's radiance (:mod:`tuibrdf.core.views.frame`) as a title
line and the tone-mapped image in ``width × (height − 1)`` cells (``width × 2(height − 1)``
square pixels).  Outside the sphere the terminal background shows; above the plane's horizon a
dim sky colour (nothing in plain text).  The title gives the brightest radiance in the picture
(in units of the white Lambert surface facing the light, see :mod:`tuibrdf.core.views.lit`),
the exposure and gamma, and how much of the surface clips at white.

Tone mapping: ``clamp(exposure · L, 0, 1) ^ (1/γ)`` (a pure power law, γ = 2.2 by default).  In
truecolor the 8-bit result is drawn on :data:`~tuibrdf.render.halfblock.SHADES` levels per
channel (≤ 2/255 off; an export keeps every bit).
"""

from __future__ import annotations

import numpy as np
from rich.console import Group

from tuibrdf.core.conventions import fmt_value
from tuibrdf.core.display import DISPLAY
from tuibrdf.core.views.lit import DEFAULT_FOV_DEG
from tuibrdf.core.views.lit import tone_map as tone_map_core
from tuibrdf.render.halfblock import SHADES, HalfBlockImage
from tuibrdf.render.text import title

#: above the plane's horizon (colour modes only): dark enough never to read as lit surface
SKY_RGB = (26, 32, 52)


def lit_picture(kind: str, name: str, theta_i_deg: float, rad: np.ndarray, mask: np.ndarray,
                width: int, *, exposure: float = DISPLAY.exposure.default,
                gamma: float = DISPLAY.gamma.default,
                color: str = "truecolor", fov_deg: float = DEFAULT_FOV_DEG) -> Group:
    """Title + the half-block picture of radiance ``rad`` (``(px_h, px_w, 3)``, the frame's)
    tone-mapped with ``exposure`` and ``gamma``."""
    img = tone_map_core(rad, exposure, gamma)
    n_surface = int(np.count_nonzero(mask))
    if kind == "plane" and color != "none":
        img = np.where(mask[..., None], img, np.array(SKY_RGB, dtype=np.uint8))
        mask = np.ones_like(mask)
    image = HalfBlockImage.from_rgb(img, mask=mask, color_system=color, shades=SHADES)
    lum = rad.max(axis=-1)
    peak = float(lum.max()) if lum.size else 0.0
    clipped = int(np.count_nonzero(lum * exposure >= 1.0))
    what = "lit sphere" if kind == "sphere" else "lit plane"
    how = "" if kind == "sphere" else f"(mirror view, fov {fov_deg:g}°)"
    clip = f"{100.0 * clipped / max(n_surface, 1):.0f}% clipped" if clipped else ""
    head = title([(name, 1), (f"θi={theta_i_deg:g}°", 3), (what, 0), (how, 6),
                  (f"L max {fmt_value(peak)}", 2), (f"exp {exposure:g} γ {gamma:g}", 4),
                  (clip, 5)], width)
    return Group(head, image)
