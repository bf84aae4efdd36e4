"""Measured data (MERL files) read off the event loop, with progress on the status line: a
mixin of the viewer (the 35 MB read never blocks a key)."""

from __future__ import annotations

import threading
from functools import partial

from tuibrdf.app.guard import survives
from tuibrdf.app.text import side_files
from tuibrdf.core.formats import merl
from tuibrdf.state.viewer import Side


class MeasuredData:
    """Needs ``state``, ``_loading`` (file → fraction read), ``_changed`` and ``_status``."""

    def _files_ready(self) -> bool:
        """Whether every side's data file is in memory; starts a loader for each missing one
        (a worker thread) and answers False meanwhile."""
        ready = True
        for side in self.state.sides:
            for path in side_files(side):
                try:
                    if merl.is_loaded(path):
                        continue
                except merl.MerlError as e:
                    self.call_later(self._load_failed, path, str(e))
                    return False
                ready = False
                if path not in self._loading:
                    self._loading[path] = 0.0
                    # a daemon thread: a read stuck on a FIFO or a dead network disk does
                    # not keep the process alive after q (Textual's pool threads would)
                    threading.Thread(target=partial(self._load_file, path), daemon=True,
                                     name="tuibrdf-merl").start()
        return ready

    def _load_file(self, path: str) -> None:
        def post(callback, *args) -> None:
            try:
                self.call_from_thread(callback, *args)
            except RuntimeError:  # the app has closed meanwhile
                pass

        try:
            merl.load_cached(path, partial(post, self._load_progress, path))
        except Exception as e:  # MerlError, OSError; anything else is a message too
            post(self._load_failed, path, str(e))
            return
        post(self._load_done, path)

    @survives
    def _load_progress(self, path: str, fraction: float) -> None:
        if path in self._loading:
            self._loading[path] = fraction
            self._status()

    @survives
    def _load_done(self, path: str) -> None:
        self._loading.pop(path, None)
        self._changed(f"loaded {path}")

    @survives
    def _load_failed(self, path: str, error: str) -> None:
        """A side whose file cannot be read shows Lambert instead; the message says why."""
        self._loading.pop(path, None)
        s = self.state
        s.sides = [Side.of("lambert") if path in side_files(x) else x for x in s.sides]
        self._changed(f"{error} — showing lambert", relayout=True)
