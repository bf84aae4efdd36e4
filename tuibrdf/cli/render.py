"""``tuibrdf render``: a picture of the BRDF on stdout, the same bytes on any machine.

``tuibrdf render MODEL [-p NAME=VALUE ...] [--theta-i DEG] [--phi-i DEG] [--view VIEW]
[--width W] [--height H] [--color auto|truecolor|256|none | --no-color] [--cmap NAME] [--log]
[--cosine]``, and the options of single views below.

Views: ``map`` (Lambert equal-area map, the default), ``incidence`` (polar cross-section in the
plane of incidence), ``perpendicular`` (the section through the lobe's peak across the plane of
incidence, ``--section-azimuth`` turns it), ``solid`` (3D photometric solid seen from
``--azimuth``, ``--elevation``), ``albedo`` (a(θi) over 0–90°), ``sphere`` and ``plane`` (the
material lit from θi, ``--exposure``, ``--gamma``), ``slice`` (θh × θd image at ``--phi-d``,
``--linear-theta-h``), ``theta-h`` (f against θh at ``--theta-d``, ``--phi-d``), ``theta-d`` (f
against θd at ``--theta-h``, ``--phi-d``), or ``overview`` (``all`` is its older name): map, both
cross-sections and the albedo curve one below the other, each ``W × H`` cells, with a blank line
between them.  A first line always names the model, θi and φi (then the parameters, as the
width allows), whatever each view's own title has room for.

Determinism: the size never comes from the terminal (default 80×24), and the console is built
with every setting Rich would otherwise read from the environment (width, colour system,
``NO_COLOR``, ``FORCE_COLOR``, ``TERM``).  ``--color auto`` is the only setting that looks at
the environment: plain text when ``NO_COLOR`` is set, ``TERM=dumb`` or stdout is not a
terminal (so ``tuibrdf render ... > file`` is readable), else truecolor when ``COLORTERM`` says
so, else 256 colours.  Plain text has no trailing spaces.
"""

from __future__ import annotations

import argparse
import io
import os
import sys

from tuibrdf.cli.common import (
    TYPE_CHECKING,
    UsageError,
    add_model_args,
    add_phi_i,
    add_setting,
    add_theta_i,
    choices_type,
    int_in,
    isatty,
)
from tuibrdf.core.display import DISPLAY
from tuibrdf.render import CMAPS, MIN_HEIGHT, MIN_WIDTH, VIEWS

if TYPE_CHECKING:
    from typing import Any

#: what ``--view overview`` draws (``all``: its older name, still accepted)
ALL = ("map", "incidence", "perpendicular", "albedo")
OVERVIEW = ("overview", "all")
COLORS = ("auto", "truecolor", "256", "none")
MAX_SIZE = 1000


