"""The hierarchical icosahedral hemisphere (SPEC §3) and adaptive refinement.

Construction
------------
Level 0 is the icosahedron with a vertex on each pole, an upper ring of five vertices at
``z = +1/√5`` (azimuths 0°, 72°, …) and a lower ring at ``z = −1/√5`` (azimuths 36°, 108°, …),
built as the exact negatives of the upper ring so that every level is centrally symmetric to the
last bit (two horizon vertices are exact antipodes, so ``wi + wo`` is exactly 0 there).
Level L+1 splits every triangle in four at its edge midpoints, pushed onto the sphere:
``10·4ᴸ + 2`` vertices and ``20·4ᴸ`` faces on the whole sphere.  New vertices are appended in
the order of their edge ``(min, max)`` vertex pair, so level-L vertex indices are a prefix of
level L+1 and the children of face ``f`` are faces ``4f … 4f+3``.

The horizon, exactly
--------------------
No great circle of the icosahedron is made of its edges, but this orientation gives one from
level 1 on: every edge of the middle band joins an upper-ring vertex (``z = +1/√5``) to a
lower-ring one (``z = −1/√5``), so its midpoint has ``z = 0`` exactly (the two z are built as
exact negatives).  At level 1 the ten band midpoints are joined by ten edges whose endpoints both
have ``z = 0``: a ring of great-circle arcs *on* the equator, and further midpoints of those
edges stay at ``z = 0``.  No face straddles the horizon, so the hemisphere (the vertices with
``z ≥ 0`` and the faces made of them) tiles the upper half-sphere exactly.  Level 0 has no
vertex on the horizon, so :func:`hemisphere` starts at level 1 (nothing is snapped or
projected).

Counts (derived by hand, tested): the equator carries ``5·2ᴸ`` vertices, the hemisphere
``5·4ᴸ + 5·2ᴸ⁻¹ + 1`` vertices and ``10·4ᴸ`` faces (L ≥ 1).

Weights
-------
Each spherical triangle's exact solid angle (Van Oosterom & Strackee 1983) is shared equally by
its three vertices, then every weight is scaled by ``1 + λ0 + λ1 z + λ2 z²`` (one λ per
hemisphere, solved from a 3×3 system) so that the rule integrates 1, cos θ and cos²θ exactly
(2π, π, 2π/3): a constant BRDF's albedo (Lambert) is exact.  The scaling differs from 1 by
O(h²) (1.4e-4 at level 6), so the rule stays second order (the error of a smooth integrand
falls ~4× per level).
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

#: Finest level :func:`hemisphere` builds: level 9 has 1.3 million hemisphere vertices and its
#: sphere ~200 MB of arrays (5.2 million faces); each level is 4× that.
MAX_LEVEL = 9
#: Finest level :func:`refine_adaptive` may reach (it only builds what it refines).
ADAPTIVE_MAX_LEVEL = 16


def _readonly(*arrays: np.ndarray) -> None:
    for a in arrays:
        a.setflags(write=False)


def _icosahedron() -> tuple[np.ndarray, np.ndarray]:
    z = 1.0 / np.sqrt(5.0)
    r = 2.0 / np.sqrt(5.0)
    k = np.arange(5)
    up = np.radians(72.0 * k)
    upper = np.stack([r * np.cos(up), r * np.sin(up), np.full(5, z)], axis=1)
    # the lower ring (azimuths 36° + 72°j) is the upper ring's antipodes, negated exactly: the
    # mesh is then centrally symmetric to the last bit at every level (−(a+b) = (−a)+(−b))
    lower = -upper[(k + 3) % 5]
    verts = np.concatenate([[[0.0, 0.0, 1.0]], upper, lower, [[0.0, 0.0, -1.0]]])
    top, u, lw, bot = 0, 1 + k, 6 + k, 11
    u1, l1 = 1 + (k + 1) % 5, 6 + (k + 1) % 5
    faces = np.concatenate(
        [
            np.stack([np.full(5, top), u, u1], axis=1),
            np.stack([u, lw, u1], axis=1),
            np.stack([u1, lw, l1], axis=1),
            np.stack([np.full(5, bot), l1, lw], axis=1),
        ]
    )
    return verts, _orient(verts, faces)


def _orient(verts: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Make every face counter-clockwise seen from outside (positive triple product)."""
    a, b, c = (verts[faces[:, i]] for i in range(3))
    flip = np.einsum("ij,ij->i", a, np.cross(b, c)) < 0
    faces = faces.copy()
    faces[flip, 1], faces[flip, 2] = faces[flip, 2], faces[flip, 1].copy()
    return faces


