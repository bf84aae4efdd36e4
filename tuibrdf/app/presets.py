"""Saved parameter sets: one small TOML file per preset (no Textual).

Files live in ``$XDG_CONFIG_HOME/tuibrdf/presets/NAME.toml`` (``~/.config`` when the variable
is unset), are read with :mod:`tomllib`, and are written atomically (a temporary file in the
same directory, then :func:`os.replace`), so a crash never leaves half a preset behind.  A
preset holds θi and one or two sides (two in compare mode)::

    # tuibrdf preset
    theta_i = 45.0

    [[sides]]
    model = "phong"
    params = { kd = 0.0, ks = 0.08, n = 70.0 }

A malformed file raises :class:`PresetError` with a one-line message naming the file.
"""

from __future__ import annotations

import json
import math
import os
import re
import tempfile
import tomllib
from pathlib import Path
from typing import Any

from ..core.models import get_model
from .state import THETA_MAX, THETA_MIN, Side, ViewerState

NAME_RE = re.compile(r"^[A-Za-z0-9_][A-Za-z0-9_.-]{0,63}$")


class PresetError(ValueError):
    """A preset that cannot be saved or loaded (bad name, unreadable or malformed file)."""


def preset_dir() -> Path:
    base = os.environ.get("XDG_CONFIG_HOME") or os.path.join(os.path.expanduser("~"), ".config")
    return Path(base) / "tuibrdf" / "presets"


def preset_path(name: str) -> Path:
    if not NAME_RE.match(name):
        raise PresetError(f"preset name {name!r} is invalid: use letters, digits, _ . - "
                          "(at most 64 characters)")
    return preset_dir() / f"{name}.toml"


def list_presets() -> list[str]:
    d = preset_dir()
    if not d.is_dir():
        return []
    return sorted(p.stem for p in d.glob("*.toml") if NAME_RE.match(p.stem))


# -- writing: a tiny TOML emitter for the few types a preset holds ---------------------------
def _toml_value(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int | float):
        v = float(v)
        if not math.isfinite(v):  # validated values are finite; TOML's inf/nan would load back
            raise PresetError(f"cannot save a non-finite value {v!r}")
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v)  # a JSON string (\" \\ \uXXXX escapes) is a TOML basic string
    if isinstance(v, tuple | list):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    raise PresetError(f"cannot save a value of type {type(v).__name__}")


def _key(k: str) -> str:
    return k if re.match(r"^[A-Za-z0-9_-]+$", k) else json.dumps(k)


def to_toml(state: ViewerState) -> str:
    lines = ["# tuibrdf preset", f"theta_i = {_toml_value(state.theta_i)}"]
    for side in state.sides:
        params = ", ".join(f"{_key(k)} = {_toml_value(v)}" for k, v in side.values.items())
        lines += ["", "[[sides]]", f"model = {_toml_value(side.model)}",
                  f"params = {{ {params} }}"]
    return "\n".join(lines) + "\n"


def save_preset(state: ViewerState, name: str) -> Path:
    """Write ``state`` as preset ``name`` atomically; return the path."""
    path = preset_path(name)
    text = to_toml(state)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{name}.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            f.write(text)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return path


# -- reading ------------------------------------------------------------------------------
def from_toml(text: str, where: str = "preset") -> tuple[float, list[Side]]:
    """Parse and validate a preset: ``(theta_i, sides)``.  Raises :class:`PresetError`."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise PresetError(f"{where}: not valid TOML ({e})") from None
    theta = data.get("theta_i", 30.0)
    if isinstance(theta, bool) or not isinstance(theta, int | float) \
            or not THETA_MIN <= theta <= THETA_MAX:
        raise PresetError(f"{where}: theta_i = {theta!r} is invalid: expected a number in [0, 90]")
    raw = data.get("sides")
    if not isinstance(raw, list) or not 1 <= len(raw) <= 2:
        raise PresetError(f"{where}: expected one or two [[sides]] tables")
    sides = []
    for entry in raw:
        if not isinstance(entry, dict) or not isinstance(entry.get("model"), str):
            raise PresetError(f"{where}: each [[sides]] needs model = \"NAME\"")
        params = entry.get("params", {})
        if not isinstance(params, dict):
            raise PresetError(f"{where}: params must be a table")
        try:
            model = get_model(entry["model"])
            sides.append(Side(model.name, model.resolve(params)))
        except ValueError as e:
            raise PresetError(f"{where}: {e}") from None
    return float(theta), sides


def load_preset(name: str) -> tuple[float, list[Side]]:
    path = preset_path(name)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        have = list_presets()
        hint = f"; saved presets: {', '.join(have)}" if have else ""
        raise PresetError(f"no preset named {name!r} in {path.parent}{hint}") from None
    except (OSError, UnicodeDecodeError) as e:
        raise PresetError(f"cannot read {path}: {e}") from None
    return from_toml(text, str(path))


def apply_loaded(state: ViewerState, theta_i: float, sides: list[Side]) -> None:
    """Put a loaded preset into ``state`` (compare mode iff it has two sides)."""
    state.theta_i = theta_i
    state.sides = sides
    state.active = 0
    state.preset = ""
    for s in sides:
        state.memory[s.model] = dict(s.values)
