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
  no cut inside it; s starts at ln(1e-16) (the lobe's mass below that is < 1e-10 of it);
* the s range is split where ABC's V-cavity G changes branch (2 cosθh cosθ = cosθd, for wi and
  for wo; found numerically per φh), so each segment's integrand is smooth.

Gauss–Legendre in each segment and in φh (``n_s`` × 3 × ``n_phi`` nodes).  Accuracy, measured
against twice the nodes, a 1D integral at normal incidence and the mesh quadrature: see
``tests/test_material_albedo.py`` and docs/materials.md.
"""

from __future__ import annotations

from functools import cache
from pathlib import Path

import numpy as np

from .evaluate import evaluate_resolved
from .frame import incident
from .materials import material_names, table
from .models import get_model

N_S = 32  # per segment: three segments in s (see _nodes)
N_PHI = 32
S_MIN = float(np.log(1e-16))
#: the Lambert part of each fit: (table, column)
DIFFUSE = {"abc": "kd", "sgd": "rho_d"}
THETAS = (0.0, 60.0)


def _half(theta_h: np.ndarray, phi: np.ndarray) -> np.ndarray:
    """Unit half vectors ``(..., 3)`` at polar ``theta_h`` and azimuth ``phi`` (broadcast)."""
    st, ct = np.sin(theta_h), np.cos(theta_h)
    return np.stack(np.broadcast_arrays(st * np.cos(phi), st * np.sin(phi), ct), axis=-1)


def _kinks(wi: np.ndarray, phi: np.ndarray, th_max: np.ndarray, n: int = 256) -> np.ndarray:
    """``(n_phi, 2)`` θh where the V-cavity G changes branch (``2 cosθh cosθ = cosθd`` for wi
    and for wo), or ``th_max`` where it does not: found by a sign change on ``n`` points and
    60 bisections.  G's kink would cost the product rule its fast convergence (ABC)."""
    def g(th):
        h = _half(th, phi[:, None])
        cd = h @ wi
        co = 2.0 * cd * h[..., 2] - wi[2]
        return np.stack([2.0 * h[..., 2] * wi[2] - cd, 2.0 * h[..., 2] * co - cd], axis=-1)

    x = np.linspace(0.0, 1.0, n + 1)[1:-1]
    th = th_max[:, None] * x[None, :]  # (n_phi, n - 1)
    v = g(th)  # (n_phi, n - 1, 2)
    change = np.signbit(v[:, :-1]) != np.signbit(v[:, 1:])  # between th[j] and th[j + 1]
    has = change.any(axis=1)  # (n_phi, 2)
    j = np.argmax(change, axis=1)  # first sign change
    rows = np.arange(len(phi))[:, None]
    lo, hi = th[rows, j], th[rows, j + 1]
    f_lo = np.take_along_axis(v[:, :, :], j[:, None, :], axis=1)[:, 0, :]
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        f_mid = np.stack([g(mid[:, k:k + 1])[:, 0, k] for k in range(2)], axis=-1)
        same = np.signbit(f_mid) == np.signbit(f_lo)
        lo, f_lo = np.where(same, mid, lo), np.where(same, f_mid, f_lo)
        hi = np.where(same, hi, mid)
    return np.where(has, 0.5 * (lo + hi), th_max[:, None])


@cache
def _nodes(theta_i_deg: float, n_s: int, n_phi: int):
    """``(wo (n, 3), weight (n,))`` with ``∫ g(wo) dωo ≈ Σ w·g`` over the upper hemisphere
    (the Jacobian 4 H·wi and the φh symmetry folded into the weights).  For each φh the s range
    is split at G's kinks into three segments of ``n_s`` nodes each (a missing kink gives an
    empty segment, of weight 0)."""
    if not 0.0 <= theta_i_deg < 90.0:
        raise ValueError(f"theta_i = {theta_i_deg} is invalid: expected in [0, 90)°")
    wi = incident(theta_i_deg)
    xs, ws = np.polynomial.legendre.leggauss(n_s)
    xp, wp = np.polynomial.legendre.leggauss(n_phi)
    phi = 0.5 * np.pi * (xp + 1.0)  # [0, π]
    w_phi = 0.5 * np.pi * wp
    si, ci = -wi[0], wi[2]
    th_max = 0.5 * np.arctan2(ci, si * np.cos(phi))  # wo on the horizon; > 0 for θi < 90°
    # ln(1 − cos θ) without cancellation: 1 − cos θ = 2 sin²(θ/2)
    edges = np.concatenate([np.sort(_kinks(wi, phi, th_max), axis=1), th_max[:, None]], axis=1)
    s_edges = np.concatenate([np.full((n_phi, 1), S_MIN),
                              np.log(2.0 * np.sin(0.5 * edges) ** 2)], axis=1)
    s_edges = np.maximum.accumulate(np.maximum(s_edges, S_MIN), axis=1)
    half = 0.5 * np.diff(s_edges, axis=1)  # (n_phi, 3) half-lengths
    s = s_edges[:, :-1, None] + half[..., None] * (xs + 1.0)  # (n_phi, 3, n_s)
    w = 2.0 * w_phi[:, None, None] * half[..., None] * ws  # ×2: φh ∈ [−π, 0] by symmetry
    u = np.exp(s)  # 1 − cos θh
    cos_h = 1.0 - u
    sin_h = np.sqrt(u * (2.0 - u))  # sin²θh = u(2 − u), no cancellation
    p = phi[:, None, None]
    h = np.stack(np.broadcast_arrays(sin_h * np.cos(p), sin_h * np.sin(p), cos_h), axis=-1)
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
STORED_NODES = (64, 64)
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
