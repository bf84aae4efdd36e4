"""``tuibrdf view`` in a pseudo-terminal of its own, for the tests that need a real terminal
(raw input bytes, signals, what is written to restore the terminal).  Waits poll with
generous timeouts: nothing here depends on the machine's speed."""

from __future__ import annotations

import fcntl
import os
import signal
import struct
import subprocess
import sys
import termios
import threading
import time

from tests import ROOT


class PtyViewer:
    """``PtyViewer(args, cols, rows, env)``: runs ``python -m tuibrdf view ARGS`` on a new
    pty; :attr:`out` collects everything it writes."""

    def __init__(self, args: list[str], cols: int = 100, rows: int = 30,
                 env: dict | None = None) -> None:
        self.master, slave = os.openpty()
        fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", rows, cols, 0, 0))
        self.attrs_before = termios.tcgetattr(slave)
        full_env = {**os.environ, "PYTHONPATH": str(ROOT), "TERM": "xterm-256color",
                    "COLORTERM": "truecolor", **(env or {})}
        full_env.pop("TMUX", None)
        self.proc = subprocess.Popen([sys.executable, "-m", "tuibrdf", "view", *args],
                                     stdin=slave, stdout=slave, stderr=slave, cwd=ROOT,
                                     env=full_env, start_new_session=True)
        self.slave = slave  # kept open: the pty's attributes can be read after the exit
        self.out = bytearray()
        self._lock = threading.Lock()
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()

    def _read(self) -> None:
        while True:
            try:
                data = os.read(self.master, 65536)
            except OSError:
                return
            if not data:
                return
            with self._lock:
                self.out += data

    def text(self) -> str:
        with self._lock:
            return self.out.decode("utf-8", "replace")

    def send(self, data: bytes | str) -> None:
        os.write(self.master, data.encode() if isinstance(data, str) else data)

    def wait_for(self, predicate, timeout: float = 60.0) -> bool:
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            if predicate(self.text()):
                return True
            if self.proc.poll() is not None:
                time.sleep(0.2)
                return predicate(self.text())
            time.sleep(0.05)
        return False

    def signal(self, signum: int) -> None:
        os.kill(self.proc.pid, signum)

    def wait(self, timeout: float = 60.0) -> int | None:
        """The exit status (None: still running after ``timeout``), once the reader thread
        has taken what the viewer wrote last (the restore sequences come just before the
        exit, and may still sit in the pty when the process is gone)."""
        try:
            code = self.proc.wait(timeout)
        except subprocess.TimeoutExpired:
            return None
        self.drain()
        return code

    def drain(self, quiet: float = 0.3, limit: float = 10.0) -> None:
        """Wait until nothing new has arrived for ``quiet`` seconds (at most ``limit``)."""
        end = time.monotonic() + limit
        seen, since = -1, time.monotonic()
        while time.monotonic() < end:
            with self._lock:
                n = len(self.out)
            if n != seen:
                seen, since = n, time.monotonic()
            elif time.monotonic() - since >= quiet:
                return
            time.sleep(0.05)

    def attrs_now(self):
        return termios.tcgetattr(self.slave)

    def close(self) -> None:
        if self.proc.poll() is None:
            try:
                os.killpg(self.proc.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
            self.proc.wait(10)
        for fd in (self.master, self.slave):
            try:
                os.close(fd)
            except OSError:
                pass


def restored_after_last_start(out: str) -> bool:
    """Whether, after the last switch to the alternate screen, the output leaves it, turns
    mouse tracking off and shows the cursor again."""
    start = out.rfind("\x1b[?1049h")
    tail = out[start:] if start >= 0 else out
    return all(seq in tail for seq in ("\x1b[?1049l", "\x1b[?1000l", "\x1b[?1003l",
                                       "\x1b[?1006l", "\x1b[?25h"))
