"""Dependency direction: core ← render ← app ← cli.  The numpy API never loads textual/rich."""

import subprocess
import sys

import pytest


def loaded_after(statement: str) -> set[str]:
    code = f"{statement}\nimport sys\nprint(' '.join(sorted(sys.modules)))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    return {m.split(".")[0] for m in out.stdout.split()}


@pytest.mark.parametrize("statement", ["import tuibrdf", "import tuibrdf.core",
                                       "import tuibrdf.core.models"])
def test_core_imports_neither_textual_nor_rich(statement):
    mods = loaded_after(statement)
    assert "textual" not in mods
    assert "rich" not in mods
