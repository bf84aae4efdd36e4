"""A writer of MERL ``.binary`` files in the exact SPEC §6 format, for the tests.

Written from SPEC §6 alone (not from ``tuibrdf.core.formats.merl``), so a reader bug cannot cancel a
writer bug: header of 3 little-endian int32 ``(90, 90, 180)``, then all R, all G, all B as
little-endian float64, sample ``(iθh, iθd, iφd)`` at ``iφd + 180·(iθd + 90·iθh)``, file values
equal to the BRDF divided by the channel scale (R 1/1500, G 1.15/1500, B 1.66/1500).

Sample ``i`` of each axis sits at the centre of its bin (SPEC §6: bin coordinate i + ½):
θh = ((i + ½)/90)²·90°, θd = (i + ½)°, φd = (i + ½)° (the SPEC's bin formulas inverted).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

DIMS = (90, 90, 180)
SCALES = np.array([1.0 / 1500.0, 1.15 / 1500.0, 1.66 / 1500.0])


def sample_angles() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(θh, θd, φd)`` in radians of the samples, broadcastable to ``(90, 90, 180)``."""
    i = np.arange(90.0) + 0.5
    theta_h = (i / 90.0) ** 2 * (np.pi / 2)
    theta_d = i / 90.0 * (np.pi / 2)
    phi_d = (np.arange(180.0) + 0.5) / 180.0 * np.pi
    return theta_h[:, None, None], theta_d[None, :, None], phi_d[None, None, :]


def write_merl(path: Path, brdf: np.ndarray, *, header=DIMS, raw: bool = False,
               extra: bytes = b"") -> Path:
    """Write ``brdf`` (shape ``(3, 90, 90, 180)``, sr⁻¹, or file units with ``raw``).

    Negative values are written as they are (they mark invalid bins).  ``header`` overrides
    the dims written; ``extra`` is appended (trailing garbage).
    """
    brdf = np.asarray(brdf, dtype=float)
    assert brdf.shape == (3, *DIMS)
    file_units = brdf if raw else np.where(brdf < 0, brdf, brdf / SCALES[:, None, None, None])
    with open(path, "wb") as f:
        f.write(np.asarray(header, dtype="<i4").tobytes())
        f.write(np.ascontiguousarray(file_units, dtype="<f8").tobytes())
        f.write(extra)
    return path


def table_from_directions(fn) -> np.ndarray:
    """``(3, 90, 90, 180)`` of ``fn(wi, wo)`` (RGB, shape ``(..., 3)``) at the samples, with
    ``-1`` (invalid, as in MERL's files) where a direction is below the horizon."""
    from tuibrdf.core.formats.merl import from_half_diff  # checked against half_diff in test_merl

    wi, wo = from_half_diff(*np.broadcast_arrays(*sample_angles()))
    f = np.asarray(fn(wi, wo), dtype=float)
    if f.ndim == wi.ndim - 1:
        f = np.repeat(f[..., None], 3, axis=-1)
    below = (wi[..., 2] < 0) | (wo[..., 2] < 0)
    f = np.where(below[..., None], -1.0, f)
    return np.moveaxis(f, -1, 0)
