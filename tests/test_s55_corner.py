"""A float circle's vertex a few ulps from a box side, under its rounding bound (issue 15).

300 float sites on a circle of radius 1e-7 at (5e5, 4e6), phase 0.75, in a box whose
top-right corner lies inside a triangle's centre: the centre of triangle (132, 133, 134)
lies 2 x-ulps inside the left side, closer than its rounding bound (7.9 ulps), and is never
put on the side (its sites are closer to each other than its reach: a negative reach,
``kernels.cellsides.side_reaches``). The uncut cell of 133 wrote it as a vertex; the cut
cells of 132 and 134 lost their edges to it and met the side instead, since
``kernels.cellcut._inside_box`` took such a centre only when inside by more than its
bound. A hole of 620 units^2 (units of 2^-34), Euler failed. A centre never put on a side
is now inside for every cell when strictly inside, the rule the uncut rings apply.

Checked against exact references, for every algorithm: Euler, valid cells, the cells'
exact (Fraction) areas summing to the box's, every edge off the box shared reversed by the
neighbouring ring, clear samples (4 ulps from every bisector) in their nearest site's cell
(brute force, exact integers), and one diagram from every algorithm. Neighbours: the left
side moved to 3 ulps either side of the centre, and sides and corners a few ulps from other
circles' sliver centres.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
import shapely

import voroforge as vf
from test_issue15_circle_sides import CENTRE, UNIT, _circle, _clear_outside, _local

ALGS = ["delaunay", "fortune", "halfplane"]


def _box(n, phase, left=None, right=None, bottom=None, top=None):
    """The default box of the circle (padded 10%), sides given in local units replaced."""
    pts = _circle(n, phase)
    x0, y0 = pts.min(0)
    x1, y1 = pts.max(0)
    box = [x0 - 0.1 * (x1 - x0), y0 - 0.1 * (y1 - y0), x1 + 0.1 * (x1 - x0), y1 + 0.1 * (y1 - y0)]
    for k, v in enumerate((left, bottom, right, top)):
        if v is not None:
            box[k] = CENTRE[k % 2] + v * UNIT
    return pts, tuple(box)


def _area2(ring):
    """Twice the signed area of a closed ring, exactly."""
    v = ring.tolist()
    return sum(
        Fraction(a) * Fraction(d) - Fraction(c) * Fraction(b)
        for (a, b), (c, d) in zip(v[:-1], v[1:], strict=True)
    )


def _check(d, pts):
    """Euler, validity, exact tiling, rings edge to edge, clear samples in their cells."""
    rep = d.describe()
    assert rep.euler_ok, rep
    cells = np.asarray(d.cells, dtype=object)
    kept = np.array([c is not None and not c.is_empty for c in cells])
    assert shapely.is_valid(cells[kept]).all()
    x0, y0, x1, y1 = d.boundary.bounds
    total = Fraction(0)
    edges = set()
    for c in cells[kept]:
        for part in shapely.get_parts(c):
            assert not part.interiors
            v = shapely.get_coordinates(part.exterior)
            assert ((v[:, 0] >= x0) & (v[:, 0] <= x1) & (v[:, 1] >= y0) & (v[:, 1] <= y1)).all()
            total += _area2(v)
            t = [tuple(q) for q in v]
            edges.update(zip(t[:-1], t[1:], strict=True))
    box2 = 2 * (Fraction(x1) - Fraction(x0)) * (Fraction(y1) - Fraction(y0))
    assert total == box2, float((total - box2) / box2)
    lone = [
        (a, b)
        for a, b in edges
        if (b, a) not in edges
        and not ((a[0] == b[0] and a[0] in (x0, x1)) or (a[1] == b[1] and a[1] in (y0, y1)))
    ]
    assert not lone, lone[:3]
    missed, clear = _clear_outside(d, pts, _local(pts), k=1000)
    assert clear > 300 and missed == 0
    return sorted(_canonical(shapely.get_coordinates(c)) for c in cells[kept])


def _canonical(v):
    """A closed ring's bytes from its lowest vertex on (algorithms start rings apart)."""
    v = v[:-1]
    k = min(range(len(v)), key=lambda j: tuple(v[j]))
    return np.roll(v, -k, axis=0).tobytes()


def _all_algorithms(pts, box):
    first = None
    for alg in ALGS:
        d = vf.voronoi(pts, box, algorithm=alg)
        got = _check(d, pts)
        if first is None:
            first = got
        assert got == first, f"{alg} differs from {ALGS[0]}"
    return d


def test_centre_under_its_bound_inside_a_side_is_every_cells_vertex():
    """The 300 / 0.75 box (right side 9413, top 1552 units: triangle 165's centre beyond
    the corner): cells 132, 133 and 134 meet at the centre (-2060, -848) of their triangle,
    2 ulps inside the left side (before: 133 alone wrote it, a hole, Euler failed)."""
    pts, box = _box(300, 0.75, right=9413.0, top=1552.0)
    assert box[0] == CENTRE[0] - 2062.0 * UNIT
    d = _all_algorithms(pts, box)
    centre = (CENTRE[0] - 2060.0 * UNIT, CENTRE[1] - 848.0 * UNIT)
    for i in (132, 133, 134):
        ring = [tuple(q) for q in shapely.get_coordinates(d.cells[i])]
        assert centre in ring, i


@pytest.mark.parametrize("k", [-3, -2, -1, 0, 1, 3])
def test_left_side_a_few_ulps_from_the_centre(k):
    """The left side ``k`` ulps left of the centre (-2060, -848) (negative: the centre
    past it; 0: on it)."""
    pts, box = _box(300, 0.75, left=-2060.0 - k, right=9413.0, top=1552.0)
    _all_algorithms(pts, box)
