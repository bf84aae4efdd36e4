"""Command line: ``main(argv=None) -> int``.  Imports the Textual app only to open it."""

from __future__ import annotations

import argparse


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="tuibrdf", description="A terminal BRDF viewer.")
    parser.parse_args(argv)
    return 0
