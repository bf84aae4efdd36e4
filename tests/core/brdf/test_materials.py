"""The ABC and SGD fits of the 100 MERL materials (issue 15).

Expected values come from outside the package code:

* the header's text: rows of ``dj_brdf.h`` (jdupuy/dj_brdf, commit 94cb16a, public domain)
  copied verbatim below, parsed here with their own regular expression;
* an independent scalar evaluation of the published formulas written in this file (Python
  ``math``, one direction pair at a time), for every material of both tables;
* values computed by hand from the formulas, with the steps in the comments.
"""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

import tuibrdf
from tuibrdf.core.brdf.fitted import MATERIAL, sgd_g1
from tuibrdf.core.brdf.materials import FILES, material_aliases, material_names, table
from tuibrdf.core.directions import from_degrees
from tuibrdf.core.numerics import kernel_errstate
from tuibrdf.core.registry import MODELS

# ------------------------------------------------------------------ rows of the header, verbatim

HEADER_SGD = [
    ('{ "black-obsidian", "black-obsidian", { 0.00130399, 0.0011376, 0.00107233 }, { 0'
     '.133029, 0.125362, 0.126188 }, { 0.000153649, 0.000148939, 0.000179285 }, { 0.18'
     '6234, 0.227495, 0.25745 }, { 2.42486e-12, 0.0174133, 0.091766 }, { -0.0800755, -'
     '0.048671, 0.0406445 }, { 5668.57, 5617.79, 4522.84 }, { 13.7614, 8.59526, 6.4466'
     '7 }, { 1e+38, 1e+38, 1e+38 }, { 117.224, 120.912, 113.366 }, { 1.19829, 1.19885,'
     ' 1.19248 }, { 0.0841374, 0.0943085, 0.123514 } },'),
    ('{ "white-fabric2", "", { 0.10784, 0.102669, 0.113943 }, { 0.0375359, 0.0296317, '
     '0.0364218 }, { 0.0583526, 0.0520763, 0.063905 }, { 9.1836e-12, 5.41897e-13, 3.47'
     '708e-12 }, { 0.0528459, 0.0854122, 0.0860966 }, { 0.0578589, 0.0971296, 0.098571'
     '7 }, { 18.1669, 20.2291, 16.6809 }, { 4.60692, 4.77932, 4.46485 }, { 0.172556, 0'
     '.23927, 0.138435 }, { 13.5006, 13.9648, 13.1165 }, { 0.561147, 0.587176, 0.54153'
     ' }, { 0.00113864, 0.00114867, 0.00119185 } },'),
    ('{ "gold-metallic-paint", "metallic-gold", { 0.0178625, 0.00995704, 0.00335044 },'
     ' { 0.17127, 0.120714, 0.115473 }, { 0.127954, 0.127825, 0.109623 }, { 0.781093, '
     '0.795517, 0.661313 }, { 1.00776e-12, 1.22243e-15, 6.18432e-13 }, { -1, -1, -0.33'
     '4497 }, { 5.90039, 5.83556, 7.14985 }, { 2.7548, 2.7057, 2.94348 }, { 9.46481e-0'
     '8, 1.06951e-07, 1.10733e-07 }, { 23.8811, 23.9059, 24.2972 }, { -0.303345, -0.29'
     '3778, -0.267019 }, { 0.0095612, 0.00483452, 0.00145599 } },'),
    ('{ "alum-bronze", "alum-bronze", { 0.0478786, 0.0313514, 0.0200638 }, { 0.0364976'
     ', 0.664975, 0.268836 }, { 0.014832, 0.0300126, 0.0490339 }, { 0.459076, 0.450056'
     ', 0.529272 }, { 6.05524, 0.235756, 0.580647 }, { 5.05524, 0.182842, 0.476088 }, '
     '{ 46.3841, 24.5961, 14.8261 }, { 2.60672, 2.97371, 2.7827 }, { 1.12717e-07, 1.06'
     '401e-07, 5.27952e-08 }, { 47.783, 36.2767, 31.6066 }, { 0.205635, 0.066289, -0.0'
     '661091 }, { 0.100735, 0.0878706, 0.0861907 } },'),
]
HEADER_ABC = [
    ('{ "alum-bronze", {0.024514, 0.022346, 0.016220}, {51.714554, 37.932693, 27.37309'
     '5}, 10482.133789, 0.816737, 2.236525 },'),
    ('{ "black-obsidian", {0.000000, 0.000000, 0.000000}, {1447.612183, 1281.373169, 1'
     '313.115601}, 223549.906250, 1.196914, 1.485313 },'),
    ('{ "gold-metallic-paint", {0.009164, 0.005649, 0.000424}, {1.685630, 1.147257, 0.'
     '418757}, 53.738525, 1.511730, 9.031934 },'),
    ('{ "white-fabric2", {0.074490, 0.068798, 0.080224}, {0.078094, 0.081885, 0.083064'
     '}, 6166446.000000, 0.023514, 2.997413 },'),
]

