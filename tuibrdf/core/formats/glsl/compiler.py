"""The GLSL compiler's last stage: the syntax tree, type-checked, → the Python source of one
kernel, and :func:`compile_shader`, the whole pipeline (lexer, parser, compiler) from the
shader's text to a function of whole arrays of directions (the package docstring says how
branches, returns and constants are compiled)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from tuibrdf.core.formats.glsl import budgets
from tuibrdf.core.formats.glsl.builtins import BUILTIN_NAMES, builtin
from tuibrdf.core.formats.glsl.emitter import _COMPARE, Ctx, Emitter, FuncInfo, Sym, Value, _py
from tuibrdf.core.formats.glsl.errors import GlslError
from tuibrdf.core.formats.glsl.parser import parse
from tuibrdf.core.formats.glsl.runtime import RUNTIME
from tuibrdf.core.formats.glsl.syntax import (
    RESERVED,
    SWIZZLE_SETS,
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
    Node,
    Num,
    Return,
    Swizzle,
    Ternary,
    Unary,
    Var,
)


class Compiler(Emitter):
    """Type-checks the syntax tree and emits the Python source of one kernel function."""

    def __init__(self, globs: list[Decl], funcs: list[Func], uniforms: dict[str, str]):
        self.globs = globs
        self.uniforms = uniforms  # GLSL name → type (float, vec3, bool)
        super().__init__()
        self.funcs: dict[str, list[FuncInfo]] = {}
        self.global_scope: dict[str, Sym] = {}
        self.prologue: list[str] = []
        for f in funcs:
            self.add_function(f)
        #: specialised copies of functions (constant arguments folded), by key, and those
        #: still to be compiled
        self.specials: dict[tuple, FuncInfo] = {}
        self.pending: list[FuncInfo] = []
        self._copies: dict[int, int] = {}  # specialised copies per function (a budget)
        #: generated function → (GLSL name, line, own lines, callees): the run-time budget
        self.callgraph: dict[str, tuple[str, int, int, list[str]]] = {}
        self._assigned: dict[int, set[str]] = {}
        #: user functions with out/inout parameters (their arguments may be assigned)
        self.out_funcs = {f.name for f in funcs
                          if any(q in ("out", "inout") for q, _, _ in f.params)}

    # -- the shader's functions, by name and signature
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
        for qual, _, pname in entry.node.params:
            if qual != "in":
                raise GlslError(f"BRDF's parameter '{pname}' is '{qual}': BRDF must be "
                                "'vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)' with "
                                "input parameters only", entry.node.line)
        for infos in self.funcs.values():
            for info in infos:
                if info.node.body is None:
                    raise GlslError(f"function '{info.node.name}' is declared but never "
                                    "defined", info.node.line)
        self.check_recursion()
        for name, ty in self.uniforms.items():  # uc_NAME_K never equals a u_NAME
            self.global_scope[name] = Sym(ty, [f"uc_{name}_{k}" for k in range(3)]
                                          if ty == "vec3" else [f"u_{name}"], 0, "uniform")
        for d in self.globs:
            self.global_decl(d)
        bodies = []
        for infos in self.funcs.values():
            for info in infos:
                bodies.extend(self.function(info, entry=info is entry))
        while self.pending:  # copies specialised for constant arguments, found on the way
            bodies.extend(self.function(self.pending.pop(), entry=False))
        self.steps = budgets.check_run_cost(self.callgraph, entry.pyname)
        args = ", ".join(f"u_{n}" for n in self.uniforms)
        src = ["def _shader(L, V" + (", " + args if args else "") + "):"]
        for name, ty in self.uniforms.items():
            if ty == "vec3":
                src.append(f"    uc_{name}_0, uc_{name}_1, uc_{name}_2 = u_{name}")
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
                self.line = info.node.line  # for a RecursionError on a very deep tree
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
            self.line = line
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
        self.line = f.line
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
        self.callgraph[info.pyname] = (f.name, f.line, len(ctx.lines) + 1, ctx.callees)
        return [f"    def {info.pyname}({', '.join(args)}):"] + ctx.lines

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
        self.line = s.line
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
                return Value("bool", [bool(_COMPARE[op](x, y))])  # two constants (IEEE)
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

    # nesting depth of the ?: being compiled (a call with out arguments is refused inside)
    _ternary_depth = 0

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
        return builtin(self, name, arg_vals, e.line, ctx)

    def specialise(self, info: FuncInfo, vals: list[Value], line: int) -> FuncInfo:
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
            n = self._copies[key_id] = self._copies.get(key_id, 0) + 1
            if n > budgets.MAX_COPIES_PER_FUNCTION or len(self.specials) >= budgets.MAX_COPIES:
                raise GlslError(f"too many specialised copies of '{info.node.name}': calls with "
                                f"constant arguments make a copy each (budget: "
                                f"{budgets.MAX_COPIES_PER_FUNCTION} per function, "
                                f"{budgets.MAX_COPIES} in all)", line)
            spec = FuncInfo(info.node, self.fresh(info.pyname.lstrip("_") + "_c"), info.sig,
                            consts)
            self.specials[key] = spec
            self.pending.append(spec)
        return spec

    def user_call(self, info: FuncInfo, e: Call, vals: list[Value], ctx: Ctx,
                  statement: bool) -> Value:
        info = self.specialise(info, vals, e.line)
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
        ctx.callees.append(info.pyname)
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
    steps: int = 1  # lines run per value (the run-time budget; sets the evaluation's chunks)


def compile_shader(src: str, uniforms: dict[str, str], first_line: int = 1) -> Shader:
    """Parse, check and translate ``src``; raises :class:`GlslError` with the line."""
    globs, funcs = parse(src, first_line)
    c = Compiler(globs, funcs, uniforms)
    try:
        source, returns = c.compile()
    except RecursionError:  # Python's stack: an expression of hundreds of operators
        raise GlslError("the shader nests too deeply to translate", c.line) from None
    namespace = dict(RUNTIME)
    exec(compile(source, "<shader>", "exec"), namespace)  # noqa: S102 — our own generated code
    return Shader(namespace["_shader"], returns, source, c.steps)
