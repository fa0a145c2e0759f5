"""min_web also measures material inside one opening's hull (a tongue between a U's arms)."""

from __future__ import annotations

import numpy as np
import pytest
import shapely

import voroforge as vf
from voroforge.design import fabrication

PANEL = shapely.box(0, 0, 100, 100)


def _u(gap_left: float, gap_right: float) -> shapely.Polygon:
    """A U-shaped opening whose arms leave the tongue gap_left..gap_right x 40..80."""
    return shapely.Polygon(
        [(20, 20), (60, 20), (60, 80), (gap_right, 80), (gap_right, 40), (gap_left, 40)]
        + [(gap_left, 80), (20, 80)]
    )


@pytest.mark.parametrize("width", [0.5, 1.9])
def test_a_thin_tongue_inside_one_opening_is_a_web(width):
    frame = PANEL.difference(_u(40.0, 40.0 + width))
    webs = [v for v in fabrication.check(frame, min_web=2.0).violations if v.kind == "web"]
    assert len(webs) == 1
    v = webs[0]
    assert v.value == pytest.approx(width, rel=1e-2)
    assert shapely.box(40, 40, 40 + width, 80).covers(shapely.Point(v.location))
    # the same gap between two separate openings is reported with the same width
    two = PANEL.difference(shapely.box(20, 20, 40, 80)).difference(
        shapely.box(40 + width, 20, 60, 80)
    )
    (pair,) = fabrication.check(two, min_web=2.0).violations
    assert pair.value == pytest.approx(width, rel=1e-9)


@pytest.mark.parametrize("width", [2.5, 10.0])
def test_a_tongue_at_least_min_web_wide_passes(width):
    # its square tip's corners are not webs either
    frame = PANEL.difference(_u(35.0, 35.0 + width))
    assert fabrication.check(frame, min_web=2.0).ok


def test_a_spike_between_the_arms_of_a_v_is_a_web_near_its_tip():
    v = shapely.Polygon([(20, 20), (80, 20), (80, 80), (51, 80), (50, 30), (49, 80), (20, 80)])
    webs = [x for x in fabrication.check(PANEL.difference(v), min_web=2.0).violations]
    assert webs and all(w.kind == "web" and w.value < 2.0 for w in webs)
    assert all(w.location[1] < 80 for w in webs)


def test_voronoi_frames_are_unchanged():
    # convex openings: nothing inside their hulls; the report is the pairwise one
    pts = np.random.default_rng(3).random((60, 2)) * 100
    d = vf.voronoi(pts, (0, 0, 100, 100))
    holes = shapely.buffer(np.asarray(d.cells, dtype=object), -1.2, join_style="mitre")
    holes = holes[~shapely.is_empty(holes)]
    report = fabrication.check(openings=holes, boundary=PANEL, min_web=3.0)
    assert report.violations
    assert all(len(set(v.items)) == 2 for v in report.violations)  # pairs, never one opening
