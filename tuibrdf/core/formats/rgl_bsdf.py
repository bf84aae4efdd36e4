"""RGL-EPFL measured materials (``.bsdf``; Dupuy & Jakob 2018, "An Adaptive Parameterization
for Efficient Material Acquisition and Rendering"): reader and evaluation.

**Container** ("tensor_file", little-endian): magic ``tensor_file\\0`` (12 bytes), version
``u8 1, u8 0``, ``u32`` field count; per field ``u16`` name length, the name (UTF-8), ``u16``
ndim, ``u8`` dtype (Mitsuba's ``Struct`` codes: 1 u8, 2 i8, 3 u16, 4 i16, 5 u32, 6 i32, 7 u64,
8 i64, 9 f16, 10 f32, 11 f64), ``u64`` offset of the data from the start of the file, and
``ndim × u64`` shape.  Every field is validated before anything is allocated: its data must lie
inside the file, so a huge declared shape is an error, not a huge allocation.

**Fields** (as the reference reader ``powitacq_rgb.h`` and Mitsuba 3's ``measured`` plugin check
them): ``description`` (u8), ``phi_i``, ``theta_i`` (f32, the incidence grid, radians,
increasing), ``ndf``, ``sigma`` (f32 2-D), ``vndf``, ``luminance`` (f32, ``(φi, θi, n, n)``),
``rgb`` (f32, ``(φi, θi, 3, n, n)``) or, in spectral files, ``spectra`` ``(φi, θi, λ, n, n)``
with ``wavelengths`` (f32, nm), and ``jacobian`` (u8, one value).  ``valid`` and ``version``
are read as information.  Float fields may be f32 or f64 (converted to f64).

**Evaluation** follows ``powitacq_rgb::BRDF::eval`` (whose ``Warp2D`` is Mitsuba's
``Marginal2D``), vectorised over directions, in float64:

1. both directions above the horizon, else 0; files covering half or a quarter of the
   incidence azimuths (Mitsuba 3's "reduction" 2 or 4, from the φi range) bring ``wi`` and
   ``wo`` into the measured range as Mitsuba 3 does (reduction 2: a half turn about the normal
   when ``wi.y ≥ 0``; 4: x and y made ≤ 0); powitacq accepts reduction 1 only;
2. ``wm = normalize(wi + wo)``; elevations by ``2 asin(|d − N|/2)``; azimuths by ``atan2``;
   ``u(θ) = √(2θ/π)``, ``u(φ) = (φ + π)/2π``; for isotropic files (≤ 2 φi samples) the
   half-vector's azimuth is taken relative to ``φi``, wrapped to [0, 1);
3. the VNDF warp (a piecewise-bilinear 2-D distribution whose marginal/conditional CDFs are
   built at load time, interpolated over (φi, θi)) maps ``u(wm)`` back to the unit square
   (``Marginal2D::invert``);
4. the ``rgb`` (or converted ``spectra``) tensor is interpolated there: bilinear in the square,
   linear in φi and θi (clamped at the grid's ends);
5. if the file's ``jacobian`` flag is set, times ``ndf(u(wm)) / (4 σ(u(wi)))`` (Mitsuba 3
   applies this factor only when the flag is set; powitacq always does — RGL files set it);
6. that is ``f·cos θo``: tuibrdf divides by ``cos θo``, held at ``cos 89.9°`` within 0.1° of
   the horizon (measured values there are noisy and need not vanish: the division amplifies
   them at most 573×); on the horizon itself (θo = 90°) the value is the limit from above
   (powitacq returns 0 there), so the closed hemisphere's largest value is one the kernel
   gives; the albedo's f (``floor=False``) is 0 there.

One ``wi`` for many ``wo`` (a map, the peak finder) mixes the (φi, θi) slices of the warps once
(every lookup is linear in the slices) and keeps them with ``σ(u(wi))`` for the last few
incidences of the file (``RglData.lights``).

Negative RGB values (out-of-gamut spectra) are clamped to 0 for display.  The ``valid`` mask is
not applied (powitacq and Mitsuba ignore it); the count of invalid entries is reported.

**Spectral files** are converted to linear sRGB at load time, with the CIE 1931 2° observer
under illuminant D65 (:mod:`tuibrdf.core.formats.cie`): the conversion is linear, so converting the
tensor and then interpolating equals interpolating and then converting.
"""

from __future__ import annotations

import os
import struct
from dataclasses import dataclass, field
from functools import partial
from typing import NamedTuple

