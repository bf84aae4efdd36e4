"""Terminal pictures: arrays in, Rich renderables and plain strings out (never imports textual).

The names every front end lists are declared here, with no import, so ``tuibrdf --help`` can
show them without loading numpy or Rich.
"""

#: every picture: the map, the two cross-sections, the 3D solid, the albedo curve
VIEWS: tuple[str, ...] = ("map", "incidence", "perpendicular", "solid", "albedo")
VIEW_TITLES = {"map": "equal-area map", "incidence": "plane of incidence",
               "perpendicular": "perpendicular plane", "solid": "3D photometric solid",
               "albedo": "albedo a(θi)"}
#: colour maps (:mod:`.colormap`)
CMAPS: tuple[str, ...] = ("grey", "viridis", "inferno")
#: the smallest pane, in cells
MIN_WIDTH, MIN_HEIGHT = 12, 6
