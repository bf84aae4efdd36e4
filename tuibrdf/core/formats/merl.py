"""MERL measured BRDFs (Matusik, Pfister, Brand, McMillan 2003): reader and lookup.

SPEC §6 fixes the format, which is that of MERL's own
``BRDFRead.cpp``:

* a header of 3 little-endian int32: ``(90, 90, 180)`` = (θh bins, θd bins, φd bins);
* then ``3 × 1 458 000`` little-endian float64, planar: all R, then all G, then all B;
* sample ``(iθh, iθd, iφd)`` is at flat index ``iφd + 180·(iθd + 90·iθh)`` of each plane;
* values are scaled by R 1/1500, G 1.15/1500, B 1.66/1500 to give sr⁻¹;
* a negative value marks a bin that was not measured;
* the file is exactly 12 + 3·1 458 000·8 = 34 992 012 bytes.

Coordinates (Rusinkiewicz 1998): ``H = normalize(wi + wo)``, ``θh = angle(H, N)``, and the
difference vector ``d = Rot_y(-θh)·Rot_z(-φh)·wi`` (``wi`` expressed in a frame where H is the
pole) gives ``θd``, ``φd``.  Bin coordinates (continuous; the bin is their floor, clamped)::

    tθh = 90·√(θh / (π/2))       the √ mapping: fine bins near the specular peak
    tθd = 90·θd / (π/2)
    tφd = 180·φd / π             φd folded to [0, π)

Bin ``i`` of an axis covers bin coordinates ``[i, i + 1)`` and its value sits at the bin's
centre, ``t = i + ½`` (SPEC §6): θh = ((i + ½)/90)²·90°, θd = (i + ½)°, φd = (i + ½)°.
Lookups:

* ``nearest``: the bin that contains the direction, ``⌊t⌋`` clamped — the rule of
  ``BRDFRead.cpp`` (and pbrt-v2's ``RegularHalfangleBRDF``);
* ``trilinear``: linear in each of ``tθh, tθd, tφd`` between the centres of bins ``⌊t − ½⌋``
  and ``⌊t − ½⌋ + 1``.  Ends: in the outer half of the first and last bins of θh and θd
  (``t < ½`` or ``t > n − ½``) the bin's value is held constant (clamped); φd is periodic
  (φd ≡ φd + π), so the outer halves of bins 179 and 0 interpolate with each other.
  At a bin's centre both lookups give the bin's own value: they agree there.

Reciprocity.  Swapping ``wi`` and ``wo`` keeps H and maps ``d → (-dx, -dy, dz)``, i.e.
``φd → φd + π``: that is the folding.  Here ``d``'s horizontal part is computed from ``wi - wo``
(which is exactly antisymmetric in floating point: ``R(wi) = (R(wi - wo)/2)_xy + |wi+wo|/2·z``
because ``wi - wo ⟂ H``), and ``(dx, dy)`` is canonicalised to the upper half-plane before
``atan2``; so swapped arguments give bit-identical bin coordinates and **both** lookups are
exactly reciprocal.

Invalid bins (negative values) are replaced at load time by the value of the nearest valid bin
along θd in the same (θh, φd) column (ties go to the smaller θd); a column with no valid bin is
filled with 0.  Unmeasured bins in MERL files are the grazing ones (large θd), whose best guess
is their neighbour toward normal incidence; never drawn as negative.  The count is kept.

Domain: directions with ``z < 0`` (below the horizon) give 0; so does ``wi = -wo`` (both on the
horizon, H undefined).  On the horizon itself the clamped bins give the data's value there.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable
from dataclasses import dataclass
from functools import partial

import numpy as np

from tuibrdf.core.formats.files import open_regular
from tuibrdf.core.lru import LRU
from tuibrdf.core.numerics import safe_div
from tuibrdf.core.params import Model, Param

N_THETA_H = 90
N_THETA_D = 90
N_PHI_D = 180
N_SAMPLES = N_THETA_H * N_THETA_D * N_PHI_D  # 1 458 000 per channel
HEADER = (N_THETA_H, N_THETA_D, N_PHI_D)
HEADER_BYTES = 12
FILE_BYTES = HEADER_BYTES + 3 * N_SAMPLES * 8  # 34 992 012
#: per-channel scale from file units to sr⁻¹ (BRDFRead.cpp's RED/GREEN/BLUE_SCALE)
SCALES = (1.0 / 1500.0, 1.15 / 1500.0, 1.66 / 1500.0)
LOOKUPS = ("nearest", "trilinear")


class MerlError(ValueError):
    """A file that is not a valid MERL ``.binary``; the message names the file and the problem."""


@dataclass(frozen=True)
class MerlData:
    """A loaded MERL BRDF.

    ``table`` has shape ``(3, 90, 90, 180)`` = (channel, θh bin, θd bin, φd bin), float64 in
    sr⁻¹, invalid bins already filled; it is the only copy of the data (a view of the array read
    from the file).  ``n_invalid`` counts the filled bins per channel.
    """

    path: str
    table: np.ndarray
    n_invalid: tuple[int, int, int]

    def __call__(self, wi: np.ndarray, wo: np.ndarray, lookup: str = "trilinear") -> np.ndarray:
        return evaluate(self, wi, wo, lookup)


#: bytes read per ``readinto`` call: 1/32 of the data, so a progress bar moves smoothly
CHUNK_BYTES = 3 * N_SAMPLES * 8 // 32


NO_FILE = "merl: no file given: pass -p file=PATH.binary (or tuibrdf view PATH.binary)"


def _bad(name: str, problem: str) -> MerlError:
    return MerlError(f"{name}: not a MERL .binary file: {problem}")


def _check_open(f, name: str) -> None:
    """Check the header and size of an open MERL file (left positioned after the header).
    Raises :class:`MerlError`."""
    bad = partial(_bad, name)
    size = os.fstat(f.fileno()).st_size
    head = f.read(HEADER_BYTES)
    if len(head) < HEADER_BYTES:
        raise bad(f"truncated header ({size} bytes, expected {FILE_BYTES:,})")
    dims = tuple(int(v) for v in np.frombuffer(head, dtype="<i4"))
    if dims != HEADER:
        raise bad(f"wrong header {dims}, expected {HEADER} (θh, θd, φd bins)")
    if size < FILE_BYTES:
        raise bad(f"truncated data ({size:,} bytes, expected {FILE_BYTES:,})")
    if size > FILE_BYTES:
        raise bad(f"wrong size ({size:,} bytes, expected {FILE_BYTES:,}: "
                  f"{size - FILE_BYTES:,} trailing bytes)")


def check_file(path: str | os.PathLike) -> None:
    """The cheap part of :func:`load`'s validation (the file opens, header, size) without
    reading the data: what ``tuibrdf view FILE.binary`` checks before the viewer opens.
    Raises :class:`MerlError`."""
    name = os.fspath(path)
    if not name:
        raise MerlError(NO_FILE)
    try:
        with open_regular(name) as f:  # never blocks on a FIFO
            _check_open(f, name)
    except OSError as e:
        raise MerlError(f"{name}: cannot read: {e.strerror or e}") from None


def load(path: str | os.PathLike,
         progress: Callable[[float], None] | None = None) -> MerlData:
    """Read and validate a MERL ``.binary`` file.

    Raises :class:`MerlError` (a ``ValueError``) naming the file and the problem for a missing
    or unreadable file, a wrong header, a wrong size (truncated or trailing bytes) and NaN or
    infinite values.  ``progress(fraction)`` is called with fractions rising from 0 to 1 (reading
    is 0 → 0.9, checking, scaling and filling 0.9 → 1), for a progress bar in the app.

    Memory: the file is read straight into one preallocated float64 array of 3·1 458 000 values
    (35 MB) with ``readinto``; it is checked, scaled and filled in place, one channel at a time,
    and becomes :attr:`MerlData.table` without a copy.  Temporaries are per channel (masks of
    1.5 MB); see docs/reference/formats.md for the measured peak.
    """
    name = os.fspath(path)
    report = progress or (lambda fraction: None)
    bad = partial(_bad, name)
    report(0.0)
    try:
        with open_regular(name) as f:  # never blocks on a FIFO
            _check_open(f, name)
            data = np.empty(3 * N_SAMPLES, dtype="<f8")  # the one copy
            raw = memoryview(data).cast("B")
            done = 0
            while done < raw.nbytes:
                n = f.readinto(raw[done:done + CHUNK_BYTES])
                if not n:  # the file shrank between stat and read
                    raise bad(f"truncated data ({HEADER_BYTES + done:,} bytes, expected "
                              f"{FILE_BYTES:,})")
                done += n
                report(0.9 * done / raw.nbytes)
            del raw
    except OSError as e:
        raise MerlError(f"{name}: cannot read: {e.strerror or e}") from None
    if data.dtype != np.float64:  # big-endian host: one conversion (a no-op on little-endian)
        data = data.astype(np.float64)
    planes = data.reshape(3, N_SAMPLES)
    n_invalid = []
    for c, scale in enumerate(SCALES):
        plane = planes[c]
        finite = np.isfinite(plane)
        if not finite.all():
            k = int(np.flatnonzero(~finite)[0])
            kind = "NaN" if np.isnan(plane[k]) else "infinite"
            ih, rest = divmod(k, N_THETA_D * N_PHI_D)
            idd, ip = divmod(rest, N_PHI_D)
            raise bad(f"{kind} value in channel {'RGB'[c]} at bin "
                      f"(θh {ih}, θd {idd}, φd {ip}) and {int((~finite).sum()) - 1} more")
        del finite
        plane *= scale
        n_invalid.append(_fill_invalid(plane.reshape(N_THETA_H, N_THETA_D, N_PHI_D)))
        report(0.9 + 0.1 * (c + 1) / 3)
    table = data.reshape(3, N_THETA_H, N_THETA_D, N_PHI_D)
    table.flags.writeable = False
    return MerlData(name, table, tuple(n_invalid))


#: θh rows filled at a time: keeps the fill's temporaries to ~1/6 of a channel
FILL_ROWS = 15


def _fill_invalid(t: np.ndarray) -> int:
    """Fill negative bins of one channel ``(θh, θd, φd)`` in place from the nearest valid bin
    along θd (ties: the smaller θd); columns without any valid bin become 0.  Returns the count.

    The rule works within one θh row, so rows are filled in slabs of :data:`FILL_ROWS`."""
    return sum(_fill_slab(t[r:r + FILL_ROWS]) for r in range(0, t.shape[0], FILL_ROWS))


def _fill_slab(t: np.ndarray) -> int:
    invalid = t < 0.0
    count = int(np.count_nonzero(invalid))
    if count == 0:
        return 0
    n = t.shape[1]
    j = np.arange(n, dtype=np.int8)[None, :, None]
    # index of the last valid bin at or before each θd (-1: none), and of the first at or
    # after it (n: none), as int8 running max / min along θd
    below = np.maximum.accumulate(np.where(invalid, np.int8(-1), j), axis=1)
    above = np.minimum.accumulate(np.where(invalid, np.int8(n), j)[:, ::-1], axis=1)[:, ::-1]
    ih, jd, kp = np.nonzero(invalid)
    del invalid
    b = below[ih, jd, kp].astype(np.intp)
    a = above[ih, jd, kp].astype(np.intp)
    del below, above
    # the nearer side; distance ties go below; a side without a valid bin is never chosen
    use_above = (b < 0) | ((a < n) & (a - jd < jd - b))
    src = np.where(use_above, a, b)
    ok = (src >= 0) & (src < n)
    t[ih, jd, kp] = np.where(ok, t[ih, np.where(ok, src, 0), kp], 0.0)
    return count


# -- coordinates -------------------------------------------------------------------------------


def half_diff(wi: np.ndarray, wo: np.ndarray):
    """``(θh, θd, φd, valid)`` in radians, φd folded to [0, π]; ``valid`` is False where
    ``wi + wo = 0`` (H undefined; the angles there are 0).

    ``d = Rot_y(-θh)·Rot_z(-φh)·wi``; its z is ``|wi+wo|/2`` and its xy part the rotated
    ``(wi - wo)/2`` (see the module docstring), which makes the result exactly symmetric in
    ``(wi, wo)``.  φh is 0 where H = N (as ``atan2(0, 0)`` in BRDFRead.cpp).
    """
    angles, valid = _angles(np.asarray(wi, dtype=float), np.asarray(wo, dtype=float))
    theta_h, theta_d, phi_d = np.where(valid, angles, 0.0) + 0.0  # + 0.0: no -0.0
    return theta_h, theta_d, phi_d, valid


def _angles(wi: np.ndarray, wo: np.ndarray):
    """:func:`half_diff`'s angles stacked, shape ``(3, ...)``, and ``valid``; where ``wi + wo =
    0`` the angles are finite but meaningless (not yet 0), and φd may be -0.0 (``np.mod`` in
    :func:`_to_bin_coordinates` makes that 0.0)."""
    s = wi + wo
    u = 0.5 * (wi - wo)
    q = s * s
    s_len = np.sqrt(q[..., 0] + q[..., 1] + q[..., 2])  # np.sum's order; 3x faster at 400
    valid = s_len > 0.0
    h = s / np.where(valid, s_len, 1.0)[..., None]  # |wi+wo| = 0: H undefined, h = 0 unused
    cos_th, sin_th = h[..., 2], np.hypot(h[..., 0], h[..., 1])
    off_pole = sin_th != 0.0
    # H = N: φh = 0 by convention (cos φh = 1, sin φh = 0)
    cos_ph = safe_div(h[..., 0], sin_th, off_pole, fill=1.0)
    sin_ph = safe_div(h[..., 1], sin_th, off_pole)
    # Rot_z(-φh), then Rot_y(-θh) applied to u (u ⟂ H)
    x1 = cos_ph * u[..., 0] + sin_ph * u[..., 1]
    dy = cos_ph * u[..., 1] - sin_ph * u[..., 0]
    dx = cos_th * x1 - sin_th * u[..., 2]
    angles = np.empty((3, *valid.shape))
    theta_h, theta_d, phi_d = angles[0, ...], angles[1, ...], angles[2, ...]  # 0-d for one pair
    np.arctan2(sin_th, cos_th, out=theta_h)
    np.arctan2(np.hypot(dx, dy), 0.5 * s_len, out=theta_d)
    # fold φd by reciprocity: (dx, dy) and (-dx, -dy) are the same sample; turn it by π where
    # dy < 0, or dy = ±0 and dx < 0 (×(−1) is exact)
    sign = np.where(np.where(dy != 0.0, dy, dx) < 0.0, -1.0, 1.0)
    np.arctan2(sign * dy, sign * dx, out=phi_d)
    return angles, valid


#: bins per axis (θh, θd, φd), as a column
_BINS = np.array([[N_THETA_H], [N_THETA_D], [N_PHI_D]], dtype=float)


def bin_coordinates(theta_h, theta_d, phi_d):
    """Continuous bin coordinates ``(tθh, tθd, tφd)``; the bin is their floor (clamped)."""
    angles = np.array(np.broadcast_arrays(theta_h, theta_d, phi_d), dtype=float)
    t_h, t_d, t_p = _to_bin_coordinates(angles.reshape(3, -1)).reshape(angles.shape)
    return t_h, t_d, t_p


def _to_bin_coordinates(t: np.ndarray) -> np.ndarray:
    """:func:`bin_coordinates` in place on stacked angles ``(3, n)``; returns ``t``."""
    t[:2] /= np.pi / 2
    np.maximum(t[:2], 0.0, out=t[:2])  # clamp to [0, 1]: np.clip without its Python wrapper
    np.minimum(t[:2], 1.0, out=t[:2])
    np.sqrt(t[0], out=t[0])  # the √ mapping of θh
    np.mod(t[2], np.pi, out=t[2])
    t *= _BINS
    t[2] /= np.pi  # tφd = 180·(φd mod π)/π
    return t


def flat_index(i_h, i_d, i_p):
    """Index into one channel's plane: ``iφd + 180·(iθd + 90·iθh)``."""
    return i_p + N_PHI_D * (i_d + N_THETA_D * i_h)


