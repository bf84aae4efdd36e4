"""``tuibrdf.picture``: the notebook object (PNG for Jupyter, a Rich renderable, ``save``)."""

from __future__ import annotations

import io
import json
import subprocess
import sys

import numpy as np
import pytest

import tuibrdf

PIL = pytest.importorskip("PIL.Image")


def test_import_tuibrdf_does_not_load_the_renderers():
    code = "import tuibrdf, sys; print('rich' in sys.modules, 'tuibrdf.render' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout
    assert out.split() == ["False", "False"]


def test_repr_png_is_the_map_and_save_by_suffix(tmp_path):
    p = tuibrdf.picture("phong", {"n": 50}, theta_i=30, size=64)
    img = PIL.open(io.BytesIO(p._repr_png_()))
    assert img.size[0] == 64 and img.mode == "P"
    assert p.save(tmp_path / "a.png").read_bytes() == p._repr_png_()
    z = np.load(io.BytesIO(p.save(tmp_path / "a.npz").read_bytes()))
    meta = json.loads(str(z["metadata"]))
    inside = ~np.isnan(z["f"])
    assert np.array_equal(tuibrdf.evaluate(meta["model"], meta["params"], z["wi"],
                                           z["wo"][inside]), z["f"][inside])
    assert (tmp_path / "a.svg").exists() is False
    assert p.save(tmp_path / "a.svg").read_text().startswith("<svg")
    with pytest.raises(ValueError, match="suffix"):
        p.save(tmp_path / "a.gif")


def test_a_line_view_has_no_png_but_its_numbers():
    p = tuibrdf.picture("lambert", {"kd": 0.5}, view="incidence")
    assert p._repr_png_() is None
    rows = json.loads(p.data("json"))
    assert all(r["f"] == pytest.approx(0.5 / np.pi, rel=1e-15) for r in rows)


def test_rich_shows_the_half_block_picture():
    from rich.console import Console

    con = Console(width=40, record=True, color_system=None, file=io.StringIO())
    con.print(tuibrdf.picture("phong", width=40, height=12))
    text = con.export_text()
    assert "phong" in text and len(text.splitlines()) == 12


def test_bad_parameter_fails_when_made():
    with pytest.raises(ValueError):
        tuibrdf.picture("phong", {"n": -1})


def test_a_lit_sphere_exports_every_bit_of_its_tone_mapped_colours():
    # the terminal draws photograph-like pictures on 64 shades a channel (halfblock.SHADES);
    # an export must not: a smooth sphere's 8-bit shading takes values between those shades
    p = tuibrdf.picture("phong", {"n": 20}, theta_i=30, view="sphere", size=128)
    rgb = np.asarray(PIL.open(io.BytesIO(p._repr_png_())).convert("RGB"))
    shades = {round(k * 255 / 63) for k in range(64)}
    values = set(np.unique(rgb).tolist())
    assert len(values - shades) > 50
