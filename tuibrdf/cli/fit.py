"""``tuibrdf fit FILE [FILE ...] --model NAME [--json] [--jobs N] [--compare]``: fit an analytic
model to a measured file: MERL ``.binary`` or RGL ``.bsdf`` (its values at the MERL sample
positions, :mod:`tuibrdf.core.fit`).

Prints the fitted parameters (one set per channel for a scalar model, one for an RGB model),
the residual (RMS of ``log(1 + f·cos θi·cos θo)`` differences, see :mod:`tuibrdf.core.fit`),
and the albedo of data and fit at θi = 0, 30, 60° with their ratio; then a verdict: fitted
parameters that ended at a bound of their range, and a poor fit (a fit / data albedo ratio
outside 1/1.25–1.25×, or ``rel_l2`` of the fit against the data above 0.5 at θi = 0, 30 or 60°
in some channel: :mod:`tuibrdf.core.sphere.compare`).  Progress goes to stderr while it runs.
Several files: one compact JSON object per line and per file, in the order given, fitted by
``--jobs N`` processes (:class:`concurrent.futures.ProcessPoolExecutor`), on a terminal a
progress line on stderr rewritten as each ends; a file that cannot be fitted is a line
``{"file": …, "error": …}``, and then one line on stderr says how many failed, exit status 2.
``--compare`` opens the viewer on data (A) against the fit (B), the numbers of ``tuibrdf
compare`` in its status line (one parameter set: an RGB model or ``--mean``).  A file named
after a MERL material (``gold-metallic-paint.binary``) also gets the residuals of the
published ABC and SGD fits of that material (models ``abc``, ``sgd``) on the same objective,
for comparison.  A missing or malformed file, an unknown model or one without continuous
parameters: one line on stderr, exit 2.
"""

from __future__ import annotations

import argparse

from tuibrdf.cli.common import (
    UsageError,
    fmt_params,
    isatty,
    json_params,
    parse_params,
    print_json,
)
from tuibrdf.core.conventions import fmt_number

#: ``tuibrdf.core.fit.STRIDE``, repeated so that ``--help`` does not import numpy (a test
#: checks that they agree)
STRIDE = (1, 3, 15)

OBJECTIVE = "rms of log(1 + f*cos(theta_i)*cos(theta_o)) - log(1 + f_data*cos*cos) over bins"


