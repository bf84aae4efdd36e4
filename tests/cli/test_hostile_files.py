"""Hostile files: malformed presets, FIFOs, directories, unwritable places (issue 17, 2–4, 8).

Every case is a reproduction from the issue: the promise is one line naming the file and the
problem (``PresetError`` in Python, exit 2 in the CLI), never a traceback and never a hang.
Cases that could hang (a FIFO) run in a subprocess with a timeout, so a regression fails the
test instead of freezing the suite.
"""

from __future__ import annotations

import os
import stat
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from tests import ROOT
from tests.merl_writer import write_merl
from tuibrdf.cli import main
from tuibrdf.core.formats.files import describe, open_regular, read_regular
from tuibrdf.state import presets
from tuibrdf.state.presets import PresetError, list_presets, load_preset, save_preset
from tuibrdf.state.viewer import Side, ViewerState

TIMEOUT = 60  # generous: a hang is minutes, a slow shared machine is seconds
fifo_only = pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="needs mkfifo")


@pytest.fixture
def cfg(tmp_path, monkeypatch):
    """An empty presets directory of our own (XDG_CONFIG_HOME)."""
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path / "cfg"))
    d = tmp_path / "cfg" / "tuibrdf" / "presets"
    d.mkdir(parents=True)
    return d


def cli(*argv: str, env: dict | None = None, stdin=subprocess.DEVNULL, **kw):
    """``python -m tuibrdf ARGV`` with a timeout: (rc, stdout, stderr)."""
    e = {**os.environ, "PYTHONPATH": str(ROOT), **(env or {})}
    p = subprocess.run([sys.executable, "-m", "tuibrdf", *argv], capture_output=True,
                       text=True, env=e, stdin=stdin, timeout=TIMEOUT, **kw)
    return p.returncode, p.stdout, p.stderr


def one_line_error(err: str) -> str:
    assert "Traceback" not in err, err
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    return lines[0]


# ------------------------------------------------------------------ malformed presets (item 2)

PRESET_HEAD = 'theta_i = 30\n[[sides]]\nmodel = "phong"\n'

#: (file content, words of the message): the issue's reproductions and their neighbours
MALFORMED = {
    "400-digit integer": (PRESET_HEAD + "params = { kd = " + "9" * 400 + " }\n",
                          ["kd", "400 digits"]),
    "400-digit theta": ("theta_i = " + "9" * 400 + "\n", ["theta_i", "[0, 90]"]),
    "600-deep nesting": ("a = " + "[" * 600 + "]" * 600 + "\n", ["nested too deeply"]),
    "5000-digit number": ("theta_i = " + "9" * 5000 + "\n", ["too many digits"]),
    "not TOML": ("theta_i = = 3\n", ["not valid TOML"]),
    "no sides": ("theta_i = 30\n", ["[[sides]]"]),
    "three sides": (PRESET_HEAD + '[[sides]]\nmodel = "phong"\n[[sides]]\nmodel = "phong"\n',
                    ["one or two"]),
    "unknown model": ('[[sides]]\nmodel = "phongg"\n', ["unknown model", "phong"]),
    "inf parameter": (PRESET_HEAD + "params = { kd = inf }\n", ["kd", "[0, 1]"]),
    "nan theta": ("theta_i = nan\n", ["theta_i"]),
    "params not a table": (PRESET_HEAD + "params = 3\n", ["params must be a table"]),
    "bool theta": ("theta_i = true\n", ["theta_i"]),
}


@pytest.mark.parametrize("case", list(MALFORMED))
def test_malformed_preset_is_one_preset_error(cfg, case):
    text, words = MALFORMED[case]
    (cfg / "bad.toml").write_text(text)
    with pytest.raises(PresetError) as e:
        load_preset("bad")
    msg = str(e.value)
    assert "\n" not in msg and len(msg) < 400, msg
    assert str(cfg / "bad.toml") in msg  # names the file
    for w in words:
        assert w in msg


@pytest.mark.parametrize("case", ["400-digit integer", "600-deep nesting", "5000-digit number"])
def test_view_preset_malformed_is_one_line_exit_2(cfg, case):
    """`tuibrdf view --preset` on the issue's files: one line, exit 2 (was a traceback)."""
    (cfg / "bad.toml").write_text(MALFORMED[case][0])
    rc, out, err = cli("view", "--preset", "bad",
                       env={"XDG_CONFIG_HOME": str(cfg.parents[1])})
    assert rc == 2
    assert "bad.toml" in one_line_error(err)


