"""3D Voronoi cells: invariants on every catalogue input, brute-force and voro++ cross-checks."""

from __future__ import annotations

import numpy as np
import pytest

import voroforge as vf
from catalogue3d import CATALOGUE3D
from reference3d import VOROPP, brute_volumes, voropp_cells

BOX = (0.0, 0.0, 0.0, 1.0, 1.0, 1.0)


def _walls(d):
    return np.asarray(d.walls)


def _power(d, x):
    """Power distances ``(m, n)`` from points ``x`` to every site."""
    w = np.zeros(len(d)) if d.weights is None else np.asarray(d.weights)
    return ((x[:, None, :] - np.asarray(d.sites)[None]) ** 2).sum(-1) - w[None]


def check3d(d, volume=None, samples=300, seed=0):
    """Every invariant of a 3D diagram; returns the number of checked samples."""
    cf, lab, farea, roff, ring = d.cell_face_table()
    n = len(d)
    V = np.asarray(d.vertices)
    np.asarray(d.sites)
    scale = float(np.abs(V).max()) if len(V) else 1.0
    size = float(np.ptp(V, axis=0).max()) if len(V) else 1.0
    # volumes tile the container
    target = d.container_volume if volume is None else volume
    assert abs(d.volumes.sum() - target) <= 1e-12 * target * max(1.0, scale / size) ** 1
    assert (d.volumes >= 0).all()
    live = d.volumes > 0
    assert np.isnan(d.centroids[~live]).all() and np.isfinite(d.centroids[live]).all()
    # duplicates own nothing
    assert (d.volumes[np.asarray(d.duplicate_of) >= 0] == 0).all()
    # shared vertices: each once, bit for bit (no two rows equal, none nearly equal)
    assert len(np.unique(V, axis=0)) == len(V)
    if len(V) > 1:
        from scipy.spatial import cKDTree

        assert not cKDTree(V).query_pairs(1e-9 * size)
    # per cell: closed (each directed edge's twin in the cell), Euler, convex and outward
    faces = {}
    for i in range(n):
        f0, f1 = cf[i], cf[i + 1]
        if f1 == f0:
            assert not live[i]
            continue
        directed = set()
        verts = set()
        for f in range(f0, f1):
            r = ring[roff[f] : roff[f + 1]].tolist()
            assert len(r) >= 3 and len(set(r)) == len(r)
            for a, b in zip(r, r[1:] + r[:1], strict=False):
                directed.add((a, b))
            verts.update(r)
            faces[(i, int(lab[f]), tuple(sorted(r)))] = r
        assert all((b, a) in directed for a, b in directed), f"cell {i} not closed"
        assert len(verts) - len(directed) // 2 + (f1 - f0) == 2, f"cell {i} Euler"
        cv = V[sorted(verts)]
        for f in range(f0, f1):
            a = farea[f]
            na = np.linalg.norm(a)
            assert na > 0
            p0 = V[ring[roff[f]]]
            assert ((cv - p0) @ (a / na)).max() <= 1e-9 * size, f"cell {i} not convex/outward"
    # face pairs: the same face from both sides, reversed
    for (i, j, key), r in faces.items():
        if j < 0:
            continue
        twin = faces.get((j, i, key))
        assert twin is not None, f"face {i}-{j} has no twin"
        k = twin.index(r[0])
        assert twin[k::-1] + twin[:k:-1] == r, f"face {i}-{j} twin not reversed"
    # every vertex is equidistant from the cells using it, and nobody is nearer
    owner = np.repeat(np.arange(n), np.diff(cf))
    rowner = np.repeat(owner, np.diff(roff))
    if len(V):
        pd = _power(d, V)
        best = pd.min(axis=1)
        tol = 1e-9 * (size**2 + np.abs(best))
        assert (np.abs(pd[ring, rowner] - best[ring]) <= tol[ring]).all()
    # samples: the nearest site's cell holds each point
    rng = np.random.default_rng(seed)
    lo, hi = np.asarray(d.box) if d.box is not None else (V.min(0), V.max(0))
    x = lo + (hi - lo) * rng.random((samples, 3))
    inside = (x @ _walls(d)[:, :3].T - _walls(d)[:, 3] <= 0).all(axis=1)
    x = x[inside]
    pd = _power(d, x)
    near = pd.argmin(axis=1)
    for q, k in zip(x, near, strict=False):
        f0, f1 = cf[k], cf[k + 1]
        a = farea[f0:f1]
        p0 = V[ring[roff[f0:f1]]]
        s = ((q - p0) * a).sum(1) / np.linalg.norm(a, axis=1)
        assert s.max() <= 1e-9 * size, "a sample lies outside its nearest site's cell"
    # neighbours: symmetric, from the faces
    indptr, idx = d.neighbors
    pairs = {(i, int(j)) for i in range(n) for j in idx[indptr[i] : indptr[i + 1]]}
    assert all((j, i) in pairs for i, j in pairs)
    return len(x)


@pytest.mark.parametrize("name", sorted(CATALOGUE3D))
def test_catalogue_invariants_and_brute_force(name):
    pts, box = CATALOGUE3D[name]
    d = vf.voronoi3d(pts, box)
    check3d(d)
    d.describe()
    assert d.describe()["euler_ok"] and d.describe()["convex"]
    assert d.unmatched_vertices == 0
    if len(pts) <= 80:
        ref = brute_volumes(pts, np.asarray(d.walls))
        ref[np.asarray(d.duplicate_of) >= 0] = 0.0
        np.testing.assert_allclose(d.volumes, ref, rtol=1e-9, atol=1e-12 * d.container_volume)


