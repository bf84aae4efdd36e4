"""BRDF Explorer ``.brdf`` (analytic) and ``.bparam`` files as tuibrdf models.

The format is that of Disney's BRDF Explorer (github.com/wdas/brdf, ``BRDFBase::loadBRDF``):

* the first line's first word is the type: ``analytic`` (a ``.brdf`` file) or ``bparam``;
* every other line is trimmed; blank lines and lines starting with ``#`` are skipped — in
  every section, the shader included (so a ``#define`` never reaches the shader);
* ``::begin NAME`` … ``::end NAME`` delimit sections, which do not nest; the ``::end`` must
  name the open section;
* ``parameters`` holds one parameter a line: ``float NAME MIN MAX DEFAULT``, ``bool NAME 0|1``,
  ``color NAME R G B``;
* ``shader`` holds the GLSL defining ``vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)``;
  the parameters are visible in it as uniforms of type float, bool and vec3;
* ``isFunc`` (importance sampling) is read and ignored, as are unknown sections (BRDF
  Explorer warns about them).

A ``.bparam`` file (first line ``bparam PATH``; BRDF Explorer's "save parameters") is a
parameter block applied to the file at ``PATH`` (relative to the ``.bparam`` file's folder):
the model is that file's, with these values as defaults.  Parameters are matched by name;
tuibrdf rejects a name the file does not declare (BRDF Explorer ignores it silently).

Parameters become declared :class:`~tuibrdf.core.params.Param`: ``float`` → a float in
``[MIN, MAX]`` (step (MAX − MIN)/100); ``bool`` → a choice ``off``/``on``; ``color`` → an RGB
in ``[0, max(1, R, G, B)]``.  So ``-p``, the panel, validation and presets treat them as for the
built-in models.

Evaluation: ``L = wi``, ``V = wo``, ``N = +z``, ``X = +x``, ``Y = +y``; the shader is compiled
once per file by :mod:`tuibrdf.core.formats.glsl`.  The returned value is made usable: NaN, ±inf and
negative values become 0 (a user formula can overflow or go negative where the GPU would draw
garbage), and directions below the horizon give 0.  A ``vec3 BRDF`` gives an RGB model, a
``float BRDF`` a scalar one.  Reciprocity is not assumed.
"""

from __future__ import annotations

import math
import os
import re
from dataclasses import dataclass, replace
from functools import partial

import numpy as np

from tuibrdf.core.formats.files import UserFileError
from tuibrdf.core.formats.glsl import BUILTIN_NAMES, RESERVED, GlslError, Shader, compile_shader
from tuibrdf.core.formats.glsl.budgets import MAX_FILE_BYTES, chunk_size
from tuibrdf.core.numerics import shader_errstate
from tuibrdf.core.params import BOOL_CHOICES, Model, Param, unknown_message

_NAME = re.compile(r"[A-Za-z_][A-Za-z_0-9]*$")


@dataclass
class Parsed:
    kind: str  # analytic | bparam
    target: str  # bparam: the referenced path
    params: list  # [(kind, name, values, line)]
    shader: str
    shader_line: int
    sections: list


def _err(path: str, line: int | None, msg: str) -> UserFileError:
    where = f"{path}:{line}" if line else path
    return UserFileError(f"{where}: {msg}")


def read_text(path: str) -> str:
    try:
        with open(path, "rb") as f:
            raw = f.read(MAX_FILE_BYTES + 1)
    except OSError as e:
        raise UserFileError(f"{path}: cannot read: {e.strerror or e}") from None
    if len(raw) > MAX_FILE_BYTES:
        raise UserFileError(f"{path}: too large for a BRDF Explorer file (over "
                            f"{MAX_FILE_BYTES // 1024} KB; the budgets are in "
                            "docs/reference/formats.md)")
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError as e:
        raise UserFileError(f"{path}: not a text file (invalid UTF-8 at byte {e.start})") \
            from None


