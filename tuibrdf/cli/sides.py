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


def add_compare_args(parser) -> None:
    """``--compare B`` and ``-q/--param-b NAME=VALUE`` (view and render)."""
    parser.add_argument("--compare", metavar="B",
                        help="compare with B (model name, file or material:NAME[:abc|sgd]): "
                             "both side by side, with the numbers of 'tuibrdf compare'")
    parser.add_argument("-q", "--param-b", action="append", default=[], metavar="NAME=VALUE",
                        help="with --compare: set a parameter of B (repeatable)")


def compare_side(args) -> tuple[Model, dict[str, Any]] | None:
    """B of ``--compare`` (None without it); ``-q`` without ``--compare`` is an error."""
    if getattr(args, "compare", None) is None:
        if getattr(args, "param_b", None):
            raise UsageError("-q sets a parameter of B: it needs --compare B")
        return None
    if getattr(args, "preset", None):
        raise UsageError("--preset and --compare both choose what to show: give one")
    return side(args.compare, args.param_b)


def sides_of(args) -> tuple[tuple[Model, dict[str, Any]], tuple[Model, dict[str, Any]] | None]:
    """A and B (None: no comparison) of ``render``: ``MODEL [-p …]`` and ``--compare B
    [-q …]``, or ``--preset NAME`` (a seed comparison or a saved preset, read as ``view``
    reads it)."""
    if not args.model and not getattr(args, "preset", None):
        raise UsageError("give a MODEL (see 'tuibrdf models') or --preset NAME")
    other = compare_side(args)
    if getattr(args, "preset", None):
        if args.model or args.param:
            raise UsageError("--preset chooses the sides: drop MODEL and -p")
        return preset_sides(args.preset, getattr(args, "trust", False))
    return side(args.model, args.param), other


def preset_sides(name: str, trust: bool = False) -> tuple[tuple[Model, dict[str, Any]],
                                                         tuple[Model, dict[str, Any]] | None]:
    """The sides of preset ``name``: a saved preset (``s`` in the viewer), or else one of the
    seed's comparisons (``diffuse``, ``specular``), as ``view --preset`` finds them.  A preset
    that names a ``.py`` model file loads only with ``trust`` (its code runs)."""
    import os

    from tuibrdf.state.presets import (
        PresetError,
        find_preset,
        list_presets,
        load_preset,
        where_presets_are,
    )
    from tuibrdf.state.viewer import COMPARE_PRESETS

    seed = {p.name: p for p in COMPARE_PRESETS}
    try:
        path = find_preset(name)
        if os.path.lexists(path) or name not in seed:
            if not os.path.lexists(path):
                have = ", ".join(list_presets() + sorted(seed))
                raise UsageError(f"no preset named {name!r} in {where_presets_are()} "
                                 f"(available: {have})")
            _, loaded, _look = load_preset(name, trust)
            pairs = [(x.spec, dict(x.values)) for x in loaded]
        else:
            pairs = [(find_model(m), find_model(m).resolve(v))
                     for m, v in (seed[name].a, seed[name].b)]
    except PresetError as e:
        raise UsageError(str(e)) from None
    return pairs[0], (pairs[1] if len(pairs) > 1 else None)
