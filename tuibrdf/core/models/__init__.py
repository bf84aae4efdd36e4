"""The model registry: registry name → :class:`~tuibrdf.core.params.Model`.

One module per model family; each opens with its formula, its source and a parameter table.
"""

from __future__ import annotations

from ..merl import MERL
from ..params import Model, unknown_message
from . import diffuse, fitted, microfacet_models, phong

MODELS: dict[str, Model] = {}


def register(*models: Model) -> None:
    for m in models:
        MODELS[m.name] = m


register(
    diffuse.LAMBERT,
    phong.PHONG,
    phong.BLINN_PHONG,
    microfacet_models.COOK_TORRANCE,
    diffuse.OREN_NAYAR,
    diffuse.OREN_NAYAR_SIMPLE,
    microfacet_models.GGX,
    microfacet_models.GLTF,
    diffuse.DISNEY_DIFFUSE,
    microfacet_models.UE4,
    MERL,
)
register(fitted.ABC, fitted.SGD)  # the published fits of the 100 MERL materials


def get_model(name: str | Model) -> Model:
    """Look a model up by registry name, with a close match in the error for a typo."""
    if isinstance(name, Model):
        return name
    try:
        return MODELS[name]
    except KeyError:
        raise ValueError(unknown_message("unknown model", str(name), list(MODELS))) from None
