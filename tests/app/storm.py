"""Seeded key storms for the viewer's robustness tests: raw terminal input of every kind
(letters, punctuation, arrows, F-keys, ctrl/alt chords, SGR mouse reports, bracketed pastes,
Unicode, kitty ``CSI … u`` keys, malformed CSI), as the bytes a terminal sends.

The quit keys (q, ctrl+q, ctrl+c) are left out: a storm must leave the viewer running.
"""

from __future__ import annotations

import random

LETTERS = "abcdefghijklmnoprstuvwxyzABCDEFGHIJKLMNOPRSTUVWXYZ0123456789"
PUNCT = "!\"#$%&'()*+,-./:;<=>?@[\\]^_`{|}~ "
UNICODE = "éθ°😀中∑\u200b\u0301ﬁ"
ARROWS = ["\x1b[A", "\x1b[B", "\x1b[C", "\x1b[D", "\x1b[1;2C", "\x1b[1;2D", "\x1b[1;5A",
          "\x1b[1;5B", "\x1b[1;5C", "\x1b[1;5D", "\x1b[H", "\x1b[F", "\x1b[5~", "\x1b[6~",
          "\x1b[2~", "\x1b[3~", "\x1bOA", "\x1bOB"]
FKEYS = ["\x1bOP", "\x1bOQ", "\x1bOR", "\x1bOS", "\x1b[15~", "\x1b[17~", "\x1b[18~",
         "\x1b[19~", "\x1b[20~", "\x1b[21~", "\x1b[23~", "\x1b[24~", "\x1b[1;2P"]
#: control characters but ctrl+c (\x03), ctrl+q (\x11) and ctrl+z (\x1a: suspends)
CTRL = [chr(c) for c in range(1, 32) if c not in (3, 17, 26, 27)] + ["\x7f"]
MALFORMED = ["\x1b[1114112u", "\x1b[99999999999999999999u", "\x1b[;;;u", "\x1b[1;9999u",
             "\x1b[0u", "\x1b[57441;2u", "\x1b[97;5:3u", "\x1b[97;1;1114112u",
             "\x1b[<99999;1;1M", "\x1b[<0;0;0M", "\x1b[<0;-5;3m", "\x1b[M   ", "\x1b[",
             "\x1b[[A", "\x1b]0;title\x07", "\x1bP1$r\x1b\\", "\x1b[?1;2c", "\x1b[8;9999;9999t",
             "\x1b[I", "\x1b[O", "\x1b[201~", "\x1b[999999999999999999999999999;1R",
             "\x1b[12;34;56;78;90;12;34;56;78;90;12;34~", "\x1b\x1b\x1b[", "\x1bO", "\x1bOZ"]
#: (a paste start without its end is left out: the terminal then reads every later byte
#: as pasted text, as a terminal would; paste() sends whole pastes)
QUIT_KEYS = frozenset({"q", "ctrl+q", "ctrl+c", "ctrl+z"})


def mouse(rng: random.Random, width: int, height: int) -> str:
    button = rng.choice([0, 1, 2, 32, 35, 64, 65, 66, 67, 4, 8, 16])
    x, y = rng.randint(1, width), rng.randint(1, height)
    return f"\x1b[<{button};{x};{y}{rng.choice('Mm')}"


def paste(rng: random.Random) -> str:
    body = "".join(rng.choice(LETTERS + PUNCT + UNICODE + "\n\t") for _ in range(rng.randint(0,
                                                                                       40)))
    return f"\x1b[200~{body}\x1b[201~"


def kitty(rng: random.Random) -> str:
    code = rng.choice([97, 65, 9, 13, 27, 57399, 57414, 0x1F600, rng.randint(0, 0x10FFFF)])
    if code in (113, 81, 99):  # q, Q, c (ctrl+c with a modifier)
        code = 97
    mods = rng.choice(["", ";2", ";3", ";5", ";9", ";1:1", ";2:3"])
    return f"\x1b[{code}{mods}u"


def chunk(rng: random.Random, width: int = 100, height: int = 30) -> str:
    """One random piece of terminal input."""
    kind = rng.randrange(10)
    if kind == 0:
        return rng.choice(ARROWS)
    if kind == 1:
        return rng.choice(FKEYS)
    if kind == 2:
        return rng.choice(CTRL)
    if kind == 3:
        return "\x1b" + rng.choice(LETTERS + PUNCT)  # alt+key
    if kind == 4:
        return mouse(rng, width, height)
    if kind == 5:
        return paste(rng) if rng.random() < 0.3 else rng.choice(UNICODE)
    if kind == 6:
        return rng.choice(MALFORMED)
    if kind == 7:
        return kitty(rng)
    if kind == 8:
        return rng.choice(PUNCT)
    return rng.choice(LETTERS)


def storm(seed: int, n: int, width: int = 100, height: int = 30) -> list[str]:
    rng = random.Random(seed)
    return [chunk(rng, width, height) for _ in range(n)]


def events(data: list[str]):
    """The events Textual's terminal parser makes of ``data`` (the viewer's guarded parser:
    a malformed sequence is dropped), without the quit keys."""
    from textual import events as ev

    from tuibrdf.app.textual_internals import SafeXTermParser

    parser = SafeXTermParser()
    out = []
    for piece in data:
        for event in parser.feed(piece):
            if isinstance(event, ev.Key) and (event.key in QUIT_KEYS or "ctrl+c" in event.key
                                              or event.key.endswith("+q")):
                continue
            out.append(event)
    out.extend(parser.tick())
    return out
