"""``tuibrdf serve`` in a real browser: Debian's chromium driven by Playwright (nothing is
downloaded: the system browser is launched by path).  The terminal is drawn on canvases, so
the test compares screenshots, and reads θi from the viewer's own SVG screenshot, which the
command palette's Screenshot delivers to the browser as a download (a new tab).

Skips, with the reason, without /usr/bin/chromium, Playwright or textual-serve (.ci/run installs
them for its serve leg)."""

from __future__ import annotations

import html
import os
import re
import socket
import subprocess
import sys
import time

import pytest

from tuibrdf.core.display import DISPLAY

CHROMIUM = "/usr/bin/chromium"
if not os.path.exists(CHROMIUM):
    pytest.skip(f"no {CHROMIUM} (apt-get install chromium)", allow_module_level=True)
pytest.importorskip("textual_serve", reason="textual-serve absent (pip install 'tuibrdf[web]')")
sync_api = pytest.importorskip("playwright.sync_api",
                               reason="Playwright absent (pip install playwright)")

#: chromium's flags for a closed network and a container (no sandbox as root, no GPU); without
#: the background-networking ones it retries unreachable services
FLAGS = ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync"]
#: generous waits: a loaded 2-core machine (never a claim about speed)
START_S = 120
SETTLE_S = 90


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.fixture
def server(tmp_path):
    """``tuibrdf serve phong`` on a free port; its URL.  Its log goes to a file (a pipe nobody
    reads would fill up and stall it)."""
    port = free_port()
    log = tmp_path / "serve.log"
    with open(log, "wb") as out:
        proc = subprocess.Popen([sys.executable, "-m", "tuibrdf", "serve", "phong",
                                 "--port", str(port)], stdout=out, stderr=subprocess.STDOUT,
                                cwd=tmp_path)
    try:
        deadline = time.monotonic() + START_S
        while b"Serving" not in log.read_bytes():
            assert proc.poll() is None, log.read_text(errors="replace")
            assert time.monotonic() < deadline, log.read_text(errors="replace")
            time.sleep(0.2)
        while True:  # the line comes before the socket is bound (aiohttp's on_startup)
            try:
                socket.create_connection(("127.0.0.1", port), timeout=5).close()
                break
            except OSError:
                assert proc.poll() is None, log.read_text(errors="replace")
                assert time.monotonic() < deadline, log.read_text(errors="replace")
                time.sleep(0.2)
        yield f"http://127.0.0.1:{port}/"
    finally:
        proc.terminate()  # textual-serve exits gracefully on SIGTERM
        try:
            proc.wait(30)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()


def settled(page, before: bytes | None = None) -> bytes:
    """A screenshot once two taken a second apart agree (and differ from ``before``)."""
    deadline = time.monotonic() + SETTLE_S
    last = page.screenshot()
    while True:
        time.sleep(1.0)
        shot = page.screenshot()
        if shot == last and shot != before:
            return shot
        assert time.monotonic() < deadline, "the picture never settled"
        last = shot


def theta_i_shown(svg: str) -> set[float]:
    """Every θi the viewer's SVG screenshot shows (title ``θi=35°``, status ``θi 35°``)."""
    texts = re.findall(r"<text[^>]*>(.*?)</text>", svg, re.S)
    screen = "".join(html.unescape(t) for t in texts).replace("\xa0", " ")
    return {float(v) for v in re.findall(r"θi\s*=?\s*(-?\d+(?:\.\d+)?)°", screen)}


def test_arrow_keys_in_chromium_move_the_light(server, tmp_path):
    with sync_api.sync_playwright() as pw:
        browser = pw.chromium.launch_persistent_context(
            str(tmp_path / "profile"), executable_path=CHROMIUM, headless=True, args=FLAGS,
            viewport={"width": 1280, "height": 800})
        try:
            page = browser.new_page()
            page.goto(server, wait_until="domcontentloaded")  # (its web font is unreachable)
            page.wait_for_selector("body.-first-byte", timeout=START_S * 1000)  # app drawn
            before = settled(page)
            page.focus(".xterm-helper-textarea")
            for _ in range(5):
                page.keyboard.press("ArrowRight")
            after = settled(page, before)
            assert after != before
            # the palette's Screenshot: Textual delivers the SVG, the page opens it in a tab
            with browser.expect_page(timeout=START_S * 1000) as tab:
                page.keyboard.press("Control+p")
                page.wait_for_timeout(1000)
                page.keyboard.type("Screenshot")
                page.wait_for_timeout(1000)
                page.keyboard.press("Enter")
            shot = tab.value
            shot.wait_for_load_state()
            assert "/download/" in shot.url
            svg = shot.content()
        finally:
            browser.close()
    # → is θi +1° (README, keys); the viewer opens at the default θi
    assert theta_i_shown(svg) == {DISPLAY.theta_i.default + 5}
