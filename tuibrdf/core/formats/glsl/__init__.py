"""A compiler from the GLSL subset of BRDF Explorer shaders to vectorised numpy.

BRDF Explorer (Disney, github.com/wdas/brdf) pastes a ``.brdf`` file's shader section into a
fragment-shader template and calls ``vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)``.
This package parses that shader (tokenizer + recursive descent) and generates Python source
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

The modules, bottom up (each imports only modules above it here): a shader goes through the
lexer, the parser and the compiler, and the code it becomes calls the runtime.

==================  ========================================================================
:mod:`.errors`      :class:`GlslError`, raised by every stage with the line in the file
:mod:`.lexer`       the shader's text → tokens
:mod:`.syntax`      the syntax tree; the subset's types, reserved words, refused constructs
:mod:`.parser`      tokens → syntax tree (recursive descent)
:mod:`.emitter`     the compiler's values and primitives: fresh names, emitted lines,
                    arithmetic with constants folded
:mod:`.builtins`    the built-in functions: names and signatures as tables, and their code
:mod:`.runtime`     what the generated code calls
:mod:`.compiler`    syntax tree → the Python source of one kernel; :func:`compile_shader`,
                    the whole pipeline
==================  ========================================================================
"""

from tuibrdf.core.formats.glsl.builtins import BUILTIN_NAMES
from tuibrdf.core.formats.glsl.compiler import Shader, compile_shader
from tuibrdf.core.formats.glsl.errors import GlslError
from tuibrdf.core.formats.glsl.syntax import RESERVED

__all__ = ["BUILTIN_NAMES", "RESERVED", "GlslError", "Shader", "compile_shader"]
