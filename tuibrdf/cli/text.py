"""Text that any terminal can take: one-line messages and an ASCII fallback for old locales.

Two problems of the output side of a command line:

* a message echoing user input (a file name, an argument) can contain a newline or an escape
  sequence; :func:`one_line` shows control characters as Python escapes (``\\n``, ``\\x1b``), so
  one error stays one line and cannot drive the terminal;
* the output uses θ, ⁻¹, ·, box-drawing, half-block and braille characters, which a Latin-1
  or ASCII locale cannot encode (``LANG=en_US.ISO-8859-1``, ``PYTHONIOENCODING=latin-1``,
  ``LANG=C`` without Python's UTF-8 mode).  :func:`install` gives ``sys.stdout`` and
  ``sys.stderr`` an encoding error handler that writes an ASCII stand-in for each character
  the stream cannot encode (θ → theta, ⁻¹ → ^-1, · → *, ─ → -, braille → . : #) instead of
  raising ``UnicodeEncodeError``.  Characters the locale can encode are left alone.
"""

from __future__ import annotations

import codecs
import sys

HANDLER = "tuibrdf-ascii"

#: stand-ins for the non-ASCII characters tuibrdf prints (anything else becomes "?")
ASCII = {
    "θ": "theta", "Θ": "Theta", "φ": "phi", "Φ": "Phi", "ψ": "psi", "α": "alpha", "σ": "sigma",
    "π": "pi", "ω": "omega", "Λ": "Lambda", "μ": "mu", "ρ": "rho", "η": "eta", "β": "beta",
    "Δ": "d", "δ": "delta", "γ": "gamma", "ε": "eps", "λ": "lambda", "τ": "tau",
    "≳": ">~", "∈": "in", "⌊": "floor(", "⌋": ")", "§": "S", "ᴸ": "L",
    "⁻¹": "^-1", "⁻": "^-", "¹": "1", "²": "^2", "³": "^3", "⁴": "^4", "⁵": "^5",
    "·": "*", "×": "x", "°": " deg", "±": "+-", "−": "-", "–": "-", "—": "--", "…": "...",
    "≤": "<=", "≥": ">=", "≲": "<~", "≈": "~", "≠": "!=", "∫": "int", "√": "sqrt", "∞": "inf",
    "→": "->", "←": "<-", "↑": "^", "↓": "v", "▶": ">", "◀": "<", "•": "*", "✓": "ok",
    "’": "'", "‘": "'", "“": '"', "”": '"', "\u00a0": " ", "ₒ": "o", "ᵢ": "i",
}

#: the ASCII ramp of ``--color none`` (tuibrdf.render.colormap), used for shaded blocks
_RAMP = " .:-=+*#%@"


def _box(ch: str) -> str:
    """A box-drawing character (U+2500–U+257F) as - | +."""
    name = _unicode_name(ch)
    horizontal = "HORIZONTAL" in name
    vertical = "VERTICAL" in name
    if horizontal and not vertical:
        return "-"
    if vertical and not horizontal:
        return "|"
    return "+"


def _block(ch: str) -> str:
    """A block element (U+2580–U+259F) as a ramp character by how much of the cell it fills."""
    fill = {"█": 1.0, "▓": 0.75, "▒": 0.5, "░": 0.25, "▀": 0.5, "▄": 0.5, "▌": 0.5, "▐": 0.5}
    f = fill.get(ch, 0.25 if "QUADRANT" in _unicode_name(ch) else 0.5)
    return _RAMP[min(len(_RAMP) - 1, round(f * (len(_RAMP) - 1)))]


def _braille(ch: str) -> str:
    """A braille cell (U+2800–U+28FF: the plots' curves) by its number of dots."""
    dots = bin(ord(ch) - 0x2800).count("1")
    return " " if dots == 0 else "." if dots <= 2 else ":" if dots <= 4 else "#"


def _unicode_name(ch: str) -> str:
    import unicodedata

    return unicodedata.name(ch, "")


