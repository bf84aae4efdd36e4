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


# ------------------------------------------------------------------ hostile model files (issue 31)
# Each is written here; the promise: one line naming the file (and the line for a shader), exit 2
# in the CLI, ValueError in the API, and a bounded cost: peak memory is read from the child's
# own getrusage (a generous bound: the package's imports take ~30 MB; the issue's files took
# 1.4–4 GB), time only through the subprocess timeout.

RSS_BOUND_KB = 400_000

# The child's own peak: VmHWM of /proc/self/status (this process image only); getrusage's
# ru_maxrss is the fallback, but on Linux it keeps the parent's peak across fork and exec
# (pytest's own hundreds of MB would count).
_RUN_MEASURED = (
    "import resource, sys\n"
    "from tuibrdf.cli import main\n"
    "rc = main(sys.argv[1:])\n"
    "sys.stdout.flush()\n"
    "kb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss\n"
    "try:\n"
    "    with open('/proc/self/status') as f:\n"
    "        kb = next(int(x.split()[1]) for x in f if x.startswith('VmHWM:'))\n"
    "except (OSError, StopIteration):\n"
    "    pass\n"
    "print('RSS', kb, file=sys.stderr)\n"
    "sys.exit(rc)\n"
)


def cli_measured(*argv: str):
    """``tuibrdf ARGV`` in a child that reports its peak RSS: (rc, stdout, stderr, KB)."""
    e = {**os.environ, "PYTHONPATH": str(ROOT)}
    p = subprocess.run([sys.executable, "-c", _RUN_MEASURED, *argv], capture_output=True,
                       text=True, env=e, timeout=TIMEOUT, stdin=subprocess.DEVNULL)
    lines = p.stderr.strip().splitlines()
    assert lines and lines[-1].startswith("RSS "), p.stderr
    return p.returncode, p.stdout, "\n".join(lines[:-1]), int(lines[-1].split()[1])


def brdf_file(path: Path, shader: str, params: str = "float kd 0 1 0.5") -> Path:
    path.write_text(f"analytic\n::begin parameters\n{params}\n::end parameters\n"
                    f"::begin shader\n{shader}\n::end shader\n")
    return path


BRDF_HEAD = "vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)"


def _specialisation_bomb() -> str:
    """The issue's compile bomb: each helper calls the next with two constants derived from its
    own, so every level doubles the specialised copies (2^23 in all)."""
    lines = ["float h24(float x, float k) { return x * k; }"]
    for i in range(23, 0, -1):
        lines.append(f"float h{i}(float x, float k) {{ return h{i + 1}(x, k * 2.0) + "
                     f"h{i + 1}(x, k * 2.0 + 1.0); }}")
    return "\n".join(lines) + f"\n{BRDF_HEAD} {{ return vec3(h1(kd, 1.0)); }}"


def _call_tree_bomb() -> str:
    """The issue's run bomb: no constants, but each helper calls the next twice (2^21 calls)."""
    lines = ["float g22(float x) { return x * 0.5; }"]
    for i in range(21, 0, -1):
        lines.append(f"float g{i}(float x) {{ return g{i + 1}(x) + g{i + 1}(x * 0.5); }}")
    return "\n".join(lines) + f"\n{BRDF_HEAD} {{ return vec3(g1(kd * L.z)); }}"


def _long_shader(statements: int) -> str:
    body = "\n".join(["  x = x * 0.999 + kd * L.z;"] * statements)
    return f"{BRDF_HEAD} {{\n  float x = 0.0;\n{body}\n  return vec3(x);\n}}"


BOMBS = {
    # name: (shader, the words of the message, the line the message names)
    "specialised copies": (_specialisation_bomb(), "specialised copies", None),
    "call tree": (_call_tree_bomb(), "call tree is too large", None),
    "generated code": (_long_shader(3000), "too large to translate", None),
    "nested parentheses": (f"{BRDF_HEAD} {{ return vec3({'(' * 40000}kd{')' * 40000}); }}",
                           "nests too deeply", None),
    "operator chain": (f"{BRDF_HEAD} {{ return vec3(kd{' + kd' * 25000}); }}",
                       "nests too deeply", None),
}


