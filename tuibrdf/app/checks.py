"""Key F: the checks of :mod:`tuibrdf.core.sphere.checks` for the viewer, as one report
(:func:`tuibrdf.render.check_view.check_report`), computed off the event loop."""

from __future__ import annotations

from tuibrdf.core.directions import incident
from tuibrdf.core.numerics import KERNEL_ERRORS


def check_work(material, theta_i: float, phi_i: float, cmap: str, color: str):
    """The report of ``material``'s model at its values (and its parameters' ends), the
    reciprocity map at the light ``(θi, φi)`` and, for a model with a sampler, the χ² maps at
    θi (where θi < 90°); a one-line message when they cannot be computed."""
    from tuibrdf.core.sphere.checks import reciprocity_on_map, run_checks
    from tuibrdf.core.sphere.chi2 import chi2_at
    from tuibrdf.render.check_view import check_report

    model, values = material.model, material.values
    try:
        results = run_checks(model, values)
        recip = reciprocity_on_map(model, values, incident(theta_i, phi_i), 32)
        chi2 = None
        if model.sampler is not None and theta_i < 89.0:
            chi2 = chi2_at(model, values, theta_i)
    except KERNEL_ERRORS as e:
        return f"checks of {material.label} failed: {e}"
    failed = [r.name for r in results if not r.ok]
    verdict = "every check holds" if not failed else "FAILS " + ", ".join(failed)
    return check_report(f"{material.label}: {verdict}", results, recip, chi2, cmap=cmap,
                        color=color)
