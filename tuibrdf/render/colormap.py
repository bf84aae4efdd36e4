"""Colour maps, scales and quantisation for the terminal pictures.

Maps (:data:`CMAPS`):

``grey``     black → white, linear in 8-bit values (the seed's default picture)
``viridis``  matplotlib's perceptually uniform map (van der Walt & Smith, 2015)
``inferno``  matplotlib's perceptually uniform black-body-like map

viridis and inferno are stored as 53 anchor points (every 5th entry and the last of the
256-entry tables published in matplotlib's ``_cm_listed.py``, six decimals as published) and
interpolated linearly between them; matplotlib is not a dependency.  The largest deviation from
the full 256-entry tables is below one 8-bit step.

Scales (:class:`Scale`): BRDF values are ≥ 0, so the linear scale runs from 0 to the maximum;
the log scale shows :data:`LOG_DECADES` decades below the maximum (values below
``max·10^-decades``, zeros included, take the lowest colour).  Values are quantised to
``levels`` colours (32–256, default :data:`DEFAULT_LEVELS`): level ``k`` holds
``t ∈ [k/L, (k+1)/L)`` of the normalised value ``t ∈ [0, 1]`` (``t = 1`` falls in the top level)
and is drawn with the map's colour at ``k/(L−1)``, so both ends of the map are used exactly.
NaN (outside the disc) becomes :data:`~tuibrdf.render.halfblock.TRANSPARENT`, the terminal's own
background, never a colour of the map.

RGB models (:func:`colorize`, ``rgb_mode``): ``"color"`` shows each channel on the common scale
(the maximum over all three channels), one 8-bit level per quantisation step;
``"luminance"`` maps the Rec.709 luminance ``0.2126 R + 0.7152 G + 0.0722 B`` of the linear
values through the colour map.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from rich.console import Group
from rich.text import Text

from tuibrdf.core.conventions import fmt_value, luminance
from tuibrdf.core.display import DISPLAY
from tuibrdf.core.numerics import snapped_floor, snapped_rint
from tuibrdf.render import CMAPS
from tuibrdf.render.halfblock import SHADES, TRANSPARENT, HalfBlockImage, register_ramp

RGB_MODES: tuple[str, ...] = ("color", "luminance")
DEFAULT_LEVELS = 256
MIN_LEVELS, MAX_LEVELS = 32, 256
#: decades below the maximum shown by the log scale
LOG_DECADES = 3.0


def _anchors(rows: tuple[tuple[float, float, float, float], ...]) -> np.ndarray:
    """``(index in the 256 table, r, g, b)`` rows → ``(K, 4)`` array with position in [0, 1]."""
    a = np.array(rows, dtype=float)
    a[:, 0] /= 255.0
    return a


# matplotlib _cm_listed.py (BSD-compatible licence), entries 0, 5, …, 250 and 255
_VIRIDIS = _anchors((
    (0, 0.267004, 0.004874, 0.329415),
    (5, 0.273809, 0.031497, 0.358853),
    (10, 0.278791, 0.062145, 0.386592),
    (15, 0.281924, 0.089666, 0.412415),
    (20, 0.283197, 0.115680, 0.436115),
    (25, 0.282623, 0.140926, 0.457517),
    (30, 0.280255, 0.165693, 0.476498),
    (35, 0.276194, 0.190074, 0.493001),
    (40, 0.270595, 0.214069, 0.507052),
    (45, 0.263663, 0.237631, 0.518762),
    (50, 0.255645, 0.260703, 0.528312),
    (55, 0.246811, 0.283237, 0.535941),
    (60, 0.237441, 0.305202, 0.541921),
    (65, 0.227802, 0.326594, 0.546532),
    (70, 0.218130, 0.347432, 0.550038),
    (75, 0.208623, 0.367752, 0.552675),
    (80, 0.199430, 0.387607, 0.554642),
    (85, 0.190631, 0.407061, 0.556089),
    (90, 0.182256, 0.426184, 0.557120),
    (95, 0.174274, 0.445044, 0.557792),
    (100, 0.166617, 0.463708, 0.558119),
    (105, 0.159194, 0.482237, 0.558073),
    (110, 0.151918, 0.500685, 0.557587),
    (115, 0.144759, 0.519093, 0.556572),
    (120, 0.137770, 0.537492, 0.554906),
    (125, 0.131172, 0.555899, 0.552459),
    (130, 0.125394, 0.574318, 0.549086),
    (135, 0.121148, 0.592739, 0.544641),
    (140, 0.119423, 0.611141, 0.538982),
    (145, 0.121380, 0.629492, 0.531973),
    (150, 0.128087, 0.647749, 0.523491),
    (155, 0.140210, 0.665859, 0.513427),
    (160, 0.157851, 0.683765, 0.501686),
    (165, 0.180653, 0.701402, 0.488189),
    (170, 0.208030, 0.718701, 0.472873),
    (175, 0.239374, 0.735588, 0.455688),
    (180, 0.274149, 0.751988, 0.436601),
    (185, 0.311925, 0.767822, 0.415586),
    (190, 0.352360, 0.783011, 0.392636),
    (195, 0.395174, 0.797475, 0.367757),
    (200, 0.440137, 0.811138, 0.340967),
    (205, 0.487026, 0.823929, 0.312321),
    (210, 0.535621, 0.835785, 0.281908),
    (215, 0.585678, 0.846661, 0.249897),
    (220, 0.636902, 0.856542, 0.216620),
    (225, 0.688944, 0.865448, 0.182725),
    (230, 0.741388, 0.873449, 0.149561),
    (235, 0.793760, 0.880678, 0.120005),
    (240, 0.845561, 0.887322, 0.099702),
    (245, 0.896320, 0.893616, 0.096335),
    (250, 0.945636, 0.899815, 0.112838),
    (255, 0.993248, 0.906157, 0.143936),
    (255, 0.993248, 0.906157, 0.143936),
))

_INFERNO = _anchors((
    (0, 0.001462, 0.000466, 0.013866),
    (5, 0.007676, 0.006136, 0.046836),
    (10, 0.019373, 0.015133, 0.088767),
    (15, 0.037668, 0.025921, 0.132232),
    (20, 0.061340, 0.036590, 0.177642),
    (25, 0.087411, 0.044556, 0.224813),
    (30, 0.116656, 0.047574, 0.272321),
    (35, 0.149073, 0.045468, 0.317085),
    (40, 0.183429, 0.040329, 0.354971),
    (45, 0.217949, 0.036615, 0.383522),
    (50, 0.251620, 0.037705, 0.403378),
    (55, 0.284321, 0.043933, 0.416608),
    (60, 0.316282, 0.053490, 0.425116),
    (65, 0.347771, 0.064616, 0.430217),
    (70, 0.379001, 0.076253, 0.432719),
    (75, 0.410113, 0.087896, 0.433098),
    (80, 0.441207, 0.099338, 0.431594),
    (85, 0.472328, 0.110547, 0.428334),
    (90, 0.503493, 0.121575, 0.423356),
    (95, 0.534683, 0.132534, 0.416667),
    (100, 0.565854, 0.143567, 0.408258),
    (105, 0.596940, 0.154848, 0.398125),
    (110, 0.627847, 0.166575, 0.386276),
    (115, 0.658463, 0.178962, 0.372748),
    (120, 0.688653, 0.192239, 0.357603),
    (125, 0.718264, 0.206636, 0.340931),
    (130, 0.747127, 0.222378, 0.322856),
    (135, 0.775059, 0.239667, 0.303526),
    (140, 0.801871, 0.258674, 0.283099),
    (145, 0.827372, 0.279517, 0.261750),
    (150, 0.851384, 0.302260, 0.239636),
    (155, 0.873741, 0.326906, 0.216886),
    (160, 0.894305, 0.353399, 0.193584),
    (165, 0.912966, 0.381636, 0.169755),
    (170, 0.929644, 0.411479, 0.145367),
    (175, 0.944285, 0.442772, 0.120354),
    (180, 0.956852, 0.475356, 0.094695),
    (185, 0.967322, 0.509078, 0.068659),
    (190, 0.975677, 0.543798, 0.043618),
    (195, 0.981895, 0.579392, 0.026250),
    (200, 0.985952, 0.615750, 0.025592),
    (205, 0.987819, 0.652773, 0.045581),
    (210, 0.987464, 0.690366, 0.079990),
    (215, 0.984865, 0.728427, 0.120785),
    (220, 0.980032, 0.766837, 0.166353),
    (225, 0.973088, 0.805409, 0.216877),
    (230, 0.964394, 0.843848, 0.273391),
    (235, 0.954997, 0.881569, 0.337475),
    (240, 0.947594, 0.917399, 0.410665),
    (245, 0.947937, 0.949318, 0.491426),
    (250, 0.961812, 0.975924, 0.571925),
    (255, 0.988362, 0.998364, 0.644924),
    (255, 0.988362, 0.998364, 0.644924),
))

_TABLES = {"viridis": _VIRIDIS, "inferno": _INFERNO}


def check_cmap(name: str) -> str:
    if name not in CMAPS:
        raise ValueError(f"unknown colour map {name!r}: expected one of {', '.join(CMAPS)}")
    return name


def check_levels(levels: int) -> int:
    if not MIN_LEVELS <= int(levels) <= MAX_LEVELS:
        raise ValueError(f"levels must lie in {MIN_LEVELS}..{MAX_LEVELS}, got {levels}")
    return int(levels)


def sample(name: str, t: np.ndarray) -> np.ndarray:
    """Colours of map ``name`` at positions ``t ∈ [0, 1]`` as floats in [0, 1], shape
    ``t.shape + (3,)``."""
    check_cmap(name)
    t = np.clip(np.asarray(t, dtype=float), 0.0, 1.0)
    if name == "grey":
        return np.repeat(t[..., None], 3, axis=-1)
    a = _TABLES[name]
    return np.stack([np.interp(t, a[:, 0], a[:, c]) for c in (1, 2, 3)], axis=-1)


@lru_cache(maxsize=64)
def _palette(name: str, levels: int) -> np.ndarray:
    pal = snapped_rint(sample(name, np.linspace(0.0, 1.0, levels)) * 255.0).astype(np.uint8)
    pal.setflags(write=False)
    return pal


def palette(name: str, levels: int = DEFAULT_LEVELS) -> np.ndarray:
    """``(levels, 3)`` uint8 palette of map ``name`` (cached, read-only), registered as a ramp
    (256 colours: lightness never falls, :func:`~.halfblock.ramp_to_xterm`)."""
    pal = _palette(check_cmap(name), check_levels(levels))
    register_ramp(pal)
    return pal


@dataclass(frozen=True)
class Scale:
    """Value → ``t ∈ [0, 1]``: linear from 0 to ``vmax`` or log over ``decades`` below it."""

    vmax: float
    log: bool = False
    decades: float = LOG_DECADES

    @classmethod
    def for_values(cls, values: np.ndarray, log: bool = False, decades: float = LOG_DECADES):
        """The scale whose top is the largest finite value (1 when there is none or it is 0,
        so an all-zero picture shows the lowest colour rather than dividing by zero)."""
        v = np.asarray(values, dtype=float)
        finite = v[np.isfinite(v)]
        vmax = float(finite.max()) if finite.size else 0.0
        return cls(vmax if vmax > 0.0 else 1.0, log, decades)

    @property
    def vmin(self) -> float:
        return self.vmax * 10.0**-self.decades if self.log else 0.0

    def normalise(self, values: np.ndarray) -> np.ndarray:
        """``t`` in [0, 1]; NaN stays NaN."""
        v = np.asarray(values, dtype=float)
        if not self.log:
            return np.clip(v / self.vmax, 0.0, 1.0)  # vmax > 0 by construction
        # values ≤ vmin (zeros included) go to 0; log10 only sees values above lo > 0.  For a
        # subnormal vmax (< 5e-321) vmin = vmax·10⁻³ underflows to 0 and log10(0) would warn:
        # lo is then the smallest subnormal, and vmax/lo ≤ 10³ keeps t ≥ 0
        lo = max(self.vmin, 5e-324)
        above = np.where(v > lo, v, lo)
        t = np.where(v > lo, 1.0 + np.log10(above / self.vmax) / self.decades, 0.0)
        return np.where(np.isnan(v), np.nan, np.clip(t, 0.0, 1.0))

    def value_at(self, t: float) -> float:
        """The value drawn at position ``t`` (inverse of :meth:`normalise`)."""
        if self.log:
            return self.vmax * 10.0 ** (self.decades * (t - 1.0))
        return self.vmax * t

    def ticks(self) -> tuple[float, float, float]:
        """(min, mid, max) values at the left end, centre and right end of the colour bar."""
        return self.vmin, self.value_at(0.5), self.vmax


def quantise(t: np.ndarray, levels: int = DEFAULT_LEVELS) -> np.ndarray:
    """Level index ``⌊t·L⌋`` clipped to ``[0, L−1]``; NaN → ``TRANSPARENT`` (−1).  The floor is
    taken on the snapped ``t·L`` (core.numerics.snap): a value on a level boundary in exact
    arithmetic (a colour bar's evenly spaced t, a ratio of two values computed alike) keeps its
    level whatever the last bits of its computation."""
    t = np.asarray(t, dtype=float)
    nan = np.isnan(t)
    k = snapped_floor(np.where(nan, 0.0, t) * levels).astype(np.int64)
    k = np.clip(k, 0, levels - 1)
    return np.where(nan, TRANSPARENT, k)


@dataclass(frozen=True)
class Colored:
    """A colour-mapped picture: ``index`` into ``palette`` (−1 transparent) and its scale;
    ``shades``: how a terminal draws it (:class:`~tuibrdf.render.halfblock.HalfBlockImage`),
    :data:`~tuibrdf.render.halfblock.SHADES` for RGB colours, None for a colour map's."""

    index: np.ndarray
    palette: np.ndarray
    scale: Scale
    shades: int | None = None


def colorize(
    values: np.ndarray,
    cmap: str = DISPLAY.cmap,
    *,
    levels: int = DEFAULT_LEVELS,
    log: bool = False,
    decades: float = LOG_DECADES,
    rgb_mode: str = "color",
    scale: Scale | None = None,
) -> Colored:
    """Map ``values`` (``(H, W)`` or RGB ``(H, W, 3)``, NaN = background) to palette indices.

    RGB input in ``"color"`` mode gives a palette of the distinct quantised colours (each
    channel on the common scale); in ``"luminance"`` mode its luminance goes through ``cmap``.
    """
    check_levels(levels)
    v = np.asarray(values, dtype=float)
    if v.ndim == 3:
        if rgb_mode not in RGB_MODES:
            raise ValueError(f"rgb mode {rgb_mode!r}: expected one of {', '.join(RGB_MODES)}")
        if rgb_mode == "luminance":
            v = luminance(v)
        else:
            scale = scale or Scale.for_values(v, log, decades)
            k = quantise(scale.normalise(v), levels)  # (H, W, 3); NaN pixels have −1 channels
            nan = k[..., 0] < 0
            code = (np.maximum(k[..., 0], 0) * levels + np.maximum(k[..., 1], 0)) * levels
            code += np.maximum(k[..., 2], 0)
            codes, inverse = np.unique(code[~nan], return_inverse=True)
            index = np.full(nan.shape, TRANSPARENT, dtype=np.int64)
            index[~nan] = inverse
            ch = np.stack([codes // (levels * levels), (codes // levels) % levels, codes % levels])
            pal = snapped_rint(ch.T * (255.0 / (levels - 1))).astype(np.uint8).reshape(-1, 3)
            return Colored(index, pal, scale, SHADES)
    scale = scale or Scale.for_values(v, log, decades)
    return Colored(quantise(scale.normalise(v), levels), palette(cmap, levels), scale)


def colorbar(
    scale: Scale,
    cmap: str = DISPLAY.cmap,
    width: int = 40,
    *,
    levels: int = DEFAULT_LEVELS,
    unit: str = "sr⁻¹",
    color_system: str | None = None,
    note: str = "",
) -> Group:
    """A one-row colour bar ``width`` cells wide, with min / mid / max values underneath.

    For RGB pictures in colour mode pass ``cmap="grey"``: the bar then shows one channel's
    ramp.  ``note`` follows the top value (compare mode: whose peak it is).
    """
    bar = _bar(max(int(width), 3), cmap, levels, color_system)
    width = bar.width
    lo, mid, hi = (fmt_value(x) for x in scale.ticks())
    log = " (log)" if scale.log else ""
    # the top value is the bar's one number that matters: in a narrow bar the note, then the
    # unit, then "(log)" go first (the map's title and the status line say them too)
    tails = [f" {unit}" + (f" {note}" if note else "") + log, f" {unit}{log}", log, ""]
    right = next(hi + t for t in tails if len(lo) + 1 + len(hi + t) <= width or not t)
    return Group(bar, Text(tick_line(width, lo, mid, right)))


@lru_cache(maxsize=64)
def _bar(width: int, cmap: str, levels: int, color_system: str | None) -> HalfBlockImage:
    """The ramp of a colour bar (the same for every frame of a view: its segments are built
    once, not once a key)."""
    t = (np.arange(width) + 0.5) / width
    idx = quantise(t, levels)[None, :].repeat(2, axis=0)
    return HalfBlockImage(idx, palette(cmap, levels), color_system=color_system)


def tick_line(width: int, left: str, mid: str, right: str) -> str:
    """``left`` at the start, ``right`` at the end and ``mid`` centred, each dropped (mid
    first) when it would touch its neighbour; never longer than ``width``."""
    line = [" "] * width
    if len(left) + 1 + len(right) > width:
        right = ""
    line[: len(left)] = left[:width]
    if right:
        line[width - len(right) :] = right
    m0 = width // 2 - len(mid) // 2
    if m0 > len(left) and m0 + len(mid) < width - len(right):
        line[m0 : m0 + len(mid)] = mid
    return "".join(line[:width])