def test_preset_that_is_not_utf8_or_too_large(cfg):
    (cfg / "latin.toml").write_bytes(b'theta_i = 30 # caf\xe9\n')
    with pytest.raises(PresetError, match="not UTF-8"):
        load_preset("latin")
    (cfg / "huge.toml").write_bytes(b"#" * (presets.MAX_BYTES + 1))
    with pytest.raises(PresetError, match="too large"):
        load_preset("huge")


def test_preset_that_is_a_directory(cfg):
    (cfg / "dir.toml").mkdir()
    with pytest.raises(PresetError, match="is a directory"):
        load_preset("dir")
    assert list_presets() == []  # a directory is not listed as a preset


@fifo_only
def test_preset_that_is_a_fifo_does_not_block(cfg):
    """The issue: a FIFO preset froze the viewer's event loop (open() waits for a writer)."""
    os.mkfifo(cfg / "pipe.toml")
    t = time.monotonic()
    with pytest.raises(PresetError, match="FIFO"):
        load_preset("pipe")
    assert time.monotonic() - t < TIMEOUT
    rc, _, err = cli("view", "--preset", "pipe", env={"XDG_CONFIG_HOME": str(cfg.parents[1])})
    assert rc == 2 and "FIFO" in one_line_error(err)


@fifo_only
def test_preset_whose_merl_file_is_a_fifo(cfg, tmp_path):
    os.mkfifo(tmp_path / "data.binary")
    (cfg / "m.toml").write_text(f'[[sides]]\nmodel = "merl"\n'
                                f'params = {{ file = "{tmp_path / "data.binary"}" }}\n')
    rc, _, err = cli("view", "--preset", "m", env={"XDG_CONFIG_HOME": str(cfg.parents[1])})
    assert rc == 2
    line = one_line_error(err)
    assert "data.binary" in line and "FIFO" in line


# ------------------------------------------------------------------ FIFOs elsewhere (item 3)


@fifo_only
@pytest.mark.parametrize("how", ["fifo", "symlink"])
def test_fit_on_a_fifo_or_a_link_to_one(tmp_path, how):
    os.mkfifo(tmp_path / "f.binary")
    target = tmp_path / "f.binary"
    if how == "symlink":
        (tmp_path / "l.binary").symlink_to(target)
        target = tmp_path / "l.binary"
    rc, _, err = cli("fit", str(target), "--model", "ggx")
    assert rc == 2
    assert "FIFO" in one_line_error(err)


@fifo_only
@pytest.mark.parametrize("argv", [
    ["eval", "merl", "-p", "file={f}", "--theta-i", "0", "--theta-r", "0", "--phi-r", "0"],
    ["albedo", "merl", "-p", "file={f}"],
    ["render", "merl", "-p", "file={f}"],
    ["view", "{f}"],
])
def test_merl_fifo_everywhere(tmp_path, argv):
    os.mkfifo(tmp_path / "f.binary")
    rc, _, err = cli(*[a.format(f=tmp_path / "f.binary") for a in argv])
    assert rc == 2
    assert "FIFO" in one_line_error(err)


def test_view_without_a_terminal_is_one_line(tmp_path):
    """`tuibrdf view` with stdin and stdout not a terminal hung (Textual waiting for keys)."""
    rc, out, err = cli("view")
    assert rc == 2
    assert "terminal" in one_line_error(err)
    rc, out, _ = cli()  # plain `tuibrdf` without a terminal: the help
    assert rc == 0 and "usage" in out


def test_open_regular_refuses_what_is_not_a_file(tmp_path):
    with pytest.raises(OSError, match="is a directory"):
        open_regular(tmp_path)
    with pytest.raises(FileNotFoundError):
        open_regular(tmp_path / "none")
    with pytest.raises(OSError, match="NUL"):
        open_regular("a\0b")
    (tmp_path / "ok").write_bytes(b"xyz")
    assert read_regular(tmp_path / "ok", 3) == b"xyz"
    with pytest.raises(OSError, match="too large"):
        read_regular(tmp_path / "ok", 2)
    if os.path.exists("/dev/null"):
        with pytest.raises(OSError, match="character device"):
            open_regular("/dev/null")


