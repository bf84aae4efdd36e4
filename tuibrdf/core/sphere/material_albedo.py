"""The directional albedos ``tuibrdf materials`` lists, stored as package data.

``tuibrdf materials`` shows 400 albedos (100 materials × 2 fits × θi ∈ {0°, 60°}).  They are
computed once by the package's albedo quadrature (:func:`tuibrdf.core.sphere.albedo.albedo_curve_
estimate_resolved`, adaptive Gauss–Kronrod about the lobe, relative tolerance
:data:`RTOL`) and stored in ``data/material_albedo.tsv`` by ``scripts/gen_material_albedo.py``,
so the listing takes milliseconds and is the same on every machine.  The tests check the stored
values against a fresh computation and against an independent 1D integral at normal incidence.
"""

from __future__ import annotations

from functools import cache
from pathlib import Path

import numpy as np

from tuibrdf.core.brdf.materials import material_names
from tuibrdf.core.registry import get_model
from tuibrdf.core.sphere.albedo import albedo_curve_estimate_resolved

THETAS = (0.0, 60.0)
#: tighter than the viewer's default: the table is written once, with 6 digits, each of them
#: right (the estimate must not straddle a rounding boundary: :func:`rounded`)
RTOL = 1e-10
#: the tolerance of a second pass for a value whose estimate straddles a rounding boundary
RTOL_TIGHT = 1e-13
DIGITS = 6


def rounded(value: float, error: float) -> str | None:
    """``value`` to :data:`DIGITS` significant digits if every number within ``error`` of it
    rounds the same way (each digit printed is then right), else None."""
    text = f"{value:.{DIGITS}g}"
    same = f"{value - error:.{DIGITS}g}" == text == f"{value + error:.{DIGITS}g}"
    return text if same else None


def fit_albedo_text(fit: str, material: str) -> list[str]:
    """The stored texts of ``fit``'s albedos of ``material`` at :data:`THETAS` (RGB, flat):
    each correctly rounded to :data:`DIGITS` digits, from the rule at :data:`RTOL`, again at
    :data:`RTOL_TIGHT` where the first estimate straddles a rounding boundary."""
    m = get_model(fit)
    values = m.resolve({"material": material})
    out = []
    for rtol in (RTOL, RTOL_TIGHT):
        est = albedo_curve_estimate_resolved(m, values, THETAS, rtol=rtol, max_evals=2_000_000)
        v, e = np.asarray(est.value).ravel(), np.asarray(est.error).ravel()
        err = np.broadcast_to(e, v.shape) if e.size == 1 else e
        out = [rounded(float(x), float(y)) for x, y in zip(v, err, strict=True)]
        if all(t is not None for t in out):
            return out
    raise ValueError(f"{fit} {material}: an albedo sits on a rounding boundary of "
                     f"{DIGITS} digits within its error at rtol {RTOL_TIGHT:g}")


def fit_albedo(fit: str, material: str, theta_i_deg: float | None = None) -> np.ndarray:
    """Directional albedo ``∫ f cos θo dωo`` (RGB) of ``fit`` (``abc`` or ``sgd``) of MERL
    ``material``, computed: ``(3,)`` at ``theta_i_deg``, or ``(len(THETAS), 3)`` at
    :data:`THETAS` (what :data:`STORED` holds)."""
    m = get_model(fit)
    values = m.resolve({"material": material})
    thetas = THETAS if theta_i_deg is None else (theta_i_deg,)
    value = np.asarray(albedo_curve_estimate_resolved(m, values, thetas, rtol=RTOL).value)
    return value if theta_i_deg is None else value[0]

# ------------------------------------------------------------------------------ stored table

#: ``tuibrdf materials`` reads the albedos from here; ``scripts/gen_material_albedo.py`` writes
#: it, and ``tests/core/sphere/test_material_albedo.py`` recomputes entries and checks them
STORED = Path(__file__).resolve().parents[1] / "brdf" / "data" / "material_albedo.tsv"
COLUMNS = tuple(f"{m}_{t:g}_{c}" for m in ("abc", "sgd") for t in THETAS for c in "rgb")


def stored_text() -> str:
    """The text of :data:`STORED`, computed now (what the script writes)."""
    lines = [
        "# Directional albedo a(theta_i) = integral of f cos(theta_o) over the hemisphere, RGB,",
        "# of the ABC and SGD fits of each MERL material at theta_i = 0 and 60 degrees.",
        "# Computed (not from dj_brdf.h) by scripts/gen_material_albedo.py with the albedo",
        f"# quadrature of tuibrdf/core/sphere/albedo.py at rtol {RTOL:g} (or {RTOL_TIGHT:g} "
        f"where",
        f"# needed); {DIGITS} digits, each right (the error estimate decides the rounding).",
        "\t".join(("name", *COLUMNS)),
    ]
    for name in material_names():
        lines.append("\t".join((name, *(t for m in ("abc", "sgd")
                                          for t in fit_albedo_text(m, name)))))
    return "\n".join(lines) + "\n"


@cache
def stored() -> dict[str, dict[str, np.ndarray]]:
    """:data:`STORED` parsed: ``{material: {"abc": (2, 3), "sgd": (2, 3)}}`` (θi = 0°, 60°)."""
    try:
        text = STORED.read_text(encoding="utf-8")
    except OSError as e:
        raise ValueError(f"{STORED}: cannot read the albedo table ({e.strerror})") from None
    rows = [ln.split("\t") for ln in text.splitlines() if ln and not ln.startswith("#")]
    if not rows or tuple(rows[0]) != ("name", *COLUMNS):
        raise ValueError(f"{STORED}: unexpected columns")
    out = {}
    for cells in rows[1:]:
        try:
            v = np.array([float(x) for x in cells[1:]]).reshape(2, len(THETAS), 3)
        except ValueError:
            raise ValueError(f"{STORED}: bad row for {cells[0]!r}") from None
        out[cells[0]] = {"abc": v[0], "sgd": v[1]}
    if sorted(out) != sorted(material_names()):
        raise ValueError(f"{STORED}: does not list the 100 materials: run "
                         "scripts/gen_material_albedo.py")
    return out
