"""The one LRU cache (tuibrdf/core/lru.py): which value goes first, what counts as a use, and
that threads sharing one keep it within its size."""

from __future__ import annotations

import threading

from tuibrdf.core.lru import LRU


def test_the_least_recently_used_goes_first():
    c = LRU(2)
    c.put("a", 1)
    c.put("b", 2)
    assert c.lookup("a") == 1  # a use: b is now the oldest
    c.put("c", 3)
    assert "b" not in c and "a" in c and "c" in c and len(c) == 2


def test_peek_is_not_a_use():
    c = LRU(2)
    c.put("a", 1)
    c.put("b", 2)
    assert c.peek("a") == 1
    c.put("c", 3)  # a is still the oldest
    assert "a" not in c and c.peek("b") == 2
    assert c.peek("missing") is None and c.lookup("missing") is None


def test_get_makes_a_value_once_and_counts_as_a_use():
    c = LRU(2)
    made = []

    def make(v):
        made.append(v)
        return v

    assert c.get("a", lambda: make(1)) == 1
    assert c.get("a", lambda: make(99)) == 1  # kept: not made again
    c.put("b", 2)
    c.get("a", lambda: make(99))  # a use: b is the oldest
    c.put("c", 3)
    assert made == [1] and "a" in c and "b" not in c


def test_clear():
    c = LRU(3)
    c.put("a", 1)
    c.clear()
    assert len(c) == 0 and c.peek("a") is None


def test_threads_share_one_cache_within_its_size():
    c = LRU(8)

    def work(t):
        for i in range(2000):
            c.get((t, i % 13), lambda i=i: i)
            c.put((t, i % 5, "p"), i)

    threads = [threading.Thread(target=work, args=(t,)) for t in range(4)]
    for th in threads:
        th.start()
    for th in threads:
        th.join()
    assert len(c) == 8
