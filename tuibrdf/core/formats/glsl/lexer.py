"""The GLSL lexer: shader text → tokens, each with its line in the file (comments and white
space dropped, a ``f`` suffix of a number too)."""

from __future__ import annotations

import re
from dataclasses import dataclass

from tuibrdf.core.formats.glsl.errors import GlslError

_TOKEN = re.compile(r"""
    (?P<ws>[ \t\r\f\v]+)
  | (?P<nl>\n)
  | (?P<lcomment>//[^\n]*)
  | (?P<bcomment>/\*.*?\*/)
  | (?P<open_comment>/\*)
  | (?P<num>(?:\d+\.\d*|\.\d+|\d+)(?:[eE][+-]?\d+)?[fF]?)
  | (?P<ident>[A-Za-z_][A-Za-z_0-9]*)
  | (?P<op>\+\+|--|\+=|-=|\*=|/=|%=|==|!=|<=|>=|&&|\|\||\^\^|<<|>>|[-+*/%<>=!?:;,(){}\[\].&|^~])
""", re.VERBOSE | re.DOTALL)


@dataclass(frozen=True)
class Tok:
    kind: str  # num | ident | op | eof
    text: str
    line: int


def tokenize(src: str, first_line: int = 1) -> list[Tok]:
    """Tokens of ``src``; line numbers start at ``first_line``."""
    out: list[Tok] = []
    line = first_line
    pos = 0
    n = len(src)
    while pos < n:
        m = _TOKEN.match(src, pos)
        if m is None:
            ch = src[pos]
            what = "a preprocessor directive ('#')" if ch == "#" else f"character {ch!r}"
            raise GlslError(f"unexpected {what}", line)
        kind = m.lastgroup
        text = m.group()
        if kind == "open_comment":
            raise GlslError("unterminated /* comment", line)
        if kind in ("num", "ident", "op"):
            if kind == "num" and text[-1] in "fF":
                text = text[:-1]
            out.append(Tok(kind, text, line))
        line += text.count("\n") if kind in ("nl", "bcomment") else 0
        pos = m.end()
    out.append(Tok("eof", "end of shader", line))
    return out