@pytest.mark.parametrize("case", list(BOMBS))
def test_brdf_bombs_fail_fast_with_file_and_line(tmp_path, case):
    shader, words, _ = BOMBS[case]
    f = brdf_file(tmp_path / "bomb.brdf", shader)
    assert f.stat().st_size < 128 * 1024
    rc, out, err, kb = cli_measured("eval", str(f), "--theta-i", "30", "--theta-r", "30",
                                    "--phi-r", "180")
    line = one_line_error(err)
    assert rc == 2 and out == ""
    assert f"{f}:" in line and words in line, line
    where = line.split(f"{f}:")[1].split(":")[0]
    assert where.isdigit() and 6 <= int(where) <= 6 + shader.count("\n"), line  # a shader line
    assert kb < RSS_BOUND_KB


def test_brdf_file_over_the_size_budget(tmp_path):
    """The issue's 4 MB file took 12–27 s and 1.4 GB; over 128 KB it is refused unread."""
    f = brdf_file(tmp_path / "big.brdf", _long_shader(150_000))
    assert f.stat().st_size > 4_000_000
    rc, _, err, kb = cli_measured("render", str(f))
    assert rc == 2 and "too large" in one_line_error(err) and "128 KB" in err
    assert kb < RSS_BOUND_KB


def test_brdf_within_the_budgets_still_runs(tmp_path):
    """A file near the run-time budget (a helper of 200 lines called 45 times: ~9,400
    operations a value) is not refused, and renders within the memory bound."""
    helper = "float h(float x) {\n  float y = x;\n" + "  y = y * 0.999 + x * 0.001;\n" * 50 + \
        "  return y;\n}\n"
    calls = "".join(f"  s += h(L.z * {i}.0 + V.z);\n" for i in range(45))
    f = brdf_file(tmp_path / "ok.brdf",
                  helper + f"{BRDF_HEAD} {{\n  float s = 0.0;\n{calls}  return vec3(s * kd);\n}}")
    rc, out, err, kb = cli_measured("render", str(f), "--width", "40", "--height", "12")
    assert rc == 0, err
    assert kb < RSS_BOUND_KB


def test_brdf_temporaries_are_bounded(tmp_path):
    """A long BRDF (9,600 generated lines, within the budgets) keeps every temporary until it
    returns: `render --view all` took 1.9 GB and `albedo` 0.9 GB; evaluated in chunks, the
    temporaries take at most 64 MB."""
    f = brdf_file(tmp_path / "wide.brdf", _long_shader(2400))
    for argv in (("render", "--view", "all", "--width", "60", "--height", "16"), ("albedo",)):
        rc, _, err, kb = cli_measured(*argv, str(f))
        assert rc == 0, err
        assert kb < 250_000, argv  # imports ~30 MB + 64 MB of temporaries + the frame


@pytest.mark.parametrize("ret", ["vec3(kd * L.z * V.z, L.z, V.z)", "kd * L.z * V.z"])
def test_brdf_chunked_evaluation_is_the_whole(tmp_path, monkeypatch, ret):
    """Evaluated in chunks of 256 directions (the temporaries' bound made tiny), a shader gives
    its closed form on every direction, one light or many, and 0 below the horizon."""
    from tuibrdf.core.evaluate import evaluate_resolved
    from tuibrdf.core.formats.brdf_explorer import load_brdf
    from tuibrdf.core.formats.glsl import budgets

    monkeypatch.setattr(budgets, "MAX_TEMP_BYTES", 1)
    rtype = "vec3" if ret.startswith("vec3") else "float"
    f = brdf_file(tmp_path / "c.brdf", f"{rtype} BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) "
                                       f"{{ return {ret}; }}")
    m = load_brdf(str(f), "t")
    rng = np.random.default_rng(7)
    wo = rng.normal(size=(37, 29, 3))
    wo /= np.linalg.norm(wo, axis=-1, keepdims=True)  # both hemispheres
    for wi in (np.array([0.6, 0.0, 0.8]), wo[::-1, ::-1]):
        wi_b = np.broadcast_to(wi, wo.shape)
        got = np.asarray(evaluate_resolved(m, m.resolve({"kd": 0.5}), wi_b, wo))
        zi, zo = wi_b[..., 2], wo[..., 2]
        above = (zi >= 0) & (zo >= 0)
        want = np.where(above, 0.5 * zi * zo, 0.0)
        if rtype == "vec3":  # negative components clamped to 0 (none above the horizon)
            want = np.stack([want, np.where(above, zi, 0.0), np.where(above, zo, 0.0)], -1)
        assert got.shape == want.shape
        assert np.allclose(got, want, rtol=0, atol=1e-15)


