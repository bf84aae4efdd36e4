"""User files in, models out.  A file is hostile until validated: each reader checks sizes and
fields before it allocates, and fails with one line naming the file and the problem.

======================  ==================================================================
:mod:`.userfiles`       a path wherever a model name goes: which reader, cached by file
:mod:`.files`           opening user files safely (regular files only, never blocking)
:mod:`.merl`            MERL ``.binary`` measured BRDFs: reader and lookup
:mod:`.rgl_bsdf`        RGL-EPFL ``.bsdf`` measured materials: reader and evaluation
:mod:`.cie`             colorimetric tables (spectral measurements → linear sRGB)
:mod:`.brdf_explorer`   BRDF Explorer ``.brdf`` and ``.bparam`` files
:mod:`.glsl`            the GLSL subset of BRDF Explorer shaders, compiled to numpy
:mod:`.pymodel`         Python model files (``.py``: code that runs when the user names it)
======================  ==================================================================
"""