_NUM = r"\s*([-+0-9.eE]+)\s*"
_VEC = r"\{" + ",".join([_NUM] * 3) + r"\}"


def header_sgd(line: str):
    m = re.fullmatch(r'\{ "([^"]+)", "([^"]*)", ' + r",\s*".join([_VEC] * 12) + r"\s*\},",
                     line)
    assert m, line
    g = m.groups()
    return g[0], g[1], np.array([float(x) for x in g[2:]]).reshape(12, 3)


def header_abc(line: str):
    m = re.fullmatch(r'\{ "([^"]+)", ' + _VEC + r",\s*" + _VEC + "," + ",".join([_NUM] * 3)
                     + r"\},", line)
    assert m, line
    g = m.groups()
    return g[0], [float(x) for x in g[1:]]


SGD_ORDER = ("rho_d", "rho_s", "alpha", "p", "f0", "f1", "kappa", "lambda", "c_g", "k",
             "theta0", "error")


def test_tables_have_100_rows_each_with_the_same_names():
    for kind in ("abc", "sgd"):
        t = table(kind)
        assert len(t.names) == 100 and len(set(t.names)) == 100
        for v in t.values.values():
            assert v.shape[0] == 100 and v.dtype == np.float64
    assert set(table("abc").names) == set(table("sgd").names) == set(material_names())
    assert len(material_names()) == 100


@pytest.mark.parametrize("line", HEADER_SGD, ids=lambda s: s.split('"')[1])
def test_sgd_rows_equal_the_header_text(line):
    name, other, vecs = header_sgd(line)
    t = table("sgd")
    i = t.index(name)
    assert t.other_names[i] == other
    for field, expected in zip(SGD_ORDER, vecs, strict=True):
        # float64 of the same decimal text: bit-for-bit equal
        assert t.values[field][i].tolist() == expected.tolist(), field


@pytest.mark.parametrize("line", HEADER_ABC, ids=lambda s: s.split('"')[1])
def test_abc_rows_equal_the_header_text(line):
    name, nums = header_abc(line)
    row = table("abc").row(name)
    got = [*row["kd"], *row["a"], row["b"], row["c"], row["eta"]]
    assert got == nums


def test_data_files_state_source_and_licence():
    for path in FILES.values():
        head = path.read_text(encoding="utf-8")[:1000]
        assert "jdupuy/dj_brdf" in head and "public domain" in head


