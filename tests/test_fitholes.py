"""power_fit with sites in a domain's holes (checker22 F3): the relaxed-density start.

Every fit is checked independently: each returned cell clipped to the domain by shapely has
its target area, the cells tile the domain, and random points of the domain lie in the
cell of the site nearest in power distance (brute force over all sites).
"""

import numpy as np
import pytest
import shapely
from shapely.geometry import MultiPolygon, Point, box
from shapely.ops import unary_union

import voroforge as vf
import voroforge.engine.capacity as capacity

from reference import check_power_fit

TOL = 1e-6


def _ring(r=0.3):
    return box(0, 0, 1, 1).difference(Point(0.5, 0.5).buffer(r))


def _targets(rng, n, dom):
    t = rng.random(n) + 0.5
    return t / t.sum() * dom.area


def _check(fit, pts, t, dom, seed=0):
    check_power_fit(fit, pts, t, dom, TOL, seed)


@pytest.mark.parametrize("r", [0.1, 0.3, 0.45])
def test_sites_in_a_hole(r):
    dom = _ring(r)
    rng = np.random.default_rng(1)
    pts = rng.random((300, 2))
    assert not shapely.contains_xy(dom, pts[:, 0], pts[:, 1]).all()
    t = _targets(rng, 300, dom)
    _check(vf.power_fit(pts, t, dom), pts, t, dom)


def test_all_sites_in_the_hole():
    dom = _ring()
    rng = np.random.default_rng(2)
    a = rng.random(150) * 2 * np.pi
    rr = 0.28 * np.sqrt(rng.random(150))
    pts = np.column_stack((0.5 + rr * np.cos(a), 0.5 + rr * np.sin(a)))
    t = _targets(rng, 150, dom)
    _check(vf.power_fit(pts, t, dom), pts, t, dom)


def test_many_holes_and_a_notch():
    holes = unary_union([Point(x, y).buffer(0.1) for x in (0.2, 0.5, 0.8) for y in (0.2, 0.5)])
    dom = box(0, 0, 1, 1).difference(holes).difference(box(0.4, 0.7, 0.6, 1.0))
    rng = np.random.default_rng(3)
    pts = rng.random((300, 2))
    t = _targets(rng, 300, dom)
    _check(vf.power_fit(pts, t, dom), pts, t, dom)


def test_no_fallback_to_the_targets_continuation(monkeypatch):
    """28% of 500 sites in the hole: before, Newton stalled twice and the targets' steps ran."""

    def fail(*args):
        raise AssertionError("the targets' continuation ran")

    monkeypatch.setattr(capacity, "_continuation", fail)
    dom = _ring()
    rng = np.random.default_rng(1)
    pts = rng.random((500, 2))
    t = _targets(rng, 500, dom)
    fit = vf.power_fit(pts, t, dom)
    assert np.max(np.abs(fit.areas - t) / t) <= TOL


def test_warm_start_skips_the_relaxation(monkeypatch):
    dom = _ring()
    rng = np.random.default_rng(4)
    pts = rng.random((200, 2))
    t = _targets(rng, 200, dom)
    fit = vf.power_fit(pts, t, dom)

    def fail(*args):
        raise AssertionError("relaxed again from a start that opens every cell")

    monkeypatch.setattr(capacity, "_gap_continuation", fail)
    again = vf.power_fit(pts, t, dom, weights=fit.weights)
    _check(again, pts, t, dom)


def test_three_parts_apart():
    n, g = 40, 1000.0
    dom = MultiPolygon([box(0, 0, 1, 1), box(g, 0, g + 1, 1), box(0, g, 1, g + 1)])
    rng = np.random.default_rng(7)
    pts = rng.random((n, 2))
    t = np.full(n, 3 / n)
    fit = vf.power_fit(pts, t, dom)
    areas = shapely.area(shapely.intersection(np.asarray(fit.cells, dtype=object), dom))
    assert np.max(np.abs(areas - t) / t) <= 2 * TOL
