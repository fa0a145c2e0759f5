"""Compressed sparse row adjacency helpers."""

from __future__ import annotations

import numpy as np


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
        key = np.unique(src * m + dst)
        src = key // m
        dst = key % m
    indptr = np.zeros(n + 1, dtype=np.int64)
    np.cumsum(np.bincount(src, minlength=n), out=indptr[1:])
    return indptr, dst.astype(np.int32)
