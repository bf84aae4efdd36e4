"""Pictures inline in the terminal: iTerm2's, kitty's and the sixel image protocols, wrapped
for tmux when inside it.

- ``iterm``: ``OSC 1337 ; File=inline=1;size=N;width=Wpx;height=Hpx;preserveAspectRatio=1 :
  BASE64 BEL`` (iTerm2's "Inline Images Protocol"; WezTerm and VS Code's terminal read it);
- ``kitty``: ``APC G a=T,f=100,… ; BASE64 ST`` (kitty's "Terminal graphics protocol", PNG
  data ``f=100``), the base64 text in chunks of at most 4096 bytes, each but the last with
  ``m=1``, the last ``m=0`` (Ghostty reads it too);
- ``sixel``: :mod:`.sixel` (foot, Windows Terminal ≥ 1.22, xterm ``-ti vt340``, mlterm).

Inside tmux (``TMUX`` set) each escape is wrapped in tmux's passthrough ``ESC P tmux; …
ESC \\`` with every ESC inside doubled; tmux passes it on only with ``set -g
allow-passthrough on`` (tmux ≥ 3.3).

:func:`detect` answers ``auto``: a protocol only where ``TERM_PROGRAM`` or ``TERM`` names a
terminal known to have it, else None (the text picture).  Over SSH only ``TERM`` arrives
(``TERM_PROGRAM`` stays on the local machine): name the protocol with ``--inline``.
"""

from __future__ import annotations

import base64
import os
from collections.abc import Mapping

import numpy as np

ESC, BEL = "\x1b", "\x07"
PROTOCOLS = ("iterm", "kitty", "sixel")
CHOICES = ("auto", *PROTOCOLS, "off")
KITTY_CHUNK = 4096

#: TERM_PROGRAM values (set by the terminal itself) → protocol
BY_PROGRAM = {"iTerm.app": "iterm", "WezTerm": "iterm", "vscode": "iterm",
              "ghostty": "kitty"}
#: TERM values → protocol (kitty and Ghostty set their own TERM; foot too)
BY_TERM = {"xterm-kitty": "kitty", "xterm-ghostty": "kitty", "foot": "sixel",
           "foot-extra": "sixel", "wezterm": "iterm", "mlterm": "sixel"}


def detect(environ: Mapping[str, str] | None = None) -> str | None:
    """The protocol ``--inline auto`` uses here, or None when not known for certain."""
    env = os.environ if environ is None else environ
    if env.get("TERM") == "dumb":
        return None
    if env.get("WT_SESSION") and not env.get("TERM_PROGRAM"):
        return None  # Windows Terminal: sixel from 1.22 on, and its version is not in the env
    prog = env.get("TERM_PROGRAM", "")
    if env.get("LC_TERMINAL") == "iTerm2":  # iTerm2 sets it; ssh forwards LC_* by default
        return "iterm"
    if prog in BY_PROGRAM:
        return BY_PROGRAM[prog]
    return BY_TERM.get(env.get("TERM", ""))


def tmux_wrap(seq: str) -> str:
    """``seq`` inside tmux's passthrough: ``ESC P tmux; seq (ESC doubled) ESC \\``."""
    return f"{ESC}Ptmux;" + seq.replace(ESC, ESC + ESC) + f"{ESC}\\"


def iterm(png: bytes, width_px: int, height_px: int, name: str = "") -> str:
    """iTerm2's inline-image escape for ``png`` (a ``\\n`` after it: the cursor below)."""
    args = ["inline=1", f"size={len(png)}", f"width={width_px}px", f"height={height_px}px",
            "preserveAspectRatio=1"]
    if name:
        args.insert(0, "name=" + base64.b64encode(name.encode()).decode("ascii"))
    return (f"{ESC}]1337;File=" + ";".join(args) + ":"
            + base64.b64encode(png).decode("ascii") + BEL)


def kitty(png: bytes) -> list[str]:
    """kitty's escapes for ``png``: transmit and display (``a=T``), PNG data (``f=100``), the
    base64 text in chunks of ≤ :data:`KITTY_CHUNK` bytes (``m=1`` but the last, ``m=0``);
    ``q=2`` keeps the terminal's replies off standard input."""
    data = base64.b64encode(png).decode("ascii")
    chunks = [data[i:i + KITTY_CHUNK] for i in range(0, len(data), KITTY_CHUNK)] or [""]
    out = []
    for k, c in enumerate(chunks):
        more = 1 if k < len(chunks) - 1 else 0
        head = f"a=T,f=100,q=2,m={more}" if k == 0 else f"m={more}"
        out.append(f"{ESC}_G{head};{c}{ESC}\\")
    return out


def escape(protocol: str, png: bytes, index: np.ndarray, palette: np.ndarray,
           tmux: bool = False) -> str:
    """The text that shows the picture inline with ``protocol`` (a newline after it)."""
    h, w = np.asarray(index).shape
    if protocol == "iterm":
        parts = [iterm(png, w, h)]
    elif protocol == "kitty":
        parts = kitty(png)
    elif protocol == "sixel":
        from tuibrdf.render.export.sixel import encode

        parts = [encode(*fit_palette(index, palette))]
    else:
        raise ValueError(f"inline protocol {protocol!r}: expected one of {', '.join(PROTOCOLS)}")
    if tmux:
        parts = [tmux_wrap(p) for p in parts]
    return "".join(parts) + "\n"


def fit_palette(index: np.ndarray, palette: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(index, palette)`` with at most 256 colours: a larger palette (a lit view's colours)
    is mapped to the 6×6×6 colour cube (216 colours, each channel to the nearest of 0, 51, …,
    255)."""
    palette = np.asarray(palette, dtype=np.int64)
    if len(palette) <= 256:
        return np.asarray(index), palette
    q = (palette * 5 + 127) // 255  # 0–5 per channel, rounded half up
    code = (q[:, 0] * 6 + q[:, 1]) * 6 + q[:, 2]
    cube = np.stack(np.meshgrid(*(np.arange(6) * 51,) * 3, indexing="ij"), -1).reshape(-1, 3)
    return code[np.asarray(index)], cube
