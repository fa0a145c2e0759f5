"""Issue 15, periodic diagrams far out in boxes an odd number of ulps across, and on one line.

Far out (4e12) a box 123 ulps tall puts some Voronoi vertices exactly half-way between two
floats; rounding to even went up for a vertex and down for its image by the (odd) period,
and the cell builder kept a vertex in one copy's cell and folded it away in the other's
(Euler 4). The reference here is exact: the sites are integers in units of the finer ulp,
their 3 x 3 copies are triangulated and every triangle around an original is checked
against its neighbours with integer in-circle tests, the vertices are rational
circumcentres.

Sites on one line: their cells reach half a period across it; the margin is now proved
along the line by the chord of the empty disk, so the copies are the line and its two
neighbours, built once after the first try.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
import shapely
from scipy.spatial import Delaunay, cKDTree

import voroforge as vf


def _far_box(off: float, ulps: int):
    y0 = off / 2
    return (off, y0, off + 3.0, y0 + ulps * float(np.spacing(y0)))


def _sites(box, n, seed):
    lo = np.array(box[:2])
    size = np.array([box[2] - box[0], box[3] - box[1]])
    return lo + np.random.default_rng(seed).random((n, 2)) * size


def _exact(sites, box):
    """Exact periodic cells: per site its rational vertices, and whether it borders itself.

    Equal sites share the cell (the engine gives it to the first, the others are empty).
    """
    _, first, back = np.unique(sites, axis=0, return_index=True, return_inverse=True)
    verts, borders = _exact_distinct(sites[first], box)
    back = back.ravel()
    return [verts[k] for k in back], borders[back]


def _exact_distinct(sites, box):
    x0, y0, x1, y1 = box
    u = float(min(np.spacing(x0), np.spacing(y0)))
    ix = (sites[:, 0] - x0) / u
    iy = (sites[:, 1] - y0) / u
    assert (ix == np.round(ix)).all() and (iy == np.round(iy)).all()
    w = (Fraction(x1) - Fraction(x0)) / Fraction(u)
    h = (Fraction(y1) - Fraction(y0)) / Fraction(u)
    assert w.denominator == 1 and h.denominator == 1
    n = len(sites)
    tiles = [(a, b) for a in (-1, 0, 1) for b in (-1, 0, 1)]
    pts = np.concatenate([np.column_stack((ix + a * int(w), iy + b * int(h))) for a, b in tiles])
    pts = pts.astype(np.int64)
    src = np.tile(np.arange(n), len(tiles))
    home = np.repeat([a == 0 and b == 0 for a, b in tiles], n)
    tri = Delaunay(pts.astype(np.float64))
    tree = cKDTree(pts)
    verts = [set() for _ in range(n)]
    for t in tri.simplices[home[tri.simplices].any(axis=1)]:
        (ax, ay), (bx, by), (cx, cy) = (pts[k].tolist() for k in t)
        d = 2 * (ax * (by - cy) + bx * (cy - ay) + cx * (ay - by))
        assert d != 0
        a2, b2, c2 = ax * ax + ay * ay, bx * bx + by * by, cx * cx + cy * cy
        ux = Fraction(a2 * (by - cy) + b2 * (cy - ay) + c2 * (ay - by), d)
        uy = Fraction(a2 * (cx - bx) + b2 * (ax - cx) + c2 * (bx - ax), d)
        r2 = (ux - ax) ** 2 + (uy - ay) ** 2
        for k in tree.query_ball_point([float(ux), float(uy)], float(r2) ** 0.5 + 2):
            qx, qy = pts[k].tolist()
            assert (ux - qx) ** 2 + (uy - qy) ** 2 >= r2, "the triangulation is not Delaunay"
        for k in t:
            if home[k]:
                verts[src[k]].add((x0 + ux * Fraction(u), y0 + uy * Fraction(u)))
    start, nbr = tri.vertex_neighbor_vertices
    orig = np.flatnonzero(home)
    borders = np.array([(src[nbr[start[k] : start[k + 1]]] == i).any() for i, k in enumerate(orig)])
    return verts, borders


def _borders_itself(cell, box) -> bool:
    """Whether a ring holds an edge and the same edge shifted by a period, reversed."""
    w, h = box[2] - box[0], box[3] - box[1]
    xy = shapely.get_coordinates(cell)
    edges = {(tuple(a), tuple(b)) for a, b in zip(xy[:-1], xy[1:], strict=True)}
    for a, b in edges:
        for sx, sy in ((0.0, h), (0.0, -h), (w, 0.0), (-w, 0.0)):
            if ((b[0] + sx, b[1] + sy), (a[0] + sx, a[1] + sy)) in edges:
                return True
    return False


@pytest.mark.parametrize(
    ("off", "ulps", "seed"), [(4e12, 123, 1), (4e12, 123, 2), (1e12, 61, 3), (1e13, 41, 4)]
)
def test_odd_period_far_out_matches_exact(off, ulps, seed):
    box = _far_box(off, ulps)
    d = vf.voronoi(_sites(box, 300, seed), box, periodic=True)
    report = str(d.describe())
    assert "FAILED" not in report.split("Euler")[1].split("\n")[0], report
    assert shapely.is_valid(d.cells).all()
    verts, borders = _exact(d.sites, box)
    w, h = Fraction(box[2]) - Fraction(box[0]), Fraction(box[3]) - Fraction(box[1])
    ux, uy = float(np.spacing(box[0])), float(np.spacing(box[1]))
    x0, y0 = Fraction(box[0]), Fraction(box[1])
    for i, cell in enumerate(d.cells):
        if d.duplicate_of[i] >= 0:
            assert shapely.is_empty(cell)
            continue
        # every corner is within an ulp of an exact vertex of its cell, or of an image
        shifts = [(a * w, b * h) for a in (-1, 0, 1) for b in (-1, 0, 1)]
        exact = [(vx + sx, vy + sy) for vx, vy in verts[i] for sx, sy in shifts]
        near = np.array([(float((ex - x0) / ux), float((ey - y0) / uy)) for ex, ey in exact])
        for px, py in shapely.get_coordinates(cell)[:-1].tolist():
            at = np.array([float((Fraction(px) - x0) / ux), float((Fraction(py) - y0) / uy)])
            ex, ey = exact[int(np.abs(near - at).max(axis=1).argmin())]
            gap = max(abs(Fraction(px) - ex) / Fraction(ux), abs(Fraction(py) - ey) / Fraction(uy))
            assert gap <= 1, (i, px, py, float(gap))
        if _borders_itself(cell, box):
            assert borders[i], f"cell {i} borders its own image; the exact cell does not"
    area = shapely.area(d.cells).sum() / ((box[2] - box[0]) * (box[3] - box[1]))
    assert abs(area - 1.0) < 1e-9


@pytest.mark.parametrize("n", [1000, 4000])
def test_sites_on_one_line_exact_strips_two_builds(n, periodic_builds):
    sizes = periodic_builds
    rng = np.random.default_rng(n)
    # dyadic x: the midpoints, the strips' sides, are floats
    x = np.unique(np.floor(rng.random(n) * 2.0**20) / 2.0**20)
    sites = np.column_stack((x, np.full(len(x), 0.5)))
    d = vf.voronoi(sites, (0.0, 0.0, 1.0, 1.0), periodic=True)
    # the line and its two neighbouring copies, no wider along the line (one build: the
    # line's margins are set up front, periodic_lines; was the line alone first)
    assert len(sizes) == 1 and sizes[0] <= 4 * len(x), sizes
    # exact: site i's cell is the strip between the midpoints to its neighbours (cyclic)
    left = (x + np.r_[x[-1] - 1.0, x[:-1]]) / 2
    right = (x + np.r_[x[1:], x[0] + 1.0]) / 2
    for i, cell in enumerate(d.cells):
        b = shapely.bounds(cell)
        if left[i] < 0.0 or right[i] > 1.0:  # the strip across x = 0 wraps unwrapped
            assert abs(shapely.area(cell) - (right[i] - left[i])) < 1e-15
            continue
        assert tuple(b) == (left[i], 0.0, right[i], 1.0), (i, b)
