"""``tuibrdf fit FILE --model NAME [--json]``: fit an analytic model to a MERL file.

Prints the fitted parameters (one set per channel for a scalar model, one for an RGB model),
the residual (RMS of ``log(1 + f·cos θi·cos θo)`` differences, see :mod:`tuibrdf.core.fit`),
and the albedo of data and fit at θi = 0, 30, 60° with their ratio; then a verdict: fitted
parameters that ended at a bound of their range, and a poor fit (a fit / data albedo ratio
outside 1/1.25–1.25×).  Progress goes to stderr while it runs.  A file named after a MERL material
(``gold-metallic-paint.binary``) also gets the residuals of the published ABC and SGD fits of
that material (models ``abc``, ``sgd``) on the same objective, for comparison.  A missing or
malformed file, an unknown model or one without continuous parameters: one line on stderr,
exit 2.
"""

from __future__ import annotations

import argparse

from tuibrdf.cli.common import UsageError, fmt_params, json_params, parse_params, print_json
from tuibrdf.core.conventions import fmt_number

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
    from tuibrdf.cli.common import parse_int

    try:
        vals = tuple(parse_int(v) for v in text.split(","))
    except ValueError:
        vals = ()
    if len(vals) != 3 or not all(1 <= v <= 45 for v in vals):
        raise argparse.ArgumentTypeError(f"stride = {text!r} is invalid: expected three "
                                         "integers in [1, 45], e.g. 1,3,15")
    return vals  # type: ignore[return-value]


def run(args: argparse.Namespace) -> int:
    import sys
    import time

    from tuibrdf.cli.common import find_model
    from tuibrdf.core.fit import albedo_ratio, albedo_table, at_bounds, fit_file, published_scores

    model = find_model(args.model)
    fixed = parse_params(model, args.param)
    if args.save_preset:
        from tuibrdf.state.presets import check_can_save  # plain Python, no Textual

        check_can_save(args.save_preset)  # a bad name or place fails now, not after the fit
        if not model.rgb and not args.mean:
            raise UsageError(f"--save-preset: a preset holds one parameter set and {model.name} "
                             "is fitted per channel: add --mean (or fit an RGB model, e.g. gltf)")
    start = time.perf_counter()

    def progress(channel: str, i: int, n: int) -> None:
        # stderr: stdout stays the result (and valid JSON with --json)
        what = f"channel {channel} ({i}/{n})" if n > 1 else f"{channel} channels"
        print(f"fitting {model.name}: {what} … {time.perf_counter() - start:.1f} s",
              file=sys.stderr, flush=True)

    data, result = fit_file(args.file, args.model, stride=args.stride, mean=args.mean,
                            fixed=fixed, progress=progress)
    print(f"computing albedos … {time.perf_counter() - start:.1f} s", file=sys.stderr,
          flush=True)
    albedo = albedo_table(data, result)
    bounds = at_bounds(result, fixed)
    ratio = albedo_ratio(albedo)
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
            "at_bound": bounds,
            "albedo_ratio": ratio,
            "invalid_bins": list(data.n_invalid),
        }
        if published:
            doc["published"] = published
        if saved:
            doc["preset"] = str(saved)
        print_json(doc)
        return 0
    print(f"# fit {result.model.name} to {data.path}")
    print(f"# {result.n_samples} samples, {result.evaluations} evaluations, "
          f"{result.seconds:.1f} s; objective: {OBJECTIVE}")
    for c, p in zip(result.channels, result.params, strict=True):
        print(f"{c:>4}  {fmt_params(p)}")
        print(f"      as options: {' '.join(f'-p {k}={fmt_number(v)}' for k, v in p.items())}")
    print(f"residual {fmt_number(result.residual)}")
    if published:
        print(f"published fits of {published['material']}, same objective: "
              f"abc residual {fmt_number(published['abc'])} (Löw et al. 2012), "
              f"sgd residual {fmt_number(published['sgd'])} (Bagher et al. 2012)")
    print(albedo_lines(albedo))
    for line in judgement(bounds, ratio):
        print(line)
    if saved:
        print(f"saved {saved}: tuibrdf view --preset {args.save_preset}")
    return 0


def albedo_lines(rows: list[dict]) -> str:
    """The albedo table, one column per channel, decimal points aligned."""
    cols = ("R", "G", "B")
    head = (f"{'theta_i':>7}  {'albedo data':^26}  {'albedo fit':^26}  fit/data\n"
            f"{'':>7}  " + "  ".join(" ".join(f"{c:>8}" for c in cols) for _ in range(2)))
    lines = [head]
    for row in rows:
        data = " ".join(f"{v:8.4f}" for v in row["data"])
        fitted = " ".join(f"{v:8.4f}" for v in row["fit"])
        ratios = [f / d for d, f in zip(row["data"], row["fit"], strict=True) if d > 0]
        worst = max(ratios, key=lambda r: abs(r - 1)) if ratios else float("nan")
        lines.append(f"{row['theta_i']:>6g}°  {data}  {fitted}  {worst:8.2f}×")
    return "\n".join(lines)


def judgement(bounds: list[dict], ratio: dict) -> list[str]:
    """The verdict lines: parameters stuck at a bound, a poor albedo match, or "fit ok"."""
    from tuibrdf.core.fit import POOR_ALBEDO_RATIO

    out = []
    for b in bounds:
        out.append(f"warning: {b['param']} at its {b['bound']}imum {fmt_number(b['value'])} "
                   f"({', '.join(b['channels'])}): the model wants a value past its range")
    if ratio["poor"]:
        out.append(f"poor fit: albedo of the fit is {ratio['ratio']:.2f}× the data's "
                   f"(θi {fmt_number(ratio['theta_i'])}°, channel {ratio['channel']}; flagged "
                   f"outside 1/{POOR_ALBEDO_RATIO:g}–{POOR_ALBEDO_RATIO:g}×): try another model")
    if not out:
        out.append(f"fit ok: no parameter at a bound, albedos within {POOR_ALBEDO_RATIO:g}× of "
                   "the data's")
    return out


def save_comparison(name: str, path: str, result):
    """Preset ``name``: A the measured file (absolute path), B the fitted model, θi 45°."""
    import os

    from tuibrdf.state.presets import save_preset
    from tuibrdf.state.viewer import Side, ViewerState

    sides = [Side.of("merl", {"file": os.path.abspath(path)}),
             Side.of(result.model.name, result.params[0])]
    return save_preset(ViewerState(sides=sides, theta_i=45.0), name)
