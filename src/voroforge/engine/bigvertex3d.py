"""Power vertices of more owners than a cell's owner table holds (issue 12).

A vertex on the power spheres of more than 1,024 sites (sites on one sphere, or moved along
their rays with weights that keep them on one power vertex) overflowed every cell's owner
table at its widest ("overflowed its biggest slots"). Without weights the cells take their
Delaunay lists, which name such a vertex from its polytope (:mod:`.lists3d`); with weights
there are no lists. Here the first cell whose widest table overflows gives the vertex: the
full row holds its owners found so far, three of whose planes fix it exactly, and every site
is tested exactly against it (:func:`.predicates3d.bisector_side`): its owners are the sites
of least power there. It then serves as a big polytope of :func:`.cells3d.build_cells`
(named from all its sites; the cell's table may overflow at it), the same set in every
cell, so every cell names it alike and the join shares it.
"""

from __future__ import annotations

import threading

import numpy as np
from numba import njit

from ..config import NJIT
from ..kernels.predicates3d import bisector_side


class BigVertices:
    """The big vertices found in one build of sites ``P``, weights ``W``, walls ``WP``.

    ``of[i]``: the vertex whose owner set holds site ``i`` (-1 none); a site is in one at
    most (a site on two such vertices keeps the first; its cell fails as before).
    """

    def __init__(self, P, W, WP):
        self.P, self.W, self.WP = P, W, WP
        self.of = np.full(len(P), -1, np.int64)
        self.sets = []

    def search(self, i):
        """``(big, None)`` for :func:`.build3d._run` where site ``i`` is on a found vertex."""
        if self.of[i] < 0:
            return None
        bstart = np.cumsum([0] + [len(s) for s in self.sets]).astype(np.int64)
        return (self.of, bstart, np.concatenate(self.sets)), None

    def find(self, i, scr) -> bool:
        """Find the vertex whose owners overflowed cell ``i``'s table in scratch ``scr``.

        ``scr`` is the dict of :func:`.build3d._run` that built the cell alone (the
        :func:`.cells3d.cell_scratch` of its thread). Returns whether one was added.
        """
        work = scr.get(threading.get_ident())
        if work is None:
            return False
        (C, OWN), X = work[:2], work[-1]
        counts = C[5][: OWN.shape[0], 0]
        full = np.flatnonzero((counts >= OWN.shape[1]) & (OWN[:, 0] == i))  # (a named row)
        if len(full) == 0:
            return False
        return self.add(i, OWN[full[0]], OWN.shape[1], X[0], X[1])

    def add(self, i, keys, width, rows, buf) -> bool:
        """Add the vertex of site ``i`` and sites among ``keys`` if past ``width`` owners.

        ``keys``: owners of one vertex of cell ``i`` (sites past ``len(P)`` are walls);
        ``width``: the owner table's; ``rows``, ``buf``: the exact predicates' scratch.
        Returns whether one was added.
        """
        keys = np.unique(np.asarray(keys).astype(np.int64))
        keys = keys[(keys != i) & (keys < len(self.P))]
        owners = _least_power(i, keys, self.P, self.W, self.WP, rows, buf)
        if len(owners) <= width or (self.of[owners] >= 0).any():
            return False
        self.of[owners] = len(self.sets)
        self.sets.append(owners)
        return True


@njit(**NJIT)
def _least_power(i, keys, P, W, WP, rows, buf):
    """The sites whose power at cell ``i``'s vertex equals site ``i``'s (``i`` too), sorted.

    The vertex is the one point of the planes of three of ``keys`` (sites sharing it with
    ``i``); none: an empty result.
    """
    ns = P.shape[0]
    m = keys.shape[0]
    a = b = c = -1
    for x in range(min(m, 64)):
        for y in range(x + 1, min(m, 64)):
            for z in range(y + 1, m):
                k0, k1, k2 = keys[x], keys[y], keys[z]
                if bisector_side(i, k0, k1, k2, k0, P, W, WP, ns, rows, buf) != 2:
                    a, b, c = k0, k1, k2
                    break
            if a >= 0:
                break
        if a >= 0:
            break
    if a < 0:
        return np.zeros(0, np.int64)
    on = np.zeros(ns, np.bool_)
    on[i] = True
    for j in range(ns):
        if j != i and bisector_side(i, a, b, c, np.int64(j), P, W, WP, ns, rows, buf) == 0:
            on[j] = True
    return np.flatnonzero(on)
