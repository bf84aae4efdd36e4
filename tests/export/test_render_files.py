"""``tuibrdf render --format png|npz|csv|json|svg|html --output FILE``: each file read back by
an independent reader (Pillow, numpy, csv, json, xml) and checked against numbers from outside
the writer: the Lambert projection's closed form, ``tuibrdf.evaluate`` and ``tuibrdf.albedo``
called here, Lambert's albedo kd."""

from __future__ import annotations

import csv
import io
import json
import math
import xml.etree.ElementTree as ET

import numpy as np
import pytest

import tuibrdf
from tuibrdf.cli import main

PIL = pytest.importorskip("PIL.Image")


def run(tmp_path, name: str, *argv: str) -> bytes:
    out = tmp_path / name
    assert main(["render", *argv, "--output", str(out)]) == 0
    return out.read_bytes()


# -- PNG ----------------------------------------------------------------------------------
@pytest.mark.parametrize("theta_i", [30.0, 60.0])
def test_png_map_peak_where_the_mirror_direction_projects(tmp_path, theta_i):
    size = 128
    data = run(tmp_path, "m.png", "phong", "-p", "kd=0", "-p", "ks=1", "-p", "n=400",
               "--theta-i", str(theta_i), "--cmap", "grey", "--size", str(size),
               "--format", "png")
    assert data == run(tmp_path, "m2.png", "phong", "-p", "kd=0", "-p", "ks=1", "-p", "n=400",
                       "--theta-i", str(theta_i), "--cmap", "grey", "--size", str(size),
                       "--format", "png")  # deterministic bytes
    img = PIL.open(io.BytesIO(data))
    assert img.mode == "P"  # a palette PNG
    rgb = np.asarray(img.convert("RGB")).astype(int)
    assert rgb.shape[1] == size and rgb.shape[0] > size  # the picture, then the colour bar
    # the mirror direction of wi (θi, φi = 180°) is (θi, φr = 0°); Lambert's equal-area
    # projection puts it at radius 2 sin(θ/2) of the √2-radius disc, on the +x axis.  The
    # disc is (size − 3) pixels across about the grid's centre (± 1 pixel: the half-pixel
    # offsets of the layout)
    radius_px = (size - 3) / 2
    x_expect = size / 2 + 2 * math.sin(math.radians(theta_i) / 2) / math.sqrt(2) * radius_px
    y_expect = size / 2
    disc = rgb[:size]
    ys, xs = np.mgrid[0:size, 0:size] + 0.5
    inside = np.hypot(xs - size / 2, ys - size / 2) < radius_px - 2
    grey = (disc[..., 0] == disc[..., 1]) & (disc[..., 1] == disc[..., 2]) & inside
    top = disc[..., 0][grey].max()
    yy, xx = np.nonzero(grey & (disc[..., 0] == top))
    assert len(xx) < 40  # a lobe of n = 400 peaks in a few pixels
    assert abs(xx.mean() + 0.5 - x_expect) <= 1.5 and abs(yy.mean() + 0.5 - y_expect) <= 1.5
    # far from the lobe the map is dark (kd = 0)
    assert disc[int(y_expect), int(size / 2 - radius_px / 2)][0] < 10


@pytest.mark.parametrize("view", ["slice", "sphere", "plane", "solid"])
def test_png_other_image_views_decode(tmp_path, view):
    data = run(tmp_path, "v.png", "phong", "--view", view, "--size", "96", "--format", "png")
    img = PIL.open(io.BytesIO(data))
    img.load()  # decodes every row: the CRCs and the zlib stream are checked by Pillow
    assert img.size[0] >= 64
    assert data == run(tmp_path, "v2.png", "phong", "--view", view, "--size", "96",
                       "--format", "png")


# -- NPZ ----------------------------------------------------------------------------------
def test_npz_map_values_are_evaluate_at_the_stated_directions(tmp_path):
    data = run(tmp_path, "m.npz", "phong", "-p", "n=50", "--theta-i", "40", "--phi-i", "120",
               "--size", "48", "--format", "npz")
    z = np.load(io.BytesIO(data))
    meta = json.loads(str(z["metadata"]))
    assert meta["model"] == "phong" and meta["params"]["n"] == 50
    assert meta["theta_i"] == 40 and meta["phi_i"] == 120
    inside = ~np.isnan(z["f"])
    assert np.isnan(z["theta_r"][~inside]).all() and np.isnan(z["phi_r"][~inside]).all()
    # equal-area: the disc (diameter 45 px) covers π·22.5² pixels, to within its rim
    assert abs(inside.sum() - math.pi * 22.5**2) < 2 * math.pi * 22.5
    wo = z["wo"][inside]
    # same function, same inputs: exactly equal
    f = tuibrdf.evaluate(meta["model"], meta["params"], z["wi"], wo)
    assert np.array_equal(f, z["f"][inside])
    # wi is the light at (θi, φi); the angles are those of wo
    t, p = math.radians(40), math.radians(120)
    assert np.allclose(z["wi"], [math.sin(t) * math.cos(p), math.sin(t) * math.sin(p),
                                 math.cos(t)], atol=1e-15)
    th = np.degrees(np.arctan2(np.hypot(wo[:, 0], wo[:, 1]), wo[:, 2]))
    ph = np.degrees(np.arctan2(wo[:, 1], wo[:, 0]))
    assert np.allclose(z["theta_r"][inside], th, atol=1e-12)
    assert np.allclose(z["phi_r"][inside], ph, atol=1e-12)
    assert data == run(tmp_path, "m2.npz", "phong", "-p", "n=50", "--theta-i", "40",
                       "--phi-i", "120", "--size", "48", "--format", "npz")