def _brdf_value(path: Path, **params) -> np.ndarray:
    from tuibrdf.core.evaluate import evaluate_resolved
    from tuibrdf.core.formats.brdf_explorer import load_brdf

    m = load_brdf(str(path), "t")
    wi = np.array([[0.0, 0.0, 1.0]])
    return np.asarray(evaluate_resolved(m, m.resolve(params), wi, wi))[0]


# IEEE: 1e999 is +inf, inf < 1 is false, exp(1000) overflows to inf, inf − inf, floor(nan) and
# sin(inf) are NaN, and NaN == NaN is false.  So each shader returns 0.5 (else 0.25).
IEEE_SHADERS = {
    "1e999 < 1.0": "return vec3(1e999 < 1.0 ? 0.25 : 0.5);",
    "exp(1000.0)": "return vec3(exp(1000.0) > 1e308 ? 0.5 : 0.25);",
    "floor(nan)": "float a = floor(1e999 - 1e999); return vec3(a == a ? 0.25 : 0.5);",
    "sin(inf)": "float a = sin(1e999); return vec3(a == a ? 0.25 : 0.5);",
    "ceil(inf)": "return vec3(ceil(1e999) > 1e308 ? 0.5 : 0.25);",
    "min(nan, 1)": "float a = min(1e999 - 1e999, 1.0); return vec3(a == a ? 0.25 : 0.5);",
    "const global": "const float big = exp(1e999); return vec3(big > 1.0 ? 0.5 : 0.25);",
}


@pytest.mark.parametrize("case", list(IEEE_SHADERS))
def test_glsl_folding_follows_ieee(tmp_path, case):
    body = IEEE_SHADERS[case]
    if body.startswith("const"):
        glob, body = body.split("; ", 1)
        shader = f"{glob};\n{BRDF_HEAD} {{ {body} }}"
    else:
        shader = f"{BRDF_HEAD} {{ {body} }}"
    f = brdf_file(tmp_path / "ieee.brdf", shader)
    assert np.all(_brdf_value(f) == 0.5)
    rc, out, err = cli("eval", str(f), "--theta-i", "0", "--theta-r", "0", "--phi-r", "0")
    assert rc == 0 and err == "" and "0.5" in out


def test_glsl_brdf_with_out_parameters_refused_at_load(tmp_path):
    from tuibrdf.core.formats.brdf_explorer import load_brdf

    for qual in ("out", "inout"):
        f = brdf_file(tmp_path / f"{qual}.brdf", f"vec3 BRDF(vec3 L, vec3 V, {qual} vec3 N, "
                      "vec3 X, vec3 Y) {\n  N = L;\n  return vec3(kd);\n}")
        with pytest.raises(ValueError, match=rf"{f}:6: BRDF's parameter 'N' is '{qual}'"):
            load_brdf(str(f), "t")
        rc, _, err = cli("render", str(f))
        assert rc == 2 and f"{f}:6:" in one_line_error(err)


def test_generated_names_never_collide(tmp_path):
    """`color c` and `float c_0` are independent: c_0 reads its own value, not c's red."""
    params = "color c 0.1 0.2 0.3\nfloat c_0 0 1 0.9"
    f = brdf_file(tmp_path / "c0.brdf", f"{BRDF_HEAD} {{ return vec3(c_0); }}", params)
    assert np.allclose(_brdf_value(f), 0.9, rtol=0, atol=1e-15)
    assert np.allclose(_brdf_value(f, c_0=0.4, c=(0.7, 0.7, 0.7)), 0.4, rtol=0, atol=1e-15)
    g = brdf_file(tmp_path / "c.brdf", f"{BRDF_HEAD} {{ return c * (1.0 + c_0); }}", params)
    assert np.allclose(_brdf_value(g, c_0=1.0), (0.2, 0.4, 0.6), rtol=0, atol=1e-15)


