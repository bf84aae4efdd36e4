"""Python model files: ``tuibrdf view my_model.py``.

A model file declares its model exactly as the built-in models do (docs/examples/minnaert.py
is the documented example)::

    import numpy as np
    from tuibrdf.core.params import Model, Param

    KD = Param("kd", "Kd", 0.8, 0.0, 1.0, 0.01, doc="diffuse reflectance")

    def kernel(wi, wo, kd):              # wi, wo: (..., 3) unit vectors
        return np.full(np.broadcast_shapes(wi.shape, wo.shape)[:-1], kd / np.pi)

    MODEL = Model("my-lambert", "My Lambert", (KD,), kernel)

The file is imported from its path (``importlib``; a fresh module each time the file changes)
and must define ``MODEL``, a :class:`~tuibrdf.core.params.Model`.  The model's registry name
becomes the file's absolute path; its title, parameters and flags are the file's.

User code is the user's: anything it raises — an import error, a syntax error, an exception
(``SystemExit`` included; only ``KeyboardInterrupt``, the user's Ctrl-C, passes through) or
a floating-point error in the kernel (kernels run under the package's raising errstate,
:mod:`tuibrdf.core.numerics`) — becomes a :class:`~tuibrdf.core.formats.userfiles.UserFileError`
naming the file and the line in it, as does a result of the wrong shape (scalars broadcast) or
containing NaN or inf.  Negative values are clamped to 0, as the built-in models clamp
formulas that go negative.
"""

from __future__ import annotations

import hashlib
import importlib.util
import os
import sys
import traceback
from dataclasses import replace

import numpy as np

from tuibrdf.core.formats.files import UserFileError
from tuibrdf.core.params import Model, Param


def _user_line(exc: BaseException, path: str) -> int | None:
    """The last line of ``path`` in the traceback of ``exc`` (or a SyntaxError's line)."""
    if isinstance(exc, SyntaxError) and exc.filename and \
            os.path.realpath(exc.filename) == os.path.realpath(path):
        return exc.lineno
    line = None
    real = os.path.realpath(path)
    for frame in traceback.extract_tb(exc.__traceback__):
        if os.path.realpath(frame.filename) == real:
            line = frame.lineno
    return line


def _where(path: str, line: int | None) -> str:
    return f"{path}:{line}" if line else path


def _describe(exc: BaseException) -> str:
    msg = str(exc).strip().splitlines()
    text = msg[0] if msg else ""
    return f"{type(exc).__name__}: {text}" if text else type(exc).__name__


def load_python_model(path: str, name: str) -> Model:
    """Import the model file at ``path``; its model, renamed ``name``, with a guarded kernel."""
    real = os.path.realpath(path)
    digest = hashlib.sha1(f"{real}:{os.stat(real).st_mtime_ns}".encode()).hexdigest()[:12]
    modname = f"tuibrdf_user_model_{digest}"
    try:
        spec = importlib.util.spec_from_file_location(modname, real)
    except Exception as e:  # noqa: BLE001 — any failure is the file's
        raise UserFileError(f"{path}: cannot import: {_describe(e)}") from None
    if spec is None or spec.loader is None:
        raise UserFileError(f"{path}: cannot import this file as a Python module")
    module = importlib.util.module_from_spec(spec)
    sys.modules[modname] = module  # dataclasses and pickling look the module up
    try:
        spec.loader.exec_module(module)
    except KeyboardInterrupt:
        raise
    except BaseException as e:  # noqa: BLE001 — SystemExit, ImportError, …: the user's error
        sys.modules.pop(modname, None)
        raise UserFileError(f"{_where(path, _user_line(e, path))}: error while importing the "
                            f"model file: {_describe(e)}") from None
    model = getattr(module, "MODEL", None)
    if not isinstance(model, Model):
        what = "does not define MODEL" if model is None else \
            f"defines MODEL as a {type(model).__name__}"
        raise UserFileError(f"{path}: {what}; a model file must define MODEL = Model(...) "
                            "(tuibrdf.core.params.Model; see docs/reference/formats.md)")
    for p in model.params:
        if not isinstance(p, Param):
            raise UserFileError(f"{path}: MODEL.params must hold tuibrdf.core.params.Param "
                                f"declarations, found a {type(p).__name__}")
    if not callable(model.kernel):
        raise UserFileError(f"{path}: MODEL.kernel is not callable")
    try:  # the defaults must validate, as for a built-in declaration
        model.resolve({p.name: p.default for p in model.params})
    except ValueError as e:
        raise UserFileError(f"{path}: the declared defaults are invalid: {e}") from None
    if model.albedo_kernel is not None:  # it would run unguarded: its errors tracebacks
        raise UserFileError(f"{path}: MODEL.albedo_kernel is not for model files: the albedo "
                            "integrates the kernel")
    guarded = _GuardedKernel(path, model.kernel, model.rgb)
    return replace(model, name=name, kernel=guarded, raw_kernel=guarded.values,
                   sampler=_sampler(path, module, model))


