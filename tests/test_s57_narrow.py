"""Tiny boxes and far polygon domains (issue 15, narrow5).

Box-side crossings in a box below ~1e-305 (subnormal ones too) were the float formula's
(0.0 for a crossing at w / 3): the exact sign tests of ``sidecross`` now scale their parts
by one power of two first, so each crossing is the double nearest the exact one. Checked
against exact Fractions: areas sum to the box exactly, each cell's area that of the exact
cell, valid, every algorithm the same cells.

Polygon domains far out (a 20-point star 80 ulps wide at 7e14): the shared edges that meet
the boundary were clipped apart from the cells (GEOS's line overlay against its polygon
overlay, or a redo in a site's frame), each rounding a crossing: edge ends lay off the
cells' vertices. They are now the runs of boundary the clipped cells share
(``engine.celledges``).
"""

from __future__ import annotations

import warnings
from fractions import Fraction

import numpy as np
import pytest
import shapely

import voroforge as vf
from voroforge.engine.celledges import shared_pieces

from reference import exact_area, exact_cell

ALGS = ["delaunay", "fortune", "halfplane"]


def _ring_area(ring):
    k = len(ring)
    s = sum(ring[i][0] * ring[(i + 1) % k][1] - ring[(i + 1) % k][0] * ring[i][1] for i in range(k))
    return abs(s) / 2


@pytest.mark.parametrize("w", [1e-305, 1e-310, 1e-320])
def test_tiny_box_nearest_crossing(w):
    """Sites (0, 5), (3, 4) in a box ``w`` wide: crossings ``+-w / 3`` rounded to nearest."""
    pts = np.array([(0.0, 5.0), (3.0, 4.0)])
    box = (-w, -w, w, w)
    third = float(Fraction(w) / 3)
    want = (Fraction(box[2]) - Fraction(box[0])) * (Fraction(box[3]) - Fraction(box[1]))
    first = None
    for alg in ALGS:
        d = vf.voronoi(pts, box, algorithm=alg)
        cells = list(d.cells)
        assert all(c.is_valid for c in cells)
        for cell in cells:
            xy = {tuple(v) for v in np.asarray(cell.exterior.coords).tolist()}
            assert (third, w) in xy and (-third, -w) in xy
        got = [exact_area(c) for c in cells]
        assert sum(got) == want
        for i in range(2):
            ref = _ring_area(exact_cell(pts, i, box))
            # the crossings' rounding: half an ulp of w / 3 along sides 2 w long
            assert abs(got[i] - ref) <= Fraction(np.spacing(w)) * 2 * Fraction(w)
        wkb = [c.wkb for c in cells]
        first = wkb if first is None else first
        assert wkb == first


def _star(off):
    t = np.linspace(0, 2 * np.pi, 41)[:-1]
    r = np.where(np.arange(40) % 2, 4.0, 10.0)
    return shapely.transform(
        shapely.Polygon(np.c_[r * np.cos(t), r * np.sin(t)]), lambda a: a + off
    )


@pytest.mark.parametrize("off", [0.0, 7e14])
def test_far_star_edges_end_at_cell_vertices(off):
    """300 sites in a 20-point star at 7e14 (80 ulps across): every edge end of two resolved
    sites is a vertex of both its cells (5 were not)."""
    geom = _star(off)
    rng = np.random.default_rng(1)
    x0, y0, x1, y1 = geom.bounds
    p = np.c_[rng.uniform(x0, x1, 1200), rng.uniform(y0, y1, 1200)]
    p = p[shapely.contains_xy(geom, p[:, 0], p[:, 1])][:300]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        d = vf.voronoi(p, geom)
    verts = [set(map(tuple, shapely.get_coordinates(c).tolist())) for c in d.cells]
    # (sites floats cannot give a cell, ``unresolved``, keep rings that overlap their
    # neighbours' before any clip: their edges are not asked)
    bad = set(d.unresolved.tolist())
    for (a, b), (i, j) in zip(d.edges.coords.tolist(), d.edges.pairs.tolist(), strict=True):
        if i in bad or j in bad:
            continue
        for q in (tuple(a), tuple(b)):
            assert q in verts[i] and q in verts[j], (i, j)


def _bufs(polys):
    _, xy, (ring, poly, geom) = shapely.to_ragged_array([shapely.MultiPolygon([q]) for q in polys])
    return xy, ring, poly, geom


def test_shared_pieces_runs():
    """Runs of segments two rings share, joined across a ring's closing vertex."""
    a = shapely.Polygon([(1, 0.5), (1, 1), (0, 1), (0, 0), (1, 0)])  # starts mid-edge
    b = shapely.Polygon([(1, 0), (2, 0), (2, 1), (1, 1), (1, 0.5)])
    c = shapely.Polygon([(0, 2), (0, 1), (1, 1), (1, 2)])
    piece, idx, found = shared_pieces(_bufs([a, b, c]), np.array([[0, 1], [0, 2], [1, 2]]))
    assert found.tolist() == [True, True, False]
    got = {(int(k), tuple(map(tuple, p.tolist()))) for k, p in zip(idx, piece, strict=True)}
    assert got == {(0, ((1.0, 0.0), (1.0, 1.0))), (1, ((1.0, 1.0), (0.0, 1.0)))}
