"""Near points without a KD-tree: pairs within a tolerance, their clusters, k nearest.

The writers snap vertices that rounding left a hair apart (:func:`close_pairs`,
:func:`cluster_labels`) and order paths with a candidate list of near path ends
(:func:`nearest`). These are small jobs; doing them with numpy keeps ``scipy.spatial`` and
``scipy.sparse`` (about a quarter of a second to import) out of a design build. Large
inputs of :func:`nearest` still go to scipy's ``cKDTree``, imported then.

Examples
--------
>>> import numpy as np
>>> pts = np.array([[0.0, 0.0], [1e-12, 0.0], [1.0, 0.0], [1.0, 1e-12]])
>>> close_pairs(pts, 1e-9).tolist()
[[0, 1], [2, 3]]
>>> cluster_labels(4, close_pairs(pts, 1e-9)).tolist()
[0, 0, 1, 1]
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["close_pairs", "cluster_labels", "nearest", "nearest_to"]

#: Grid cells per axis beyond which :func:`close_pairs` asks scipy (keys would overflow).
_MAX_CELLS = 2**30
#: Points up to which :func:`nearest` compares every pair (above: a KD-tree).
NEAREST_BRUTE = 1024
#: Point-query pairs up to which :func:`nearest_to` compares every pair (above: a KD-tree):
#: 4M pairs take about 0.05 s, less than importing ``scipy.spatial`` (0.15-0.3 s).
NEAREST_TO_BRUTE = 4_000_000
_BLOCK = 1 << 20  # distances per chunk
#: The same in space (three keys of 21 bits fit an int64).
_MAX_CELLS_3D = 2**20


def _half(dim: int) -> list[tuple[int, ...]]:
    """The zero offset and the neighbour offsets whose first nonzero step is +1."""
    import itertools

    steps = [s for s in itertools.product((-1, 0, 1), repeat=dim) if s > (0,) * dim]
    return [(0,) * dim, *steps]


_HALF_NEIGHBOURS = {2: _half(2), 3: _half(3)}


def _check(points, dims=(2,)) -> np.ndarray:
    pts = np.ascontiguousarray(points, dtype=np.float64)
    if pts.ndim != 2 or pts.shape[1] not in dims:
        shape = " or ".join(f"(n, {d})" for d in dims)
        raise ValueError(f"points must have shape {shape}, got {pts.shape}")
    if not np.isfinite(pts).all():
        raise ValueError("points contain NaN or infinite coordinates")
    return pts


def close_pairs(points, tol: float) -> np.ndarray:
    """Every pair of points at distance ``<= tol``, as ``(i, j)`` rows with ``i < j``.

    Parameters
    ----------
    points : (n, 2) or (n, 3) float64
    tol : float
        Distance (>= 0; 0 gives no pairs).

    Returns
    -------
    (p, 2) int64
        Sorted by ``i`` then ``j``.

    Notes
    -----
    The points are hashed into square (cubic) cells of side ``tol`` (a little more, so
    rounding cannot put two points within ``tol`` two cells apart); a pair within ``tol``
    lies in one cell or two neighbouring ones, so each point looks at its own cell and half
    of its neighbours (4 in the plane, 13 in space; the other half see it). Exact distances
    decide. Where the keys would overflow (more than 2**30 cells across in the plane, 2**20
    in space), the cells are made larger: any side of at least ``tol`` finds every pair.
    """
    pts = _check(points, (2, 3))
    tol = float(tol)
    if not (math.isfinite(tol) and tol >= 0):
        raise ValueError(f"tol must be a finite number >= 0, got {tol!r}")
    n = len(pts)
    if n < 2 or tol == 0:
        return np.zeros((0, 2), dtype=np.int64)
    lo = pts.min(axis=0)
    cell = tol * (1.0 + 1e-5)
    extent = float((pts.max(axis=0) - lo).max())
    dim = pts.shape[1]
    most = _MAX_CELLS if dim == 2 else _MAX_CELLS_3D
    if not extent / cell < most - 4:
        # a tolerance far below the extent (merging seams at 1e-10 of it): larger cells
        # find the same pairs (any cell of at least ``tol`` does), with more to compare
        cell = extent / (most - 4)
    k = np.floor((pts - lo) / cell).astype(np.int64) + 1  # >= 1: a row below stays apart
    # row-major keys over a grid one cell wider each way
    stride = np.ones(dim, dtype=np.int64)
    for a in range(dim - 2, -1, -1):
        stride[a] = stride[a + 1] * (int(k[:, a + 1].max()) + 2)
    key = k @ stride
    order = np.argsort(key, kind="stable")
    skey = key[order]
    found = []
    for step in _HALF_NEIGHBOURS[dim]:
        q = key + int(np.dot(step, stride))
        first = np.searchsorted(skey, q, side="left")
        count = np.searchsorted(skey, q, side="right") - first
        total = int(count.sum())
        if not total:
            continue
        i = np.repeat(np.arange(n), count)
        offset = np.arange(total) - np.repeat(np.cumsum(count) - count, count)
        j = order[np.repeat(first, count) + offset]
        if not any(step):
            keep = i < j
            i, j = i[keep], j[keep]
        d = pts[i] - pts[j]
        near = np.einsum("ij,ij->i", d, d) <= tol * tol
        found.append(np.stack((i[near], j[near]), axis=1))
    if not found:
        return np.zeros((0, 2), dtype=np.int64)
    pairs = np.sort(np.concatenate(found), axis=1)
    return pairs[np.lexsort((pairs[:, 1], pairs[:, 0]))]


def cluster_labels(n: int, pairs) -> np.ndarray:
    """Connected components of ``n`` points joined by ``pairs``.

    Parameters
    ----------
    n : int
        Number of points.
    pairs : (p, 2) int array_like
        Joined points.

    Returns
    -------
    (n,) int64
        Component of each point, numbered ``0, 1, ...`` in the order of each component's
        lowest point (scipy's ``connected_components`` numbering for undirected graphs).
    """
    label = np.arange(n, dtype=np.int64)
    pairs = np.asarray(pairs, dtype=np.int64).reshape(-1, 2)
    if len(pairs):
        a, b = pairs[:, 0], pairs[:, 1]
        while True:  # each point takes the lowest label of its pairs, then jumps pointers
            low = np.minimum(label[a], label[b])
            new = label.copy()
            np.minimum.at(new, a, low)
            np.minimum.at(new, b, low)
            new = new[new]
            if np.array_equal(new, label):
                break
            label = new
    return np.unique(label, return_inverse=True)[1].astype(np.int64)


def nearest(points, k: int) -> np.ndarray:
    """The ``k`` nearest points of each point (itself included), nearest first.

    Parameters
    ----------
    points : (n, 2) float64
    k : int
        How many (1 <= k <= n).

    Returns
    -------
    (n, k) int64
        Indices. Up to NEAREST_BRUTE points every pair is compared and equal distances
        come in increasing index (the k-th place among equal distances is numpy's
        ``argpartition`` choice); beyond, scipy's ``cKDTree.query`` answers.
    """
    pts = _check(points)
    n = len(pts)
    k = int(k)
    if not 1 <= k <= max(n, 1):
        raise ValueError(f"k must be in [1, {n}], got {k}")
    if n > NEAREST_BRUTE:
        from scipy.spatial import cKDTree

        _, nb = cKDTree(pts).query(pts, k=k)
        return np.asarray(nb, dtype=np.int64).reshape(n, k)
    out = np.zeros((n, k), dtype=np.int64)
    step = max(1, _BLOCK // max(n, 1))
    for s in range(0, n, step):
        p = pts[s : s + step]
        dx = p[:, 0, None] - pts[None, :, 0]
        dy = p[:, 1, None] - pts[None, :, 1]
        d2 = dx * dx + dy * dy
        idx = (
            np.argpartition(d2, k - 1, axis=1)[:, :k]
            if k < n
            else np.tile(np.arange(n), (len(p), 1))
        )
        near = np.take_along_axis(d2, idx, axis=1)
        # nearest first; equal distances by increasing index
        rank = np.lexsort((idx, near), axis=1)
        out[s : s + step] = np.take_along_axis(idx, rank, axis=1)
    return out


def nearest_to(points, queries) -> tuple[np.ndarray, np.ndarray]:
    """The nearest of ``points`` to each query, and its distance.

    Parameters
    ----------
    points : (n, 2) float64
        At least one point.
    queries : (m, 2) float64

    Returns
    -------
    distance : (m,) float64
    index : (m,) int64
        Equal distances go to the lowest index when every pair is compared (up to
        NEAREST_TO_BRUTE pairs); beyond, scipy's ``cKDTree.query`` answers.
    """
    pts = _check(points)
    q = _check(queries)
    if not len(pts):
        raise ValueError("nearest_to needs at least one point")
    if len(pts) * len(q) > NEAREST_TO_BRUTE:
        from scipy.spatial import cKDTree

        dist, idx = cKDTree(pts).query(q, k=1)
        return np.asarray(dist, dtype=np.float64), np.asarray(idx, dtype=np.int64)
    dist = np.zeros(len(q))
    idx = np.zeros(len(q), dtype=np.int64)
    step = max(1, _BLOCK // len(pts))
    for s in range(0, len(q), step):
        dx = q[s : s + step, 0, None] - pts[None, :, 0]
        dy = q[s : s + step, 1, None] - pts[None, :, 1]
        d2 = dx * dx + dy * dy
        best = d2.argmin(axis=1)  # the first of equal minima
        idx[s : s + step] = best
        dist[s : s + step] = np.sqrt(np.take_along_axis(d2, best[:, None], axis=1)[:, 0])
    return dist, idx
