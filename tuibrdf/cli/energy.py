"""``tuibrdf energy``: the directional-albedo table E(μ, p) for multiple-scattering
compensation, with error estimates, as CSV, JSON, ``.npz`` or a C header.

``E(μ, p)`` is the directional albedo at μ = cos θi over a grid of one parameter ``p``
(``--param``, ``--range LO:HI``, ``--n``; linear, or geometric with ``--log-param``) and of μ
(``--mu-n`` values from 0 to 1); both grids include both ends.  Every entry carries the
quadrature's error estimate; ``E_avg(p) = 2∫₀¹ E(μ) μ dμ`` carries its own.  Kulla & Conty's
compensation terms ``1 − E(μ)`` and ``1 − E_avg`` are columns of the output.  The integrals are
:mod:`tuibrdf.core.sphere.energy`.

Formats (``--format``):

``csv``   one row per (p, μ): ``p, mu, E, error, 1-E, E_avg, E_avg_error, 1-E_avg`` (RGB models:
          ``E_R, E_G, E_B`` …); ``#`` comment lines first (model, parameters, error bound)
``json``  ``param``, ``values``, ``mu``, ``E`` (len(values) × len(mu)), ``error``, ``E_avg``,
          ``E_avg_error``, ``one_minus_E``, ``one_minus_E_avg``, and the model and parameters
``npz``   the same arrays in a numpy archive (``np.load``); binary: to ``--output`` or a pipe
``h``     a C header: ``static const float`` arrays of the grids and the tables, and a comment
          with the model, its parameters and the error bound
"""

from __future__ import annotations

import argparse
import sys

from tuibrdf.cli.common import (
    UsageError,
    add_phi_i,
    find_model,
    fmt_params,
    int_in,
    isatty,
    json_params,
    parse_float,
    parse_params,
)

FORMATS = ("csv", "json", "npz", "h")
#: tables with at least this many entries report their progress on stderr
PROGRESS_CELLS = 4096


def add_args(parser: argparse.ArgumentParser) -> None:
    # add_model_args without its long --param, which is the swept parameter here
    parser.add_argument("model", metavar="MODEL",
                        help="model name (see 'tuibrdf models') or a file: .brdf, .bparam, "
                             ".py, .bsdf, .binary")
    parser.add_argument("-p", dest="param", action="append", default=[], metavar="NAME=VALUE",
                        help="set another parameter (repeatable); RGB as R,G,B or one grey "
                             "value; angles in degrees; unset parameters take their defaults")
    parser.add_argument("--param", dest="sweep", required=True, metavar="NAME",
                        help="the parameter p the table runs over (a real-valued one)")
    parser.add_argument("--range", dest="range", metavar="LO:HI",
                        help="the range of p, both ends included (default: the parameter's "
                             "whole range)")
    parser.add_argument("--n", type=int_in("n", 1, 4096), default=32, metavar="N",
                        help="number of values of p (default 32)")
    parser.add_argument("--mu-n", type=int_in("mu-n", 1, 4096), default=32, metavar="M",
                        help="number of values of μ = cos θi from 0 to 1 (default 32)")
    parser.add_argument("--log-param", action="store_true",
                        help="space the values of p geometrically (the range must be above 0)")
    add_phi_i(parser)
    parser.add_argument("--format", choices=FORMATS, default="csv",
                        help="output format (default csv)")
    parser.add_argument("-o", "--output", metavar="FILE",
                        help="write to FILE instead of standard output")


def parse_range(text: str | None, p) -> tuple[float, float]:
    """``LO:HI`` → floats; the parameter's own range when ``text`` is None."""
    if text is None:
        return float(p.min), float(p.max)
    lo, sep, hi = text.partition(":")
    try:
        if not sep:
            raise ValueError
        return parse_float(lo.strip()), parse_float(hi.strip())
    except ValueError:
        raise UsageError(f"--range {text!r}: expected LO:HI, two numbers") from None