def test_describe_says_what_a_path_is(tmp_path):
    assert describe(tmp_path / "none") == "no such file"
    assert describe(tmp_path).startswith("is a directory")
    (tmp_path / "dangling").symlink_to(tmp_path / "nowhere")
    assert describe(tmp_path / "dangling") == "broken symbolic link"
    (tmp_path / "f").write_bytes(b"")
    assert describe(tmp_path / "f") == ""
    if hasattr(os, "mkfifo"):
        os.mkfifo(tmp_path / "p")
        assert "FIFO" in describe(tmp_path / "p")


# ------------------------------------------------------------------ directories (item 8)


def test_directory_as_merl_file_says_directory(tmp_path, capsys):
    d = tmp_path / "dir.binary"
    d.mkdir()
    rc = main(["eval", "merl", "-p", f"file={d}", "--theta-i", "0", "--theta-r", "0",
               "--phi-r", "0"])
    err = capsys.readouterr().err
    assert rc == 2 and "is a directory" in one_line_error(err)
    rc = main(["fit", str(d), "--model", "ggx"])
    err = capsys.readouterr().err
    assert rc == 2 and "is a directory" in one_line_error(err)


@pytest.mark.parametrize("bad", [np.nan, np.inf])
def test_view_rejects_non_finite_merl_like_eval(tmp_path, capsys, monkeypatch, bad):
    """`view` opened a NaN/inf MERL file that `eval` rejects: both say the same now."""
    table = np.full((3, 90, 90, 180), 0.1)
    table[1, 3, 4, 5] = bad
    f = write_merl(tmp_path / "bad.binary", table)
    import tuibrdf.cli.view as view

    opened = []
    monkeypatch.setattr(view, "open_viewer", lambda *a: opened.append(a))
    monkeypatch.setattr(view, "check_terminal", lambda: None)
    rc = main(["view", str(f)])
    err_view = one_line_error(capsys.readouterr().err)
    rc_eval = main(["eval", "merl", "-p", f"file={f}", "--theta-i", "0", "--theta-r", "0",
                    "--phi-r", "0"])
    err_eval = one_line_error(capsys.readouterr().err)
    assert (rc, rc_eval) == (2, 2) and not opened
    kind = "NaN" if np.isnan(bad) else "infinite"
    assert kind in err_view and kind in err_eval


# ------------------------------------------------------------------ saving (item 4)

STATE = ViewerState(sides=[Side.of("phong", {"kd": 0.1})], theta_i=20.0)


def test_save_into_a_read_only_directory(cfg):
    if os.geteuid() == 0:
        pytest.skip("root writes into read-only directories")
    cfg.chmod(stat.S_IRUSR | stat.S_IXUSR)
    try:
        with pytest.raises(PresetError, match="cannot save preset 'x'"):
            save_preset(STATE, "x")
    finally:
        cfg.chmod(stat.S_IRWXU)


def test_save_when_the_presets_path_is_a_file(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path))
    (tmp_path / "tuibrdf").write_text("not a directory")
    with pytest.raises(PresetError, match="cannot create"):
        save_preset(STATE, "x")
    assert list_presets() == []


def test_save_onto_a_directory_of_that_name(cfg):
    (cfg / "x.toml").mkdir()
    with pytest.raises(PresetError, match="is a directory"):
        save_preset(STATE, "x")


def test_save_on_a_full_disk_leaves_nothing(cfg, monkeypatch):
    """ENOSPC while writing: a PresetError, no half file, no temporary file left."""
    import errno

    real_fsync = os.fsync

    def full(fd):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(presets.os, "fsync", full)
    with pytest.raises(PresetError, match="No space left"):
        save_preset(STATE, "x")
    monkeypatch.setattr(presets.os, "fsync", real_fsync)
    assert sorted(p.name for p in cfg.iterdir()) == []


@pytest.mark.skipif(not os.path.exists("/dev/full"), reason="needs /dev/full")
def test_fit_save_preset_errors_are_one_line(tmp_path):
    """`fit --save-preset` where the presets path is a file (and so cannot be created)."""
    table = np.full((3, 90, 90, 180), 0.05)
    f = write_merl(tmp_path / "grey.binary", table)
    (tmp_path / "cfg").write_text("a file where the config directory should be")
    rc, out, err = cli("fit", str(f), "--model", "gltf", "--stride", "9,9,45",
                       "--save-preset", "p", env={"XDG_CONFIG_HOME": str(tmp_path / "cfg")})
    assert rc == 2
    assert "cannot save preset 'p'" in one_line_error(err)


