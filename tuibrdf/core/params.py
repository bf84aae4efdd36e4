"""Parameter declarations: each model declares its parameters once, here is the vocabulary.

Everything user-facing is generated from these declarations: CLI ``-p NAME=VALUE`` parsing and
its error messages, the UI parameter panel and its key steps, validation in
:func:`tuibrdf.evaluate`, and ``tuibrdf models``.

Kinds of parameter:

========  ================================  =========================================
kind      value                             notes
========  ================================  =========================================
float     a real in ``[min, max]``          ``unit == "deg"`` is converted to radians
                                            before it reaches a kernel
rgb       three reals in ``[min, max]``     one panel row per channel
choice    one of ``choices``                cycled with +/- in the UI; a *bool* is the
                                            choice ``off``/``on`` (:data:`BOOL_CHOICES`),
                                            which also accepts 0/1, true/false, yes/no
path      a file path                       the MERL file
========  ================================  =========================================
"""

from __future__ import annotations

import difflib
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from tuibrdf.core.conventions import fmt_number

Value = float | tuple[float, float, float] | str

#: a bool parameter is the choice ``off``/``on``; :func:`parse_bool` reads the other spellings
BOOL_CHOICES = ("off", "on")
_BOOL_WORDS = {"0": "off", "1": "on", "off": "off", "on": "on", "false": "off", "true": "on",
               "no": "off", "yes": "on"}


def parse_bool(value: Any) -> str | None:
    """``"on"``/``"off"`` for any spelling of a switch (0/1, true/false, on/off, yes/no, any
    case, Python ``True``/``False`` and the ints/floats 0 and 1), else None — the one parser
    for CLI ``-p``, the Python API, presets and typed values."""
    if isinstance(value, bool):
        return "on" if value else "off"
    if isinstance(value, int | float):
        return "on" if value == 1 else "off" if value == 0 else None
    if isinstance(value, str):
        return _BOOL_WORDS.get(value.strip().lower())
    return None


@dataclass(frozen=True)
class Param:
    """One model parameter, declared once."""

    name: str
    symbol: str
    default: Value
    min: float = 0.0
    max: float = 1.0
    step: float = 0.01
    unit: str = ""
    doc: str = ""
    kind: str = "float"  # float | rgb | choice | path
    choices: tuple[str, ...] = ()
    #: coarse step (shift + key); defaults to 10 steps
    coarse: float | None = None
    #: other accepted spellings of a choice, ``((alias, canonical), ...)``; validation maps
    #: an alias to its canonical choice (e.g. the names the SGD paper's data uses)
    aliases: tuple[tuple[str, str], ...] = ()
    #: for a long list of choices: the text errors and listings show instead of all of them
    choices_doc: str = ""
    #: step by a factor instead of a constant (roughness, exponents: a value spanning
    #: decades); the fine step multiplies by 1.1, the coarse one by 2
    relative: bool = False

    @property
    def coarse_step(self) -> float:
        return self.coarse if self.coarse is not None else 10 * self.step

    def range_text(self) -> str:
        """The valid values, as every error message and listing shows them."""
        if self.is_bool:
            return "on/off (also 1/0, true/false, yes/no)"
        if self.kind == "choice":
            return self.choices_doc or "one of " + ", ".join(self.choices)
        if self.kind == "path":
            return "a file path"
        unit = "°" if self.unit == "deg" else (f" {self.unit}" if self.unit else "")
        rng = f"[{fmt_number(self.min)}, {fmt_number(self.max)}]{unit}"
        return f"three values in {rng} (R,G,B)" if self.kind == "rgb" else f"in {rng}"

    def validate(self, value: Any, model: str = "") -> Value:
        """Return the canonical value, or raise ``ValueError`` naming the parameter and range."""
        where = f"{model}: " if model else ""
        bad = f"{where}{self.name} = {value!r} is invalid: expected {self.range_text()}"
        if self.kind == "choice":
            canonical = self.choice(value)
            if canonical is not None:
                return canonical
            if self.choices_doc and isinstance(value, str):
                raise ValueError(self.unknown_choice(value, model))
            raise ValueError(bad)
        if self.kind == "path":
            if isinstance(value, str | bytes) or hasattr(value, "__fspath__"):
                return str(value)
            raise ValueError(bad)
        if self.kind == "rgb":
            if isinstance(value, str):
                value = value.split(",")
            if isinstance(value, int | float):
                value = (value,) * 3  # a grey
            try:
                vals = tuple(float(v) for v in value)
            except (TypeError, ValueError):
                raise ValueError(bad) from None
            if len(vals) != 3 or not all(self._in_range(v) for v in vals):
                raise ValueError(bad)
            return vals
        try:
            v = float(value)
        except (TypeError, ValueError):
            raise ValueError(bad) from None
        if not self._in_range(v):
            raise ValueError(bad)
        return v

    @property
    def is_bool(self) -> bool:
        return self.kind == "choice" and self.choices == BOOL_CHOICES

    def choice(self, value: Any) -> str | None:
        """The canonical choice ``value`` names (case-insensitive, aliases mapped), or None."""
        if self.is_bool:
            return parse_bool(value)
        if not isinstance(value, str):
            return None
        v = value.lower()
        if v in self.choices:
            return v
        return dict(self.aliases).get(v)

    def unknown_choice(self, value: str, model: str = "") -> str:
        """``abc: material: unknown choice 'x' (did you mean 'y'?); valid: ...`` — the valid
        names, or :attr:`choices_doc` when there are too many to list on one line."""
        where = f"{model}: " if model else ""
        names = [*self.choices, *(a for a, _ in self.aliases)]
        msg = unknown_message(f"{where}{self.name}: unknown choice", value, names)
        if self.is_bool:
            msg = msg[: msg.index("; valid: ")] + f"; valid: {self.range_text()}"
        elif self.choices_doc:
            msg = msg[: msg.index("; valid: ")] + f"; valid: {self.choices_doc}"
        return msg

    def _in_range(self, v: float) -> bool:
        return math.isfinite(v) and self.min <= v <= self.max

    def to_kernel(self, value: Value) -> Any:
        """Convert a validated user value to the kernel's unit (degrees → radians)."""
        if self.kind == "float" and self.unit == "deg":
            return math.radians(value)
        return value


