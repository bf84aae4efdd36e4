"""One side of a comparison from the command line: ``SPEC`` and its ``NAME=VALUE`` tokens.

``SPEC`` is a model name (``tuibrdf models``), a file (``.brdf``, ``.bparam``, ``.py``,
``.bsdf``, ``.binary``: a ``.binary`` is the ``merl`` model with ``file=PATH``) or
``material:NAME[:abc|sgd]``, a MERL material's published fit (ABC by default).  Used by
``tuibrdf compare``, ``view --compare`` and ``render --compare``.
"""

from __future__ import annotations

from tuibrdf.cli.common import UsageError, find_model, parse_params

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Any

    from tuibrdf.core.params import Model

FITS = ("abc", "sgd")


def side(spec: str, tokens: list[str]) -> tuple[Model, dict[str, Any]]:
    """The model ``spec`` names and its validated values; :class:`UsageError` (or the
    formats' ``ValueError``) for bad input, one line."""
    tokens = list(tokens)
    if spec.startswith("material:"):
        parts = spec.split(":")
        if len(parts) not in (2, 3) or not parts[1]:
            raise UsageError(f"{spec!r}: expected material:NAME or material:NAME:abc|sgd")
        fit = parts[2].lower() if len(parts) == 3 else "abc"
        if fit not in FITS:
            raise UsageError(f"{spec!r}: unknown fit {parts[2]!r}; expected abc or sgd")
        spec, tokens = fit, [f"material={parts[1]}", *tokens]
    elif spec.lower().endswith(".binary"):
        from tuibrdf.core.formats.files import describe

        problem = describe(spec)  # "no such file", "is a directory, ..."
        if problem:
            raise UsageError(f"{spec}: {problem}")
        spec, tokens = "merl", [f"file={spec}", *tokens]
    model = find_model(spec)
    values = model.resolve(parse_params(model, tokens))
    for p in model.params:  # a bad MERL file is one line here, read whole as `eval` does
        if p.kind == "path" and model.name == "merl":
            from tuibrdf.core.formats.merl import check_file, load_cached

            check_file(values[p.name])
            load_cached(values[p.name])
    return model, values
