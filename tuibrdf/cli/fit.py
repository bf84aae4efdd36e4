"""``tuibrdf fit FILE --model NAME [--json]``: fit an analytic model to a MERL file.

Prints the fitted parameters (one set per channel for a scalar model, one for an RGB model),
the residual (RMS of ``log(1 + f·cos θi·cos θo)`` differences, see :mod:`tuibrdf.core.fit`),
and the albedo of data and fit at θi = 0, 30, 60°.  A file named after a MERL material
(``gold-metallic-paint.binary``) also gets the residuals of the published ABC and SGD fits of
that material (models ``abc``, ``sgd``) on the same objective, for comparison.  A missing or
malformed file, an unknown model or one without continuous parameters: one line on stderr,
exit 2.
"""

from __future__ import annotations

import argparse
import json

from .common import UsageError, fmt, fmt_params, json_params, parse_params

#: ``tuibrdf.core.fit.STRIDE``, repeated so that ``--help`` does not import numpy (a test
#: checks that they agree)
STRIDE = (1, 3, 15)

OBJECTIVE = "rms of log(1 + f*cos(theta_i)*cos(theta_o)) - log(1 + f_data*cos*cos) over bins"


def add_args(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("file", metavar="FILE", help="MERL .binary file")
    parser.add_argument("--model", required=True, metavar="NAME",
                        help="analytic model to fit (e.g. ggx, cook-torrance, blinn-phong, gltf)")
    parser.add_argument("-p", "--param", action="append", default=[], metavar="NAME=VALUE",
                        help="keep a parameter at this value instead of fitting it "
                             "(repeatable), e.g. -p kd=0 or -p fresnel=schlick")
    parser.add_argument("--stride", type=stride_type, default=STRIDE, metavar="H,D,P",
                        help="use every H-th θh, D-th θd, P-th φd bin (default: "
                             f"{','.join(map(str, STRIDE))}; larger is faster and coarser)")
    parser.add_argument("--mean", action="store_true",
                        help="fit a scalar model once, to the mean of R, G, B (one parameter "
                             "set) instead of once per channel")
    parser.add_argument("--json", action="store_true", help="print JSON instead of text")
    parser.add_argument("--save-preset", metavar="NAME",
                        help="save data (A) and fit (B) as a viewer preset: then "
                             "'tuibrdf view --preset NAME' compares them (needs one parameter "
                             "set: an RGB model, or --mean)")


def stride_type(text: str) -> tuple[int, int, int]:
    from .common import parse_int

    try:
        vals = tuple(parse_int(v) for v in text.split(","))
    except ValueError:
        vals = ()
    if len(vals) != 3 or not all(1 <= v <= 45 for v in vals):
        raise argparse.ArgumentTypeError(f"stride = {text!r} is invalid: expected three "
                                         "integers in [1, 45], e.g. 1,3,15")
    return vals  # type: ignore[return-value]


def run(args: argparse.Namespace) -> int:
    from ..core.fit import albedo_table, fit_file, published_scores
    from .common import find_model

    model = find_model(args.model)
    fixed = parse_params(model, args.param)
    if args.save_preset:
        from ..app.presets import check_can_save  # plain Python, no Textual

        check_can_save(args.save_preset)  # a bad name or place fails now, not after the fit
        if not model.rgb and not args.mean:
            raise UsageError(f"--save-preset: a preset holds one parameter set and {model.name} "
                             "is fitted per channel: add --mean (or fit an RGB model, e.g. gltf)")
    data, result = fit_file(args.file, args.model, stride=args.stride, mean=args.mean,
                            fixed=fixed)
    albedo = albedo_table(data, result)
    published = published_scores(data, args.stride)
    saved = save_comparison(args.save_preset, data.path, result) if args.save_preset else None
    if args.json:
        doc = {
            "file": data.path,
            "model": result.model.name,
            "objective": OBJECTIVE,
            "samples": result.n_samples,
            "stride": list(args.stride),
            "evaluations": result.evaluations,
            "seconds": round(result.seconds, 3),
            "residual": result.residual,
            "fits": [{"channel": c, "params": json_params(p)}
                     for c, p in zip(result.channels, result.params, strict=True)],
            "albedo": albedo,
            "invalid_bins": list(data.n_invalid),
        }
        if published:
            doc["published"] = published
        if saved:
            doc["preset"] = str(saved)
        print(json.dumps(doc, indent=2, allow_nan=False))
        return 0
    print(f"# fit {result.model.name} to {data.path}")
    print(f"# {result.n_samples} samples, {result.evaluations} evaluations, "
          f"{result.seconds:.1f} s; objective: {OBJECTIVE}")
    for c, p in zip(result.channels, result.params, strict=True):
        print(f"{c:>4}  {fmt_params(p)}")
        print(f"      as options: {' '.join(f'-p {k}={fmt(v)}' for k, v in p.items())}")
    print(f"residual {fmt(result.residual)}")
    if published:
        print(f"published fits of {published['material']}, same objective: "
              f"abc residual {fmt(published['abc'])} (Löw et al. 2012), "
              f"sgd residual {fmt(published['sgd'])} (Bagher et al. 2012)")
    print(f"{'theta_i':>7}  {'albedo data (R,G,B)':>26}  {'albedo fit (R,G,B)':>26}")
    for row in albedo:
        print(f"{fmt(row['theta_i']):>7}  {fmt(tuple(row['data'])):>26}  "
              f"{fmt(tuple(row['fit'])):>26}")
    if saved:
        print(f"saved {saved}: tuibrdf view --preset {args.save_preset}")
    return 0


def save_comparison(name: str, path: str, result):
    """Preset ``name``: A the measured file (absolute path), B the fitted model, θi 45°."""
    import os

    from ..app.presets import save_preset
    from ..app.state import Side, ViewerState

    sides = [Side.of("merl", {"file": os.path.abspath(path)}),
             Side.of(result.model.name, result.params[0])]
    return save_preset(ViewerState(sides=sides, theta_i=45.0), name)
