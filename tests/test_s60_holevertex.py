"""A bisector through (or ulps beside) a box corner or a domain vertex, every algorithm alike.

Found by hypothesis (``test_properties``, issue 15): sites (0, 0), (1, 1) in the box
(-0.2, -0.2, 1.2, 1.2) with a triangular hole. The box corners (1.2, -0.2) and (-0.2, 1.2)
lie 2**-54 inside site 0's side of the bisector x + y = 1 (their float sums are exactly
1 - 2**-54), so the true cell 0 has edges 2 ulps long along the right and top sides. The
half-plane cut rounded those corners' bisector values to 0 and kept them as vertices on
the bisector: its cell 0 lost both short sides, ended at the corners while cell 1 ended at
the true crossings, crossed the hole's edge an ulp away from where cell 1 did, and the
diagram had no shared edge at all. The hole's vertex (0.675, 0.325) is not on the bisector
(its exact sum is 1 + 2**-54; its float sum rounds to 1).

Every case here runs with the three algorithms: each diagram passes ``validate_diagram``,
neighbours are symmetric and the same for all three, the cells are the same vertex for
vertex (bit for bit), and the shared edges are the same.
"""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from shapely.geometry import Polygon

import voroforge as vf

from validate import validate_diagram

_ALGORITHMS = ("delaunay", "fortune", "halfplane")


def _padded_box(pts, pad=0.2):
    """The box of the property test's random profile: the sites' box padded by ``pad``."""
    lo, hi = pts.min(0), pts.max(0)
    size = np.maximum(hi - lo, np.maximum(np.abs(lo), 1.0) * 1e-3)
    (x0, y0), (x1, y1) = lo - pad * size, hi + pad * size
    return float(x0), float(y0), float(x1), float(y1)


def _with_triangle_hole(b):
    x0, y0, x1, y1 = b
    cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
    w, h = (x1 - x0) / 8, (y1 - y0) / 8
    hole = [(cx - w, cy - h), (cx + w, cy - h), (cx, cy + h)]
    return Polygon([(x0, y0), (x1, y0), (x1, y1), (x0, y1)], [hole])


def _pairs(d):
    indptr, indices = d.neighbors
    out = set()
    for i in range(len(indptr) - 1):
        for j in indices[indptr[i] : indptr[i + 1]]:
            out.add((i, int(j)))
    return out


def _vertex_sets(d):
    return [
        frozenset(map(tuple, shapely.get_coordinates(c).tolist())) if not c.is_empty else None
        for c in d.cells
    ]


def _check(pts, domain):
    pts = np.asarray(pts, dtype=np.float64)
    got = {}
    for alg in _ALGORITHMS:
        d = vf.voronoi(pts, domain, algorithm=alg)
        geom = domain if not isinstance(domain, tuple) else None
        validate_diagram(d, pts, geom, samples=500)
        pairs = _pairs(d)
        assert pairs == {(j, i) for i, j in pairs}, alg
        edges = {tuple(p) for p in np.asarray(d.edges.pairs).tolist()}
        assert edges == {p for p in pairs if p[0] < p[1]}, alg
        got[alg] = (pairs, _vertex_sets(d))
    ref = got["delaunay"]
    for alg in _ALGORITHMS[1:]:
        assert got[alg][0] == ref[0], alg
        assert got[alg][1] == ref[1], alg
    return ref


def test_hypothesis_case():
    """The input hypothesis found: one shared boundary, cells the same bit for bit."""
    pts = np.array([(0.0, 0.0), (1.0, 1.0)])
    b = _padded_box(pts)
    assert b == (-0.2, -0.2, 1.2, 1.2)
    pairs, cells = _check(pts, _with_triangle_hole(b))
    assert pairs == {(0, 1), (1, 0)}
    # the true crossing of the right side, 2 ulps above the corner, in both cells
    y = float(np.nextafter(np.nextafter(-0.2, 1.0), 1.0))
    assert (1.2, y) in cells[0] and (1.2, y) in cells[1] and (1.2, -0.2) in cells[0]
    # the hole's edge crossed at one point (the exact crossing 0.675 - 2**-54, a tie,
    # rounds to even: 0.675), which is also cell 1's vertex of the hole
    assert (0.675, 0.325) in cells[0] and (0.675, 0.325) in cells[1]


@pytest.mark.parametrize("pad", [0.1, 0.2, 0.3, 0.7, 1.1, 1.3])
@pytest.mark.parametrize("hole", [False, True])
def test_box_corners_ulps_from_bisector(pad, hole):
    """Box corners an ulp or two either side of (or on) the bisector x + y = 1."""
    pts = np.array([(0.0, 0.0), (1.0, 1.0)])
    b = _padded_box(pts, pad)
    pairs, _ = _check(pts, _with_triangle_hole(b) if hole else b)
    assert pairs == {(0, 1), (1, 0)}


@pytest.mark.parametrize(
    ("scale", "shift"),
    [(1e-9, 0.0), (1e9, 0.0), (1.0, 5e5), (3.0, -7.0), (0.1, 0.3), (2.0**-20, 1.0)],
)
def test_scaled_and_shifted(scale, shift):
    """The hypothesis case's recipe at other scales and offsets."""
    pts = np.array([(0.0, 0.0), (1.0, 1.0)]) * scale + shift
    b = _padded_box(pts)
    pairs, _ = _check(pts, _with_triangle_hole(b))
    assert pairs == {(0, 1), (1, 0)}
    pairs, _ = _check(pts, b)
    assert pairs == {(0, 1), (1, 0)}


def test_hole_vertex_exactly_on_bisector():
    """A hole's vertex exactly on the bisector (0.75 + 0.25 == 1 exactly) is a vertex of both."""
    pts = np.array([(0.0, 0.0), (1.0, 1.0)])
    dom = Polygon(
        [(-0.5, -0.5), (1.5, -0.5), (1.5, 1.5), (-0.5, 1.5)],
        [[(0.25, 0.25), (0.75, 0.25), (0.5, 0.75)]],
    )
    pairs, cells = _check(pts, dom)
    assert pairs == {(0, 1), (1, 0)}
    assert (0.75, 0.25) in cells[0] and (0.75, 0.25) in cells[1]


def test_outline_vertices_exactly_on_bisector():
    """Outline corners and a reflex vertex exactly on the bisector, with three sites."""
    pts = np.array([(0.0, 0.0), (1.0, 1.0), (2.0, -0.25)])
    # (1.5, -0.5) and (-0.5, 1.5) on x + y = 1; the reflex vertex (0.5, 0.5) on it too
    dom = Polygon([(-0.5, -0.5), (1.5, -0.5), (2.5, 0.0), (0.5, 0.5), (0.5, 1.5), (-0.5, 1.5)])
    pairs, cells = _check(pts, dom)
    assert (0, 1) in pairs or (0, 2) in pairs
    assert (-0.5, 1.5) in cells[0] and (-0.5, 1.5) in cells[1]
    assert (0.5, 0.5) in cells[0] and (0.5, 0.5) in cells[1]
