"""``tuibrdf compare``: how far apart two BRDFs are, at each θi.

``tuibrdf compare A [-p NAME=VALUE ...] B [-q NAME=VALUE ...] [--theta-i DEG [DEG ...]]
[--phi-i DEG] [--json]`` (θi by default every 15° and 89°, as ``tuibrdf albedo``).  A and B
are model names, files or ``material:NAME[:abc|sgd]`` (:mod:`tuibrdf.cli.sides`); ``-p``
sets A's parameters, ``-q`` B's.  For each θi: each side's
directional albedo with its error estimate, ``rel_l2 = sqrt(∫(fA − fB)² cos θo dω /
∫ fref² cos θo dω)`` with its error estimate (the reference is B, or the data when A alone is
measured), and the largest difference relative to the reference's peak, signed as fA − fB,
with its direction (:mod:`tuibrdf.core.sphere.compare`).  RGB sides: luminance, and per
channel.  ``--json``: a list with one object per θi.
"""

from __future__ import annotations

import argparse

from tuibrdf.cli.common import DEFAULT_THETAS, add_phi_i, add_theta_i, fmt_params, print_json


def add_args(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("a", metavar="A", help="model name, file (.brdf, .bparam, .py, .bsdf, "
                                               ".binary) or material:NAME[:abc|sgd]")
    parser.add_argument("-p", "--param", action="append", default=[], metavar="NAME=VALUE",
                        help="set a parameter of A (repeatable)")
    parser.add_argument("b", metavar="B", help="the other side, as A")
    parser.add_argument("-q", "--param-b", action="append", default=[], metavar="NAME=VALUE",
                        help="set a parameter of B (repeatable)")
    add_theta_i(parser, many=True, default=list(DEFAULT_THETAS))
    add_phi_i(parser)
    parser.add_argument("--json", action="store_true", help="print JSON instead of a table")


def _pm(v, e) -> str:
    return "—" if v is None else f"{v:.6g} ± {e:.0e}"


def _pct(v) -> str:
    return "—" if v is None else f"{100 * v:+.3g} %"


def run(args: argparse.Namespace) -> int:
    from tuibrdf.cli.sides import side
    from tuibrdf.core.sphere.compare import compare, reference_side

    ma, va = side(args.a, args.param)
    mb, vb = side(args.b, args.param_b)
    ref = reference_side(ma, mb)
    rows = compare(ma, va, mb, vb, [float(t) for t in args.theta_i], args.phi_i,
                   reference=ref)
    if args.json:
        print_json([r.as_dict() for r in rows])
        return 0
    print(f"# A: {ma.name}  {fmt_params(va)}".rstrip())
    print(f"# B: {mb.name}  {fmt_params(vb)}".rstrip())
    print(f"# reference: {ref.upper()}; rel_l2 = sqrt(∫(fA−fB)² cos θo dω / ∫ f{ref.upper()}² "
          f"cos θo dω); max diff = (fA−fB)/peak f{ref.upper()} where |fA−fB| is largest")
    lum = " (luminance)" if rows and rows[0].channels else ""
    print(f"{'theta_i':>8}  {'albedo A':>20}  {'albedo B':>20}  {'rel_l2':>20}  "
          f"{'max diff':>10}  at (θo, φo){lum}")

    def line(label, d):
        return (f"{label:>8}  {_pm(d['albedo_a'], d['albedo_a_error']):>20}  "
                f"{_pm(d['albedo_b'], d['albedo_b_error']):>20}  "
                f"{_pm(d['rel_l2'], d['rel_l2_error']):>20}  {_pct(d['max_diff']):>10}  "
                f"({d['max_diff_theta_o']:.4g}°, {d['max_diff_phi_o']:.4g}°)")

    for r in rows:
        print(line(f"{r.theta_i:g}", r.as_dict()))
        for name, d in (r.channels or {}).items():
            print(line(name, d))
    return 0
