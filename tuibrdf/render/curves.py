"""The curves the plots draw, and how they are told apart: the sections (:mod:`.sections`), the
albedo curve (:mod:`.albedo_plot`) and the f(θh), f(θd) plots (:mod:`.halfdiff_view`).

An RGB model's values become one curve per channel, its luminance, or one channel
(:func:`channel_curves`, the viewer's ``C`` key); in compare mode each side's curves are
labelled ``A:``/``B:`` and drawn in the side's own style, so the sides differ in every colour
mode (:func:`side_curves`).  A curve is ``(label, θ degrees, values)``, with the side's marker
and colour after them in compare mode.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

#: curve colours in order (names both Rich and plotext know, from the 16-colour palette:
#: readable on dark and light terminals)
CURVE_COLORS = ("red", "cyan", "green", "magenta", "yellow", "blue")
#: (label, θ degrees, values[, side marker, colour]): compare mode gives each side its own
#: marker (a line style that survives every colour mode) and the channels their colours
Curve = tuple
#: the marker of each side in compare mode, as plotext names them (A braille dots, B a '+'
#: per sample); the sections draw each side with its own dot pattern instead
#: (:data:`.sections.SIDE_PATTERNS`)
SIDE_MARKERS = ("braille", "+")
#: each compare side's hue family, whatever the channel (A orange, B violet: apart for the
#: common colour-vision deficiencies, and neither is the light's cyan nor the guides' grey):
#: the side's own colour (a scalar side, or the luminance), then its R, G, B shades (the
#: channels told apart by lightness and their legend, the sides by hue and dot pattern)
SIDE_HUES = (("#ff8c1a", "#ffb366", "#ff8c1a", "#b35900"),
             ("#b266ff", "#d9b3ff", "#b266ff", "#7a29cc"))
#: an RGB channel where a side may be named too (compare mode's legends, a peak's channel):
#: in words, so that "B" only ever means side B, never the blue channel; also its colour
CHANNEL_WORDS = {"R": "red", "G": "green", "B": "blue"}


def curve_color(label: str, j: int) -> str:
    """Channel curves R, G, B in their own colour, other curves in :data:`CURVE_COLORS` order."""
    return CHANNEL_WORDS.get(label, CURVE_COLORS[j % len(CURVE_COLORS)])


def channel_curves(label: str, values: np.ndarray, channel: str = "rgb"
                   ) -> list[tuple[str, np.ndarray]]:
    """``[(label, v)]`` for ``(n,)`` values; for ``(n, 3)`` the ``channel`` choice: ``rgb``
    ``[("R", r), ("G", g), ("B", b)]``, ``lum`` the Rec.709 luminance, or one of R, G, B."""
    if values.ndim != 2:
        return [(label, values)]
    if values.shape[-1] == 3 and np.array_equal(values[:, 0], values[:, 1]) and \
            np.array_equal(values[:, 0], values[:, 2]):
        return [(label, values[:, 0])]  # a grey model (R = G = B): one curve, its own name
    if channel == "lum":
        from tuibrdf.core.conventions import luminance

        return [("lum", luminance(values))]
    if channel in ("R", "G", "B"):
        return [(channel, values[:, "RGB".index(channel)])]
    return [(ch, values[:, k]) for k, ch in enumerate("RGB")]


def side_curves(sides: Sequence[tuple[str, np.ndarray]], channel: str = "rgb") -> list[tuple]:
    """The curves of one or two sides ``(label, values)``: alone, :func:`channel_curves`
    (``"all"`` is ``"rgb"``); in compare mode each label prefixed ``A:``/``B:`` and each side
    drawn with its own marker (:data:`SIDE_MARKERS`) in its own hue family
    (:data:`SIDE_HUES`), so the sides differ in every colour mode; an RGB side shows its
    luminance for ``"rgb"`` (six curves in one plot cannot be read) and its three channels
    only for ``"all"``.  Items: ``(label, values, marker, colour)``."""
    if len(sides) == 1:
        channel = "rgb" if channel == "all" else channel
        return [(lab, v) for lab, v in channel_curves(sides[0][0], sides[0][1], channel)]
    channel = {"rgb": "lum", "all": "rgb"}.get(channel, channel)
    out = []
    for k, (name, values) in enumerate(sides):
        side = "AB"[k]
        for lab, v in channel_curves(name, values, channel):
            col = SIDE_HUES[k][1 + "RGB".index(lab)] if lab in CHANNEL_WORDS else SIDE_HUES[k][0]
            text = (f"{side}:{name}" if lab == name else f"{side}:{name} (Y)" if lab == "lum"
                    else f"{side}:{CHANNEL_WORDS.get(lab, lab)}")
            out.append((text, v, SIDE_MARKERS[k], col))
    return out
