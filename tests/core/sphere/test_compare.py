"""tuibrdf.core.sphere.compare against integrals written here: a composite product
Gauss–Legendre rule in (cos θo, φo), independent of the package's adaptive integrator."""

from __future__ import annotations

import numpy as np
import pytest

import tuibrdf
from tuibrdf.core.directions import incident
from tuibrdf.core.registry import get_model
from tuibrdf.core.sphere.compare import compare

SPEC_A = ("phong", {"kd": 0.0, "ks": 0.08, "n": 70.0})
SPEC_B = ("cook-torrance", {"kd": 0.0, "f0": 0.04, "m": 0.07})


def composite(a: float, b: float, panels: int, order: int = 16):
    x, w = np.polynomial.legendre.leggauss(order)
    edges = np.linspace(a, b, panels + 1)
    h = np.diff(edges) / 2
    mid = (edges[:-1] + edges[1:]) / 2
    return (mid[:, None] + h[:, None] * x).ravel(), (h[:, None] * w).ravel()


def product_rule(panels_u: int = 96, panels_phi: int = 128):
    """Directions and weights of ∫ g cos θ dω = ∫₀¹ dμ ∫₀^2π dφ g·μ (weights include μ)."""
    mu, wmu = composite(0.0, 1.0, panels_u)
    phi, wphi = composite(-np.pi, np.pi, panels_phi)
    s = np.sqrt(1.0 - mu * mu)
    d = np.stack([np.outer(s, np.cos(phi)), np.outer(s, np.sin(phi)),
                  np.outer(mu, np.ones_like(phi))], -1).reshape(-1, 3)
    return d, np.outer(wmu * mu, wphi).ravel()


def reference(a, b, theta_i):
    wo, w = product_rule()
    wi = incident(theta_i)
    fa = tuibrdf.evaluate(a[0], a[1], wi, wo)
    fb = tuibrdf.evaluate(b[0], b[1], wi, wo)
    return (w @ fa, w @ fb, float(np.sqrt(w @ (fa - fb) ** 2 / (w @ fb ** 2))),
            float(np.max(np.abs(fa - fb)) / np.max(fb)))


def numbers(a, b, thetas):
    ma, mb = get_model(a[0]), get_model(b[0])
    return compare(ma, ma.resolve(a[1]), mb, mb.resolve(b[1]), thetas)


def test_lambert_pair_is_exact():
    # albedo kd, and fA − fB = fB everywhere: rel_l2 = 1 and max_diff = +1 exactly
    for n in numbers(("lambert", {"kd": 0.8}), ("lambert", {"kd": 0.4}), [0.0, 45.0, 89.0]):
        assert n.albedo_a == pytest.approx(0.8, abs=max(n.albedo_a_error, 1e-12))
        assert n.albedo_b == pytest.approx(0.4, abs=max(n.albedo_b_error, 1e-12))
        assert n.rel_l2 == pytest.approx(1.0, abs=1e-9)
        assert n.rel_l2_error < 1e-6
        assert n.max_diff == pytest.approx(1.0, rel=1e-12)


@pytest.mark.parametrize("order", ["ab", "ba"])
def test_specular_pair_at_60(order):
    a, b = (SPEC_A, SPEC_B) if order == "ab" else (SPEC_B, SPEC_A)
    ra, rb, rl2, rmax = reference(a, b, 60.0)
    (n,) = numbers(a, b, [60.0])
    # the composite rule (1536 × 2048 nodes, lobes ≳ 4° wide) converges to ~1e-8 here;
    # the adaptive rule's own tolerances are 1e-5 (albedo) and 1e-4 (the L2 integrals)
    assert n.albedo_a == pytest.approx(ra, rel=1e-5)
    assert n.albedo_b == pytest.approx(rb, rel=1e-5)
    assert n.rel_l2 == pytest.approx(rl2, rel=2e-4)
    assert abs(n.rel_l2 - rl2) <= n.rel_l2_error + 1e-8 * rl2
    # the search on the function finds at least the grid's maximum (less its own last step)
    assert abs(n.max_diff) >= rmax * (1 - 1e-3)
    assert abs(n.max_diff) <= rmax * 1.05  # the grid is dense: the sup is not far above it
    # both lobes sit in the plane of incidence, on the mirror side (φo = 0 with φi = 180°)
    assert n.max_diff_phi_o == pytest.approx(0.0, abs=1e-6) or n.max_diff_phi_o > 359.99


def test_rgb_side_has_channels_and_luminance():
    a = ("lambert", {"kd": 0.5})
    mb = get_model("abc")
    ma = get_model("lambert")
    (n,) = compare(ma, ma.resolve(a[1]), mb, mb.resolve({}), [30.0])
    assert set(n.channels) == {"R", "G", "B"}
    y = 0.2126 * n.channels["R"]["albedo_b"] + 0.7152 * n.channels["G"]["albedo_b"] \
        + 0.0722 * n.channels["B"]["albedo_b"]
    assert n.albedo_b == pytest.approx(y, rel=1e-12)  # Rec.709 of linear RGB
    for ch in n.channels.values():
        assert ch["albedo_a"] == pytest.approx(0.5, abs=1e-9)  # grey side in every channel
