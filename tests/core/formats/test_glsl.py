"""The GLSL subset of BRDF Explorer shaders (:mod:`tuibrdf.core.formats.glsl`), through
``.brdf`` files: semantics (masked branches, early returns per direction, undefined operations,
out parameters, overloads, swizzles) and errors naming the file, the line and the construct.
The file format itself, and the files checked against independent references, are
tests/core/formats/test_brdf_explorer.py's.
"""

from __future__ import annotations

import numpy as np
import pytest

from tests.core.formats.test_brdf_explorer import (
    FIRST_SHADER_LINE,
    HEAD,
    ev,
    shader_error,
    shader_file,
)

# --------------------------------------------------------------------------- semantics


def run_shader(tmp_path, body, helpers="", wi=None, wo=None, params=None, name="s.brdf"):
    f = tmp_path / name
    f.write_text(shader_file(body, helpers))
    if wi is None:
        wi = np.array([[0.6, 0.0, 0.8], [-0.6, 0.0, 0.8], [0.0, 0.0, 1.0]])
    if wo is None:
        wo = np.array([[0.0, 0.0, 1.0]] * len(wi))
    return ev(f, params or {}, wi, wo)


@pytest.mark.parametrize("expr,want", [
    ("pow(-2.0, 2.0)", 0.0),        # pow of x < 0: 0 (undefined in GLSL)
    ("pow(0.0, 0.0)", 0.0),         # pow(0, y ≤ 0): 0
    ("pow(2.0, 3.0)", 8.0),
    ("1.0 / (k - 0.5)", 0.0),       # division by zero: 0
    ("sqrt(k - 1.0)", 0.0),         # sqrt of x < 0: 0
    ("log(k - 0.5)", 0.0),          # log of 0: 0
    ("acos(1.0 + k)", 0.0),         # acos clamps to [-1, 1]: acos(1) = 0
    ("length(normalize(vec3(k - 0.5)))", 0.0),  # normalize(0) = 0
    ("exp(2000.0 * k)", 0.0),       # overflow to inf: made 0
    ("-1.0", 0.0),                  # negative result: 0
    ("smoothstep(0.0, 1.0, k)", 0.5),
    ("mix(1.0, 3.0, k)", 2.0),
    ("clamp(3.0, 0.0, 1.0) + step(0.5, k) + mod(7.0, 4.0)", 5.0),
    ("atan(1.0, 1.0) * 4.0", np.pi),
    ("degrees(radians(30.0))", 30.0),
    ("flag ? 1.0 : 2.0", 2.0),
    ("float(k > 0.25) + float(!flag)", 2.0),
])
def test_undefined_and_builtin_operations(tmp_path, expr, want):
    # each expression is evaluated by the shader at k = 0.5, flag off; expected values are
    # the documented choice (docs/reference/formats.md) or the closed form
    got = run_shader(tmp_path, f"return vec3({expr});")
    np.testing.assert_allclose(got, want, rtol=1e-15)


def test_early_return_is_per_direction(tmp_path):
    body = "if (L.x > 0.0) return vec3(1.0);\nif (L.x < 0.0) { return vec3(2.0); }\n" \
           "return vec3(3.0);"
    got = run_shader(tmp_path, body)[:, 0]
    assert got.tolist() == [1.0, 2.0, 3.0]  # L.x = 0.6, -0.6, 0


def test_branch_assignment_and_nested_early_return_in_a_helper(tmp_path):
    helpers = """
float pick(float x)
{
    float y = 10.0;
    if (x > 0.0) {
        y = 20.0;
        if (x > 0.5) return 30.0;
    } else y = 40.0;
    return y;
}"""
    got = run_shader(tmp_path, "return vec3(pick(L.x), pick(L.x * 0.5), pick(-1.0));",
                     helpers)
    # L.x = 0.6: 30; 0.3: 20; L.x = -0.6: 40 ... columns: pick(L.x), pick(L.x/2), pick(-1)
    assert got.tolist() == [[30.0, 20.0, 40.0], [40.0, 40.0, 40.0], [40.0, 40.0, 40.0]]