@pytest.mark.parametrize("view", ["sphere", "plane", "solid"])
def test_npz_of_the_views_drawn_from_the_hemisphere_is_f_over_it(tmp_path, view):
    """The lit sphere, the lit plane and the solid are drawn from f over the hemisphere at the
    light: their NPZ holds those values, each ``tuibrdf.evaluate`` at the stated directions."""
    data = run(tmp_path, f"{view}.npz", "ggx", "--theta-i", "50", "--size", "32", "--view",
               view, "--format", "npz")
    z = np.load(io.BytesIO(data))
    meta = json.loads(str(z["metadata"]))
    inside = ~np.isnan(z["f"])
    assert inside.sum() > 0.7 * math.pi * 15**2  # most of the disc of a 32-px grid
    f = tuibrdf.evaluate(meta["model"], meta["params"], z["wi"], z["wo"][inside])
    assert np.array_equal(f, z["f"][inside])


def test_npz_rgb_model_has_three_channels(tmp_path):
    data = run(tmp_path, "rgb.npz", "gltf", "-p", "base_color=0.9,0.5,0.1", "--size", "32",
               "--format", "npz")
    z = np.load(io.BytesIO(data))
    assert z["f"].shape == (32, 32, 3)
    inside = ~np.isnan(z["f"][..., 0])
    f = tuibrdf.evaluate("gltf", {"base_color": (0.9, 0.5, 0.1)}, z["wi"], z["wo"][inside])
    assert np.array_equal(f, z["f"][inside])


# -- CSV / JSON ---------------------------------------------------------------------------
def read_csv(data: bytes) -> tuple[list[str], list[list[str]]]:
    rows = list(csv.reader(io.StringIO(data.decode())))
    return rows[0], rows[1:]


@pytest.mark.parametrize("view", ["incidence", "perpendicular"])
def test_csv_section_values_round_trip_and_equal_evaluate(tmp_path, view):
    data = run(tmp_path, "s.csv", "phong", "-p", "n=80", "--theta-i", "35", "--view", view,
               "--format", "csv")
    head, rows = read_csv(data)
    assert head == ["theta", "wi_x", "wi_y", "wi_z", "wo_x", "wo_y", "wo_z", "f"]
    assert len(rows) == 181
    for r in rows:
        assert all(repr(float(s)) == s for s in r)  # full precision: the text round-trips
    a = np.array(rows, dtype=float)
    f = tuibrdf.evaluate("phong", {"n": 80}, a[:, 1:4], a[:, 4:7])
    assert np.array_equal(f, a[:, 7])
    assert a[0, 0] == -90.0 and a[-1, 0] == 90.0
    if view == "incidence":
        # signed θ: negative on the light's side (φi = 180°: −x), wo = (sin θ, 0, cos θ)
        th = np.radians(a[:, 0])
        assert np.allclose(a[:, 4:7], np.stack([np.sin(th), 0 * th, np.cos(th)], 1),
                           atol=1e-15)
        assert np.all(a[:, 1] < 0)  # the light on −x
    # the JSON has the same numbers
    rows_json = json.loads(run(tmp_path, "s.json", "phong", "-p", "n=80", "--theta-i", "35",
                               "--view", view, "--format", "json"))
    assert [r["f"] for r in rows_json] == list(a[:, 7])


def test_albedo_json_and_csv_agree_with_tuibrdf_albedo(tmp_path):
    rows = json.loads(run(tmp_path, "a.json", "phong", "-p", "n=30", "--view", "albedo",
                          "--format", "json"))
    assert [r["theta_i"] for r in rows] == [3.0 * k for k in range(31)]
    for r in rows[::5]:
        assert set(r) == {"theta_i", "albedo", "error"}
        ref = tuibrdf.albedo("phong", {"n": 30}, r["theta_i"])
        assert abs(r["albedo"] - float(ref)) <= 2 * r["error"] + 1e-12
    head, body = read_csv(run(tmp_path, "a.csv", "phong", "-p", "n=30", "--view", "albedo",
                              "--format", "csv"))
    assert head == ["theta_i", "albedo", "error"]
    assert [float(b[1]) for b in body] == [r["albedo"] for r in rows]