def test_importing_tuibrdf_does_not_parse_the_numbers():
    import subprocess
    import sys

    code = ("import tuibrdf; from tuibrdf.core.brdf.materials import table; "
            "print(table.cache_info().currsize)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True)
    assert out.stdout.strip() == "0"


# ------------------------------------------------------------------ the material parameter


def test_material_is_one_declared_choice_shared_by_both_models():
    assert MODELS["abc"].params == (MATERIAL,) and MODELS["sgd"].params == (MATERIAL,)
    assert MATERIAL.kind == "choice" and MATERIAL.choices == material_names()
    assert MATERIAL.default in MATERIAL.choices


def test_sgd_other_names_are_accepted_and_mapped():
    # from the header: { "beige-fabric", "fabric-beige", ... }, { "gold-metallic-paint",
    # "metallic-gold", ... }, { "specular-black-phenolic", "black-bball", ... }
    assert dict(material_aliases())["fabric-beige"] == "beige-fabric"
    assert MODELS["sgd"].resolve({"material": "metallic-gold"}) == {
        "material": "gold-metallic-paint"}
    assert MODELS["abc"].resolve({"material": "BLACK-BBALL"}) == {
        "material": "specular-black-phenolic"}
    wi, wo = from_degrees(30.0, 180.0), from_degrees(40.0, 10.0)
    a = tuibrdf.evaluate("sgd", {"material": "fabric-beige"}, wi, wo)
    b = tuibrdf.evaluate("sgd", {"material": "beige-fabric"}, wi, wo)
    assert np.array_equal(a, b)


def test_unknown_material_is_one_short_line_with_a_close_match():
    with pytest.raises(ValueError) as e:
        tuibrdf.evaluate("abc", {"material": "gold-metalic-paint"}, [0, 0, 1], [0, 0, 1])
    msg = str(e.value)
    assert "did you mean 'gold-metallic-paint'" in msg
    assert "tuibrdf materials" in msg and len(msg) < 200 and "\n" not in msg


# ------------------------------------------------------------------ independent evaluation


def _unit(v):
    n = math.sqrt(sum(x * x for x in v))
    return [x / n for x in v]


def _dir(theta_deg, phi_deg):
    t, p = math.radians(theta_deg), math.radians(phi_deg)
    return [math.sin(t) * math.cos(p), math.sin(t) * math.sin(p), math.cos(t)]


def _polar(w):
    return math.atan2(math.hypot(w[0], w[1]), w[2])


def ref_abc(r, wi, wo):
    """Löw et al. 2012 as the issue writes it, one channel at a time.  Fresnel in the rs/rp
    form (a different algebra from the kernel's), 1 − cos θh as 2 sin²(θh/2)."""
    h = _unit([a + b for a, b in zip(wi, wo, strict=True)])
    ci, co, ch = wi[2], wo[2], h[2]
    cd = sum(a * b for a, b in zip(h, wi, strict=True))
    th = _polar(h)
    n = r["eta"]
    g = math.sqrt(n * n - 1.0 + cd * cd)
    rs = (cd - g) / (cd + g)
    rp = (n * n * cd - g) / (n * n * cd + g)
    fres = 0.5 * (rs * rs + rp * rp)
    geo = min(1.0, 2.0 * ch * ci / cd, 2.0 * ch * co / cd)
    out = []
    for c in range(3):
        d = r["a"][c] / (1.0 + r["b"] * 2.0 * math.sin(th / 2.0) ** 2) ** r["c"]
        out.append(r["kd"][c] / math.pi + fres * d * geo / (math.pi * ci * co))
    return out


def ref_g1(theta, lam, c_g, k, theta0):
    t = max(0.0, theta - theta0)
    try:
        x = c_g * t**k
        e = math.expm1(x)  # 1 − exp(x) = −expm1(x), without losing x's digits
    except OverflowError:  # exp(x) beyond 1e308: G1 = 1 + Λ(1 − e^x) is far below 0
        return 0.0
    return min(1.0, max(0.0, 1.0 - lam * e))


def ref_sgd(r, wi, wo):
    """Bagher et al. 2012 as the issue writes it, one channel at a time."""
    h = _unit([a + b for a, b in zip(wi, wo, strict=True)])
    ci, co, ch = wi[2], wo[2], h[2]
    cd = sum(a * b for a, b in zip(h, wi, strict=True))
    tan2 = (h[0] ** 2 + h[1] ** 2) / (ch * ch)
    ti, to = _polar(wi), _polar(wo)
    out = []
    for c in range(3):
        v = {k: r[k][c] for k in SGD_ORDER}
        fres = v["f0"] - cd * v["f1"] + (1.0 - cd) ** 5 * (1.0 - v["f0"])
        a = v["alpha"] + tan2 / v["alpha"]
        d = v["kappa"] * math.exp(-a) / (math.pi * a ** v["p"] * ch**4)
        g1 = [ref_g1(t, v["lambda"], v["c_g"], v["k"], v["theta0"]) for t in (ti, to)]
        f = (v["rho_d"] + v["rho_s"] * fres * d * g1[0] * g1[1] / (ci * co)) / math.pi
        out.append(max(f, 0.0))
    return out


#: generic pairs (θi, φi, θo, φo) in degrees: away from H = N, the horizon and wi = wo, and
#: with θ up to 80° so the G1 and Fresnel terms vary
GENERIC = [(10.0, 180.0, 20.0, 0.0), (35.0, 180.0, 45.0, 40.0), (60.0, 180.0, 75.0, 130.0),
           (25.0, 200.0, 30.0, 10.0), (50.0, 170.0, 52.0, 0.0), (70.0, 180.0, 65.0, -20.0),
           (15.0, 90.0, 80.0, 250.0), (45.0, 180.0, 10.0, 60.0), (80.0, 180.0, 78.0, 5.0)]
#: and grazing ones: wi = wo 0.02° above the horizon (H = wi, cos θh = 3.5e-4), and a pair
#: 0.5° above it on either side of the plane of incidence
GRAZING = [(89.98, 180.0, 89.98, 180.0), (89.5, 150.0, 89.5, 20.0)]
REF = {"abc": ref_abc, "sgd": ref_sgd}


@pytest.mark.parametrize("model", ["abc", "sgd"])
def test_every_material_equals_the_independent_evaluation(model):
    pairs = GENERIC + GRAZING
    wi = np.array([_dir(a, b) for a, b, _, _ in pairs])
    wo = np.array([_dir(c, d) for _, _, c, d in pairs])
    for name in material_names():
        got = tuibrdf.evaluate(model, {"material": name}, wi, wo)
        row = table(model).row(name)
        want = np.array([REF[model](row, list(a), list(b)) for a, b in zip(wi, wo, strict=True)])
        assert np.all(want > 0.0), name
        rel = np.abs(got - want) / want
        assert rel.max() <= 1e-12, (name, rel.max())


# ------------------------------------------------------------------ by hand


def test_abc_by_hand_alum_bronze():
    # header: { "alum-bronze", {0.024514, 0.022346, 0.016220}, {51.714554, 37.932693,
    #           27.373095}, 10482.133789, 0.816737, 2.236525 }
    # 1. wi = wo = N: H = N, θh = 0 → D = A; cos θd = 1 → G = min(1, 2, 2) = 1;
    #    F(1) = ((η − 1)/(η + 1))² = (1.236525/3.236525)² = 0.382063² = 0.1459647;
    #    f = (kd + F·A)/π: R (0.024514 + 0.1459647·51.714554)/π = 7.573157/π = 2.410565
    n = np.array([0.0, 0.0, 1.0])
    f = tuibrdf.evaluate("abc", {"material": "alum-bronze"}, n, n)
    np.testing.assert_allclose(f, [2.410565, 1.769542, 1.276972], rtol=1e-6)
    # 2. θi = 0, θo = 60° (φo = 0): H at θh = 30°, cos θd = cos 30° = 0.8660254;
    #    1 − cos θh = 0.1339746, 1 + B·0.1339746 = 1405.3396, ^C = 372.31407;
    #    D_R = 51.714554/372.31407 = 0.1389003;
    #    g = √(η² − 1 + cd²) = √(5.002044 − 1 + 0.75) = 2.1799184;
    #    F = ½ (g − c)²/(g + c)² (1 + (c(g + c) − 1)²/(c(g − c) + 1)²) = 0.1476412;
    #    G = min(1, 2·0.866·1/0.866, 2·0.866·0.5/0.866) = min(1, 2, 1) = 1;
    #    f_R = (0.024514 + 0.1476412·0.1389003·1/(1·0.5))/π = 0.0655313/π = 0.02085847
    f = tuibrdf.evaluate("abc", {"material": "alum-bronze"}, n, from_degrees(60.0, 0.0))
    np.testing.assert_allclose(f, [0.02085847, 0.01668912, 0.01207337], rtol=1e-6)


def test_sgd_by_hand_alum_bronze():
    # header: { "alum-bronze", "alum-bronze", ρd {0.0478786, 0.0313514, 0.0200638}, ρs
    #   {0.0364976, 0.664975, 0.268836}, α {0.014832, ...}, p {0.459076, ...}, f0 {6.05524,
    #   0.235756, 0.580647}, f1 {5.05524, 0.182842, 0.476088}, κ {46.3841, ...}, Λ {2.60672,
    #   ...}, c_g {1.12717e-07, ...}, k {47.783, ...}, θ0 {0.205635, 0.066289, -0.0661091}, ...}
    # wi = wo = N: cos θd = 1 → F = f0 − f1: R 1.0, G 0.052914, B 0.104559;
    # θh = 0 → a = α, D = κ e^(−α)/(π α^p): R 46.3841·0.985277/(π·0.144696) = 100.53936;
    # θ = 0: G1 = 1 for R and G (θ0 > 0: t = 0); B: t = 0.0661091, x = c_g t^k = 2.7e-45 → 1;
    # f = (ρd + ρs·F·D)/π: R (0.0478786 + 0.0364976·1·100.53936)/π = 3.717358/π = 1.183261
    n = np.array([0.0, 0.0, 1.0])
    f = tuibrdf.evaluate("sgd", {"material": "alum-bronze"}, n, n)
    np.testing.assert_allclose(f, [1.183261, 0.4222732, 0.2047056], rtol=1e-6)


def test_sgd_g1_by_hand_and_its_clamp():
    r = table("sgd").row("alum-bronze")
    args = (r["lambda"], r["c_g"], r["k"], r["theta0"])
    with kernel_errstate():
        # θ = 80° = 1.3962634 rad, red: t = θ − 0.205635 = 1.1906284, k ln t = 47.783·0.1744812
        # = 8.337237, t^k = 4176.534, x = 1.12717e-07·4176.534 = 4.707663e-4,
        # G1 = 1 − 2.60672·expm1(x) = 1 − 2.60672·4.708772e-4 = 0.9987726
        g = sgd_g1(np.array(np.radians(80.0)), *args)
        assert g[0] == pytest.approx(0.9987726, rel=1e-7)
        # θ = 90°: x = 0.3247023, just below the clamp's threshold log(1 + 1/Λ) = 0.3247060:
        # G1 = 1 − Λ·expm1(x) = 1.35e-5 > 0
        g = sgd_g1(np.array(np.pi / 2), *args)
        assert g[0] == pytest.approx(1.345783e-5, rel=1e-4)
        # black-obsidian, c_g = 1e38, k = 117.224, θ0 = 1.19829: at θ = 90°, t = 0.372506,
        # x = 1e38·t^117.224 = 1e38·10^(−50.26) ≈ 5.5e-13: G1 = 1 − 13.7614·5.5e-13 ≈ 1
        b = table("sgd").row("black-obsidian")
        g = sgd_g1(np.array(np.pi / 2), b["lambda"], b["c_g"], b["k"], b["theta0"])
        assert 1.0 - 1e-10 < g[0] <= 1.0
        # an extreme the guard must survive: the same parameters with k = 1 give x = 3.7e37,
        # exp(x) overflows; G1 is 0 (Λ > 0), no FloatingPointError
        g = sgd_g1(np.array(np.pi / 2), b["lambda"], b["c_g"], np.ones(3), b["theta0"])
        assert np.all(g == 0.0)


@pytest.mark.parametrize("model", ["abc", "sgd"])
def test_opposite_directions_on_the_horizon_leave_the_diffuse_term(model):
    """wi = −wo on the horizon: H is undefined, the specular term is 0 there and the value
    is the diffuse term, kd/π (abc) or ρd/π (sgd; ρd ≥ 0 in every table)."""
    wi = np.array([math.cos(math.radians(200.0)), math.sin(math.radians(200.0)), 0.0])
    for name in material_names():
        row = table(model).row(name)
        want = (row["kd"] if model == "abc" else row["rho_d"]) / math.pi
        np.testing.assert_array_equal(tuibrdf.evaluate(model, {"material": name}, wi, -wi), want)


def test_both_models_are_declared_reciprocal_rgb():
    for name in ("abc", "sgd"):
        assert MODELS[name].rgb and MODELS[name].reciprocal
