"""Saved parameter sets: one small TOML file per preset (no Textual).

Presets are saved in :func:`preset_dir`, ``platformdirs.user_config_path("tuibrdf") /
"presets"`` (on Linux ``$XDG_CONFIG_HOME/tuibrdf/presets``, ``~/.config`` when the variable is
unset; on macOS ``~/Library/Application Support/tuibrdf/presets``), as ``NAME.toml``.  They are
read from there and from where earlier versions saved them on every system,
``$XDG_CONFIG_HOME/tuibrdf/presets`` or ``~/.config/tuibrdf/presets`` (:func:`legacy_preset_dir`;
the same directory on Linux), so no preset is lost; a name in both is the new one.  Files are
read with :mod:`tomllib` and written atomically (a temporary file in the same directory, then
:func:`os.replace`), so a crash never leaves half a preset behind.  A
preset holds θi, the look (:data:`LOOK`: the main view, φi, ψ, log scale, colour map,
channel, exposure, gamma, the fixed angles, the solid's camera) and one or two sides (two in
compare mode)::

    # tuibrdf preset
    theta_i = 45.0

    [look]
    view = "sphere"
    phi_i = 180.0
    log = true
    ...

    [[sides]]
    model = "phong"
    params = { kd = 0.0, ks = 0.08, n = 70.0 }

A malformed file raises :class:`PresetError` with a one-line message naming the file: the
reader checks that the path is a regular file of at most :data:`MAX_BYTES` before opening it
(a FIFO never blocks it, see :mod:`tuibrdf.core.formats.files`), and a hostile TOML document (a
400-digit integer, 600-deep nesting, a 5 000-digit number) is a message, not an exception.
Saving and listing remove temporary files that a killed save left behind (``.NAME.*.partial``,
older than :data:`STALE_SECONDS`); a failed save (read-only or full disk, the presets path is
a file) is a :class:`PresetError` too.  A preset without ``[look]`` (saved by an earlier
version) loads as before: θi and the sides, the rest of the look left as it is; a look key
this version does not know is ignored (a newer version's preset still loads).

A side whose model is a ``.py`` file would run that file's code when the preset is loaded:
:func:`load_preset` refuses such a preset (:class:`PresetRunsCode`, before importing anything)
unless the caller allows that file (``allow_code``: the files the user named, or True for
``--trust``).  Strings are written as UTF-8 TOML strings, so any path round-trips (😀 too).

Nothing here blocks for long, but it does touch the disk: a caller with an event loop runs
:func:`load_preset` and :func:`save_preset` in a worker thread.
"""

from __future__ import annotations

import json
import math
import os
import re
import tempfile
import time
from pathlib import Path
from typing import Any, NamedTuple

from tuibrdf.core.display import DISPLAY
from tuibrdf.core.formats.files import read_regular
from tuibrdf.core.registry import get_model
from tuibrdf.render import CMAPS
from tuibrdf.state import sandbox
from tuibrdf.state.viewer import CHANNEL_NAMES, MAIN_VIEWS, Side, ViewerState

NAME_RE = re.compile(r"^[A-Za-z0-9_][A-Za-z0-9_.-]{0,63}$")


#: a preset is a few hundred bytes; anything much larger is not one
MAX_BYTES = 64 * 1024
#: suffix of the temporary file a save writes before renaming it (recognisable, so a stale one
#: left by a killed save can be removed)
TMP_SUFFIX = ".partial"
#: a temporary file older than this is left over from a killed save (a save takes milliseconds)
STALE_SECONDS = 60.0


#: the look a preset remembers: :class:`ViewerState` attributes; numbers with their
#: :data:`DISPLAY` range, switches, and names from a list
LOOK_NUMBERS = ("phi_i", "section_azimuth", "exposure", "gamma", "theta_d", "theta_h", "phi_d",
                "azimuth", "elevation")
LOOK_FLAGS = ("log", "cosine", "sqrt_h", "slice_log")
LOOK_NAMES = {"view": MAIN_VIEWS, "cmap": CMAPS, "channel": tuple(CHANNEL_NAMES)}
LOOK = (*LOOK_NAMES, *LOOK_NUMBERS, *LOOK_FLAGS)


class Preset(NamedTuple):
    """A loaded preset: θi, the sides, and the look (empty for a preset saved before looks
    were: then the viewer's look is left as it is)."""

    theta_i: float
    sides: list[Side]
    look: dict[str, Any] = {}


