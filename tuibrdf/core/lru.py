"""The one least-recently-used cache the package keeps its computed and loaded things in: the
frame's parts (:mod:`tuibrdf.core.views.frame`), loaded user files
(:mod:`tuibrdf.core.formats.userfiles`), MERL data (:mod:`tuibrdf.core.formats.merl`) and the
half-block renderer's code tables (:mod:`tuibrdf.render.halfblock`).

Thread-safe: the viewer computes frames and loads files in worker threads.  A value is made
outside the lock (:meth:`LRU.get`), so other threads go on meanwhile; two threads that miss the
same key both make it, and the later one's value is kept.  A function of hashable arguments
with no file behind it is better served by :func:`functools.lru_cache`.
"""

from __future__ import annotations

import threading
from collections import OrderedDict
from collections.abc import Callable, Hashable
from typing import Any


class LRU:
    """At most ``size`` values by key, the least recently used dropped first."""

    def __init__(self, size: int) -> None:
        self.size = size
        self._data: OrderedDict[Hashable, Any] = OrderedDict()
        self._lock = threading.Lock()

    def __len__(self) -> int:
        with self._lock:
            return len(self._data)

    def __contains__(self, key: Hashable) -> bool:
        with self._lock:
            return key in self._data

    def peek(self, key: Hashable) -> Any:
        """The value of ``key``, or None; it does not count as a use."""
        with self._lock:
            return self._data.get(key)

    def lookup(self, key: Hashable) -> Any:
        """The value of ``key``, now the most recently used, or None."""
        with self._lock:
            if key in self._data:
                self._data.move_to_end(key)
                return self._data[key]
        return None

    def put(self, key: Hashable, value: Any) -> Any:
        """Store ``value`` as the most recently used (dropping the oldest beyond ``size``);
        returns it."""
        with self._lock:
            self._data[key] = value
            self._data.move_to_end(key)
            while len(self._data) > self.size:
                self._data.popitem(last=False)
        return value

    def get(self, key: Hashable, make: Callable[[], Any]) -> Any:
        """The value of ``key`` (:meth:`lookup`), or ``make()`` stored under it."""
        with self._lock:
            if key in self._data:
                self._data.move_to_end(key)
                return self._data[key]
        return self.put(key, make())  # made outside the lock: other threads go on

    def clear(self) -> None:
        with self._lock:
            self._data.clear()
