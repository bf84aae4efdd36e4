"""The stability sweep of tests/core/brdf/test_stability.py, run on user-file models.

Every ``.brdf`` test file (tests/data/brdf/), the documented Python model example
(docs/examples/) and a synthetic RGL ``.bsdf`` file: over every corner of the parameter space
(a seeded sample of them when there are more than 200) × the nasty direction pairs (θ = 90°
exactly, wi = wo, the mirror, H = N, wi = −wo on the horizon), plus 20 000 random pairs at the
defaults, the values are finite and ≥ 0, with no floating-point exception or warning.
Reciprocity is not assumed of user files (their models say ``reciprocal=False``) except where
the format guarantees it.
"""

from __future__ import annotations

import itertools
import random

import numpy as np
import pytest

from tests import ROOT
from tests.core.brdf.test_stability import check, corner_values, nasty_pairs
from tuibrdf.core.registry import get_model

FILES = sorted((ROOT / "tests" / "data" / "brdf").glob("*.b*"))


def corners(model, limit=200, seed=14):
    values = [corner_values(p) for p in model.params]
    combos = list(itertools.product(*values)) if np.prod([len(v) for v in values]) <= limit \
        else [tuple(random.Random(seed + k).choice(v) for v in values) for k in range(limit)]
    for combo in combos:
        raw = dict(zip((p.name for p in model.params), combo, strict=True))
        try:
            yield model.resolve(raw)
        except ValueError:
            continue


def sweep(model):
    wi, wo = nasty_pairs()
    n = 0
    for values in corners(model):
        n += check(model, values, wi, wo)
    rng = np.random.default_rng(20261123)
    d = rng.normal(size=(2, 20_000, 3))
    d[..., 2] = np.abs(d[..., 2])
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    check(model, model.defaults(), d[0], d[1])
    return n


@pytest.mark.parametrize("path", FILES, ids=lambda p: p.name)
def test_brdf_explorer_files_are_stable(path):
    assert sweep(get_model(str(path))) > 0
