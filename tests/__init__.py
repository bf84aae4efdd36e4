"""The tests mirror the package: tests/core/brdf/test_fresnel.py beside tuibrdf/core/brdf/."""

from pathlib import Path

#: the repository
ROOT = Path(__file__).resolve().parents[1]
#: files the tests read (BRDF Explorer examples)
DATA_DIR = Path(__file__).resolve().parent / "data"