#: directions per block of :func:`evaluate`: a block's temporaries (1-2 MB) stay in cache and are
#: recycled by malloc; 20 000 directions in one block spent half their time faulting in pages
BLOCK = 2048


def evaluate(data: MerlData, wi: np.ndarray, wo: np.ndarray,
             lookup: str = "trilinear") -> np.ndarray:
    """RGB BRDF values (sr⁻¹, shape ``(..., 3)``) for directions of shape ``(..., 3)``.

    Cost: the viewer calls this ~25 times a frame with 50-400 directions, where numpy's fixed
    cost per call dominates; so the trilinear lookup treats the three axes and the eight corners
    in one array each (a few dozen numpy calls in all).  Many directions go in blocks of
    :data:`BLOCK`.
    """
    if lookup not in LOOKUPS:
        raise ValueError(f"merl: lookup {lookup!r} is invalid: expected one of "
                         + ", ".join(LOOKUPS))
    wi = np.asarray(wi, dtype=float)
    wo = np.asarray(wo, dtype=float)
    shape = np.broadcast(wi, wo).shape
    if math.prod(shape[:-1]) <= BLOCK:
        return _evaluate(data, wi, wo, lookup)
    wi = np.broadcast_to(wi, shape).reshape(-1, 3)
    wo = np.broadcast_to(wo, shape).reshape(-1, 3)
    out = np.empty(wi.shape)
    for start in range(0, len(out), BLOCK):
        block = slice(start, start + BLOCK)
        out[block] = _evaluate(data, wi[block], wo[block], lookup)
    return out.reshape(shape)


