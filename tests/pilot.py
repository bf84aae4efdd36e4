"""Waiting in the viewer's Pilot tests: for a condition, a pause at a time."""

from __future__ import annotations


async def wait_for(pilot, cond, seconds: float = 10.0, step: float = 0.02) -> bool:
    """Whether ``cond()`` became true within ``seconds``, checked every ``step`` s (the app
    runs in between)."""
    for _ in range(int(seconds / step)):
        if cond():
            return True
        await pilot.pause(step)
    return False
