"""Issue 12's speed work after the per-cell kernel keeps the results (not timings).

- ``Diagram3D.neighbors`` and ``.faces`` run over runs of build positions in parallel
  (counts, a prefix sum, then the rows): they must equal a plain loop over the per-cell face
  table, on one thread and on two, with duplicates, weights and a periodic box.
- ``build3d.bucket_keys3d`` and ``bucket_sort3d`` are one numba pass and a counting sort:
  the keys must be numpy's floor / NaN-to-0 / clip formula and the order its stable argsort,
  for points outside the grid, NaN and infinities too.
- ``build3d.duplicate_owners`` hashes each point's bits with one zero (no ``P + 0.0`` copy,
  int32 table): it must equal a plain dictionary of the points, ``-0.0`` meeting ``+0.0``.
- ``build_cells3d`` writes each chunk's per-cell results straight to the caller's order
  (no build-order copies to permute): a build of some cells, in any order, must give each
  cell what the build of all gives it, with the joining thread and without.
"""

from __future__ import annotations

import numba
import numpy as np
import pytest

import voroforge as vf
from voroforge.config import PARALLEL_MIN_SITES
from voroforge.engine.build3d import (
    bucket_keys3d,
    bucket_sort3d,
    build_cells3d,
    duplicate_owners,
    grid3d_shape,
)
from voroforge.engine.containers import box_template

BOX = (0.0, 0.0, 0.0, 1.0, 1.0, 1.0)


def _numpy_keys(P, g):
    n = np.asarray(g[6:9], np.int64)
    with np.errstate(invalid="ignore", over="ignore"):
        idx = np.floor((P - g[:3]) / g[3:6])
    idx = np.clip(np.nan_to_num(idx, nan=0.0), 0, n - 1).astype(np.int64)
    return (idx[:, 2] * n[1] + idx[:, 1]) * n[0] + idx[:, 0]


def _reference(d):
    """Neighbours and unique faces from ``cell_face_table`` by numpy (sorts and masks)."""
    cf, lab, area, roff, ring = d.cell_face_table()
    lab = np.asarray(lab, np.int64)
    cell = np.repeat(np.arange(len(d)), np.diff(cf))
    # a face of zero area (its fan's vector exactly 0) makes no neighbour
    nb = (lab >= 0) & (lab != cell) & (area != 0).any(axis=1)
    pairs = np.unique(np.column_stack([cell[nb], lab[nb]]), axis=0)
    indptr = np.concatenate([[0], np.cumsum(np.bincount(pairs[:, 0], minlength=len(d)))])
    keep = (lab < 0) | (lab > cell)
    lens = np.diff(roff)[keep]
    take = np.repeat(roff[:-1][keep] - np.concatenate([[0], np.cumsum(lens)[:-1]]), lens)
    fidx = ring[take + np.arange(lens.sum())]
    fptr = np.concatenate([[0], np.cumsum(lens)])
    return indptr, pairs[:, 1], fptr, fidx, np.column_stack([cell[keep], lab[keep]])


def _cases():
    rng = np.random.default_rng(12)
    n = PARALLEL_MIN_SITES + 500  # past serial_below: the parallel runs are used
    p = rng.random((n, 3))
    return {
        "uniform": lambda: vf.voronoi3d(p, BOX),
        "duplicates": lambda: vf.voronoi3d(np.vstack([p, p[:300]]), BOX),
        "weights": lambda: vf.voronoi3d(p, BOX, weights=1e-4 * rng.random(n)),
        "periodic": lambda: vf.voronoi3d(p, BOX, periodic=True),
    }


@pytest.mark.parametrize("case", ["uniform", "duplicates", "weights", "periodic"])
def test_neighbors_and_faces_match_a_plain_loop(case):
    d = _cases()[case]()
    indptr, indices, fptr, fidx, fcells = _reference(d)
    before = numba.get_num_threads()
    seen = []
    for nt in sorted({1, min(2, numba.config.NUMBA_NUM_THREADS)}):
        numba.set_num_threads(nt)
        try:
            d._cache.pop("nb", None)
            d._cache.pop("unique", None)
            ip, ix = d.neighbors
            f = d.faces
        finally:
            numba.set_num_threads(before)
        assert np.array_equal(ip, indptr)
        assert np.array_equal(ix, indices)
        if not d.periodic:  # periodic faces are kept by image (face_keep), not by label
            assert np.array_equal(f.indptr, fptr)
            assert np.array_equal(f.indices, fidx)
            assert np.array_equal(f.cells, fcells)
        seen.append((f.indptr.tobytes(), f.indices.tobytes(), f.cells.tobytes()))
    assert len(set(seen)) == 1  # one thread and two give the same faces
    # every face of positive area between two sites appears in both cells' rows
    rows = np.repeat(np.arange(len(d)), np.diff(indptr))
    pairs = set(zip(rows.tolist(), indices.tolist(), strict=True))
    assert all((j, i) in pairs for i, j in pairs)


@pytest.mark.parametrize("seed", range(6))
def test_bucket_keys_and_sort_match_numpy(seed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(1, 4000))
    P = rng.random((n, 3)) * 10 ** rng.uniform(-8, 8) + rng.uniform(-1e6, 1e6)
    P[::7] = P[0]  # ties keep the input order
    g = grid3d_shape(P, 2.0)
    Q = P.copy()
    if seed % 2:  # outside the grid, NaN and infinities: clamped like numpy's clip
        Q[::11, 1] = np.nan
        Q[::13, 0] = np.inf
        Q[::17, 2] = -np.inf
        Q[::19] *= -1e300
    keys = _numpy_keys(Q, g)
    assert np.array_equal(bucket_keys3d(Q, g), keys)
    start, SP, sidx = bucket_sort3d(Q, g)
    want = np.argsort(keys, kind="stable")
    assert np.array_equal(sidx, want)
    assert np.array_equal(SP, Q[want], equal_nan=True)
    nb = int(np.prod(g[6:9]))
    assert np.array_equal(start, np.concatenate([[0], np.cumsum(np.bincount(keys, minlength=nb))]))


