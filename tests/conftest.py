"""Test-wide setup: a deterministic environment for snapshots and renderers."""

import os

import pytest

for var in ("NO_COLOR", "TEXTUAL_THEME", "FORCE_COLOR", "COLORTERM", "TEXTUAL_COLOR_SYSTEM"):
    os.environ.pop(var, None)


@pytest.fixture
def no_color(monkeypatch):
    monkeypatch.setenv("NO_COLOR", "1")


@pytest.fixture(autouse=True)
def fresh_styles():
    """Each test starts without the renderers' cached ``Style`` objects: Rich keeps a Style's
    SGR codes for the first colour system it is rendered in (``Style._ansi``), so a style
    first rendered by a 16-colour console in one test would print 16-colour codes in the next
    test's truecolor golden.  The app and the CLI render in one colour system a process."""
    from tuibrdf.render import braille, halfblock

    halfblock.cell_style.cache_clear()
    halfblock._TABLES.clear()
    halfblock._rgb.cache_clear()
    braille._style.cache_clear()
    yield
