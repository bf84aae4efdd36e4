"""Specular microfacet models: Cook-Torrance, GGX/Smith, glTF metal-roughness, UE4.

All share ``f = diffuse + F·D·G / (4 cos θi cos θo)`` and differ in D, G, F and the diffuse
term; the pieces live in :mod:`tuibrdf.core.brdf.microfacet` and :mod:`tuibrdf.core.brdf.fresnel`.

**cook-torrance** (Cook & Torrance 1981; the seed's form)::

    f = kd/π + F(ψ)·D_Beckmann(θh; m)·G_Vcavity / (4 cos θi cos θo)

=======  ======  =======  ===============  ==============================================
name     symbol  default  range            meaning
=======  ======  =======  ===============  ==============================================
kd       Kd      0        [0, 1]           diffuse reflectance
f0       F0      0.04     [0, 1]           Fresnel reflectance at normal incidence
m        m       0.2      [0.001, 1]       Beckmann RMS slope (roughness)
fresnel          exact    exact | schlick  exact unpolarised dielectric, or Schlick
=======  ======  =======  ===============  ==============================================

**ggx** (Walter et al. 2007; Heitz 2014 eqs. 71, 72, 99)::

    f = kd/π + F(ψ)·D_GGX(θh; α)·G2(wi, wo) / (4 cos θi cos θo),   G2 height-correlated Smith

Parameters as cook-torrance with ``alpha`` ∈ [0.001, 1] (0.2) instead of ``m``.

**gltf** (glTF 2.0 spec appendix B, metal-roughness, the pre-2024 form the seed uses)::

    α = roughness², F0 = mix(0.04, base, metallic), c_diff = mix(base, 0, metallic)
    f = (1 − F)·c_diff/π + F·D_GGX·G2 / (4 |N·wi| |N·wo|),  F = Schlick per channel

Later glTF revisions mix a dielectric and a metal lobe (``mix(dielectric_brdf, metal_brdf,
metallic)``); the two agree at metallic ∈ {0, 1} and differ in between.

**ue4** (Karis 2013, "Real Shading in Unreal Engine 4")::

    f = c_diff/π + F·D_GGX·G / (4 cos θi cos θo),   c_diff = (1 − metallic)·base
    G = G1(wi)·G1(wo), G1(c) = c / (c(1 − k) + k), k = (roughness + 1)²/8 (Schlick-GGX)

For gltf and ue4, ``base_color`` is RGB (0.8, 0.8, 0.8), ``metallic`` ∈ [0, 1] (0) and
``roughness`` ∈ [0, 1] (0.5).  A roughness of 0 would make α = 0, a Dirac mirror: α is floored at
``ALPHA_MIN = 0.001`` (roughness ≈ 0.032), as pbrt-v4 and Mitsuba 3 floor theirs.

Horizon: the specular term divides by cos θi cos θo.  Where exactly one of them is 0 the limit
exists and is returned (V-cavity: G ≤ 2cosθh cosθ/cosψ; Smith: cosθ·Λ(θ) → α sinθ/2); where both
are 0 there is no limit and the specular term is 0.  All four are reciprocal.
"""

from __future__ import annotations

from dataclasses import replace
from functools import lru_cache

import numpy as np

from tuibrdf.core.brdf.common_params import BASE, KD
from tuibrdf.core.brdf.common_params import ROUGHNESS as _ROUGHNESS
from tuibrdf.core.brdf.fresnel import fresnel as fresnel_term
from tuibrdf.core.brdf.fresnel import pow5
from tuibrdf.core.brdf.microfacet import (
    ALPHA_MIN,
    alpha_from_roughness,
    beckmann_d,
    ggx_d,
    ggx_g2_over_cos,
    vcavity_g_over_cos,
)
from tuibrdf.core.brdf.rgb import rgb
from tuibrdf.core.brdf.sampling import GGX_VNDF
from tuibrdf.core.directions import Geometry
from tuibrdf.core.numerics import safe_div
from tuibrdf.core.params import Model, Param

KD0 = replace(KD, default=0.0)
F0 = Param("f0", "F0", 0.04, 0.0, 1.0, 0.01, doc="Fresnel reflectance at normal incidence")
M = Param("m", "m", 0.2, 0.001, 1.0, 0.005, coarse=0.05, relative=True,
          doc="Beckmann RMS slope (roughness)")
ALPHA = Param("alpha", "α", 0.2, ALPHA_MIN, 1.0, 0.005, coarse=0.05, relative=True,
              doc="GGX width (roughness²)")
FRESNEL = Param("fresnel", "F", "exact", kind="choice", choices=("exact", "schlick"),
                doc="Fresnel: exact unpolarised dielectric or Schlick")
METALLIC = Param("metallic", "metal", 0.0, 0.0, 1.0, 0.01, doc="0 dielectric, 1 metal")
ROUGHNESS = replace(_ROUGHNESS, doc=f"perceptual roughness; α = roughness², floored at {ALPHA_MIN}")


def _specular(g: Geometry, d: np.ndarray, g_over_cos: np.ndarray) -> np.ndarray:
    """``D·G/(4 ci co)`` restricted to where it exists (upper hemisphere, H defined)."""
    return np.where(g.above & g.h_valid, d * g_over_cos, 0.0)