def _progress(done: int, total: int) -> None:
    if sys.stderr is None:
        return
    if isatty(sys.stderr):
        end = "\n" if done == total else ""
        print(f"\rtuibrdf energy: {done}/{total} parameter values", end=end, file=sys.stderr,
              flush=True)
    elif done == total or done % max(1, total // 10) == 0:
        print(f"tuibrdf energy: {done}/{total} parameter values", file=sys.stderr, flush=True)


def run(args: argparse.Namespace) -> int:
    from tuibrdf.core.sphere.energy import check_table, energy_table

    model = find_model(args.model)
    user = parse_params(model, args.param)
    try:
        p = model.param(args.sweep)
    except ValueError as e:
        raise UsageError(str(e)) from None
    lo, hi = parse_range(args.range, p)
    check_table(model, args.sweep, lo, hi, args.n, args.mu_n, args.log_param)
    if args.format == "npz" and args.output is None and isatty(sys.stdout):
        raise UsageError("--format npz is binary: give --output FILE or redirect the output")
    big = args.n * args.mu_n >= PROGRESS_CELLS
    table = energy_table(model, user, args.sweep, lo, hi, args.n, args.mu_n,
                         log=args.log_param, phi_i=args.phi_i,
                         progress=_progress if big else None)
    data = render(table, args.format)
    if args.output is None:
        if isinstance(data, bytes):
            sys.stdout.flush()
            sys.stdout.buffer.write(data)
        else:
            sys.stdout.write(data)
        return 0
    mode = "wb" if isinstance(data, bytes) else "w"
    with open(args.output, mode, **({} if mode == "wb" else {"encoding": "utf-8"})) as f:
        f.write(data)
    return 0


# --------------------------------------------------------------------------- writers


def render(table, fmt: str) -> str | bytes:
    """The table in format ``fmt`` (:data:`FORMATS`)."""
    return {"csv": to_csv, "json": to_json, "npz": to_npz, "h": to_header}[fmt](table)


def _channels(table) -> list[str]:
    return ["_R", "_G", "_B"] if table.rgb else [""]


def _header_lines(table) -> list[str]:
    scale = "geometric" if table.log else "linear"
    others = {k: v for k, v in table.params.items() if k != table.param}
    return [f"model: {table.model}  {fmt_params(others)}  ({table.param}: the table's axis)",
            f"E(mu, {table.param}) = directional albedo at mu = cos(theta_i); {table.param}: "
            f"{len(table.values)} values, {scale}, {table.values[0]:g} to {table.values[-1]:g};"
            f" mu: {len(table.mu)} values, 0 to 1",
            "E_avg = 2 * integral of E(mu) mu dmu over [0, 1]; Kulla-Conty terms 1-E, 1-E_avg",
            f"error bound (largest error estimate of any entry): {table.error_bound:.1e}"]


def to_csv(table) -> str:
    ch = _channels(table)
    cols = ([table.param, "mu"] + [f"E{c}" for c in ch] + [f"error{c}" for c in ch]
            + [f"1-E{c}" for c in ch] + [f"E_avg{c}" for c in ch]
            + [f"E_avg_error{c}" for c in ch] + [f"1-E_avg{c}" for c in ch])
    out = [f"# {line}" for line in _header_lines(table)]
    out.append(",".join(cols))

    def row(x) -> list[str]:
        return [repr(float(v)) for v in (x.tolist() if table.rgb else [float(x)])]

    for i, v in enumerate(table.values.tolist()):
        for j, m in enumerate(table.mu.tolist()):
            out.append(",".join([repr(float(v)), repr(float(m))] + row(table.E[i, j])
                                + row(table.error[i, j]) + row(table.one_minus_E[i, j])
                                + row(table.E_avg[i]) + row(table.E_avg_error[i])
                                + row(table.one_minus_E_avg[i])))
    return "\n".join(out) + "\n"


def to_json(table) -> str:
    import json

    doc = {"model": table.model, "params": json_params(table.params), "param": table.param,
           "log_param": table.log, "rgb": table.rgb,
           "values": table.values.tolist(), "mu": table.mu.tolist(), "E": table.E.tolist(),
           "error": table.error.tolist(), "E_avg": table.E_avg.tolist(),
           "E_avg_error": table.E_avg_error.tolist(),
           "one_minus_E": table.one_minus_E.tolist(),
           "one_minus_E_avg": table.one_minus_E_avg.tolist(),
           "error_bound": table.error_bound}
    return json.dumps(doc, indent=1, allow_nan=False) + "\n"


def to_npz(table) -> bytes:
    import io

    import numpy as np

    buf = io.BytesIO()
    np.savez(buf, values=table.values, mu=table.mu, E=table.E, error=table.error,
             E_avg=table.E_avg, E_avg_error=table.E_avg_error,
             one_minus_E=table.one_minus_E, one_minus_E_avg=table.one_minus_E_avg,
             param=np.array(table.param), model=np.array(table.model),
             params=np.array(fmt_params(table.params)))
    return buf.getvalue()


def _c_ident(text: str) -> str:
    import re

    s = re.sub(r"[^0-9A-Za-z_]", "_", text)
    return s if s and not s[0].isdigit() else f"_{s}"


def _c_array(name: str, a, dims: list[int]) -> str:
    """``static const float NAME[d0][d1]… = {…};`` with 6 numbers a line (%.9g: a float
    round-trips)."""
    import numpy as np

    flat = np.asarray(a, dtype=float).ravel().tolist()
    nums = [f"{v:.9g}f" if np.isfinite(v) else "0.0f" for v in flat]
    nums = [n if any(c in n for c in ".en") else n.replace("f", ".0f") for n in nums]
    lines = [", ".join(nums[k:k + 6]) for k in range(0, len(nums), 6)]
    shape = "".join(f"[{d}]" for d in dims)
    return f"static const float {name}{shape} = {{\n    " + ",\n    ".join(lines) + "\n};\n"


def to_header(table) -> str:
    base = _c_ident(f"{table.model.rsplit('/', 1)[-1].rsplit('.', 1)[0]}_{table.param}")
    base = base.lower()
    P, M = len(table.values), len(table.mu)
    C = [3] if table.rgb else []
    guard = f"TUIBRDF_ENERGY_{base.upper()}_H"
    comment = "\n".join(f" * {line.replace('*/', '* /')}" for line in _header_lines(table))
    parts = [f"/*\n * Generated by tuibrdf energy.\n{comment}\n"
             f" * Layout: {base}_E[i][j] is E at {table.param} = {base}_{_c_ident(table.param)}"
             f"[i], mu = {base}_mu[j]" + ("; last index R, G, B" if table.rgb else "") +
             "\n */\n", f"#ifndef {guard}\n#define {guard}\n\n",
             f"#define {base.upper()}_N {P}\n#define {base.upper()}_MU_N {M}\n\n",
             _c_array(f"{base}_{_c_ident(table.param)}", table.values, [P]),
             _c_array(f"{base}_mu", table.mu, [M]),
             _c_array(f"{base}_E", table.E, [P, M] + C),
             _c_array(f"{base}_E_error", table.error, [P, M] + C),
             _c_array(f"{base}_E_avg", table.E_avg, [P] + C),
             _c_array(f"{base}_E_avg_error", table.E_avg_error, [P] + C),
             f"\n#endif /* {guard} */\n"]
    return "".join(parts)
