"""End to end in a real terminal: tmux runs ``python -m tuibrdf`` (the viewer, no arguments).

Skipped when tmux is missing (``.ci/run`` installs it).  Waits poll the captured pane with a
generous timeout, so the test does not depend on machine speed.
"""

import os
import shutil
import subprocess
import sys
import time
import uuid

import pytest

from tests import ROOT

pytestmark = pytest.mark.skipif(shutil.which("tmux") is None, reason="tmux not installed")


def wait_for(sock, predicate, timeout=30.0):
    end = time.monotonic() + timeout
    screen = ""
    while time.monotonic() < end:
        screen = subprocess.run(["tmux", "-L", sock, "capture-pane", "-p", "-t", "t"],
                                capture_output=True, text=True).stdout
        if predicate(screen):
            return screen
        time.sleep(0.1)
    raise AssertionError(f"timed out; last screen:\n{screen}")


def test_viewer_in_tmux(tmp_path):
    sock = f"tuibrdf-test-{uuid.uuid4().hex[:8]}"
    env_cmd = (f"cd {ROOT} && XDG_CONFIG_HOME={tmp_path} PYTHONPATH={ROOT} "
               f"{sys.executable} -m tuibrdf; sleep 5")
    subprocess.run(["tmux", "-L", sock, "new-session", "-d", "-s", "t", "-x", "100", "-y", "30",
                    "-e", "COLORTERM=truecolor", env_cmd], check=True,
                   env={k: v for k, v in os.environ.items() if k != "TMUX"})
    try:
        # the map's frame: title line (model, θi) and the colour bar's unit under the disc
        # (plain tuibrdf opens on Phong, issue 36)
        first = wait_for(sock, lambda s: "phong  θi=30°" in s and "sr⁻¹" in s)
        assert "θi 30°" in first
        assert "▀" in first or "▄" in first  # the disc's half-block edge
        subprocess.run(["tmux", "-L", sock, "send-keys", "-t", "t", "Right", "Right"],
                       check=True)
        after = wait_for(sock, lambda s: "θi 32°" in s and "phong  θi=32°" in s)
        assert "θi 30°" not in after
        subprocess.run(["tmux", "-L", sock, "send-keys", "-t", "t", "q"], check=True)
    finally:
        subprocess.run(["tmux", "-L", sock, "kill-server"], capture_output=True)


def test_held_key_status_ends_on_the_final_albedo(tmp_path):
    # issue 11: → held (15 presses at 10/s) from θi = 0°; the status line must end on θi 15°
    # with that state's albedo (the core quadrature's, computed here), in every run
    from tuibrdf.core.conventions import fmt_value
    from tuibrdf.core.sphere.albedo import albedo

    want = f"θi 15°  a(θi)={fmt_value(albedo('ggx', {}, 15.0))} "
    for _ in range(2):
        sock = f"tuibrdf-test-{uuid.uuid4().hex[:8]}"
        env_cmd = (f"cd {ROOT} && XDG_CONFIG_HOME={tmp_path} PYTHONPATH={ROOT} "
                   f"{sys.executable} -m tuibrdf view ggx --theta-i 0; sleep 5")
        subprocess.run(["tmux", "-L", sock, "new-session", "-d", "-s", "t", "-x", "100", "-y",
                        "30", "-e", "COLORTERM=truecolor", env_cmd], check=True,
                       env={k: v for k, v in os.environ.items() if k != "TMUX"})
        try:
            wait_for(sock, lambda s: "θi 0°  a(θi)=" in s)
            for _ in range(15):
                subprocess.run(["tmux", "-L", sock, "send-keys", "-t", "t", "Right"], check=True)
                time.sleep(0.1)
            wait_for(sock, lambda s: want in s, timeout=20.0)
            subprocess.run(["tmux", "-L", sock, "send-keys", "-t", "t", "q"], check=True)
        finally:
            subprocess.run(["tmux", "-L", sock, "kill-server"], capture_output=True)


def test_enlarging_past_the_minimum_shows_the_viewer_each_time(tmp_path):
    # issue 12 item 1: start at 59×17 (one below the 60×18 minimum each way), enlarge, shrink,
    # enlarge again: each time the viewer (not the too-small message) must be on screen
    sock = f"tuibrdf-test-{uuid.uuid4().hex[:8]}"
    env_cmd = (f"cd {ROOT} && XDG_CONFIG_HOME={tmp_path} PYTHONPATH={ROOT} "
               f"{sys.executable} -m tuibrdf; sleep 5")
    subprocess.run(["tmux", "-L", sock, "new-session", "-d", "-s", "t", "-x", "59", "-y", "17",
                    "-e", "COLORTERM=truecolor", env_cmd], check=True,
                   env={k: v for k, v in os.environ.items() if k != "TMUX"})

    def resize(w, h):
        subprocess.run(["tmux", "-L", sock, "resize-window", "-t", "t", "-x", str(w), "-y",
                        str(h)], check=True)

    def viewer(s):
        return "Enlarge the window" not in s and "θi 30°" in s and "phong" in s

    try:
        wait_for(sock, lambda s: "59×17" in s and "Enlarge the window" in s)
        for w, h in ((100, 30), (120, 40)):
            resize(w, h)
            wait_for(sock, viewer)
            resize(59, 17)
            wait_for(sock, lambda s: "59×17" in s and "Enlarge the window" in s)
        resize(100, 30)
        wait_for(sock, viewer)
        subprocess.run(["tmux", "-L", sock, "send-keys", "-t", "t", "q"], check=True)
    finally:
        subprocess.run(["tmux", "-L", sock, "kill-server"], capture_output=True)