def _midpoints(verts: np.ndarray, edges: np.ndarray) -> np.ndarray:
    s = verts[edges[:, 0]] + verts[edges[:, 1]]  # never 0: edges join non-antipodal vertices
    m = s / np.linalg.norm(s, axis=1, keepdims=True)
    # both endpoints on the horizon → the midpoint is too (z sums to exactly 0 already; this
    # only documents the invariant)
    m[(verts[edges[:, 0], 2] == 0.0) & (verts[edges[:, 1], 2] == 0.0), 2] = 0.0
    return m


def _split(faces: np.ndarray, mid: np.ndarray) -> np.ndarray:
    """Children of each face ``(a, b, c)`` with edge-midpoint vertex ids ``mid (F, 3)`` for the
    edges ab, bc, ca; the children of face f are rows 4f … 4f+3, all counter-clockwise."""
    a, b, c = faces[:, 0], faces[:, 1], faces[:, 2]
    mab, mbc, mca = mid[:, 0], mid[:, 1], mid[:, 2]
    kids = np.stack(
        [
            np.stack([a, mab, mca], axis=1),
            np.stack([b, mbc, mab], axis=1),
            np.stack([c, mca, mbc], axis=1),
            np.stack([mab, mbc, mca], axis=1),
        ],
        axis=1,
    )
    return kids.reshape(-1, 3)


def _face_edges(faces: np.ndarray) -> np.ndarray:
    """``(F, 3, 2)`` sorted vertex pairs of the edges ab, bc, ca."""
    e = np.stack([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]], axis=1)
    return np.sort(e, axis=2)


