"""The model registry: registry name → :class:`~tuibrdf.core.params.Model`.

One module per model family; each opens with its formula, its source and a parameter table.
"""

from __future__ import annotations

from tuibrdf.core.brdf import diffuse, fitted, microfacet_models, phong
from tuibrdf.core.formats.merl import MERL
from tuibrdf.core.params import Model, unknown_message

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

#: Kernels of the analytic built-in models: each accepts any ``wi``, ``wo`` that broadcast
#: together (one direction of shape ``(3,)`` against many), so a direction broadcast along
#: every axis may be passed as that one vector (:func:`tuibrdf.core.evaluate.evaluate_resolved`)
BROADCAST_KERNELS = frozenset(
    m.kernel for m in MODELS.values() if m is not MERL
)


def registered_name(model: Model) -> str | None:
    """The registry name of the model whose kernel ``model`` runs: its own name, or that of
    the registered model a file's model was made from (a MERL file opened by its path, as
    ``tuibrdf albedo X.binary`` does: MERL's model, named by the file); None for any other (a
    ``.brdf``, ``.py``, ``.bsdf`` file, a plugin).  What per-model knowledge (integration
    hints, "measured data") is keyed by."""
    reg = MODELS.get(model.name)
    if reg is not None and reg.kernel is model.kernel:
        return model.name
    return next((name for name, m in MODELS.items() if m.kernel is model.kernel), None)


def get_model(name: str | Model) -> Model:
    """Look a model up by registry name, with a close match in the error for a typo; a path to
    a user file (``.brdf``, ``.bparam``, ``.py``, ``.bsdf``, ``.binary``) or the name of an
    installed plugin model resolves too (:mod:`tuibrdf.core.formats.userfiles`)."""
    if isinstance(name, Model):
        return name
    try:
        return MODELS[name]
    except (KeyError, TypeError):
        pass
    from tuibrdf.core.formats import userfiles

    if userfiles.looks_like_path(name):
        return userfiles.load_model_file(name)
    plugin = userfiles.plugin_model(name) if isinstance(name, str) else None
    if plugin is not None:
        return plugin
    raise ValueError(unknown_message("unknown model", str(name), list(MODELS)))
