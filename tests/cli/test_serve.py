"""``tuibrdf serve`` without a browser: the served viewer starts under Textual's web driver over
pipes, the sandbox refuses what it must (paths outside ``--data-dir``, ``.py`` files), and the
missing extra is one line.  The browser test is tests/app/test_serve_browser.py."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import threading
from pathlib import Path

import pytest

from tuibrdf.cli import main, serve, view
from tuibrdf.cli.common import UsageError
from tuibrdf.state import presets, sandbox
from tuibrdf.state.viewer import Side, ViewerState

DATA = Path(__file__).resolve().parents[1] / "data" / "brdf"
#: the line textual-serve waits for before it calls an app started (textual_serve/app_service.py,
#: AppService.run: ``if line == b"__GANGLION__\n"``, read among the first ten lines)
GANGLION = b"__GANGLION__\n"
WEB_DRIVER = "textual.drivers.web_driver:WebDriver"  # what textual-serve sets TEXTUAL_DRIVER to
#: a packet of textual-serve's protocol: b"M", the length (4 bytes, big-endian), JSON
QUIT = b'{"type": "quit"}'
QUIT_PACKET = b"M" + len(QUIT).to_bytes(4, "big") + QUIT
#: generous: a loaded 2-core machine starts Python, numpy and Textual in a few seconds
START_S = 120


@pytest.fixture
def policy():
    """Install a policy for one test; none afterwards."""
    yield lambda p: sandbox.install(p)
    sandbox.install(None)


@pytest.fixture
def tree(tmp_path):
    """data/ (served) holding a .brdf, a .py and a MERL-named file; outside/ beside it."""
    data, outside = tmp_path / "data", tmp_path / "outside"
    data.mkdir()
    outside.mkdir()
    for d in (data, outside):
        shutil.copy(DATA / "ggx.brdf", d / "ggx.brdf")
        (d / "m.py").write_text("raise SystemExit('this file must never run')\n")
        (d / "gold.binary").write_bytes(b"")
    return data, outside


def test_the_constants_are_textual_serves(tmp_path):
    ts = pytest.importorskip("textual_serve.app_service")
    source = Path(ts.__file__).read_text(encoding="utf-8")
    assert 'b"__GANGLION__\\n"' in source
    assert f'"{WEB_DRIVER}"' in source


def _start(command, env, cwd):
    proc = subprocess.Popen(command, stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, env=env, cwd=cwd)
    lines: list[bytes] = []

    def read():  # textual-serve reads at most ten lines before the packets
        for _ in range(10):
            line = proc.stdout.readline()
            lines.append(line)
            if not line or line == GANGLION:
                return

    reader = threading.Thread(target=read, daemon=True)
    reader.start()
    reader.join(START_S)
    return proc, lines


def test_the_served_command_starts_the_viewer_on_pipes(tmp_path, tree):
    data, _ = tree
    args = Parser_args(["phong", "-p", "ks=0.3", "--data-dir", str(data)])
    command = serve.viewer_command(args)
    env = dict(os.environ, TEXTUAL_DRIVER=WEB_DRIVER, COLUMNS="100", ROWS="30",
               **{sandbox.ENV: serve.policy_for(args).to_json()})
    proc, lines = _start(command, env, tmp_path)
    with proc:
        try:
            started = GANGLION in lines
            # what textual-serve sends when the tab closes; closes the pipes
            _, err = proc.communicate(QUIT_PACKET, timeout=START_S)
        finally:
            if proc.poll() is None:
                proc.kill()
                proc.communicate()
    assert started, (lines, err)
    assert proc.returncode == 0, err


def test_a_served_viewer_refuses_a_file_it_was_not_given(tmp_path, tree):
    data, outside = tree
    env = dict(os.environ, TEXTUAL_DRIVER=WEB_DRIVER,
               **{sandbox.ENV: sandbox.Policy.make(str(data), [], False).to_json()})
    out = subprocess.run([sys.executable, "-m", "tuibrdf", "view", str(outside / "ggx.brdf")],
                         capture_output=True, text=True, env=env, stdin=subprocess.PIPE,
                         timeout=START_S)
    assert out.returncode == 2
    assert out.stdout == ""
    lines = out.stderr.splitlines()
    assert len(lines) == 1 and "refused" in lines[0] and str(data) in lines[0]


def Parser_args(argv):
    parser = serve.Parser(prog="tuibrdf serve")
    serve.add_args(parser)
    return parser.parse_args(argv)


# -- the policy ------------------------------------------------------------------------------
def test_files_under_the_data_dir_open(policy, tree):
    data, _ = tree
    policy(sandbox.Policy.make(str(data), [], False))
    assert Side(str(data / "ggx.brdf")).material.label == "ggx.brdf"
    s = ViewerState(sides=[Side("merl", {"file": str(data / "gold.binary")})])
    assert s.sides[0].values["file"] == str(data / "gold.binary")


def test_paths_outside_the_data_dir_are_refused(policy, tree, monkeypatch):
    data, outside = tree
    policy(sandbox.Policy.make(str(data), [], False))
    for path in (outside / "ggx.brdf", data / ".." / "outside" / "ggx.brdf"):
        with pytest.raises(ValueError, match="refused"):
            Side(str(path))
    with pytest.raises(ValueError, match="refused"):  # a data file, as -p or a preset gives it
        Side("merl", {"file": str(outside / "gold.binary")})
    (data / "link.brdf").symlink_to(outside / "ggx.brdf")  # a link does not leave it either
    with pytest.raises(ValueError, match="refused"):
        Side(str(data / "link.brdf"))
    monkeypatch.chdir(data)  # a relative path resolves from the working directory
    with pytest.raises(ValueError, match="refused"):
        Side("../outside/ggx.brdf")


def test_a_typed_path_is_refused_and_nothing_changes(policy, tree):
    data, outside = tree
    policy(sandbox.Policy.make(str(data), [], False))
    state = ViewerState(sides=[Side("merl", {"file": str(data / "gold.binary")})])
    state.active = 0
    state.sides[0].selected = 0  # the file row (merl's only parameter)
    msg = state.type_value(str(outside / "gold.binary"))
    assert msg is not None and "refused" in msg
    assert state.sides[0].values["file"] == str(data / "gold.binary")
    assert state.type_value(str(data / "gold.binary")) is None


def test_only_named_files_without_a_data_dir(policy, tree):
    data, _ = tree
    named = data / "ggx.brdf"
    policy(sandbox.Policy.make(None, [str(named)], False))
    assert Side(str(named)).material.label == "ggx.brdf"
    (data / "other.brdf").write_bytes(named.read_bytes())
    with pytest.raises(ValueError, match="named on its command line"):
        Side(str(data / "other.brdf"))


def test_python_files_are_refused_unless_allowed(policy, tree):
    data, _ = tree
    py = data / "m.py"
    for p in (sandbox.Policy.make(str(data), [], False),
              sandbox.Policy.make(str(data), [str(py)], False)):  # named, still refused
        policy(p)
        with pytest.raises(ValueError, match="--allow-python"):
            Side(str(py))  # refused before it is read: the file would raise SystemExit
    with pytest.raises(UsageError, match="--allow-python"):
        serve.policy_for(Parser_args([str(py)]))


def test_a_preset_cannot_reach_other_files(policy, tree):
    data, outside = tree
    policy(sandbox.Policy.make(str(data), [], False))
    for model in (outside / "ggx.brdf", data / "m.py"):
        text = f'theta_i = 30.0\n[[sides]]\nmodel = "{model}"\n'
        with pytest.raises(presets.PresetError, match="refused|--allow-python"):
            presets.from_toml(text, "p.toml")
    text = (f'theta_i = 30.0\n[[sides]]\nmodel = "merl"\n'
            f'params = {{ file = "{outside}/g.binary" }}\n')
    with pytest.raises(presets.PresetError, match="refused"):
        presets.from_toml(text, "p.toml")


def test_a_bparam_cannot_point_outside(policy, tree):
    data, outside = tree
    text = (DATA / "ggx.bparam").read_text().replace("bparam ggx.brdf",
                                                       f"bparam {outside / 'ggx.brdf'}")
    (data / "x.bparam").write_text(text)
    policy(sandbox.Policy.make(str(data), [], False))
    with pytest.raises(ValueError, match="refused"):
        Side(str(data / "x.bparam"))


def test_no_policy_no_restriction(tree):
    _, outside = tree
    assert sandbox.current() is None
    assert Side(str(outside / "ggx.brdf")).material.label == "ggx.brdf"


def test_a_malformed_policy_is_one_line(monkeypatch, capsys):
    monkeypatch.setenv(sandbox.ENV, "{not json")
    monkeypatch.setenv("TEXTUAL_DRIVER", WEB_DRIVER)
    try:
        assert main(["view"]) == 2
    finally:
        sandbox.install(None)
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 1 and sandbox.ENV in err[0]


# -- the command -------------------------------------------------------------------------------
def test_view_accepts_the_web_driver_as_a_terminal(monkeypatch):
    import io

    pipe = io.StringIO()
    monkeypatch.delenv("TEXTUAL_DRIVER", raising=False)
    with pytest.raises(UsageError, match="terminal"):
        view.check_terminal(pipe, pipe)
    monkeypatch.setenv("TEXTUAL_DRIVER", WEB_DRIVER)
    view.check_terminal(pipe, pipe)  # no error


def test_without_the_extra_one_line(monkeypatch, capsys):
    monkeypatch.setitem(sys.modules, "textual_serve", None)  # import fails as if absent
    monkeypatch.setitem(sys.modules, "textual_serve.server", None)
    assert main(["serve"]) == 2
    out = capsys.readouterr()
    assert out.out == ""
    lines = out.err.splitlines()
    assert len(lines) == 1 and "pip install 'tuibrdf[web]'" in lines[0]


class FakeServer:
    made: list[FakeServer] = []

    def __init__(self, command, host, port, title=None):
        self.command, self.host, self.port = command, host, port
        self.policy = json.loads(os.environ[sandbox.ENV])
        FakeServer.made.append(self)

    def serve(self):
        pass


@pytest.mark.parametrize(("host", "warned"), [("127.0.0.1", False), ("localhost", False),
                                              ("::1", False), ("0.0.0.0", True),
                                              ("192.168.1.5", True)])
def test_a_non_loopback_host_is_warned_about(monkeypatch, capsys, tree, host, warned):
    ts = pytest.importorskip("textual_serve.server")
    data, _ = tree
    monkeypatch.setattr(ts, "Server", FakeServer)
    monkeypatch.delenv(sandbox.ENV, raising=False)
    monkeypatch.setenv(sandbox.ENV, "")  # restored after the test (serve sets it)
    FakeServer.made.clear()
    assert main(["serve", str(data / "ggx.brdf"), "--host", host, "--port", "8123"]) == 0
    err = capsys.readouterr().err
    assert ("no authentication" in err) is warned
    (made,) = FakeServer.made
    assert (made.host, made.port) == (host, 8123)
    assert made.command.split()[-2:] == ["view", str(data / "ggx.brdf")]
    assert made.policy["files"] == [os.path.realpath(data / "ggx.brdf")]
    assert made.policy["data_dir"] is None and made.policy["allow_python"] is False


def test_a_port_in_use_is_one_line(tmp_path):
    pytest.importorskip("textual_serve")
    import socket

    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        port = taken.getsockname()[1]
        out = subprocess.run([sys.executable, "-m", "tuibrdf", "serve", "--port", str(port)],
                             capture_output=True, text=True, cwd=tmp_path, timeout=START_S)
    assert out.returncode == 2
    assert out.stderr.splitlines() == [f"tuibrdf: error: cannot listen on 127.0.0.1:{port}: "
                                       "address already in use"]


def test_bad_ports_and_data_dirs_are_one_line(capsys, tmp_path):
    for argv in (["serve", "--port", "0"], ["serve", "--port", "x"],
                 ["serve", "--data-dir", str(tmp_path / "none")]):
        assert main(argv) == 2
        assert len(capsys.readouterr().err.splitlines()) == 1


def test_the_other_model_files_are_allowed_and_cycled_to(tree, policy):
    data, _ = tree
    second = data / "second.brdf"
    second.write_bytes((data / "ggx.brdf").read_bytes())
    p = serve.policy_for(Parser_args([str(data / "ggx.brdf"), str(second), "-p", "alpha=0.5"]))
    assert p.models == (str(second),)  # `m` reaches it (view adds it to ViewerState.files)
    assert p.files == {os.path.realpath(data / "ggx.brdf"), os.path.realpath(second)}
    policy(p)
    assert Side(str(second)).material.label == "second.brdf"