class PresetError(ValueError):
    """A preset that cannot be saved or loaded (bad name, unreadable or malformed file)."""


class PresetRunsCode(PresetError):
    """A preset names a Python model file that the caller did not allow: loading it would
    run that file's code (:func:`from_toml`'s ``allow_code``)."""

    def __init__(self, message: str, files: list[str]) -> None:
        super().__init__(message)
        self.files = files


def runs_code(model: str) -> bool:
    """Whether loading model ``model`` (a preset's ``model = "…"``) runs a Python file."""
    return model.lower().endswith(".py")


def _allowed(model: str, allow_code) -> bool:
    if allow_code is True:
        return True
    real = os.path.realpath(model)
    return any(real == os.path.realpath(f) for f in (allow_code or ()))


def preset_dir() -> Path:
    """Where presets are saved: the user's configuration directory for tuibrdf (platformdirs;
    ``appauthor=False``: no second ``tuibrdf`` level on Windows)."""
    from platformdirs import user_config_path  # ≈ 10 ms: when a preset is listed or saved

    return user_config_path("tuibrdf", appauthor=False) / "presets"


def legacy_preset_dir() -> Path:
    """Where tuibrdf saved presets before :func:`preset_dir`, on every system:
    ``$XDG_CONFIG_HOME/tuibrdf/presets``, ``~/.config`` when the variable is unset."""
    base = os.environ.get("XDG_CONFIG_HOME") or os.path.join(os.path.expanduser("~"), ".config")
    return Path(base) / "tuibrdf" / "presets"


def preset_dirs() -> list[Path]:
    """The directories presets are read from, the one saved to first (one on Linux)."""
    new, old = preset_dir(), legacy_preset_dir()
    return [new] if old == new else [new, old]


def where_presets_are() -> str:
    """The directories :func:`preset_dirs`, as a message names them."""
    return " or ".join(str(d) for d in preset_dirs())


def _check_name(name: str) -> None:
    if not NAME_RE.match(name):
        raise PresetError(f"preset name {name!r} is invalid: use letters, digits, _ . - "
                          "(at most 64 characters)")


def preset_path(name: str) -> Path:
    """Where preset ``name`` is saved (:func:`preset_dir`); :class:`PresetError` for a bad
    name."""
    _check_name(name)
    return preset_dir() / f"{name}.toml"


def find_preset(name: str) -> Path:
    """Where preset ``name`` is read from: the first of :func:`preset_dirs` that has an entry
    of that name (whatever it is: a FIFO or a directory is reported by the reader), else its
    :func:`preset_path`; :class:`PresetError` for a bad name."""
    _check_name(name)
    for d in preset_dirs():
        path = d / f"{name}.toml"
        if os.path.lexists(path):
            return path
    return preset_dir() / f"{name}.toml"


def list_presets() -> list[str]:
    """Names of the saved presets (regular files ``NAME.toml`` with a valid name) in every
    one of :func:`preset_dirs`, sorted.  Never raises: an unreadable directory lists
    nothing."""
    names: set[str] = set()
    for d in preset_dirs():
        try:
            if not d.is_dir():
                continue
            clean_stale(d)
            names.update(p.stem for p in d.glob("*.toml")
                         if NAME_RE.match(p.stem) and p.is_file())
        except OSError:
            continue
    return sorted(names)


def clean_stale(d: Path, now: float | None = None) -> int:
    """Remove temporary files of killed saves (``.NAME.toml.XXXX.partial`` older than
    :data:`STALE_SECONDS`) from ``d``; returns how many.  Errors are ignored (a read-only
    directory keeps its leftovers)."""
    now = time.time() if now is None else now
    removed = 0
    try:
        entries = list(d.glob(f".*.toml.*{TMP_SUFFIX}"))
    except OSError:
        return 0
    for p in entries:
        try:
            st = p.lstat()
            if p.is_file() and not p.is_symlink() and now - st.st_mtime > STALE_SECONDS:
                p.unlink()
                removed += 1
        except OSError:
            continue
    return removed


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
        if any("\ud800" <= c <= "\udfff" for c in v):  # (a file name that is not UTF-8)
            raise PresetError(f"cannot save {v!r}: not valid Unicode text")
        # a TOML basic string: JSON's escapes (\" \\ control characters as \uXXXX) and every
        # other character as itself (JSON's ASCII form writes 😀 as a surrogate pair,
        # \ud83d\ude00, which TOML refuses), DEL escaped too (TOML refuses it raw)
        return json.dumps(v, ensure_ascii=False).replace("\x7f", "\\u007f")
    if isinstance(v, tuple | list):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    raise PresetError(f"cannot save a value of type {type(v).__name__}")


