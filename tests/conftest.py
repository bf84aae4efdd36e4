"""Test-wide setup: a deterministic environment for snapshots and renderers."""

import os

import pytest

for var in ("NO_COLOR", "TEXTUAL_THEME", "FORCE_COLOR", "COLORTERM", "TEXTUAL_COLOR_SYSTEM"):
    os.environ.pop(var, None)


@pytest.fixture
def no_color(monkeypatch):
    monkeypatch.setenv("NO_COLOR", "1")
