"""``tuibrdf eval``: BRDF values for given directions, as a table or JSON.

The light is at ``(θi, φi)``, φi = 180° unless ``--phi-i`` moves it (SPEC §1), so the mirror
direction is ``(θr = θi, φr = φi − 180°)``: ``φr = 0`` by default.
Several ``--theta-r`` and ``--phi-r`` values give their **outer product**, θr varying slowest:
``--theta-r 0 30 --phi-r 0 180`` prints the four rows (0, 0), (0, 180), (30, 0), (30, 180).
Several ``--theta-i`` values (BRDF Explorer's habit of comparing incidences) repeat that for
each θi, θi slowest, with a ``theta_i`` column.
Values are in sr⁻¹ (no cosine factor; ``--cosine`` multiplies by cos θr), printed with
``%.6g`` in the table and at full precision in JSON.
"""

from __future__ import annotations

import argparse

from tuibrdf.cli.common import (
    add_model_args,
    add_phi_i,
    add_theta_i,
    fmt_params,
    json_params,
    phi_r_deg,
    print_json,
    resolve,
    theta_r_deg,
)
from tuibrdf.core.conventions import fmt_number
from tuibrdf.core.display import DISPLAY


def add_args(parser: argparse.ArgumentParser) -> None:
    add_model_args(parser)
    add_theta_i(parser, many=True)
    add_phi_i(parser)
    parser.add_argument("--theta-r", type=theta_r_deg, nargs="+", required=True, metavar="DEG",
                        help="viewing polar angle(s) θr in degrees, in [0, 90]")
    parser.add_argument("--phi-r", type=phi_r_deg, nargs="+", required=True, metavar="DEG",
                        help="viewing azimuth(s) φr in degrees, in [-360, 360]; with the "
                             "default --phi-i 180, 0 is the mirror side and 180 the light's")
    parser.add_argument("--cosine", action="store_true",
                        help="print f·cos θr (reflected intensity) instead of f")
    parser.add_argument("--json", action="store_true", help="print JSON instead of a table")
    parser.add_argument("--save-bparam", metavar="PATH",
                        help="also write the parameters to a BRDF Explorer .bparam file (for "
                             "a .brdf or .bparam model)")


def values(model, params, theta_i: float, theta_r, phi_r, cosine: bool = False,
           phi_i: float = DISPLAY.phi_i.default):
    """f(θi; θr, φr) over the outer product θr × φr: shape ``(len θr, len φr)`` (+ ``(3,)``
    for an RGB model)."""
    import numpy as np  # here, not at the top: --help stays light

    from tuibrdf.core.directions import from_degrees, incident
    from tuibrdf.core.evaluate import evaluate_resolved, f_cos

    wi = incident(theta_i, phi_i)
    wo = from_degrees(np.asarray(theta_r, dtype=float)[:, None],
                      np.asarray(phi_r, dtype=float)[None, :])
    f = np.asarray(evaluate_resolved(model, params, np.broadcast_to(wi, wo.shape), wo))
    return f_cos(f, wo) if cosine else f


def run(args: argparse.Namespace) -> int:
    model, params = resolve(args)
    if args.save_bparam:
        from tuibrdf.cli.common import UsageError
        from tuibrdf.core.formats.bparam_write import write_bparam
        from tuibrdf.core.formats.files import UserFileError

        try:
            write_bparam(model, params, args.save_bparam)
        except UserFileError as e:
            raise UsageError(str(e)) from None
    thetas = list(args.theta_i)
    many = len(thetas) > 1
    rows = []
    for ti in thetas:
        f = values(model, params, ti, args.theta_r, args.phi_r, args.cosine, args.phi_i)
        rows += [(ti, tr, pr, f[a, b]) for a, tr in enumerate(args.theta_r)
                 for b, pr in enumerate(args.phi_r)]
    quantity = "f*cos(theta_r)" if args.cosine else "f"
    if args.json:
        doc = {
            "model": model.name,
            "params": json_params(params),
            "theta_i": thetas if many else thetas[0],
            "phi_i": args.phi_i,
            "quantity": quantity,
            "unit": "1/sr",
            "rgb": model.rgb,
            "values": [{**({"theta_i": ti} if many else {}), "theta_r": tr, "phi_r": pr,
                        "f": v.tolist() if model.rgb else float(v)} for ti, tr, pr, v in rows],
        }
        print_json(doc)
        return 0
    ti_text = "" if many else f"  theta_i={fmt_number(thetas[0])}"
    print(f"# {model.name}  {fmt_params(params)}{ti_text}"
          + (f"  phi_i={fmt_number(args.phi_i)}" if args.phi_i != DISPLAY.phi_i.default else ""))
    cols = ["f_R", "f_G", "f_B"] if model.rgb else ["f"]
    if args.cosine:
        cols = [c + "*cos" for c in cols]
    first = [f"{'theta_i':>8}"] if many else []
    print(" ".join(first + [f"{'theta_r':>8}", f"{'phi_r':>8}"] + [f"{c:>12}" for c in cols])
          + "  [1/sr]")
    for ti, tr, pr, v in rows:
        vals = v.tolist() if model.rgb else [float(v)]
        ti_col = [f"{fmt_number(ti):>8}"] if many else []
        print(" ".join(ti_col + [f"{fmt_number(tr):>8}", f"{fmt_number(pr):>8}"]
                       + [f"{fmt_number(x):>12}" for x in vals]))
    return 0
