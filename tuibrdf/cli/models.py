"""``tuibrdf models``: every model, its parameters, ranges, defaults, units."""

from __future__ import annotations

import argparse

from ..core.models import MODELS


def add_args(parser: argparse.ArgumentParser) -> None:
    pass


def run(args: argparse.Namespace) -> int:
    for m in MODELS.values():
        print(f"{m.name}  {m.summary}")
        for p in m.params:
            print(f"    {p.name:<12} {p.range_text():<28} default {p.default}  {p.doc}")
    return 0