def _key(k: str) -> str:
    return k if re.match(r"^[A-Za-z0-9_-]+$", k) else _toml_value(k)


def to_toml(state: ViewerState) -> str:
    lines = ["# tuibrdf preset", f"theta_i = {_toml_value(state.theta_i)}", "", "[look]"]
    lines += [f"{k} = {_toml_value(getattr(state, k))}" for k in LOOK]
    for side in state.sides:
        params = ", ".join(f"{_key(k)} = {_toml_value(v)}" for k, v in side.values.items())
        lines += ["", "[[sides]]", f"model = {_toml_value(side.model)}",
                  f"params = {{ {params} }}"]
    return "\n".join(lines) + "\n"


def _save_path(name: str) -> Path:
    """The path preset ``name`` is saved to, its directory made; :class:`PresetError` when
    the directory cannot be made or the path is a directory (os.replace onto it fails)."""
    path = preset_path(name)
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
    except OSError as e:
        raise PresetError(f"cannot save preset {name!r}: cannot create {path.parent}: "
                          f"{_why(e)}") from None
    if path.is_dir():
        raise PresetError(f"cannot save preset {name!r}: {path} is a directory")
    return path


def check_can_save(name: str) -> Path:
    """Raise :class:`PresetError` now if preset ``name`` could not be saved (bad name, the
    directory cannot be created or written): for a caller about to spend time computing
    what it will save (``tuibrdf fit --save-preset``).  Returns the path."""
    path = _save_path(name)
    if not os.access(path.parent, os.W_OK | os.X_OK):
        raise PresetError(f"cannot save preset {name!r} to {path.parent}: permission denied")
    return path


def save_preset(state: ViewerState, name: str) -> Path:
    """Write ``state`` as preset ``name`` atomically; return the path.  Raises
    :class:`PresetError` naming the path and the problem when it cannot be written (read-only
    or full disk, no permission, the presets directory is a file)."""
    path = preset_path(name)
    text = to_toml(state)
    _save_path(name)
    clean_stale(path.parent)
    tmp = ""
    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{name}.toml.", suffix=TMP_SUFFIX, dir=path.parent)
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            f.write(text)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except OSError as e:
        if tmp:
            _unlink_quietly(tmp)
        raise PresetError(f"cannot save preset {name!r} to {path}: {_why(e)}") from None
    except BaseException:
        if tmp:
            _unlink_quietly(tmp)
        raise
    return path


def _why(e: OSError) -> str:
    return e.strerror or str(e)


def _unlink_quietly(path: str) -> None:
    try:
        os.unlink(path)
    except OSError:
        pass


# -- reading ------------------------------------------------------------------------------
def from_toml(text: str, where: str = "preset", allow_code=False) -> Preset:
    """Parse and validate a preset: ``(theta_i, sides, look)``.  Raises :class:`PresetError`;
    a side whose model is a Python file (:func:`runs_code`) is loaded (its code run) only if
    ``allow_code`` is True or names that file (an iterable of paths), else
    :class:`PresetRunsCode` is raised before anything is loaded."""
    import tomllib  # ≈ 20 ms (its regular expressions): when a preset is read, not at start

    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise PresetError(f"{where}: not valid TOML ({e})") from None
    except RecursionError:  # tomllib recurses once per nesting level
        raise PresetError(f"{where}: not a preset: nested too deeply") from None
    except ValueError as e:  # int() of a number beyond Python's digit limit, etc.
        msg = str(e)
        if "digits" in msg:
            msg = "a number has too many digits"
        raise PresetError(f"{where}: not a preset: {_one_line(msg)}") from None
    theta = data.get("theta_i", DISPLAY.theta_i.default)
    if isinstance(theta, bool) or not isinstance(theta, int | float) \
            or not DISPLAY.theta_i.accepts(theta):
        raise PresetError(f"{where}: theta_i = {_one_line(repr(theta), 40)} is invalid: "
                          f"expected a number in [{DISPLAY.theta_i.lo:g}, "
                          f"{DISPLAY.theta_i.hi:g}]")
    raw = data.get("sides")
    if not isinstance(raw, list) or not 1 <= len(raw) <= 2:
        raise PresetError(f"{where}: expected one or two [[sides]] tables")
    for entry in raw:
        if not isinstance(entry, dict) or not isinstance(entry.get("model"), str):
            raise PresetError(f"{where}: each [[sides]] needs model = \"NAME\"")
    for entry in raw:  # served: no file outside what serve allows, before anything else
        try:
            sandbox.check_name(entry["model"])
        except ValueError as e:
            raise PresetError(f"{where}: {_one_line(str(e))}") from None
    code = [e["model"] for e in raw if runs_code(e["model"]) and
            not _allowed(e["model"], allow_code)]
    if code:
        raise PresetRunsCode(f"{where}: loading it would run the Python file "
                             f"{_one_line(code[0])}, not named by you: name that file too "
                             "(tuibrdf view FILE --preset NAME) or add --trust", code)
    sides = []
    for entry in raw:
        params = entry.get("params", {})
        if not isinstance(params, dict):
            raise PresetError(f"{where}: params must be a table")
        try:
            model = get_model(entry["model"])
            for k, v in params.items():  # float() of a 400-digit integer overflows
                if isinstance(v, int) and not isinstance(v, bool) and abs(v) > 1e300:
                    raise ValueError(f"{model.name}: {k} = an integer of {len(str(abs(v)))} "
                                     "digits is invalid: expected a number")
            sides.append(Side(model.name, model.resolve(params)))
        except (ValueError, OverflowError) as e:  # OverflowError: float() of a 400-digit int
            raise PresetError(f"{where}: {_one_line(str(e))}") from None
    return Preset(float(theta), sides, _look(data.get("look", {}), where))


