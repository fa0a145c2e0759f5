"""A box corner on the centre of a float circle: every Voronoi vertex crowds it (issue 15).

Sites ``R (cos t, sin t)`` with ``t = (k + 0.17) 2 pi / n``, R = 100, in the box
(0, 0, 1, 1): the circle's centre is the box's corner, and every triangle's centre lies
within 1e-14 of it, while each cut cell's float bisector values are off by ulps of the
sites' distance (~1e-14). Each cell decided alone which of its edges reach which side:
n = 5 a non-convex cell, n = 12 Euler failed (three cells of sites whose exact cells miss
the box), n = 64 an invalid cell (checker37's scan). A cut cell with a centre that close
to a corner is now cut exactly (``kernels/cornercut.py``: exact signs, new vertices by
their names).

Checked against exact references for every algorithm: Euler, valid convex cells, the
cells' exact (Fraction) areas summing to the box's, the non-empty cells those of the exact
cut (``reference.exact_cell``), and each vertex within 1e-13 of an exact vertex, within
2^-40 of its own size within 1e-13 of the corner. Neighbours: the corner moved a few
ulps of the vertices' scale off the centre.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
import shapely

import voroforge as vf

from reference import exact_cell

ALGS = ["delaunay", "fortune", "halfplane"]


def _circle(n, r=100.0):
    t = (np.arange(n) + 0.17) * 2 * np.pi / n
    return np.column_stack((r * np.cos(t), r * np.sin(t)))


def _area2(v):
    """Twice the signed area of a closed ring, exactly."""
    v = v.tolist()
    return sum(
        Fraction(a) * Fraction(d) - Fraction(c) * Fraction(b)
        for (a, b), (c, d) in zip(v[:-1], v[1:], strict=True)
    )


def _near(p, ring):
    """Whether float point ``p`` is one of the exact ``ring``'s vertices, to its scale."""
    for x, y in ring:
        q = (float(x), float(y))
        size = max(abs(q[0]), abs(q[1]))
        # near the corner the cut is exact (nearest doubles, exact centres); farther out
        # a crossing keeps the float formula (off by ulps of the sites)
        tol = 1e-13 if size > 1e-13 else 2.0**-40 * size + 1e-300
        if abs(q[0] - p[0]) <= tol and abs(q[1] - p[1]) <= tol:
            return True
    return False


def _check(pts, box):
    exact = [exact_cell(pts, i, box) for i in range(len(pts))]
    want = {i for i, r in enumerate(exact) if len(r) >= 3}
    for alg in ALGS:
        d = vf.voronoi(pts, box, algorithm=alg)
        rep = d.describe()
        assert rep.euler_ok, (alg, rep)
        cells = np.asarray(d.cells, dtype=object)
        got = {i for i, c in enumerate(cells) if c is not None and not c.is_empty}
        assert got == want, (alg, sorted(got ^ want))
        total = Fraction(0)
        for i in sorted(got):
            c = cells[i]
            assert shapely.is_valid(c) and c.geom_type == "Polygon", (alg, i)
            v = shapely.get_coordinates(c.exterior)
            a2 = _area2(v)
            assert a2 > 0, (alg, i)
            total += a2
            # convex: every turn left or straight, exactly
            u = v[:-1]
            for k in range(len(u)):
                (ax, ay), (bx, by), (cx, cy) = u[k - 2], u[k - 1], u[k]
                turn = (Fraction(bx) - Fraction(ax)) * (Fraction(cy) - Fraction(ay)) - (
                    Fraction(by) - Fraction(ay)
                ) * (Fraction(cx) - Fraction(ax))
                assert turn >= 0, (alg, i, k)
            for p in u:
                assert _near(p, exact[i]), (alg, i, p)
        x0, y0, x1, y1 = box
        box2 = 2 * (Fraction(x1) - Fraction(x0)) * (Fraction(y1) - Fraction(y0))
        assert abs(total - box2) <= Fraction(1, 10**12) * box2, (alg, float(total / box2 - 1))


@pytest.mark.parametrize("n", [5, 12, 64])
def test_corner_on_the_circles_centre(n):
    """checker37's three rows: R = 100, n = 5 / 12 / 64, box (0, 0, 1, 1)."""
    _check(_circle(n), (0.0, 0.0, 1.0, 1.0))


@pytest.mark.parametrize(
    ("n", "box"),
    [
        (5, (-1.0, -1.0, 0.0, 0.0)),
        (12, (-1.0, 0.0, 0.0, 1.0)),
        (7, (0.0, -1.0, 1.0, 0.0)),
        (12, (2.0**-54, 2.0**-54, 1.0, 1.0)),
        (12, (-(2.0**-53), 0.0, 1.0, 1.0)),
        (5, (3 * 2.0**-54, -(2.0**-53), 1.0, 1.0)),
    ],
)
def test_corner_beside_the_circles_centre(n, box):
    """Other corners on the centre, and the corner an ulp or so (of the vertices' 1e-15
    scale) off it."""
    _check(_circle(n), box)