def test_released_memory_keeps_the_results(monkeypatch):
    # voronoi3d hands the build's freed heap pages back (malloc_trim) from TRIM_CELLS cells:
    # forced on a small input, the diagram is the same bits and stays usable
    from voroforge.engine import build3d

    p = np.random.default_rng(5).random((3000, 3))
    plain = vf.voronoi3d(p, BOX)
    monkeypatch.setattr(build3d, "TRIM_CELLS", 0)
    d = vf.voronoi3d(p, BOX)
    assert (d.volumes == plain.volumes).all() and (d.vertices == plain.vertices).all()
    for a, b in zip(d.neighbors, plain.neighbors, strict=True):
        assert (a == b).all()
    assert (d.faces.indices == plain.faces.indices).all()
    build3d.release_freed_memory(0)  # and called directly


def _owners_reference(P, W):
    best = {}
    for i, p in enumerate((P + 0.0).tolist()):
        o = best.get(tuple(p))
        if o is None or W[i] > W[o]:
            best[tuple(p)] = i
    return np.array(
        [-1 if best[tuple(p)] == i else best[tuple(p)] for i, p in enumerate((P + 0.0).tolist())],
        np.int64,
    )


@pytest.mark.parametrize("seed", range(4))
def test_duplicate_owners_match_a_dictionary(seed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(2, 3000))
    P = np.round(rng.random((n, 3)) * 4) / 4 - 0.5  # many equal points, zeros among them
    P[rng.random((n, 3)) < 0.2] *= -1.0  # -0.0 where a coordinate is 0
    W = np.round(rng.random(n) * 3) if seed % 2 else np.zeros(n)  # ties: lowest index owns
    dup = duplicate_owners(P, W)
    assert dup.dtype == np.int64
    assert np.array_equal(dup, _owners_reference(P, W))


@pytest.mark.parametrize("threads", [1, 2])
def test_some_cells_get_what_all_cells_get(threads):
    rng = np.random.default_rng(7)
    n = PARALLEL_MIN_SITES + 5000  # past serial_below, more than one chunk: the joining thread
    P = rng.random((n, 3))
    W = np.zeros(n)
    t = box_template(np.zeros(3), np.ones(3))
    before = numba.get_num_threads()
    numba.set_num_threads(min(threads, numba.config.NUMBA_NUM_THREADS))
    try:
        every = build_cells3d(P, W, t)
        some = rng.permutation(n)[: n // 2]  # any order, not the bucket order
        part = build_cells3d(P, W, t, cells=some)
    finally:
        numba.set_num_threads(before)
    assert np.array_equal(part.cells, some)
    assert (every.status == 0).all() and (part.status == 0).all()
    assert np.array_equal(part.volume, every.volume[some])
    assert np.array_equal(part.centroid, every.centroid[some])
    assert np.array_equal(part.rad2, every.rad2[some])
    assert abs(every.volume.sum() - 1.0) < 1e-12
    for res, k in ((every, n), (part, len(some))):
        # the offsets in build order: cell c's faces and vertices at its position pos[c]
        assert np.array_equal(np.sort(res.pos), np.arange(k))
        nf = np.diff(res.cell_faces)[res.pos]
        assert (nf >= 4).all() and res.cell_faces[-1] == len(res.flabel)
        assert res.voff[-1] == len(res.vid)
    # each cell's faces name the same neighbours in both builds
    for c in rng.choice(len(some), 50, replace=False):
        i = some[c]
        a = every.flabel[every.cell_faces[every.pos[i]] : every.cell_faces[every.pos[i] + 1]]
        b = part.flabel[part.cell_faces[part.pos[c]] : part.cell_faces[part.pos[c] + 1]]
        assert np.array_equal(np.sort(a), np.sort(b))


def test_periodic_face_shifts_one_and_two_threads():
    # voronoi3d._torus_faces runs its cells in parallel (prange): the labels, the faces kept
    # once and each face's image shift must be the same on one thread and two, and each
    # face must lie midway between its site and the image across it
    rng = np.random.default_rng(21)
    p = rng.random((PARALLEL_MIN_SITES + 3000, 3))
    before = numba.get_num_threads()
    got = []
    for nt in sorted({1, min(2, numba.config.NUMBA_NUM_THREADS)}):
        numba.set_num_threads(nt)
        try:
            d = vf.voronoi3d(p, BOX, periodic=True)
            f = d.faces
        finally:
            numba.set_num_threads(before)
        got.append((d.face_shifts.tobytes(), f.cells.tobytes(), f.indices.tobytes()))
    assert len(set(got)) == 1
    cf, lab, area, roff, ring = d.cell_face_table()
    sh = np.asarray(d.face_shifts)
    assert sh.shape == (len(lab), 3)
    owner = np.repeat(np.arange(len(d)), np.diff(cf))
    site = lab >= 0
    assert (sh[~site] == 0).all() and np.abs(sh).max() == 1
    # each face's first vertex is as far from its site as from the image across it
    first = np.asarray(ring)[np.asarray(roff)[:-1]]
    c = np.asarray(d.vertices)[first][site]
    di = np.linalg.norm(c - p[owner[site]], axis=1)
    dj = np.linalg.norm(c - (p[lab[site]] + sh[site]), axis=1)
    assert np.abs(di - dj).max() < 1e-9
