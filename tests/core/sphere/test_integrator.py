"""The albedo rule's bookkeeping (``core.sphere.integrator``): the tables and vectorised steps that
replace straightforward loops must give the same numbers as those loops, written here from
their definitions (bit for bit where the order of the floating-point operations is the same;
the albedo itself is compared bit for bit against the previous code by
``scripts/bench_accuracy.py``'s values, docs/reference/accuracy.md)."""

import math

import numpy as np
import pytest

from tuibrdf.core.sphere import integrator
from tuibrdf.core.sphere.integrator import adaptive, rules


def test_one_minus_tables_are_one_minus_the_nodes():
    # 1 − x of the K15 and K7 nodes, element by element (the rule's distance to a panel's end)
    for x, table in ((rules.X15, rules._ONE_MINUS[15]), (rules.X7, rules._ONE_MINUS[7])):
        assert table.tolist() == [1.0 - float(t) for t in x]
        assert not table.flags.writeable


def _panels_by_loop(vals, brk, rmax):
    """Initial panels level by level: a breakpoint (cut at ρmax) makes a panel from the last
    panel's end when it passes it; ``end``: a radial break, or ρmax reached."""
    m, n = vals.shape
    lo, hi, node, end = [], [], [], []
    for level in range(m + 1):
        for j in range(n):
            prev = 0.0
            for k in range(level):  # the end of the last panel before this level
                prev = max(prev, min(float(vals[k, j]), float(rmax[j])))
            e = float(rmax[j]) if level == m else min(float(vals[level, j]), float(rmax[j]))
            if e > prev:
                lo.append(prev)
                hi.append(e)
                node.append(j)
                end.append(level == m or e >= rmax[j] or bool(brk is not None and brk[level, j]))
    return lo, hi, node, end


@pytest.mark.parametrize("with_breaks", [False, True])
def test_initial_panels_match_the_loop(with_breaks):
    rng = np.random.default_rng(7)
    n = 40
    rmax = rng.uniform(0.0, 1.6, n)
    rmax[:3] = 0.0  # nodes without a domain (the far side at θi = 90°)
    grading = np.array([0.01, 0.04, 0.16, 0.64])
    if with_breaks:
        extra = rng.uniform(0.0, 1.0, (2, n))
        extra[0, 5:8] = 0.16  # a break on a grading end: a repeat makes no panel
        vals = np.sort(np.vstack([np.repeat(grading[:, None], n, axis=1), extra]), axis=0)
        brk = rng.random(vals.shape) < 0.3
    else:
        vals, brk = grading[:, None], None
    lo, hi, node, end = adaptive._initial_panels(vals, brk, rmax)
    want = _panels_by_loop(np.broadcast_to(vals, (len(vals), n)), brk, rmax)
    assert lo.tolist() == want[0]
    assert hi.tolist() == want[1]
    assert node.tolist() == want[2]
    assert end.tolist() == want[3]


def test_rule_rgb_is_the_weighted_sum_per_channel():
    # K = half·Σ wk g and G = half·Σ wg g, per channel, the terms added in node order (the
    # order einsum uses over "pnc": the same bits); fsum for the correctly rounded sums
    rng = np.random.default_rng(3)
    g = rng.standard_normal((25, 15, 3)) * 10.0 ** rng.uniform(-6, 6, (25, 15, 3))
    half = rng.uniform(0.01, 1.0, 25)
    k, e = rules._rule(g, half)
    k_3d = np.einsum("pnc,n->pc", g, rules.WK15) * half[:, None]
    g_3d = np.einsum("pnc,n->pc", g, rules.WG15) * half[:, None]
    assert np.array_equal(k, k_3d)
    assert np.array_equal(e, np.abs(k_3d - g_3d))
    for p in range(25):
        for c in range(3):
            terms = g[p, :, c] * rules.WK15
            seq = 0.0
            for t in terms:
                seq += t
            assert k[p, c] == seq * half[p]
            scale = math.fsum(abs(t) for t in terms) * half[p]
            assert abs(k[p, c] - math.fsum(terms) * half[p]) <= 1e-14 * scale
    # K7/G3 and one channel: the same sums
    g7 = g[:, :7, :1]
    k7, _ = rules._rule(g7, half, rules.WK7, rules.WG7)
    for p in range(25):
        seq = 0.0
        for t in g7[p, :, 0] * rules.WK7:
            seq += t
        assert k7[p, 0] == seq * half[p]


def test_sum_by_rgb_adds_rows_in_order():
    rng = np.random.default_rng(5)
    x = rng.standard_normal((200, 3)) * 10.0 ** rng.uniform(-8, 8, (200, 3))
    idx = rng.integers(0, 6, 200)
    got = rules._sum_by(idx, x, 8)  # groups 6 and 7 are empty: 0
    want = np.zeros((8, 3))
    for i, row in zip(idx, x, strict=True):
        want[i] += row
    assert np.array_equal(got, want)


def test_count_is_bincount():
    idx = np.array([0, 2, 2, 1, 2])
    assert rules._count(idx, 4).tolist() == [1, 1, 3, 0]
    assert rules._count(np.zeros(7, dtype=int), 1).tolist() == [7]


def test_cases_frame_vectors():
    # u = (cos φi, sin φi, 0) toward the light, v = N × u = (−sin φi, cos φi, 0)
    phi = np.array([0.0, 0.7, 2.0, math.pi])
    sp, cp = np.sin(phi), np.cos(phi)
    c = integrator.cases(sp, cp, sp, cp)
    for i in range(len(phi)):
        assert c.u[i].tolist() == [cp[i], sp[i], 0.0]
        assert c.v[i].tolist() == [-sp[i], cp[i], 0.0]
