"""A view as a pixel picture (the PNG of ``tuibrdf render --format png``, the inline images,
the viewer's ``w`` key, :func:`tuibrdf.picture`): the same pixels the half-block picture is
made of, one pixel per sample, at ``size`` pixels across.

The picture is the pane's own (:func:`tuibrdf.render.panes.pane`, through
:func:`tuibrdf.render.views.render_view`) drawn with ``size`` cells across, so it has the
same colour scale, colour map, horizon ring and palette as the terminal's; here its pixels
are taken as they are (:class:`~tuibrdf.render.halfblock.HalfBlockImage`'s ``index`` and
``palette``) and laid out with:

- the marks drawn as pixels (map: a red ring around the mirror direction's pixel, a cyan
  one around the light's Lambert point; the rings leave the marked pixel itself as it is);
- the colour bar (map, slice) below the picture, stretched to its width, 0 (or 3 decades
  below the top, in log) on the left to the top on the right;
- a white background where the picture has none (outside the disc, the sphere).

The numbers of the scale and the view's settings go in the PNG's text chunks (no font is
drawn).  Line views (sections, albedo, θh, θd) have no pixel picture: their numbers are
tables (:mod:`tuibrdf.core.views.tables`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from rich.text import Text

from tuibrdf.render.halfblock import TRANSPARENT, HalfBlockImage
from tuibrdf.render.text import INCIDENT_MARK, MIRROR_MARK

#: the views with a pixel picture
IMAGE_VIEWS = ("map", "slice", "sphere", "plane", "solid")
BACKGROUND = (255, 255, 255)
DEFAULT_SIZE = 512
#: a 2048² map is 4 M directions: ≈ 0.4 GB of arrays for its numbers (NPZ) at most
MIN_SIZE, MAX_SIZE = 32, 2048
#: colour levels of a picture: with the ring, the marks, the background and the bar's own
#: levels merged in, a palette PNG (≤ 256 colours)
LEVELS = 240


@dataclass(frozen=True)
class Figure:
    """A palette picture: ``index`` ``(H, W)`` into ``palette`` ``(n, 3)`` uint8 (n may exceed
    256 for a lit view's colours), and text for the PNG's chunks."""

    index: np.ndarray
    palette: np.ndarray
    text: dict[str, str]

    @property
    def rgb(self) -> np.ndarray:
        return self.palette[self.index]

    def png(self) -> bytes:
        from tuibrdf.render.export.png import encode

        return encode(self.index, self.palette, self.text)


def _parts(r: Any, kind: type) -> list:
    """The parts of a renderable tree that are ``kind`` (half-block images, texts), in
    drawing order."""
    if isinstance(r, kind):
        return [r]
    out: list = []
    for child in getattr(r, "renderables", None) or ():
        out += _parts(child, kind)
    body = getattr(r, "body", None)
    if body is not None:
        out += _parts(body, kind)
    return out


def cells_for(view: str, size: int) -> tuple[int, int]:
    """The pane size in cells whose picture is ``size`` pixels across (and as tall)."""
    if view == "map":
        return size, size // 2 + 3
    if view == "slice":
        from tuibrdf.render.halfdiff_view import MARGIN

        return size + MARGIN, size // 4 + 4  # θh × θd: twice as wide as tall
    return size, size // 2 + 1  # sphere, plane, solid: a title line above


def ring_pixels(shape: tuple[int, int], row: float, col: float, radius: float) -> np.ndarray:
    """The pixels whose centres lie within half a pixel of the circle of ``radius`` about
    the centre of pixel ``(row, col)``."""
    ys, xs = np.mgrid[0:shape[0], 0:shape[1]]
    d = np.hypot(ys - row, xs - col)
    return np.abs(d - radius) <= 0.75


def figure(view: str, model: Any, values: dict[str, Any], theta_i: float, size: int = DEFAULT_SIZE,
           **look: Any) -> Figure:
    """The pixel picture of image view ``view`` (:data:`IMAGE_VIEWS`) about ``size`` pixels
    across; ``look``: :func:`~tuibrdf.render.views.render_view`'s keywords (colour map, log,
    exposure, …; ``color`` is always truecolor here)."""
    from tuibrdf.core.material import Material
    from tuibrdf.core.views.frame import compute_frame
    from tuibrdf.render.views import render_view, request_for

    if view not in IMAGE_VIEWS:
        raise ValueError(f"view {view!r} has no pixel picture (PNG): the image views are "
                         f"{', '.join(IMAGE_VIEWS)}")
    if not MIN_SIZE <= int(size) <= MAX_SIZE:
        raise ValueError(f"size {size}: expected {MIN_SIZE} to {MAX_SIZE} pixels")
    w, h = cells_for(view, int(size))
    look = {k: v for k, v in look.items() if k != "color"}
    look.setdefault("levels", LEVELS)
    r = render_view(view, model, values, theta_i, w, h, color="truecolor", **look)
    images = _parts(r, HalfBlockImage)
    if not images:  # the view could not be computed: its pane's text says why
        texts = _parts(r, Text)
        raise ValueError(" ".join(texts[-1].plain.split()) if texts else f"no {view} picture")
    main = images[0]
    index, pal = main.index.copy(), np.asarray(main.palette, dtype=np.uint8)
    extra = [BACKGROUND]
    bg = len(pal)
    index[index == TRANSPARENT] = bg
    rings = []
    if view == "map":
        req = request_for("map", (Material(model, values),), float(theta_i), w, h,
                          cosine=bool(look.get("cosine", False)),
                          **_request_extras(look))
        info = compute_frame(req, slow=False).sides[0].map[1]  # cached: render_view made it
        radius = max(3.0, size / 64)
        rings = [(info.incident_px, INCIDENT_MARK["rgb"]), (info.mirror_px, MIRROR_MARK["rgb"])]
        for k, ((row, col), rgb) in enumerate(rings):
            index[ring_pixels(index.shape, row, col, radius)] = bg + 1 + k
            extra.append(rgb)
    parts = [index]
    if len(images) > 1:  # the colour bar: stretched to the picture's width, below a gap
        bar = images[-1]
        cols = (np.arange(index.shape[1]) * bar.width) // index.shape[1]
        bar_row = bar.index[0, cols] + len(pal) + len(extra)
        bar_h = max(6, index.shape[0] // 24)
        parts += [np.full((max(2, bar_h // 2), index.shape[1]), bg),
                  np.repeat(bar_row[None, :], bar_h, axis=0)]
        full = np.concatenate([pal, np.array(extra, dtype=np.uint8), bar.palette])
    else:
        full = np.concatenate([pal, np.array(extra, dtype=np.uint8)])
    out = np.concatenate(parts, axis=0)
    return _compact(out, full, _text(view, model, values, theta_i, look, r))


def _request_extras(look: dict[str, Any]) -> dict[str, Any]:
    from tuibrdf.core.display import DISPLAY

    return {"section_azimuth": float(look.get("section_azimuth_deg",
                                              DISPLAY.section_azimuth.default)),
            "theta_d": float(look.get("theta_d_deg", DISPLAY.theta_d.default)),
            "theta_h": float(look.get("theta_h_deg", DISPLAY.theta_h.default)),
            "phi_d": float(look.get("phi_d_deg", DISPLAY.phi_d.default)),
            "sqrt_h": bool(look.get("sqrt_h", DISPLAY.sqrt_h)),
            "phi_i": float(look.get("phi_i_deg", DISPLAY.phi_i.default)),
            "method": look.get("method", "exact")}


def _compact(index: np.ndarray, palette: np.ndarray, text: dict[str, str]) -> Figure:
    """Drop palette entries no pixel uses and merge equal colours (a palette PNG holds 256):
    the first use of a colour keeps the lowest index, so the palette's order is the
    picture's, the same for the same picture."""
    used = np.unique(index)
    colours, first = np.unique(palette[used], axis=0, return_index=True)
    order = np.argsort(first, kind="stable")
    colours = colours[order]
    remap = np.empty(len(palette), dtype=np.int64)
    code = {tuple(int(x) for x in c): k for k, c in enumerate(colours)}
    for i in used:
        remap[i] = code[tuple(int(x) for x in palette[i])]
    return Figure(remap[index], colours.astype(np.uint8), text)


def _text(view: str, model: Any, values: dict[str, Any], theta_i: float, look: dict[str, Any],
          renderable: Any) -> dict[str, str]:
    import json

    from tuibrdf.core.params import Model

    name = model.name if isinstance(model, Model) else str(model)
    params = {k: (list(v) if isinstance(v, tuple) else v) for k, v in values.items()}
    text = {"Software": "tuibrdf", "Title": f"tuibrdf {view} of {name}",
            "tuibrdf": json.dumps({"view": view, "model": name, "params": params,
                                   "theta_i": float(theta_i),
                                   **{k: v for k, v in look.items()
                                      if isinstance(v, int | float | str | bool)}},
                                  sort_keys=True, default=str)}
    first = getattr(renderable, "renderables", None)
    if first:  # the title line: the peak, the scale
        plain = getattr(first[0], "plain", None)
        if isinstance(plain, str):
            text["Description"] = plain.strip()
    return text