def test_out_parameters_overloads_and_swizzles(tmp_path):
    helpers = """
float twice(float x) { return 2.0 * x; }
vec3 twice(vec3 v) { return v.zyx * 2.0; }
void split(vec3 v, out float a, inout vec3 b) { a = v.x + v[1]; b.y = v.z; }
"""
    body = "float a; vec3 b = vec3(7.0);\nsplit(vec3(1.0, 2.0, 3.0), a, b);\n" \
           "vec3 t = twice(vec3(1.0, 2.0, 3.0));\nreturn vec3(a, b.y + b.x, t.r + twice(k));"
    got = run_shader(tmp_path, body, helpers)
    assert got[0].tolist() == [3.0, 10.0, 7.0]  # a = 1+2; b = (7,3,7); t = (6,4,2) → 6+1


def test_uniform_branches_select_without_masks(tmp_path):
    body = "float r = 1.0;\nif (flag) r = 2.0; else r = 3.0;\nreturn vec3(r);"
    assert run_shader(tmp_path, body)[0, 0] == 3.0
    assert run_shader(tmp_path, body, params={"flag": "on"})[0, 0] == 2.0


def test_below_the_horizon_is_zero_and_float_brdf_is_scalar(tmp_path):
    f = tmp_path / "scalar.brdf"
    f.write_text("analytic\n::begin shader\nfloat BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)"
                 "\n{ return 0.5; }\n::end shader\n")
    wi = np.array([[0.0, 0.0, 1.0], [0.0, 0.6, -0.8]])
    got = ev(f, {}, wi, wi[:1])
    assert got.shape == (2,) and got.tolist() == [0.5, 0.0]


# --------------------------------------------------------------------------- errors


@pytest.mark.parametrize("body,line,what", [
    ("return vec3(1.0)", 3, "expected ';'"),                     # missing semicolon
    ("float x = ;\nreturn vec3(x);", 2, "expected an expression"),
    ("return vec3(1.0);\n", 3, "missing '}'"),                   # unbalanced brace (below)
    ("return vec3(foo(1.0));", 2, "unknown function 'foo'"),
    ("return vec3(q);", 2, "unknown name 'q'"),
    ("float x = vec3(1.0);\nreturn vec3(x);", 2, "type error"),
    ("return 1.0 + true;", 2, "type error"),
    ("return vec3(pow(1.0));", 2, "'pow' takes 2 arguments"),
    ("for (int i = 0; i < 3; i++) {}\nreturn vec3(0.0);", 2, "loops ('for')"),
    ("while (true) {}\nreturn vec3(0.0);", 2, "loops ('while')"),
    ("int i = 0;\nreturn vec3(0.0);", 2, "type 'int'"),
    ("vec4 c = vec4(1.0);\nreturn c.rgb;", 2, "type 'vec4'"),
    ("float i = k;\nvec3 v = vec3(1.0);\nreturn vec3(v[i]);", 4, "not a constant"),
    ("return vec3(1.0).xy;", 2, "swizzle '.xy'"),
    ("k = 1.0;\nreturn vec3(k);", 2, "cannot assign to 'k'"),
    ("return vec3(1.0 % 2.0);", 2, "operator '%'"),
    ("discard;", 2, "'discard'"),
    ("return vec3(1.0) @ 2;", 2, "unexpected character '@'"),
])
def test_glsl_errors_name_line_and_construct(tmp_path, body, line, what):
    text = shader_file(body)
    if "missing '}'" in what:
        text = text.replace("\n}\n::end shader", "\n::end shader")
    msg = shader_error(tmp_path, text)
    assert what in msg, msg
    assert f"bad.brdf:{FIRST_SHADER_LINE + line}:" in msg, msg


def test_recursion_is_rejected(tmp_path):
    helpers = "float f(float x);\nfloat g(float x) { return f(x); }\n" \
              "float f(float x) { return g(x) + 1.0; }"
    msg = shader_error(tmp_path, shader_file("return vec3(f(1.0));", helpers))
    assert "recursion (f → g → f)" in msg or "recursion (g → f → g)" in msg, msg


def test_no_brdf_function_and_preprocessor_lines(tmp_path):
    msg = shader_error(tmp_path, HEAD + "float h(float x) { return x; }\n::end shader\n")
    assert "no function 'vec3 BRDF(" in msg
    # BRDF Explorer drops '#' lines in every section, so #define never reaches the shader
    text = HEAD + "#define TWO 2.0\n" + "vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)\n" \
                                        "{ return vec3(TWO); }\n::end shader\n"
    assert "unknown name 'TWO'" in shader_error(tmp_path, text)