@dataclass(frozen=True)
class Constraint:
    """A relation between parameters, e.g. ``kd + ks ≤ 1`` (checked with a 1e-9 slack so that
    0.3 + 0.7 passes despite rounding)."""

    text: str
    names: tuple[str, ...]
    check: Callable[..., bool]

    def holds(self, values: Mapping[str, Value]) -> bool:
        return bool(self.check(*(values[n] for n in self.names)))


def sum_at_most_one(*names: str) -> Constraint:
    return Constraint(" + ".join(names) + " ≤ 1", tuple(names), lambda *v: sum(v) <= 1 + 1e-9)


@dataclass(frozen=True)
class Model:
    """A registered reflectance model.

    ``kernel(wi, wo, **kernel_params)`` receives unit directions of shape ``(..., 3)``
    (broadcast against each other) and parameters in kernel units; it returns ``(...)`` for a
    scalar model or ``(..., 3)`` for an RGB one, finite and ≥ 0 everywhere.
    """

    name: str
    title: str
    params: tuple[Param, ...]
    kernel: Callable[..., Any]
    rgb: bool = False
    reciprocal: bool = True
    constraints: tuple[Constraint, ...] = ()
    summary: str = ""
    #: what the model returns on the horizon, for docs and `tuibrdf models`
    horizon: str = ""
    notes: tuple[str, ...] = field(default=())
    #: importance sampling, if the model has it: an object with ``sample(wi, u1, u2,
    #: **kernel_params) -> (wo, pdf)`` and ``pdf(wi, wo, **kernel_params)``
    #: (:mod:`tuibrdf.core.brdf.sampling`; ``tuibrdf check`` runs its χ² test)
    sampler: Any = None
    #: a user file's kernel *before* negative values are clamped to 0 (None: a built-in
    #: model), for the note saying how much is clamped (:mod:`tuibrdf.core.negatives`)
    raw_kernel: Callable[..., Any] | None = None
    #: the function its albedo integrates, ``(wi, wo) -> f``, when it is not the kernel (a
    #: ``.bsdf`` file's own f, all the way to the horizon: :func:`tuibrdf.core.formats.
    #: rgl_bsdf.load_model`); None: the kernel
    albedo_kernel: Callable[..., Any] | None = None
    #: its values are measurements (a MERL table, an RGL ``.bsdf`` file): a comparison's
    #: reference against a model (:func:`tuibrdf.core.sphere.compare.reference_side`), and
    #: measured data's albedo budget (:func:`tuibrdf.core.sphere.albedo.albedo_rule`)
    measured: bool = False

    def param(self, name: str) -> Param:
        for p in self.params:
            if p.name == name:
                return p
        raise ValueError(unknown_message(f"{self.name}: unknown parameter", name,
                                         [p.name for p in self.params]))

    def defaults(self) -> dict[str, Value]:
        return {p.name: p.default for p in self.params}

    def resolve(self, params: Mapping[str, Any] | None = None) -> dict[str, Value]:
        """Validate ``params`` (user units), fill defaults, check constraints."""
        values = self.defaults()
        for name, value in (params or {}).items():
            values[name] = self.param(name).validate(value, self.name)
        for c in self.constraints:
            if not c.holds(values):
                got = ", ".join(f"{n} = {fmt_number(values[n])}" for n in c.names)
                raise ValueError(f"{self.name}: constraint {c.text} violated ({got})")
        return values

    def kernel_params(self, values: Mapping[str, Value]) -> dict[str, Any]:
        return {p.name: p.to_kernel(values[p.name]) for p in self.params}


def unknown_message(what: str, name: str, valid: Sequence[str]) -> str:
    """``unknown X 'nme' (did you mean 'name'?); valid: a, b, c``."""
    close = difflib.get_close_matches(name, list(valid), n=1)
    hint = f" (did you mean {close[0]!r}?)" if close else ""
    return f"{what} {name!r}{hint}; valid: {', '.join(valid)}"
