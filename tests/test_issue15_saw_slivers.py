"""Issue 15: strips under an ulp wide crossing a saw-toothed domain (the saw scan's last gaps).

Three or four sites an ulp apart (per coordinate) at a valley of ``SAW`` going north-west
(or south-east): the middle sites' cells are strips a fraction of an ulp wide that cross
every tooth. Their rings are clipped through one arrangement (``assemble._clip_arranged``),
where a strip's piece of a tooth is a face less than an ulp wide: its float interior point
fell outside it, so the face went to no cell and the cells either side of the strip kept
their crossings an ulp apart, with a gap between (an edge neither shared nor on the
boundary; 12 of the scan's 1,656 runs, 9 with no flagged site). Such a face now gets a
rational inner point and exact owners (``engine/slivers.py``).

Checks against independent references: every edge is another cell's reversed or lies on
the domain's boundary (its middle within 1e-12 of it), Euler's count, sample points in
their exact nearest site's cell (rationals); the exact helpers against shapely on fat
polygons.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
import shapely

import voroforge as vf
from test_issue15_polygon_domains import SAW, _check, _ulps_from
from test_issue15_saw_scan import _samples_agree
from voroforge.engine.slivers import inner_point, inside

ALGORITHMS = ("delaunay", "fortune", "halfplane")
DIRS = {"nw": (-1, 1), "se": (1, -1)}
# (valley, direction, sites): the scan's runs with a gap at 44f26cd, every algorithm
GAPS = [((1.5, 0.5), "nw", 4), ((0.5, 0.5), "nw", 3), ((0.5, 0.5), "nw", 4), ((0.5, 0.5), "se", 4)]


def _unshared_off_boundary(d, dom):
    """Edges that no other cell has reversed and whose middle is off the boundary."""
    edges = {}
    for i, c in enumerate(d.cells):
        for part in shapely.get_parts(c):
            for ring in (part.exterior, *part.interiors):
                xy = [tuple(p) for p in np.asarray(ring.coords).tolist()]
                for a, b in zip(xy[:-1], xy[1:], strict=True):
                    edges[(a, b)] = i
    bad = []
    for (a, b), i in edges.items():
        if (b, a) in edges:
            assert edges[(b, a)] != i
            continue
        mid = shapely.Point((a[0] + b[0]) / 2, (a[1] + b[1]) / 2)
        if dom.boundary.distance(mid) > 1e-12:
            bad.append((i, a, b))
    return bad


@pytest.mark.parametrize(("v", "step", "count"), GAPS)
def test_strip_crossing_teeth_leaves_no_gap(v, step, count):
    pts = _ulps_from(v, DIRS[step], count)
    for algorithm in ALGORITHMS:
        d = vf.voronoi(pts, SAW, algorithm=algorithm)
        _check(d, pts, SAW)
        assert not _unshared_off_boundary(d, SAW), algorithm
        assert d.describe().euler_ok, algorithm
        _samples_agree(d, pts, SAW)
        # the areas tile the domain to its rounding
        assert abs(d.areas.sum() - SAW.area) <= 1e-12


def _exact_inside_convex(p, ring):
    """Strictly inside a counter-clockwise convex ring (rationals)."""
    for (ax, ay), (bx, by) in zip(ring[:-1], ring[1:], strict=True):
        ax, ay, bx, by = map(Fraction, (ax, ay, bx, by))
        if (bx - ax) * (p[1] - ay) - (by - ay) * (p[0] - ax) <= 0:
            return False
    return True


def test_inner_point_is_strictly_inside():
    rng = np.random.default_rng(5)
    tried = 0
    for _ in range(60):
        # a random simple polygon: a star around the origin, sometimes clockwise
        k = int(rng.integers(3, 9))
        ang = np.sort(rng.random(k)) * 2 * np.pi
        r = 0.2 + rng.random(k)
        xy = np.column_stack((r * np.cos(ang), r * np.sin(ang)))
        if rng.random() < 0.5:
            xy = xy[::-1]
        poly = shapely.Polygon(xy)
        if not poly.is_valid:
            continue
        ring = np.asarray(poly.exterior.coords)
        p = inner_point(ring)
        assert p is not None
        # strictly inside: inside by the exact crossing test and at a positive distance
        assert inside(p, poly)
        # and, rounded to floats, in the closed polygon by shapely too
        assert shapely.covers(poly, shapely.Point(float(p[0]), float(p[1])))
        tried += 1
    assert tried > 30
    # a sliver: a triangle one ulp high at 3.7 (no float point strictly inside)
    y = 4.970588235294118
    sliver = np.array([(3.735294117647059, y), (4.2, 5.9), (3.735294117647059, np.nextafter(y, 9))])
    sliver = np.vstack((sliver, sliver[:1]))
    tri = sliver if shapely.Polygon(sliver).exterior.is_ccw else sliver[::-1]
    p = inner_point(sliver)
    assert p is not None and _exact_inside_convex(p, tri)
    # no area: None
    assert inner_point(np.array([(0.0, 0.0), (1.0, 1.0), (2.0, 2.0), (0.0, 0.0)])) is None


def test_inside_agrees_with_shapely_away_from_edges():
    holes = shapely.Polygon(
        [(0, 0), (10, 0), (10, 10), (0, 10)], [[(2, 2), (4, 2), (3, 5)], [(6, 6), (8, 6), (8, 8)]]
    )
    dom = shapely.MultiPolygon([holes, shapely.box(11, 0, 12, 3)])
    rng = np.random.default_rng(2)
    q = rng.random((400, 2)) * [13, 11] - [0.5, 0.5]
    far = shapely.distance(dom.boundary, shapely.points(q)) > 1e-9
    want = shapely.contains_xy(dom, q[:, 0], q[:, 1])
    for (x, y), w, ok in zip(q, want, far, strict=True):
        if ok:
            assert inside((Fraction(x), Fraction(y)), dom) == w


def test_faces_a_union_drops_are_not_lost(monkeypatch):
    # GEOS's cascaded union can drop a polygon a rounding from its neighbours (checker10:
    # 2 of 25 insets): a union of a cell's faces that loses one is refused (area check),
    # and the cells are clipped one by one instead. Here every union of several polygons
    # drops its first one.
    union_all = shapely.union_all

    def dropping(geoms, *args, **kwargs):
        parts = shapely.get_parts(np.asarray(geoms, dtype=object).ravel())
        if len(parts) > 1 and (shapely.get_type_id(parts) == 3).all():
            parts = parts[1:]
        return union_all(parts, *args, **kwargs)

    v, step, count = GAPS[0]
    pts = _ulps_from(v, DIRS[step], count)
    monkeypatch.setattr(shapely, "union_all", dropping)
    d = vf.voronoi(pts, SAW)
    monkeypatch.undo()
    _check(d, pts, SAW)
    assert abs(d.areas.sum() - SAW.area) <= 1e-12
