"""The ``[plot]`` extra: PDF figures with matplotlib, imported only when asked for."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from tuibrdf.cli import main


def modules_after(code: str) -> set[str]:
    code += "\nimport sys\nprint(' '.join(sys.modules))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout
    return {m.split(".")[0] for m in out.split()}


def test_matplotlib_is_never_on_the_help_or_viewer_path():
    mods = modules_after("from tuibrdf.cli import main\nimport contextlib, io\n"
                         "with contextlib.redirect_stdout(io.StringIO()):\n"
                         "    main(['render', '--help'])\n"
                         "import tuibrdf.cli.export, tuibrdf.app.app\n"
                         "import tuibrdf.render.export.picture")
    assert "matplotlib" not in mods


@pytest.mark.parametrize("view", ["map", "incidence", "perpendicular", "albedo", "theta-h"])
def test_pdf_figures_are_pdf_and_deterministic(tmp_path, view):
    pytest.importorskip("matplotlib")
    args = ["render", "phong", "--view", view, "--size", "64", "--format", "pdf"]
    assert main([*args, "--output", str(tmp_path / "a.pdf")]) == 0
    assert main([*args, "--output", str(tmp_path / "b.pdf")]) == 0
    a = (tmp_path / "a.pdf").read_bytes()
    assert a.startswith(b"%PDF-") and a.rstrip().endswith(b"%%EOF")
    assert a == (tmp_path / "b.pdf").read_bytes()
    assert b"CreationDate" not in a


def test_pdf_of_a_view_without_one_is_exit_2(capsys):
    assert main(["render", "phong", "--view", "solid", "--format", "pdf", "-o", "x.pdf"]) == 2
    assert "pdf" in capsys.readouterr().err


def test_pdf_without_matplotlib_says_how_to_get_it(capsys, monkeypatch):
    from tuibrdf.render.export import plot

    monkeypatch.setattr(plot, "available", lambda: False)
    assert main(["render", "phong", "--format", "pdf", "-o", "x.pdf"]) == 2
    err = capsys.readouterr().err
    assert "tuibrdf[plot]" in err and err.count("\n") == 1


def test_picture_saves_pdf(tmp_path):
    pytest.importorskip("matplotlib")
    import tuibrdf

    p = tuibrdf.picture("ggx", view="albedo")
    assert p.save(tmp_path / "a.pdf").read_bytes().startswith(b"%PDF-")
    assert json.loads(p.data("json"))[0]["theta_i"] == 0.0
