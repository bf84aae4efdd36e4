"""Directional albedo of the fitted MERL materials, fast: a half-vector product Gauss rule.

``tuibrdf materials`` lists 400 albedos (100 materials × 2 fits × θi ∈ {0°, 60°}); the general
mesh quadrature (:func:`tuibrdf.core.quadrature.albedo`, adaptive for sharp lobes) takes 0.01 to
0.25 s each, too slow for a listing.  Both fits are a Lambert term plus a microfacet lobe around
H = N, so this rule integrates over the half vector, where the lobe is compact:

* the Lambert term ``kd/π`` (abc) or ``ρd/π`` (sgd) integrates to ``kd`` (``ρd``) exactly;
* the rest, ``f − diffuse``, is integrated over H with ``dωo = 4 (H·wi) dωh`` (Walter et al.
  2007, eq. 14), in the variables ``s = ln(1 − cos θh)`` (sharp lobes, α down to 1.6e-5, live at
  1 − cos θh ≈ 1e-5; long ABC tails reach θh = 90°) and φh ∈ [0, π] (the integrand is even in
  φh about the plane of incidence), with ``sin θh dθh = (1 − cos θh) ds``;
* for each φh the domain ends where wo reaches the horizon, ``θh,max = ½·atan2(cos θi,
  sin θi·cos φh)`` (from wo·N = cos θi cos 2θh − sin θi cos φh sin 2θh = 0), so the integrand has
  no cut inside it; s starts at ln(1e-16) (the lobe's mass below that is < 1e-10 of it).

Gauss–Legendre in both variables (:data:`N_S` × :data:`N_PHI` nodes).  Accuracy: measured
against the mesh quadrature and against twice as many nodes in ``tests/test_material_albedo.py``
and docs/materials.md.
"""

from __future__ import annotations

from functools import cache
from pathlib import Path

import numpy as np

from .evaluate import evaluate_resolved
from .frame import incident
from .materials import material_names, table
from .models import get_model

N_S = 64
N_PHI = 32
S_MIN = float(np.log(1e-16))
#: the Lambert part of each fit: (table, column)
DIFFUSE = {"abc": "kd", "sgd": "rho_d"}
THETAS = (0.0, 60.0)


@cache
def _nodes(theta_i_deg: float, n_s: int, n_phi: int):
    """``(wo (n, 3), weight (n,))`` with ``∫ g(wo) dωo ≈ Σ w·g`` over the upper hemisphere
    (the Jacobian 4 H·wi and the φh symmetry folded into the weights)."""
    wi = incident(theta_i_deg)
    xs, ws = np.polynomial.legendre.leggauss(n_s)
    xp, wp = np.polynomial.legendre.leggauss(n_phi)
    phi = 0.5 * np.pi * (xp + 1.0)  # [0, π]
    w_phi = 0.5 * np.pi * wp
    si, ci = -wi[0], wi[2]
    th_max = 0.5 * np.arctan2(ci, si * np.cos(phi))  # wo on the horizon
    s_max = np.log(-np.expm1(np.log(np.cos(th_max))))  # ln(1 − cos θh,max)
    half = 0.5 * (s_max - S_MIN)
    s = S_MIN + half[:, None] * (xs[None, :] + 1.0)  # (n_phi, n_s)
    w = 2.0 * w_phi[:, None] * half[:, None] * ws[None, :]  # ×2: φh ∈ [−π, 0] by symmetry
    u = np.exp(s)  # 1 − cos θh
    cos_h = 1.0 - u
    sin_h = np.sqrt(u * (2.0 - u))  # sin²θh = u(2 − u), no cancellation
    h = np.stack([sin_h * np.cos(phi)[:, None], sin_h * np.sin(phi)[:, None], cos_h], axis=-1)
    hw = h @ wi  # > 0 inside the domain
    wo = 2.0 * hw[..., None] * h - wi
    wo[..., 2] = np.maximum(wo[..., 2], 0.0)  # rounding at θh,max must not dip below 0
    weight = w * u * 4.0 * hw  # sin θh dθh = u ds; dωo = 4 (H·wi) dωh
    return wo.reshape(-1, 3), weight.ravel()


def albedo(model: str, material: str, theta_i_deg: float, *, n_s: int = N_S,
           n_phi: int = N_PHI) -> np.ndarray:
    """Directional albedo ``∫ f cos θo dωo`` (RGB, ``(3,)``) of fit ``model`` (``abc`` or
    ``sgd``) of ``material`` at incidence ``theta_i_deg`` (by the rule of the docstring)."""
    m = get_model(model)
    values = m.resolve({"material": material})
    wo, weight = _nodes(float(theta_i_deg), n_s, n_phi)
    wi = np.broadcast_to(incident(theta_i_deg), wo.shape)
    f = np.asarray(evaluate_resolved(m, values, wi, wo))
    diffuse = table(model).row(values["material"])[DIFFUSE[model]]
    lobe = (f - diffuse / np.pi) * wo[:, 2:3]
    return diffuse + weight @ lobe




# ------------------------------------------------------------------------------ stored table

#: ``tuibrdf materials`` reads the albedos from here (400 of them take ~8 s to compute at the
#: nodes below); ``scripts/gen_material_albedo.py`` writes it, and ``tests/test_material_albedo
#: .py`` recomputes entries and checks them
STORED = Path(__file__).resolve().parent / "data" / "material_albedo.tsv"
STORED_NODES = (128, 64)
COLUMNS = tuple(f"{m}_{t:g}_{c}" for m in ("abc", "sgd") for t in THETAS for c in "rgb")


def stored_text() -> str:
    """The text of :data:`STORED`, computed now (what the script writes)."""
    n_s, n_phi = STORED_NODES
    lines = [
        "# Directional albedo a(theta_i) = integral of f cos(theta_o) over the hemisphere, RGB,",
        "# of the ABC and SGD fits of each MERL material at theta_i = 0 and 60 degrees.",
        "# Computed (not from dj_brdf.h) by scripts/gen_material_albedo.py with the half-vector",
        f"# Gauss rule of tuibrdf/core/material_albedo.py, {n_s} x {n_phi} nodes; 6 digits.",
        "\t".join(("name", *COLUMNS)),
    ]
    for name in material_names():
        vals = [v for m in ("abc", "sgd") for t in THETAS
                for v in albedo(m, name, t, n_s=n_s, n_phi=n_phi)]
        lines.append("\t".join((name, *(f"{v:.6g}" for v in vals))))
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
