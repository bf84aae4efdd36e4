"""A sixel encoder (DEC's VT330/340 graphics, as xterm, foot, WezTerm, mlterm and Windows
Terminal ≥ 1.22 read it): a palette image of at most 256 colours.

Layout (VT330/340 Programmer Reference, "Sixel Graphics"; xterm's ctlseqs): ``ESC P q``
starts the picture; ``"1;1;W;H`` sets a 1:1 pixel aspect and the size (raster attributes);
``#n;2;r;g;b`` defines colour ``n`` (components in percent, 0–100); then bands of six pixel
rows: per colour present in the band ``#n`` and one character per column, ``chr(63 + bits)``
(bit k set where row k of the band has that colour), ``!count char`` repeating a character,
``$`` back to the band's left edge, ``-`` to the next band; ``ESC \\`` ends it.
"""

from __future__ import annotations

import numpy as np

ESC = "\x1b"


def _run(ch: str, n: int) -> str:
    return f"!{n}{ch}" if n > 3 else ch * n


def encode(index: np.ndarray, palette: np.ndarray) -> str:
    """The sixel string of ``index`` ``(H, W)`` into ``palette`` ``(n ≤ 256, 3)`` (0–255)."""
    index = np.asarray(index)
    pal = np.asarray(palette, dtype=np.int64)
    if len(pal) > 256:
        raise ValueError("sixel: at most 256 colours")
    h, w = index.shape
    out = [f'{ESC}Pq"1;1;{w};{h}']
    for n, (r, g, b) in enumerate(pal):
        # 0–255 → 0–100 %, rounded half up (integers: exact)
        out.append(f"#{n};2;{(r * 100 + 127) // 255};{(g * 100 + 127) // 255};"
                   f"{(b * 100 + 127) // 255}")
    for top in range(0, h, 6):
        band = index[top:top + 6]
        weights = (1 << np.arange(band.shape[0]))[:, None]
        parts = []
        for n in np.unique(band):
            bits = ((band == n) * weights).sum(axis=0)
            chars = "".join(chr(63 + int(b)) for b in bits)
            line, i = [], 0
            while i < w:
                j = i
                while j < w and chars[j] == chars[i]:
                    j += 1
                line.append(_run(chars[i], j - i))
                i = j
            parts.append(f"#{int(n)}" + "".join(line))
        out.append("$".join(parts) + ("-" if top + 6 < h else ""))
    out.append(f"{ESC}\\")
    return "".join(out)
