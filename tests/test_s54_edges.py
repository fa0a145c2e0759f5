"""Shared edges never name an empty cell (checker35 F1).

In a power diagram whose light sites lie exactly on their heavy neighbours' radical lines (a
lattice with weights 1 and 0 in a checkerboard), the light cells are empty (segments or
points), and the builders named them across the edge their two neighbours share: the pair
``(0, 1)`` with cell 1 empty where cells 0 and 2 meet. The reference: neighbours from the
length of the shapely cells' shared boundary.
"""

import numpy as np
import pytest
import shapely

import voroforge as vf


def _reference_pairs(d, tol=1e-9):
    cells = d.cells
    tree = shapely.STRtree(cells)
    out = set()
    for i, j in tree.query(cells, predicate="intersects").T.tolist():
        if i < j and not cells[i].is_empty and not cells[j].is_empty:
            if shapely.length(shapely.intersection(cells[i].boundary, cells[j].boundary)) > tol:
                out.add((i, j))
    return out


def _check(d):
    pairs = {tuple(p) for p in d.edges.pairs.tolist()}
    assert pairs == _reference_pairs(d)
    empty = shapely.is_empty(d.cells)
    assert not empty[d.edges.pairs].any()
    for (i, j), s in zip(d.edges.pairs.tolist(), d.edges.coords, strict=True):
        seg = shapely.LineString(s)
        for c in (i, j):  # the edge lies on both cells' boundaries
            assert d.cells[c].boundary.distance(seg.interpolate(0.5, normalized=True)) < 1e-12
    ip, nb = d.neighbors
    for i in range(len(d.sites)):
        for j in nb[ip[i] : ip[i + 1]].tolist():
            assert i in nb[ip[j] : ip[j + 1]].tolist()


@pytest.mark.parametrize("shape", [(4, 4), (5, 7), (6, 3)])
@pytest.mark.parametrize("off", [0.0, 1024.0])
def test_checkerboard_power_ties(shape, off):
    g = np.array([(i, j) for i in range(shape[0]) for j in range(shape[1])], float) + off
    w = np.where((np.arange(len(g)) // shape[1] + np.arange(len(g)) % shape[1]) % 2 == 0, 1.0, 0.0)
    box = (off - 0.5, off - 0.5, off + shape[0] - 0.5, off + shape[1] - 0.5)
    d = vf.power(g, w, box)
    assert (d.areas[w == 0] == 0).any()  # light cells on the box's sides are empty
    _check(d)


def test_three_on_a_line():
    # the middle site lies on the outer two's radical line: its cell is that line's piece
    d = vf.power([[0, 0], [0, 1], [0, 2]], [1.0, 0.0, 1.0], (-1, -1, 1, 3))
    assert d.areas[1] == 0
    assert d.edges.pairs.tolist() == [[0, 2]]
    _check(d)


def test_plain_diagram_untouched():
    p = np.random.default_rng(4).random((200, 2))
    d = vf.voronoi(p)
    _check(d)
