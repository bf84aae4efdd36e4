"""Terminal pictures: arrays in, Rich renderables and plain strings out (never imports textual).

The names every front end lists are declared here, with no import, so ``tuibrdf --help`` can
show them without loading numpy or Rich.
"""

#: the lit and half/difference views (issue 13; ``tuibrdf.core.views.frame.EXTRA_VIEWS``)
EXTRA_VIEWS: tuple[str, ...] = ("sphere", "plane", "slice", "theta-h", "theta-d", "energy")
#: every picture: the map, the two cross-sections, the 3D solid, the albedo curve, the extras
VIEWS: tuple[str, ...] = ("map", "incidence", "perpendicular", "solid", "albedo",
                          *EXTRA_VIEWS)
VIEW_TITLES = {"map": "equal-area map", "incidence": "plane of incidence",
               "perpendicular": "section through the peak", "solid": "3D photometric solid",
               "albedo": "albedo a(θi)", "sphere": "lit sphere", "plane": "lit plane",
               "slice": "θh × θd slice", "theta-h": "f(θh) at fixed θd",
               "theta-d": "f(θd) at fixed θh", "energy": "energy E(μ, p)"}
#: colour maps (:mod:`.colormap`)
CMAPS: tuple[str, ...] = ("grey", "viridis", "inferno")
#: the smallest pane, in cells
MIN_WIDTH, MIN_HEIGHT = 12, 6