def _dielectric(g: Geometry, kd: float, f0: float, fresnel: str, d, g_over_cos):
    """``kd/π + F(ψ)·D·G/(4 ci co)`` above the horizon (the specular term where H is defined),
    0 below (cook-torrance, ggx)."""
    # cos θd ∈ [0, 1] by construction (Geometry): no clip
    f = fresnel_term(g.cos_d, f0, fresnel, clipped=True) * (d * g_over_cos)
    ok = g.above & g.h_valid
    if not kd:  # kd = 0 would add an exact 0.0
        return np.where(ok, f, 0.0)
    return np.where(ok, kd / np.pi + f, np.where(g.above, kd / np.pi, 0.0))


def cook_torrance(wi, wo, kd: float, f0: float, m: float, fresnel: str):
    g = Geometry(wi, wo)
    return _dielectric(g, kd, f0, fresnel, beckmann_d(g.cos_h * g.cos_h, g.sin2_h, m),
                       vcavity_g_over_cos(g.cos_h, g.cos_i, g.cos_o, g.cos_d))


def ggx(wi, wo, kd: float, f0: float, alpha: float, fresnel: str):
    g = Geometry(wi, wo)
    return _dielectric(g, kd, f0, fresnel, ggx_d(g.cos_h * g.cos_h, g.sin2_h, alpha),
                       ggx_g2_over_cos(g.cos_i, g.sin2_i, g.cos_o, g.sin2_o, alpha))


@lru_cache(maxsize=64)
def _metal_rough(base: tuple, metallic: float):
    """``(F0, c_diff)`` as read-only ``(3,)`` arrays, computed once per parameter set."""
    b = np.asarray(base, dtype=float)
    f0, c_diff = 0.04 * (1.0 - metallic) + b * metallic, b * (1.0 - metallic)
    f0.flags.writeable = c_diff.flags.writeable = False
    return f0, c_diff


def gltf(wi, wo, base_color, metallic: float, roughness: float):
    g = Geometry(wi, wo)
    alpha = alpha_from_roughness(roughness)
    spec_f0, c_diff = _metal_rough(tuple(base_color), metallic)
    m = pow5(1.0 - g.cos_d)  # Schlick's weight; cos θd ∈ [0, 1] (Geometry)
    spec = _specular(g, ggx_d(g.cos_h * g.cos_h, g.sin2_h, alpha),
                     ggx_g2_over_cos(g.cos_i, g.sin2_i, g.cos_o, g.sin2_o, alpha))
    return rgb(g.above, (m, spec), (spec_f0, c_diff), _gltf_channel)


def _gltf_channel(m, spec, f0, c_diff):
    f = f0 + (1.0 - f0) * m  # Schlick F
    return (1.0 - f) * c_diff / np.pi + f * spec


def ue4(wi, wo, base_color, metallic: float, roughness: float):
    g = Geometry(wi, wo)
    alpha = alpha_from_roughness(roughness)
    k = (roughness + 1.0) ** 2 / 8.0
    spec_f0, c_diff = _metal_rough(tuple(base_color), metallic)
    m = pow5(1.0 - g.cos_d)  # Schlick's weight; cos θd ∈ [0, 1] (Geometry)
    # G1(c)/c = 1/(c(1-k)+k): k ≥ 1/8, so the denominators are ≥ 1/8 even on the horizon
    g_over_cos = safe_div(
        0.25, (g.cos_i * (1.0 - k) + k) * (g.cos_o * (1.0 - k) + k), g.above, fill=0.0
    )
    spec = _specular(g, ggx_d(g.cos_h * g.cos_h, g.sin2_h, alpha), g_over_cos)
    return rgb(g.above, (m, spec), (spec_f0, c_diff), _ue4_channel)


def _ue4_channel(m, spec, f0, c_diff):
    f = f0 + (1.0 - f0) * m  # Schlick F
    return c_diff / np.pi + f * spec


COOK_TORRANCE = Model(
    "cook-torrance", "Cook-Torrance", (KD0, F0, M, FRESNEL), cook_torrance,
    summary="kd/π + F·D·G/(4 cosθi cosθo), Beckmann D, V-cavity G, exact or Schlick F",
    horizon="limit where one of θi, θo is 90°; specular 0 where both are",
)
GGX = Model(
    "ggx", "GGX / Smith", (KD0, F0, ALPHA, FRESNEL), ggx, sampler=GGX_VNDF,
    summary="kd/π + F·D·G2/(4 cosθi cosθo), GGX D, height-correlated Smith G2",
    horizon="limit where one of θi, θo is 90°; specular 0 where both are",
)
GLTF = Model(
    "gltf", "glTF metal-roughness", (BASE, METALLIC, ROUGHNESS), gltf, rgb=True,
    summary="glTF 2.0 appendix B: (1−F)c_diff/π + F·D·G2/(4|N·wi||N·wo|), Schlick F",
    horizon="limit where one of θi, θo is 90°; specular 0 where both are",
    notes=(f"roughness 0 is clamped to α = {ALPHA_MIN} (a perfect mirror cannot be drawn)",),
)
UE4 = Model(
    "ue4", "Unreal Engine 4", (BASE, METALLIC, ROUGHNESS), ue4, rgb=True,
    summary="Karis 2013: c_diff/π + F·D·G/(4 cosθi cosθo), Schlick-GGX G, k=(r+1)²/8",
    horizon="the formula's value (Schlick-GGX G/cos stays finite)",
    notes=(f"roughness 0 is clamped to α = {ALPHA_MIN} (a perfect mirror cannot be drawn)",),
)
