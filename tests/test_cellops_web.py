"""Smoothing and filleting openings never eat a design's web (checker19 F5).

Chaikin's curve passes outside a cell at its concave corners: a cell that wraps a window's
corner grew into the web, one opening 0.0057 mm^2 into the window itself. ``smooth`` keeps
a cell's inside part. A fillet's closing fills concave corners too (web/2 0.60 instead of 1
at fillet 2, nothing in the window); ``fillet(concave=False)`` leaves them sharp, what a
cutter leaves of an opening (the design files keep the closing: its clip to the cell adds
vertices microns apart at those corners).
"""

from __future__ import annotations

import numpy as np
import pytest
import shapely

from voroforge.design import cellops
from voroforge.design.compute import compute
from voroforge.design.designfile import load

L_SHAPE = shapely.Polygon([(0, 0), (4, 0), (4, 1), (1, 1), (1, 3), (0, 3)])
WINDOW = shapely.box(60, 40, 140, 80)


def _panel(**cells):
    spec = {
        "boundary": {
            "shape": "polygon",
            "points": [[0, 0], [200, 0], [200, 120], [0, 120]],
            "holes": [list(WINDOW.exterior.coords)[:-1]],
        },
        "seeds": {"method": "poisson", "radius": 18},
        "cells": {"web": 2.0, **cells},
    }
    return compute(*load(spec))


@pytest.mark.parametrize("iterations", [1, 2, 4])
def test_smooth_stays_inside_a_concave_cell(iterations):
    out = cellops.smooth([L_SHAPE, shapely.box(0, 0, 2, 1)], iterations=iterations)
    for got, cell in zip(out, [L_SHAPE, shapely.box(0, 0, 2, 1)], strict=True):
        assert got.is_valid and not got.is_empty
        assert got.difference(cell).area <= 1e-12 * cell.area
        assert got.area < cell.area  # the convex corners are still cut
    # the concave corner (1, 1) stays: nothing of the L was cut there
    assert out[0].distance(shapely.Point(1, 1)) == 0.0


def test_fillet_concave_false_stays_inside_and_default_fills_the_corner():
    inside = cellops.fillet([L_SHAPE], 0.3, concave=False)[0]
    filled = cellops.fillet([L_SHAPE], 0.3)[0]
    assert inside.difference(L_SHAPE).area <= 1e-12
    assert filled.difference(L_SHAPE).area > 0.01  # the closing rounds (1, 1) outward
    both = cellops.inset_fillet([L_SHAPE], 0.1, 0.3, concave=False)[0]
    assert both.difference(L_SHAPE.buffer(-0.1, join_style="mitre")).area <= 1e-12


@pytest.mark.parametrize("smooth", [1, 2, 4])
def test_smoothed_openings_keep_half_the_web_from_a_window(smooth):
    res = _panel(smooth=smooth)
    live = [g for g in res.cells if not g.is_empty]
    assert live
    gap = min(g.distance(WINDOW) for g in live)
    assert gap >= 1.0 - 1e-9  # web / 2
    assert all(g.difference(r).area <= 1e-9 for g, r in zip(res.cells, res.raw, strict=True))
    assert np.isfinite([g.area for g in live]).all()