# --- RGL .bsdf


def _bsdf(path: Path, **kw) -> Path:
    from tests.rgl_writer import material, write_tensor

    fields = material(n=5, n_theta=2)
    fields.update(kw.pop("fields", {}))
    return write_tensor(path, fields, **kw)


def test_bsdf_overlapping_fields_allocate_nothing(tmp_path):
    """The issue's 9.4 MB file: 240 fields declared over one 9.4 MB block allocated 2.2 GB."""
    import io

    from tests.rgl_writer import material, tensor_bytes
    from tuibrdf.core.formats.rgl_bsdf import read_header

    n = 9_400_000
    fields = material(n=5, n_theta=2)
    fields["pad"] = np.zeros(n, np.uint8)
    aliases = [f"x{k}" for k in range(240)]
    fields.update({a: np.zeros(1, np.uint8) for a in aliases})
    first = tensor_bytes(fields)
    off = read_header(io.BytesIO(first), "x", len(first))["pad"].offset
    data = tensor_bytes(fields, shapes={a: (n,) for a in aliases},
                        offsets={a: off for a in aliases})
    (tmp_path / "alias.bsdf").write_bytes(data)
    rc, _, err, kb = cli_measured("models", str(tmp_path / "alias.bsdf"))
    line = one_line_error(err)
    assert rc == 2 and "alias.bsdf" in line and "overlaps" in line
    assert kb < RSS_BOUND_KB


def test_bsdf_known_fields_overlapping_each_other_or_the_header(tmp_path):
    from tuibrdf.core.formats.rgl_bsdf import load

    f = _bsdf(tmp_path / "a.bsdf", offsets={"ndf": 8})
    with pytest.raises(ValueError, match="'ndf' .* overlaps the header"):
        load(f)


def test_bsdf_unknown_fields_are_not_read(tmp_path):
    from tuibrdf.core.formats.rgl_bsdf import load, read_tensor

    f = _bsdf(tmp_path / "x.bsdf", fields={"comment": np.zeros(1000, np.uint8)})
    load(f)  # loads
    assert set(read_tensor(str(f), ("phi_i",))) == {"phi_i"}


@pytest.mark.parametrize("case", ["f32 near max", "f64 near max", "0x0 luminance", "empty"])
def test_bsdf_degenerate_data_is_one_line(tmp_path, case):
    from tests.rgl_writer import material

    base = material(n=5, n_theta=2)
    kw: dict = {}
    if case == "f32 near max":
        kw["fields"] = {"rgb": base["rgb"].astype(np.float32) * np.float32(1e38)}
        words = "'rgb' has values up to"
    elif case == "f64 near max":
        kw["fields"] = {"vndf": base["vndf"] * 1e307}
        words = "'vndf' has values up to"
    elif case == "0x0 luminance":
        kw["fields"] = {"luminance": np.zeros((1, 2, 0, 0)), "rgb": np.zeros((1, 2, 3, 0, 0))}
        words = "n ≥ 2"
    else:  # a zero side makes a field empty whatever its other sides declare
        kw["shapes"] = {"ndf": (0, 10**15)}
        words = "larger than the file"
    f = _bsdf(tmp_path / "d.bsdf", **kw)
    for argv in (("models", str(f)), ("render", str(f)), ("eval", str(f), "--theta-i", "30",
                                                          "--theta-r", "30", "--phi-r", "0")):
        rc, _, err = cli(*argv)
        line = one_line_error(err)
        assert rc == 2 and str(f) in line and words in line, line


def test_bsdf_description_escapes_never_reach_the_terminal(tmp_path):
    evil = b"evil \x1b[31mRED\x1b[0m \x1b]0;title\x07 \xc2\x9b2J \r\n"
    f = _bsdf(tmp_path / "esc.bsdf", fields={"description": np.frombuffer(evil, np.uint8)})
    for argv in (("models", str(f)), ("models", "--json", str(f))):
        rc, out, err = cli(*argv)
        assert rc == 0, err
        for raw in ("\x1b", "\x07", "\x9b", "\r"):
            assert raw not in out
    rc, out, _ = cli("models", str(f))
    assert "\\x1b[31mRED" in out  # shown, escaped


