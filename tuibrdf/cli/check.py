"""``tuibrdf check``: the checks a renderer runs on a BRDF before shipping it, for CI.

At the given parameters and at each parameter's ends (a real's minimum and maximum, an RGB
colour's all-0 and all-1, a choice's every value), over a fixed set of directions including
the normal, the horizon, wi = wo and the mirror direction:

``finite``       no NaN, no inf, no floating-point exception
``positivity``   the smallest raw value (before the clamp to 0 pictures apply), and where
``reciprocity``  the largest |f(i,o) − f(o,i)| relative to the local value, and where
``energy``       the largest directional albedo less its error estimate over θi; fails above 1
``chi2``         only for a model with a sampler (a ``.py`` file's ``sample``/``pdf``, the
                 built-in ggx): the χ² test of the samples against the pdf, at the given
                 parameters

One line per check: ok or FAIL, the worst value and where.  ``--json`` prints
``{"checks": [{"name", "ok", "worst", "where", "detail"}], ...}``.  Exit status 0 when every
check holds, 1 when one fails, 2 for bad input.  The checks are
:mod:`tuibrdf.core.sphere.checks`.
"""

from __future__ import annotations

import argparse

from tuibrdf.cli.common import add_model_args, fmt_params, json_params, print_json, resolve


def add_args(parser: argparse.ArgumentParser) -> None:
    add_model_args(parser)
    parser.add_argument("--json", action="store_true", help="print JSON instead of lines")
    parser.add_argument("--no-chi2", action="store_true",
                        help="skip the χ² sampling test of a model with a sampler")


def _fmt(x) -> str:
    return "—" if x is None else f"{x:.6g}"


def run(args: argparse.Namespace) -> int:
    from tuibrdf.core.sphere.checks import configurations, run_checks

    model, params = resolve(args)
    results = run_checks(model, params, chi2=not args.no_chi2)
    n = len(configurations(model, params))
    failed = any(not r.ok for r in results)
    if args.json:
        print_json({"model": model.name, "params": json_params(params), "configurations": n,
                    "ok": not failed,
                    "checks": [{"name": r.name, "ok": r.ok, "worst": r.worst,
                                "where": r.where, "detail": r.detail} for r in results]})
        return 1 if failed else 0
    print(f"# {model.name}  {fmt_params(params)}: {n} configuration{'s' * (n != 1)} "
          "(these parameters and each parameter's ends)")
    for r in results:
        verdict = "ok  " if r.ok else "FAIL"
        print(f"{r.name:<12} {verdict}  {_fmt(r.worst):>12}  {r.where}  [{r.detail}]")
    return 1 if failed else 0
