"""The terminal picture as a file: Rich's console export (SVG, HTML, text), self-contained
and deterministic.

SVG: Rich's template without its ``@font-face`` rules (they fetch Fira Code from a CDN; the
picture uses the reader's Fira Code if installed, else its monospace font) and a fixed
``unique_id`` (Rich's default is a hash of the content: fixed too, but the ids of two
pictures in one page would differ anyway).  HTML: styles inline, the same colours.
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from functools import lru_cache
from typing import Any

UNIQUE_ID = "tuibrdf"


@lru_cache(maxsize=1)
def svg_format() -> str:
    from rich._export_format import CONSOLE_SVG_FORMAT

    return re.sub(r"\s*@font-face \{\{.*?\}\}", "", CONSOLE_SVG_FORMAT, flags=re.S)


class _Null:
    def write(self, s: str) -> int:
        return len(s)

    def flush(self) -> None:
        pass


def recording_console(width: int, color: str = "truecolor"):
    """A console that records what it prints and reads nothing from the environment."""
    from rich.console import Console

    return Console(file=_Null(), record=True, width=int(width),
                   color_system=None if color == "none" else color,
                   force_terminal=color != "none", no_color=False, highlight=False,
                   markup=False, emoji=False, legacy_windows=False, soft_wrap=False,
                   force_jupyter=False, force_interactive=False, _environ={})


def export(renderables: Iterable[Any], width: int, fmt: str, title: str = "tuibrdf") -> str:
    """``renderables`` printed one below the other, as ``svg``, ``html``, ``ansi`` or
    ``text``."""
    con = recording_console(width, "none" if fmt == "text" else "truecolor")
    for r in renderables:
        con.print(r, no_wrap=True, overflow="ignore", crop=False)
    if fmt == "svg":
        return con.export_svg(title=title, code_format=svg_format(), unique_id=UNIQUE_ID)
    if fmt == "html":
        return con.export_html(inline_styles=True)
    if fmt in ("text", "ansi"):
        text = con.export_text(styles=fmt == "ansi")
        return "\n".join(line.rstrip() for line in text.split("\n")) if fmt == "text" else text
    raise ValueError(f"format {fmt!r}: expected svg, html, ansi or text")
