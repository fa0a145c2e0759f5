"""Polygon domains 80 ulps wide at 7e14: neighbours meet edge to edge (issue 15, far polygons).

A holed square and a hexagon 10 wide at offset 7e14 (an ulp is 0.125 there), 300 sites:
most sites are ulps apart and many cells are empty. Session 58 found the holed square's
cells 7, 55 and 197 meeting the side y = -5 at two floats, (2.625, -5) and (2.75, -5)
(offsets from 7e14): cell 55 overlapped cell 7 by an ulp, and two edge ends were off
their cells' vertices. Those were vertices of the rings the builders return (the side is
a side of the box), not crossings of the polygon clip: the clipped rings of these cells
equal their convex rings. Checked here, exactly: every edge end is a vertex of both its
cells' rings (bit for bit), no two cells overlap (areas in the frame at the offset, where
the shift is exact and every coordinate a multiple of 1/8), every cell is valid, and the
cells' exact area sum is the domain's (the square's sides hold every crossing exactly) or,
on the hexagon's sloped sides, within half an ulp times the perimeter of it (crossings
rounded once, shared by both cells: :mod:`voroforge.kernels.polyclip`).
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
import shapely

import voroforge as vf

from reference import exact_area

OFF = 7e14
HALF = 5.0


def _domain(name):
    s = HALF
    if name == "holed":
        inner = s / 3
        geom = shapely.Polygon(
            [(-s, -s), (s, -s), (s, s), (-s, s)],
            [[(-inner, -inner), (-inner, inner), (inner, inner), (inner, -inner)]],
        )
    else:
        t = np.linspace(0, 2 * np.pi, 7)[:-1]
        geom = shapely.Polygon(np.c_[s * np.cos(t), s * np.sin(t)])
    return shapely.transform(geom, lambda a: a + OFF)


def _sites(geom, n, seed=1):
    rng = np.random.default_rng(seed)
    x0, y0, x1, y1 = geom.bounds
    p = np.c_[rng.uniform(x0, x1, 8 * n), rng.uniform(y0, y1, 8 * n)]
    return p[shapely.contains_xy(geom, p[:, 0], p[:, 1])][:n]


@pytest.fixture(scope="module", params=["holed", "hexagon"])
def built(request):
    geom = _domain(request.param)
    return request.param, geom, vf.voronoi(_sites(geom, 300), geom)


def test_edge_ends_are_both_cells_vertices(built):
    _, _, d = built
    cells = np.asarray(d.cells, dtype=object)
    verts = [{tuple(q) for q in shapely.get_coordinates(c).tolist()} for c in cells]
    coords = np.asarray(d.edges.coords).tolist()
    pairs = np.asarray(d.edges.pairs).tolist()
    assert len(pairs) > 100
    off = [
        (i, j, tuple(q))
        for (a, b), (i, j) in zip(coords, pairs, strict=True)
        for q in (a, b)
        if tuple(q) not in verts[i] or tuple(q) not in verts[j]
    ]
    assert not off, off[:4]


def test_cells_do_not_overlap(built):
    _, _, d = built
    cells = np.asarray(d.cells, dtype=object)
    assert shapely.is_valid(cells).all()
    # the shift to the offset is exact: coordinates stay multiples of 1/8, areas exact
    local = shapely.transform(cells, lambda a: a - OFF)
    a, b = shapely.STRtree(local).query(local, predicate="intersects")
    keep = a < b
    area = shapely.area(shapely.intersection(local[a[keep]], local[b[keep]]))
    bad = np.flatnonzero(area > 0)
    assert not len(bad), [(a[keep][k], b[keep][k]) for k in bad[:4]]


def test_cells_sum_to_the_domain(built):
    name, geom, d = built
    cells = np.asarray(d.cells, dtype=object)
    total = sum((exact_area(c) for c in cells), Fraction(0))
    domain = exact_area(geom)
    if name == "holed":
        assert total == domain
    else:
        # a sloped side's crossings round once each: the cells' outline is within half an
        # ulp of the side
        slack = Fraction(np.spacing(OFF)) / 2 * Fraction(geom.length)
        assert abs(total - domain) <= slack
