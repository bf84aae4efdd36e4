"""Title lines that fit their width (the least important parts go first, never the numbers),
and the marks and guide colours every picture shares.

A title is a list of parts in display order, each with a rank (0 = always kept).  When the
joined title is wider than the view, the part with the highest rank goes, then the next; what
remains of rank 0 is cropped at the end.  A narrow 80×24 pane thus still shows
``incidence  max 6.14 · circles every 2`` instead of ``cook-torrance  θi=60°  incidence (φ``.
"""

from __future__ import annotations

from collections.abc import Sequence

from rich.cells import cell_len
from rich.text import Text

SEP = "  "


def fit_parts(parts: Sequence[tuple[str, int]], width: int) -> str:
    """Join the non-empty ``(text, rank)`` parts with two spaces, dropping the highest ranks
    (the last of equals first) until the line is at most ``width`` cells; rank 0 parts stay,
    and the line is cropped as a last resort."""
    kept = [(i, s, r) for i, (s, r) in enumerate(parts) if s]
    while cell_len(SEP.join(s for _, s, _ in kept)) > width:
        worst = max(range(len(kept)), key=lambda k: (kept[k][2], kept[k][0]), default=None)
        if worst is None or kept[worst][2] == 0:  # rank 0 parts are never dropped
            break
        del kept[worst]
    line = SEP.join(s for _, s, _ in kept)
    if cell_len(line) <= width:
        return line
    n = used = 0
    while n < len(line) and used + cell_len(line[n]) <= width:
        used += cell_len(line[n])
        n += 1
    head = line[:n]
    # a cut inside a word would show a wrong number ("0.113" as "0.11"): the word goes whole
    if not line[n].isspace() and " " in head:
        head = head[:head.rindex(" ")]
    return head.rstrip()


def title(parts: Sequence[tuple[str, int]], width: int, style: str = "") -> Text:
    """:func:`fit_parts` as a one-row Rich ``Text``."""
    return Text(fit_parts(parts, width), style=style, no_wrap=True, overflow="crop")


def first_fitting(variants: Sequence[Sequence[tuple[str, int]]], width: int,
                  style: str = "") -> Text:
    """:func:`title` of the first variant whose rank 0 parts fit ``width`` whole (a longer
    wording first, a shorter one after), else of the last: the shorter wording goes before
    :func:`fit_parts` crops a number's label."""
    for parts in variants:
        if cell_len(SEP.join(s for s, r in parts if s and r == 0)) <= width:
            return title(parts, width, style)
    return title(variants[-1], width, style)


# -------------------------------------------------------------------- guides and marks
#: colour of the horizon ring drawn just outside the disc and of the solid's guides: a muted
#: blue that quantises to xterm colour 61 (95, 95, 175), which no colour map (grey, viridis,
#: inferno at any level count) quantises to in 256 colours, so "outside" never reads as a
#: value (tests/render/test_views.py); plain text draws it as ``~`` (halfblock.RING_CHAR)
RING_RGB = (72, 72, 160)
LIGHT_RGB = (40, 220, 255)
MIRROR_MARK = dict(glyph="×", ascii="X", rgb=(255, 40, 40))
INCIDENT_MARK = dict(glyph="o", ascii="o", rgb=LIGHT_RGB)


def mark_legend(color: str) -> str:
    """``× mirror  o light`` with the glyphs the picture uses (ASCII ones in plain text)."""
    key = "ascii" if color == "none" else "glyph"
    return f"{MIRROR_MARK[key]} mirror  {INCIDENT_MARK[key]} light"


def where(theta_deg: float, phi_deg: float) -> str:
    """``θ=62° φ=0°``: whole degrees, as ints so a tiny negative φ never reads ``-0°``; φ in
    (−180°, 180°], the one convention of every picture and the CLI."""
    return f"θ={round(theta_deg)}° φ={phi_deg_text(phi_deg)}°"


def phi_deg_text(phi_deg: float) -> str:
    """An azimuth as every title writes it: whole degrees in (−180°, 180°] (315° is −45°)."""
    ph = round(phi_deg) % 360
    return str(ph - 360 if ph > 180 else ph)
