"""``tuibrdf models``: every model, its parameters, ranges, defaults, units, constraints.

Generated from the declarations only (:class:`~tuibrdf.core.params.Model`), in registry order,
so the listing is deterministic and a new model appears without touching this file.
"""

from __future__ import annotations

import argparse

from tuibrdf.cli.common import TYPE_CHECKING, print_json
from tuibrdf.core.conventions import fmt_number

if TYPE_CHECKING:
    from typing import Any

    from tuibrdf.core.params import Model, Param

COLUMNS = ("name", "symbol", "range", "default", "unit", "meaning")


def add_args(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("names", nargs="*", metavar="MODEL",
                        help="only these models (default: all)")
    parser.add_argument("--json", action="store_true", help="print JSON instead of text")


def param_doc(p: Param) -> dict[str, Any]:
    d: dict[str, Any] = {
        "name": p.name, "symbol": p.symbol, "kind": p.kind, "default": p.default,
        "unit": p.unit, "doc": p.doc, "range": p.range_text(),
    }
    if p.kind in ("float", "rgb"):
        d.update(min=p.min, max=p.max, step=p.step)
    if p.kind == "choice":
        d["choices"] = list(p.choices)
    if isinstance(p.default, tuple):
        d["default"] = list(p.default)
    return d


def model_doc(m: Model) -> dict[str, Any]:
    return {
        "name": m.name, "title": m.title, "summary": m.summary,
        "rgb": m.rgb, "reciprocal": m.reciprocal, "horizon": m.horizon,
        "constraints": [c.text for c in m.constraints],
        "notes": list(m.notes),
        "params": [param_doc(p) for p in m.params],
    }


def model_text(m: Model) -> list[str]:
    kind = "RGB" if m.rgb else "scalar"
    recip = "reciprocal" if m.reciprocal else "not reciprocal"
    lines = [f"{m.name} — {m.title}"]
    if m.summary:
        lines.append(f"  {m.summary}")
    lines.append(f"  {kind}, {recip}" + (f"; horizon: {m.horizon}" if m.horizon else ""))
    rows = [COLUMNS] + [(p.name, p.symbol, p.range_text(), fmt_number(p.default),
                         "°" if p.unit == "deg" else p.unit, p.doc) for p in m.params]
    widths = [max(len(r[i]) for r in rows) for i in range(len(COLUMNS))]
    if m.params:
        for r in rows:
            cells = [c.ljust(w) for c, w in zip(r[:-1], widths[:-1], strict=True)] + [r[-1]]
            lines.append(("    " + "  ".join(cells)).rstrip())
    else:
        lines.append("    (no parameters)")
    for c in m.constraints:
        lines.append(f"  constraint: {c.text}")
    for n in m.notes:
        lines.append(f"  note: {n}")
    return lines


def run(args: argparse.Namespace) -> int:
    from tuibrdf.cli.common import find_model
    from tuibrdf.core.registry import MODELS

    models = [find_model(n) for n in args.names] if args.names else list(MODELS.values())
    if args.json:
        print_json([model_doc(m) for m in models], ascii=False)
        return 0
    from tuibrdf.cli.text import one_line  # a file's text (titles, notes) is printed inert

    print("\n\n".join("\n".join(one_line(x) for x in model_text(m)) for m in models))
    return 0
