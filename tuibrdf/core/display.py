"""The look's defaults, declared once: what the viewer starts with, what ``tuibrdf render``
draws without options, and the one range each setting may take.

The viewer's keys stop at a setting's range (an angle marked *turn* goes round instead);
``tuibrdf render`` and ``tuibrdf view`` refuse an option outside it; both start from its
default, as do :func:`tuibrdf.render.views.render_view` and
:class:`tuibrdf.render.panes.Look`.  Nothing here imports numpy: ``tuibrdf --help`` shows
these defaults.

===================  =======  ===========  =====================================================
setting              default  range        what
===================  =======  ===========  =====================================================
``theta_i``          30°      0–90°        the light's polar angle θi
``phi_i``            180°     ±360°, turn  the light's azimuth φi (180°: the light on the left)
``azimuth``          −60°     ±360°, turn  the 3D solid's camera azimuth (from +x toward +y)
``elevation``        25°      −90–90°      the 3D solid's camera elevation above the surface
``section_azimuth``  90°      ±360°, turn  ψ of the section through the peak (90°: across
                                           the plane of incidence)
``exposure``         1        2⁻¹²–2¹²     the lit views' radiance scale before the clip at
                                           white (1: a white Lambert surface facing the
                                           light is white)
``gamma``            2.2      1–3          the lit views' display gamma (1: linear; the
                                           displays in use are 1.8–2.6)
``theta_d``          30°      0–90°        f(θh)'s fixed θd
``theta_h``          0°       0–90°        f(θd)'s fixed θh
``phi_d``            90°      0–180°       the half/difference views' fixed φd
===================  =======  ===========  =====================================================

and two choices without a range: ``cmap`` (``grey``, the seed's picture; the colour maps are
:data:`tuibrdf.render.CMAPS`) and ``sqrt_h`` (the slice's θh axis in √θh, as MERL's table).
"""

from __future__ import annotations

from collections import namedtuple  # not dataclasses: --help stays light


class Setting(namedtuple("Setting", "default lo hi unit turn text", defaults=("", False, ""))):
    """A default and its range ``[lo, hi]`` (``unit``: ``"°"`` for an angle).  ``turn``: an
    angle the viewer's keys turn round (by whole turns) instead of stopping at a bound; the
    range is then what a typed value may be.  ``text``: the range as messages write it, when
    ``lo–hi`` is not the clearest way."""

    __slots__ = ()

    def clamp(self, v: float) -> float:
        """``v`` moved into the range."""
        return min(self.hi, max(self.lo, v))

    def accepts(self, v: float) -> bool:
        """Whether ``v`` lies in the range (never for NaN)."""
        return self.lo <= v <= self.hi

    def range_text(self) -> str:
        """``0–90°``, ``1–3``, ``-90 to 90°``, ``2^-12–2^12``."""
        if self.text:
            return self.text
        dash = " to " if self.lo < 0 else "–"
        return f"{self.lo:g}{dash}{self.hi:g}{self.unit}"


Display = namedtuple("Display", "theta_i phi_i azimuth elevation section_azimuth exposure gamma "
                                "theta_d theta_h phi_d cmap sqrt_h")

#: every default of the look and its range (the table above)
DISPLAY = Display(
    theta_i=Setting(30.0, 0.0, 90.0, "°"),
    phi_i=Setting(180.0, -360.0, 360.0, "°", turn=True),
    azimuth=Setting(-60.0, -360.0, 360.0, "°", turn=True),
    elevation=Setting(25.0, -90.0, 90.0, "°"),
    section_azimuth=Setting(90.0, -360.0, 360.0, "°", turn=True),
    exposure=Setting(1.0, 2.0**-12, 2.0**12, text="2^-12–2^12"),
    gamma=Setting(2.2, 1.0, 3.0),
    theta_d=Setting(30.0, 0.0, 90.0, "°"),
    theta_h=Setting(0.0, 0.0, 90.0, "°"),
    phi_d=Setting(90.0, 0.0, 180.0, "°"),
    cmap="grey",
    sqrt_h=True,
)