# --- .py models


@pytest.mark.parametrize("where", ["kernel", "import"])
@pytest.mark.parametrize("exc", ["sys.exit(0)", "sys.exit(3)", "raise GeneratorExit('x')"])
def test_py_base_exceptions_are_one_line_exit_2(tmp_path, where, exc):
    from tuibrdf.core.formats.pymodel import load_python_model

    kernel = f"    {exc}\n" if where == "kernel" else "    return 0.0 * wi[..., 2]\n"
    top = f"{exc}\n" if where == "import" else ""
    f = tmp_path / "m.py"
    f.write_text("import sys\nfrom tuibrdf.core.params import Model, Param\n" + top +
                 "def kernel(wi, wo, kd):\n" + kernel +
                 "MODEL = Model('m', 'M', (Param('kd', 'kd', 0.5, 0.0, 1.0, 0.01),), kernel)\n")
    name = exc.split("(")[0].replace("raise ", "").replace("sys.exit", "SystemExit")
    for argv in (("eval", str(f), "--theta-i", "0", "--theta-r", "0", "--phi-r", "0"),
                 ("render", str(f))):
        rc, out, err = cli(*argv)
        line = one_line_error(err)
        assert rc == 2 and str(f) in line and name in line, (argv, line)
    if where == "kernel":
        m = load_python_model(str(f), "m")
        with pytest.raises(ValueError, match=name):
            m.kernel(np.array([0.0, 0.0, 1.0]), np.array([0.0, 0.0, 1.0]), kd=0.5)


# --- the CLI's exits


def test_render_into_a_pipe_whose_reader_left_exits_141():
    """`tuibrdf render … | head`: output larger than a pipe's buffer (64 KiB), the reader takes
    100 bytes and leaves; the write is cut short (CPython may drop the rest silently): 141."""
    e = {**os.environ, "PYTHONPATH": str(ROOT)}
    p = subprocess.Popen([sys.executable, "-m", "tuibrdf", "render", "phong", "--view", "all",
                          "--width", "300", "--height", "150"], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, env=e, bufsize=0)
    assert len(os.read(p.stdout.fileno(), 100)) > 0
    p.stdout.close()
    err = p.stderr.read().decode()
    p.stderr.close()
    assert p.wait(timeout=TIMEOUT) == 141
    assert err == ""


VIEWS = ["map", "incidence", "perpendicular", "solid", "albedo", "sphere", "plane", "slice",
         "theta-h", "theta-d"]


@pytest.mark.parametrize("extra", [(), ("--log",), ("--cosine",)])
@pytest.mark.parametrize("params", [("blinn-phong", "kd=0", "ks=5e-324"), ("lambert", "kd=1e-307"),
                                    ("phong", "kd=0", "ks=1e-289")])
def test_render_tiny_peak_draws_every_view(capsys, params, extra):
    """`render blinn-phong -p kd=0 -p ks=5e-324 --view incidence` exited 2 (a 10^k step of a
    subnormal maximum underflowed to 0 and was divided by), a 3e-308 Lambert overflowed the
    solid's pixels/max: every view draws, without a warning."""
    model, *ps = params
    for view in VIEWS:
        rc = main(["render", model, *(x for p in ps for x in ("-p", p)), "--view", view,
                   "--width", "30", "--height", "10", "--color", "none", *extra])
        out, err = capsys.readouterr()
        assert rc == 0 and err == "", (view, err)


def test_flush_tiny():
    """Values under 1e-290 in magnitude are 0; the rest, and exact zeros, are unchanged."""
    from tuibrdf.core.evaluate import FLUSH_BELOW, flush_tiny

    assert FLUSH_BELOW == 1e-290
    tiny = np.finfo(float).tiny  # the smallest normal float64
    f = np.array([0.0, 5e-324, tiny / 2, tiny, 9.9e-291, 1e-290, 1.0, -1e-310])
    assert flush_tiny(f).tolist() == [0.0, 0.0, 0.0, 0.0, 0.0, 1e-290, 1.0, 0.0]
    assert flush_tiny(5e-324) == 0.0 and flush_tiny(0.25) == 0.25
    g = np.array([0.5, 2.0])
    assert flush_tiny(g) is g  # nothing to flush: no copy
