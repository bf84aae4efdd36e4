"""Generated documentation matches the declarations it is generated from."""

from __future__ import annotations

import subprocess
import sys

from tests import ROOT


def test_models_doc_is_current():
    r = subprocess.run([sys.executable, "scripts/gen_docs.py", "--check"], cwd=ROOT,
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr


def test_readme_opens_with_the_two_commands():
    lines = [ln for ln in (ROOT / "README.md").read_text().splitlines() if ln.strip()]
    code = [ln for ln in lines[:12] if "pip install" in ln]
    assert any("tuibrdf" in ln and "[test]" not in ln for ln in code)
    assert any("[test]" in ln and "pytest" in ln for ln in code)


def test_readme_picture_is_the_commands_real_output():
    # the README shows `$ tuibrdf render ...` and its output: they must stay the same
    import shlex

    sys.path.insert(0, str(ROOT / "scripts"))
    from gen_docs import run_cli

    text = (ROOT / "README.md").read_text(encoding="utf-8")
    block = text.split("```text\n", 1)[1].split("```", 1)[0]
    first, _, shown = block.partition("\n")
    assert first.startswith("$ tuibrdf render ")
    rc, out = run_cli(" ".join(shlex.split(first[2:])))
    assert rc == 0 and out == shown