import numpy as np

from tuibrdf.core.formats.files import UserFileError
from tuibrdf.core.lru import LRU
from tuibrdf.core.numerics import safe_div
from tuibrdf.core.params import Model

MAGIC = b"tensor_file\0"
DTYPES = {1: "<u1", 2: "<i1", 3: "<u2", 4: "<i2", 5: "<u4", 6: "<i4", 7: "<u8", 8: "<i8",
          9: "<f2", 10: "<f4", 11: "<f8"}
DTYPE_NAMES = {1: "uint8", 2: "int8", 3: "uint16", 4: "int16", 5: "uint32", 6: "int32",
               7: "uint64", 8: "int64", 9: "float16", 10: "float32", 11: "float64"}
MAX_FIELDS = 256
MAX_NDIM = 8
#: the fields tuibrdf reads (the module docstring); the data of any other field is not read
KNOWN_FIELDS = ("description", "phi_i", "theta_i", "ndf", "sigma", "vndf", "luminance", "rgb",
                "spectra", "wavelengths", "jacobian", "valid", "version")
#: float fields must lie within ±MAX_MAGNITUDE, and values closer to 0 than MIN_MAGNITUDE are
#: read as 0, so that every step of the evaluation stays finite: a warp's slice total (sums of
#: trapezoids, no products) is 0 or ≥ 1e-20/4, so its inverse ≤ 4e20; an interpolated σ is 0
#: or ≥ 1e-20 times a cell fraction ≥ 1e-77 (u = √(2θ/π) with θ ≥ 1e-154, the smallest
#: non-zero elevation of a unit vector in float64), so ndf/(4σ) ≤ 1e20/4e-97 and the value,
#: times rgb ≤ 1e20 over cos θo ≥ cos 89.9°, stays under 1e140.  Measured data lies many
#: decades inside these bounds.
MAX_MAGNITUDE = 1e20
MIN_MAGNITUDE = 1e-20
#: ``cos θo`` floor of step 6: cos 89.9°
COS_FLOOR = float(np.cos(np.radians(89.9)))
#: incidences a file keeps prepared (:func:`_light`): a frame's views and its peak finder
#: evaluate one light many times; a few more for the lights of a comparison
LIGHT_CACHE = 8


class BsdfError(UserFileError):
    """A file that is not a valid RGL ``.bsdf``: the message names the file and the problem."""


@dataclass(frozen=True)
class Field:
    dtype: int
    offset: int
    shape: tuple[int, ...]

    @property
    def nbytes(self) -> int:
        n = np.dtype(DTYPES[self.dtype]).itemsize
        for s in self.shape:
            n *= s
        return n


def read_header(f, path: str, size: int) -> dict[str, Field]:
    """Parse the header of an open tensor file; every field's data lies inside the file."""

    def bad(msg):
        return BsdfError(f"{path}: not an RGL .bsdf tensor file: {msg}")

    def read(n, what):
        b = f.read(n)
        if len(b) < n:
            raise bad(f"truncated header (ends inside {what}; the file has {size} bytes)")
        return b

    magic = f.read(12)
    if magic != MAGIC:
        if len(magic) < 12 and MAGIC.startswith(magic):
            raise bad(f"truncated header (ends inside the magic; the file has {size} bytes)")
        raise bad(f"wrong magic {magic[:12]!r}, expected {MAGIC!r}")
    major, minor = read(2, "the version")
    if (major, minor) != (1, 0):
        raise bad(f"unknown version {major}.{minor}, expected 1.0")
    (count,) = struct.unpack("<I", read(4, "the field count"))
    if count > MAX_FIELDS:
        raise bad(f"{count} fields declared (at most {MAX_FIELDS})")
    fields: dict[str, Field] = {}
    for k in range(count):
        (nlen,) = struct.unpack("<H", read(2, f"field {k}'s name length"))
        try:
            name = read(nlen, f"field {k}'s name").decode("utf-8")
        except UnicodeDecodeError:
            raise bad(f"field {k}'s name is not UTF-8") from None
        ndim, dtype = struct.unpack("<HB", read(3, f"field {name!r}'s rank and type"))
        (offset,) = struct.unpack("<Q", read(8, f"field {name!r}'s offset"))
        if ndim > MAX_NDIM:
            raise bad(f"field {name!r} has {ndim} dimensions (at most {MAX_NDIM})")
        shape = struct.unpack(f"<{ndim}Q", read(8 * ndim, f"field {name!r}'s shape"))
        if dtype not in DTYPES:
            raise bad(f"field {name!r} has unknown type code {dtype} (1-11)")
        fld = Field(dtype, offset, tuple(int(s) for s in shape))
        if offset > size or fld.nbytes > size - offset:
            raise bad(f"field {name!r} ({DTYPE_NAMES[dtype]} × {fld.shape}: {fld.nbytes:,} "
                      f"bytes at offset {offset:,}) runs past the end of the file "
                      f"({size:,} bytes): truncated data or a wrong shape")
        if any(s > size for s in fld.shape):  # empty, yet a side larger than the file
            raise bad(f"field {name!r} declares shape {fld.shape}: a side is larger than "
                      f"the file ({size:,} bytes)")
        if name in fields:
            raise bad(f"field {name!r} appears twice")
        fields[name] = fld
    end = f.tell()  # the data lies after the header, each field's bytes its own
    spans = sorted((fld.offset, fld.offset + fld.nbytes, name) for name, fld in fields.items()
                   if fld.nbytes)
    prev_end, prev = end, "the header"
    for start, stop, name in spans:
        if start < prev_end:
            other = prev if prev == "the header" else f"field {prev!r}"
            raise bad(f"field {name!r} (bytes {start:,}–{stop:,}) overlaps {other} (which ends "
                      f"at byte {prev_end:,}): each field's data must be its own")
        prev_end, prev = stop, name
    return fields


