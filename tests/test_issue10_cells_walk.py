"""Issue 10: uncut cells with merged classes come from their halfedge walk, bit for bit.

``cells._build`` counts and writes a cell whose site is interior and whose centres all lie in
the box straight from its halfedge walk (``_classed_ring``); every other cell, and every cell
that ``_rebuild`` builds again (``_some``), goes through ``_cell``. Both must give the same
rings and owners, bit for bit, on inputs whose cocircular sites merge classes.
"""

from __future__ import annotations

import numpy as np
import pytest

from voroforge.kernels import cells as K
from voroforge.kernels.cellcut import class_err, side_reaches
from voroforge.kernels.centers import circumcenters, merge_cocircular
from voroforge.kernels.delaunay import triangulate_sorted


def _lattice(k, angle=0.0, offset=0.0):
    axis = (np.arange(k, dtype=np.float64) + 0.5) / k
    gx, gy = np.meshgrid(axis, axis)
    p = np.column_stack([gx.ravel(), gy.ravel()])
    if angle:
        c, s = np.cos(angle), np.sin(angle)
        p = (p - 0.5) @ np.array([[c, -s], [s, c]]) + 0.5
    return p + offset


CASES = {
    "square_lattice": (_lattice(24), (0.0, 0.0, 1.0, 1.0)),
    "lattice_in_small_box": (_lattice(24), (0.2, 0.2, 0.8, 0.8)),
    "rotated_lattice": (_lattice(20, angle=0.3), (0.0, 0.0, 1.0, 1.0)),
    "lattice_and_random": (
        np.concatenate([_lattice(20), np.random.default_rng(3).random((60, 2))]),
        (-0.1, -0.1, 1.1, 1.0),
    ),
    "lattice_far_away": (_lattice(16, offset=1e6), (1e6, 1e6, 1e6 + 1.0, 1e6 + 1.0)),
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_walk_matches_cell_builder(name):
    pts, box = CASES[name]
    xs = np.ascontiguousarray(pts[:, 0])
    ys = np.ascontiguousarray(pts[:, 1])
    order, sx, sy, tri, he, _, ok = triangulate_sorted(xs, ys)
    assert ok
    sx = np.ascontiguousarray(sx)
    sy = np.ascontiguousarray(sy)
    n = sx.shape[0]
    box = np.array(box, dtype=np.float64)
    kmap = np.ascontiguousarray(order, dtype=np.int64)
    order = np.asarray(order, dtype=np.int64)
    cx, cy, err, flag = circumcenters(sx, sy, tri, he)
    cls, _ = merge_cocircular(sx, sy, tri, he, cx, cy, err, flag, kmap, box)
    merges = int((cls != np.arange(cls.shape[0])).sum())
    # as the engine (cells.build) calls it: the classes' bounds and the box-side reaches
    err = class_err(cls, err)
    reach = side_reaches(sx, sy, tri, cls, cx, cy, err, box)
    out, (coords, lengths, owner) = K._build(
        sx, sy, tri, he, cx, cy, err, reach, cls, box, order, kmap, True
    )
    _, deg, cut = K._outgoing(tri, he, cx, cy, reach, box, n)
    # the walk is taken: classes were merged and some cells are uncut (others are cut)
    assert merges > 0
    assert 0 < int((~cut).sum()) < n

    # every cell again through _cell (_rebuild's path), at the same places
    sites = np.arange(n, dtype=np.int64)
    starts = np.arange(0, n, K._CHUNK)
    cap = np.maximum.reduceat(deg[sites], starts) + 16
    ws = np.zeros(n)
    counts = np.zeros(n, dtype=np.int64)
    none = np.zeros(0, dtype=np.int64)
    args = (reach, cls, out, box, cap, counts)
    K._some(sites, sx, sy, ws, tri, he, cx, cy, err, *args, none, coords, owner, kmap)
    closed = np.where(counts > 0, counts + 1, 0)
    assert np.array_equal(closed, np.diff(lengths)[order])
    coords2 = np.full_like(coords, np.nan)
    owner2 = np.full_like(owner, -99)
    K._some(
        sites, sx, sy, ws, tri, he, cx, cy, err, *args, lengths[:-1][order], coords2, owner2, kmap
    )
    assert np.array_equal(coords.view(np.int64), coords2.view(np.int64))
    assert np.array_equal(owner, owner2)
