"""Five sites an ulp apart on a diagonal at (2.25, 3.7) in a 10 x 10 box (issue 15).

Along ``(1, 1)`` the sites' bisectors are the lines ``x + y = c``, one ulp of 5.95 apart: the
middle sites' cells are strips that hold no float point where they cross the box, so they
may be flagged (``Diagram.unresolved``) and left empty. Before, three middle sites were
flagged and their strip left as a gap (Euler's count 2, "ne" and "sw"); the neighbours'
cells must meet. Checked exactly: every edge off the box is its neighbour's reversed, bit
for bit, the rings' areas sum exactly to the box's (Fractions), every site not flagged is
in its cell, and every float point of the box's bottom side between the outer sites' exact
crossings lies in the cell of an exactly nearest site (Fractions), unless every site
nearest to it is flagged.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
import shapely

import voroforge as vf
from test_issue15_polygon_domains import _ulps_from
from test_issue15_ulpid import _edge_to_edge, _rings

ALGS = ("delaunay", "fortune", "halfplane")
BOX = (0.0, 0.0, 10.0, 10.0)


@pytest.mark.parametrize("direction", [(1, 1), (-1, -1), (1, -1), (-1, 1)])
@pytest.mark.parametrize("count", [3, 5])
def test_diagonal_strips_tile_the_box(direction, count):
    pts = _ulps_from((2.25, 3.7), direction, count)
    got = []
    for alg in ALGS:
        d = vf.voronoi(pts, BOX, algorithm=alg)
        r = d.describe()
        assert r.euler_ok, (alg, str(r))
        cells = np.asarray(d.cells, dtype=object)
        assert shapely.is_valid(cells).all(), alg
        lone, exact = _edge_to_edge(_rings(d), BOX)
        assert lone == [] and exact, (alg, lone)
        held = shapely.intersects(cells, shapely.points(pts))
        flagged = set(d.unresolved.tolist())
        assert all(held[i] or i in flagged for i in range(count)), alg
        # the bottom side: each float between the outer sites' exact crossings is in a cell
        # of a site exactly nearest to it
        sites = [(Fraction(x), Fraction(y)) for x, y in pts]
        xs = [x for x, _ in sites]
        lo = float(min(xs) + min(y for _, y in sites)) - 4 * np.spacing(6.0)
        hi = float(max(xs) + max(y for _, y in sites)) + 4 * np.spacing(6.0)
        x = lo
        while x <= hi:
            q = (Fraction(x), Fraction(0))
            dist = [(sx - q[0]) ** 2 + (sy - q[1]) ** 2 for sx, sy in sites]
            near = {i for i, v in enumerate(dist) if v == min(dist)}
            mine = {i for i in range(count) if shapely.intersects(cells[i], shapely.Point(x, 0))}
            # (a point nearest only to flagged sites, whose strips floats cannot hold as a
            # ring, goes to a neighbour)
            assert mine & near or near <= flagged, (alg, x, mine, near)
            x = float(np.nextafter(x, np.inf))
        got.append(_rings(d))
    assert got[0] == got[1] == got[2]
