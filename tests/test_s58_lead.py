"""Issue 15 leftovers found by corner10 (s58): a box corner's sliver lost beside an empty
neighbour, and a padded box of no height for sites on a line far out or subnormal.

1. Two sites near a box corner at (-8.4e6, -1e7), one outside the box: the outside site's
   exact cell is a corner sliver floats cannot hold (its crossings round together), so its
   ring is empty; ``agree`` then joined the inside cell's edge across it, moving the ring
   off the box corner, and 1.2e-9 of the box was in no cell (every algorithm). A ring now
   keeps an edge whose neighbour is empty.
2. ``boundary=None`` pads a degenerate extent by a tenth of the other side; for sites on a
   horizontal line at y = 1e20 (or a few subnormal ulps apart) that pad is below half an
   ulp of the coordinate and rounded away: a box of zero height, every cell silently empty.
   The box now reaches at least the next double on each side.

Checked exactly: the cells' Fraction shoelace areas sum to the box's.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
import shapely

import voroforge as vf
from voroforge.engine.domain import padded_bounds

ALGS = ["delaunay", "fortune", "halfplane"]


def _area(cell) -> Fraction:
    total = Fraction(0)
    for part in shapely.get_parts(cell):
        for k, ring in enumerate((part.exterior, *part.interiors)):
            r = [(Fraction(x), Fraction(y)) for x, y in np.asarray(ring.coords)]
            s = sum(a[0] * b[1] - a[1] * b[0] for a, b in zip(r, r[1:], strict=False)) / 2
            total += abs(s) if k == 0 else -abs(s)
    return total


def _box_area(b) -> Fraction:
    return (Fraction(b[2]) - Fraction(b[0])) * (Fraction(b[3]) - Fraction(b[1]))


def _tiles_exactly(d, b) -> bool:
    return sum((_area(c) for c in d.cells if not c.is_empty), Fraction(0)) == _box_area(b)


@pytest.mark.parametrize("alg", ALGS)
def test_corner_sliver_beside_an_empty_neighbour_stays_in_a_cell(alg):
    pts = np.array([[-8388560.75, -9999984.5], [-8388560.15, -9999983.9]])  # 1 outside
    box = (-8388563.05, -9999986.8, -8388560.45, -9999984.2)
    keep = pts.copy()
    d = vf.voronoi(pts, box, algorithm=alg)
    assert np.array_equal(pts, keep)
    assert all(shapely.is_valid(c) for c in d.cells)
    assert _tiles_exactly(d, box)
    # the box corner nearest site 0's side is a vertex of site 0's ring
    assert (box[2], box[1]) in {tuple(map(float, p)) for p in d.cells[0].exterior.coords}


LINES = {
    "horizontal_1e20": np.array([[0.0, 1e20], [1.0, 1e20], [0.25, 1e20]]),
    "vertical_1e20": np.array([[1e20, 0.0], [1e20, 3.0]]),
    "subnormal_row": np.array([[101.0, 102.0], [100.0, 102.0], [101.5, 102.0]]) * 5e-324,
    "subnormal_two": np.array([[101.0, 102.0], [100.0, 102.0]]) * 5e-324,
}


@pytest.mark.parametrize("name", sorted(LINES))
def test_padded_box_of_a_far_or_subnormal_line_has_area(name):
    pts = LINES[name]
    b = padded_bounds(pts)
    assert b[0] < b[2] and b[1] < b[3]
    assert b[0] <= pts[:, 0].min() and pts[:, 0].max() <= b[2]
    assert b[1] <= pts[:, 1].min() and pts[:, 1].max() <= b[3]
    for alg in ALGS:
        d = vf.voronoi(pts, algorithm=alg)
        assert d.bounds == b
        assert not any(c.is_empty for c in d.cells), alg
        assert _tiles_exactly(d, b), alg
