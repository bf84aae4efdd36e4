"""A material: a model with validated parameter values, as one immutable value.

``Material("phong", {"kd": 0.2})`` looks the model up once (a registry name, a user file, a
plugin: :func:`~tuibrdf.core.registry.get_model`), validates through :meth:`Model.resolve`
(defaults filled, ranges and constraints checked; ``ValueError`` otherwise), and holds the
:class:`~tuibrdf.core.params.Model` it validated against with the values in declaration order
as a tuple.  So a material is hashable and compares by value: it is the cache key of every
computed frame, and what the viewer, the renderers and the presets pass around instead of
``(name, values)`` pairs.  Reading :attr:`Material.model` looks nothing up: a model file
edited on disk does not change a material's model under its validated values; the viewer
makes a new material from the new file (:meth:`Material.refreshed`).
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from typing import Any

from tuibrdf.core.conventions import fmt_number
from tuibrdf.core.params import Model, Value
from tuibrdf.core.registry import MODELS, get_model


def file_stamp(name: str) -> tuple[int, int] | None:
    """``(mtime_ns, size)`` of the file a model name (an absolute path) was read from; None for
    a registered model or a file that cannot be stat'ed now."""
    if name in MODELS or not os.path.isabs(name):
        return None
    try:
        st = os.stat(name)
    except OSError:
        return None
    return (st.st_mtime_ns, st.st_size)


class Material:
    """``Material(model, params=None)``: immutable, validated, hashable."""

    __slots__ = ("name", "model", "items", "stamp", "_hash")
    name: str
    #: the model the values were validated against (looked up once, when made)
    model: Model
    items: tuple[tuple[str, Value], ...]

    def __init__(self, model: str | Model, params: Mapping[str, Any] | None = None) -> None:
        m = get_model(model)
        # a model read from a file: the file's (mtime, size) when read, so an edited file
        # makes another material (another cache key) once re-read; None for the others
        self._hold(m, m.resolve(params), file_stamp(m.name))

    def _hold(self, m: Model, values: Mapping[str, Value], stamp: tuple[int, int] | None
              ) -> None:
        object.__setattr__(self, "name", m.name)
        object.__setattr__(self, "model", m)
        object.__setattr__(self, "items", tuple((p.name, values[p.name]) for p in m.params))
        object.__setattr__(self, "stamp", stamp)
        object.__setattr__(self, "_hash", hash((self.name, self.items, self.stamp)))

    def __setattr__(self, key: str, value: Any) -> None:
        raise AttributeError("a Material is immutable: use with_values()")

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Material):
            return NotImplemented
        # the same model object too: a Model passed in may share a registered model's name
        return (self.model is other.model and (self.name, self.items, self.stamp)
                == (other.name, other.items, other.stamp))

    def __hash__(self) -> int:
        return self._hash

    def __repr__(self) -> str:
        return f"Material({self.name!r}, {self.values!r})"

    @property
    def values(self) -> dict[str, Value]:
        """The resolved values (user units), a fresh dict in declaration order."""
        return dict(self.items)

    @property
    def label(self) -> str:
        """The name a title shows: a model read from a file by its file name (``ggx.brdf``),
        not its absolute path."""
        if self.stamp is not None or os.path.isabs(self.name):
            return os.path.basename(self.name)
        data = dict(self.items).get("file")  # measured data (merl): the data file's name
        return os.path.basename(str(data)) if data else self.name

    def refreshed(self) -> Material:
        """This material again if its model file is unchanged on disk, else re-read (a new
        material; ``ValueError`` when the edited file is no longer valid)."""
        if self.stamp is None or file_stamp(self.name) == self.stamp:
            return self
        return Material(self.name, self.values)

    def with_values(self, **changes: Any) -> Material:
        """A new material of the same model (and file stamp) with some values changed
        (validated; ``ValueError`` otherwise)."""
        new = object.__new__(Material)
        new._hold(self.model, self.model.resolve({**self.values, **changes}), self.stamp)
        return new

    def describe(self) -> str:
        """``phong kd=0.2 ks=0.5 n=20`` — for titles and messages."""
        vals = " ".join(f"{k}={fmt_number(os.path.basename(v) if k == 'file' else v)}"
                        for k, v in self.items)
        return f"{self.label} {vals}".strip()