def add_args(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("file", metavar="FILE", nargs="+",
                        help="measured file: MERL .binary or RGL .bsdf (several: one JSON line "
                             "each)")
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
    parser.add_argument("--jobs", type=jobs_type, default=1, metavar="N",
                        help="fit several files in N processes at once (default 1)")
    parser.add_argument("--compare", action="store_true",
                        help="then open the viewer: data (A) against the fit (B), with rel_l2 "
                             "(needs one parameter set: an RGB model, or --mean)")


def jobs_type(text: str) -> int:
    from tuibrdf.cli.common import int_in

    return int_in("jobs", 1, 64)(text)


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
    from tuibrdf.cli.common import find_model

    model = find_model(args.model)
    fixed = parse_params(model, args.param)
    one_set = model.rgb or args.mean
    for flag, on in (("--save-preset", args.save_preset), ("--compare", args.compare)):
        if on and len(args.file) > 1:
            raise UsageError(f"{flag} takes one FILE ({len(args.file)} given)")
        if on and not one_set:
            raise UsageError(f"{flag}: one parameter set is needed and {model.name} is fitted "
                             "per channel: add --mean (or fit an RGB model, e.g. gltf)")
    if args.save_preset:
        from tuibrdf.state.presets import check_can_save  # plain Python, no Textual

        check_can_save(args.save_preset)  # a bad name or place fails now, not after the fit
    if args.compare:
        from tuibrdf.cli.view import check_terminal

        check_terminal()  # no terminal: fail now, not after the fit
    if len(args.file) > 1 or args.jobs > 1:
        return run_many(args, fixed)
    return run_one(args, model, fixed)


def fit_report(path: str, model_name: str, fixed: dict, stride, mean: bool, progress=None,
               start: float = 0.0) -> tuple[dict, object, object]:
    """Fit ``path`` and every number the report holds: ``(doc, data, result)``, ``doc`` the
    JSON document (without the preset)."""
    import sys
    import time

    from tuibrdf.core.fit import (
        albedo_ratio,
        albedo_table,
        at_bounds,
        fit_file,
        published_scores,
        rel_l2_table,
        worst_rel_l2,
    )

    data, result = fit_file(path, model_name, stride=stride, mean=mean, fixed=fixed,
                            progress=progress)
    if progress is not None:
        print(f"computing albedos and rel_l2 … {time.perf_counter() - start:.1f} s",
              file=sys.stderr, flush=True)
    albedo = albedo_table(data, result)
    l2 = rel_l2_table(data, result)
    doc = {
        "file": data.path,
        "model": result.model.name,
        "objective": OBJECTIVE,
        "samples": result.n_samples,
        "stride": list(stride),
        "evaluations": result.evaluations,
        "seconds": round(result.seconds, 3),
        "residual": result.residual,
        "fits": [{"channel": c, "params": json_params(p)}
                 for c, p in zip(result.channels, result.params, strict=True)],
        "albedo": albedo,
        "rel_l2": l2,
        "at_bound": at_bounds(result, fixed),
        "albedo_ratio": albedo_ratio(albedo),
        "worst_rel_l2": worst_rel_l2(l2),
        "invalid_bins": list(data.n_invalid),
    }
    published = published_scores(data, stride)
    if published:
        doc["published"] = published
    return doc, data, result


def _fit_job(path: str, model_name: str, fixed: dict, stride, mean: bool) -> dict:
    """One file of ``run_many``, in a worker process: its document, or ``{"file", "error"}``
    (a bad file is one line, as everywhere)."""
    try:
        return fit_report(path, model_name, fixed, stride, mean)[0]
    except (ValueError, OSError, UsageError) as e:
        return {"file": path, "error": str(e)}


def run_many(args: argparse.Namespace, fixed: dict) -> int:
    """Several files: one JSON line each, in the order given, ``--jobs`` processes."""
    import json
    import sys
    import time
    from concurrent.futures import ProcessPoolExecutor

    start = time.perf_counter()
    n, done, failed = len(args.file), 0, 0
    live = isatty(sys.stderr)  # elsewhere each file's line on stdout is the progress
    with ProcessPoolExecutor(max_workers=min(args.jobs, n)) as pool:
        futures = [pool.submit(_fit_job, f, args.model, fixed, args.stride, args.mean)
                   for f in args.file]
        for fut in futures:  # in order: the output does not depend on which ends first
            doc = fut.result()
            done += 1
            failed += "error" in doc
            print(json.dumps(doc, ensure_ascii=True, allow_nan=False), flush=True)
            if live:  # one line, rewritten as each file ends
                print(f"\rfitted {done}/{n} files ({failed} failed) … "
                      f"{time.perf_counter() - start:.1f} s", end="\n" if done == n else "",
                      file=sys.stderr, flush=True)
    if failed:  # one line says so, as for every error (each file's line says why)
        raise UsageError(f"{failed} of {n} files could not be fitted: see their \"error\" "
                         "lines")
    return 0


def run_one(args: argparse.Namespace, model, fixed: dict) -> int:
    import sys
    import time

    start = time.perf_counter()

    def progress(channel: str, i: int, n: int) -> None:
        # stderr: stdout stays the result (and valid JSON with --json)
        what = f"channel {channel} ({i}/{n})" if n > 1 else f"{channel} channels"
        print(f"fitting {model.name}: {what} … {time.perf_counter() - start:.1f} s",
              file=sys.stderr, flush=True)

    doc, data, result = fit_report(args.file[0], args.model, fixed, args.stride, args.mean,
                                   progress, start)
    saved = save_comparison(args.save_preset, data, result) if args.save_preset else None
    if args.json:
        if saved:
            doc["preset"] = str(saved)
        print_json(doc)
    else:
        print_text(doc, result, saved, args.save_preset)
    if args.compare:
        return open_comparison(data, result)
    return 0


def print_text(doc: dict, result, saved, preset_name) -> None:
    print(f"# fit {result.model.name} to {doc['file']}")
    print(f"# {result.n_samples} samples, {result.evaluations} evaluations, "
          f"{result.seconds:.1f} s; objective: {OBJECTIVE}")
    for c, p in zip(result.channels, result.params, strict=True):
        print(f"{c:>4}  {fmt_params(p)}")
        print(f"      as options: {' '.join(f'-p {k}={fmt_number(v)}' for k, v in p.items())}")
    print(f"residual {fmt_number(result.residual)}")
    published = doc.get("published")
    if published:
        print(f"published fits of {published['material']}, same objective: "
              f"abc residual {fmt_number(published['abc'])} (Löw et al. 2012), "
              f"sgd residual {fmt_number(published['sgd'])} (Bagher et al. 2012)")
    print(albedo_lines(doc["albedo"], doc["rel_l2"]))
    for line in judgement(doc["at_bound"], doc["albedo_ratio"], doc["worst_rel_l2"]):
        print(line)
    if saved:
        print(f"saved {saved}: tuibrdf view --preset {preset_name}")


def open_comparison(data, result) -> int:
    """The viewer on data (A, the reference) against the fit (B), θi 45°."""
    from tuibrdf.cli.view import open_viewer

    return open_viewer(comparison_state(data, result), None)


def comparison_state(data, result):
    """The viewer's state of data (A) against the fit (B), θi 45°."""
    from tuibrdf.core.fit import measured
    from tuibrdf.core.material import Material
    from tuibrdf.state.viewer import Side, ViewerState

    sides = [Side(Material(*measured(data))),
             Side(Material(result.model, result.params[0]))]
    return ViewerState(sides=sides, theta_i=45.0)


def albedo_lines(rows: list[dict], l2: list[dict] | None = None) -> str:
    """The albedo table, one column per channel, decimal points aligned; with ``l2``
    (:func:`tuibrdf.core.fit.rel_l2_table`) the worst channel's rel_l2 last."""
    cols = ("R", "G", "B")
    head = (f"{'theta_i':>7}  {'albedo data':^26}  {'albedo fit':^26}  fit/data"
            f"{'    rel_l2' if l2 else ''}\n"
            f"{'':>7}  " + "  ".join(" ".join(f"{c:>8}" for c in cols) for _ in range(2)))
    lines = [head]
    for i, row in enumerate(rows):
        data = " ".join(f"{v:8.4f}" for v in row["data"])
        fitted = " ".join(f"{v:8.4f}" for v in row["fit"])
        ratios = [f / d for d, f in zip(row["data"], row["fit"], strict=True) if d > 0]
        worst = max(ratios, key=lambda r: abs(r - 1)) if ratios else float("nan")
        tail = ""
        if l2:
            vals = [v for v in l2[i]["rel_l2"] if v is not None]
            tail = f"  {max(vals):8.3g}" if vals else "         —"
        lines.append(f"{row['theta_i']:>6g}°  {data}  {fitted}  {worst:8.2f}×{tail}")
    return "\n".join(lines)


def judgement(bounds: list[dict], ratio: dict, l2: dict | None = None) -> list[str]:
    """The verdict lines: parameters stuck at a bound, a poor albedo match, a large rel_l2
    (:func:`tuibrdf.core.fit.worst_rel_l2`), or "fit ok"."""
    from tuibrdf.core.fit import POOR_ALBEDO_RATIO, POOR_REL_L2

    out = []
    for b in bounds:
        out.append(f"warning: {b['param']} at its {b['bound']}imum {fmt_number(b['value'])} "
                   f"({', '.join(b['channels'])}): the model wants a value past its range")
    if ratio["poor"]:
        out.append(f"poor fit: albedo of the fit is {ratio['ratio']:.2f}× the data's "
                   f"(θi {fmt_number(ratio['theta_i'])}°, channel {ratio['channel']}; flagged "
                   f"outside 1/{POOR_ALBEDO_RATIO:g}–{POOR_ALBEDO_RATIO:g}×): try another model")
    if l2 is not None and l2["poor"]:
        out.append(f"poor fit: rel_l2 of the fit against the data is {l2['rel_l2']:.3g} "
                   f"(θi {fmt_number(l2['theta_i'])}°, channel {l2['channel']}; flagged above "
                   f"{POOR_REL_L2:g}): try another model")
    if not out:
        out.append(f"fit ok: no parameter at a bound, albedos within {POOR_ALBEDO_RATIO:g}× of "
                   f"the data's, rel_l2 ≤ {POOR_REL_L2:g}")
    return out


def save_comparison(name: str, data, result):
    """Preset ``name``: A the measured file (absolute path), B the fitted model, θi 45°."""
    import os

    from tuibrdf.core.fit import ModelTarget
    from tuibrdf.state.presets import save_preset
    from tuibrdf.state.viewer import Side, ViewerState

    a = (Side.of(os.path.abspath(data.path)) if isinstance(data, ModelTarget)
         else Side.of("merl", {"file": os.path.abspath(data.path)}))
    sides = [a, Side.of(result.model.name, result.params[0])]
    return save_preset(ViewerState(sides=sides, theta_i=45.0), name)
