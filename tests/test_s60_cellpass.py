"""The Delaunay dual's one cell pass (``cells._pass``) in its four modes, bit for bit.

``cells._build`` counts and writes every cell (uncut cells from their halfedge walk, cut
ones through ``_cell``) and ``cells.rebuild_cells`` builds listed cells again, all in one
parallel function with an ``np.int64`` mode, so that ``_cell``'s call tree is compiled into
one parallel function, with one signature, not three. Each mode must give the rings the
others give.
"""

from __future__ import annotations

import numpy as np
import pytest

from voroforge.kernels import cells as K
from voroforge.kernels.cellcut import class_err, side_reaches
from voroforge.kernels.centers import circumcenters, merge_cocircular
from voroforge.kernels.delaunay import triangulate_sorted


def _dual(pts, box):
    """What the engine hands ``_build``: sorted sites, triangles, classes and reaches."""
    xs = np.ascontiguousarray(pts[:, 0])
    ys = np.ascontiguousarray(pts[:, 1])
    order, sx, sy, tri, he, _, ok = triangulate_sorted(xs, ys)
    assert ok
    sx = np.ascontiguousarray(sx)
    sy = np.ascontiguousarray(sy)
    box = np.array(box, dtype=np.float64)
    kmap = np.ascontiguousarray(order, dtype=np.int64)
    order = np.asarray(order, dtype=np.int64)
    cx, cy, err, flag = circumcenters(sx, sy, tri, he)
    cls, _ = merge_cocircular(sx, sy, tri, he, cx, cy, err, flag, kmap, box)
    merged = bool(flag.any()) or bool((cls != np.arange(cls.shape[0])).any())
    err = class_err(cls, err) if merged else err
    reach = side_reaches(sx, sy, tri, cls, cx, cy, err, box)
    return (sx, sy, tri, he, cx, cy, err, reach, cls, box, order, kmap), merged


def _grid(k):
    axis = (np.arange(k, dtype=np.float64) + 0.5) / k
    gx, gy = np.meshgrid(axis, axis)
    return np.column_stack([gx.ravel(), gy.ravel()])


CASES = {
    # no cocircular merges: uncut cells counted by their degree, written by the walk
    "random": (np.random.default_rng(5).random((400, 2)), (0.0, 0.0, 1.0, 1.0), False),
    "random_small_box": (np.random.default_rng(6).random((300, 2)), (0.2, 0.1, 0.7, 0.9), False),
    # merges: uncut cells counted and written from their classed walk
    "lattice": (_grid(18), (0.0, 0.0, 1.0, 1.0), True),
}


def _same(a, b):
    """Equal arrays, bit for bit (floats compared as their bits)."""
    a, b = np.asarray(a), np.asarray(b)
    if a.dtype.kind == "f":
        a, b = a.view(np.int64), b.view(np.int64)
    return a.shape == b.shape and np.array_equal(a, b)


@pytest.mark.parametrize("name", sorted(CASES))
def test_listed_pass_rebuilds_every_mode_bit_for_bit(name):
    pts, box, merges = CASES[name]
    args, merged = _dual(pts, box)
    assert merged == merges
    sx, sy, tri, he, cx, cy, err, reach, cls, box, order, kmap = args
    n = sx.shape[0]
    out, cells = K._build(*args, merged)
    coords, lengths, owner = cells
    sigs = len(K._pass.signatures)
    _, deg, cut = K._outgoing(tri, he, cx, cy, reach, box, n)
    assert 0 < int(cut.sum()) < n  # both branches of the all-sites pass are taken

    # every cell again through _cell (listed count, then listed fill), at the same places
    sites = np.arange(n, dtype=np.int64)
    cap = np.maximum.reduceat(deg[sites], np.arange(0, n, K._CHUNK)) + 16
    ws = np.zeros(n)
    counts = np.zeros(n, dtype=np.int64)
    none = np.zeros(0, dtype=np.int64)
    common = (sites, sx, sy, ws, tri, he, cx, cy, err, reach, cls, out, box, cap, counts)
    K._some(*common, none, coords, owner, kmap)
    assert np.array_equal(np.where(counts > 0, counts + 1, 0), np.diff(lengths)[order])
    coords2 = np.full_like(coords, np.nan)
    owner2 = np.full_like(owner, -99)
    K._some(*common, lengths[:-1][order], coords2, owner2, kmap)
    assert _same(coords, coords2)
    assert _same(owner, owner2)

    # a few cells rebuilt (the listed pass) and the others kept: the same diagram
    redo = np.zeros(n, dtype=np.bool_)
    redo[np.flatnonzero(cut)[:3]] = True
    redo[np.flatnonzero(~cut)[:3]] = True
    assert 8 * int(redo.sum()) <= n  # (more and rebuild_cells builds all again)
    out2, (c3, l3, o3) = K.rebuild_cells(*args, cells, redo)
    assert np.array_equal(out, out2)
    assert _same(coords, c3) and _same(lengths, l3) and _same(owner, o3)

    # one compiled pass for every mode: no new signature for the listed ones
    assert len(K._pass.signatures) == sigs