def add_args(parser: argparse.ArgumentParser) -> None:
    add_model_args(parser, optional=True)
    add_theta_i(parser, default=DISPLAY.theta_i.default)
    add_phi_i(parser)
    views = (*VIEWS, OVERVIEW[0])
    parser.add_argument("--view", type=choices_type("view", (*views, *OVERVIEW[1:])),
                        default="map", metavar="|".join(views),
                        help="what to draw (default: map); overview = map, both "
                             "cross-sections and the albedo curve (all: the same)")
    parser.add_argument("--width", type=int_in("width", MIN_WIDTH, MAX_SIZE), default=80,
                        metavar="W", help=f"width in cells (default 80, {MIN_WIDTH} to "
                                          f"{MAX_SIZE})")
    parser.add_argument("--height", type=int_in("height", MIN_HEIGHT, MAX_SIZE), default=24,
                        metavar="H", help=f"height in cells of each view (default 24, "
                                          f"{MIN_HEIGHT} to {MAX_SIZE})")
    parser.add_argument("--color", type=choices_type("color mode", COLORS), default="auto",
                        metavar="|".join(COLORS),
                        help="auto (default): plain text unless stdout is a colour terminal "
                             "(NO_COLOR and TERM=dumb respected)")
    parser.add_argument("--no-color", dest="color", action="store_const", const="none",
                        help="plain text, the same as --color none")
    parser.add_argument("--cmap", type=choices_type("colour map", CMAPS), default=DISPLAY.cmap,
                        metavar="|".join(CMAPS), help="colour map of the map and the solid "
                                                      f"(default {DISPLAY.cmap}, as in the "
                                                      "source document)")
    parser.add_argument("--log", action="store_true",
                        help="logarithmic scale (3 decades below the maximum)")
    parser.add_argument("--cosine", action="store_true",
                        help="show f·cos θr (reflected intensity) instead of f")
    add_setting(parser, "--azimuth", DISPLAY.azimuth, "DEG",
                "3D solid: view azimuth in degrees")
    add_setting(parser, "--elevation", DISPLAY.elevation, "DEG",
                "3D solid: view elevation in degrees")
    add_extra_args(parser)
    from tuibrdf.cli import export

    export.add_args(parser)
    from tuibrdf.cli.sides import add_compare_args

    add_compare_args(parser)
    parser.add_argument("--preset", metavar="NAME",
                        help="draw a saved preset, or a seed comparison: diffuse, specular "
                             "(its sides; θi from --theta-i); a preset naming a .py model "
                             "file runs that file's code, so it needs --trust")
    parser.add_argument("--trust", action="store_true",
                        help="let --preset load a preset that names a .py model file (its "
                             "Python code runs)")


def add_extra_args(parser: argparse.ArgumentParser) -> None:
    """Options of the perpendicular, lit and half/difference views."""
    add_setting(parser, "--section-azimuth", DISPLAY.section_azimuth, "DEG",
                "perpendicular: turn the section about the lobe's peak; 90 is across the "
                "plane of incidence, 0 the plane itself")
    add_setting(parser, "--exposure", DISPLAY.exposure, "X",
                "sphere, plane: radiance scale before the clip at white (1: a white Lambert "
                "surface facing the light is white)")
    add_setting(parser, "--gamma", DISPLAY.gamma, "G", "sphere, plane: display gamma")
    add_setting(parser, "--theta-d", DISPLAY.theta_d, "DEG", "theta-h: the fixed θd")
    add_setting(parser, "--theta-h", DISPLAY.theta_h, "DEG", "theta-d: the fixed θh")
    add_setting(parser, "--phi-d", DISPLAY.phi_d, "DEG", "slice, theta-h, theta-d: the fixed φd")
    parser.add_argument("--linear-theta-h", action="store_true",
                        help="slice: a linear θh axis instead of MERL's √θh")


def color_system(choice: str, environ: os._Environ | dict = os.environ,
                 stream: Any = None) -> str:
    """The colour system ``--color choice`` means here (``auto`` looks at the environment and
    at ``stream``, standard output as it is at the call: not at import, which a caller that
    redirects it later, or closes what it was then, would not see)."""
    if choice != "auto":
        return choice
    if "NO_COLOR" in environ or environ.get("TERM") == "dumb":
        return "none"
    if not isatty(sys.stdout if stream is None else stream):
        return "none"
    return "truecolor" if environ.get("COLORTERM") in ("truecolor", "24bit") else "256"


