"""Below the syntax tree: what the compiler works with and its primitives.

A :class:`Value` is a GLSL type and its components (1 or 3), each a compile-time constant
(a float or bool) or the name of a Python variable of the generated code; a :class:`Sym` a
declared name, :class:`FuncInfo` a function to compile (or its copy specialised for
constant arguments), :class:`Ctx` the function being compiled.  :class:`Emitter` makes
fresh names, emits lines and does the arithmetic of components, folding constants.
"""

from __future__ import annotations

import math
import operator
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from tuibrdf.core.formats.glsl.budgets import MAX_GENERATED_LINES
from tuibrdf.core.formats.glsl.errors import GlslError
from tuibrdf.core.formats.glsl.syntax import Func

Comp = Any  # float | bool (compile-time constant) or str (a Python name)
#: comparisons of two constants, folded as the runtime compares (IEEE: NaN compares false)
_COMPARE = {"<": operator.lt, ">": operator.gt, "<=": operator.le, ">=": operator.ge}


@dataclass
class Value:
    type: str  # float | vec3 | bool | void
    comps: list  # 1 or 3 components

    @property
    def const(self) -> bool:
        return all(not isinstance(c, str) for c in self.comps)


@dataclass
class Sym:
    type: str
    names: list  # Python names (1 or 3), or constant components
    depth: int  # branch depth of the declaration
    kind: str  # local | param | global | uniform
    const: bool = False


@dataclass
class FuncInfo:
    node: Func
    pyname: str
    sig: tuple
    #: parameter index → constant components: a copy specialised for constant arguments
    consts: dict = field(default_factory=dict)


@dataclass
class Ctx:
    func: FuncInfo
    lines: list = field(default_factory=list)
    indent: str = "        "
    scopes: list = field(default_factory=list)
    path: Comp = True  # lane mask of the current branch
    depth: int = 0
    done: bool = False  # a masked return happened before this point
    grey: bool = True  # every return so far had equal components (vec3(x))
    outs: list = field(default_factory=list)  # [(param name, Sym)]
    callees: list = field(default_factory=list)  # generated functions called, per call site


def _py(x: Comp) -> str:
    if isinstance(x, str):
        return x
    if isinstance(x, bool | np.bool_):
        return "True" if x else "False"
    if math.isinf(x) or math.isnan(x):
        return f"float('{x!r}')"
    return repr(float(x))


class Emitter:
    """Fresh names, emitted lines, and arithmetic on components with constants folded: the base
    of :class:`~tuibrdf.core.formats.glsl.compiler.Compiler`, and what the built-ins are
    emitted with (:func:`~tuibrdf.core.formats.glsl.builtins.builtin`)."""

    def __init__(self) -> None:
        self.counter = 0
        self.n_lines = 0  # lines emitted, all functions together (a budget)
        self.line = 1  # the shader's line being compiled (for the budget's error)

    # -- naming and emitting
    def fresh(self, stem: str = "t") -> str:
        self.counter += 1
        return f"_{stem}{self.counter}"

    def emit(self, ctx: Ctx, line: str) -> None:
        self.n_lines += 1
        if self.n_lines > MAX_GENERATED_LINES:
            raise GlslError(f"the shader is too large to translate: over "
                            f"{MAX_GENERATED_LINES:,} lines of generated code (budget; helpers "
                            "count once per set of constant arguments they are called with)",
                            self.line)
        ctx.lines.append(ctx.indent + line)

    def tmp(self, ctx: Ctx, code: str) -> str:
        name = self.fresh()
        self.emit(ctx, f"{name} = {code}")
        return name

    # -- values
    def zero(self, ty: str) -> Value:
        if ty == "vec3":
            return Value("vec3", [0.0, 0.0, 0.0])
        return Value(ty, [False] if ty == "bool" else [0.0])

    def convert(self, v: Value, ty: str, line: int, what: str) -> Value:
        if v.type == ty:
            return v
        raise GlslError(f"type error: {what} is {ty} but the value is {v.type}", line)

    def arith(self, op: str, a: Value, b: Value, line: int) -> Value:
        if a.type not in ("float", "vec3") or b.type not in ("float", "vec3"):
            raise GlslError(f"type error: '{op}' between {a.type} and {b.type}", line)
        ty = "vec3" if "vec3" in (a.type, b.type) else "float"
        n = 3 if ty == "vec3" else 1
        xs = a.comps * 3 if len(a.comps) < n else a.comps
        ys = b.comps * 3 if len(b.comps) < n else b.comps
        return Value(ty, [self.scalar_op(op, x, y) for x, y in zip(xs, ys, strict=True)])

    def scalar_op(self, op: str, x: Comp, y: Comp) -> Comp:
        cx, cy = not isinstance(x, str), not isinstance(y, str)
        if cx and cy:
            if op == "+":
                return x + y
            if op == "-":
                return x - y
            if op == "*":
                return x * y
            return x / y if y != 0 else 0.0
        if op == "+":
            if cx and x == 0.0:
                return y
            if cy and y == 0.0:
                return x
        if op == "-" and cy and y == 0.0:
            return x
        if op == "*":
            if (cx and x == 0.0) or (cy and y == 0.0):
                return 0.0  # also where the other factor is inf/NaN: those lanes are masked
            if cx and x == 1.0:
                return y
            if cy and y == 1.0:
                return x
        if op == "/":
            if cy and y != 0.0:
                return self._emit_tmp(f"{_py(x)} / {_py(y)}")
            if cy:
                return 0.0
            return self._emit_tmp(f"_div({_py(x)}, {_py(y)})")
        return self._emit_tmp(f"{_py(x)} {op} {_py(y)}")

    # scalar_op is called from arith, which has no ctx argument: the current context is kept
    # here while a function body is compiled
    _cur_ctx: Ctx | None = None

    def _emit_tmp(self, code: str) -> str:
        assert self._cur_ctx is not None
        return self.tmp(self._cur_ctx, code)

    def dot(self, a: list, b: list) -> Comp:
        acc: Comp = 0.0
        for x, y in zip(a, b, strict=True):
            acc = self.scalar_op("+", acc, self.scalar_op("*", x, y))
        return acc
