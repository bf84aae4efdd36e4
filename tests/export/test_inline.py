"""Inline pictures, byte for byte on tiny images: the PNG's chunks (CRC-32 recomputed here
with zlib.crc32, the pixels inflated here), iTerm2's OSC 1337 header, kitty's chunking, tmux's
passthrough, and the sixel of an 8×12 pattern read back by a small decoder written here from
the VT340 description (not the encoder's code)."""

from __future__ import annotations

import base64
import re
import struct
import zlib

import numpy as np
import pytest

from tuibrdf.render.export import inline, png, sixel

ESC = "\x1b"


def chunks(data: bytes) -> list[tuple[bytes, bytes]]:
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    out, i = [], 8
    while i < len(data):
        (n,) = struct.unpack(">I", data[i:i + 4])
        kind, body = data[i + 4:i + 8], data[i + 8:i + 8 + n]
        (crc,) = struct.unpack(">I", data[i + 8 + n:i + 12 + n])
        assert crc == zlib.crc32(kind + body) & 0xFFFFFFFF, kind
        out.append((kind, body))
        i += 12 + n
    return out


def tiny() -> tuple[np.ndarray, np.ndarray]:
    index = np.array([[0, 1, 2], [2, 1, 0]])
    palette = np.array([[0, 0, 0], [255, 0, 0], [10, 20, 30]], dtype=np.uint8)
    return index, palette


def test_png_chunks_crc_and_pixels():
    index, palette = tiny()
    data = png.encode_indexed(index, palette, {"Title": "t"})
    cs = chunks(data)
    assert [k for k, _ in cs] == [b"IHDR", b"PLTE", b"tEXt", b"IDAT", b"IEND"]
    assert cs[0][1] == struct.pack(">IIBBBBB", 3, 2, 8, 3, 0, 0, 0)  # 3×2, 8 bit, palette
    assert cs[1][1] == bytes([0, 0, 0, 255, 0, 0, 10, 20, 30])
    assert cs[2][1] == b"Title\0t"
    # each scanline: filter byte 0, then the indices
    assert zlib.decompress(cs[3][1]) == bytes([0, 0, 1, 2, 0, 2, 1, 0])
    assert cs[4][1] == b""


def test_iterm_escape():
    data = png.encode_indexed(*tiny())
    esc = inline.escape("iterm", data, *tiny())
    head = f"{ESC}]1337;File=inline=1;size={len(data)};width=3px;height=2px;" \
           "preserveAspectRatio=1:"
    assert esc == head + base64.b64encode(data).decode() + "\x07\n"


def test_kitty_chunks_of_at_most_4096_with_m_flags():
    payload = bytes(range(256)) * 40  # 10240 bytes → 13656 base64 characters: 4 chunks
    esc = inline.escape("kitty", payload, *tiny())
    parts = re.findall(f"{ESC}_G([^;]*);([^{ESC}]*){ESC}\\\\", esc)
    assert "".join(p for _, p in parts) == base64.b64encode(payload).decode()
    assert [len(p) for _, p in parts] == [4096, 4096, 4096, 13656 - 3 * 4096]
    assert parts[0][0] == "a=T,f=100,q=2,m=1"
    assert [c for c, _ in parts[1:]] == ["m=1", "m=1", "m=0"]
    assert esc.endswith("\n")


def test_tmux_passthrough_doubles_every_escape():
    esc = inline.escape("kitty", b"x", *tiny(), tmux=True)
    inner = f"{ESC}_Ga=T,f=100,q=2,m=0;eA=={ESC}\\"
    assert esc == f"{ESC}Ptmux;" + inner.replace(ESC, ESC * 2) + f"{ESC}\\\n"