def to_ascii(ch: str) -> str:
    """The ASCII stand-in of one character."""
    if ch in ASCII:
        return ASCII[ch]
    o = ord(ch)
    if 0x2500 <= o <= 0x257F:
        return _box(ch)
    if 0x2580 <= o <= 0x259F:
        return _block(ch)
    if 0x2800 <= o <= 0x28FF:
        return _braille(ch)
    import unicodedata

    # a letter with a diacritic (the ö of Löw) or a compatibility form: its ASCII base letter
    base = unicodedata.normalize("NFKD", ch).encode("ascii", "ignore").decode("ascii")
    return base or "?"


def _stand_in(s: str, i: int) -> tuple[str, int]:
    """The ASCII stand-in of ``s[i]`` (or of the sequence starting there) and where to go on."""
    if s.startswith("⁻¹", i):  # one unit: sr⁻¹ → sr^-1 (¹ alone is Latin-1, ⁻ is not)
        return "^-1", i + 2
    out = to_ascii(s[i])
    if s[i] in _GREEK and _subscript_follows(s, i + 1):
        out += "_"  # θi → theta_i, not thetai
    return out, i + 1


_GREEK = frozenset("θφψαωσ")


def _subscript_follows(s: str, j: int) -> bool:
    """``s[j]`` is a one-letter subscript (the i of θi) and not the start of a word."""
    return j < len(s) and s[j] in "iorhd" and not (j + 1 < len(s) and s[j + 1].isalpha())


def _handler(err: UnicodeError) -> tuple[str, int]:
    if not isinstance(err, UnicodeEncodeError):
        raise err
    s, out, i = err.object, [], err.start
    while i < err.end:
        rep, i = _stand_in(s, i)
        out.append(rep)
    return "".join(out), i


codecs.register_error(HANDLER, _handler)


def to_stream(text: str, stream, table: dict[str, str] | None = None) -> str:
    """``text`` with every character ``stream`` cannot encode replaced by its ASCII stand-in
    (``table`` first): for a picture, where the handler's choices (· → *) read badly."""
    if can_encode(stream, text):
        return text
    enc = _encoding(stream)
    table = table or {}
    out, i = [], 0
    while i < len(text):
        ch = text[i]
        try:
            ch.encode(enc)
            out.append(ch)
            i += 1
            continue
        except (UnicodeEncodeError, LookupError):
            pass
        if ch in table:
            out.append(table[ch])
            i += 1
        else:
            rep, i = _stand_in(text, i)
            out.append(rep)
    return "".join(out)


#: characters a stream must encode to get tuibrdf's output unchanged
PROBE = "θφ⁻¹·—≤▀─⠿"


def _encoding(stream) -> str:
    # a stream without an encoding (io.StringIO) holds str: anything goes
    return getattr(stream, "encoding", None) or "utf-8"


def can_encode(stream, text: str = PROBE) -> bool:
    """Whether ``stream`` (a text stream) can write ``text`` as it is."""
    enc = _encoding(stream)
    try:
        text.encode(enc)
    except (UnicodeEncodeError, LookupError):
        return False
    return True


def install(*streams) -> None:
    """Give each text stream that cannot encode tuibrdf's characters the ASCII fallback."""
    for stream in streams or (sys.stdout, sys.stderr):
        if stream is None or can_encode(stream) or not hasattr(stream, "reconfigure"):
            continue
        try:
            stream.reconfigure(errors=HANDLER)
        except (ValueError, OSError, AttributeError):  # closed, or not a TextIOWrapper
            continue


_CONTROL = {c: f"\\x{c:02x}" for c in (*range(0x20), 0x7F, *range(0x80, 0xA0))}
_CONTROL.update({0x09: "\\t", 0x0A: "\\n", 0x0D: "\\r", 0x2028: "\\u2028", 0x2029: "\\u2029"})


def one_line(text: str) -> str:
    """``text`` with control characters escaped (``\\n``, ``\\x1b``): one line, inert."""
    return str(text).translate(_CONTROL)


__all__ = ["ASCII", "HANDLER", "can_encode", "install", "one_line", "to_ascii", "to_stream"]
