"""Lead fixes of session s55, each checked against an exact reference.

- ``Diagram.areas`` of a cell with parts in both parts of a far MultiPolygon (checker37 F4):
  each part's shoelace is now summed about its own first vertex, so a gap of 1e12 between
  the parts no longer costs the area its digits (it was 3.9e-5 relative off).
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
import shapely
from shapely.geometry import MultiPolygon, box

import voroforge as vf


def _exact_area(geom) -> Fraction:
    """The exact area of polygonal ``geom`` (Fractions over its float vertices)."""
    total = Fraction(0)
    for poly in shapely.get_parts(geom):
        rings = [poly.exterior, *poly.interiors]
        for k, ring in enumerate(rings):
            xy = [(Fraction(x), Fraction(y)) for x, y in ring.coords]
            pairs = zip(xy[:-1], xy[1:], strict=True)
            twice = sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1) in pairs)
            total += abs(twice) / 2 if k == 0 else -abs(twice) / 2
    return total


@pytest.mark.parametrize("gap", [1e6, 1e9, 1e12])
def test_areas_of_cells_spanning_far_parts(gap, algorithm):
    rng = np.random.default_rng(33)
    dom = MultiPolygon([box(0, 0, 1, 1), box(gap, 0, gap + 1, 1)])
    d = vf.voronoi(rng.random((20, 2)), dom, algorithm=algorithm)
    spanning = 0
    for i, cell in enumerate(d.cells):
        if cell.is_empty:
            continue
        exact = _exact_area(cell)
        assert abs(Fraction(d.areas[i]) - exact) <= Fraction(1, 10**14) * exact, i
        if len(shapely.get_parts(cell)) > 1:
            spanning += 1
            cx = float(sum(Fraction(p.centroid.x) * _exact_area(p) for p in cell.geoms) / exact)
            assert abs(d.centroids[i, 0] - cx) <= 1e-14 * gap, i
    assert spanning  # some cell reaches across the gap (else the check above proves nothing)
    total = sum(_exact_area(c) for c in d.cells if not c.is_empty)
    assert abs(float(total) - 2.0) <= 1e-13