def test_stale_temporary_files_are_removed(cfg):
    """A killed save leaves `.NAME.toml.XXXX.partial`; old ones go on the next save or list,
    fresh ones (a save in progress elsewhere) stay, and other files are never touched."""
    stale = cfg / ".a.toml.abc123.partial"
    fresh = cfg / ".b.toml.def456.partial"
    other = cfg / "notes.txt"
    for p in (stale, fresh, other):
        p.write_text("x")
    old = time.time() - presets.STALE_SECONDS - 10
    os.utime(stale, (old, old))
    os.utime(other, (old, old))
    assert list_presets() == []
    assert not stale.exists() and fresh.exists() and other.exists()
    os.utime(fresh, (old, old))
    save_preset(STATE, "c")
    assert not fresh.exists() and other.exists()
    assert list_presets() == ["c"]


def test_a_save_uses_a_recognisable_temporary_name(cfg, monkeypatch):
    seen = []
    real = os.replace

    def spy(src, dst):
        seen.append(Path(src).name)
        return real(src, dst)

    monkeypatch.setattr(presets.os, "replace", spy)
    save_preset(STATE, "named")
    assert len(seen) == 1
    assert seen[0].startswith(".named.toml.") and seen[0].endswith(presets.TMP_SUFFIX)
    assert load_preset("named")[0] == 20.0


@pytest.mark.parametrize("code, words", [(13, "Permission denied"), (30, "Read-only")])
def test_save_permission_or_read_only_filesystem(cfg, monkeypatch, code, words):
    """EACCES / EROFS from the temporary file (what a read-only directory gives a non-root
    user, and a read-only mount gives root too): one PresetError naming the preset."""
    def refuse(*a, **k):
        raise OSError(code, os.strerror(code))

    monkeypatch.setattr(presets.tempfile, "mkstemp", refuse)
    with pytest.raises(PresetError, match=words) as e:
        save_preset(STATE, "x")
    assert "'x'" in str(e.value) and str(cfg) in str(e.value)


def test_fit_save_preset_fails_before_the_fit(tmp_path, capsys, monkeypatch):
    """A presets path that cannot be written is reported before minutes of fitting."""
    import tuibrdf.core.fit as core_fit

    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path / "cfg"))
    (tmp_path / "cfg").write_text("a file")
    called = []
    monkeypatch.setattr(core_fit, "fit_file", lambda *a, **k: called.append(a))
    rc = main(["fit", str(tmp_path / "x.binary"), "--model", "gltf", "--save-preset", "p"])
    assert rc == 2 and not called
    assert "cannot save preset 'p'" in one_line_error(capsys.readouterr().err)


KILLER = """
import os, sys, time
from tuibrdf.state import presets
from tuibrdf.state.viewer import Side, ViewerState
state = ViewerState(sides=[Side.of("phong", {"kd": 0.1})], theta_i=20.0)
presets.save_preset(state, "k")          # a complete preset first
def slow(fd):
    print("writing", flush=True)
    time.sleep(60)                        # killed here, the temporary file written
presets.os.fsync = slow
presets.save_preset(state, "k")
"""


@pytest.mark.skipif(not hasattr(os, "kill"), reason="needs signals")
def test_sigkill_mid_save_leaves_the_old_preset_and_a_removable_temporary(cfg):
    """The issue's 400 SIGKILLs: never half a preset (kept), 281 leftover .tmp files (fixed:
    they are recognisable and removed once stale)."""
    import signal

    p = subprocess.Popen([sys.executable, "-c", KILLER], stdout=subprocess.PIPE, text=True,
                         env={**os.environ, "PYTHONPATH": str(ROOT)})
    try:
        assert p.stdout.readline().strip() == "writing"
    finally:
        p.send_signal(signal.SIGKILL)
        p.wait(timeout=TIMEOUT)
        p.stdout.close()
    left = [f for f in cfg.iterdir() if f.name.endswith(presets.TMP_SUFFIX)]
    assert len(left) == 1 and left[0].name.startswith(".k.toml.")
    assert load_preset("k")[0] == 20.0  # the old preset, whole
    assert presets.clean_stale(cfg) == 0  # fresh: maybe a save in progress, kept
    assert presets.clean_stale(cfg, now=time.time() + presets.STALE_SECONDS + 1) == 1
    assert sorted(f.name for f in cfg.iterdir()) == ["k.toml"]
