"""Compressed sparse row adjacency helpers."""

from __future__ import annotations

import numpy as np


def unique(values) -> np.ndarray:
    """Sorted distinct values of a 1-D array: ``np.unique(values)``, by a sort.

    numpy 2.3+ answers a plain ``np.unique`` of integers with a hash table that is 10-60x
    slower than sorting for millions of keys (6e6 int64 keys: 19 s against 0.3 s with numpy
    2.4.6 here), so the engine and the layers above use this for 1-D keys.
    """
    flat = np.sort(np.asarray(values).ravel())
    if flat.size < 2:
        return flat
    keep = np.ones(flat.size, dtype=bool)
    np.not_equal(flat[1:], flat[:-1], out=keep[1:])
    return flat[keep]


def used_only(points: np.ndarray, index: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(points[used], index renumbered)``: the points ``index`` refers to, in their order.

    A mesh's vertices after some of its triangles were dropped (every vertex used again).
    """
    used = np.zeros(len(points), dtype=bool)
    used[np.asarray(index).ravel()] = True
    return points[used], (np.cumsum(used) - 1)[index]


def csr_from_pairs(n: int, a, b) -> tuple[np.ndarray, np.ndarray]:
    """Symmetric CSR ``(indptr, indices)`` from undirected pairs; duplicates removed, rows sorted.

    Parameters
    ----------
    n : int
        Number of nodes.
    a, b : (m,) int array_like
        End points of each pair.
    """
    a = np.asarray(a, dtype=np.int64)
    b = np.asarray(b, dtype=np.int64)
    src = np.concatenate((a, b))
    dst = np.concatenate((b, a))
    m = max(n, 1)
    if src.size:
        key = unique(src * m + dst)
        src = key // m
        dst = key % m
    indptr = np.zeros(n + 1, dtype=np.int64)
    np.cumsum(np.bincount(src, minlength=n), out=indptr[1:])
    return indptr, dst.astype(np.int32)
