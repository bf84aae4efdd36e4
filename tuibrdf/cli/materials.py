"""``tuibrdf materials [--json] [--color ...]``: the 100 MERL materials the fitted models carry.

One line per material, sorted by name: a colour swatch of each fit (its albedo at θi = 0° as an
sRGB colour) where stdout is a colour terminal, then the directional albedo a(θi) (R,G,B) of the
ABC and SGD fits at θi = 0° and 60°.  Colour follows ``tuibrdf render``'s rule (``--color auto``:
plain text when piped, with ``NO_COLOR`` or ``TERM=dumb``).  The albedos are read from
``tuibrdf/core/brdf/data/material_albedo.tsv`` (computed by the albedo quadrature, see
:mod:`~tuibrdf.core.sphere.material_albedo`), so the listing takes milliseconds and is the
same on every machine.  ``--json`` adds each material's other name in the SGD data (accepted as
an alias) and the stored digits.
"""

from __future__ import annotations

import argparse
import io
import sys

from tuibrdf.cli.common import choices_type, print_json
from tuibrdf.cli.render import COLORS, color_system

SWATCH = "██"
HEADER = "# {n} MERL materials (fits: abc = Löw et al. 2012, sgd = Bagher et al. 2012, numbers " \
         "from dj_brdf.h)\n# albedo a(θi) = ∫ f cos θo dω, R,G,B; 'tuibrdf view --material NAME'"


def add_args(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--json", action="store_true", help="print JSON instead of text")
    parser.add_argument("--color", type=choices_type("color mode", COLORS), default="auto",
                        metavar="|".join(COLORS),
                        help="swatches: auto (default) colours only a colour terminal "
                             "(NO_COLOR and TERM=dumb respected)")
    parser.add_argument("--no-color", dest="color", action="store_const", const="none",
                        help="plain text, the same as --color none")


def srgb8(linear) -> tuple[int, int, int]:
    """Linear RGB in [0, 1] (clipped) → 8-bit sRGB (IEC 61966-2-1 transfer function)."""
    out = []
    for v in linear:
        v = min(max(float(v), 0.0), 1.0)
        s = 12.92 * v if v <= 0.0031308 else 1.055 * v ** (1 / 2.4) - 0.055
        out.append(int(round(255 * s)))
    return out[0], out[1], out[2]


def _rgb(v) -> str:
    return ",".join(f"{x:.3f}" for x in v)


def rows():
    """``[(name, other name, {"abc": (2, 3), "sgd": (2, 3)}), ...]`` sorted by name."""
    from tuibrdf.core.brdf.materials import material_names, table
    from tuibrdf.core.sphere.material_albedo import stored

    sgd = table("sgd")
    data = stored()
    return [(n, sgd.other_names[sgd.index(n)], data[n]) for n in material_names()]


def text(color: str) -> str:
    from rich.console import Console
    from rich.segment import Segment, Segments
    from rich.style import Style

    items = rows()
    width = max(len(n) for n, _, _ in items)
    cols = ["abc 0°", "abc 60°", "sgd 0°", "sgd 60°"]
    swatch_w = 6 if color != "none" else 0
    head = " " * swatch_w + f"{'name':<{width}}  " + "  ".join(f"{c:<17}" for c in cols)
    buf = io.StringIO()
    con = Console(file=buf, width=1000, color_system=None if color == "none" else color,
                  force_terminal=color != "none", no_color=False, highlight=False,
                  markup=False, emoji=False, legacy_windows=False, soft_wrap=True,
                  force_jupyter=False, force_interactive=False, _environ={})
    con.print(HEADER.format(n=len(items)))
    con.print(head.rstrip())
    for name, _, alb in items:
        # segments, not a Text: Rich keeps a Style's escape codes on it for the first colour
        # system that rendered it, and a Text's styles go through Rich's cache of combined
        # styles, shared by the process (a 256-colour rendering before made these 256-colour)
        line = []
        if color != "none":
            for model in ("abc", "sgd"):
                r, g, b = srgb8(alb[model][0])
                line += [Segment(SWATCH, Style(color=f"rgb({r},{g},{b})")), Segment(" ")]
            line.append(Segment(" "))
        line.append(Segment(f"{name:<{width}}  " + "  ".join(
            f"{_rgb(alb[m][k]):<17}" for m in ("abc", "sgd") for k in (0, 1)).rstrip()))
        con.print(Segments([*line, Segment.line()]), end="")
    return buf.getvalue()


def run(args: argparse.Namespace) -> int:
    if args.json:
        from tuibrdf.core.sphere.material_albedo import THETAS

        doc = {
            "source": "dj_brdf.h (jdupuy/dj_brdf, public domain): djb::abc::s_data, "
                      "djb::sgd::s_data",
            "albedo": "directional albedo, integral of f cos(theta_o) over the hemisphere, "
                      "R,G,B, per theta_i",
            "theta_i": list(THETAS),
            "materials": [
                {"name": n, "aliases": [o] if o and o != n else [],
                 "albedo": {m: {f"{t:g}": v.tolist() for t, v in zip(THETAS, a[m], strict=True)}
                            for m in ("abc", "sgd")}}
                for n, o, a in rows()
            ],
        }
        print_json(doc, ascii=False)
        return 0
    sys.stdout.write(text(color_system(args.color)))
    return 0
