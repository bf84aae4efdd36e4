"""The built-in functions of the GLSL subset: their names and signatures as tables (a
template of the generated code for the component-wise ones), and :func:`builtin`, which
type-checks one call and emits it (constants folded)."""

from __future__ import annotations

import math

import numpy as np

from tuibrdf.core.formats.glsl.emitter import Ctx, Emitter, Value, _py
from tuibrdf.core.formats.glsl.errors import GlslError
from tuibrdf.core.numerics import shader_errstate

#: one-argument component-wise built-ins: GLSL name → runtime expression template
UNARY_BUILTINS = {
    "sqrt": "_sqrt({})", "inversesqrt": "_isqrt({})", "exp": "np.exp({})",
    "exp2": "np.exp2({})", "log": "_log({})", "log2": "_log2({})", "sin": "np.sin({})",
    "cos": "np.cos({})", "tan": "np.tan({})", "asin": "_asin({})", "acos": "_acos({})",
    "sinh": "np.sinh({})", "cosh": "np.cosh({})", "tanh": "np.tanh({})",
    "abs": "np.abs({})", "sign": "_sign({})", "floor": "np.floor({})", "ceil": "np.ceil({})",
    "fract": "_fract({})", "radians": "({} * 0.017453292519943295)",
    "degrees": "({} * 57.29577951308232)",
}
#: the one-argument built-ins computed at compile time on a constant component: the
#: runtime's own numpy functions on a float64 under the shader's IEEE errstate, so a folded
#: value is the one the runtime computes (exp(1000) → inf, floor(nan) → nan, sin(inf) → nan)
_FOLD_UNARY = {
    "sqrt": lambda x: np.sqrt(max(x, 0.0)), "exp": np.exp, "sin": np.sin,
    "cos": np.cos, "abs": np.abs, "floor": np.floor, "ceil": np.ceil,
    "radians": lambda x: x * 0.017453292519943295, "degrees": lambda x: x * 57.29577951308232,
}


def fold_unary(name: str, x: float) -> float:
    """``name(x)`` of a constant, as the runtime computes it."""
    with shader_errstate():
        return float(_FOLD_UNARY[name](np.float64(x)))
#: component-wise built-ins with 2 or 3 arguments (a float may stand for a vec3 where GLSL
#: allows it: min/max/clamp/mix/step/smoothstep/mod/pow per component)
NARY_BUILTINS = {
    "pow": (2, "_pow({}, {})"), "min": (2, "np.minimum({}, {})"),
    "max": (2, "np.maximum({}, {})"), "mod": (2, "_mod({}, {})"),
    "step": (2, "_step({}, {})"), "atan2": (2, "np.arctan2({}, {})"),
    "clamp": (3, "np.minimum(np.maximum({}, {}), {})"),
    "mix": (3, "(({0}) * (1.0 - ({2})) + ({1}) * ({2}))"),
    "smoothstep": (3, "_smooth({}, {}, {})"),
}
#: the geometric built-ins: GLSL name → argument types
GEOMETRIC = {"dot": ("vec3", "vec3"), "cross": ("vec3", "vec3"), "length": ("vec3",),
             "distance": ("vec3", "vec3"), "normalize": ("vec3",),
             "reflect": ("vec3", "vec3"), "faceforward": ("vec3", "vec3", "vec3")}
#: every built-in function and constructor
BUILTIN_NAMES = set(UNARY_BUILTINS) | set(NARY_BUILTINS) | set(GEOMETRIC) | {
    "atan", "vec3", "float", "bool"}


