"""The GLSL syntax tree (one dataclass per construct, each with its line) and the subset's
vocabulary: its types, the reserved words, and the constructs refused with a name."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any


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

RESERVED = set(TYPES) | set(UNSUPPORTED_TYPES) | {
    "if", "else", "return", "const", "true", "false", "in", "out", "inout", "uniform",
    "for", "while", "do", "break", "continue", "discard", "struct", "switch"}
