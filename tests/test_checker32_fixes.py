"""checker32's findings in the design layer's fabrication check, against shapely and brute force.

F1: openings that tile what they divide (recursion without a web, a diagram cut whole) left
a frame of GEOS slivers: loose "islands" of 1e-13 mm^2 in the check, sliver cut paths.
F2: a periodic tile's check missed some webs across the seams and reported others twice.
F3: the same sharp notch read a different corner value in an opening and in the outline.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
import shapely

from voroforge import config
from voroforge.design.build import check_design
from voroforge.design.compute import compute
from voroforge.design.designfile import load
from voroforge.design.fabrication import check


def _design(**extra) -> dict:
    d = {
        "design": {"name": "c32", "seed": 1},
        "boundary": {"shape": "rectangle", "width": 200, "height": 120},
        "seeds": {"method": "random", "count": 30},
    }
    d.update(extra)
    return d


def _compute(design):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        d, b = load(design)
        return compute(d, b)


# --- F1 ---------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "extra",
    [
        {"recursion": {"depth": 1, "count": 3}},
        {"recursion": {"depth": 2, "count": 2, "probability": 0.5}},
        {"boundary": {"shape": "circle", "radius": 60}},
        {"boundary": {"shape": "circle", "radius": 60}, "recursion": {"depth": 1, "count": 3}},
    ],
)
def test_f1_openings_that_tile_leave_no_frame(extra):
    design = _design(**extra)
    r = _compute(design)
    # reference: the leaves tile the boundary (their areas sum to it, shapely's union covers it)
    leaves = shapely.union_all(r.openings)
    assert abs(shapely.area(r.openings).sum() - r.boundary.area) <= 1e-9 * r.boundary.area
    assert r.boundary.difference(leaves).area <= 1e-9 * r.boundary.area
    assert r.frame.is_empty
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        assert check_design(design).violations == []


def _slivers(frame, area: float) -> int:
    return int((shapely.area(shapely.get_parts(frame)) < 1e-6 * area).sum())


@pytest.mark.parametrize("webs", [[2, 0], [0, 2], [3, 1]])
def test_f1_recursion_webs_stay_right(webs):
    r = _compute(_design(recursion={"depth": 1, "count": 3, "web": webs}))
    lv0, lv1 = r.extra["levels"]
    divided = np.zeros(len(lv0), dtype=bool)
    divided[lv1.parent] = True
    # reference: boundary minus every level's undivided openings; with no web inside the
    # divided cells their children fill their openings, so those openings stand for them
    holes = list(lv0.openings[~divided]) + list(lv1.openings)
    if webs[1] == 0:
        holes = list(lv0.openings)
    want = r.boundary.difference(shapely.union_all(holes))
    area = r.boundary.area
    assert abs(r.frame.area - want.area) <= 1e-9 * area
    assert r.frame.symmetric_difference(want).area <= 1e-9 * area
    assert _slivers(r.frame, area) == 0
    assert len(shapely.get_parts(r.frame)) == len(shapely.get_parts(want))
    # the webs: every pair of openings at least its level's web apart (less rounding)
    tree = shapely.STRtree(r.openings)
    a, b = tree.query(r.openings, predicate="dwithin", distance=min(webs) * 0.999)
    assert not (a < b).any() or min(webs) == 0


def test_f1_margin_frame_is_the_margin():
    design = _design(boundary={"shape": "circle", "radius": 60, "margin": 4})
    r = _compute(design)
    ring = r.boundary.difference(r.boundary.buffer(-4, join_style="mitre"))
    assert r.frame.symmetric_difference(ring).area <= 1e-9 * r.boundary.area
    assert len(shapely.get_parts(r.frame)) == 1


def test_f1_islands_thinner_than_the_tolerance_are_not_material():
    panel = shapely.box(0, 0, 100, 100)
    ring = shapely.box(20, 20, 80, 80)
    real = ring.difference(shapely.box(40, 40, 45, 45))  # a 5 x 5 island: falls out
    thin = ring.difference(shapely.box(40, 40, 60, 40 + 1e-9))  # rounding, not material
    got = check(openings=[real], boundary=panel).violations
    assert [(v.kind, round(v.value, 9)) for v in got] == [("island", 25.0)]
    assert check(openings=[thin], boundary=panel).violations == []
    # below the tolerance only: a 0.01-wide strip is still an island with a 0.005 tolerance
    strip = ring.difference(shapely.box(40, 40, 60, 40.01))
    assert len(check(openings=[strip], boundary=panel, corner_tolerance=0.005).violations) == 1
    assert check(openings=[strip], boundary=panel, corner_tolerance=0.02).violations == []


def test_f1_check_takes_the_callers_frame():
    panel = shapely.box(0, 0, 100, 100)
    holes = [shapely.box(10, 10, 50, 90), shapely.box(50, 10, 90, 90)]
    frame = panel.difference(shapely.box(10, 10, 90, 90))  # the two tile this one
    got = check(openings=holes, boundary=panel, frame=frame, min_web=2.0)
    assert got.frame.equals(frame)
    assert [v.kind for v in got.violations] == ["web"]  # the pair touching: web 0
    with pytest.raises(ValueError, match="not both"):
        check(frame, openings=holes)


# --- F2 ---------------------------------------------------------------------------------


def test_f2_periodic_tile_reports_every_torus_web_once():
    design = {
        "design": {"name": "per", "seed": 5},
        "boundary": {"shape": "rectangle", "width": 120, "height": 80},
        "seeds": {"method": "random", "count": 40},
        "voronoi": {"periodic": True},
        "cells": {"web": 2},
        "fabrication": {"min_web": 2.5},
    }
    rep = check_design(design)
    r = _compute(design)
    x0, y0, x1, y1 = r.extra["tile"]
    w, h = x1 - x0, y1 - y0
    t = r.extra["tile_openings"]
    want = {}  # brute force: torus pairs (i, j, shift) closer than min_web, either way round
    for i in range(len(t)):
        for j in range(i, len(t)):
            for dx in (-1, 0, 1):
                for dy in (-1, 0, 1):
                    if i == j and (dx, dy) <= (0, 0):
                        continue  # itself, or the same pair the other way round
                    g = shapely.transform(t[j], lambda xy, dx=dx, dy=dy: xy + (dx * w, dy * h))
                    d = t[i].distance(g)
                    if d < 2.5 * (1 - 1e-6):
                        want[(i, j)] = [*want.get((i, j), []), d]
    webs = [v for v in rep.violations if v.kind == "web"]
    got = {}
    for v in webs:
        got[tuple(sorted(v.items))] = [*got.get(tuple(sorted(v.items)), []), v.value]
        assert x0 <= v.location[0] <= x1 and y0 <= v.location[1] <= y1
    assert len(webs) == sum(len(d) for d in want.values())
    assert sorted(got) == sorted(want)
    for k in want:
        assert np.allclose(sorted(got[k]), sorted(want[k]), rtol=0, atol=1e-9)


# --- F3 ---------------------------------------------------------------------------------


def test_f3_same_notch_same_value_in_an_opening_and_the_outline():
    tol = config.FAB_CORNER_TOLERANCE
    step = 2.0 / 2**config.FAB_CORNER_BISECTIONS
    hole = check(
        openings=[shapely.box(20, 20, 40, 40)],
        boundary=shapely.box(0, 0, 100, 100),
        min_inside_radius=2.0,
    )
    ell = shapely.Polygon([[0, 0], [200, 0], [200, 120], [120, 120], [120, 60], [0, 60]])
    rim = check(openings=[], boundary=ell, min_inside_radius=2.0)
    a = sorted({round(v.value, 12) for v in hole.violations})
    b = [v.value for v in rim.violations]
    assert len(a) == 1 and len(b) == 1
    # reference: a tool of radius t leaves a 90-degree corner t (sqrt 2 - 1) from its arc
    exact = tol / (math.sqrt(2) - 1)
    assert exact - step <= a[0] <= exact and exact - step <= b[0] <= exact
    assert abs(a[0] - b[0]) <= 1e-9
    # both at the corner the tool cannot reach
    assert np.allclose(rim.violations[0].location, (120, 60), atol=1e-9)
    assert {tuple(np.round(v.location, 9)) for v in hole.violations} == {
        (20.0, 20.0),
        (40.0, 20.0),
        (40.0, 40.0),
        (20.0, 40.0),
    }
