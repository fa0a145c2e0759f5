"""Float circles far out: edges a cut cell lost between a bisector and the box side (issue 15).

1000 float sites on a circle of radius 1e-7 at (5e5, 4e6) (1.3 ulps apart): the hull cells
are wedges from near the centre to the box's sides, and neighbouring wedges' bisectors are
nearly parallel. Cutting the box by them in floats, two of them (site 324's with 321 and
320 at phase 0.40) met past the side, so 320's edge (13 ulps long) was lost, 324's ring
ran along 321's bisector to the side and the cells left a hole (Euler -1; 4 of 240 inputs
of the r = 1e-7 scan, every algorithm). A cut edge that meets a side now ends at the centre
of the Delaunay triangle after it (before it, for an edge entering the box) whenever that
centre lies inside the box by more than its rounding reach: exactly, a segment cannot
leave a convex box and end inside it (``kernels.cellcut._lost_at_side``). Before: Euler -1
and 30 flagged sites; now Euler 1 and 28. At phase 0.90 site 47's cut kept an edge with 52
whose two ends (triangle centres) both lie past the right side, losing 51's 13-ulp edge:
such an edge is given to the next neighbour whose edge reaches the box
(``kernels.cellcut._drop_outside_edges``). Every algorithm gives the same cells.

Checked against exact references: the exact cell of site 324 (Fractions), the largest
distance of a vertex past a bisector of its site and any other (integers), Euler, every
cell valid and inside the box.
"""

from __future__ import annotations

import numpy as np
import pytest
import shapely

import voroforge as vf
from test_issue15_circle_sides import ULP, _circle, _local, _past

# the circle, its exact local frame and the past-a-bisector measure of the side tests
from reference import exact_cell

ALGS = ["delaunay", "fortune", "halfplane"]
#: phases of 1000 sites whose cells left a hole at a box side (Euler -1). Phases 0.05 and 0.80
#: still fail Euler: two side crossings 0.8 ulp off come out of order (docs/exactness.md,
#: still failing)
PHASES = [0.40, 0.90]


@pytest.mark.parametrize("phase", PHASES)
def test_cells_meet_at_the_side(phase):
    """Every algorithm: Euler holds, every cell valid, inside the box, near its exact cell."""
    pts = _circle(1000, phase)
    p = _local(pts)
    first = None
    for alg in ALGS:
        d = vf.voronoi(pts, None, algorithm=alg)
        rep = d.describe()
        assert rep.euler_ok, f"{alg}: {rep}"
        cells = np.asarray(d.cells, dtype=object)
        assert shapely.is_valid(cells).all()
        x0, y0, x1, y1 = d.boundary.bounds
        worst = 0.0
        for i, c in enumerate(d.cells):
            if c is None or c.is_empty:
                continue
            v = shapely.get_coordinates(c)
            assert ((v[:, 0] >= x0) & (v[:, 0] <= x1) & (v[:, 1] >= y0) & (v[:, 1] <= y1)).all()
            if i not in d.unresolved:
                worst = max(worst, _past(_local(v), p, i))
        assert worst <= 8.0, f"{alg}: a vertex {worst:.2f} ulps past its exact cell"
        got = sorted(shapely.get_coordinates(c).tobytes() for c in d.cells if c is not None)
        if first is None:
            first = got
        assert got == first, f"{alg} differs from {ALGS[0]}"


def test_lost_edge_is_back():
    """Phase 0.40, site 324: every exact vertex of its cell within 1 ulp of a float vertex
    (320's edge, 13 ulps long between the box side and the triangle 324-321-320, was lost)."""
    pts = _circle(1000, 0.40)
    p = _local(pts)
    d = vf.voronoi(pts, None)
    box = _local(np.reshape(d.boundary.bounds, (2, 2))).ravel()
    got = _local(shapely.get_coordinates(d.cells[324]))
    for ex, ey in exact_cell(p, 324, box):
        near = np.abs(got[:, 0] - float(ex)) + np.abs(got[:, 1] - float(ey))
        assert near.min() <= 2.0 * ULP, (float(ex) / ULP, float(ey) / ULP)
