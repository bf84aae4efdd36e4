"""User files wherever a model name goes (SPEC §5b): the resolver behind ``get_model``.

``get_model(NAME)`` looks ``NAME`` up in the registry first; when it is not a registered name
and looks like a path (it has a file extension or a directory separator, or names an existing
file), the file is loaded by its extension:

==========  =================================================  ============================
extension   format                                             module
==========  =================================================  ============================
.brdf       BRDF Explorer analytic BRDF (GLSL)                 :mod:`.brdf_explorer`
.bparam     BRDF Explorer saved parameters for a .brdf file    :mod:`.brdf_explorer`
.py         a Python model file (``MODEL = Model(...)``)       :mod:`.pymodel`
.bsdf       RGL-EPFL measured material (Dupuy & Jakob 2018)    :mod:`.rgl_bsdf`
.binary     MERL measured BRDF                                 :mod:`.merl`
==========  =================================================  ============================

The model's registry-style ``name`` is the file's absolute path, so anything that stores a
model name (a viewer side, a preset) stores the path and resolves it again.  Loaded models are
cached by (real path, modification time, size): a file edited on disk is loaded again on the
next lookup; an unchanged one is not re-read.

Installed packages add models through the entry-point group ``tuibrdf.models``: each entry
point's name is a model name and its object a :class:`~tuibrdf.core.params.Model`.  They are
loaded lazily, on the first lookup of that name; a plugin that fails to load is an error
of one line.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from dataclasses import replace

from tuibrdf.core.formats.files import UserFileError  # the readers' error, re-exported here
from tuibrdf.core.lru import LRU
from tuibrdf.core.params import Model

#: extension → what it is (for messages and docs)
EXTENSIONS = {
    ".brdf": "BRDF Explorer analytic BRDF",
    ".bparam": "BRDF Explorer parameters",
    ".py": "Python model",
    ".bsdf": "RGL-EPFL measured BSDF",
    ".binary": "MERL measured BRDF",
}
ENTRY_POINT_GROUP = "tuibrdf.models"


def understood() -> str:
    return ", ".join(EXTENSIONS)


def looks_like_path(name: object) -> bool:
    """Whether a model argument should be treated as a file path."""
    if hasattr(name, "__fspath__"):
        return True
    if not isinstance(name, str) or not name:
        return False
    if os.sep in name or "/" in name or os.path.splitext(name)[1]:
        return True
    return os.path.isfile(name)


# --------------------------------------------------------------------------- cache

CACHE_SIZE = 16
_CACHE = LRU(CACHE_SIZE)


def _key(path: str) -> tuple:
    try:
        st = os.stat(path)
    except FileNotFoundError:
        raise UserFileError(f"{path}: no such file") from None
    except OSError as e:
        raise UserFileError(f"{path}: cannot read: {e.strerror or e}") from None
    if not os.path.isfile(path):
        raise UserFileError(f"{path}: not a file")
    return (os.path.realpath(path), st.st_mtime_ns, st.st_size)


def load_model_file(path: str | os.PathLike) -> Model:
    """The model in the file at ``path`` (cached); raises :class:`UserFileError` (or a
    ``ValueError`` subclass of the format) naming the file and the problem."""
    given = os.fspath(path)
    ext = os.path.splitext(given)[1].lower()
    if ext not in EXTENSIONS:
        what = f"unknown file type {ext!r}" if ext else "no file extension"
        raise UserFileError(f"{given}: {what}: tuibrdf reads {understood()} files, or a "
                            "model name (see 'tuibrdf models')")
    return _CACHE.get(_key(given), lambda: _LOADERS[ext](given, os.path.abspath(given)))


def clear_cache() -> None:
    _CACHE.clear()


def _load_brdf(path: str, name: str) -> Model:
    from tuibrdf.core.formats.brdf_explorer import load_brdf

    return load_brdf(path, name)


def _load_bparam(path: str, name: str) -> Model:
    from tuibrdf.core.formats.brdf_explorer import load_bparam

    return load_bparam(path, name)


def _load_py(path: str, name: str) -> Model:
    from tuibrdf.core.formats.pymodel import load_python_model

    return load_python_model(path, name)


def _load_bsdf(path: str, name: str) -> Model:
    from tuibrdf.core.formats.rgl_bsdf import load_model

    return load_model(path, name)


def _load_binary(path: str, name: str) -> Model:
    from tuibrdf.core.formats.merl import FILE, MERL, check_file

    check_file(path)
    file_param = replace(FILE, default=os.path.abspath(path))
    return replace(MERL, name=name, title=f"MERL {os.path.basename(path)}",
                   params=(file_param, *(p for p in MERL.params if p.name != "file")))


_LOADERS: dict[str, Callable[[str, str], Model]] = {
    ".brdf": _load_brdf, ".bparam": _load_bparam, ".py": _load_py, ".bsdf": _load_bsdf,
    ".binary": _load_binary,
}


# --------------------------------------------------------------------------- plugins

_PLUGINS: dict[str, Model] = {}


def _entry_points():
    from importlib.metadata import entry_points

    return list(entry_points(group=ENTRY_POINT_GROUP))


def _load_entry_point(ep) -> Model:
    try:
        obj = ep.load()
        if callable(obj) and not isinstance(obj, Model):
            obj = obj()
    except Exception as e:  # a broken plugin is the plugin's error, in one line
        raise UserFileError(f"plugin model {ep.name!r} ({ep.value}) failed to load: "
                            f"{type(e).__name__}: {e}") from None
    if not isinstance(obj, Model):
        raise UserFileError(f"plugin model {ep.name!r} ({ep.value}) is a "
                            f"{type(obj).__name__}, not a tuibrdf Model")
    return obj


def plugin_model(name: str) -> Model | None:
    """The installed plugin model called ``name`` (loaded on first use), or None."""
    if name in _PLUGINS:
        return _PLUGINS[name]
    for ep in _entry_points():
        if ep.name == name:
            model = _load_entry_point(ep)
            _PLUGINS[name] = model
            return model
    return None