def _evaluate(data: MerlData, wi: np.ndarray, wo: np.ndarray, lookup: str) -> np.ndarray:
    """:func:`evaluate` in one block (float64 arrays, ``lookup`` checked)."""
    angles, valid = _angles(wi, wo)  # broadcasts wi against wo
    inside = valid & (np.minimum(wi[..., 2], wo[..., 2]) >= 0.0)  # elsewhere the angles are moot
    planes = data.table.reshape(3, N_SAMPLES)
    t = _to_bin_coordinates(angles.reshape(3, -1))
    if lookup == "nearest":
        i = np.minimum(t.astype(np.intp), _I_LAST)
        rgb = planes.take(flat_index(*i), axis=1)  # take: 2-3x fancy indexing
    else:
        rgb = _trilinear(planes, t)
    np.maximum(rgb, 0.0, out=rgb)
    rgb *= inside.reshape(-1)  # 0 outside (the values are finite: load checks them)
    return rgb.T.copy().reshape(*inside.shape, 3)  # (n, 3) in C order


#: per axis (θh, θd, φd), as columns: the range of s = t − ½ in units of samples (θh and θd
#: clamped to their first and last samples; φd periodic, not clamped), the last sample, and
#: the stride of the flat index
_S_FIRST = np.array([[0.0], [0.0], [-np.inf]])
_S_LAST = np.array([[N_THETA_H - 1.0], [N_THETA_D - 1.0], [np.inf]])
_I_LAST = np.array([[N_THETA_H - 1], [N_THETA_D - 1], [N_PHI_D - 1]])
_STRIDE = np.array([[N_THETA_D * N_PHI_D], [N_PHI_D], [1]])


