"""Issue 15: a Delaunay triangle's centre past a box corner is clipped like any other vertex.

Sites on a float circle of radius 1e-7 at (5e5, 4e6), 257 at phase 0.05: site 94 is pulled
inside the circle by rounding, and its triangle with 93 and 96 is a sliver whose centre
lies 40 ulps of x past the left side and 32 past the top of the sites' padded box. When
that triangle is its own class (a join rule that leaves the slivers of a far circle
unmerged, cocjoin, nineteenth round), the cut cell of site 94 kept the centre: its two
bisectors meet the box within rounding of the corner, the float cut lost both crossings,
and ``cellcut._past_side_crossings`` stood in for a centre past one side only. A centre past
a corner now gives the two canonical crossings and the corner between them when they lie
on its two sides. The cells are built here from every triangle's own centre (each its own
class), as such a join rule leaves them, and checked against the box.
"""

from __future__ import annotations

import numpy as np
import shapely

from voroforge.kernels import cells
from voroforge.kernels.cellcut import side_reaches
from voroforge.kernels.centers import circumcenters
from voroforge.kernels.delaunay import triangulate_sorted

CENTRE = (5e5, 4e6)


def _circle(n, phase):
    t = np.arange(n) * (2.0 * np.pi / n) + phase
    return np.column_stack((1e-7 * np.cos(t), 1e-7 * np.sin(t))) + CENTRE


def _own_centre_rings(pts, box):
    """Cells of ``pts`` in ``box`` with every triangle its own class (no merge)."""
    xs = np.ascontiguousarray(pts[:, 0])
    ys = np.ascontiguousarray(pts[:, 1])
    order, sx, sy, tri, he, _, ok = triangulate_sorted(xs, ys)
    assert ok
    sx = np.ascontiguousarray(sx)
    sy = np.ascontiguousarray(sy)
    cx, cy, err, _ = circumcenters(sx, sy, tri, he)
    cls = np.arange(tri.shape[0] // 3)
    reach = side_reaches(sx, sy, tri, cls, cx, cy, err, box)
    kmap = np.arange(len(pts))[order]
    args = (cx, cy, err, reach, cls, box, order, kmap, True)
    _, (coords, lengths, _) = cells._build(sx, sy, tri, he, *args)
    return coords, lengths, (cx, cy)


def test_sliver_centre_past_a_corner_is_clipped():
    pts = _circle(257, 0.05)
    lo = pts.min(0)
    hi = pts.max(0)
    pad = 0.1 * (hi - lo)
    box = np.array([*(lo - pad), *(hi + pad)])
    coords, lengths, (cx, cy) = _own_centre_rings(pts, box)
    # the case: a triangle's own centre strictly past the top-left corner
    past = (cx < box[0]) & (cy > box[3]) & np.isfinite(cx)
    assert past.any()
    inside = (
        (coords[:, 0] >= box[0])
        & (coords[:, 0] <= box[2])
        & (coords[:, 1] >= box[1])
        & (coords[:, 1] <= box[3])
    )
    assert inside.all(), coords[~inside]
    # site 94's cell meets the left side where its neighbours' cells do (both bisectors'
    # crossings round to one point there), and is a valid ring
    ring = coords[lengths[94] : lengths[95]]
    assert shapely.is_valid(shapely.Polygon(ring))
    side = {tuple(v) for v in ring if v[0] == box[0]}
    assert side
    for j in (93, 96):
        assert side <= {tuple(v) for v in coords[lengths[j] : lengths[j + 1]]}
