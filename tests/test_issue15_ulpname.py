"""A merged vertex of sites ulps apart named by one of its exact vertices (issue 15).

Where four sites 1-3 ulps apart have centres that are one point by the merge rule, the
half-plane cells join them and name the vertex by a triple of the four. The first triple by
site number was taken whatever it was: in the ulp cluster c236 (816 seeded clusters of
``test_issue15_ulpid``'s kind) the triple's circle held the fourth site, so its centre was a
vertex of no exact cell, 4 ulps from both of the four's exact vertices; the one cell that
joined them left a gap. The name is now a triple of the four's exact Delaunay triangles.
Checked against exact rational Voronoi vertices of the sites (brute force over triples).
"""

from __future__ import annotations

import itertools
from fractions import Fraction

import numpy as np
import pytest
import shapely

import voroforge as vf
from test_issue15_ulpid import BOX, CENTRE, ULP, _edge_to_edge, _rings

ALGS = ("delaunay", "fortune", "halfplane")
# offsets in ulps (x, y) from CENTRE: clusters of the 816-cluster scan whose rings did not
# meet edge to edge (the seed of each in the scan's numbering)
CLUSTERS = {
    "c55": [[-2, -1], [-2, 0], [-2, 1], [1, -3], [1, 0], [1, 3], [2, -2], [2, 0]],
    "c72": [[-3, -3], [-3, 0], [-3, 2], [-2, 0], [-1, 0], [0, -2], [0, 1], [2, -3]],
    "c236": [[-1, -3], [1, -1], [2, -2], [2, -1], [3, -3], [3, -1]],
    "c253": [[-3, 0], [-2, 1], [-1, 2], [1, -2], [2, -2], [3, -2]],
    "c672": [[-3, 0], [0, 1], [0, 3], [1, -2], [1, 1], [2, 0], [2, 1], [3, 1]],
}


def _exact_vertices(pts):
    """Exact Voronoi vertices of ``pts`` (Fractions) with the sites on each one's circle."""
    p = [(Fraction(float(x)), Fraction(float(y))) for x, y in pts]
    out = {}
    for t in itertools.combinations(range(len(p)), 3):
        (ax, ay), (bx, by), (cx, cy) = (p[k] for k in t)
        d = 2 * (ax * (by - cy) + bx * (cy - ay) + cx * (ay - by))
        if d == 0:
            continue
        a2, b2, c2 = ax * ax + ay * ay, bx * bx + by * by, cx * cx + cy * cy
        ux = (a2 * (by - cy) + b2 * (cy - ay) + c2 * (ay - by)) / d
        uy = (a2 * (cx - bx) + b2 * (ax - cx) + c2 * (bx - ax)) / d
        r2 = (ux - ax) ** 2 + (uy - ay) ** 2
        dist = [(ux - x) ** 2 + (uy - y) ** 2 for x, y in p]
        if min(dist) == r2:
            out[(ux, uy)] = {k for k, e in enumerate(dist) if e == r2}
    return out


def _off_vertices(d, pts, exact):
    """Ring vertices near the cluster an ulp or more from every exact vertex of their cell.

    Per coordinate, strictly more than an ulp: a name that is no vertex of the cell.
    """
    bad = []
    for i, c in enumerate(d.cells):
        if c is None or c.is_empty:
            continue
        for x, y in np.asarray(c.exterior.coords)[:-1]:
            if abs(x - CENTRE[0]) > 1e-6 or abs(y - CENTRE[1]) > 1e-6:
                continue  # a box crossing far out
            ok = any(
                i in own
                and abs(Fraction(float(x)) - ex) <= Fraction(float(ULP[0]))
                and abs(Fraction(float(y)) - ey) <= Fraction(float(ULP[1]))
                for (ex, ey), own in exact.items()
            )
            if not ok:
                bad.append((i, (x - CENTRE[0]) / ULP[0], (y - CENTRE[1]) / ULP[1]))
    return bad


@pytest.mark.parametrize("name", sorted(CLUSTERS))
def test_ulp_cluster_names_are_exact_vertices(name):
    """Rings edge to edge, every vertex near an exact vertex of its cell, all algorithms."""
    pts = CENTRE + np.array(CLUSTERS[name], dtype=np.float64) * ULP
    exact = _exact_vertices(pts)
    got = []
    for alg in ALGS:
        d = vf.voronoi(pts, BOX, algorithm=alg)
        assert d.describe().euler_ok, alg
        assert shapely.is_valid(np.asarray(d.cells, dtype=object)).all(), alg
        lone, area = _edge_to_edge(_rings(d), BOX)
        assert lone == [] and area, (alg, lone)
        assert _off_vertices(d, pts, exact) == [], alg
        got.append(_rings(d))
    assert got[0] == got[1] == got[2]


def test_joined_four_named_by_a_delaunay_triple():
    """The kernel: c236's joined four get a Delaunay triangle's centre, not (2, 3, 4)'s.

    Site 5 asking, site 2 joined: the first of the four's exact Delaunay triangles by site
    number, (2, 3, 5); 5 is inside the circle of (2, 3, 4).
    """
    from voroforge.kernels.halfplane_join import name4
    from voroforge.kernels.vertex import voronoi_vertex

    pts = CENTRE + np.array(CLUSTERS["c236"], dtype=np.float64) * ULP
    xs, ys = pts[:, 0].copy(), pts[:, 1].copy()
    v = voronoi_vertex(5, 3, 4, xs, ys)
    c1 = voronoi_vertex(2, 3, 5, xs, ys)
    c2 = voronoi_vertex(2, 4, 5, xs, ys)
    got = name4(2, 4, 3, 5, *v, *c1, *c2, xs, ys)
    assert got == c1  # (2, 3, 5): 4 is outside its circle; 5 is inside (2, 3, 4)'s
    exact = _exact_vertices(pts)
    assert any(own == {2, 3, 5} for own in exact.values())
    assert not any(own >= {2, 3, 4} for own in exact.values())
