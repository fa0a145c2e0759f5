"""QA regressions for the CVT, power, periodic, query and describe features (issue 4).

Each test reproduces an input that broke one of these features, checked against a slow,
obvious reference (shapely half-planes, brute-force minima) rather than stored answers.
"""

from __future__ import annotations

import numpy as np
import shapely

import voroforge as vf


def _power_cells_ref(pts, w, dom):
    """Power cells by intersecting half-planes with shapely (slow and obvious)."""
    x0, y0, x1, y1 = dom.bounds
    size = max(x1 - x0, y1 - y0)
    cells = []
    for i in range(len(pts)):
        cell = shapely.box(x0, y0, x1, y1)
        for j in range(len(pts)):
            d = pts[j] - pts[i]
            if j == i or not d.any():
                continue
            # u . (x - p_i) <= t with u = d / |d|
            norm = float(np.hypot(*d))
            u = d / norm
            t = (d @ d + (w[i] - w[j])) / (2.0 * norm)
            base = pts[i] + u * t
            perp = np.array([-u[1], u[0]])
            far = 10.0 * size + abs(t) + float(np.hypot(*(pts[i] - [x0, y0])))
            cell = cell.intersection(
                shapely.Polygon(
                    [
                        base + perp * far,
                        base - perp * far,
                        base - (perp + 2 * u) * far,
                        base + (perp - 2 * u) * far,
                    ]
                )
            )
        cells.append(cell.intersection(dom))
    return np.array(cells, dtype=object)


def test_power_large_weights_leave_no_gap():
    # |d|^2 + w_i was rounded at the scale of w (1e8) before w_j was subtracted, so two
    # neighbours cut along bisectors 4e-9 apart and the cells missed part of the box
    rng = np.random.default_rng(2)
    pts = rng.random((80, 2))
    w = np.r_[1e8, 1e8 - 0.01, rng.random(78)]
    d = vf.power(pts, w, (0, 0, 1, 1))
    assert abs(d.areas.sum() - 1.0) <= 1e-13
    ref = _power_cells_ref(pts[:2], w[:2], shapely.box(0, 0, 1, 1))
    assert np.allclose(d.areas[:2], shapely.area(ref), rtol=0, atol=1e-13)
    assert (d.areas[2:] == 0).all()
