"""A material: one registered model with validated parameter values, as one immutable value.

``Material("phong", {"kd": 0.2})`` validates through :meth:`Model.resolve` (defaults filled,
ranges and constraints checked; ``ValueError`` otherwise) and stores the values in declaration
order as a tuple, so a material is hashable and compares by value: it is the cache key of
every computed frame, and what the viewer, the renderers and the presets pass around instead
of ``(name, values)`` pairs.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from .models import get_model
from .params import Model, Value, _fmt


class Material:
    """``Material(model, params=None)``: immutable, validated, hashable."""

    __slots__ = ("name", "items", "_hash")
    name: str
    items: tuple[tuple[str, Value], ...]

    def __init__(self, model: str | Model, params: Mapping[str, Any] | None = None) -> None:
        m = get_model(model)
        values = m.resolve(params)
        object.__setattr__(self, "name", m.name)
        object.__setattr__(self, "items", tuple((p.name, values[p.name]) for p in m.params))
        object.__setattr__(self, "_hash", hash((self.name, self.items)))

    def __setattr__(self, key: str, value: Any) -> None:
        raise AttributeError("a Material is immutable: use with_values()")

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Material):
            return NotImplemented
        return self.name == other.name and self.items == other.items

    def __hash__(self) -> int:
        return self._hash

    def __repr__(self) -> str:
        return f"Material({self.name!r}, {self.values!r})"

    @property
    def model(self) -> Model:
        return get_model(self.name)

    @property
    def values(self) -> dict[str, Value]:
        """The resolved values (user units), a fresh dict in declaration order."""
        return dict(self.items)

    def with_values(self, **changes: Any) -> Material:
        """A new material with some values changed (validated; ``ValueError`` otherwise)."""
        return Material(self.name, {**self.values, **changes})

    def describe(self) -> str:
        """``phong kd=0.2 ks=0.5 n=20`` — for titles and messages."""
        vals = " ".join(f"{k}={_fmt(v)}" for k, v in self.items)
        return f"{self.name} {vals}".strip()