@functools.cache
def sphere(level: int) -> tuple[np.ndarray, np.ndarray]:
    """``(vertices (10·4ᴸ+2, 3), faces (20·4ᴸ, 3))`` of the whole sphere at ``level``."""
    level = _check_level(level, 0)
    if level == 0:
        v, f = _icosahedron()
    else:
        pv, pf = sphere(level - 1)
        n = len(pv)
        e = _face_edges(pf)
        keys = e[..., 0].astype(np.int64) * n + e[..., 1]
        uniq, inv = np.unique(keys.ravel(), return_inverse=True)
        edges = np.stack([uniq // n, uniq % n], axis=1)
        v = np.concatenate([pv, _midpoints(pv, edges)])
        f = _split(pf, n + inv.reshape(-1, 3))
    _readonly(v, f)
    return v, f


def _check_level(level, lowest: int, highest: int = MAX_LEVEL) -> int:
    if int(level) != level or not lowest <= level <= highest:
        raise ValueError(f"mesh level = {level!r} is invalid: expected an integer in "
                         f"[{lowest}, {highest}]")
    return int(level)


def triangle_solid_angles(a: np.ndarray, b: np.ndarray, c: np.ndarray) -> np.ndarray:
    """Exact solid angle of spherical triangles with unit vertices (Van Oosterom & Strackee
    1983): ``tan(Ω/2) = |a·(b×c)| / (1 + a·b + b·c + c·a)``."""
    num = np.abs(np.einsum("...j,...j->...", a, np.cross(b, c)))
    den = (1.0 + np.einsum("...j,...j->...", a, b) + np.einsum("...j,...j->...", b, c)
           + np.einsum("...j,...j->...", c, a))
    return 2.0 * np.arctan2(num, den)


def vertex_weights(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Solid angle per vertex: a third of each adjacent triangle's area."""
    area = triangle_solid_angles(*(vertices[faces[:, i]] for i in range(3)))
    return np.bincount(faces.ravel(), weights=np.repeat(area / 3.0, 3), minlength=len(vertices))


#: ∫ cosᵏθ dω over the upper hemisphere, k = 0, 1, 2: 2π/(k+1).
HEMISPHERE_MOMENTS = np.array([2.0 * np.pi, np.pi, 2.0 * np.pi / 3.0])


def exact_moment_weights(z: np.ndarray, w: np.ndarray) -> np.ndarray:
    """``w·(1 + λ0 + λ1 z + λ2 z²)`` with λ chosen so that ``Σ w' zᵏ = 2π/(k+1)`` for
    k = 0, 1, 2 (a tiling of the hemisphere, ``z = cos θ`` of each vertex).

    The 3×3 system is the Gram matrix ``Σ w z^(j+k)`` (positive definite: the z values are not
    all equal on any hemisphere mesh); the λ are O(h²), so the weights stay positive.
    """
    p = np.stack([np.ones_like(z), z, z * z])  # (3, N)
    wp = p * w
    gram = np.einsum("jn,kn->jk", wp, p)
    lam = np.linalg.solve(gram, HEMISPHERE_MOMENTS - wp.sum(axis=1))
    return w * (1.0 + np.einsum("k,kn->n", lam, p))


@dataclass(frozen=True, eq=False)
class HemiMesh:
    """The upper hemisphere at one level (arrays are read-only).

    ``vertices (N, 3)`` unit vectors with ``z ≥ 0`` (horizon vertices have ``z == 0``
    exactly), ``faces (F, 3)`` indices into ``vertices``, ``weights (N,)`` solid angle per
    vertex (exact for 1, cos θ, cos²θ: :func:`exact_moment_weights`); ``sphere_index (N,)``
    the index of each vertex in :func:`sphere`.
    """

    level: int
    vertices: np.ndarray
    faces: np.ndarray
    weights: np.ndarray
    sphere_index: np.ndarray

    def integrate(self, values: np.ndarray) -> np.ndarray:
        """``∫ g dω`` from vertex values ``(N,)`` or ``(N, k)``."""
        return _weighted_sum(self.weights, values)


@functools.cache
def hemisphere(level: int) -> HemiMesh:
    """The hemisphere mesh of ``level`` (1 … :data:`MAX_LEVEL`), built once and cached."""
    level = _check_level(level, 1)
    v, f = sphere(level)
    keep = v[:, 2] >= 0.0
    idx = np.flatnonzero(keep)
    remap = np.full(len(v), -1, dtype=np.int64)
    remap[idx] = np.arange(len(idx))
    faces = remap[f[keep[f].all(axis=1)]]
    verts = v[idx]
    weights = exact_moment_weights(verts[:, 2], vertex_weights(verts, faces))
    _readonly(verts, faces, weights, idx)
    return HemiMesh(level, verts, faces, weights, idx)


def _weighted_sum(w: np.ndarray, values) -> np.ndarray:
    """``Σ w·values`` over the first axis, in numpy's own loops (``einsum``): ``tensordot``
    calls BLAS, whose thread pool hands the work to a second core and stalls on a busy
    machine."""
    v = np.asarray(values, dtype=float)
    return np.einsum("n,n...->...", w, v)


# ---------------------------------------------------------------------------------------------
# point location and interpolation


def _sphere_to_hemi(level: int) -> np.ndarray:
    m = hemisphere(level)
    remap = np.full(len(sphere(level)[0]), -1, dtype=np.int64)
    remap[m.sphere_index] = np.arange(len(m.vertices))
    return remap


@functools.cache
def _edge_normals(level: int) -> np.ndarray:
    """``(F, 3, 3)``: for each sphere face (a, b, c) the normals b×c, c×a, a×b of the planes
    through its edges; ``p·normal ≥ 0`` for all three iff p is in the triangle."""
    v, f = sphere(level)
    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    n = np.stack([np.cross(b, c), np.cross(c, a), np.cross(a, b)], axis=1)
    _readonly(n)
    return n


def _dets(v: np.ndarray, tri: np.ndarray, p: np.ndarray) -> np.ndarray:
    """``(..., 3)`` triple products det(b, c, p), det(c, a, p), det(a, b, p) for triangles
    ``tri (..., 3)`` of vertex ids: all ≥ 0 when p is inside, and proportional to p's
    barycentric coordinates in the flat triangle."""
    a, b, c, p = np.broadcast_arrays(v[tri[..., 0]], v[tri[..., 1]], v[tri[..., 2]], p)
    return np.stack(
        [
            np.einsum("...j,...j->...", p, np.cross(b, c)),
            np.einsum("...j,...j->...", p, np.cross(c, a)),
            np.einsum("...j,...j->...", p, np.cross(a, b)),
        ],
        axis=-1,
    )


def locate(mesh: HemiMesh, directions: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Containing triangle of each direction: ``(vertex ids (..., 3), barycentric (..., 3),
    inside (...))``.

    Vectorised descent of the hierarchy: the best of the 20 icosahedron faces (largest smallest
    edge test, robust to rounding on shared edges), then at each level one of the 4 children
    from the three edge planes of the centre child (inside all three: the centre; else the
    corner beyond the most violated one).  Barycentric coordinates are those of the direction's
    central projection onto the flat triangle (exact for a function linear on that triangle).
    A weight that would fall on a vertex below the horizon (a direction on the horizon can tie
    with a lower face) is moved onto the others.  ``inside`` is False for directions below the
    horizon; their results are meaningless.
    """
    d = np.asarray(directions, dtype=float)
    shape = d.shape[:-1]
    p = d.reshape(-1, 3)
    t0 = np.einsum("fkj,nj->nfk", _edge_normals(0), p)
    face = np.argmax(np.minimum(np.minimum(t0[..., 0], t0[..., 1]), t0[..., 2]), axis=1)
    corner = np.array([2, 0, 1])  # centre child's edge k faces the corner child corner[k]
    for lv in range(1, mesh.level + 1):
        centre = 4 * face + 3
        t = np.einsum("nkj,nj->nk", _edge_normals(lv)[centre], p)
        k = np.argmin(t, axis=1)
        outside = t[np.arange(len(p)), k] < 0.0
        face = np.where(outside, 4 * face + corner[k], centre)
    tri = sphere(mesh.level)[1][face]
    # rounding: a point on an edge may give -1e-17
    bary = np.maximum(np.einsum("nkj,nj->nk", _edge_normals(mesh.level)[face], p), 0.0)
    ids = _sphere_to_hemi(mesh.level)[tri]
    bary = np.where(ids >= 0, bary, 0.0)
    s = bary.sum(axis=1, keepdims=True)
    # s > 0 for any direction in or on the hemisphere (one kept vertex carries weight)
    bary = np.divide(bary, s, out=np.full_like(bary, 1.0 / 3.0), where=s > 0)
    ids = np.maximum(ids, 0)
    inside = p[:, 2] >= 0.0
    return ids.reshape(*shape, 3), bary.reshape(*shape, 3), inside.reshape(shape)


def interpolate(mesh: HemiMesh, values: np.ndarray, directions: np.ndarray) -> np.ndarray:
    """Barycentric interpolation of vertex ``values (N,)`` or ``(N, k)`` at ``directions
    (..., 3)``; NaN below the horizon."""
    values = np.asarray(values, dtype=float)
    ids, bary, inside = locate(mesh, directions)
    vals = values[ids]  # (..., 3) or (..., 3, k)
    if values.ndim == 1:
        out = np.einsum("...i,...i->...", vals, bary)
        return np.where(inside, out, np.nan)
    out = np.einsum("...ik,...i->...k", vals, bary)
    return np.where(inside[..., None], out, np.nan)


# ---------------------------------------------------------------------------------------------
# adaptive refinement


@dataclass(frozen=True, eq=False)
class AdaptiveMesh:
    """Result of :func:`refine_adaptive`: a (non-conforming) triangulation of the hemisphere.

    ``weights`` are a third of each final triangle's solid angle per vertex (sum 2π); a vertex
    that is only a midpoint of an unrefined triangle's edge (a hanging node) was evaluated to
    test that triangle and carries the weight of the refined neighbours that use it.
    ``evaluations`` counts calls of ``f`` per direction.  ``error`` estimates the integral's
    error: over the final triangles, the change of their integral from their own rule to
    their four children's (tested when deciding not to split), or a third of their parent's
    (second order) for the triangles of the last round.  An estimate, not a bound.
    """

    vertices: np.ndarray
    faces: np.ndarray
    weights: np.ndarray
    values: np.ndarray
    evaluations: int
    level: np.ndarray  # (F,) refinement level of each face
    error: float = 0.0

    def integrate(self, values: np.ndarray | None = None) -> np.ndarray:
        return _weighted_sum(self.weights, self.values if values is None else values)


def _magnitude(values: np.ndarray, channels: bool) -> np.ndarray:
    """Size used by the refinement test: |v|, or the largest channel of an RGB value."""
    a = np.abs(values)
    return a.max(axis=-1) if channels else a


def _tri_rule(verts: np.ndarray, vals: np.ndarray, tri: np.ndarray) -> np.ndarray:
    """``Ω/3·Σ f`` of triangles ``tri (F, 3)``: ``(F,)`` or ``(F, k)``."""
    area = triangle_solid_angles(*(verts[tri[:, i]] for i in range(3)))
    s = vals[tri[:, 0]] + vals[tri[:, 1]] + vals[tri[:, 2]]
    return (area / 3.0)[:, None] * s if s.ndim == 2 else area / 3.0 * s


#: Default evaluation budget of :func:`refine_adaptive` (bounds its time and memory).
ADAPTIVE_MAX_EVALS = 2_000_000


def refine_adaptive(
    f: Callable[[np.ndarray], np.ndarray],
    tol: float,
    *,
    max_level: int = 8,
    base_level: int = 2,
    focus: np.ndarray | None = None,
    max_evals: int = ADAPTIVE_MAX_EVALS,
) -> AdaptiveMesh:
    """Refine :func:`hemisphere` ``(base_level)`` where the integral of ``f`` is not resolved.

    ``f`` maps directions ``(n, 3)`` to values ``(n,)`` or ``(n, k)``.  Every round evaluates the
    edge midpoints of the active triangles (once per edge: neighbours share them) and, for each
    triangle, compares its vertex rule ``Ω/3·Σ f`` with the sum of its four children's: a
    triangle is split in four while that difference (its integral's error estimate) exceeds
    its share of the tolerance, ``tol·|∫f|·Ω/2π`` (``∫f`` the running estimate), until
    ``max_level`` or ``max_evals`` evaluations.  Triangles containing a ``focus`` direction
    (e.g. the mirror direction, where a sharp lobe may hide between vertices) are split down to
    ``max_level`` regardless.
    """
    _check_level(base_level, 1)
    _check_level(max_level, base_level, ADAPTIVE_MAX_LEVEL)
    base = hemisphere(base_level)
    verts = [np.array(base.vertices)]
    vals = [np.asarray(f(base.vertices), dtype=float)]
    nverts = len(base.vertices)
    rgb = vals[0].ndim == 2
    total = float(_magnitude(np.atleast_1d(base.integrate(vals[0])), False).max(initial=0.0))
    # sorted edge keys (a·2³² + b, a < b) → midpoint vertex id: neighbours share midpoints
    edge_keys = np.empty(0, dtype=np.int64)
    edge_vids = np.empty(0, dtype=np.int64)
    key_scale = np.int64(1) << 32
    active = np.array(base.faces, dtype=np.int64)
    done: list[np.ndarray] = []
    done_level: list[np.ndarray] = []
    error = pending = 0.0
    focus_p = None if focus is None else np.asarray(focus, dtype=float).reshape(-1, 3)

    for lv in range(base_level, max_level):
        if len(active) == 0:
            break
        if nverts >= max_evals:
            break
        allv = np.concatenate(verts)
        allval = np.concatenate(vals)
        e = _face_edges(active)
        keys = (e[..., 0] * key_scale + e[..., 1]).ravel()
        uniq, inv = np.unique(keys, return_inverse=True)
        pos = np.searchsorted(edge_keys, uniq)
        found = pos < len(edge_keys)
        found[found] = edge_keys[pos[found]] == uniq[found]
        known = np.full(len(uniq), -1, dtype=np.int64)
        known[found] = edge_vids[pos[found]]
        new = ~found
        a_id, b_id = uniq[new] // key_scale, uniq[new] % key_scale
        mids = _midpoints(allv, np.stack([a_id, b_id], axis=1))
        new_vals = np.asarray(f(mids), dtype=float)
        known[new] = nverts + np.arange(int(new.sum()))
        edge_keys = np.concatenate([edge_keys, uniq[new]])
        edge_vids = np.concatenate([edge_vids, known[new]])
        order = np.argsort(edge_keys, kind="stable")
        edge_keys, edge_vids = edge_keys[order], edge_vids[order]
        nverts += len(mids)
        verts.append(mids)
        vals.append(new_vals)
        allv = np.concatenate([allv, mids])
        allval = np.concatenate([allval, new_vals])
        mid = known[inv].reshape(-1, 3)
        kids = _split(active, mid)
        coarse = _tri_rule(allv, allval, active)
        fine = _tri_rule(allv, allval, kids)
        fine = fine.reshape(len(active), 4, *fine.shape[1:]).sum(axis=1)
        err = _magnitude(fine - coarse, rgb)
        # running estimate: finished triangles' share is not tracked separately; the finest
        # rule over the active ones plus the finished ones is close enough for a tolerance
        area = triangle_solid_angles(*(allv[active[:, i]] for i in range(3)))
        total = max(total, float(_magnitude(np.atleast_1d(fine.sum(axis=0)), False).max()))
        split = err > tol * total * area / (2.0 * np.pi)
        if focus_p is not None:
            hit = (_dets(allv, active[:, None, :], focus_p[None, :, :]).min(axis=-1)
                   >= -1e-12).any(axis=1)
            split |= hit
        error += float(err[~split].sum())
        # the split ones are tested again next round, unless refinement stops: then their
        # children's error is estimated as a third of this difference (second order)
        pending = float(err[split].sum()) / 3.0
        done.append(active[~split])
        done_level.append(np.full(int((~split).sum()), lv))
        active = kids.reshape(len(active), 4, 3)[split].reshape(-1, 3)
    done.append(active)
    done_level.append(np.full(len(active), max_level))
    error += pending

    vertices = np.concatenate(verts)
    faces = np.concatenate(done)
    values = np.concatenate(vals)
    # equal shares: the moment scaling of the uniform meshes would be global here, and the
    # coarse triangles' error would leak into the fine ones'
    weights = vertex_weights(vertices, faces)
    _readonly(vertices, faces, weights, values)
    return AdaptiveMesh(vertices, faces, weights, values, len(vertices),
                        np.concatenate(done_level), error)
