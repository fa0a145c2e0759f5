"""power_fit with sites in a hole, the cheaper paths (issue 15, fitgrow).

The relaxed density's masses need the diagram on the domain and on its convex hull; they
share one bounding box, so the box cells are built once (``power.power_diagrams``): checked
bit for bit against one ``power_diagram`` per domain. A small hole, whose few sites start
with empty cells, is fitted by Newton from the slivers seeded for them, without the
relaxed density; the fit is checked with shapely areas, tiling and brute-force ownership.
"""

import numpy as np
import shapely
from shapely.geometry import MultiPolygon, Point, box

import voroforge as vf
import voroforge.engine.capacity as capacity
from voroforge.engine.diagram import buffers
from voroforge.engine.domain import make_domain
from voroforge.engine.power import power_diagram, power_diagrams

from reference import check_power_fit

TOL = 1e-6


def _same(a, b):
    for x, y in zip(buffers(a), buffers(b), strict=True):
        assert np.array_equal(x, y)
    assert np.array_equal(a.edges.coords, b.edges.coords)
    assert np.array_equal(a.edges.pairs, b.edges.pairs)
    assert np.array_equal(a.areas, b.areas)


def test_one_box_build_for_a_domain_and_its_hull():
    rng = np.random.default_rng(5)
    pts = rng.random((400, 2))
    w = rng.random(400) * 1e-3
    for geom in (
        box(0, 0, 1, 1).difference(Point(0.5, 0.5).buffer(0.3)),
        box(0, 0, 1, 1).difference(box(0.3, 0.3, 0.7, 1.0)),
        MultiPolygon([box(0, 0, 1, 1), box(50, 0, 51, 1), box(0, 50, 1, 51)]),
    ):
        dom = make_domain(geom, pts)
        hull = make_domain(shapely.convex_hull(geom), pts)
        for weights in (w, np.zeros(400)):
            both = power_diagrams(pts, weights, (dom, hull))
            _same(both[0], power_diagram(pts, weights, dom))
            _same(both[1], power_diagram(pts, weights, hull))
    # bounding boxes that differ: each built on its own
    dom = make_domain((0, 0, 1, 1), pts)
    other = make_domain((0, 0, 2, 2), pts)
    both = power_diagrams(pts, w, (dom, other))
    _same(both[1], power_diagram(pts, w, other))


def _check(fit, pts, t, dom):
    check_power_fit(fit, pts, t, dom, TOL, samples=3000)


def test_small_hole_needs_no_relaxed_density(monkeypatch):
    def fail(*args):
        raise AssertionError("the relaxed density ran for a small hole")

    monkeypatch.setattr(capacity, "_gap_continuation", fail)
    dom = box(0, 0, 1, 1).difference(Point(0.5, 0.5).buffer(0.1))
    rng = np.random.default_rng(11)
    pts = rng.random((500, 2))
    assert not shapely.contains_xy(dom, pts[:, 0], pts[:, 1]).all()
    t = rng.random(500) + 0.5
    t = t / t.sum() * dom.area
    _check(vf.power_fit(pts, t, dom), pts, t, dom)


def test_big_hole_still_relaxes():
    """28% of the sites in the hole: too many empty cells for the seeded slivers."""
    dom = box(0, 0, 1, 1).difference(Point(0.5, 0.5).buffer(0.3))
    rng = np.random.default_rng(12)
    pts = rng.random((400, 2))
    t = rng.random(400) + 0.5
    t = t / t.sum() * dom.area
    start, few = capacity._hole_start(pts, make_domain(dom, pts), np.zeros(400))
    assert start is not None and not few
    _check(vf.power_fit(pts, t, dom), pts, t, dom)
