"""The GLSL parser: recursive descent over the lexer's tokens into the syntax tree of
:mod:`.syntax`, refusing what the subset does not support with the line and the construct."""

from __future__ import annotations

from tuibrdf.core.formats.glsl.errors import GlslError
from tuibrdf.core.formats.glsl.lexer import Tok, tokenize
from tuibrdf.core.formats.glsl.syntax import (
    QUALIFIERS_REJECTED,
    TYPES,
    UNSUPPORTED_STATEMENTS,
    UNSUPPORTED_TYPES,
    Assign,
    Binary,
    Block,
    BoolLit,
    Call,
    Decl,
    ExprStmt,
    Func,
    If,
    Index,
    Num,
    Return,
    Swizzle,
    Ternary,
    Unary,
    Var,
)


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
    p = Parser(tokenize(src, first_line))
    try:
        return p.program()
    except RecursionError:  # Python's stack, about 60 nested parentheses: a line, not a crash
        raise GlslError("the shader nests too deeply (parentheses, blocks or ?:)",
                        p.tok.line) from None
