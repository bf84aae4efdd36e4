"""Output streams and locales (issue 17, items 4, 5 and 8; issue 16 for --help's imports).

Each case runs ``python -m tuibrdf`` in a subprocess, in the environment the issue names:
stdout on a full disk (/dev/full), stdout closed, a Latin-1 or ASCII output encoding.  The
promise: valid commands work (degrading to ASCII where the locale cannot show a character),
failures are one line on stderr with a non-zero status, never a traceback.
"""

from __future__ import annotations

import io
import os
import subprocess
import sys

import pytest

from tests import ROOT
from tuibrdf.cli import main
from tuibrdf.cli.text import can_encode, one_line, to_ascii, to_stream


def cli(*argv: str, env: dict | None = None, **kw) -> subprocess.CompletedProcess:
    e = {k: v for k, v in os.environ.items() if not k.startswith(("LC_", "PYTHONIO"))}
    e.update({"PYTHONPATH": str(ROOT), **(env or {})})
    return subprocess.run([sys.executable, "-m", "tuibrdf", *argv], capture_output=True,
                          env=e, timeout=120, stdin=subprocess.DEVNULL, **kw)


def no_traceback_one_line(err: bytes) -> str:
    text = err.decode("ascii", "replace")
    assert "Traceback" not in text, text
    lines = text.strip().splitlines()
    assert len(lines) == 1, text
    return lines[0]


# ------------------------------------------------------------------ stream errors (item 4)


@pytest.mark.skipif(not os.path.exists("/dev/full"), reason="needs /dev/full")
@pytest.mark.parametrize("argv", [["models"], ["--help"], ["render", "lambert"],
                                  ["eval", "lambert", "--theta-i", "0", "--theta-r", "0",
                                   "--phi-r", "0"]])
def test_full_disk_is_one_line_nonzero(argv):
    with open("/dev/full", "w") as full:
        p = subprocess.run([sys.executable, "-m", "tuibrdf", *argv], stdout=full,
                           stderr=subprocess.PIPE, env={**os.environ, "PYTHONPATH": str(ROOT)},
                           timeout=120)
    assert p.returncode != 0
    assert "No space left" in no_traceback_one_line(p.stderr)


@pytest.mark.parametrize("argv", [["render", "lambert"], ["models"]])
def test_closed_stdout_is_one_line_nonzero(argv):
    """`tuibrdf render lambert >&-`: Python starts with sys.stdout = None."""
    p = subprocess.run([sys.executable, "-m", "tuibrdf", *argv], stdout=subprocess.DEVNULL,
                       stderr=subprocess.PIPE, env={**os.environ, "PYTHONPATH": str(ROOT)},
                       timeout=120, preexec_fn=lambda: os.close(1))
    assert p.returncode != 0
    assert "standard output is closed" in no_traceback_one_line(p.stderr)


# ------------------------------------------------------------------ locales (item 5)

#: environments whose output encoding cannot show θ: Latin-1 and ASCII.  LANG=C alone gives
#: UTF-8 (Python coerces the C locale), so the ASCII case also turns the coercion off.
LOCALES = {
    "PYTHONIOENCODING=latin-1": {"PYTHONIOENCODING": "latin-1"},
    "PYTHONIOENCODING=ascii": {"PYTHONIOENCODING": "ascii"},
    "LANG=C ascii": {"LANG": "C", "LC_ALL": "C", "PYTHONUTF8": "0",
                     "PYTHONCOERCECLOCALE": "0"},
}
VALID = {
    "models": ["models"],
    "materials": ["materials"],
    "help": ["--help"],
    "eval help": ["eval", "--help"],
    "albedo": ["albedo", "phong", "--theta-i", "30"],
    "eval": ["eval", "cook-torrance", "--theta-i", "30", "--theta-r", "30", "--phi-r", "0"],
    "render": ["render", "phong", "--view", "all", "--width", "40", "--height", "10"],
    "render colour": ["render", "phong", "--color", "256", "--width", "40", "--height", "10"],
    "render solid": ["render", "phong", "--view", "solid", "--width", "40", "--height", "10"],
}


@pytest.mark.parametrize("loc", list(LOCALES))
@pytest.mark.parametrize("cmd", list(VALID))
def test_valid_commands_work_in_a_non_utf8_locale(loc, cmd):
    p = cli(*VALID[cmd], env=LOCALES[loc])
    assert p.returncode == 0, p.stderr.decode("latin-1")
    assert p.stderr == b""
    enc = "ascii" if "ascii" in loc else "latin-1"
    out = p.stdout.decode(enc)  # raises if a byte is not of the locale's encoding
    assert "?" not in out.replace("'?'", ""), out  # every character had a stand-in
    if cmd in ("models", "albedo", "eval"):
        assert "θ" not in out and ("theta" in out or cmd == "models")
    if cmd == "render":
        assert "sr^-1" in out  # ⁻¹ → ^-1 even in Latin-1, which has ¹ but not ⁻


def test_a_latin1_locale_error_is_one_line():
    p = cli("eval", "phong", "-p", "kd=2", "--theta-i", "0", "--theta-r", "0", "--phi-r", "0",
            env={"PYTHONIOENCODING": "ascii"})
    assert p.returncode == 2
    assert "kd" in no_traceback_one_line(p.stderr)


