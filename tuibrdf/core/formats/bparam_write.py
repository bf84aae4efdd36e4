"""Writing BRDF Explorer ``.bparam`` files (its "save parameters"): the values of a ``.brdf``
model's parameters, in the format :func:`tuibrdf.core.formats.brdf_explorer.load_bparam`
reads and BRDF Explorer loads::

    bparam ward.brdf

    ::begin parameters
    float alpha_x 0.01 1 0.15
    bool isotropic 1
    color Cd 0.2 0.2 0.2
    ::end parameters

The first line names the ``.brdf`` file, relative to the ``.bparam`` file's folder when it
can be (else absolute).  A float keeps its declared range; values are written with ``repr``,
so they load back exactly.  A model from a ``.bparam`` file is saved against the ``.brdf``
file that one refers to.
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Mapping
from typing import Any

from tuibrdf.core.formats.files import UserFileError
from tuibrdf.core.params import Model


def _num(v: float) -> str:
    text = repr(float(v))
    return text[:-2] if text.endswith(".0") else text


def source_brdf(model: Model) -> str | None:
    """The ``.brdf`` file whose parameters ``model`` has (its own file, or the one its
    ``.bparam`` file refers to), or None for a model that is not from BRDF Explorer."""
    name = model.name
    low = name.lower()
    if low.endswith(".brdf"):
        return name
    if low.endswith(".bparam"):
        from tuibrdf.core.formats.brdf_explorer import parse_file

        target = parse_file(name).target
        if not os.path.isabs(target):
            target = os.path.join(os.path.dirname(os.path.abspath(name)), target)
        return target
    return None


def bparam_text(brdf: str, out: str, model: Model, values: Mapping[str, Any]) -> str:
    """The text of a ``.bparam`` file at ``out`` holding ``values`` for ``brdf``."""
    try:
        ref = os.path.relpath(os.path.abspath(brdf), os.path.dirname(os.path.abspath(out)))
    except ValueError:  # another drive (Windows)
        ref = os.path.abspath(brdf)
    lines = [f"bparam {ref}", "", "::begin parameters"]
    for p in model.params:
        v = values[p.name]
        if p.is_bool:
            lines.append(f"bool {p.name} {1 if v == 'on' else 0}")
        elif p.kind == "rgb":
            lines.append(f"color {p.name} " + " ".join(_num(c) for c in v))
        else:
            lines.append(f"float {p.name} {_num(p.min)} {_num(p.max)} {_num(v)}")
    return "\n".join([*lines, "::end parameters", ""])


def write_bparam(model: Model, values: Mapping[str, Any], out: str) -> str:
    """Write ``values`` of a BRDF Explorer model to the ``.bparam`` file ``out`` (atomically:
    a temporary file, then a rename); returns the path.  :class:`UserFileError` (one line)
    for a model not from a ``.brdf`` file, or a file that cannot be written."""
    brdf = source_brdf(model)
    if brdf is None:
        raise UserFileError(f"{out}: a .bparam file holds the parameters of a BRDF Explorer "
                            f".brdf model, and {model.name} is not one")
    if "\n" in brdf or "\r" in brdf:
        raise UserFileError(f"{out}: the .brdf file's path has a line break")
    text = bparam_text(brdf, out, model, values)
    folder = os.path.dirname(os.path.abspath(out))
    tmp = ""
    try:
        fd, tmp = tempfile.mkstemp(prefix=".bparam.", suffix=".partial", dir=folder)
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            f.write(text)
        os.replace(tmp, out)
    except OSError as e:
        if tmp:
            try:
                os.unlink(tmp)
            except OSError:
                pass
        raise UserFileError(f"{out}: cannot write: {e.strerror or e}") from None
    return out
