"""One decision per group of four sites in the half-plane settling (issue 15).

Sites 1-3 ulps apart (the clusters of ``test_issue15_ulpid``): the half-plane cells settle
each ring alone, and a site near the circle of a cell's vertex joins it (the edge it
would add or shorten is rounding noise) when the centres of the four sites' triples are
one point by the merge rule. That rule is not transitive, and each cell tested it from
its own vertex, so two cells at one group could decide it differently: one merged an
edge an ulp long that its neighbour kept, one vertex stood at two points, and Euler's
count failed with no site flagged. The group is now decided from its four centres, pair
by pair, at a scale of the four (``halfplane_settle._joins``): the same from every cell.
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest
import shapely

import voroforge as vf
from test_issue15_ulpid import BOX, CENTRE, ULP, _edge_to_edge, _rings
from voroforge.kernels.halfplane_settle import _joins
from voroforge.kernels.vertex import voronoi_vertex_lazy

ALGS = ("delaunay", "fortune", "halfplane")

# offsets in ulps (x, y) from CENTRE; each failed Euler's count with no site flagged for
# every algorithm (one cell merged an edge its neighbour kept); from the seeded scan of
# 816 clusters (/tmp/lead/s41/scan_ulp.py, clusters 142, 183, 345, 425, 605, 769)
FIXED = {
    "c142": [[-3, -3], [-1, -1], [0, -3], [0, 0], [1, -3], [1, 1], [2, -3], [2, 0]],
    "c183": [[-3, 3], [-1, 3], [0, -3], [1, -2], [2, -2], [2, -1], [3, 0]],
    "c345": [[-3, 2], [-3, 3], [-2, -3], [-1, -1], [-1, 1], [0, -3], [1, -1], [2, -3]],
    "c425": [[-3, 0], [-1, 3], [0, -2], [1, 3], [2, 0], [2, 3], [3, 0]],
    "c605": [[-2, -3], [-2, -2], [-1, -2], [0, -2], [3, -3], [3, -1]],
    "c769": [[-3, -3], [-3, 2], [-1, -2], [-1, -1], [0, -3], [1, -2], [1, 3], [3, -1]],
}


@pytest.mark.parametrize("alg", ALGS)
@pytest.mark.parametrize("name", sorted(FIXED))
def test_cluster_rings_meet_edge_to_edge(name, alg):
    """Euler's count, rings exactly edge to edge and tiling the box, valid, each distinct
    site in its own cell, no site flagged."""
    pts = CENTRE + np.array(FIXED[name], dtype=np.float64) * ULP
    d = vf.voronoi(pts, BOX, algorithm=alg)
    r = d.describe()
    assert r.euler_ok, str(r)
    lone, exact = _edge_to_edge(_rings(d), BOX)
    assert lone == [] and exact, lone
    cells = np.asarray(d.cells, dtype=object)
    assert shapely.is_valid(cells).all()
    assert len(d.unresolved) == 0
    assert shapely.intersects(cells, shapely.points(pts))[d.duplicate_of < 0].all()


def _answers(quad, xs, ys):
    """``_joins`` asked from every cell of ``quad`` about every vertex it may have there."""
    got = set()
    for i in quad:
        rest = [s for s in quad if s != i]
        for a, b, x in itertools.permutations(rest):
            vx, vy, ev, lv = voronoi_vertex_lazy(i, a, b, xs, ys)
            if not (np.isfinite(vx) and np.isfinite(vy)):
                continue
            got.add(bool(_joins(i, a, b, x, vx, vy, ev, lv, xs, ys)[0]))
    return got


def test_a_group_of_four_is_decided_alike_from_each_cell():
    """Every group of four sites of the clusters above gets one answer, whichever of its
    cells asks and from whichever of its vertices (the answer before depended on both)."""
    mixed = 0
    for off in FIXED.values():
        pts = CENTRE + np.array(off, dtype=np.float64) * ULP
        xs = pts[:, 0].copy()
        ys = pts[:, 1].copy()
        for quad in itertools.combinations(range(len(pts)), 4):
            mixed += len(_answers(quad, xs, ys)) > 1
    assert mixed == 0


def test_a_square_joins_from_each_cell():
    """Four corners of an axis-aligned square (exactly cocircular): joined from every cell."""
    pts = CENTRE + np.array([[0.0, 0.0], [2.0, 0.0], [0.0, 2.0], [2.0, 2.0]]) * ULP
    assert _answers((0, 1, 2, 3), pts[:, 0].copy(), pts[:, 1].copy()) == {True}