def test_real_latin1_locale_if_installed():
    """With a real ISO-8859-1 locale (when the machine has one), not just PYTHONIOENCODING."""
    avail = subprocess.run(["locale", "-a"], capture_output=True, text=True).stdout.split() \
        if os.path.exists("/usr/bin/locale") else []
    loc = next((a for a in avail if a.lower().replace("-", "").endswith("iso88591")), None)
    if loc is None:
        pytest.skip("no Latin-1 locale installed")
    p = cli("albedo", "phong", "--theta-i", "30", env={"LANG": loc, "LC_ALL": loc})
    assert p.returncode == 0 and p.stderr == b""
    p.stdout.decode("latin-1")


def test_to_ascii_stand_ins():
    """The issue's list: θ → theta, ⁻¹ → ^-1, · → *, box and half blocks → ASCII."""
    stream = io.TextIOWrapper(io.BytesIO(), encoding="ascii")
    assert to_stream("θi=30° f·cos 1.8 sr⁻¹", stream) == "theta_i=30 deg f*cos 1.8 sr^-1"
    assert to_ascii("─") == "-" and to_ascii("│") == "|" and to_ascii("┼") == "+"
    assert to_ascii("█") == "@" and to_ascii("▀") in ".:-=+*#%@"
    assert to_ascii("\u2800") == " " and to_ascii("\u28ff") == "#"
    assert to_ascii("ö") == "o" and to_ascii("é") == "e" and to_ascii("☃") == "?"
    latin = io.TextIOWrapper(io.BytesIO(), encoding="latin-1")
    assert to_stream("30° sr⁻¹ ·", latin) == "30° sr^-1 ·"  # what Latin-1 has stays
    assert can_encode(io.StringIO())  # a str buffer takes anything


# ------------------------------------------------------------------ one line (item 8)


@pytest.mark.parametrize("argv", [
    ["eval", "lam\nbert", "--theta-i", "0", "--theta-r", "0", "--phi-r", "0"],
    ["fit", "a\nb\nc\nd\ne\nf\ng\nh\ni.binary", "--model", "ggx"],
    ["eval", "phong", "-p", "k\nd=1", "--theta-i", "0", "--theta-r", "0", "--phi-r", "0"],
    ["eval", "phong", "--theta-i", "3\n0", "--theta-r", "0", "--phi-r", "0"],
    ["models", "ph\nong"],
    ["render", "phong", "--view", "m\nap"],
    ["models", "--j\nson"],
    ["l\x1b[2Jx"],
    ["view", "--preset", "a\nb"],
])
def test_newlines_in_arguments_stay_one_line(capsys, argv):
    rc = main(argv)
    err = capsys.readouterr().err
    assert rc == 2
    assert len(err.strip().splitlines()) == 1, err
    assert "\x1b" not in err  # an escape sequence is shown, not sent to the terminal


def test_one_line_escapes_controls():
    assert one_line("a\nb\tc\x1b[0m\x7f\u2028") == "a\\nb\\tc\\x1b[0m\\x7f\\u2028"
    assert one_line("θ é") == "θ é"


# ------------------------------------------------------------------ --help stays light


def test_help_and_argument_errors_do_not_import_numpy_and_help_not_typing_or_json():
    """Issue 16: `tuibrdf --help` paid for numpy (~60 ms), then for typing, json and shutil
    (≈ 3, 2 and 4 ms) and every command's module.  --help of every command must import none
    of them beyond what argparse itself does, in an interpreter without site (which imports
    more on some machines), nor another command's module; an argparse error not numpy (a
    typo's close match may import the declarations)."""
    code = ("import sys, argparse, math, os, re, textwrap\nbefore = set(sys.modules)\n"
            "from tuibrdf.cli import main\n"
            "for argv in (['--help'], ['view', '--help'], ['fit', '--help'],"
            " ['render', '--help'], ['albedo', '--help'], ['models', '--help'],"
            " ['materials', '--help']):\n"
            "    main(argv)\n"
            "print(sorted({'numpy', 'typing', 'json', 'shutil', 'tuibrdf.cli.eval'}"
            " & (set(sys.modules) - before)))\n"
            "for argv in (['eval', 'x', '--theta-i', '99'], ['modls'], ['eval', 'phong', '-p']):\n"
            "    main(argv)\n"
            "print('numpy' in sys.modules)\n")
    p = subprocess.run([sys.executable, "-S", "-c", code], capture_output=True, text=True,
                       env={**os.environ, "PYTHONPATH": str(ROOT)}, timeout=120)
    assert p.stdout.strip().splitlines()[-2:] == ["[]", "False"], p.stdout + p.stderr


def test_fit_stride_default_agrees_with_the_core():
    from tuibrdf.cli.fit import STRIDE
    from tuibrdf.core.fit import STRIDE as CORE

    assert STRIDE == CORE


@pytest.mark.parametrize("columns", ["40", "80", "137", "", "junk", "-5", None])
@pytest.mark.parametrize("argv", [["--help"], ["eval", "--help"], ["view", "--help"]])
def test_help_is_as_wide_as_argparse_makes_it(monkeypatch, capsys, columns, argv):
    # the help's width is found without shutil (common.Formatter): the same text as
    # argparse's own formatter gives, whatever COLUMNS says
    import argparse

    from tuibrdf.cli import common

    if columns is None:
        monkeypatch.delenv("COLUMNS", raising=False)
    else:
        monkeypatch.setenv("COLUMNS", columns)
    assert main(argv) == 0
    ours = capsys.readouterr().out
    monkeypatch.setattr(common, "Formatter", argparse.HelpFormatter)
    assert main(argv) == 0
    assert ours == capsys.readouterr().out
    if columns == "40" and argv == ["--help"]:  # (a long option's usage can overflow)
        assert max(map(len, ours.splitlines())) <= 38
