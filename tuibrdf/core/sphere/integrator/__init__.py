"""Directional albedo by nested adaptive Gauss–Kronrod in polar coordinates about the lobe.

``a(wi) = ∫ f(wi, wo) cos θo dωo`` over the upper hemisphere, written in polar coordinates
``(ρ, ψ)`` about an axis chosen so that the model's lobe sits at ``ρ = 0`` and the horizon is a
curve ``ρ = ρmax(ψ)`` known in closed form (so no cell straddles it)::

    a = ∫ dψ ∫₀^ρmax(ψ) g(ρ, ψ) dρ,     g = f(wi, wo(ρ, ψ)) · cos θo · J(ρ, ψ)

The modules, bottom up (each imports only modules above it here):

====================  ======================================================================
:mod:`.rules`         the Gauss–Kronrod pairs (K15/G7, K7/G3) and their constants; a pair's
                      value and error on panels, and the panels' sums by incidence
:mod:`.geometry`      the three polar frames (normal, mirror, half): the incidences
                      (:class:`Cases`), ρmax(ψ), the directions and weights at polar points,
                      and the integrand at panels' nodes
:mod:`.horizon_cut`   the first round's cut toward a pole just beyond the horizon
:mod:`.adaptive`      :func:`integrate`, the adaptive driver (inner over ρ, outer over ψ),
                      its gradings and tolerances
====================  ======================================================================

This package re-exports what the rest of tuibrdf uses (:mod:`tuibrdf.core.sphere.albedo`).  A
constant is read where it is defined, and albedo reads the ``OUTER_*`` re-exported here: to
change one (as scripts/bench_accuracy.py's ablations do), set it in every module that binds it.
"""

from tuibrdf.core.sphere.integrator.adaptive import (
    OUTER_GRADING,
    OUTER_LIMIT,
    OUTER_START,
    PolarResult,
    integrate,
    outer_grading,
    radial_grading,
)
from tuibrdf.core.sphere.integrator.geometry import FRAMES, Cases, cases

__all__ = ["FRAMES", "OUTER_GRADING", "OUTER_LIMIT", "OUTER_START", "Cases", "PolarResult",
           "cases", "integrate", "outer_grading", "radial_grading"]
