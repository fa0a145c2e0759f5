"""Edges cut at T-junctions beside lost sites (issue 15, s58 edges8).

1000 float sites on a circle of radius 1e-7 at (5e5, 4e6), phase 0.1: beside the lost
site 484, the vertex (-1078, 0) (units of 2^-34 from the centre) that cells 485 and 488
share lies exactly on the straight side (-2062, 0) -> (-758, 0) of cell 483's ring, which
does not have it. The builder names 485 across the whole side, so the edge (483, 485) ran
on past 485's end to 488's vertex and cells 483 and 488 shared no edge. Such an edge is now
cut at the vertices of its cells lying on it, and each piece given to the two rings that
hold it (``engine.edgeowners.split_at_junctions``). Checked in the circle's integer frame
with exact integer orientation tests (no engine code).
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest
import shapely

import voroforge as vf
from test_s56_strips import CENTRE, UNIT, _circle
from voroforge.engine.edgeowners import split_at_junctions


def _local(xy):
    out = (np.asarray(xy, dtype=np.float64).reshape(-1, 2) - CENTRE) / UNIT
    assert (out == np.round(out)).all()  # exact: every float here is on the unit grid
    return [tuple(int(v) for v in q) for q in out.tolist()]


def _on(p, a, b):
    """Integer point ``p`` on the closed segment ``a b``, exactly."""
    cross = (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])
    return (
        cross == 0
        and min(a[0], b[0]) <= p[0] <= max(a[0], b[0])
        and (min(a[1], b[1]) <= p[1] <= max(a[1], b[1]))
    )


def test_split_at_a_vertex_on_the_side():
    """Cell 0's side (0, 0) -> (4, 0) named against cell 1 only; cells 1 and 2 meet at
    (2, 0) below it: two edges, (0, 1) and (0, 2)."""
    rings = [
        [(0, 0), (4, 0), (4, 2), (0, 2), (0, 0)],
        [(0, -2), (2, -2), (2, 0), (0, 0), (0, -2)],
        [(2, -2), (4, -2), (4, 0), (2, 0), (2, -2)],
    ]
    coords = np.array([q for r in rings for q in r], dtype=np.float64)
    off = np.array([0, 5, 10, 15], dtype=np.int64)
    bufs = (coords, off, np.arange(4, dtype=np.int64), np.arange(4, dtype=np.int64))
    seg = np.array([[(0.0, 0.0), (4.0, 0.0)], [(2.0, -2.0), (2.0, 0.0)]])
    pairs = np.array([[0, 1], [1, 2]])
    got_s, got_p = split_at_junctions((seg, pairs), bufs, 1e-12)
    got = {
        (tuple(map(tuple, s)), tuple(p))
        for s, p in zip(got_s.tolist(), got_p.tolist(), strict=True)
    }
    assert got == {
        (((0.0, 0.0), (2.0, 0.0)), (0, 1)),
        (((2.0, 0.0), (4.0, 0.0)), (0, 2)),
        (((2.0, -2.0), (2.0, 0.0)), (1, 2)),
    }
    # edges whose ends are vertices of both cells come back as they were
    same = split_at_junctions((got_s, got_p), bufs, 1e-12)
    assert same[0] is got_s


def test_shared_side_named_against_an_empty_cell():
    """Cells 1 and 2 share a side, but both rings named the lost (empty) cell 0 across it,
    so neither gave the edge: it is added, once."""
    rings = [
        [(0, 0), (2, 0), (2, 2), (0, 2), (0, 0)],
        [(0, -2), (2, -2), (2, 0), (0, 0), (0, -2)],
        [(2, 0), (4, 0), (4, 2), (2, 2), (2, 0)],
    ]
    coords = np.array([q for r in rings for q in r], dtype=np.float64)
    off = np.array([0, 5, 10, 15], dtype=np.int64)
    # cell 0 is empty: cells 1, 2 and 3 hold the three rings
    bufs = (coords, off, np.arange(4, dtype=np.int64), np.array([0, 0, 1, 2, 3], dtype=np.int64))
    seg = np.array([[(2.0, 0.0), (2.0, 2.0)]])
    pairs = np.array([[1, 3]])
    got_s, got_p = split_at_junctions((seg, pairs), bufs, 1e-12)
    got = {
        (tuple(map(tuple, s)), tuple(p))
        for s, p in zip(got_s.tolist(), got_p.tolist(), strict=True)
    }
    assert got == {(((2.0, 0.0), (2.0, 2.0)), (1, 3)), (((0.0, 0.0), (2.0, 0.0)), (1, 2))}


@pytest.fixture(scope="module")
def diagram():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return vf.voronoi(_circle(1000, 0.1), None)


def test_edges_are_the_rings_sides(diagram):
    d = diagram
    x0, y0, x1, y1 = d.bounds
    rings = []
    for c in d.cells:
        parts = [] if c is None or c.is_empty else shapely.get_parts(c)
        rings.append([_local(shapely.get_coordinates(p.exterior)) for p in parts])
    verts = [{q for r in rs for q in r} for rs in rings]
    lo, hi = _local([(x0, y0), (x1, y1)])
    mine = {}
    pairs = [tuple(p) for p in d.edges.pairs.tolist()]
    assert (483, 488) in pairs  # the pair the long edge hid
    for s, (i, j) in zip(d.edges.coords, pairs, strict=True):
        a, b = _local(s)
        mine.setdefault(i, []).append((a, b))
        mine.setdefault(j, []).append((a, b))
        # each end a vertex of both cells, or on the straight side of the ring (a T-junction)
        for q in (a, b):
            for c in (i, j):
                assert q in verts[c] or any(
                    _on(q, u, v) for r in rings[c] for u, v in zip(r[:-1], r[1:], strict=True)
                ), (i, j, q, c)
    # every ring side off the box is covered by its cell's edges along it
    for c, rs in enumerate(rings):
        for r in rs:
            for a, b in zip(r[:-1], r[1:], strict=True):
                if (a[0] == b[0] and a[0] in (lo[0], hi[0])) or (
                    a[1] == b[1] and a[1] in (lo[1], hi[1])
                ):
                    continue
                axis = 0 if a[0] != b[0] else 1
                lo_t, hi_t = min(a[axis], b[axis]), max(a[axis], b[axis])
                spans = sorted(
                    (max(min(p[axis], q[axis]), lo_t), min(max(p[axis], q[axis]), hi_t))
                    for p, q in mine.get(c, [])
                    if _collinear(p, a, b) and _collinear(q, a, b)
                )
                reach = lo_t
                for s0, s1 in spans:
                    if s0 > reach:
                        break
                    reach = max(reach, s1)
                assert reach >= hi_t, (c, a, b)


def _collinear(p, a, b):
    return (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]) == 0