def parse_file(path: str, text: str | None = None) -> Parsed:
    """Split a ``.brdf``/``.bparam`` file into its parameter lines and shader text."""
    text = read_text(path) if text is None else text
    lines = text.split("\n")
    first = lines[0].strip() if lines else ""
    kind = first.split(" ", 1)[0] if first else ""
    if kind not in ("analytic", "bparam"):
        shown = first[:40] or "(empty)"
        raise _err(path, 1, f"not a BRDF Explorer file: the first line must be 'analytic' "
                            f"(or 'bparam PATH'), found {shown!r}")
    target = first[len(kind):].strip() if kind == "bparam" else ""
    if kind == "bparam" and not target:
        raise _err(path, 1, "'bparam' needs the path of the .brdf file it applies to")
    params: list = []
    shader_lines: list[str] = []
    shader_line = 0
    section = ""
    section_line = 0
    sections: list[str] = []
    for n, line in enumerate(lines[1:], start=2):
        t = line.strip()
        if not t or t.startswith("#"):
            if section == "shader":
                shader_lines.append("")  # keep line numbers
            continue
        words = t.split()
        if words[0] == "::begin":
            if len(words) < 2:
                raise _err(path, n, "'::begin' needs a section name")
            if section:
                raise _err(path, n, f"'::begin {words[1]}' inside section '{section}' "
                                    f"(opened on line {section_line}; sections do not nest)")
            section, section_line = words[1], n
            sections.append(section)
            if section == "shader":
                shader_line = n + 1
                shader_lines = []
            continue
        if words[0] == "::end":
            name = words[1] if len(words) > 1 else ""
            if name != section:
                if not section:
                    raise _err(path, n, f"'::end {name}' without '::begin {name}'")
                raise _err(path, n, f"'::end {name}' but the open section is '{section}' "
                                    f"(line {section_line})")
            section = ""
            continue
        if section == "parameters":
            params.append(_param_line(path, n, words))
        elif section == "shader":
            shader_lines.append(line)
        elif not section:
            raise _err(path, n, f"text outside a section: {t[:40]!r} (expected '::begin "
                                "parameters' or '::begin shader')")
    if section:
        raise _err(path, section_line, f"section '{section}' is never closed (missing "
                                       f"'::end {section}'; truncated file?)")
    if kind == "analytic" and "shader" not in sections:
        raise _err(path, None, "no '::begin shader' section (the GLSL defining BRDF)")
    if kind == "bparam" and "parameters" not in sections:
        raise _err(path, None, "no '::begin parameters' section")
    return Parsed(kind, target, params, "\n".join(shader_lines), shader_line, sections)


def _number(path: str, n: int, text: str, what: str) -> float:
    try:
        v = float(text)
    except ValueError:
        raise _err(path, n, f"{what} {text!r} is not a number") from None
    if not math.isfinite(v):
        raise _err(path, n, f"{what} {text!r} is not finite")
    return v


def _param_line(path: str, n: int, words: list[str]):
    kind = words[0]
    want = {"float": 5, "bool": 3, "color": 5}
    if kind not in want:
        raise _err(path, n, f"bad parameter line: unknown type {kind!r} (expected 'float NAME "
                            "MIN MAX DEFAULT', 'bool NAME 0|1' or 'color NAME R G B')")
    form = {"float": "float NAME MIN MAX DEFAULT", "bool": "bool NAME 0|1",
            "color": "color NAME R G B"}[kind]
    if len(words) < want[kind]:
        raise _err(path, n, f"bad parameter line: expected '{form}', found "
                            f"{' '.join(words)!r}")
    name = words[1]
    if not _NAME.match(name) or name in RESERVED or name in BUILTIN_NAMES:
        raise _err(path, n, f"bad parameter name {name!r} (a GLSL identifier that is not a "
                            "keyword or built-in)")
    if kind == "bool":
        if words[2] not in ("0", "1"):
            raise _err(path, n, f"bool {name}: value {words[2]!r} must be 0 or 1")
        return kind, name, (words[2] == "1",), n
    vals = tuple(_number(path, n, w, f"{kind} {name}:") for w in words[2:5])
    if kind == "float":
        lo, hi, default = vals
        if not lo < hi:
            raise _err(path, n, f"float {name}: min {lo:g} must be below max {hi:g}")
        if not lo <= default <= hi:
            raise _err(path, n, f"float {name}: default {default:g} is outside [{lo:g}, "
                                f"{hi:g}]")
    elif any(v < 0 for v in vals):
        raise _err(path, n, f"color {name}: components must be ≥ 0")
    return kind, name, vals, n


