"""Triangle-mesh topology helpers."""

from __future__ import annotations

import numpy as np


def halfedges_from_triangles(triangles: np.ndarray, n: int) -> np.ndarray:
    """Twin of every halfedge of a flat CCW triangle array (-1 on the boundary).

    Parameters
    ----------
    triangles : (3 t,) int
        Flat corner indices; halfedge ``e`` runs from ``triangles[e]`` to the next corner.
    n : int
        Number of points (bounds the indices).

    Returns
    -------
    (3 t,) int32
    """
    tri = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
    a = tri.ravel()
    b = tri[:, [1, 2, 0]].ravel()
    key = a * n + b
    twin_key = b * n + a
    order = np.argsort(key, kind="stable")
    pos = np.searchsorted(key[order], twin_key)
    pos = np.minimum(pos, len(key) - 1) if len(key) else pos
    found = len(key) > 0
    he = np.full(len(key), -1, dtype=np.int32)
    if found:
        hit = key[order][pos] == twin_key
        he[hit] = order[pos[hit]]
    return he
