"""A Voronoi vertex on a side of the box (to rounding): every algorithm, valid shared rings.

Found by the independent check of 2026-12-04 (periodic diagrams build the images of a grid
whose Voronoi vertices lie on the box's sides): the default's cut cells named such a vertex
by its circumcentre, which rounding put an ulp past the side, and kept the edge from the
side out to it (a spike, or a vertex outside the box); a chain of lost edges could go round
the wrong way, outside the box (an extra 2/9 of the box in a 3 x 3 periodic grid).
"""

from __future__ import annotations

import numpy as np
import pytest
import shapely

import voroforge as vf

CASES = {
    # the bisector of sites 0 and 2 is the right side to rounding: their vertex is on it
    "vertex_on_right_side": (
        np.array([[1.0, 1.08], [1.5, 0.9], [1.2, 1.08]]),
        (-0.1, -0.09, 1.1, 0.99),
    ),
    # the bisector of sites 1 and 2 is the bottom side, rounded 4e-17 below it
    "vertex_below_bottom": (
        np.array([[1 / 6, 1 / 6], [0.5, 1 / 6], [0.5, 0.8333333333333333 - 1]]),
        (0, 0, 1, 1),
    ),
    # images of a 3 x 3 grid, as the periodic diagram builds them
    "grid_images": (
        np.array(
            [
                [1 / 6, 1 / 6],
                [0.5, 1 / 6],
                [0.5, 0.8333333333333333],
                [0.8333333333333333, 0.8333333333333333],
                [1 / 6 - 1 / 3, 0.8333333333333333 + 1],
                [1 / 6, 0.8333333333333333 - 1],
                [0.5, 0.8333333333333333 - 1],
            ]
        ),
        (0, 0, 1, 1),
    ),
}


@pytest.mark.parametrize("name", list(CASES))
def test_vertex_on_a_box_side(name, algorithm):
    p, box = CASES[name]
    d = vf.voronoi(p, box, algorithm=algorithm)
    cells = np.asarray(d.cells, dtype=object)
    assert shapely.is_valid(cells).all(), [c.wkt for c in cells]
    full = cells[~shapely.is_empty(cells)]
    assert shapely.covered_by(full, shapely.box(*box)).all()
    assert d.areas.sum() == pytest.approx(shapely.box(*box).area, rel=1e-12)
    assert d.describe().euler_ok


@pytest.mark.parametrize("k", [3, 5, 7, 13])
@pytest.mark.parametrize("size", [1.0, 0.7, 3.3])
@pytest.mark.parametrize("off", [0.0, 0.3])
def test_periodic_grid_whose_vertices_lie_on_the_sides(k, size, off):
    # cells are the h x h squares; wrapped, they tile the box once
    h = size / k
    g = np.stack(np.meshgrid(np.arange(k) * h, np.arange(k) * h), -1).reshape(-1, 2)
    g = g + h / 2 + off
    box = (off, off, off + size, off + size)
    area = (box[2] - box[0]) * (box[3] - box[1])
    for wrap in (False, True):
        d = vf.voronoi(g, box, periodic=True, wrap=wrap)
        assert d.areas.sum() == pytest.approx(area, rel=1e-12)
        assert np.allclose(d.areas, h * h, rtol=1e-9)
        assert d.describe().euler_ok