def _trilinear(planes: np.ndarray, t: np.ndarray) -> np.ndarray:
    """``(3, n)`` RGB by trilinear lookup at bin coordinates ``t`` (shape ``(3, n)``: tθh, tθd,
    tφd) between bin centres (sample ``i`` at ``t = i + ½``).

    Per axis: ``s = t − ½`` (sample ``i`` at ``s = i``), samples ``⌊s⌋`` and ``⌊s⌋ + 1`` with
    weights ``1 − w`` and ``w = s − ⌊s⌋``.  Clamping ``s`` of θh and θd to ``[0, n − 1]`` is the
    end rule (outside it the end sample, with weight 1); φd's samples wrap (−1 → 179, 180 → 0).
    The three axes are the rows of one array and the eight corners one broadcast; directions
    stay the last (contiguous) axis, which numpy's loops need to be fast."""
    s = t - 0.5
    np.maximum(s, _S_FIRST, out=s)
    np.minimum(s, _S_LAST, out=s)
    lower = np.floor(s)
    n = s.shape[1]
    idx = np.empty((2, 3, n), dtype=np.intp)  # (sample ⌊s⌋ or ⌊s⌋ + 1, axis, direction)
    idx[0] = lower
    np.add(idx[0], 1, out=idx[1])
    np.minimum(idx[1, :2], _I_LAST[:2], out=idx[1, :2])  # θh, θd at s = n − 1 (where w = 0)
    np.mod(idx[:, 2], N_PHI_D, out=idx[:, 2])
    idx *= _STRIDE
    weight = np.empty((2, 3, n))
    np.subtract(s, lower, out=weight[1])
    np.subtract(1.0, weight[1], out=weight[0])
    # corner (a, b, c) = (θh sample, θd sample, φd sample), weight (w_θh·w_θd)·w_φd
    corner = idx[:, 0, None, None] + idx[None, :, 1, None] + idx[None, None, :, 2]
    corner_w = weight[:, 0, None, None] * weight[None, :, 1, None] * weight[None, None, :, 2]
    corner_w = corner_w.reshape(8, n)
    values = planes.take(corner.reshape(-1), axis=1).reshape(3, 8, n)
    values *= corner_w
    # the corners summed in turn, 000, 001, …, 111 (for n = 1 numpy pairs them: equal to rounding)
    return np.add.reduce(values, axis=1)


