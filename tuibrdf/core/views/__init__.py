"""What each pane of the viewer draws, as numbers (the pictures are :mod:`tuibrdf.render`'s).

=================  ======================================================================
:mod:`.frame`      one frame: a :class:`~.frame.FrameRequest` computed once into a
                   :class:`~.frame.FrameResult` that every pane draws from
:mod:`.hemimap`    the Lambert azimuthal equal-area map of the hemisphere
:mod:`.sections`   sections of the hemisphere through the lobe's peak
:mod:`.lit`        a lit sphere and a lit plane under one light
:mod:`.halfdiff`   any model in Rusinkiewicz's half/difference angles (θh, θd, φd)
=================  ======================================================================
"""
