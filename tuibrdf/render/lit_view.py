"""The lit sphere and the lit plane as half-block pictures (:mod:`tuibrdf.core.lit`).

``lit_view(kind, ...)`` draws a title line and the tone-mapped image in ``width × (height − 1)``
cells (``width × 2(height − 1)`` square pixels).  Outside the sphere the terminal background
shows; above the plane's horizon a dim sky colour (nothing in plain text).  The title gives the
brightest radiance in the picture (in units of the white Lambert surface facing the light, see
``core/lit.py``), the exposure and gamma, and how much of the surface clips at white.

Tone mapping: ``clamp(exposure · L, 0, 1) ^ (1/γ)`` (a pure power law, default γ = 2.2).  In
truecolor the 8-bit result is drawn on :data:`LEVELS` levels per channel (≤ 2/255 off): a
shaded sphere then has ~1,750 runs of equal cells instead of ~2,600, and a key's picture
costs ~4 ms instead of ~15–20 ms (every new colour is a new terminal style).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from rich.console import Group

from ..core.lit import DEFAULT_EXPOSURE, DEFAULT_FOV_DEG, DEFAULT_GAMMA, lit_plane, lit_sphere
from ..core.lit import tone_map as tone_map_core
from ..core.numerics import snapped_rint
from ..core.params import Model
from .colormap import fmt_value
from .halfblock import HalfBlockImage
from .text import title

KINDS = ("sphere", "plane")
#: levels per channel of the drawn picture (see the module docstring)
LEVELS = 64
#: above the plane's horizon (colour modes only): dark enough never to read as lit surface
SKY_RGB = (26, 32, 52)


def lit_arrays(
    kind: str,
    model: Model,
    values: dict[str, Any],
    theta_i_deg: float,
    px_w: int,
    px_h: int,
    *,
    exposure: float = DEFAULT_EXPOSURE,
    gamma: float = DEFAULT_GAMMA,
    fov_deg: float = DEFAULT_FOV_DEG,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(radiance, image, mask)``: linear RGB radiance ``(px_h, px_w, 3)``, the tone-mapped
    ``uint8`` image and the pixels that show the surface."""
    if kind not in KINDS:
        raise ValueError(f"unknown lit view {kind!r}: expected one of {', '.join(KINDS)}")
    if kind == "sphere":
        rad, mask = lit_sphere(model, values, theta_i_deg, px_w, px_h)
    else:
        rad, mask = lit_plane(model, values, theta_i_deg, px_w, px_h, fov_deg=fov_deg)
    return rad, tone_map_core(rad, exposure, gamma), mask


def lit_view(
    kind: str,
    model: Model,
    values: dict[str, Any],
    theta_i_deg: float,
    width: int,
    height: int,
    *,
    exposure: float = DEFAULT_EXPOSURE,
    gamma: float = DEFAULT_GAMMA,
    color: str = "truecolor",
    fov_deg: float = DEFAULT_FOV_DEG,
) -> Group:
    """Title + the half-block picture of the lit ``kind`` (``sphere`` or ``plane``)."""
    px_w, px_h = int(width), 2 * (int(height) - 1)
    rad, _, mask = lit_arrays(kind, model, values, theta_i_deg, px_w, px_h,
                              exposure=exposure, gamma=gamma, fov_deg=fov_deg)
    return lit_picture(kind, model.name, theta_i_deg, rad, mask, width, exposure=exposure,
                       gamma=gamma, color=color, fov_deg=fov_deg)


def quantise_rgb(img: np.ndarray, levels: int = LEVELS) -> np.ndarray:
    """8-bit colours rounded to the nearest of ``levels`` evenly spaced values (0 and 255
    kept); each rounding decided on the snapped value (core.numerics.snap)."""
    step = 255.0 / (levels - 1)  # levels ≥ 2
    return snapped_rint(snapped_rint(img / step) * step).astype(np.uint8)


def lit_picture(kind: str, name: str, theta_i_deg: float, rad: np.ndarray, mask: np.ndarray,
                width: int, *, exposure: float = DEFAULT_EXPOSURE, gamma: float = DEFAULT_GAMMA,
                color: str = "truecolor", fov_deg: float = DEFAULT_FOV_DEG) -> Group:
    """Title + the half-block picture of radiance ``rad`` (``(px_h, px_w, 3)``, from
    :func:`lit_arrays` or the frame) tone-mapped with ``exposure`` and ``gamma``."""
    img = tone_map_core(rad, exposure, gamma)
    if color == "truecolor":  # 256 colours and plain text quantise on their own
        img = quantise_rgb(img)
    n_surface = int(np.count_nonzero(mask))
    if kind == "plane" and color != "none":
        img = np.where(mask[..., None], img, np.array(SKY_RGB, dtype=np.uint8))
        mask = np.ones_like(mask)
    image = HalfBlockImage.from_rgb(img, mask=mask, color_system=color)
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