def declare(path: str, params: list) -> tuple[tuple[Param, ...], dict[str, str]]:
    """Declared parameters and the shader's uniform types, from the parameter lines."""
    out = []
    uniforms: dict[str, str] = {}
    for kind, name, vals, n in params:
        if name in uniforms:
            raise _err(path, n, f"parameter {name!r} is declared twice")
        if kind == "float":
            lo, hi, default = vals
            out.append(Param(name, name, default, lo, hi, (hi - lo) / 100.0,
                             doc="from the file's parameter block"))
            uniforms[name] = "float"
        elif kind == "bool":
            out.append(Param(name, name, BOOL_CHOICES[int(vals[0])], kind="choice",
                             choices=BOOL_CHOICES, doc="bool parameter (off = 0, on = 1)"))
            uniforms[name] = "bool"
        else:
            out.append(Param(name, name, tuple(vals), 0.0, max(1.0, *vals), 0.01, kind="rgb",
                             doc="colour parameter"))
            uniforms[name] = "vec3"
    return tuple(out), uniforms


def _kernel(shader: Shader, params: tuple[Param, ...], clamp: bool = True, /, *args,
            **values):
    """The shader on arrays of directions; ``clamp=False`` keeps negative values, NaN and inf
    (the model's ``raw_kernel``: the note on how much is clamped, ``tuibrdf check``).
    Positional-only, so a parameter may be called ``clamp``."""
    wi, wo = args
    uniforms = []
    for p in params:
        v = values[p.name]
        if p.kind == "choice":
            v = v == "on"
        uniforms.append(v)
    shape = np.broadcast_shapes(wi.shape[:-1], wo.shape[:-1])
    n = math.prod(shape)
    step = chunk_size(shader.steps)
    if n <= step:
        f = _run(shader, wi, wo, uniforms, shape, clamp)
    else:  # the generated code's temporaries live until a call returns: bounded chunks
        wi_f = np.broadcast_to(wi, shape + (3,)).reshape(n, 3)
        wo_f = np.broadcast_to(wo, shape + (3,)).reshape(n, 3)
        f = np.concatenate([_run(shader, wi_f[k:k + step], wo_f[k:k + step], uniforms,
                                 (min(step, n - k),), clamp) for k in range(0, n, step)])
        f = f.reshape(shape + f.shape[1:])
    below = (wi[..., 2] < 0.0) | (wo[..., 2] < 0.0)
    if below.any():
        f[np.broadcast_to(below, shape)] = 0.0
    return f


def _run(shader: Shader, wi, wo, uniforms: list, shape: tuple, clamp: bool) -> np.ndarray:
    """The shader on directions of ``shape``, made usable (module docstring); negative values
    kept unless ``clamp``."""
    L = (wi[..., 0], wi[..., 1], wi[..., 2])
    V = (wo[..., 0], wo[..., 1], wo[..., 2])
    with shader_errstate():  # the user's arithmetic: IEEE, made finite below
        out = shader.fn(L, V, *uniforms)
        if shader.returns == "vec3":
            f = np.empty(shape + (3,))
            for k, c in enumerate(out):
                f[..., k] = c
        else:
            f = np.array(np.broadcast_to(out, shape), dtype=float)
        if clamp:
            np.fmax(f, 0.0, out=f)  # negative → 0, and NaN → 0 (fmax ignores NaN)
            np.putmask(f, f == np.inf, 0.0)  # overflow → 0
    return f


