"""The viewer in a real pseudo-terminal (issue 31): terminating signals restore the terminal
and exit 128 + n; a kernel that never returns does not stop q; a storm of raw input bytes
(malformed sequences included) leaves it running.

Expected values: the exit statuses are POSIX's convention (128 + the signal's number; 130 for
SIGINT); the restore sequences are the xterm control sequences that undo what a full-screen
app sets (alternate screen 1049, mouse tracking 1000/1003/1006, cursor 25); the tty's local
modes must be those the pty had before the viewer started.  Waits are generous and nothing
is timed.
"""

from __future__ import annotations

import signal
import termios
import time

import pytest

from tests.app.ptyrun import PtyViewer, restored_after_last_start
from tests.app.storm import QUIT_KEYS, storm

#: robustness runs: CI's Python 3.13 leg skips them (pyproject.toml, markers)
pytestmark = pytest.mark.slow

UP = "θi 30°"


@pytest.fixture
def env(tmp_path):
    return {"XDG_CONFIG_HOME": str(tmp_path / "config")}


@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGHUP, signal.SIGINT],
                         ids=["TERM", "HUP", "INT"])
def test_a_terminating_signal_restores_the_terminal(sig, env):
    v = PtyViewer(["lambert"], env=env)
    try:
        assert v.wait_for(lambda s: UP in s and "a(θi)" in s), v.text()[-500:]
        v.signal(sig)
        assert v.wait(60) == 128 + sig  # SIGINT: 130
        assert restored_after_last_start(v.text())
        lflag = v.attrs_now()[3]
        for flag in (termios.ICANON, termios.ECHO, termios.ISIG):
            assert lflag & flag == v.attrs_before[3] & flag
    finally:
        v.close()


LOOPING = '''
import numpy as np
from tuibrdf.core.params import Model, Param

KD = Param("kd", "Kd", 0.4, 0.0, 1.0, 0.2, doc="diffuse reflectance")


def kernel(wi, wo, kd):
    while kd > 0.5:  # never returns
        pass
    return np.full(np.broadcast_shapes(wi.shape, wo.shape)[:-1], kd / np.pi)


MODEL = Model("looping", "Looping", (KD,), kernel)
'''


@pytest.mark.parametrize("start", ["first-frame-loops", "loops-after-a-key"])
@pytest.mark.parametrize("quit_key", ["q", "\x11"], ids=["q", "ctrl+q"])
def test_q_ends_the_viewer_while_a_kernel_loops_forever(tmp_path, env, start, quit_key):
    path = tmp_path / "looping.py"
    path.write_text(LOOPING)
    args = [str(path)] + (["-p", "kd=0.6"] if start == "first-frame-loops" else [])
    v = PtyViewer(args, env=env)
    try:
        assert v.wait_for(lambda s: UP in s), v.text()[-500:]
        if start == "loops-after-a-key":
            # kd = 0.4: a frame (its colour bar's unit), then its albedo (the screen quiet: a
            # status line's text is not looked for, only its changed cells are sent)
            assert v.wait_for(lambda s: "sr⁻¹" in s), v.text()[-800:]
            v.drain(quiet=1.0, limit=60.0)
            v.send("+")  # kd 0.6: the kernel loops
        assert v.wait_for(lambda s: "model too slow" in s), v.text()[-800:]
        v.send(quit_key)
        assert v.wait(60) == 0  # (a generous bound: not a speed assertion)
        assert restored_after_last_start(v.text())
    finally:
        v.close()


def _clean_storm(seed: int, n: int) -> list[str]:
    """A storm without the keys that quit or suspend, nor ctrl+p (the command palette's
    "Quit" is one fuzzy match away; the Pilot storm covers the palette)."""
    from textual import events as ev

    from tuibrdf.app.textual_internals import SafeXTermParser

    def keys(data: str) -> set[str]:
        p = SafeXTermParser()
        return {e.key for e in [*p.feed(data)] if isinstance(e, ev.Key)}

    banned = QUIT_KEYS | {"ctrl+p"}
    pieces = [c for c in storm(seed, n) if not (keys(c) & banned)]
    assert not keys("".join(pieces)) & banned
    return pieces


def test_a_raw_byte_storm_leaves_the_viewer_running(tmp_path, env):
    from tests.rgl_writer import material, write_tensor

    bsdf = write_tensor(tmp_path / "synthetic.bsdf", material())
    v = PtyViewer([str(bsdf)], env=env)
    try:
        assert v.wait_for(lambda s: UP in s), v.text()[-500:]
        for piece in _clean_storm(31, 600):
            v.send(piece)
        time.sleep(2.0)
        assert v.proc.poll() is None, v.text()[-2000:]
        # the storm may still be being handled and may open a dialog (where q is typed):
        # Esc closes one, then q; again until the viewer has quit (or a generous limit)
        rc = None
        for _ in range(30):
            v.send("\x1b")
            time.sleep(0.5)
            v.send("q")
            rc = v.wait(3)
            if rc is not None:
                break
        assert rc == 0, v.text()[-2000:]
        assert restored_after_last_start(v.text())
    finally:
        v.close()


def test_a_flood_of_window_size_changes_leaves_the_viewer_running(env):
    import fcntl
    import random
    import struct

    v = PtyViewer(["phong"], env=env)
    try:
        assert v.wait_for(lambda s: UP in s), v.text()[-500:]
        rng = random.Random(31)
        for _ in range(2000):  # sizes from tiny to huge, each announced by SIGWINCH
            fcntl.ioctl(v.slave, termios.TIOCSWINSZ,
                        struct.pack("HHHH", rng.randint(1, 300), rng.randint(1, 600), 0, 0))
            v.signal(signal.SIGWINCH)
        fcntl.ioctl(v.slave, termios.TIOCSWINSZ, struct.pack("HHHH", 30, 100, 0, 0))
        v.signal(signal.SIGWINCH)
        time.sleep(2.0)
        assert v.proc.poll() is None, v.text()[-2000:]
        v.send("q")
        assert v.wait(60) == 0, v.text()[-2000:]
        assert restored_after_last_start(v.text())
    finally:
        v.close()


def test_the_screen_is_drawn_again_after_a_suspension(env):
    # SIGTSTP (ctrl+z in a shell) leaves the alternate screen; SIGCONT (fg) comes back to a
    # blank one: every pane must be sent again (not only what changed since)
    import re

    v = PtyViewer(["phong"], env=env)
    try:
        assert v.wait_for(lambda s: UP in s and "a(θi)" in s), v.text()[-500:]
        time.sleep(1.0)
        v.signal(signal.SIGTSTP)
        assert v.wait_for(lambda s: s.rfind("\x1b[?1049l") > s.rfind("\x1b[?1049h"))
        n = len(v.text())
        v.signal(signal.SIGCONT)

        def redrawn(s: str) -> bool:
            plain = re.sub(r"\x1b\[[0-9;?]*[A-Za-z]", "", s[n:])
            return all(w in plain for w in ("incidence", "perp.", "m/M model", "θi 30°"))

        assert v.wait_for(redrawn), v.text()[n:][-1500:]
        v.send("q")
        assert v.wait(60) == 0
    finally:
        v.close()
