"""Half-plane settling gives the Delaunay dual's cells on float-rotated lattices far out.

A 9 x 9 unit lattice rotated by a Pythagorean ``(a / c, b / c)`` rounded to floats and moved
to ``(off, -0.3 off)`` has squares that are cocircular only to rounding: the exact diagram
has Voronoi edges a fraction of an ulp long, which the one merge rule contracts (docs/
exactness.md "How vertex identity is decided"). The half-plane cells kept them (3-4-5 at
1e12: 208 neighbour pairs against the dual's 156, no cell bit-equal; checker30 F1): the
settling skipped a site within the merge band of a vertex's circle as outside by the float
test, a square's diagonal at ``2 (1 + 1.6e-9) r`` was past the search's reach, and a four
whose centres are not one point pair by pair was decided by a local ``incircle`` where the
dual joins adjacent centres. Now such a site is tested for joining, watched, and a cell
whose four does not join is left to the dual.

Reference: the default's cells bit for bit (and the sweep's), and each cell within a few
ulps of the magnitude (Hausdorff) of its exact cell, the box cut by every other site's
half-plane in Fractions: a contracted edge is shorter than its ends' proven rounding bounds
(about an ulp each here), and a named vertex lies within its bound of its exact centre.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
import shapely

import voroforge as vf

# (a, b, c) of the rotation and the offset: checker30 F1's three, and neighbours of them
CASES = [
    ((3, 4, 5), 1e12, 9),
    ((5, 12, 13), 1e9, 9),
    ((20, 21, 29), 1e6, 9),
    ((3, 4, 5), 1e3, 9),
    ((8, 15, 17), 1e7, 6),
    ((7, 24, 25), 1e11, 9),
    ((12, 35, 37), 1e13, 6),
    ((20, 21, 29), 1e9, 9),
]
# Hausdorff distance of a cell from its exact cell, in ulps of the offset: a vertex named
# within its rounding bound (~1 ulp) of its class's member, whose exact centre is within
# the bounds of the contracted edge's other end (~2 ulps)
EXACT_ULPS = 4.0


def _lattice(rot, off, n):
    a, b, c = rot
    cs, sn = a / c, b / c
    h = n // 2
    u, v = np.meshgrid(np.arange(-h, n - h, dtype=float), np.arange(-h, n - h, dtype=float))
    u, v = u.ravel(), v.ravel()
    pts = np.column_stack((u * cs - v * sn, u * sn + v * cs)) + [off, -0.3 * off]
    box = (off - 6, -0.3 * off - 6, off + 6, -0.3 * off + 6)
    return pts, box


def _equal(c1, c2):
    return c1.is_empty == c2.is_empty and (
        c1.is_empty or shapely.equals_exact(shapely.normalize(c1), shapely.normalize(c2), 0.0)
    )


def _pairs(d):
    ptr, idx = d.neighbors
    return {(i, int(j)) for i in range(len(ptr) - 1) for j in idx[ptr[i] : ptr[i + 1]]}


@pytest.mark.parametrize(("rot", "off", "n"), CASES)
def test_halfplane_cells_are_the_duals(rot, off, n):
    pts, box = _lattice(rot, off, n)
    want = vf.voronoi(pts, box)
    for alg in ("halfplane", "fortune"):
        got = vf.voronoi(pts, box, algorithm=alg)
        assert _pairs(got) == _pairs(want), alg
        assert all(_equal(a, b) for a, b in zip(got.cells, want.cells, strict=True)), alg


def test_permuted_input():
    """The same, with the sites in another order (names follow the input's ranks)."""
    pts, box = _lattice((3, 4, 5), 1e12, 9)
    pts = pts[np.random.default_rng(5).permutation(len(pts))]
    want = vf.voronoi(pts, box)
    got = vf.voronoi(pts, box, algorithm="halfplane")
    assert _pairs(got) == _pairs(want)
    assert all(_equal(a, b) for a, b in zip(got.cells, want.cells, strict=True))


def _exact_cell(pts, q, i, box):
    """Site ``i``'s cell in the box, exactly: the box cut by every other site's half-plane.

    The sites are taken nearest first; one farther than twice the cell's radius so far
    (with a margin for the float distances) cannot cut it, nor can any after it.
    """
    x0, y0, x1, y1 = (Fraction(v) for v in box)
    ring = [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]
    ax, ay = q[i]
    dist = np.hypot(pts[:, 0] - pts[i, 0], pts[:, 1] - pts[i, 1])
    for j in np.argsort(dist, kind="stable"):
        if j == i:
            continue
        far = max(abs(float(x - ax)) + abs(float(y - ay)) for x, y in ring)
        if dist[j] > 2.0 * far * (1 + 1e-6):
            break
        bx, by = q[j]
        # p is nearer a than b: f(p) = 2 (b - a) . p - |b|^2 + |a|^2 <= 0
        gx, gy, h = 2 * (bx - ax), 2 * (by - ay), bx * bx + by * by - ax * ax - ay * ay
        f = [gx * x + gy * y - h for x, y in ring]
        if max(f) <= 0:
            continue
        out = []
        for k in range(len(ring)):
            p, fp = ring[k], f[k]
            r, fr = ring[(k + 1) % len(ring)], f[(k + 1) % len(ring)]
            if fp <= 0:
                out.append(p)
            if (fp < 0 < fr) or (fr < 0 < fp):
                t = fp / (fp - fr)
                out.append((p[0] + t * (r[0] - p[0]), p[1] + t * (r[1] - p[1])))
        ring = out
    return ring


@pytest.mark.parametrize(("rot", "off", "n"), CASES[:3])
def test_cells_near_the_exact_ones(rot, off, n):
    pts, box = _lattice(rot, off, n)
    d = vf.voronoi(pts, box, algorithm="halfplane")
    q = [(Fraction(x), Fraction(y)) for x, y in pts]
    ox, oy = Fraction(off), Fraction(-0.3 * off)
    ulp = np.spacing(off)
    for i, cell in enumerate(d.cells):
        exact = shapely.Polygon(
            [(float(x - ox), float(y - oy)) for x, y in _exact_cell(pts, q, i, box)]
        )
        near = shapely.Polygon(
            [(float(Fraction(x) - ox), float(Fraction(y) - oy)) for x, y in cell.exterior.coords]
        )
        assert shapely.hausdorff_distance(near, exact) <= EXACT_ULPS * ulp, i
