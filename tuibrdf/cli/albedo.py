"""``tuibrdf albedo``: the directional albedo a(θi) = ∫ f cos θr dω, as a table or JSON.

One row per ``--theta-i`` value (default: every 15° and 89°).  RGB models print one column per
channel.  The table shows 4 decimals, what the quadrature guarantees; JSON has every digit.  A
value above 1 reflects more energy than arrives: the row is flagged ``not energy-conserving``
(the JSON has ``"energy_conserving": false``).  The integral is
:func:`tuibrdf.core.quadrature.albedo_resolved` with its defaults (the icosahedral mesh at
level 6, checked against level 5 and refined adaptively where a sharp lobe needs it; about
1e-4 or better on the default parameters, see docs/accuracy.md).
"""

from __future__ import annotations

import argparse
import json

from .common import add_model_args, add_phi_i, add_theta_i, fmt, fmt_params, json_params, resolve

DEFAULT_THETAS = (0.0, 15.0, 30.0, 45.0, 60.0, 75.0, 89.0)


def add_args(parser: argparse.ArgumentParser) -> None:
    add_model_args(parser)
    add_theta_i(parser, many=True, default=list(DEFAULT_THETAS))
    add_phi_i(parser)
    parser.add_argument("--json", action="store_true", help="print JSON instead of a table")


def albedos(model, params, thetas, phi_i: float = 180.0):
    """a(θi) for each θi: shape ``(n,)``, or ``(n, 3)`` for an RGB model."""
    import numpy as np

    from ..core.quadrature import albedo_resolved

    return np.array([np.asarray(albedo_resolved(model, params, t, phi_i), dtype=float)
                     for t in thetas])


def run(args: argparse.Namespace) -> int:
    import numpy as np

    from ..core.conventions import ENERGY_TOL  # a > 1 + ENERGY_TOL is flagged

    model, params = resolve(args)
    thetas = [float(t) for t in args.theta_i]
    a = albedos(model, params, thetas, args.phi_i)
    over = [bool(np.max(row) > 1.0 + ENERGY_TOL) for row in a]
    if args.json:
        doc = {
            "model": model.name,
            "params": json_params(params),
            "quantity": "directional albedo: integral of f*cos(theta_r) over the hemisphere",
            "rgb": model.rgb,
            "values": [{"theta_i": t, "albedo": row.tolist() if model.rgb else float(row),
                        "energy_conserving": not o}
                       for t, row, o in zip(thetas, a, over, strict=True)],
        }
        print(json.dumps(doc, indent=2, allow_nan=False))
        return 0
    print(f"# {model.name}  {fmt_params(params)}")
    print("# directional albedo a = ∫ f cos θr dω (quadrature error ≲ 1e-4, docs/accuracy.md)")
    cols = ["a_R", "a_G", "a_B"] if model.rgb else ["a"]
    print(" ".join([f"{'theta_i':>8}"] + [f"{c:>10}" for c in cols]))
    for t, row, o in zip(thetas, a, over, strict=True):
        vals = row.tolist() if model.rgb else [float(row)]
        flag = "  > 1: not energy-conserving" if o else ""
        print(" ".join([f"{fmt(t):>8}"] + [f"{x:>10.4f}" for x in vals]) + flag)
    return 0
