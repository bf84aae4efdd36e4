"""``tuibrdf render … --format FMT [--output FILE] [--size PX] [--inline …]``: the picture or
the numbers of a view as a file (see docs/guide.md, "Figures and numbers").

==========  ==================================================================================
``text``    the text picture (the default; plain in a file unless ``--color`` says otherwise)
``ansi``    the text picture with colour escapes (truecolor unless ``--color 256``)
``svg``     Rich's SVG export of the ANSI picture (no web font, fixed ids: the same bytes)
``html``    Rich's HTML export of it (styles inline)
``png``     the pixel picture of an image view (:mod:`tuibrdf.render.export.figure`)
``npz``     the numbers of the map or the slice (:mod:`tuibrdf.core.views.tables`)
``csv``     the numbers of a section, the albedo curve, the θh or θd curve
``json``    the same as a list of objects
``pdf``     a matplotlib figure of the map, a section or a curve (the ``[plot]`` extra)
==========  ==================================================================================
"""

from __future__ import annotations

import argparse
import sys

from tuibrdf.cli.common import TYPE_CHECKING, UsageError, choices_type, int_in, isatty

if TYPE_CHECKING:  # typing is not imported for ``render --help``
    from collections.abc import Callable
    from typing import Any

FORMATS = ("text", "ansi", "svg", "html", "png", "csv", "npz", "json", "pdf")
INLINE = ("auto", "iterm", "kitty", "sixel", "off")
IMAGE_VIEWS = ("map", "slice", "sphere", "plane", "solid")  # render.export.figure's
NPZ_VIEWS = ("map", "slice", "sphere", "plane", "solid")  # the last three: the map's numbers
TABLE_VIEWS = ("incidence", "perpendicular", "albedo", "theta-h", "theta-d")
BINARY = ("png", "npz", "pdf")
MIN_SIZE, MAX_SIZE = 32, 2048  # render.export.figure's (not imported for --help)
PDF_VIEWS = ("map", *TABLE_VIEWS)  # render.export.plot's


def add_args(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--format", type=choices_type("format", FORMATS), default="text",
                        metavar="|".join(FORMATS),
                        help="what to write (default text): png for the image views (map, "
                             "slice, sphere, plane, solid), npz for those (the slice's or the "
                             "map's numbers: f over the hemisphere at this light), csv and "
                             "json for the sections, albedo, theta-h and theta-d; pdf (needs "
                             "the [plot] extra, matplotlib) for the map and those")
    parser.add_argument("--output", "-o", default="-", metavar="FILE",
                        help="where to write it (default -: standard output)")
    parser.add_argument("--size", type=int_in("size", MIN_SIZE, MAX_SIZE), default=512,
                        metavar="PX",
                        help=f"png and npz: pixels across (default 512, {MIN_SIZE} to "
                             f"{MAX_SIZE})")
    parser.add_argument("--inline", type=choices_type("inline mode", INLINE), default="off",
                        metavar="|".join(INLINE),
                        help="show the image view as a picture in the terminal: iterm "
                             "(iTerm2, WezTerm, VS Code), kitty (kitty, Ghostty), sixel (foot, "
                             "Windows Terminal 1.22+); auto when TERM/TERM_PROGRAM say which "
                             "(over ssh only TERM arrives: name it); in tmux set "
                             "allow-passthrough on (default off)")


def wanted(args: argparse.Namespace) -> bool:
    """Whether ``run`` has something to do (else the text picture goes to stdout as ever)."""
    return args.format != "text" or args.output != "-" or args.inline != "off"


def offered(view: str) -> str:
    """What ``view`` can be written as besides text, ansi, svg and html (every view's)."""
    kinds = [f for f, views in (("png", IMAGE_VIEWS), ("npz", NPZ_VIEWS),
                                ("csv or json", TABLE_VIEWS)) if view in views]
    if view == "energy":  # its numbers are the table `tuibrdf energy` writes
        kinds.append("its table from tuibrdf energy (csv, json or h)")
    return " or ".join(kinds) if kinds else "svg or html"


def _check(args: argparse.Namespace) -> None:
    fmt, view = args.format, args.view
    if fmt == "png" and view not in IMAGE_VIEWS:
        raise UsageError(f"--format png: the {view} view has no pixel picture; image views: "
                         f"{', '.join(IMAGE_VIEWS)}; the {view} view: {offered(view)}")
    if fmt == "npz" and view not in NPZ_VIEWS:
        raise UsageError(f"--format npz: for the views {', '.join(NPZ_VIEWS)}; the "
                         f"{view} view: {offered(view)}")
    if fmt in ("csv", "json") and view not in TABLE_VIEWS:
        raise UsageError(f"--format {fmt}: for the views {', '.join(TABLE_VIEWS)}; the {view} "
                         f"view: {offered(view)}")
    if fmt == "pdf":
        if view not in PDF_VIEWS:
            raise UsageError(f"--format pdf: for the views {', '.join(PDF_VIEWS)}")
        from tuibrdf.render.export.plot import available

        if not available():
            raise UsageError("--format pdf needs matplotlib: pip install 'tuibrdf[plot]'")
    if fmt in BINARY and args.output == "-" and isatty(sys.stdout):
        raise UsageError(f"--format {fmt} is binary: give --output FILE (or --inline for a "
                         "picture in the terminal)")


