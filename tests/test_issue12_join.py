"""Issue 12's speed work after the per-cell kernel keeps the results (not timings).

- ``Diagram3D.neighbors`` and ``.faces`` run over runs of build positions in parallel
  (counts, a prefix sum, then the rows): they must equal a plain loop over the per-cell face
  table, on one thread and on two, with duplicates, weights and a periodic box.
- ``build3d.bucket_keys3d`` and ``bucket_sort3d`` are one numba pass and a counting sort:
  the keys must be numpy's floor / NaN-to-0 / clip formula and the order its stable argsort,
  for points outside the grid, NaN and infinities too.
"""

from __future__ import annotations

import numba
import numpy as np
import pytest

import voroforge as vf
from voroforge.config import PARALLEL_MIN_SITES
from voroforge.engine.build3d import bucket_keys3d, bucket_sort3d, grid3d_shape

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