def read_tensor(path: str, names=None) -> dict[str, np.ndarray]:
    """The fields of a tensor file as arrays (all, or those in ``names``), validated against
    the file's size and against each other first (no overlap: at most the file is read)."""
    try:
        with open(path, "rb") as f:
            size = os.fstat(f.fileno()).st_size
            fields = read_header(f, path, size)
            out = {}
            for name, fld in fields.items():
                if names is not None and name not in names:
                    continue  # unknown fields are not read
                f.seek(fld.offset)
                raw = f.read(fld.nbytes)
                if len(raw) < fld.nbytes:
                    raise BsdfError(f"{path}: field {name!r} is truncated")
                out[name] = np.frombuffer(raw, dtype=DTYPES[fld.dtype]).reshape(fld.shape)
    except OSError as e:
        raise BsdfError(f"{path}: cannot read: {e.strerror or e}") from None
    return out


# --------------------------------------------------------------------------- the warps


class Warp:
    """Mitsuba's ``Marginal2D`` over a grid ``(ny, nx)`` of values, with ``S`` parameter slices
    (the flattened (φi, θi) grid) in front.  ``cdf`` builds the marginal/conditional CDFs and
    normalises each slice (as ``build_cdf = true``).  The tables are kept with each slice's grid
    flattened, row-major: ``data`` and ``cond`` ``(S, ny·nx)`` (``data`` of the rgb warp
    ``(S, ny·nx, 3)``), ``marg`` ``(S, ny)``; cell (iy, ix) is at ``iy·nx + ix``."""

    def __init__(self, data: np.ndarray, params: list[np.ndarray], cdf: bool):
        self.params = params
        self.sizes = [len(p) for p in params]
        s = int(np.prod(self.sizes)) if params else 1
        data = np.asarray(data, dtype=np.float64).reshape(s, *data.shape[-2:])
        self.ny, self.nx = data.shape[1:]
        if cdf:
            # conditional CDF along x (trapezoids), marginal along y of the row totals
            cond = np.zeros_like(data)
            cond[:, :, 1:] = np.cumsum(0.5 * (data[:, :, 1:] + data[:, :, :-1]), axis=2)
            rows = cond[:, :, -1]
            marg = np.zeros((s, self.ny))
            marg[:, 1:] = np.cumsum(0.5 * (rows[:, 1:] + rows[:, :-1]), axis=1)
            total = marg[:, -1]
            norm = safe_div(1.0, total, total > 0)  # a slice of zeros: checked at load
            self.cond = (cond * norm[:, None, None]).reshape(s, -1)
            self.marg = marg * norm[:, None]
            data = data * norm[:, None, None]
        self.data = data.reshape(s, -1)

    def corners(self, values: list[np.ndarray]):
        """``[(slice index, weight)]`` over the 2^D corners of the parameter cell (linear
        interpolation, clamped at the ends; a parameter with one value has weight 1)."""
        if not self.params:
            return ONE  # no parameters (ndf, σ): the one table
        out = [(np.zeros(np.shape(values[0]), dtype=np.intp), 1.0)]
        stride = 1
        strides = []
        for n in reversed(self.sizes):
            strides.append(stride)
            stride *= n
        strides.reverse()
        for grid, v, st in zip(self.params, values, strides, strict=True):
            n = len(grid)
            if n == 1:
                continue
            i0 = np.minimum(np.maximum(np.searchsorted(grid, v, side="right") - 1, 0), n - 2)
            p0, p1 = grid[i0], grid[i0 + 1]
            # grid strictly increasing (checked at load): p1 > p0
            w1 = np.minimum(np.maximum((v - p0) / (p1 - p0), 0.0), 1.0)
            out = [(idx + i0 * st, w * (1.0 - w1)) for idx, w in out] + \
                  [(idx + (i0 + 1) * st, w * w1) for idx, w in out]
        return out

    @staticmethod
    def lookup(arr: np.ndarray, corners, cells: np.ndarray, offsets=(0,)) -> list[np.ndarray]:
        """``[Σ_corners w · arr[slice, cells + o] for o in offsets]``, ``arr`` being
        ``(S, n, *channels)`` (the channels are kept) and ``cells`` flat indices into a slice:
        one flat ``take`` per corner and offset, 2–3× faster than fancy indexing.  (One
        ``take`` of all offsets, a (4, N) index, measured no faster; with several slices and
        many directions its 4× larger temporaries were slower.)"""
        n = arr.shape[1]
        flat = arr.reshape(-1, *arr.shape[2:])
        if corners is ONE:  # one table (collapsed, or no parameters): slice 0
            return [flat.take(cells + o, axis=0) for o in offsets]
        weights = [_spread(w, flat.shape[1:]) for _, w in corners]
        out = []
        for o in offsets:
            at, acc = cells + o, None
            for (idx, _), w in zip(corners, weights, strict=True):
                v = flat.take(idx * n + at, axis=0)
                v *= w  # in place, as the sum: fewer temporaries (many directions)
                if acc is None:
                    acc = v
                else:
                    acc += v
            out.append(acc)
        return out

    def collapse(self, corners) -> Warp:
        """This warp at one parameter point (``corners`` of a single incidence): the slices
        mixed once, so that later lookups gather from one table.  Identical to interpolating
        at every lookup, since every lookup is linear in the slices."""
        w = Warp.__new__(Warp)
        w.params, w.sizes = [], []
        w.ny, w.nx = self.ny, self.nx

        def mix(a):
            m = sum(float(np.ravel(wt)[0]) * a[int(np.ravel(ix)[0])] for ix, wt in corners)[None]
            m.flags.writeable = False  # kept in RglData.lights, shared by later evaluations
            return m

        w.data = mix(self.data)
        if hasattr(self, "cond"):
            w.cond, w.marg = mix(self.cond), mix(self.marg)
        return w

    def cells(self, u) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """``(ix, fx, iy, fy)``: cell indices and fractions of ``u = (x, y)`` in this grid.
        They depend on ``u`` and the grid's size only: warps of equal sizes share them."""
        return (*_cell(u[0], self.nx), *_cell(u[1], self.ny))

    def eval(self, u, corners, cells=None) -> np.ndarray:
        """Bilinear interpolation of the (un-normalised) data at ``u = (x, y)``."""
        ix, fx, iy, fy = self.cells(u) if cells is None else cells
        d = self.data
        if d.ndim == 3:  # (S, ny·nx, channels): the same weights for every channel
            fx, fy = _spread(fx, d.shape[2:]), _spread(fy, d.shape[2:])
        nx = self.nx  # cell (iy, ix) is at iy·nx + ix; its corners (y, x) = (0, 0) … (1, 1)
        v00, v01, v10, v11 = self.lookup(d, corners, iy * nx + ix, (0, 1, nx, nx + 1))
        return (1 - fy) * ((1 - fx) * v00 + fx * v01) + fy * ((1 - fx) * v10 + fx * v11)

    def invert(self, u, corners, cells=None) -> tuple[np.ndarray, np.ndarray]:
        """``Marginal2D::invert``: the unit-square sample that ``sample()`` maps to ``u``."""
        ix, sx, iy, sy = self.cells(u) if cells is None else cells
        nx = self.nx
        at, end = iy * nx + ix, iy * nx + (nx - 1)  # cell (iy, ix) and its row's end
        v00, v10, v01, v11 = self.lookup(self.data, corners, at, (0, 1, nx, nx + 1))  # v_xy
        c0 = (1 - sy) * v00 + sy * v01
        c1 = (1 - sy) * v10 + sy * v11
        x = sx * (c0 + 0.5 * sx * (c1 - c0))
        C0, C1 = self.lookup(self.cond, corners, at, (0, nx))  # rows iy and iy + 1
        x = x + (1 - sy) * C0 + sy * C1
        r0, r1 = self.lookup(self.cond, corners, end, (0, nx))
        row = (1 - sy) * r0 + sy * r1
        x = safe_div(x, row, row > 0)  # an all-zero row (no density): 0
        y = sy * (r0 + 0.5 * sy * (r1 - r0))
        y = y + self.lookup(self.marg, corners, iy)[0]
        return x, y


