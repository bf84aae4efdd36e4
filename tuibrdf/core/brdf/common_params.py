"""Parameters shared by several models, declared once.

A model that needs a different default or a more specific one-line doc derives its copy with
:func:`dataclasses.replace`, so name, symbol, range and step stay in one place.

==========  ======  ===============  ========  ====================================
name        symbol  default          range     used by
==========  ======  ===============  ========  ====================================
kd          Kd      0.8              [0, 1]    lambert, oren-nayar(-simple); phong and
                                               blinn-phong (default 0.2); cook-torrance and
                                               ggx (default 0)
base_color  base    (0.8, 0.8, 0.8)  [0, 1]³   disney-diffuse, gltf, ue4
roughness   rough   0.5              [0, 1]    disney-diffuse, gltf, ue4 (doc per model)
==========  ======  ===============  ========  ====================================
"""

from __future__ import annotations

from tuibrdf.core.params import Param

KD = Param("kd", "Kd", 0.8, 0.0, 1.0, 0.01, doc="diffuse reflectance")
BASE = Param("base_color", "base", (0.8, 0.8, 0.8), 0.0, 1.0, 0.01, kind="rgb",
             doc="base colour (linear RGB)")
ROUGHNESS = Param("roughness", "rough", 0.5, 0.0, 1.0, 0.01, doc="roughness")
