"""The albedo of a measured RGL ``.bsdf`` file: its own f, to the horizon.

A ``.bsdf`` file holds f·cos θo (:mod:`tuibrdf.core.formats.rgl_bsdf`); the viewer's f divides
it by cos θo held at cos 89.9° within 0.1° of the horizon (the pictures would otherwise show
the measurement noise there multiplied by up to 1/cos θo).  The albedo ∫ f cos θo dωo is the
integral of the file's f·cos θo itself, so it integrates the file's own f, divided by cos θo
all the way to the horizon (``rgl_bsdf.evaluate(floor=False)``): the singular 1/cos θo is
cancelled by the albedo's cos θo.  (With the held cosine it would lose the part beyond 89.9°:
7.1e-5 of paper_white's albedo at θi = 0.)

The rule is the adaptive one of :mod:`tuibrdf.core.sphere.albedo`, in the half-vector frame
(the data is tabulated over the half vector), with measured data's budget of
:data:`~tuibrdf.core.sphere.lobes.MEASURED_MAX_EVALS` evaluations per incidence (MERL's too).
The frame caches each (file, θi, φi) once computed.
"""

from __future__ import annotations

from functools import partial

from tuibrdf.core.formats import rgl_bsdf
from tuibrdf.core.params import Model
from tuibrdf.core.sphere.lobes import MEASURED_MAX_EVALS, Lobe


def rgl_data(model: Model) -> rgl_bsdf.RglData | None:
    """The file's data if ``model`` is a loaded ``.bsdf`` file, else None."""
    k = model.kernel
    if isinstance(k, partial) and k.func is rgl_bsdf._kernel and k.args:
        return k.args[0]
    return None


def albedo_setup(model: Model):
    """``(kernel(wi, wo), Lobe)`` for the albedo of a ``.bsdf`` model, or None for another."""
    data = rgl_data(model)
    if data is None:
        return None

    def kernel(wi, wo):
        return rgl_bsdf.evaluate(data, wi, wo, floor=False)

    return kernel, Lobe("half", 1e-3, None, symmetric=False, max_evals=MEASURED_MAX_EVALS)