def builtin(em: Emitter, name: str, vals: list[Value], line: int, ctx: Ctx) -> Value:
    """The call ``name(vals)`` of a built-in, type-checked against its GLSL overloads and
    emitted into ``ctx`` by ``em`` (constants folded)."""
    types = tuple(v.type for v in vals)
    sig = f"{name}({', '.join(types)})"
    if name not in BUILTIN_NAMES:
        raise GlslError(f"unknown function '{name}'", line)
    if any(t in ("bool", "void") for t in types) and name not in ("bool", "float"):
        raise GlslError(f"type error: no built-in {sig}", line)
    if name == "vec3":
        if types == ("float",):
            return Value("vec3", vals[0].comps * 3)
        if types == ("vec3",):
            return vals[0]
        if types == ("float",) * 3:
            return Value("vec3", [v.comps[0] for v in vals])
        raise GlslError(f"type error: no constructor {sig} (vec3(float), "
                        "vec3(float, float, float), vec3(vec3))", line)
    if name == "float":
        if types == ("float",):
            return vals[0]
        if types == ("bool",):
            c = vals[0].comps[0]
            return Value("float", [float(c) if not isinstance(c, str)
                                   else em.tmp(ctx, f"np.where({c}, 1.0, 0.0) + 0.0")])
        raise GlslError(f"type error: no constructor {sig}", line)
    if name == "bool":
        if types == ("bool",):
            return vals[0]
        if types == ("float",):
            c = vals[0].comps[0]
            return Value("bool", [c != 0.0 if not isinstance(c, str)
                                  else em.tmp(ctx, f"np.not_equal({c}, 0.0)")])
        raise GlslError(f"type error: no constructor {sig}", line)
    if name in UNARY_BUILTINS:
        if len(vals) != 1:
            raise GlslError(f"'{name}' takes 1 argument, not {len(vals)}", line)
        out = []
        for c in vals[0].comps:
            if not isinstance(c, str) and name in _FOLD_UNARY:
                out.append(fold_unary(name, c))
            else:
                out.append(em.tmp(ctx, UNARY_BUILTINS[name].format(_py(c))))
        return Value(vals[0].type, out)
    if name == "atan":
        if len(vals) == 1:
            return Value(vals[0].type, [em.tmp(ctx, f"np.arctan({_py(c)})")
                                        for c in vals[0].comps])
        name = "atan2"
    if name in NARY_BUILTINS:
        n, template = NARY_BUILTINS[name]
        if len(vals) != n:
            raise GlslError(f"'{name}' takes {n} arguments, not {len(vals)}", line)
        ty = "vec3" if "vec3" in types else "float"
        if ty == "vec3" and not broadcast_ok(name, types):
            raise GlslError(f"type error: no built-in {sig}", line)
        cols = [v.comps * 3 if (ty == "vec3" and v.type == "float") else v.comps
                for v in vals]
        out = []
        for k in range(3 if ty == "vec3" else 1):
            args = [col[k] for col in cols]
            if all(not isinstance(a, str) for a in args) and name in ("min", "max",
                                                                      "clamp", "mix"):
                out.append(fold_nary(name, args))
            else:
                out.append(em.tmp(ctx, template.format(*(_py(a) for a in args))))
        return Value(ty, out)
    # geometric
    want = GEOMETRIC[name]
    if types != want:
        if name in ("length", "normalize") and types == ("float",):
            c = vals[0].comps[0]
            code = f"np.abs({_py(c)})" if name == "length" else f"_sign({_py(c)})"
            return Value("float", [em.tmp(ctx, code)])
        raise GlslError(f"type error: no built-in {sig} (expects {name}"
                        f"({', '.join(want)}))", line)
    if name == "dot":
        return Value("float", [em.dot(vals[0].comps, vals[1].comps)])
    if name == "cross":
        a, b = vals[0].comps, vals[1].comps
        out = []
        for i, j in ((1, 2), (2, 0), (0, 1)):
            out.append(em.scalar_op("-", em.scalar_op("*", a[i], b[j]),
                                    em.scalar_op("*", a[j], b[i])))
        return Value("vec3", out)
    if name in ("length", "distance"):
        v = vals[0].comps if name == "length" else \
            [em.scalar_op("-", x, y) for x, y in zip(vals[0].comps, vals[1].comps,
                                                       strict=True)]
        d = em.dot(v, v)
        return Value("float", [math.sqrt(d) if not isinstance(d, str)
                               else em.tmp(ctx, f"np.sqrt({d})")])
    if name == "normalize":
        v = vals[0].comps
        d = em.dot(v, v)
        if not isinstance(d, str):
            inv = 1.0 / math.sqrt(d) if d > 0 else 0.0
            return Value("vec3", [em.scalar_op("*", c, inv) for c in v])
        length = em.tmp(ctx, f"np.sqrt({d})")
        return Value("vec3", [em.scalar_op("/", c, length) for c in v])
    if name == "reflect":  # I - 2 dot(N, I) N
        i, n = vals[0].comps, vals[1].comps
        k = em.scalar_op("*", 2.0, em.dot(n, i))
        return Value("vec3", [em.scalar_op("-", a, em.scalar_op("*", k, b))
                              for a, b in zip(i, n, strict=True)])
    # faceforward(N, I, Nref) = dot(Nref, I) < 0 ? N : -N
    n, i, nref = (v.comps for v in vals)
    d = em.dot(nref, i)
    neg = [em.scalar_op("-", 0.0, c) for c in n]
    if not isinstance(d, str):
        return Value("vec3", n if d < 0 else neg)
    c = em.tmp(ctx, f"({d} < 0.0)")
    return Value("vec3", [em.tmp(ctx, f"_sel({c}, {_py(a)}, {_py(b)})")
                          for a, b in zip(n, neg, strict=True)])


def broadcast_ok(name: str, types: tuple) -> bool:
    """GLSL's genType overloads: which arguments may be a float when the result is vec3."""
    if all(t == "vec3" for t in types):
        return True
    if name in ("min", "max", "mod"):
        return types[0] == "vec3"
    if name == "clamp":
        return types[0] == "vec3" and types[1] == types[2]
    if name == "mix":
        return types[0] == types[1] == "vec3"
    if name == "step":
        return types[1] == "vec3"
    if name == "smoothstep":
        return types[2] == "vec3" and types[0] == types[1]
    return False


def fold_nary(name: str, a: list) -> float:
    """``min``, ``max``, ``clamp`` or ``mix`` of constant components, at compile time."""
    with shader_errstate():  # as the runtime: np.minimum/np.maximum propagate NaN
        if name == "min":
            return float(np.minimum(a[0], a[1]))
        if name == "max":
            return float(np.maximum(a[0], a[1]))
        if name == "clamp":
            return float(np.minimum(np.maximum(a[0], a[1]), a[2]))
        return float(np.float64(a[0]) * (1.0 - a[2]) + np.float64(a[1]) * a[2])
