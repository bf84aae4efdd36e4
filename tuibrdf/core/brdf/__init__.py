"""The reflectance models, each module opening with its formula, its source and a parameter table.

=========================  ===================================================================
:mod:`.fresnel`            Fresnel reflectance, exact and Schlick
:mod:`.microfacet`         microfacet distributions and shadowing-masking
:mod:`.diffuse`            Lambert, Oren-Nayar (full and simplified), Disney diffuse
:mod:`.phong`              modified Phong and normalised Blinn-Phong
:mod:`.microfacet_models`  Cook-Torrance, GGX/Smith, glTF metal-roughness, UE4
:mod:`.fitted`             the ABC and SGD fits of the 100 MERL materials
:mod:`.materials`          their published parameter tables (``data/*.tsv``)
:mod:`.rgb`                evaluating an RGB model's three channels at once
:mod:`.common_params`      parameters several models share, declared once
=========================  ===================================================================
"""
