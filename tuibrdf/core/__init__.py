"""The numpy core: every number tuibrdf shows.  Never imports textual or rich.

Grouped by trade, bottom up (a module imports only from its own floor or below;
tests/test_architecture.py checks it):

=================  ==========================================================================
base               :mod:`.params` (parameter declarations, :class:`~.params.Model`),
                   :mod:`.numerics` (the floating-point policy), :mod:`.conventions`
                   (luminance, number formats), :mod:`.display` (the look's defaults and
                   ranges), :mod:`.directions` (the shading frame: angles ↔ directions, the
                   half/difference angles, the one range check of θi and φi), :mod:`.lru`
                   (the one LRU cache)
:mod:`.brdf`       the reflectance models: Fresnel, microfacet pieces, the model families,
                   the published fits of the 100 MERL materials and their data
:mod:`.formats`    user files in, models out: MERL, RGL ``.bsdf``, BRDF Explorer ``.brdf``
                   (with its GLSL compiler), Python model files, safe reading
:mod:`.registry`,  the registry (a name or a path → a model), validated broadcasting
:mod:`.evaluate`,  evaluation, and a model with checked values as one value
:mod:`.material`
:mod:`.sphere`     on the hemisphere: the icosahedral mesh, the adaptive Gauss–Kronrod
                   integrator, the directional albedo with its error, the peak finder,
                   peaks on the horizon
:mod:`.views`      what each pane of the viewer draws, as numbers: the frame request and
                   result, the equal-area map, sections, lit sphere and plane, θh/θd views
:mod:`.fit`        fitting a model's parameters to measured data
=================  ==========================================================================

Where to add things: a new model → :mod:`.brdf` (and register it in :mod:`.registry`); a new
file format → :mod:`.formats` (and :mod:`.formats.userfiles`); a new pane's numbers →
:mod:`.views` (its picture goes in :mod:`tuibrdf.render`).
"""