def _sampler(path: str, module, model: Model):
    """The file's ``sample`` and ``pdf`` functions as a sampler (both or neither), each
    failure of theirs a one-line :class:`UserFileError`; else the model's own (None)."""
    from tuibrdf.core.brdf.sampling import Sampler

    fns = {n: getattr(module, n, None) for n in ("sample", "pdf")}
    if all(f is None for f in fns.values()):
        return model.sampler
    for n, f in fns.items():
        if not callable(f):
            other = "pdf" if n == "sample" else "sample"
            raise UserFileError(f"{path}: defines {other} but no function {n}(...): a sampler "
                                "needs both (docs/reference/formats.md)")
    return Sampler(*(_GuardedCall(path, fns[n], n) for n in ("sample", "pdf")))


class _GuardedCall:
    """One of the file's sampling functions; what it raises becomes a one-line error."""

    def __init__(self, path: str, fn, what: str):
        self.path, self.fn, self.what = path, fn, what

    def __call__(self, *args, **kw):
        try:
            return self.fn(*args, **kw)
        except KeyboardInterrupt:
            raise
        except Exception as e:  # noqa: BLE001 — the user's error, shown as theirs
            line = _user_line(e, self.path)
            raise UserFileError(f"{_where(self.path, line)}: {self.what}() raised "
                                f"{_describe(e)}") from None


class _GuardedKernel:
    """Calls the user's kernel; turns its failures and bad results into one-line errors."""

    def __init__(self, path: str, kernel, rgb: bool):
        self.path = path
        self.kernel = kernel
        self.rgb = rgb
        code = getattr(kernel, "__code__", None)
        self.def_line = code.co_firstlineno if code is not None else None

    def __call__(self, wi, wo, **params):
        return np.maximum(self.raw(wi, wo, **params), 0.0)  # negatives clamped, as built-ins

    def raw(self, wi, wo, **params):
        """The kernel's values checked (shape, finite) but not clamped: negatives kept."""
        f = self.values(wi, wo, **params)
        where = _where(self.path, self.def_line)
        shape = f.shape
        bad = ~np.isfinite(f)
        if bad.any():
            n = int(bad.sum())
            k = np.unravel_index(int(np.flatnonzero(bad)[0]), f.shape)
            d = k[:-1] if self.rgb else k
            wi_b = np.broadcast_to(wi, shape[:len(d)] + (3,))[d] if d else np.asarray(wi)
            wo_b = np.broadcast_to(wo, shape[:len(d)] + (3,))[d] if d else np.asarray(wo)
            kind = "NaN" if np.isnan(f[k]) else "inf"
            raise UserFileError(
                f"{where}: the kernel returned {kind} ({n} of {f.size} values; first at "
                f"wi={np.round(wi_b, 4).tolist()}, wo={np.round(wo_b, 4).tolist()}, "
                f"params {params})")
        return f

    def values(self, wi, wo, **params):
        """The kernel's values with their shape checked, nothing else: NaN, inf and negatives
        kept (the model's ``raw_kernel``, which ``tuibrdf check`` examines); what the kernel
        raises becomes a one-line error."""
        try:
            out = self.kernel(wi, wo, **params)
        except KeyboardInterrupt:  # the user's Ctrl-C, not the file's error: it stops us
            raise
        except BaseException as e:  # noqa: BLE001 — SystemExit too: the user's error
            line = _user_line(e, self.path) or self.def_line
            raise UserFileError(f"{_where(self.path, line)}: the kernel raised "
                                f"{_describe(e)}") from None
        where = _where(self.path, self.def_line)
        shape = np.broadcast_shapes(np.shape(wi), np.shape(wo))[:-1] + ((3,) if self.rgb else ())
        try:
            f = np.asarray(out, dtype=float)
        except (TypeError, ValueError):
            raise UserFileError(f"{where}: the kernel returned a {type(out).__name__}, not an "
                                "array of numbers") from None
        try:
            f = np.broadcast_to(f, shape)
        except ValueError:
            kind = "RGB model: (..., 3)" if self.rgb else "scalar model: (...)"
            raise UserFileError(f"{where}: the kernel returned shape {f.shape} for directions "
                                f"of shape {np.shape(wi)}: expected {shape} ({kind})") from None
        return f
