"""power_fit with sites whose cells start wholly in a hole (issue 15, fitholes).

Such cells get area in the domain by damped Newton steps on the domain's convex hull
(``power.fit_breakout``), all at once, before Newton on the domain; the relaxed density's
continuation (which moved them out about half at a time) is not needed. Every fit is
checked independently with shapely areas, tiling and brute-force power ownership.
"""

import numpy as np
import pytest
from shapely.geometry import Point, box

import voroforge as vf
import voroforge.engine.capacity as capacity

from reference import check_power_fit

TOL = 1e-6

DOMAINS = {
    "ring": box(0, 0, 1, 1).difference(Point(0.5, 0.5).buffer(0.3)),
    "wide_ring": box(0, 0, 1, 1).difference(Point(0.5, 0.5).buffer(0.45)),
    "notch": box(0, 0, 1, 1).difference(box(0.3, 0.3, 0.7, 1.0)),
    "small_hole": box(0, 0, 1, 1).difference(Point(0.5, 0.5).buffer(0.1)),
}


@pytest.mark.parametrize("name", sorted(DOMAINS))
def test_stranded_cells_break_out_without_the_relaxed_density(monkeypatch, name):
    def fail(*args):
        raise AssertionError("the relaxed density's continuation ran")

    monkeypatch.setattr(capacity, "_gap_continuation", fail)
    dom = DOMAINS[name]
    rng = np.random.default_rng(21)
    pts = rng.random((400, 2))
    t = rng.random(400) + 0.5
    t = t / t.sum() * dom.area
    check_power_fit(vf.power_fit(pts, t, dom), pts, t, dom, TOL, samples=3000)