def _look(raw: Any, where: str) -> dict[str, Any]:
    """The ``[look]`` table, validated: each key's value in its range or list."""
    if not isinstance(raw, dict):
        raise PresetError(f"{where}: look must be a table")
    look: dict[str, Any] = {}
    for k, v in raw.items():
        if k in LOOK_NAMES:
            if v not in LOOK_NAMES[k]:
                raise PresetError(f"{where}: look.{k} = {_one_line(repr(v), 40)} is invalid: "
                                  f"expected one of {', '.join(LOOK_NAMES[k])}")
        elif k in LOOK_FLAGS:
            if not isinstance(v, bool):
                raise PresetError(f"{where}: look.{k} = {_one_line(repr(v), 40)} is invalid: "
                                  "expected true or false")
        elif k in LOOK_NUMBERS:
            s = getattr(DISPLAY, k)
            if isinstance(v, bool) or not isinstance(v, int | float) or not s.accepts(v):
                raise PresetError(f"{where}: look.{k} = {_one_line(repr(v), 40)} is invalid: "
                                  f"expected a number in {s.range_text()}")
            v = float(v) % 360.0 if k == "phi_i" else float(v)  # φi as the viewer keeps it
        else:
            continue  # a newer version's setting: ignored
        look[k] = v
    return look


def _one_line(text: str, limit: int = 300) -> str:
    """A message from a hostile file on one line of bounded length (its values are echoed)."""
    text = " ".join(text.split())
    return text if len(text) <= limit else text[:limit] + "…"


def load_preset(name: str, allow_code=False) -> Preset:
    """``(theta_i, sides, look)`` of the saved preset ``name`` (:func:`find_preset`: the new
    directory first); raises :class:`PresetError` (one line naming the file) for a missing,
    non-regular, oversized, undecodable or malformed file, and :class:`PresetRunsCode` for
    a preset that would run a Python file not allowed (``allow_code``, :func:`from_toml`).
    Never blocks on a FIFO."""
    path = find_preset(name)
    try:
        text = read_regular(path, MAX_BYTES).decode("utf-8")
    except FileNotFoundError:
        have = list_presets()
        hint = f"; saved presets: {', '.join(have)}" if have else ""
        raise PresetError(f"no preset named {name!r} in {where_presets_are()}{hint}") from None
    except OSError as e:
        raise PresetError(f"cannot read {path}: {_why(e)}") from None
    except UnicodeDecodeError as e:
        raise PresetError(f"cannot read {path}: not UTF-8 text (byte {e.start})") from None
    return from_toml(text, str(path), allow_code)


def apply_loaded(state: ViewerState, theta_i: float, sides: list[Side],
                 look: dict[str, Any] | None = None) -> None:
    """Put a loaded preset into ``state`` (compare mode iff it has two sides; its look, what
    it has of one)."""
    for k, v in (look or {}).items():
        setattr(state, k, v)
    state.theta_i = theta_i
    state.sides = sides
    state.active = 0
    state.preset = ""
    for s in sides:
        state.memory[s.model] = dict(s.values)
