"""A compiler from the GLSL subset of BRDF Explorer shaders to vectorised numpy.

BRDF Explorer (Disney, github.com/wdas/brdf) pastes a ``.brdf`` file's shader section into a
fragment-shader template and calls ``vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)``.
This module parses that shader (tokenizer + recursive descent) and generates Python source
that evaluates ``BRDF`` on whole arrays of directions at once: no per-direction loop.

Representation.  A ``float`` is a Python float or an ndarray of shape ``(...)``; a ``vec3`` is
three of those (one per component, "structure of arrays"); a ``bool`` is a Python bool or a
bool array.  Compile-time constants are folded (literals, ``const`` globals, and ``N``, ``X``,
``Y`` inside ``BRDF``: ``dot(N, L)`` compiles to ``L.z``).

Control flow.  Every statement runs on every direction ("lanes", as on a GPU).  An ``if``
whose condition varies per direction compiles its branches with a lane mask: an assignment in
a branch becomes ``x = where(mask, new, x)``; a ``return`` in a branch records the value for
the masked lanes and marks them done, and the function's result is the recorded value where
done.  A uniform condition (a parameter) selects without ``where``.  Ternaries select the same
way.  Both sides of a branch are evaluated, so their arithmetic may divide by zero on lanes
that do not use the result: the shader runs under IEEE semantics (no FP exception), see
:func:`tuibrdf.core.numerics.shader_errstate`.

Semantics where GLSL leaves the result undefined (documented in docs/reference/formats.md):

* ``x / 0`` → 0 (a GPU gives ±inf or NaN);
* ``pow(x, y)`` → 0 for ``x < 0``, and for ``x = 0`` with ``y ≤ 0``;
* ``sqrt(x)``, ``inversesqrt(x)`` of ``x < 0`` → as of 0 (``inversesqrt(0)`` → 0);
* ``log(x)``, ``log2(x)`` for ``x ≤ 0`` → 0;
* ``asin(x)``, ``acos(x)`` clamp ``x`` to [-1, 1];
* ``normalize(0)`` → 0; ``atan(0, 0)`` → 0; ``smoothstep`` with ``edge0 = edge1`` → ``step``;
* a variable declared without a value starts at 0; a function that ends without ``return``
  returns 0;
* overflow gives ±inf as in IEEE arithmetic; the model makes the final value finite (see
  :mod:`tuibrdf.core.formats.brdf_explorer`).

Not supported (one error naming the file, line and construct): loops (``for``, ``while``,
``do``), ``break``/``continue``/``discard``/``switch``, recursion, ``int``/``vec2``/``vec4``/
matrix/struct types, arrays, dynamic indexing, ``uniform``/``varying`` declarations, bitwise
and ``%`` operators, assignments inside expressions, and calls with ``out`` arguments inside
``?:``.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from typing import Any

import numpy as np

# --------------------------------------------------------------------------- errors


class GlslError(ValueError):
    """A construct outside the supported subset, or a syntax/type error; ``line`` is the line
    in the file (1-based), ``construct`` the offending text."""

    def __init__(self, message: str, line: int):
        super().__init__(message)
        self.line = line
        self.message = message


# --------------------------------------------------------------------------- tokenizer

_TOKEN = re.compile(r"""
    (?P<ws>[ \t\r\f\v]+)
  | (?P<nl>\n)
  | (?P<lcomment>//[^\n]*)
  | (?P<bcomment>/\*.*?\*/)
  | (?P<open_comment>/\*)
  | (?P<num>(?:\d+\.\d*|\.\d+|\d+)(?:[eE][+-]?\d+)?[fF]?)
  | (?P<ident>[A-Za-z_][A-Za-z_0-9]*)
  | (?P<op>\+\+|--|\+=|-=|\*=|/=|%=|==|!=|<=|>=|&&|\|\||\^\^|<<|>>|[-+*/%<>=!?:;,(){}\[\].&|^~])
""", re.VERBOSE | re.DOTALL)


@dataclass(frozen=True)
class Tok:
    kind: str  # num | ident | op | eof
    text: str
    line: int


def tokenize(src: str, first_line: int = 1) -> list[Tok]:
    """Tokens of ``src``; line numbers start at ``first_line``."""
    out: list[Tok] = []
    line = first_line
    pos = 0
    n = len(src)
    while pos < n:
        m = _TOKEN.match(src, pos)
        if m is None:
            ch = src[pos]
            what = "a preprocessor directive ('#')" if ch == "#" else f"character {ch!r}"
            raise GlslError(f"unexpected {what}", line)
        kind = m.lastgroup
        text = m.group()
        if kind == "open_comment":
            raise GlslError("unterminated /* comment", line)
        if kind in ("num", "ident", "op"):
            if kind == "num" and text[-1] in "fF":
                text = text[:-1]
            out.append(Tok(kind, text, line))
        line += text.count("\n") if kind in ("nl", "bcomment") else 0
        pos = m.end()
    out.append(Tok("eof", "end of shader", line))
    return out


# --------------------------------------------------------------------------- syntax tree

@dataclass
class Node:
    line: int


@dataclass
class Num(Node):
    value: float


@dataclass
class BoolLit(Node):
    value: bool


@dataclass
class Var(Node):
    name: str


@dataclass
class Call(Node):
    name: str
    args: list


@dataclass
class Unary(Node):
    op: str
    operand: Any


@dataclass
class Binary(Node):
    op: str
    left: Any
    right: Any


@dataclass
class Ternary(Node):
    cond: Any
    then: Any
    other: Any


@dataclass
class Index(Node):
    base: Any
    index: Any


@dataclass
class Swizzle(Node):
    base: Any
    comps: str


@dataclass
class Decl(Node):
    type: str
    const: bool
    items: list  # [(name, expr | None, line)]


@dataclass
class Assign(Node):
    target: Any
    op: str
    value: Any


@dataclass
class ExprStmt(Node):
    expr: Any


@dataclass
class If(Node):
    cond: Any
    then: Any
    other: Any


@dataclass
class Return(Node):
    value: Any


@dataclass
class Block(Node):
    stmts: list


@dataclass
class Func(Node):
    ret: str
    name: str
    params: list  # [(qualifier, type, name)]
    body: Block | None


TYPES = ("float", "vec3", "bool", "void")
UNSUPPORTED_TYPES = {
    "int": "type 'int'", "uint": "type 'uint'", "double": "type 'double'",
    "vec2": "type 'vec2'", "vec4": "type 'vec4'", "ivec2": "type 'ivec2'",
    "ivec3": "type 'ivec3'", "ivec4": "type 'ivec4'", "bvec2": "type 'bvec2'",
    "bvec3": "type 'bvec3'", "bvec4": "type 'bvec4'", "mat2": "matrix type 'mat2'",
    "mat3": "matrix type 'mat3'", "mat4": "matrix type 'mat4'", "struct": "'struct'",
    "sampler2D": "textures ('sampler2D')", "samplerCube": "textures ('samplerCube')",
}
UNSUPPORTED_STATEMENTS = {
    "for": "loops ('for')", "while": "loops ('while')", "do": "loops ('do')",
    "break": "'break'", "continue": "'continue'", "discard": "'discard'",
    "switch": "'switch'", "case": "'switch'", "default": "'switch'",
}
QUALIFIERS_REJECTED = {
    "uniform": "'uniform' declarations (parameters come from the ::begin parameters block)",
    "varying": "'varying' declarations", "attribute": "'attribute' declarations",
    "in": "global 'in' declarations", "out": "global 'out' declarations",
    "precision": "'precision' statements", "layout": "'layout' qualifiers",
}
SWIZZLE_SETS = ("xyz", "rgb", "stp")


class Parser:
    """Recursive descent over the token list; every node carries its line."""

    def __init__(self, toks: list[Tok]):
        self.toks = toks
        self.i = 0

    # -- helpers
    @property
    def tok(self) -> Tok:
        return self.toks[self.i]

    def peek(self, k: int = 1) -> Tok:
        return self.toks[min(self.i + k, len(self.toks) - 1)]

    def next(self) -> Tok:
        t = self.toks[self.i]
        if t.kind != "eof":
            self.i += 1
        return t

    def at(self, text: str) -> bool:
        return self.tok.kind != "eof" and self.tok.text == text

    def accept(self, text: str) -> bool:
        if self.at(text):
            self.next()
            return True
        return False

    def expect(self, text: str, what: str = "") -> Tok:
        if not self.at(text):
            raise GlslError(f"expected '{text}'{what} but found '{self.tok.text}'", self.tok.line)
        return self.next()

    def ident(self, what: str) -> Tok:
        t = self.tok
        if t.kind != "ident":
            raise GlslError(f"expected {what} but found '{t.text}'", t.line)
        return self.next()

    def type_name(self, allow_void: bool = False) -> Tok:
        t = self.tok
        if t.kind == "ident" and t.text in UNSUPPORTED_TYPES:
            raise GlslError(f"unsupported construct: {UNSUPPORTED_TYPES[t.text]} "
                            "(supported types: float, vec3, bool)", t.line)
        if t.kind != "ident" or t.text not in TYPES or (t.text == "void" and not allow_void):
            raise GlslError(f"expected a type (float, vec3, bool) but found '{t.text}'", t.line)
        return self.next()

    # -- top level
    def program(self) -> tuple[list[Decl], list[Func]]:
        globs: list[Decl] = []
        funcs: list[Func] = []
        while self.tok.kind != "eof":
            t = self.tok
            if t.text in QUALIFIERS_REJECTED:
                raise GlslError(f"unsupported construct: {QUALIFIERS_REJECTED[t.text]}", t.line)
            if t.text == ";":
                self.next()
                continue
            const = self.accept("const")
            ty = self.type_name(allow_void=not const)
            name = self.ident("a name")
            if self.at("(") and not const:
                funcs.append(self.function(ty, name))
            else:
                if ty.text == "void":
                    raise GlslError("a variable cannot have type void", ty.line)
                globs.append(self.declaration_rest(ty.text, const, name))
        return globs, funcs

    def function(self, ty: Tok, name: Tok) -> Func:
        self.expect("(")
        params = []
        if self.at("void") and self.peek().text == ")":
            self.next()
        while not self.at(")"):
            qual = "in"
            if self.tok.text in ("in", "out", "inout", "const"):
                qual = self.next().text
                if qual == "const":
                    qual = "in"
                if self.tok.text in ("in", "out", "inout"):
                    qual = self.next().text
            pty = self.type_name()
            pname = self.ident("a parameter name")
            if self.at("["):
                raise GlslError("unsupported construct: array parameters", self.tok.line)
            params.append((qual, pty.text, pname.text))
            if not self.accept(","):
                break
        self.expect(")", f" to close the parameters of '{name.text}'")
        if self.accept(";"):
            return Func(name.line, ty.text, name.text, params, None)  # a prototype
        if not self.at("{"):
            raise GlslError(f"expected '{{' to open the body of '{name.text}' but found "
                            f"'{self.tok.text}'", self.tok.line)
        return Func(name.line, ty.text, name.text, params, self.block())

    def declaration_rest(self, ty: str, const: bool, first: Tok) -> Decl:
        items = []
        name = first
        while True:
            if self.at("["):
                raise GlslError("unsupported construct: arrays", self.tok.line)
            init = None
            if self.accept("="):
                init = self.ternary()
            elif const:
                raise GlslError(f"const '{name.text}' needs a value", name.line)
            items.append((name.text, init, name.line))
            if not self.accept(","):
                break
            name = self.ident("a variable name")
        self.expect(";", " after the declaration")
        return Decl(first.line, ty, const, items)

    # -- statements
    def block(self) -> Block:
        start = self.expect("{")
        stmts = []
        while not self.at("}"):
            if self.tok.kind == "eof":
                raise GlslError(f"missing '}}' for the block opened on line {start.line}",
                                self.tok.line)
            stmts.append(self.statement())
        self.next()
        return Block(start.line, stmts)

    def statement(self):
        t = self.tok
        if t.kind == "ident" and t.text in UNSUPPORTED_STATEMENTS:
            raise GlslError(f"unsupported construct: {UNSUPPORTED_STATEMENTS[t.text]}", t.line)
        if t.text == "{":
            return self.block()
        if t.text == ";":
            self.next()
            return Block(t.line, [])
        if t.text == "if":
            self.next()
            self.expect("(", " after 'if'")
            cond = self.expression()
            self.expect(")", " to close the 'if' condition")
            then = self.statement()
            other = self.statement() if self.accept("else") else None
            return If(t.line, cond, then, other)
        if t.text == "return":
            self.next()
            value = None if self.at(";") else self.expression()
            self.expect(";", " after 'return'")
            return Return(t.line, value)
        if t.kind == "ident" and t.text in UNSUPPORTED_TYPES:
            self.type_name()  # raises
        if t.text == "const" or (t.kind == "ident" and t.text in TYPES and t.text != "void"
                                 and self.peek().kind == "ident"):
            const = self.accept("const")
            ty = self.type_name()
            name = self.ident("a variable name")
            return self.declaration_rest(ty.text, const, name)
        if t.text in ("++", "--"):
            self.next()
            target = self.unary()
            self.expect(";")
            return Assign(t.line, target, "+=" if t.text == "++" else "-=", Num(t.line, 1.0))
        expr = self.expression()
        if self.tok.text in ("=", "+=", "-=", "*=", "/="):
            op = self.next().text
            value = self.expression()
            if self.tok.text in ("=", "+=", "-=", "*=", "/="):
                raise GlslError("unsupported construct: chained assignment", self.tok.line)
            self.expect(";", " after the assignment")
            return Assign(t.line, expr, op, value)
        if self.tok.text == "%=":
            raise GlslError("unsupported construct: '%=' (integer operator)", self.tok.line)
        if self.tok.text in ("++", "--"):
            op = self.next().text
            self.expect(";")
            return Assign(t.line, expr, "+=" if op == "++" else "-=", Num(t.line, 1.0))
        self.expect(";", " after the expression")
        return ExprStmt(t.line, expr)

    # -- expressions (GLSL precedence, lowest first)
    def expression(self):
        e = self.ternary()
        if self.at(","):
            raise GlslError("unsupported construct: the comma operator", self.tok.line)
        return e

    def ternary(self):
        cond = self.binary(0)
        if self.at("?"):
            t = self.next()
            then = self.ternary()
            self.expect(":", " in the ?: expression")
            other = self.ternary()
            return Ternary(t.line, cond, then, other)
        return cond

    LEVELS = (("||",), ("^^",), ("&&",), ("|",), ("^",), ("&",), ("==", "!="),
              ("<", ">", "<=", ">="), ("<<", ">>"), ("+", "-"), ("*", "/", "%"))

    def binary(self, level: int):
        if level == len(self.LEVELS):
            return self.unary()
        left = self.binary(level + 1)
        while self.tok.kind == "op" and self.tok.text in self.LEVELS[level]:
            t = self.next()
            if t.text in ("|", "^", "&", "<<", ">>", "%"):
                raise GlslError(f"unsupported construct: operator '{t.text}' (integer/bitwise)",
                                t.line)
            right = self.binary(level + 1)
            left = Binary(t.line, t.text, left, right)
        return left

    def unary(self):
        t = self.tok
        if t.text in ("-", "+", "!"):
            self.next()
            return Unary(t.line, t.text, self.unary())
        if t.text == "~":
            raise GlslError("unsupported construct: operator '~' (bitwise)", t.line)
        if t.text in ("++", "--"):
            raise GlslError(f"unsupported construct: '{t.text}' inside an expression "
                            "(use it as a statement)", t.line)
        return self.postfix()

    def postfix(self):
        e = self.primary()
        while True:
            t = self.tok
            if t.text == "[":
                self.next()
                idx = self.expression()
                self.expect("]")
                e = Index(t.line, e, idx)
            elif t.text == ".":
                self.next()
                comps = self.ident("a component name after '.'")
                e = Swizzle(t.line, e, comps.text)
            elif t.text in ("++", "--"):
                if self.peek().text == ";":
                    return e  # statement-level x++ (handled by statement())
                raise GlslError(f"unsupported construct: '{t.text}' inside an expression "
                                "(use it as a statement)", t.line)
            else:
                return e

    def primary(self):
        t = self.tok
        if t.kind == "num":
            self.next()
            try:
                return Num(t.line, float(t.text))
            except ValueError:
                raise GlslError(f"bad number '{t.text}'", t.line) from None
        if t.kind == "ident":
            if t.text in ("true", "false"):
                self.next()
                return BoolLit(t.line, t.text == "true")
            if t.text in UNSUPPORTED_TYPES:
                self.type_name()  # raises
            if t.text in UNSUPPORTED_STATEMENTS or t.text in ("if", "return", "else", "const"):
                raise GlslError(f"expected an expression but found '{t.text}'", t.line)
            self.next()
            if self.at("("):
                self.next()
                args = []
                if self.at("void") and self.peek().text == ")":
                    self.next()
                while not self.at(")"):
                    args.append(self.ternary())
                    if not self.accept(","):
                        break
                self.expect(")", f" to close the call of '{t.text}'")
                return Call(t.line, t.text, args)
            return Var(t.line, t.text)
        if t.text == "(":
            self.next()
            e = self.expression()
            self.expect(")")
            return e
        raise GlslError(f"expected an expression but found '{t.text}'", t.line)


def parse(src: str, first_line: int = 1) -> tuple[list[Decl], list[Func]]:
    return Parser(tokenize(src, first_line)).program()


# --------------------------------------------------------------------------- runtime helpers
# Called by the generated code; each is vectorised and takes scalars or arrays.


def _zeros_like(*xs):
    shape = np.broadcast_shapes(*(np.shape(x) for x in xs))
    return np.zeros(shape) if shape else 0.0


def rt_div(a, b):
    """``a / b``, 0 where ``b == 0`` (GLSL leaves it undefined; a GPU gives ±inf/NaN)."""
    if np.ndim(b) == 0:
        return a / b if b != 0 else _zeros_like(a)
    out = np.zeros(np.broadcast_shapes(np.shape(a), np.shape(b)))
    np.divide(a, b, out=out, where=b != 0)
    return out


def rt_sel(c, a, b):
    """``c ? a : b`` lane by lane; a uniform (scalar) condition picks without ``where``."""
    if np.ndim(c) == 0:
        return a if c else b
    return np.where(c, a, b)


def rt_sqrt(x):
    return np.sqrt(np.maximum(x, 0.0))  # sqrt of x < 0 is undefined in GLSL: as of 0


def rt_inversesqrt(x):
    return rt_div(1.0, rt_sqrt(x))


def rt_pow(x, y):
    """``x^y`` for ``x > 0``, else 0 (GLSL: undefined for x < 0, and for x = 0, y ≤ 0).
    Lanes with ``x ≤ 0`` may compute NaN/inf before being replaced (shader errstate)."""
    pos = np.greater(x, 0.0)
    if np.ndim(pos) == 0 and np.ndim(y) == 0:
        return np.power(np.float64(x), y) if pos else 0.0
    if np.ndim(y) == 0 and y in (2.0, 3.0, 4.0, 5.0):  # small integer powers: products
        p = x * x
        if y >= 4.0:
            p = p * p
        if y in (3.0, 5.0):
            p = p * x
        return np.where(pos, p, 0.0)
    return np.where(pos, np.power(x, y), 0.0)


def rt_log(x, fn=np.log):
    pos = np.greater(x, 0.0)  # log of x ≤ 0 is undefined in GLSL: 0
    if np.ndim(pos) == 0:
        return fn(np.float64(x)) if pos else 0.0
    return np.where(pos, fn(np.where(pos, x, 1.0)), 0.0)


def rt_log2(x):
    return rt_log(x, np.log2)


def rt_asin(x):
    return np.arcsin(np.clip(x, -1.0, 1.0))  # |x| > 1 is undefined in GLSL: clamped


def rt_acos(x):
    return np.arccos(np.clip(x, -1.0, 1.0))


def rt_fract(x):
    return x - np.floor(x)


def rt_mod(x, y):
    return x - y * np.floor(rt_div(x, y))


def rt_step(edge, x):
    return np.where(np.less(x, edge), 0.0, 1.0) + 0.0


def rt_smoothstep(e0, e1, x):
    t = np.clip(rt_div(np.subtract(x, e0), np.subtract(e1, e0)), 0.0, 1.0)
    same = np.equal(e0, e1)  # undefined in GLSL: a step at the edge
    return np.where(same, rt_step(e0, x), t * t * (3.0 - 2.0 * t)) + 0.0


def rt_sign(x):
    return np.sign(x) + 0.0


def rt_and(a, b):
    return np.logical_and(a, b)


def rt_or(a, b):
    return np.logical_or(a, b)


def rt_xor(a, b):
    return np.logical_xor(a, b)


def rt_not(a):
    return np.logical_not(a)


RUNTIME = {
    "np": np, "_div": rt_div, "_sel": rt_sel, "_sqrt": rt_sqrt, "_isqrt": rt_inversesqrt,
    "_pow": rt_pow, "_log": rt_log, "_log2": rt_log2, "_asin": rt_asin, "_acos": rt_acos,
    "_fract": rt_fract, "_mod": rt_mod, "_step": rt_step, "_smooth": rt_smoothstep,
    "_sign": rt_sign, "_and": rt_and, "_or": rt_or, "_xor": rt_xor, "_not": rt_not,
}

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
_FOLD_UNARY = {
    "sqrt": lambda x: math.sqrt(max(x, 0.0)), "exp": math.exp, "sin": math.sin,
    "cos": math.cos, "abs": abs, "floor": math.floor, "ceil": math.ceil,
    "radians": math.radians, "degrees": math.degrees,
}
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
GEOMETRIC = ("dot", "cross", "length", "distance", "normalize", "reflect", "faceforward")
BUILTIN_NAMES = set(UNARY_BUILTINS) | set(NARY_BUILTINS) | set(GEOMETRIC) | {
    "atan", "vec3", "float", "bool"}
RESERVED = set(TYPES) | set(UNSUPPORTED_TYPES) | {
    "if", "else", "return", "const", "true", "false", "in", "out", "inout", "uniform",
    "for", "while", "do", "break", "continue", "discard", "struct", "switch"}


# --------------------------------------------------------------------------- code generation

Comp = Any  # float | bool (compile-time constant) or str (a Python name)


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


def _py(x: Comp) -> str:
    if isinstance(x, str):
        return x
    if isinstance(x, bool | np.bool_):
        return "True" if x else "False"
    if math.isinf(x) or math.isnan(x):
        return f"float('{x!r}')"
    return repr(float(x))


class Compiler:
    """Type-checks the syntax tree and emits the Python source of one kernel function."""

    def __init__(self, globs: list[Decl], funcs: list[Func], uniforms: dict[str, str]):
        self.globs = globs
        self.uniforms = uniforms  # GLSL name → type (float, vec3, bool)
        self.counter = 0
        self.funcs: dict[str, list[FuncInfo]] = {}
        self.global_scope: dict[str, Sym] = {}
        self.prologue: list[str] = []
        for f in funcs:
            self.add_function(f)
        #: specialised copies of functions (constant arguments folded), by key, and those
        #: still to be compiled
        self.specials: dict[tuple, FuncInfo] = {}
        self.pending: list[FuncInfo] = []
        self._assigned: dict[int, set[str]] = {}
        #: user functions with out/inout parameters (their arguments may be assigned)
        self.out_funcs = {f.name for f in funcs
                          if any(q in ("out", "inout") for q, _, _ in f.params)}

    # -- naming
    def fresh(self, stem: str = "t") -> str:
        self.counter += 1
        return f"_{stem}{self.counter}"

    def add_function(self, f: Func) -> None:
        if f.name in RESERVED:
            raise GlslError(f"'{f.name}' is a reserved word and cannot name a function", f.line)
        if f.name in self.uniforms:
            raise GlslError(f"function '{f.name}' has the name of a parameter", f.line)
        sig = tuple(t for _, t, _ in f.params)
        infos = self.funcs.setdefault(f.name, [])
        for info in infos:
            if info.sig == sig:
                if info.node.body is None and f.body is not None:
                    info.node = f
                    return
                if f.body is None:
                    return
                raise GlslError(f"function '{f.name}({', '.join(sig)})' is defined twice "
                                f"(first on line {info.node.line})", f.line)
        infos.append(FuncInfo(f, self.fresh("f_" + f.name + "_"), sig))

    # -- entry
    def compile(self) -> tuple[str, str]:
        """``(source, return type)``: the source defines ``_shader(L, V, **uniforms)``."""
        brdf = [i for i in self.funcs.get("BRDF", []) if i.node.body is not None]
        if not brdf:
            raise GlslError("no function 'vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)' "
                            "in the shader", 1)
        entry = brdf[0]
        if entry.sig != ("vec3",) * 5 or entry.node.ret not in ("vec3", "float"):
            raise GlslError("BRDF must be 'vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)'",
                            entry.node.line)
        for infos in self.funcs.values():
            for info in infos:
                if info.node.body is None:
                    raise GlslError(f"function '{info.node.name}' is declared but never "
                                    "defined", info.node.line)
        self.check_recursion()
        for name, ty in self.uniforms.items():
            self.global_scope[name] = Sym(ty, [f"u_{name}_{k}" for k in range(3)]
                                          if ty == "vec3" else [f"u_{name}"], 0, "uniform")
        for d in self.globs:
            self.global_decl(d)
        bodies = []
        for infos in self.funcs.values():
            for info in infos:
                bodies.extend(self.function(info, entry=info is entry))
        while self.pending:  # copies specialised for constant arguments, found on the way
            bodies.extend(self.function(self.pending.pop(), entry=False))
        args = ", ".join(f"u_{n}" for n in self.uniforms)
        src = ["def _shader(L, V" + (", " + args if args else "") + "):"]
        for name, ty in self.uniforms.items():
            if ty == "vec3":
                src.append(f"    u_{name}_0, u_{name}_1, u_{name}_2 = u_{name}")
        src += ["    " + s for s in self.prologue]
        src += bodies
        src.append(f"    return {entry.pyname}(L, V)")
        return "\n".join(src) + "\n", entry.node.ret

    def check_recursion(self) -> None:
        calls: dict[str, set[str]] = {}

        def walk(n, acc):
            if isinstance(n, Call):
                acc.add(n.name)
            if isinstance(n, Node):
                for v in vars(n).values():
                    walk(v, acc)
            elif isinstance(n, list | tuple):
                for v in n:
                    walk(v, acc)

        for name, infos in self.funcs.items():
            acc: set[str] = set()
            for info in infos:
                walk(info.node.body, acc)
            calls[name] = acc & set(self.funcs)
        state: dict[str, int] = {}

        def visit(name, stack):
            state[name] = 1
            for callee in sorted(calls[name]):
                if state.get(callee) == 1:
                    cyc = stack[stack.index(callee):] + [callee] if callee in stack \
                        else [name, callee]
                    line = self.funcs[callee][0].node.line
                    raise GlslError("unsupported construct: recursion ("
                                    + " → ".join(cyc) + "); GLSL forbids it", line)
                if state.get(callee) is None:
                    visit(callee, stack + [callee])
            state[name] = 2

        for name in self.funcs:
            if state.get(name) is None:
                visit(name, [name])

    def global_decl(self, d: Decl) -> None:
        ctx = Ctx(FuncInfo(Func(d.line, "void", "<global>", [], None), "", ()))
        ctx.scopes = [self.global_scope]
        self._cur_ctx = ctx
        for name, init, line in d.items:
            self.check_new_name(name, line, self.global_scope)
            if init is None:
                val = self.zero(d.type)
            else:
                val = self.convert(self.expr(init, ctx), d.type, line, f"'{name}'")
            if not val.const:
                raise GlslError(f"global '{name}' must have a constant value (parameters are "
                                "only visible inside functions)", line)
            self.global_scope[name] = Sym(d.type, list(val.comps), 0, "global", const=True)

    def check_new_name(self, name: str, line: int, scope: dict) -> None:
        if name in RESERVED:
            raise GlslError(f"'{name}' is a reserved word", line)
        if name in scope:
            raise GlslError(f"'{name}' is declared twice in the same scope", line)

    # -- functions
    def function(self, info: FuncInfo, entry: bool) -> list[str]:
        f = info.node
        ctx = Ctx(info)
        scope: dict[str, Sym] = {}
        ctx.scopes = [self.global_scope, scope]
        prev_ctx, self._cur_ctx = self._cur_ctx, ctx
        try:
            args: list[str] = []
            head: list[str] = []
            assigned = _assigned_names(f.body, self.out_funcs)
            for k, (qual, ty, name) in enumerate(f.params):
                self.check_new_name(name, f.line, scope)
                names = [self.fresh("v_" + name + "_") for _ in range(3 if ty == "vec3" else 1)]
                sym = Sym(ty, names, 0, "param")
                if entry and k >= 2:
                    # N, X, Y of BRDF are the fixed frame: compile-time constants (folded)
                    vec = ((0.0, 0.0, 1.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0))[k - 2]
                    if name not in assigned:
                        sym = Sym("vec3", list(vec), 0, "param", const=True)
                    else:
                        head += [f"{n} = {_py(c)}" for n, c in zip(names, vec, strict=True)]
                    scope[name] = sym
                    continue
                if k in info.consts:  # specialised copy: this argument is a constant
                    scope[name] = Sym(ty, list(info.consts[k]), 0, "param", const=True)
                    continue
                pn = self.fresh("a_" + name + "_")
                if qual == "out":
                    zero = "False" if ty == "bool" else "0.0"
                    head += [f"{n} = {zero}" for n in names]
                else:
                    args.append(pn)
                    head.append(f"{', '.join(names)} = {pn}")
                scope[name] = sym
                if qual in ("out", "inout"):
                    ctx.outs.append((name, sym))
            ctx.lines = [ctx.indent + h for h in head]
            if not self.block(f.body, ctx, new_scope=False):
                self.emit_function_end(ctx)
        finally:
            self._cur_ctx = prev_ctx
        return [f"    def {info.pyname}({', '.join(args)}):"] + ctx.lines

    def emit(self, ctx: Ctx, line: str) -> None:
        ctx.lines.append(ctx.indent + line)

    def tmp(self, ctx: Ctx, code: str) -> str:
        name = self.fresh()
        self.emit(ctx, f"{name} = {code}")
        return name

    def ret_names(self, ctx: Ctx) -> list[str]:
        n = 3 if ctx.func.node.ret == "vec3" else 1
        return [f"_ret{k}" for k in range(n)] if ctx.func.node.ret != "void" else []

    def pack_return(self, ctx: Ctx, comps: list[str]) -> str:
        parts = []
        if ctx.func.node.ret == "vec3":
            parts.append("(" + ", ".join(comps) + ")")
        elif ctx.func.node.ret != "void":
            parts.append(comps[0])
        for _, sym in ctx.outs:
            o = [f"_out_{n}" if ctx.done else n for n in sym.names]
            parts.append("(" + ", ".join(o) + ")" if sym.type == "vec3" else o[0])
        if not parts:
            return "None"
        return parts[0] if len(parts) == 1 else "(" + ", ".join(parts) + ")"

    def emit_function_end(self, ctx: Ctx) -> None:
        """Falling off the end: lanes not yet returned give 0 (and the outs as they are)."""
        zero = "False" if ctx.func.node.ret == "bool" else "0.0"
        if ctx.done:
            for r in self.ret_names(ctx):
                self.emit(ctx, f"{r} = _sel(_done, {r}, {zero})")
            for _, sym in ctx.outs:
                for n in sym.names:
                    self.emit(ctx, f"_out_{n} = _sel(_done, _out_{n}, {n})")
            self.emit(ctx, "return " + self.pack_return(ctx, self.ret_names(ctx)))
        else:
            self.emit(ctx, "return " + self.pack_return(ctx, [zero] * len(self.ret_names(ctx))))

    # -- statements
    def block(self, b, ctx: Ctx, new_scope: bool = True) -> bool:
        """Compile a statement or block; True if it ended in a return on every lane of the
        current path (the rest of the enclosing block is dead)."""
        stmts = b.stmts if isinstance(b, Block) else [b]
        if new_scope:
            ctx.scopes.append({})
        try:
            for s in stmts:
                if self.statement(s, ctx):
                    return True
            return False
        finally:
            if new_scope:
                ctx.scopes.pop()

    def statement(self, s, ctx: Ctx) -> bool:
        if isinstance(s, Block):
            return self.block(s, ctx)
        if isinstance(s, Decl):
            scope = ctx.scopes[-1]
            for name, init, line in s.items:
                if name in scope:
                    raise GlslError(f"'{name}' is declared twice in the same scope", line)
                if name in RESERVED:
                    raise GlslError(f"'{name}' is a reserved word", line)
                val = self.zero(s.type) if init is None else \
                    self.convert(self.expr(init, ctx), s.type, line, f"'{name}'")
                if s.const and val.const:
                    scope[name] = Sym(s.type, list(val.comps), ctx.depth, "local", const=True)
                    continue
                names = [self.fresh("v_" + name + "_") for _ in val.comps]
                for n, c in zip(names, val.comps, strict=True):
                    self.emit(ctx, f"{n} = {_py(c)}")
                scope[name] = Sym(s.type, names, ctx.depth, "local", const=s.const)
            return False
        if isinstance(s, Assign):
            self.assign(s, ctx)
            return False
        if isinstance(s, ExprStmt):
            if isinstance(s.expr, Call):
                self.expr(s.expr, ctx, statement=True)
            else:
                self.expr(s.expr, ctx)  # type-checked, no effect
            return False
        if isinstance(s, If):
            c = self.expr(s.cond, ctx)
            if c.type != "bool":
                raise GlslError(f"the 'if' condition must be bool, not {c.type}", s.line)
            cond = c.comps[0]
            if not isinstance(cond, str):  # compile-time constant: one branch only
                taken = s.then if cond else s.other
                return self.block(taken, ctx) if taken is not None else False
            saved_path, saved_depth = ctx.path, ctx.depth
            then_path = cond if saved_path is True else self.tmp(ctx, f"_and({saved_path}, "
                                                                    f"{cond})")
            ctx.path, ctx.depth = then_path, saved_depth + 1
            self.block(s.then, ctx)
            if s.other is not None:
                neg = self.tmp(ctx, f"_not({cond})")
                ctx.path = neg if saved_path is True else self.tmp(
                    ctx, f"_and({saved_path}, {neg})")
                self.block(s.other, ctx)
            ctx.path, ctx.depth = saved_path, saved_depth
            return False
        if isinstance(s, Return):
            return self.ret(s, ctx)
        raise GlslError("unsupported statement", s.line)

    def ret(self, s: Return, ctx: Ctx) -> bool:
        rt = ctx.func.node.ret
        if s.value is None:
            if rt != "void":
                raise GlslError(f"'{ctx.func.node.name}' must return a {rt}", s.line)
            comps: list = []
        else:
            if rt == "void":
                raise GlslError(f"void function '{ctx.func.node.name}' cannot return a value",
                                s.line)
            v = self.convert(self.expr(s.value, ctx), rt, s.line, "the returned value")
            comps = [_py(c) for c in v.comps]
        rets = self.ret_names(ctx)
        grey = ctx.grey and len(set(comps)) <= 1  # every return so far has R = G = B
        ctx.grey = grey

        def set_rets(code):
            """``_retK = code(_retK, component K)``, computed once when all are equal."""
            if grey and len(rets) == 3:
                self.emit(ctx, f"{rets[0]} = {code(rets[0], comps[0])}")
                self.emit(ctx, f"{rets[1]} = {rets[2]} = {rets[0]}")
                return
            for r, c in zip(rets, comps, strict=True):
                self.emit(ctx, f"{r} = {code(r, c)}")

        if ctx.path is True:  # every remaining lane returns here
            if ctx.done:
                set_rets(lambda r, c: f"_sel(_done, {r}, {c})")
                for _, sym in ctx.outs:
                    for n in sym.names:
                        self.emit(ctx, f"_out_{n} = _sel(_done, _out_{n}, {n})")
                self.emit(ctx, "return " + self.pack_return(ctx, rets))
            else:
                self.emit(ctx, "return " + self.pack_return(ctx, comps))
            return True
        p = ctx.path
        zero = "False" if rt == "bool" else "0.0"
        if not ctx.done:
            set_rets(lambda r, c: zero if c == zero else f"_sel({p}, {c}, {zero})")
            for _, sym in ctx.outs:
                for n in sym.names:
                    self.emit(ctx, f"_out_{n} = {n}")
            self.emit(ctx, f"_done = {p}")
            ctx.done = True
        else:
            act = self.tmp(ctx, f"_and({p}, _not(_done))")
            set_rets(lambda r, c: f"_sel({act}, {c}, {r})")
            for _, sym in ctx.outs:
                for n in sym.names:
                    self.emit(ctx, f"_out_{n} = _sel({act}, {n}, _out_{n})")
            self.emit(ctx, f"_done = _or(_done, {p})")
        return True

    def lookup(self, name: str, line: int, ctx: Ctx) -> Sym:
        for scope in reversed(ctx.scopes):
            if name in scope:
                return scope[name]
        if name in self.funcs or name in BUILTIN_NAMES:
            raise GlslError(f"'{name}' is a function: call it with ( )", line)
        raise GlslError(f"unknown name '{name}'", line)

    def assign(self, s: Assign, ctx: Ctx) -> None:
        target = s.target
        comp_index: list[int] | None = None
        if isinstance(target, Index | Swizzle):
            base = target.base
            if not isinstance(base, Var):
                raise GlslError("unsupported construct: assignment to this expression", s.line)
            comp_index = self.component_indices(target, ctx)
            target = base
        if not isinstance(target, Var):
            raise GlslError("the left side of an assignment must be a variable", s.line)
        sym = self.lookup(target.name, s.line, ctx)
        if sym.kind == "uniform":
            raise GlslError(f"cannot assign to '{target.name}': it is a parameter of the "
                            "::begin parameters block", s.line)
        if sym.kind == "global" or sym.const:
            raise GlslError(f"cannot assign to constant '{target.name}'", s.line)
        value = self.expr(s.value, ctx)
        cur_type = sym.type if comp_index is None else (
            "float" if len(comp_index) == 1 else "vec3")
        cur = Value(cur_type, [sym.names[k] for k in comp_index] if comp_index is not None
                    else list(sym.names))
        if s.op != "=":
            value = self.arith(s.op[0], cur, value, s.line)
        value = self.convert(value, cur_type, s.line, f"'{target.name}'")
        self.store(ctx, sym, comp_index, value)

    def store(self, ctx: Ctx, sym: Sym, comp_index, value: Value) -> None:
        idx = comp_index if comp_index is not None else list(range(len(sym.names)))
        masked = ctx.depth > sym.depth and ctx.path is not True
        new = []
        for k, c in zip(idx, value.comps, strict=True):
            name = sym.names[k]
            code = f"_sel({ctx.path}, {_py(c)}, {name})" if masked else _py(c)
            new.append((name, code))
        if len(new) > 1:  # evaluate all before writing (v = v.zyx)
            self.emit(ctx, ", ".join(n for n, _ in new) + " = " + ", ".join(c for _, c in new))
        else:
            self.emit(ctx, f"{new[0][0]} = {new[0][1]}")

    def component_indices(self, e, ctx: Ctx) -> list[int]:
        if isinstance(e, Index):
            idx = self.expr(e.index, ctx)
            k = idx.comps[0]
            if idx.type != "float" or isinstance(k, str):
                raise GlslError("unsupported construct: indexing with a value that is not a "
                                "constant (v[i] needs i = 0, 1 or 2)", e.line)
            if k not in (0.0, 1.0, 2.0):
                raise GlslError(f"index {k:g} out of range for vec3 (0, 1 or 2)", e.line)
            return [int(k)]
        comps = e.comps
        for letters in SWIZZLE_SETS:
            if all(ch in letters for ch in comps):
                if len(comps) not in (1, 3):
                    raise GlslError(f"unsupported construct: swizzle '.{comps}' (only one or "
                                    "three components: float or vec3)", e.line)
                return [letters.index(ch) for ch in comps]
        raise GlslError(f"unknown component '.{comps}' of a vec3", e.line)

    # -- expressions
    def zero(self, ty: str) -> Value:
        if ty == "vec3":
            return Value("vec3", [0.0, 0.0, 0.0])
        return Value(ty, [False] if ty == "bool" else [0.0])

    def convert(self, v: Value, ty: str, line: int, what: str) -> Value:
        if v.type == ty:
            return v
        raise GlslError(f"type error: {what} is {ty} but the value is {v.type}", line)

    def expr(self, e, ctx: Ctx, statement: bool = False) -> Value:
        if isinstance(e, Num):
            return Value("float", [e.value])
        if isinstance(e, BoolLit):
            return Value("bool", [e.value])
        if isinstance(e, Var):
            sym = self.lookup(e.name, e.line, ctx)
            return Value(sym.type, list(sym.names))
        if isinstance(e, Unary):
            v = self.expr(e.operand, ctx)
            if e.op == "!":
                if v.type != "bool":
                    raise GlslError(f"type error: '!' needs a bool, not {v.type}", e.line)
                c = v.comps[0]
                return Value("bool", [not c if not isinstance(c, str)
                                      else self.tmp(ctx, f"_not({c})")])
            if v.type == "bool":
                raise GlslError(f"type error: unary '{e.op}' of a bool", e.line)
            if e.op == "+":
                return v
            return Value(v.type, [-c if not isinstance(c, str) else self.tmp(ctx, f"-{c}")
                                  for c in v.comps])
        if isinstance(e, Binary):
            return self.binary(e, ctx)
        if isinstance(e, Ternary):
            c = self.expr(e.cond, ctx)
            if c.type != "bool":
                raise GlslError(f"type error: the ?: condition must be bool, not {c.type}",
                                e.line)
            cond = c.comps[0]
            if not isinstance(cond, str):
                return self.expr(e.then if cond else e.other, ctx)
            self._ternary_depth += 1
            try:
                a = self.expr(e.then, ctx)
                b = self.expr(e.other, ctx)
            finally:
                self._ternary_depth -= 1
            if a.type != b.type:
                raise GlslError(f"type error: the two sides of ?: are {a.type} and {b.type}",
                                e.line)
            return Value(a.type, [self.tmp(ctx, f"_sel({cond}, {_py(x)}, {_py(y)})")
                                  for x, y in zip(a.comps, b.comps, strict=True)])
        if isinstance(e, Index | Swizzle):
            base = self.expr(e.base, ctx)
            if base.type != "vec3":
                raise GlslError(f"type error: cannot take a component of a {base.type}", e.line)
            idx = self.component_indices(e, ctx)
            comps = [base.comps[k] for k in idx]
            return Value("float" if len(comps) == 1 else "vec3", comps)
        if isinstance(e, Call):
            return self.call(e, ctx, statement)
        raise GlslError("unsupported expression", e.line)

    def binary(self, e: Binary, ctx: Ctx) -> Value:
        a = self.expr(e.left, ctx)
        b = self.expr(e.right, ctx)
        op = e.op
        if op in ("&&", "||", "^^"):
            if a.type != "bool" or b.type != "bool":
                raise GlslError(f"type error: '{op}' needs bools, not {a.type} and {b.type}",
                                e.line)
            x, y = a.comps[0], b.comps[0]
            if not isinstance(x, str) and not isinstance(y, str):
                r = {"&&": x and y, "||": x or y, "^^": x != y}[op]
                return Value("bool", [bool(r)])
            if op == "&&" and not isinstance(x, str):
                return b if x else Value("bool", [False])
            if op == "||" and not isinstance(x, str):
                return Value("bool", [True]) if x else b
            fn = {"&&": "_and", "||": "_or", "^^": "_xor"}[op]
            return Value("bool", [self.tmp(ctx, f"{fn}({_py(x)}, {_py(y)})")])
        if op in ("<", ">", "<=", ">="):
            if a.type != "float" or b.type != "float":
                raise GlslError(f"type error: '{op}' compares floats, not {a.type} and "
                                f"{b.type}", e.line)
            x, y = a.comps[0], b.comps[0]
            if not isinstance(x, str) and not isinstance(y, str):
                return Value("bool", [bool(eval(f"{x!r} {op} {y!r}"))])  # two constants
            return Value("bool", [self.tmp(ctx, f"({_py(x)} {op} {_py(y)})")])
        if op in ("==", "!="):
            if a.type != b.type:
                raise GlslError(f"type error: '{op}' between {a.type} and {b.type}", e.line)
            parts = []
            for x, y in zip(a.comps, b.comps, strict=True):
                if not isinstance(x, str) and not isinstance(y, str):
                    parts.append(x == y)
                else:
                    parts.append(self.tmp(ctx, f"np.equal({_py(x)}, {_py(y)})"))
            r: Any = True
            for p in parts:
                if r is True:
                    r = p
                elif p is not True:
                    r = self.tmp(ctx, f"_and({_py(r)}, {_py(p)})") if (
                        isinstance(r, str) or isinstance(p, str)) else bool(r and p)
            if op == "!=":
                r = (not r) if not isinstance(r, str) else self.tmp(ctx, f"_not({r})")
            return Value("bool", [r])
        return self.arith(op, a, b, e.line)

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
    _ternary_depth = 0

    def _emit_tmp(self, code: str) -> str:
        assert self._cur_ctx is not None
        return self.tmp(self._cur_ctx, code)

    # -- calls
    def call(self, e: Call, ctx: Ctx, statement: bool) -> Value:
        name = e.name
        if name in UNSUPPORTED_TYPES:
            raise GlslError(f"unsupported construct: {UNSUPPORTED_TYPES[name]}", e.line)
        user = self.funcs.get(name)
        arg_vals = []
        for a in e.args:
            arg_vals.append(self.expr(a, ctx))
        types = tuple(v.type for v in arg_vals)
        if user:
            for info in user:
                if info.sig == types:
                    return self.user_call(info, e, arg_vals, ctx, statement)
            if name not in BUILTIN_NAMES:
                have = "; ".join(f"{name}({', '.join(i.sig)})" for i in user)
                raise GlslError(f"no overload of '{name}' takes ({', '.join(types)}); "
                                f"defined: {have}", e.line)
        return self.builtin(name, arg_vals, e.line, ctx)

    def specialise(self, info: FuncInfo, vals: list[Value]) -> FuncInfo:
        """The copy of ``info`` with its constant ``in`` arguments folded (partial
        evaluation: ``dot(N, v)`` inside a helper called with ``N`` becomes ``v.z``)."""
        key_id = id(info.node)
        if key_id not in self._assigned:
            self._assigned[key_id] = _assigned_names(info.node.body, self.out_funcs)
        assigned = self._assigned[key_id]
        consts = {k: tuple(v.comps) for k, ((qual, _, name), v)
                  in enumerate(zip(info.node.params, vals, strict=True))
                  if qual == "in" and v.const and name not in assigned}
        if not consts:
            return info
        key = (info.pyname, tuple(sorted(consts.items())))
        spec = self.specials.get(key)
        if spec is None:
            spec = FuncInfo(info.node, self.fresh(info.pyname.lstrip("_") + "_c"), info.sig,
                            consts)
            self.specials[key] = spec
            self.pending.append(spec)
        return spec

    def user_call(self, info: FuncInfo, e: Call, vals: list[Value], ctx: Ctx,
                  statement: bool) -> Value:
        info = self.specialise(info, vals)
        passed = []
        outs = []
        for k, ((qual, ty, pname), a, v) in enumerate(zip(info.node.params, e.args, vals,
                                                         strict=True)):
            if k in info.consts:
                continue
            if qual in ("out", "inout"):
                if self._ternary_depth:
                    raise GlslError(f"unsupported construct: a call of '{e.name}' with out "
                                    "arguments inside ?:", e.line)
                outs.append((a, ty, pname))
            if qual == "out":
                continue
            passed.append("(" + ", ".join(_py(c) for c in v.comps) + ")" if ty == "vec3"
                          else _py(v.comps[0]))
        call = f"{info.pyname}({', '.join(passed)})"
        rt = info.node.ret
        parts = []
        if rt == "vec3":
            parts.append([self.fresh() for _ in range(3)])
        elif rt != "void":
            parts.append([self.fresh()])
        for _, ty, _ in outs:
            parts.append([self.fresh() for _ in range(3 if ty == "vec3" else 1)])
        if not parts:
            self.emit(ctx, call)
            return Value("void", [])
        lhs = ", ".join("(" + ", ".join(p) + ")" if len(p) == 3 else p[0] for p in parts)
        if len(parts) == 1 and len(parts[0]) == 3:
            lhs = ", ".join(parts[0])
        self.emit(ctx, f"{lhs} = {call}")
        for (a, ty, pname), names in zip(outs, parts[1:] if rt != "void" else parts,
                                         strict=True):
            comp_index = None
            target = a
            if isinstance(a, Index | Swizzle) and isinstance(a.base, Var):
                comp_index = self.component_indices(a, ctx)
                target = a.base
            if not isinstance(target, Var):
                raise GlslError(f"the out argument '{pname}' of '{e.name}' must be a variable",
                                e.line)
            sym = self.lookup(target.name, e.line, ctx)
            if sym.kind in ("uniform", "global") or sym.const:
                raise GlslError(f"cannot pass '{target.name}' as an out argument: it is "
                                "constant", e.line)
            self.store(ctx, sym, comp_index, Value(ty, list(names)))
        if rt == "void":
            return Value("void", [])
        return Value(rt, list(parts[0]))

    def builtin(self, name: str, vals: list[Value], line: int, ctx: Ctx) -> Value:
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
                                       else self.tmp(ctx, f"np.where({c}, 1.0, 0.0) + 0.0")])
            raise GlslError(f"type error: no constructor {sig}", line)
        if name == "bool":
            if types == ("bool",):
                return vals[0]
            if types == ("float",):
                c = vals[0].comps[0]
                return Value("bool", [c != 0.0 if not isinstance(c, str)
                                      else self.tmp(ctx, f"np.not_equal({c}, 0.0)")])
            raise GlslError(f"type error: no constructor {sig}", line)
        if name in UNARY_BUILTINS:
            if len(vals) != 1:
                raise GlslError(f"'{name}' takes 1 argument, not {len(vals)}", line)
            out = []
            for c in vals[0].comps:
                if not isinstance(c, str) and name in _FOLD_UNARY:
                    out.append(float(_FOLD_UNARY[name](c)))
                else:
                    out.append(self.tmp(ctx, UNARY_BUILTINS[name].format(_py(c))))
            return Value(vals[0].type, out)
        if name == "atan":
            if len(vals) == 1:
                return Value(vals[0].type, [self.tmp(ctx, f"np.arctan({_py(c)})")
                                            for c in vals[0].comps])
            name = "atan2"
        if name in NARY_BUILTINS:
            n, template = NARY_BUILTINS[name]
            if len(vals) != n:
                raise GlslError(f"'{name}' takes {n} arguments, not {len(vals)}", line)
            ty = "vec3" if "vec3" in types else "float"
            if ty == "vec3" and not self.broadcast_ok(name, types):
                raise GlslError(f"type error: no built-in {sig}", line)
            cols = [v.comps * 3 if (ty == "vec3" and v.type == "float") else v.comps
                    for v in vals]
            out = []
            for k in range(3 if ty == "vec3" else 1):
                args = [col[k] for col in cols]
                if all(not isinstance(a, str) for a in args) and name in ("min", "max",
                                                                          "clamp", "mix"):
                    out.append(self.fold_nary(name, args))
                else:
                    out.append(self.tmp(ctx, template.format(*(_py(a) for a in args))))
            return Value(ty, out)
        # geometric
        want = {"dot": ("vec3", "vec3"), "cross": ("vec3", "vec3"), "length": ("vec3",),
                "distance": ("vec3", "vec3"), "normalize": ("vec3",),
                "reflect": ("vec3", "vec3"), "faceforward": ("vec3", "vec3", "vec3")}[name]
        if types != want:
            if name in ("length", "normalize") and types == ("float",):
                c = vals[0].comps[0]
                code = f"np.abs({_py(c)})" if name == "length" else f"_sign({_py(c)})"
                return Value("float", [self.tmp(ctx, code)])
            raise GlslError(f"type error: no built-in {sig} (expects {name}"
                            f"({', '.join(want)}))", line)
        if name == "dot":
            return Value("float", [self.dot(vals[0].comps, vals[1].comps)])
        if name == "cross":
            a, b = vals[0].comps, vals[1].comps
            out = []
            for i, j in ((1, 2), (2, 0), (0, 1)):
                out.append(self.scalar_op("-", self.scalar_op("*", a[i], b[j]),
                                          self.scalar_op("*", a[j], b[i])))
            return Value("vec3", out)
        if name in ("length", "distance"):
            v = vals[0].comps if name == "length" else \
                [self.scalar_op("-", x, y) for x, y in zip(vals[0].comps, vals[1].comps,
                                                             strict=True)]
            d = self.dot(v, v)
            return Value("float", [math.sqrt(d) if not isinstance(d, str)
                                   else self.tmp(ctx, f"np.sqrt({d})")])
        if name == "normalize":
            v = vals[0].comps
            d = self.dot(v, v)
            if not isinstance(d, str):
                inv = 1.0 / math.sqrt(d) if d > 0 else 0.0
                return Value("vec3", [self.scalar_op("*", c, inv) for c in v])
            length = self.tmp(ctx, f"np.sqrt({d})")
            return Value("vec3", [self.scalar_op("/", c, length) for c in v])
        if name == "reflect":  # I - 2 dot(N, I) N
            i, n = vals[0].comps, vals[1].comps
            k = self.scalar_op("*", 2.0, self.dot(n, i))
            return Value("vec3", [self.scalar_op("-", a, self.scalar_op("*", k, b))
                                  for a, b in zip(i, n, strict=True)])
        # faceforward(N, I, Nref) = dot(Nref, I) < 0 ? N : -N
        n, i, nref = (v.comps for v in vals)
        d = self.dot(nref, i)
        neg = [self.scalar_op("-", 0.0, c) for c in n]
        if not isinstance(d, str):
            return Value("vec3", n if d < 0 else neg)
        c = self.tmp(ctx, f"({d} < 0.0)")
        return Value("vec3", [self.tmp(ctx, f"_sel({c}, {_py(a)}, {_py(b)})")
                              for a, b in zip(n, neg, strict=True)])

    @staticmethod
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

    @staticmethod
    def fold_nary(name: str, a: list) -> float:
        if name == "min":
            return min(a[0], a[1])
        if name == "max":
            return max(a[0], a[1])
        if name == "clamp":
            return min(max(a[0], a[1]), a[2])
        return a[0] * (1.0 - a[2]) + a[1] * a[2]

    def dot(self, a: list, b: list) -> Comp:
        acc: Comp = 0.0
        for x, y in zip(a, b, strict=True):
            acc = self.scalar_op("+", acc, self.scalar_op("*", x, y))
        return acc


def _assigned_names(node, out_funcs: set[str]) -> set[str]:
    """Names assigned anywhere in ``node`` (including as arguments of functions with out
    parameters)."""
    out: set[str] = set()

    def walk(n):
        if isinstance(n, Assign):
            t = n.target
            while isinstance(t, Index | Swizzle):
                t = t.base
            if isinstance(t, Var):
                out.add(t.name)
        if isinstance(n, Call) and n.name in out_funcs:
            for a in n.args:  # possibly out arguments
                t = a
                while isinstance(t, Index | Swizzle):
                    t = t.base
                if isinstance(t, Var):
                    out.add(t.name)
        if isinstance(n, Node):
            for v in vars(n).values():
                walk(v)
        elif isinstance(n, list | tuple):
            for v in n:
                walk(v)

    walk(node)
    return out


@dataclass
class Shader:
    """A compiled shader: ``fn(L, V, **uniforms)`` with ``L``, ``V`` as 3-tuples of arrays
    returns a 3-tuple (``vec3 BRDF``) or one value (``float BRDF``)."""

    fn: Any
    returns: str
    source: str


def compile_shader(src: str, uniforms: dict[str, str], first_line: int = 1) -> Shader:
    """Parse, check and translate ``src``; raises :class:`GlslError` with the line."""
    globs, funcs = parse(src, first_line)
    source, returns = Compiler(globs, funcs, uniforms).compile()
    namespace = dict(RUNTIME)
    exec(compile(source, "<shader>", "exec"), namespace)  # noqa: S102 — our own generated code
    return Shader(namespace["_shader"], returns, source)
