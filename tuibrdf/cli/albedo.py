"""``tuibrdf albedo``: the directional albedo a(θi) = ∫ f cos θr dω, as a table or JSON.

One row per ``--theta-i`` value (default: every 15° and 89°).  RGB models print one column per
channel.  Each row carries the quadrature's estimate of its absolute error (``± 3e-10``; the
largest of the channels, plus the printed value's own rounding, rounded up) and shows the
digits the error leaves (JSON: every digit and ``"error"``, the estimate alone).  A value
above 1 by more than its error reflects more energy than arrives: the row
is flagged ``not energy-conserving`` (the JSON has ``"energy_conserving": false``); the test is
:func:`tuibrdf.core.sphere.albedo.exceeds_one`.  The integral is
:func:`tuibrdf.core.sphere.albedo.albedo_estimate_resolved` (adaptive Gauss–Kronrod about the
lobe, docs/reference/accuracy.md).
"""

from __future__ import annotations

import argparse

from tuibrdf.cli.common import (
    DEFAULT_THETAS,
    add_model_args,
    add_phi_i,
    add_theta_i,
    fmt_params,
    json_params,
    print_json,
    resolve,
)
from tuibrdf.core.conventions import fmt_number
from tuibrdf.core.display import DISPLAY


def add_args(parser: argparse.ArgumentParser) -> None:
    add_model_args(parser)
    add_theta_i(parser, many=True, default=list(DEFAULT_THETAS))
    add_phi_i(parser)
    parser.add_argument("--json", action="store_true", help="print JSON instead of a table")


def albedos(model, params, thetas, phi_i: float = DISPLAY.phi_i.default):
    """``(a, error)`` for each θi: shapes ``(n,)``, or ``(n, 3)`` for an RGB model."""
    import numpy as np

    from tuibrdf.core.sphere.albedo import albedo_estimate_resolved

    est = [albedo_estimate_resolved(model, params, t, phi_i) for t in thetas]
    return (np.array([np.asarray(e.value, dtype=float) for e in est]),
            np.array([np.asarray(e.error, dtype=float) for e in est]))


def run(args: argparse.Namespace) -> int:
    from tuibrdf.core.conventions import decimals_for, fmt_error
    from tuibrdf.core.sphere.albedo import exceeds_one

    model, params = resolve(args)
    thetas = [float(t) for t in args.theta_i]
    a, err = albedos(model, params, thetas, args.phi_i)
    over = [exceeds_one((row, e)) for row, e in zip(a, err, strict=True)]
    if args.json:
        doc = {
            "model": model.name,
            "params": json_params(params),
            "quantity": "directional albedo: integral of f*cos(theta_r) over the hemisphere",
            "rgb": model.rgb,
            "values": [{"theta_i": t, "albedo": row.tolist() if model.rgb else float(row),
                        "error": e.tolist() if model.rgb else float(e),
                        "energy_conserving": not o}
                       for t, row, e, o in zip(thetas, a, err, over, strict=True)],
        }
        print_json(doc)
        return 0
    print(f"# {model.name}  {fmt_params(params)}")
    print("# directional albedo a = ∫ f cos θr dω ± the quadrature's error estimate "
          "(docs/reference/accuracy.md)")
    cols = ["a_R", "a_G", "a_B"] if model.rgb else ["a"]
    width = max(10, 3 + max(decimals_for(e) for e in err))
    print(" ".join([f"{'theta_i':>8}"] + [f"{c:>{width}}" for c in cols] + ["   error"]))
    for t, row, e, o in zip(thetas, a, err, over, strict=True):
        vals = row.tolist() if model.rgb else [float(row)]
        d = decimals_for(e)
        flag = "  > 1: not energy-conserving" if o else ""
        print(" ".join([f"{fmt_number(t):>8}"] + [f"{x:>{width}.{d}f}" for x in vals]
                       + [f"± {fmt_error(e, d)}"]) + flag)
    return 0
