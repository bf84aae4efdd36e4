"""The compile-time and run-time budgets of a shader: a ``.brdf`` file is hostile input, and a
short one can ask for unbounded work (a helper specialised for ever more constant arguments, a
call tree that doubles at every level).  Each budget is checked while compiling, before the
work is done, and refused with one :class:`GlslError` naming the line.

The numbers are generous for real files: the largest shader BRDF Explorer ships (Disney's,
3.2 KB) compiles to 276 lines with one specialised copy, makes 3 calls and runs 276 lines per
value.  docs/reference/formats.md lists them for users.
"""

from __future__ import annotations

from tuibrdf.core.formats.glsl.errors import GlslError

#: a ``.brdf``/``.bparam`` file's size, bytes (parsing costs ≈ 4 µs a byte)
MAX_FILE_BYTES = 128 * 1024
#: specialised copies of one function (its constant arguments folded), and of all functions
MAX_COPIES_PER_FUNCTION = 32
MAX_COPIES = 256
#: lines of generated Python, all functions together
MAX_GENERATED_LINES = 10_000
#: function calls made to evaluate BRDF once (the call tree's size, BRDF included)
MAX_CALLS = 1_000
#: generated lines run to evaluate BRDF once (each line is one array operation)
MAX_STEPS = 10_000
#: the generated code keeps every temporary of a call alive until it returns (up to 3 arrays a
#: line, 8 bytes an element): directions are evaluated in chunks of at most this many bytes of
#: temporaries, at least 256 directions a chunk (see :func:`chunk_size`)
MAX_TEMP_BYTES = 64 * 1024 * 1024


def chunk_size(steps: int) -> int:
    """Directions per evaluation of a shader that runs ``steps`` lines a value: its temporaries
    (≤ 3 arrays a line, 8 bytes an element) then take at most :data:`MAX_TEMP_BYTES` (about 256
    directions for a shader at :data:`MAX_STEPS`, 10,000 for Disney's)."""
    return max(256, MAX_TEMP_BYTES // (24 * max(steps, 1)))


def check_run_cost(graph: dict[str, tuple[str, int, int, list[str]]], entry: str) -> int:
    """Refuse a shader whose one evaluation runs more than :data:`MAX_CALLS` calls or
    :data:`MAX_STEPS` lines; returns the lines it runs.  ``graph`` maps a generated function
    to ``(GLSL name, line, its own lines, the generated functions it calls, one entry per call
    site)``; recursion was refused before, so the graph has no cycle.  Costs are summed bottom
    up, and the first function over a budget is named (the one whose callees are all within
    it)."""
    cost: dict[str, tuple[int, int]] = {}

    def visit(fn: str) -> tuple[int, int]:
        if fn in cost:
            return cost[fn]
        name, line, own, callees = graph[fn]
        calls, steps = 1, own
        for c in callees:
            c_calls, c_steps = visit(c)
            calls += c_calls
            steps += c_steps
            if calls > MAX_CALLS:
                raise GlslError(f"the call tree is too large: one evaluation of '{name}' makes "
                                f"over {MAX_CALLS:,} function calls (budget; a helper called "
                                "twice by one called twice counts four times)", line)
            if steps > MAX_STEPS:
                raise GlslError(f"too much work per value: one evaluation of '{name}' runs "
                                f"over {MAX_STEPS:,} operations (budget), counting every "
                                "call of its helpers", line)
        cost[fn] = (calls, steps)
        return cost[fn]

    # bottom-up without deep Python recursion: callees first, in an explicit order
    order: list[str] = []
    seen: set[str] = set()
    stack = [(entry, False)]
    while stack:
        fn, done = stack.pop()
        if done:
            order.append(fn)
            continue
        if fn in seen:
            continue
        seen.add(fn)
        stack.append((fn, True))
        stack.extend((c, False) for c in graph[fn][3] if c not in seen)
    for fn in order:
        visit(fn)
    return cost[entry][1]  # the lines one evaluation runs
