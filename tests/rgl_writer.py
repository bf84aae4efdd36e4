"""A writer of RGL-EPFL ``.bsdf`` tensor files, for the tests (written from the format as the
issue and powitacq's Python loader describe it, not from tuibrdf.core.formats.rgl_bsdf).

Container: ``tensor_file\\0``, version ``1, 0``, ``u32`` field count; per field ``u16`` name
length, name, ``u16`` ndim, ``u8`` dtype code (Mitsuba's Struct: 1 u8 … 10 f32, 11 f64),
``u64`` offset, ``ndim × u64`` shape; then each field's bytes at its offset (8-byte aligned).

``material`` builds a synthetic material whose evaluation has a closed form:

* the VNDF density is ``p(x, y) ∝ 1 + x`` on the unit square (x: the half-vector's elevation
  coordinate ``u = √(2θm/π)``, y: its azimuth coordinate), linear, so the piecewise-bilinear
  warp and its trapezoid CDFs are exact: the inverse warp is ``s = ((u + u²/2)/1.5, v)``;
* the rgb slices are ``(a_c + b·s_x)·(1 + θi)·(1 + k·(φi + π))``, linear in every
  interpolated coordinate, so interpolation is exact;
* ``ndf(u, v) = 1 + u`` and ``sigma(u, v) = 2 + u`` (u of wm resp. wi), used when ``jacobian``.

So ``f·cos θo = (a_c + b·s_x(u_m))·(1 + θi)·(1 + k(φi + π))·[ndf/(4σ)]``.
"""

from __future__ import annotations

import struct
from pathlib import Path

import numpy as np

CODES = {np.dtype("uint8"): 1, np.dtype("int8"): 2, np.dtype("uint16"): 3,
         np.dtype("int16"): 4, np.dtype("uint32"): 5, np.dtype("int32"): 6,
         np.dtype("uint64"): 7, np.dtype("int64"): 8, np.dtype("float16"): 9,
         np.dtype("float32"): 10, np.dtype("float64"): 11}
A = (0.2, 0.5, 0.9)
B = 0.3


def tensor_bytes(fields: dict, *, magic=b"tensor_file\0", version=(1, 0),
                 shapes: dict | None = None, offsets: dict | None = None,
                 codes: dict | None = None) -> bytes:
    """The file's bytes; ``shapes``/``offsets``/``codes`` override what the header declares."""
    names = list(fields)
    head = len(magic) + 2 + 4 + sum(2 + len(n.encode()) + 2 + 1 + 8 + 8 * np.ndim(fields[n])
                                     for n in names)
    pos = (head + 7) // 8 * 8
    blobs, entries = [], []
    for n in names:
        a = np.ascontiguousarray(fields[n])
        a = a.astype(a.dtype.newbyteorder("<"))
        shape = (shapes or {}).get(n, a.shape)
        off = (offsets or {}).get(n, pos)
        code = (codes or {}).get(n, CODES[a.dtype.newbyteorder("=")])
        entries.append(struct.pack("<H", len(n.encode())) + n.encode()
                       + struct.pack("<HBQ", len(shape), code, off)
                       + struct.pack(f"<{len(shape)}Q", *shape))
        blobs.append((pos, a.tobytes()))
        pos = (pos + len(a.tobytes()) + 7) // 8 * 8
    out = bytearray(magic + bytes(version) + struct.pack("<I", len(names)) + b"".join(entries))
    for p, b in blobs:
        out += b"\0" * (p - len(out)) + b
    return bytes(out)


def write_tensor(path: Path, fields: dict, **kw) -> Path:
    path.write_bytes(tensor_bytes(fields, **kw))
    return path


def material(*, n_phi=1, phi_span=2 * np.pi, n_theta=4, n=9, jacobian=True, k=0.0,
             spectral_values=None, dtype=np.float64) -> dict:
    """Fields of the synthetic material of the module docstring."""
    phi = np.linspace(-np.pi, -np.pi + phi_span, n_phi) if n_phi > 1 else np.zeros(1)
    theta = np.linspace(0.0, np.pi / 2, n_theta)
    x = np.linspace(0.0, 1.0, n)
    vndf = np.broadcast_to(1.0 + x, (n_phi, n_theta, n, n))
    lum = np.ones((n_phi, n_theta, n, n))
    base = np.array(A)[:, None, None] + B * x[None, None, :]  # (3, 1, n): a_c + b·s_x
    tfac = (1.0 + theta)[None, :, None, None, None]
    pfac = (1.0 + k * (phi + np.pi))[:, None, None, None, None]
    rgb = base[None, None] * tfac * pfac * np.ones((1, 1, 1, n, 1))
    f = {
        "description": np.frombuffer(b"synthetic test material", dtype=np.uint8),
        "phi_i": phi.astype(dtype), "theta_i": theta.astype(dtype),
        "ndf": np.broadcast_to(1.0 + x, (n, n)).astype(dtype),
        "sigma": np.broadcast_to(2.0 + x, (n, n)).astype(dtype),
        "vndf": vndf.astype(dtype), "luminance": lum.astype(dtype),
        "jacobian": np.array([1 if jacobian else 0], dtype=np.uint8),
        "valid": np.ones((n_phi, n_theta, n, n), dtype=np.uint8),
    }
    if spectral_values is None:
        f["rgb"] = rgb.astype(dtype)
    else:
        wl, v = spectral_values
        f["wavelengths"] = np.asarray(wl, dtype=np.float32)
        f["spectra"] = (np.asarray(v)[None, None, :, None, None] *
                        np.ones((n_phi, n_theta, 1, n, n))).astype(dtype)
    return f


def expected(wi: np.ndarray, wo: np.ndarray, *, jacobian=True, k=0.0) -> np.ndarray:
    """The closed form of the module docstring divided by cos θo (sr⁻¹), shape (..., 3)."""
    h = wi + wo
    h = h / np.linalg.norm(h, axis=-1, keepdims=True)
    theta_m = np.arccos(np.clip(h[..., 2], -1, 1))
    theta_i = np.arccos(np.clip(wi[..., 2], -1, 1))
    phi_i = np.arctan2(wi[..., 1], wi[..., 0])
    u_m = np.sqrt(2 * theta_m / np.pi)
    u_i = np.sqrt(2 * theta_i / np.pi)
    s_x = (u_m + u_m**2 / 2) / 1.5
    scale = (1 + theta_i) * (1 + k * (phi_i + np.pi))
    val = (np.array(A) + B * s_x[..., None]) * scale[..., None]
    if jacobian:
        val = val * ((1 + u_m) / (4 * (2 + u_i)))[..., None]
    return val / wo[..., 2:3]