#: the corners of a warp without parameters (ndf, σ) or of a collapsed one: its one table
ONE = ((0, 1.0),)


def _spread(w, channels: tuple[int, ...]):
    """Per-direction weights ``w`` repeated over ``channels`` (a copy: numpy multiplies an
    (N, 3) array by an (N, 1) one several times slower than by an (N, 3) one)."""
    if not channels or not np.ndim(w):
        return w
    return np.repeat(w[..., None], channels[0], axis=-1)


def _cell(pos: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Cell index and fraction of unit-square coordinate ``pos`` on an axis of n samples
    (``np.minimum``/``np.maximum``: ``np.clip``'s wrapper costs more than the clipping)."""
    p = np.minimum(np.maximum(pos, 0.0), 1.0) * (n - 1)
    i = np.minimum(p.astype(np.intp), n - 2)
    return i, p - i


# --------------------------------------------------------------------------- the material


@dataclass
class RglData:
    path: str
    description: str
    isotropic: bool
    jacobian: bool
    reduction: int
    spectral: bool
    n_wavelengths: int
    n_invalid: int | None
    phi_i: np.ndarray
    theta_i: np.ndarray
    ndf: Warp
    sigma: Warp
    vndf: Warp
    rgb: Warp  # (S, ny·nx, 3) float64, linear sRGB; shares the vndf's parameter grid
    #: :class:`Light` by its (φi, θi): this file's own, bounded
    lights: LRU = field(default_factory=lambda: LRU(LIGHT_CACHE), repr=False, compare=False)

    def __call__(self, wi, wo):
        return evaluate(self, wi, wo)


def _check_float(path, arrays, name, ndim):
    if name not in arrays:
        raise BsdfError(f"{path}: missing field {name!r}")
    a = arrays[name]
    if a.dtype.kind != "f" or a.dtype.itemsize not in (4, 8):
        raise BsdfError(f"{path}: field {name!r} has type {a.dtype}, expected float32")
    if a.ndim != ndim:
        raise BsdfError(f"{path}: field {name!r} has {a.ndim} dimensions, expected {ndim}")
    a = a.astype(np.float64)
    if not np.all(np.isfinite(a)):
        n = int((~np.isfinite(a)).sum())
        raise BsdfError(f"{path}: field {name!r} has {n} NaN or infinite values")
    mag = np.abs(a)
    if a.size and mag.max() > MAX_MAGNITUDE:
        raise BsdfError(f"{path}: field {name!r} has values up to {mag.max():.3g} in magnitude "
                        f"(at most {MAX_MAGNITUDE:g}; measured data lies far below)")
    a[mag < MIN_MAGNITUDE] = 0.0  # below any measurement's resolution: 0 (keeps 1/x finite)
    return a


def load(path: str | os.PathLike) -> RglData:
    """Read, validate and prepare an RGL ``.bsdf`` file (raises :class:`BsdfError`)."""
    path = os.fspath(path)
    arrays = read_tensor(path, KNOWN_FIELDS)

    def need(name):
        if name not in arrays:
            raise BsdfError(f"{path}: missing field {name!r} (an RGL material has "
                            "description, phi_i, theta_i, ndf, sigma, vndf, luminance, rgb or "
                            "spectra + wavelengths, jacobian)")
        return arrays[name]

    desc = need("description")
    jac = need("jacobian")
    if desc.dtype != np.uint8 or desc.ndim != 1:
        raise BsdfError(f"{path}: field 'description' must be uint8 text")
    if jac.dtype != np.uint8 or jac.shape != (1,):
        raise BsdfError(f"{path}: field 'jacobian' must be one uint8, found {jac.dtype} × "
                        f"{jac.shape}")
    phi = _check_float(path, arrays, "phi_i", 1)
    theta = _check_float(path, arrays, "theta_i", 1)
    ndf = _check_float(path, arrays, "ndf", 2)
    sigma = _check_float(path, arrays, "sigma", 2)
    vndf = _check_float(path, arrays, "vndf", 4)
    lum = _check_float(path, arrays, "luminance", 4)
    spectral = "rgb" not in arrays and "spectra" in arrays
    if not spectral:
        need("rgb")
    values = _check_float(path, arrays, "spectra" if spectral else "rgb", 5)
    n_phi, n_theta = len(phi), len(theta)
    for name, grid in (("phi_i", phi), ("theta_i", theta)):
        if len(grid) < 1 or (len(grid) > 1 and not np.all(np.diff(grid) > 0)):
            raise BsdfError(f"{path}: field {name!r} must be a non-empty, strictly increasing "
                            "grid")
    for name, a in (("ndf", ndf), ("sigma", sigma)):
        if min(a.shape) < 2:
            raise BsdfError(f"{path}: field {name!r} has shape {a.shape}: each side ≥ 2")
    if vndf.shape[:2] != (n_phi, n_theta) or min(vndf.shape[2:]) < 2:
        raise BsdfError(f"{path}: field 'vndf' has shape {vndf.shape}, expected "
                        f"({n_phi}, {n_theta}, ny ≥ 2, nx ≥ 2)")
    if lum.shape[:2] != (n_phi, n_theta) or lum.shape[2] != lum.shape[3] or lum.shape[2] < 2:
        raise BsdfError(f"{path}: field 'luminance' has shape {lum.shape}, expected "
                        f"({n_phi}, {n_theta}, n, n) with n ≥ 2")
    name = "spectra" if spectral else "rgb"
    if values.shape[:2] != (n_phi, n_theta) or values.shape[3:] != lum.shape[2:]:
        raise BsdfError(f"{path}: field {name!r} has shape {values.shape}, expected "
                        f"({n_phi}, {n_theta}, {'λ' if spectral else 3}, {lum.shape[2]}, "
                        f"{lum.shape[3]})")
    if spectral:
        wl = _check_float(path, arrays, "wavelengths", 1)
        if len(wl) != values.shape[2] or (len(wl) > 1 and not np.all(np.diff(wl) > 0)):
            raise BsdfError(f"{path}: field 'wavelengths' must list the {values.shape[2]} "
                            "wavelengths of 'spectra', increasing")
        from tuibrdf.core.formats.cie import spectrum_to_srgb_matrix

        try:
            m = spectrum_to_srgb_matrix(wl)
        except ValueError as e:
            raise BsdfError(f"{path}: {e}") from None
        rgb = np.einsum("pwl...,lc->pwc...", values, m)
    else:
        if values.shape[2] != 3:
            raise BsdfError(f"{path}: field 'rgb' has {values.shape[2]} channels, expected 3")
        rgb = values
    if np.any(vndf < 0):
        raise BsdfError(f"{path}: field 'vndf' has negative values (it is a density)")
    isotropic = n_phi <= 2
    reduction = 1
    if not isotropic:
        span = phi[-1] - phi[0]
        reduction = int(np.rint(2 * np.pi / span)) if span > 0 else 0
        if reduction not in (1, 2, 4):
            raise BsdfError(f"{path}: the φi grid spans {np.degrees(span):.4g}°: expected "
                            "360°, 180° or 90° (symmetry reduction 1, 2 or 4)")
    params = [phi.astype(np.float64), theta.astype(np.float64)]
    vwarp = Warp(vndf, params, cdf=True)
    empty = vwarp.marg[:, -1] <= 0.0
    if np.any(empty):
        raise BsdfError(f"{path}: field 'vndf' is zero everywhere in {int(empty.sum())} "
                        "incidence slice(s)")
    valid = arrays.get("valid")
    n_invalid = int(np.count_nonzero(valid == 0)) if valid is not None else None
    return RglData(
        path=path,
        description=_inert(bytes(desc).decode("utf-8", errors="replace").strip("\0 \n")),
        isotropic=isotropic, jacobian=bool(jac[0]), reduction=reduction, spectral=spectral,
        n_wavelengths=int(values.shape[2]) if spectral else 0, n_invalid=n_invalid,
        phi_i=params[0], theta_i=params[1],
        ndf=Warp(ndf, [], cdf=False), sigma=Warp(sigma, [], cdf=False), vndf=vwarp,
        rgb=_channels_last(rgb, params),
    )


#: control characters (C0, DEL, C1, line separators) → visible escapes: a description is the
#: file's text, printed by `tuibrdf models` and shown in the viewer, never sent raw
_CONTROL = {c: f"\\x{c:02x}" for c in (*range(0x20), 0x7F, *range(0x80, 0xA0))}
_CONTROL.update({0x2028: "\\u2028", 0x2029: "\\u2029"})


def _inert(text: str) -> str:
    return text.translate(_CONTROL)


def _channels_last(rgb: np.ndarray, params: list[np.ndarray]) -> Warp:
    """The ``(φi, θi, 3, ny, nx)`` tensor as a warp over ``(S, ny·nx, 3)`` (no CDFs)."""
    w = Warp.__new__(Warp)
    w.params = params
    w.sizes = [len(p) for p in params]
    s = int(np.prod(w.sizes))
    w.ny, w.nx = rgb.shape[3:]
    w.data = np.ascontiguousarray(np.moveaxis(rgb.reshape(s, 3, w.ny * w.nx), 1, -1),
                                  dtype=np.float64)
    return w


def _elevation(d: np.ndarray) -> np.ndarray:
    """``acos(d.z)`` computed as ``2 asin(|d − N| / 2)`` (powitacq's robust form)."""
    dist = np.sqrt(d[..., 0] ** 2 + d[..., 1] ** 2 + (d[..., 2] - 1.0) ** 2)
    return 2.0 * np.arcsin(np.minimum(0.5 * dist, 1.0))


def _theta2u(t):
    return np.sqrt(np.maximum(t, 0.0) * (2.0 / np.pi))


def _phi2u(p):
    return (p + np.pi) / (2.0 * np.pi)


class Light(NamedTuple):
    """What evaluating one incidence needs of it, computed once (:func:`_light`)."""

    vndf: Warp  # the warps collapsed at the incidence (:meth:`Warp.collapse`)
    rgb: Warp
    den: np.ndarray | None  # 4 σ(u(wi)), shape (1,) (step 5; None without the jacobian)


def _light(data: RglData, phi_i: float, theta_i: float) -> Light:
    """The :class:`Light` of incidence (φi, θi), kept in the file's :attr:`RglData.lights`:
    the key is all it depends on, the elevation and azimuth of ``wi`` (after the reduction)."""

    def make():
        phi, theta = np.array([phi_i]), np.array([theta_i])
        corners = data.vndf.corners([phi, theta])
        den = None
        if data.jacobian:
            den = _sigma4(data, phi, theta)
            den.flags.writeable = False  # shared by later evaluations
        return Light(data.vndf.collapse(corners), data.rgb.collapse(corners), den)

    return data.lights.get((phi_i, theta_i), make)


def _sigma4(data: RglData, phi_i: np.ndarray, theta_i: np.ndarray) -> np.ndarray:
    """``4 σ(u(wi))``, the jacobian's denominator (step 5)."""
    return 4.0 * data.sigma.eval((_theta2u(theta_i), _phi2u(phi_i)), ONE)


def evaluate(data: RglData, wi: np.ndarray, wo: np.ndarray, clamp: bool = True,
             floor: bool = True) -> np.ndarray:
    """RGB BRDF values (sr⁻¹, no cosine factor), shape ``(..., 3)``; negative values clamped to
    0 unless ``clamp`` is False (module docstring).  ``floor=False``: the file's own f, its
    f·cos θo divided by cos θo all the way to the horizon (the albedo integrates that)."""
    wi, wo = np.asarray(wi, dtype=float), np.asarray(wo, dtype=float)
    # one incidence for all (a map, the peak finder): wi stays one row, broadcast against wo
    # in each operation, and what depends on it alone is computed once (_light)
    one_light = wi.size == 3
    shape = wo.shape[:-1] if wi.ndim == 1 else np.broadcast_shapes(wi.shape, wo.shape)[:-1]
    if one_light:
        wi = wi.reshape(1, 3).copy()
        wo = wo.reshape(-1, 3).copy()
    else:
        wi, wo = np.broadcast_arrays(wi, wo)
        wi = wi.reshape(-1, 3).copy()
        wo = wo.reshape(-1, 3).copy()
    # wo on the horizon: the limit from above (the held cos θo), so f is continuous on the
    # closed hemisphere and its supremum there is a value (powitacq returns 0); the file's
    # own f (floor=False) has no finite limit there and stays 0
    active = (wi[:, 2] > 0) & ((wo[:, 2] >= 0) if floor else (wo[:, 2] > 0))
    if data.reduction >= 2:  # into the measured half/quadrant (Mitsuba 3's mulsign_neg)
        sy = wi[:, 1]
        sx = wi[:, 0] if data.reduction == 4 else sy
        fx = np.where(sx >= 0, -1.0, 1.0)
        fy = np.where(sy >= 0, -1.0, 1.0)
        wi[:, 0] *= fx
        wo[:, 0] *= fx
        wi[:, 1] *= fy
        wo[:, 1] *= fy
    s = wi + wo
    n = np.sqrt(np.add.reduce(s * s, axis=-1))
    ok = active & (n > 0)
    wm = s / np.where(ok, n, 1.0)[:, None]  # wi = −wo: H undefined (inactive anyway)
    theta_i, phi_i = _elevation(wi), np.arctan2(wi[:, 1], wi[:, 0])
    theta_m, phi_m = _elevation(wm), np.arctan2(wm[:, 1], wm[:, 0])
    um_y = _phi2u(phi_m - phi_i if data.isotropic else phi_m)
    u_wm = (_theta2u(theta_m), um_y - np.floor(um_y))
    if one_light:
        vndf, rgb, den = _light(data, float(phi_i[0]), float(theta_i[0]))
        corners = ONE
    else:
        vndf, rgb = data.vndf, data.rgb
        corners = vndf.corners([phi_i, theta_i])
        den = _sigma4(data, phi_i, theta_i) if data.jacobian else None
    cells_m = vndf.cells(u_wm)  # u(wm)'s cells, shared with the ndf if its grid is the same
    x, y = vndf.invert(u_wm, corners, cells_m)
    out = rgb.eval((x, y), corners)  # (N, 3): all channels in one gather per corner
    if data.jacobian:
        ndf = data.ndf
        same = (ndf.ny, ndf.nx) == (vndf.ny, vndf.nx)
        num = ndf.eval(u_wm, ONE, cells_m if same else None)
        out *= safe_div(num, den, den > 0)[:, None]  # σ = 0: no projected area, value 0
    # the data is f·cos θo (powitacq's eval); floor=False: cos θo itself, ≥ 1e-200 (no
    # overflow; that close to the horizon the solid angle is nil)
    cos_o = np.maximum(wo[:, 2], COS_FLOOR if floor else 1e-200)
    out /= cos_o[:, None]
    if clamp:
        out = np.maximum(out, 0.0)  # out-of-gamut spectra give negative RGB: shown as 0
    out = np.where(ok[:, None], out, 0.0)
    return out.reshape(*shape, 3)


# --------------------------------------------------------------------------- the model

def _kernel(data: RglData, wi, wo):
    return evaluate(data, wi, wo)


def load_model(path: str, name: str) -> Model:
    """A ``.bsdf`` file as an RGB model named ``name`` (no parameters)."""
    data = load(path)
    kind = f"spectral ({data.n_wavelengths} λ → sRGB, D65)" if data.spectral else "RGB"
    sym = "isotropic" if data.isotropic else f"anisotropic (reduction {data.reduction})"
    notes = [f"{kind}, {sym}, jacobian {int(data.jacobian)}",
             "negative RGB (out-of-gamut spectra) clamped to 0 for display"]
    if data.n_invalid is not None:
        notes.append(f"'valid' mask: {data.n_invalid} invalid entries (not applied, as "
                     "powitacq and Mitsuba)")
    title = os.path.basename(path) + (f" — {data.description[:40]}" if data.description else "")
    # The albedo ∫ f cos θo dωo of a file of f·cos θo is the integral of that f·cos θo
    # itself: it integrates the file's own f, divided by cos θo all the way to the horizon
    # (floor=False; the albedo's cos θo cancels the 1/cos θo), not the shown f, whose cos θo
    # is held at cos 89.9° (it would lose the part beyond 89.9°: 7.1e-5 of paper_white's
    # albedo at θi = 0)
    return Model(
        name, title, (), partial(_kernel, data), rgb=True, reciprocal=False,
        albedo_kernel=partial(evaluate, data, floor=False), measured=True,
        summary="RGL-EPFL measured material (Dupuy & Jakob 2018), evaluated as powitacq",
        horizon=("cos θo held at cos 89.9° within 0.1° of the horizon, on it too (powitacq: "
                 "0 on it)"),
        notes=tuple(notes),
    )


__all__ = ["BsdfError", "RglData", "evaluate", "load", "load_model", "read_tensor"]