def from_half_diff(theta_h, theta_d, phi_d, phi_h=0.0):
    """``(wi, wo)`` for half/difference angles (radians): the inverse of :func:`half_diff`.

    ``wi = Rot_z(φh)·Rot_y(θh)·d`` with ``d = dir(θd, φd)``, and ``wo`` the same with ``d``
    turned by π about the pole (``(-dx, -dy, dz)``).  Directions may lie below the horizon.
    """
    theta_h, theta_d, phi_d, phi_h = np.broadcast_arrays(
        *(np.asarray(a, dtype=float) for a in (theta_h, theta_d, phi_d, phi_h)))
    st, ct = np.sin(theta_d), np.cos(theta_d)
    dx, dy = st * np.cos(phi_d), st * np.sin(phi_d)
    sh, ch = np.sin(theta_h), np.cos(theta_h)
    sp, cp = np.sin(phi_h), np.cos(phi_h)

    def turn(x, y, z):  # Rot_z(φh)·Rot_y(θh)
        x1, z1 = ch * x + sh * z, -sh * x + ch * z
        return np.stack([cp * x1 - sp * y, sp * x1 + cp * y, z1], axis=-1)

    return turn(dx, dy, ct), turn(-dx, -dy, ct)


def _kernel(wi, wo, file: str, lookup: str):
    return evaluate(load_cached(file), wi, wo, lookup)


