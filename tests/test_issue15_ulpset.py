"""One neighbour set for every algorithm where float vertices are ulps apart (issue 15).

The promised neighbour set is the exact diagram's after the one merge rule
(:func:`voroforge.kernels.vertex.same_vertex`, docs/exactness.md "How vertex identity is
decided"): two vertices closer than their proven rounding bounds are one vertex, so an
edge that short is contracted and its two cells are not neighbours. The Delaunay dual
merges adjacent centres by it, and the half-plane cells join a site near a vertex's circle
by it (``halfplane_settle._joins``: all four centres one point pair by pair) or, where it
does not join, leave the cell to the dual (at 1e3 with (0.6, 0.8) the square of sites 337,
338, 357, 358 has Delaunay centres 3.4e-13 apart, one vertex by the rule, and non-Delaunay
ones 1.1e-13 apart with bounds of 4e-14: half-plane kept an edge the dual merges). An
integer lattice rotated by a float cosine and sine and moved far out has squares that are
cocircular only to rounding: the exact diagram has edges an ulp long there (a 20 x 20
lattice at 1e6: 1,049 neighbour pairs, 289 of them such edges), which every algorithm
contracts (760 pairs). A half-plane settling that kept the edges floats could order gave
1,049 while the others gave 760.

Reference: the exact neighbour pairs (the bisector of two sites clipped by every other
site's half-plane in Fractions, a positive length left inside the box), less those whose
exact edge ends (the centres of the two sites with the sites bounding the edge) are one
vertex by the merge rule, computed from those centres' float values and proven bounds;
each float centre is checked to lie within its bound of the exact one.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

import voroforge as vf
from voroforge.kernels.vertex import same_vertex, voronoi_vertex, voronoi_vertex_error

ALGS = ("delaunay", "fortune", "halfplane")
# (cos, sin) of the rotation, each rounded to a float: the lattice is not exact
ROTATIONS = ((0.6, 0.8), (0.28, 0.96), (5 / 13, 12 / 13))


def _lattice(n, rotation, offset):
    c, s = rotation
    ij = np.array([(i, j) for i in range(n) for j in range(n)], dtype=np.float64)
    return np.column_stack([c * ij[:, 0] - s * ij[:, 1], s * ij[:, 0] + c * ij[:, 1]]) + offset


def _pairs(d):
    ptr, idx = d.neighbors
    return {
        (min(i, int(j)), max(i, int(j)))
        for i in range(len(ptr) - 1)
        for j in idx[ptr[i] : ptr[i + 1]]
        if i != j
    }


def _exact_edges(pts, box):
    """Exact Voronoi edges of positive length inside ``box``: ``{(i, j): (k_lo, k_hi)}``.

    The bisector of ``i, j`` is ``m + t u``; each other site ``k`` bounds ``t`` by an exact
    half-plane, the box by four more (``k`` -1). ``k_lo``, ``k_hi``: the sites bounding the
    surviving segment at its two ends, whose centres with ``i, j`` are its end vertices.
    """
    q = [(Fraction(x), Fraction(y)) for x, y in pts]
    x0, y0, x1, y1 = (Fraction(v) for v in box)
    out = {}
    for i in range(len(q)):
        for j in range(i + 1, len(q)):
            (ax, ay), (bx, by) = q[i], q[j]
            mx, my = (ax + bx) / 2, (ay + by) / 2
            ux, uy = ay - by, bx - ax
            lo, hi, klo, khi = None, None, -1, -1
            cons = [(ux, x0 - mx, -1), (-ux, mx - x1, -1), (uy, y0 - my, -1), (-uy, my - y1, -1)]
            for k, (cx, cy) in enumerate(q):
                if k != i and k != j:  # |p - a|^2 <= |p - c|^2 at p = m + t u
                    gx, gy = 2 * (cx - ax), 2 * (cy - ay)
                    rhs = cx * cx + cy * cy - ax * ax - ay * ay - gx * mx - gy * my
                    cons.append((-(gx * ux + gy * uy), -rhs, k))
            empty = False
            for a, r, k in cons:  # a t >= r
                if a == 0:
                    empty = empty or r > 0
                elif a > 0 and (lo is None or r / a > lo):
                    lo, klo = r / a, k
                elif a < 0 and (hi is None or r / a < hi):
                    hi, khi = r / a, k
            if not empty and lo < hi:
                out[(i, j)] = (klo, khi)
    return out, q


def _contracted_reference(pts, box):
    """The exact pairs less those whose edge the merge rule contracts, and how many went."""
    edges, q = _exact_edges(pts, box)
    xs, ys = pts[:, 0].copy(), pts[:, 1].copy()
    keep, gone = set(), 0
    for (i, j), ends in edges.items():
        if min(ends) < 0:
            keep.add((i, j))  # an end on the box: a crossing, no merge by this rule
            continue
        got = []
        for k in ends:
            vx, vy = voronoi_vertex(i, j, k, xs, ys)
            e = voronoi_vertex_error(i, j, k, xs, ys)
            ex, ey = _exact_centre(q[i], q[j], q[k])
            assert abs(Fraction(vx) - ex) + abs(Fraction(vy) - ey) <= Fraction(e)  # proven
            got.append((vx, vy, e))
        (v1x, v1y, e1), (v2x, v2y, e2) = got
        r = abs(v1x - xs[i]) + abs(v1y - ys[i])
        if same_vertex(v1x, v1y, e1, v2x, v2y, e2, r):
            gone += 1
        else:
            keep.add((i, j))
    return keep, gone, len(edges)


def _exact_centre(a, b, c):
    (ax, ay), (bx, by), (cx, cy) = a, b, c
    d = 2 * (ax * (by - cy) + bx * (cy - ay) + cx * (ay - by))
    a2, b2, c2 = ax * ax + ay * ay, bx * bx + by * by, cx * cx + cy * cy
    ux = (a2 * (by - cy) + b2 * (cy - ay) + c2 * (ay - by)) / d
    uy = (a2 * (cx - bx) + b2 * (ax - cx) + c2 * (bx - ax)) / d
    return ux, uy


@pytest.mark.parametrize(
    ("rotation", "offset"),
    [(rot, off) for rot in ROTATIONS for off in (0.0, 1e3, 1e6, 1e7)],
)
def test_rotated_lattice_one_neighbour_set(rotation, offset):
    """A 20 x 20 lattice: every algorithm gives the same neighbour pairs (a lattice's 760)
    and the same vertices inside the box, bit for bit (a merged square named alike: by
    the one canonical triple, not by one of its exact vertices in one algorithm only)."""
    pts = _lattice(20, rotation, offset)
    got, cells = [], []
    for alg in ALGS:
        d = vf.voronoi(pts, algorithm=alg)
        assert d.describe().euler_ok, alg
        assert len(d.unresolved) == 0, alg
        got.append(_pairs(d))
        x0, y0, x1, y1 = d._domain.bounds
        cells.append(
            [
                {(x, y) for x, y in np.asarray(c.exterior.coords) if x0 < x < x1 and y0 < y < y1}
                for c in d.cells
            ]
        )
    assert got[0] == got[1] == got[2]
    assert cells[0] == cells[1] == cells[2]
    assert len(got[0]) == 760  # the lattice edges, 2 * 19 * 20: no square keeps a diagonal


@pytest.mark.parametrize("rotation", ROTATIONS)
@pytest.mark.parametrize("offset", [1e6, 1e7])
def test_neighbours_are_the_exact_ones_after_contraction(rotation, offset):
    """A 6 x 6 lattice far out: each algorithm's pairs are the exact diagram's after the
    merge rule contracts the edges shorter than their ends' rounding bounds (some are)."""
    pts = _lattice(6, rotation, offset)
    box = vf.voronoi(pts, algorithm="delaunay")._domain.bounds
    want, gone, exact = _contracted_reference(pts, box)
    assert gone > 0 and len(want) + gone == exact
    for alg in ALGS:
        assert _pairs(vf.voronoi(pts, algorithm=alg)) == want, alg
