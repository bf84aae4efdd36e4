"""Integration and search on the hemisphere of outgoing directions.

=========================  ==================================================================
:mod:`.mesh`               the hierarchical icosahedral hemisphere and adaptive refinement
:mod:`.integrator`         nested adaptive Gauss–Kronrod in polar coordinates about a lobe
:mod:`.albedo`             directional albedo with its error estimate, the energy test
:mod:`.lobes`              per built-in model, where its lobe is: the albedo's integration hints
:mod:`.peak`               the peak of a lobe: the one finder every number on screen uses
:mod:`.horizon`            peaks on the horizon, and the colour scale the pictures use
:mod:`.material_albedo`    the stored albedos of the 100 MERL materials' fits
=========================  ==================================================================
"""