def look(args: argparse.Namespace) -> dict[str, Any]:
    """The keywords of :func:`tuibrdf.render.views.render_view` from the options."""
    return dict(cmap=args.cmap, log=args.log, cosine=args.cosine and args.view != "albedo",
                azimuth_deg=args.azimuth, elevation_deg=args.elevation,
                section_azimuth_deg=args.section_azimuth, exposure=args.exposure,
                gamma=args.gamma, theta_d_deg=args.theta_d, theta_h_deg=args.theta_h,
                phi_d_deg=args.phi_d, sqrt_h=not args.linear_theta_h, phi_i_deg=args.phi_i)


def table(view: str, model, values: dict, args: argparse.Namespace):
    """The numbers of ``view`` (:func:`tuibrdf.core.views.tables.for_view`)."""
    from tuibrdf.core.views.tables import for_view

    return for_view(view, model, values, args.theta_i, args.phi_i, size=args.size,
                    section_azimuth=args.section_azimuth, theta_d=args.theta_d,
                    theta_h=args.theta_h, phi_d=args.phi_d, sqrt_h=not args.linear_theta_h,
                    cosine=args.cosine)


def rich_export(ansi: str, width: int, fmt: str, title: str) -> str:
    """``ansi`` (the picture with colour escapes) as SVG or HTML
    (:func:`tuibrdf.render.export.terminal.export`)."""
    from rich.text import Text

    from tuibrdf.render.export.terminal import export

    lines = [Text.from_ansi(line) for line in ansi.rstrip("\n").split("\n")]
    return export(lines, width, fmt, title)


def _write(data: bytes | str, output: str) -> None:
    if output == "-":
        if isinstance(data, bytes):
            sys.stdout.flush()
            sys.stdout.buffer.write(data)
            sys.stdout.buffer.flush()
        else:
            sys.stdout.write(data)
        return
    mode = "wb" if isinstance(data, bytes) else "w"
    with open(output, mode, **({} if mode == "wb" else {"encoding": "utf-8",
                                                        "newline": ""})) as f:
        f.write(data)


def run(args: argparse.Namespace, model, values: dict, draw: Callable[[str], str],
        color_system: Callable[..., str]) -> int:
    """Write what ``args`` ask for; ``draw(color)`` is the text picture and ``color_system``
    what ``--color`` means (both :mod:`tuibrdf.cli.render`'s)."""
    _check(args)
    fmt, view = args.format, args.view
    if args.inline != "off" and fmt == "text" and args.output == "-":
        if _inline(args, model, values):
            return 0
    if fmt in ("text", "ansi"):
        if fmt == "ansi":
            color = args.color if args.color not in ("auto", "none") else "truecolor"
        else:
            color = color_system(args.color, stream=sys.stdout if args.output == "-" else None)
            color = "none" if args.output != "-" and args.color == "auto" else color
        _write(draw(color), args.output)
    elif fmt in ("svg", "html"):
        ansi = draw("truecolor")
        title = f"tuibrdf render {model.name} --view {view}"
        _write(rich_export(ansi, args.width, fmt, title), args.output)
    elif fmt == "png":
        from tuibrdf.render.export.figure import figure

        _write(figure(view, model, values, args.theta_i, args.size, **look(args)).png(),
               args.output)
    elif fmt == "pdf":
        from tuibrdf.render.export.plot import pdf

        _write(pdf(table(view, model, values, args), cmap=args.cmap, log=args.log),
               args.output)
    else:
        from tuibrdf.render.export import numbers

        tab = table(view, model, values, args)
        data = {"npz": numbers.to_npz, "csv": numbers.to_csv, "json": numbers.to_json}[fmt](tab)
        _write(data, args.output)
    return 0


def _inline(args: argparse.Namespace, model, values: dict) -> bool:
    """Print the view inline when a protocol applies; False: the text picture instead."""
    import os

    from tuibrdf.render.export import inline

    if args.view not in IMAGE_VIEWS:
        return False
    proto = args.inline
    if proto == "auto":
        proto = inline.detect() if isatty(sys.stdout) else None
        if proto is None:
            return False
    from tuibrdf.render.export.figure import figure

    fig = figure(args.view, model, values, args.theta_i, args.size, **look(args))
    esc = inline.escape(proto, fig.png(), fig.index, fig.palette, tmux=bool(os.environ.get(
        "TMUX")))
    sys.stdout.write(esc)
    return True