def model_from_text(path: str, parsed: Parsed, title: str, name: str) -> Model:
    params, uniforms = declare(path, parsed.params)
    try:
        shader = compile_shader(parsed.shader, uniforms, parsed.shader_line)
    except GlslError as e:
        raise UserFileError(f"{path}:{e.line}: {e.message}") from None
    except RecursionError:
        raise UserFileError(f"{path}: the shader nests too deeply to compile") from None
    rgb = shader.returns == "vec3"
    return Model(
        name, title, params, partial(_kernel, shader, params, True), rgb=rgb, reciprocal=False,
        raw_kernel=partial(_kernel, shader, params, False),
        summary=f"BRDF Explorer file {os.path.basename(path)}",
        horizon="the shader's value (0 below the horizon; NaN, inf, negatives → 0)",
        notes=("GLSL compiled to numpy; undefined operations as docs/reference/formats.md says",),
    )


def _apply_overrides(path: str, params: tuple[Param, ...], overrides: dict) -> tuple:
    by_name = {p.name: p for p in params}
    out = dict(by_name)
    for name, (kind, vals, n) in overrides.items():
        p = by_name.get(name)
        if p is None:
            raise _err(path, n, unknown_message("parameter not in the referenced file:", name,
                                                list(by_name)))
        want = {"float": "float", "choice": "bool", "rgb": "color"}[p.kind]
        if kind != want:
            raise _err(path, n, f"{name} is a {want} parameter in the referenced file, not a "
                                f"{kind}")
        if kind == "float":
            value = vals[2]
        elif kind == "bool":
            value = BOOL_CHOICES[int(vals[0])]
        else:
            value = tuple(vals)
        try:
            value = p.validate(value)
        except ValueError as e:
            raise _err(path, n, str(e)) from None
        out[name] = replace(p, default=value)
    return tuple(out[p.name] for p in params)


def load_brdf(path: str, name: str) -> Model:
    """A ``.brdf`` file as a model named ``name``."""
    parsed = parse_file(path)
    if parsed.kind != "analytic":
        raise _err(path, 1, "a .brdf file must start with 'analytic' (this is a 'bparam' "
                            "file: name it .bparam)")
    return model_from_text(path, parsed, os.path.basename(path), name)


def load_bparam(path: str, name: str) -> Model:
    """A ``.bparam`` file: the referenced ``.brdf`` with the saved values as defaults."""
    parsed = parse_file(path)
    if parsed.kind != "bparam":
        raise _err(path, 1, "a .bparam file must start with 'bparam PATH'")
    target = parsed.target
    if not os.path.isabs(target):
        target = os.path.join(os.path.dirname(os.path.abspath(path)), target)
    if not target.lower().endswith(".brdf"):
        raise _err(path, 1, f"the referenced file {parsed.target!r} is not a .brdf file "
                            "(tuibrdf applies .bparam files to analytic .brdf files)")
    if not os.path.isfile(target):
        raise _err(path, 1, f"the referenced file {parsed.target!r} does not exist "
                            f"(looked for {target})")
    ref = parse_file(target)
    if ref.kind != "analytic":
        raise _err(target, 1, "the file a .bparam refers to must be an 'analytic' .brdf")
    overrides = {}
    for kind, pname, vals, n in parsed.params:
        if pname in overrides:
            raise _err(path, n, f"parameter {pname!r} is given twice")
        overrides[pname] = (kind, vals, n)
    title = f"{os.path.basename(path)} → {os.path.basename(target)}"
    m = model_from_text(target, ref, title, name)
    return replace(m, params=_apply_overrides(path, m.params, overrides))
