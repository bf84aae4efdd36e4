"""What a served viewer may open (``tuibrdf serve``): the one policy every file the viewer
resolves passes through (no Textual).

``tuibrdf serve`` hands the browser a viewer on the server's disk; textual-serve has no
authentication, so the viewer it starts opens files only under ``--data-dir`` and the ones named
on serve's command line, and refuses Python model files (they run code) unless
``--allow-python``.  serve puts the policy in the environment variable :data:`ENV` (JSON), which
textual-serve passes to each viewer process; ``view`` installs it (:func:`install_from_environment`)
before it builds anything.  With no policy installed (a viewer in a terminal) every check passes.

The viewer turns a name into a file in three places, each of which asks here first: a side's
model and its data files (:class:`~tuibrdf.state.viewer.Side`), a value typed into a file row
(``ViewerState._commit``), and a preset's model (:func:`~tuibrdf.state.presets.from_toml`, before
the model file is read, so a refused ``.py`` never runs).  Paths are compared after
:func:`os.path.realpath`, so neither ``..`` nor a symbolic link leaves the data directory; a
``.bparam`` file's ``.brdf`` is checked too.
"""

from __future__ import annotations

import json
import os
from collections.abc import Iterable
from dataclasses import dataclass

#: the environment variable serve sets for the viewer processes it starts
ENV = "TUIBRDF_SERVE_POLICY"


@dataclass(frozen=True)
class Policy:
    """``data_dir``: a real path or None; ``files``: the real paths named on the command line."""

    data_dir: str | None = None
    files: frozenset[str] = frozenset()
    allow_python: bool = False
    #: model files named on the command line after the first (``m`` cycles to them)
    models: tuple[str, ...] = ()

    def to_json(self) -> str:
        return json.dumps({"data_dir": self.data_dir, "files": sorted(self.files),
                           "allow_python": self.allow_python, "models": list(self.models)})

    @classmethod
    def from_json(cls, text: str) -> Policy:
        """Raises ValueError for anything but what :meth:`to_json` writes."""
        try:
            d = json.loads(text)
            data_dir, files = d["data_dir"], d["files"]
            allow, models = d["allow_python"], d.get("models", [])
            ok = (data_dir is None or isinstance(data_dir, str)) and isinstance(allow, bool) \
                and all(isinstance(f, str) for f in [*files, *models])
        except (ValueError, TypeError, KeyError):
            ok = False
        if not ok:
            raise ValueError(f"{ENV}: not a policy written by tuibrdf serve")
        return cls(data_dir, frozenset(files), allow, tuple(models))

    @classmethod
    def make(cls, data_dir: str | None, files: Iterable[str], allow_python: bool,
             models: Iterable[str] = ()) -> Policy:
        return cls(os.path.realpath(data_dir) if data_dir else None,
                   frozenset(os.path.realpath(f) for f in files), allow_python, tuple(models))


_policy: Policy | None = None


def install(policy: Policy | None) -> None:
    """Make ``policy`` the one every check consults (None: no restriction)."""
    global _policy
    _policy = policy


def current() -> Policy | None:
    return _policy


def install_from_environment() -> Policy | None:
    """The policy in :data:`ENV`, installed; None (nothing installed) when it is unset."""
    text = os.environ.get(ENV)
    if text is None:
        return None
    policy = Policy.from_json(text)
    install(policy)
    return policy


def _is_path(name: object) -> bool:
    from tuibrdf.core.formats.userfiles import looks_like_path

    return looks_like_path(name)


def check_path(path: str, policy: Policy | None = None) -> None:
    """Raise ValueError (one line) if the served viewer may not open ``path``."""
    policy = policy or _policy
    if policy is None:
        return
    path = os.fspath(path)
    real = os.path.realpath(path)
    if real.lower().endswith(".py") and not policy.allow_python:
        raise ValueError(f"{path}: Python model files run code, and this server was started "
                         "without --allow-python")
    if real in policy.files:
        return
    top = policy.data_dir
    if top is not None and os.path.commonpath([real, top]) == top:
        return
    where = (f"opens only files under {top} and those named on its command line" if top
             else "opens only the files named on its command line (--data-dir DIR adds a "
                  "directory)")
    raise ValueError(f"{path}: refused: this served viewer {where}")


def check_name(name: object) -> None:
    """A model name before it is resolved: a file path must be allowed (a ``.bparam``'s
    ``.brdf`` too, unless the ``.bparam`` was named on the command line)."""
    from tuibrdf.core.registry import MODELS

    if _policy is None or not isinstance(name, str) or name in MODELS or not _is_path(name):
        return
    check_path(name)
    real = os.path.realpath(name)
    if real.lower().endswith(".bparam") and real not in _policy.files and os.path.isfile(real):
        from tuibrdf.core.formats.brdf_explorer import parse_file

        target = parse_file(real).target  # a malformed file: its own message, from the loader
        if target:  # resolved as the loader resolves it (load_bparam)
            check_path(os.path.join(os.path.dirname(os.path.abspath(name)), target))


def check_material(material) -> None:
    """A material's model file and data files (its path parameters) must be allowed."""
    if _policy is None:
        return
    check_name(material.name)
    for p in material.model.params:
        value = material.values.get(p.name)
        if p.kind == "path" and value:
            check_path(str(value))