def picture(model, values, args: argparse.Namespace, color: str, other=None) -> str:
    """The text ``run`` prints (ANSI escapes unless ``color == "none"``); ``other``: side B
    ``(model, values)`` of a comparison (:func:`tuibrdf.render.pair.render_pair`)."""
    from functools import partial

    from rich.console import Console

    from tuibrdf.render.braille import charset_for
    from tuibrdf.render.pair import render_pair
    from tuibrdf.render.views import render_view

    views = ALL if args.view in OVERVIEW else (args.view,)
    buf = io.StringIO()
    con = Console(file=buf, width=args.width, color_system=None if color == "none" else color,
                  force_terminal=color != "none", no_color=False, highlight=False,
                  markup=False, emoji=False, legacy_windows=False, soft_wrap=False,
                  force_jupyter=False, force_interactive=False, _environ={})
    con.print(context_line(model, values, args), no_wrap=True, crop=True)
    note = negative_line(model, values, args)
    if note:  # a user model's sign slip would otherwise look like a dark material
        con.print(note, no_wrap=True, crop=True)
    for i, view in enumerate(views):
        if i:
            con.print()
        # every view through the one frame computation (render_view → compute_frame → pane)
        con.print((partial(render_pair, view, (model, values), other) if other else
                   partial(render_view, view, model, values))(
            args.theta_i, args.width, args.height, color=color,
            cmap=args.cmap, log=args.log, cosine=args.cosine and view != "albedo",
            azimuth_deg=args.azimuth, elevation_deg=args.elevation,
            section_azimuth_deg=args.section_azimuth, exposure=args.exposure, gamma=args.gamma,
            theta_d_deg=args.theta_d, theta_h_deg=args.theta_h, phi_d_deg=args.phi_d,
            sqrt_h=not args.linear_theta_h, phi_i_deg=args.phi_i,
            charset=charset_for(getattr(sys.stdout, "encoding", None))))
    text = buf.getvalue()
    if color == "none":  # for logs and docs: no trailing spaces
        text = "\n".join(line.rstrip() for line in text.split("\n"))
    return text


def context_line(model, values, args: argparse.Namespace) -> str:
    """``phong  θi=40°  φi=180°  kd=0.2 ks=0.5 n=20``: what every picture shows, whole at
    any width (the parameters go first when the line is too long)."""
    from tuibrdf.cli.common import fmt_params
    from tuibrdf.core.conventions import fmt_number
    from tuibrdf.core.material import Material
    from tuibrdf.render.text import fit_parts, phi_deg_text

    need = [Material(model, values).label, f"θi={fmt_number(args.theta_i)}°",
            f"φi={phi_deg_text(args.phi_i)}°"]
    line = fit_parts([*((s, 0) for s in need), (fmt_params(values), 1)], args.width)
    if all(s in line for s in need):
        return line
    import textwrap  # narrower than the three: on as many lines as they take, never cut

    return "\n".join(textwrap.wrap(" ".join(need), args.width, break_long_words=True,
                                   break_on_hyphens=False))


def negative_line(model, values, args: argparse.Namespace) -> str:
    """``f < 0 in 12 % of directions, clamped to 0`` for a user model that goes negative at
    this light, else ``""``."""
    from tuibrdf.core.directions import incident
    from tuibrdf.core.views.negatives import negative_note, negative_share

    return negative_note(negative_share(model, values, incident(args.theta_i, args.phi_i)))


#: stand-ins in a picture for a stream that cannot encode them (plot grids are dotted with ·)
PICTURE_ASCII = {"·": "."}


def run(args: argparse.Namespace) -> int:
    from tuibrdf.cli.sides import sides_of
    from tuibrdf.cli.text import can_encode, to_stream

    (model, values), other = sides_of(args)
    from tuibrdf.cli import export

    if export.wanted(args):  # --format, --output, --inline (cli/export.py)
        if other is not None and args.format not in ("text", "ansi", "svg", "html"):
            raise UsageError(f"--format {args.format} writes one model's numbers or picture; "
                             "with --compare: text, ansi, svg or html")
        return export.run(args, model, values,
                          lambda c: picture(model, values, args, c, other), color_system)
    color = color_system(args.color)
    if color != "none" and not can_encode(sys.stdout, "▀"):
        color = "none"  # no half blocks in this locale: the ASCII ramp of --color none
    sys.stdout.write(to_stream(picture(model, values, args, color, other), sys.stdout,
                               PICTURE_ASCII))
    sys.stdout.flush()
    return 0