def test_albedo_of_lambert_is_kd(tmp_path):
    rows = json.loads(run(tmp_path, "a.json", "lambert", "-p", "kd=0.3", "--view", "albedo",
                          "--format", "json"))
    for r in rows:
        assert abs(r["albedo"] - 0.3) <= r["error"] + 1e-12


@pytest.mark.parametrize("view", ["theta-h", "theta-d"])
def test_halfdiff_curves_are_evaluate_at_their_directions(tmp_path, view):
    head, rows = read_csv(run(tmp_path, "c.csv", "cook-torrance", "--view", view,
                              "--format", "csv"))
    assert head[0] == view.replace("-", "_") and head[-1] == "f"
    a = np.array(rows, dtype=float)
    ok = ~np.isnan(a[:, -1])
    assert ok.sum() > 100
    f = tuibrdf.evaluate("cook-torrance", None, a[ok, 1:4], a[ok, 4:7])
    assert np.array_equal(f, a[ok, -1])


# -- SVG / HTML ---------------------------------------------------------------------------
@pytest.mark.parametrize("view", ["map", "incidence", "albedo"])
def test_svg_is_xml_self_contained_and_deterministic(tmp_path, view):
    args = ("phong", "--view", view, "--width", "40", "--height", "14", "--format", "svg")
    data = run(tmp_path, "p.svg", *args)
    root = ET.fromstring(data)
    assert root.tag.endswith("svg")
    assert b"http" not in data.replace(b"http://www.w3.org/2000/svg", b"").replace(
        b"https://www.textualize.io", b"")  # no font or anything else fetched
    assert data == run(tmp_path, "p2.svg", *args)
    html = run(tmp_path, "p.html", *args[:-1], "html")
    assert b"<pre" in html and b"url(" not in html


# -- errors -------------------------------------------------------------------------------
@pytest.mark.parametrize("argv", [
    ("--view", "albedo", "--format", "png"),
    ("--view", "map", "--format", "csv"),
    ("--view", "incidence", "--format", "npz"),
    ("--view", "all", "--format", "json"),
    ("--format", "jpeg"),
])
def test_a_format_a_view_has_not_is_one_line_and_exit_2(tmp_path, capsys, argv):
    rc = main(["render", "phong", *argv, "--output", str(tmp_path / "x")])
    _, err = capsys.readouterr()
    assert rc == 2 and err.count("\n") == 1 and "format" in err
    assert not (tmp_path / "x").exists()


def test_text_to_a_file_is_plain_and_ansi_has_colour(tmp_path):
    text = run(tmp_path, "p.txt", "phong", "--width", "40", "--height", "12").decode()
    assert "\x1b" not in text and "phong" in text
    assert all(line == line.rstrip() for line in text.splitlines())
    ansi = run(tmp_path, "p.ansi", "phong", "--width", "40", "--height", "12",
               "--format", "ansi").decode()
    assert "\x1b[38;2;" in ansi  # truecolor escapes
    # the same picture (half blocks instead of the ASCII ramp) under the same title
    import re

    plain = re.sub(r"\x1b\[[0-9;]*m", "", ansi).splitlines()
    # the context line (model, θi, φi), then the picture's 12 lines
    assert len(plain) == len(text.splitlines()) == 1 + 12
    assert plain[0].startswith("phong  θi=")
    assert "▀" in "".join(plain)


def test_binary_to_a_terminal_is_refused(capsys, monkeypatch):
    from tuibrdf.cli import export

    monkeypatch.setattr(export, "isatty", lambda stream: True)
    rc = main(["render", "phong", "--format", "png"])
    out, err = capsys.readouterr()
    assert rc == 2 and out == "" and "--output FILE" in err


def test_png_to_stdout_when_piped(capsysbinary):
    assert main(["render", "phong", "--format", "png", "--size", "40"]) == 0
    out = capsysbinary.readouterr().out
    assert out.startswith(b"\x89PNG\r\n\x1a\n") and PIL.open(io.BytesIO(out)).size[0] == 40


def test_the_size_limits_agree():
    from tuibrdf.cli import export
    from tuibrdf.render.export import figure

    assert (export.MIN_SIZE, export.MAX_SIZE) == (figure.MIN_SIZE, figure.MAX_SIZE)
    assert export.IMAGE_VIEWS == figure.IMAGE_VIEWS
    from tuibrdf.render.export import plot

    assert set(export.PDF_VIEWS) == set(plot.VIEWS)