def decode_sixel(s: str) -> tuple[np.ndarray, dict[int, tuple[int, int, int]]]:
    """A small sixel reader: DCS … q, raster attributes, colour definitions (percent),
    '#n' select, '!n' repeat, '$' carriage return, '-' next band, ST."""
    assert s.startswith(f"{ESC}P") and s.endswith(f"{ESC}\\")
    body = s[2:-2]
    body = body[body.index("q") + 1:]
    m = re.match(r'"1;1;(\d+);(\d+)', body)
    w, h = int(m.group(1)), int(m.group(2))
    body = body[m.end():]
    img = np.full((h, w), -1)
    colours, cur, x, band, i = {}, 0, 0, 0, 0
    while i < len(body):
        c = body[i]
        if c == "#":
            m = re.match(r"#(\d+)(;2;(\d+);(\d+);(\d+))?", body[i:])
            if m.group(2):
                colours[int(m.group(1))] = tuple(int(m.group(k)) for k in (3, 4, 5))
            else:
                cur = int(m.group(1))
            i += m.end()
            continue
        if c == "$":
            x = 0
        elif c == "-":
            x, band = 0, band + 1
        else:
            n = 1
            if c == "!":
                m = re.match(r"!(\d+)(.)", body[i:])
                n, c = int(m.group(1)), m.group(2)
                i += m.end() - 1
            bits = ord(c) - 63
            for _ in range(n):
                for k in range(6):
                    if bits >> k & 1:
                        img[band * 6 + k, x] = cur
                x += 1
        i += 1
    return img, colours


def test_sixel_of_an_8x12_pattern():
    yy, xx = np.mgrid[0:12, 0:8]
    index = (xx // 2 + yy // 3) % 3  # stripes crossing both sixel bands
    index[:, 5:] = 1  # a run of one colour: the repeat introducer
    palette = np.array([[255, 255, 255], [255, 0, 0], [0, 128, 255]], dtype=np.uint8)
    s = sixel.encode(index, palette)
    assert s.startswith(f'{ESC}Pq"1;1;8;12#0;2;100;100;100#1;2;100;0;0#2;2;0;50;100')
    img, colours = decode_sixel(s)
    assert np.array_equal(img, index)
    assert colours == {0: (100, 100, 100), 1: (100, 0, 0), 2: (0, 50, 100)}


def test_sixel_escape_reduces_a_large_palette():
    index = np.arange(300).reshape(10, 30)
    palette = np.stack([np.arange(300) % 256, np.arange(300) // 2 % 256,
                        np.full(300, 7)], 1).astype(np.uint8)
    img, colours = decode_sixel(inline.escape("sixel", b"", index, palette).rstrip("\n"))
    assert len(colours) <= 256 and img.min() >= 0


@pytest.mark.parametrize("env, want", [
    ({"TERM": "xterm-kitty"}, "kitty"),
    ({"TERM_PROGRAM": "iTerm.app", "TERM": "xterm-256color"}, "iterm"),
    ({"TERM_PROGRAM": "WezTerm"}, "iterm"),
    ({"TERM_PROGRAM": "vscode"}, "iterm"),
    ({"TERM_PROGRAM": "ghostty", "TERM": "xterm-ghostty"}, "kitty"),
    ({"TERM": "foot"}, "sixel"),
    ({"TERM": "screen-256color", "TERM_PROGRAM": "tmux", "LC_TERMINAL": "iTerm2"}, "iterm"),
    ({"TERM": "xterm-256color"}, None),  # could be anything: the text picture
    ({"TERM": "tmux-256color", "TERM_PROGRAM": "tmux"}, None),
    ({"TERM": "dumb", "TERM_PROGRAM": "iTerm.app"}, None),
    ({}, None),
])
def test_auto_only_where_the_terminal_is_known(env, want):
    assert inline.detect(env) == want


def test_render_inline_through_the_cli(capsys, monkeypatch):
    from tuibrdf.cli import main

    monkeypatch.delenv("TMUX", raising=False)
    assert main(["render", "phong", "--inline", "iterm", "--size", "48"]) == 0
    out = capsys.readouterr().out
    m = re.fullmatch(f"{ESC}]1337;File=inline=1;size=(\\d+);width=48px;height=(\\d+)px;"
                     f"preserveAspectRatio=1:([A-Za-z0-9+/=]+)\x07\n", out)
    data = base64.b64decode(m.group(3))
    assert len(data) == int(m.group(1))
    assert chunks(data)[0][0] == b"IHDR"
    # auto on a stream that is not a terminal: the text picture, as without the flag
    assert main(["render", "phong", "--inline", "auto", "--color", "none"]) == 0
    assert ESC not in capsys.readouterr().out