FILE = Param("file", "file", "", kind="path", doc="MERL .binary file (90×90×180, RGB)")
LOOKUP = Param("lookup", "lookup", "trilinear", kind="choice", choices=LOOKUPS,
               doc="nearest bin (as BRDFRead.cpp) or trilinear in bin coordinates")

MERL = Model(
    "merl", "MERL measured", (FILE, LOOKUP), _kernel, rgb=True, reciprocal=True, measured=True,
    summary="measured isotropic BRDF (Matusik et al. 2003), 90×90×180 bins in (θh, θd, φd)",
    horizon="the data's value at the clamped last bins; 0 below the horizon",
    notes=("unmeasured (negative) bins are filled from the nearest valid θd bin, else 0",),
)


# -- cache -------------------------------------------------------------------------------------

#: how many loaded files stay in memory (35 MB each): the measured one and one being compared
CACHE_SIZE = 2
_CACHE = LRU(CACHE_SIZE)  # thread-safe: the app loads in a worker thread


def _cache_key(name: str) -> tuple:
    """(real path, mtime, size): a file changed on disk is a new key."""
    if not name:
        raise MerlError(NO_FILE)
    try:
        st = os.stat(name)
    except OSError as e:
        raise MerlError(f"{name}: cannot read: {e.strerror or e}") from None
    return (os.path.realpath(name), st.st_mtime_ns, st.st_size)


def is_loaded(path: str | os.PathLike) -> bool:
    """Whether :func:`load_cached` would answer from memory (no reading).  Raises
    :class:`MerlError` when the file cannot be found."""
    return _cache_key(os.fspath(path)) in _CACHE


def load_cached(path: str | os.PathLike,
                progress: Callable[[float], None] | None = None) -> MerlData:
    """:func:`load` through a small LRU keyed by (real path, mtime, size): the model kernel
    receives its file as a parameter on every evaluation and must not re-read it; a file that
    changed on disk is read again.  The app calls this (with ``progress``) in a worker thread,
    so the kernel's later calls are cache hits."""
    name = os.fspath(path)
    key = _cache_key(name)
    hit = _CACHE.lookup(key)
    if hit is not None:
        if progress is not None:
            progress(1.0)
        return hit
    return _CACHE.put(key, load(name, progress))


def clear_cache() -> None:
    _CACHE.clear()


__all__ = ["FILE_BYTES", "LOOKUPS", "MERL", "MerlData", "MerlError", "SCALES",
           "bin_coordinates", "check_file", "clear_cache", "evaluate",
           "flat_index", "from_half_diff", "half_diff", "is_loaded", "load", "load_cached"]