def test_cubic_grid_exact_structure():
    d = vf.voronoi3d(CATALOGUE3D["cubic_grid"][0])
    # 4x4x4 unit grid in a box padded 0.3: 5 vertex planes per axis, 64 cells, 6 faces each
    assert len(d.vertices) == 125
    assert (np.diff(d.cell_face_table()[0]) == 6).all()
    indptr, _ = d.neighbors
    assert np.diff(indptr).sum() == 2 * 3 * 4 * 4 * 3  # face neighbours only
    np.testing.assert_allclose(d.volumes.max(), 1.0, rtol=1e-14)


def test_random_box_and_locate():
    rng = np.random.default_rng(5)
    pts = rng.random((400, 3))
    d = vf.voronoi3d(pts, BOX)
    check3d(d, volume=1.0, samples=500)
    q = rng.random((200, 3))
    brute = ((q[:, None] - pts[None]) ** 2).sum(-1).argmin(1)
    np.testing.assert_array_equal(d.locate(q), brute)
    assert d.locate(pts[7]) == 7
    # an exact tie goes to the lowest index
    d2 = vf.voronoi3d([[0, 0, 0], [2, 0, 0], [1, 5, 5]], (-1, -1, -1, 3, 6, 6))
    assert d2.locate([1.0, 0.0, 0.0]) == 0


def test_contract_shapes():
    rng = np.random.default_rng(1)
    pts = rng.random((60, 3))
    d = vf.voronoi3d(pts, BOX)
    assert d.sites.shape == (60, 3) and d.volumes.shape == (60,) and d.centroids.shape == (60, 3)
    f = d.faces
    assert f.cells.shape == (len(f), 2) and len(f.indptr) == len(f) + 1
    assert d.face_areas.shape == (len(f),) and d.face_normals.shape == (len(f), 3)
    np.testing.assert_allclose(np.linalg.norm(d.face_normals, axis=1), 1.0, rtol=1e-12)
    # interior faces point from cells[:, 0] to cells[:, 1]; walls numbered as voro++
    inner = f.cells[:, 1] >= 0
    dvec = pts[f.cells[inner, 1]] - pts[f.cells[inner, 0]]
    assert ((d.face_normals[inner] * dvec).sum(1) > 0).all()
    assert set(f.cells[~inner, 1].tolist()) <= set(range(-6, 0))
    assert (f.cells[inner, 0] < f.cells[inner, 1]).all()
    # every interior face area once: the per-cell total counts it twice
    cf, lab, farea, roff, ring = d.cell_face_table()
    tot = np.linalg.norm(farea, axis=1).sum()
    np.testing.assert_allclose(tot, 2 * d.face_areas[inner].sum() + d.face_areas[~inner].sum())
    np.testing.assert_allclose(d.face_areas[~inner].sum(), 6.0, rtol=1e-12)
    p = d.cell(3)
    assert p.vertices.shape[1] == 3 and len(p.faces) == len(p.neighbors)
    m = d.to_trimesh(3)
    assert m.is_watertight and m.is_winding_consistent
    np.testing.assert_allclose(m.volume, d.volumes[3], rtol=1e-12)
    assert len(d.to_trimesh()) == 60
    with pytest.raises(ValueError):
        d.volumes[0] = 1.0  # results are read-only


def test_input_not_mutated_and_order_kept():
    rng = np.random.default_rng(2)
    pts = rng.random((80, 3))
    keep = pts.copy()
    d = vf.voronoi3d(pts, BOX)
    np.testing.assert_array_equal(pts, keep)
    perm = rng.permutation(80)
    e = vf.voronoi3d(pts[perm], BOX)
    np.testing.assert_allclose(e.volumes, d.volumes[perm], rtol=1e-12)


def test_metamorphic_translate_scale():
    rng = np.random.default_rng(3)
    pts = rng.random((60, 3))
    d = vf.voronoi3d(pts, BOX)
    for s, t in ((1e-9, 0.0), (1e9, 0.0), (1.0, 5e5), (2.0**-30, 2.0**-20)):
        # translated input is rounded: ulp(t) / cell size bounds the relative change
        e = vf.voronoi3d(pts * s + t, tuple(np.array(BOX) * s + t))
        np.testing.assert_allclose(e.volumes / s**3, d.volumes, rtol=1e-8 if t else 1e-11)


@pytest.mark.skipif(VOROPP is None, reason="voro++ CLI not installed")
def test_against_voropp():
    rng = np.random.default_rng(11)
    pts = rng.random((500, 3))
    d = vf.voronoi3d(pts, BOX)
    vol, nbs = voropp_cells(pts, BOX)
    np.testing.assert_allclose(d.volumes, vol, rtol=2e-5, atol=1e-9)  # voro++ prints 6 digits
    cf, lab, farea, roff, ring = d.cell_face_table()
    for i in range(len(pts)):
        ours = sorted(lab[cf[i] : cf[i + 1]].tolist())
        assert ours == nbs[i], f"cell {i}: {ours} != voro++ {nbs[i]}"
