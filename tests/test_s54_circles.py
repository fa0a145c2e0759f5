"""Issue 15: chained classes of a far float circle named where their cells keep their sites.

Sites on a circle of radius 1e-7 at (5e5, 4e6): the exact Voronoi vertices lie a few ulps
apart, and the fold joins of ``kernels.centers`` chain triangles whose exact centres lie
many rounding bounds apart into one class. Named near one member, such a class put site
243's vertex of 257 (phase 0.35; 92 at 0.90) across its thin wedge: the site was flagged.
``kernels.chainfit.fit_chains`` renames a chain where its sites' rings of centres turn
left and hold their sites. Checked here: every cell valid and holding its own site,
nothing flagged, Euler's count, for every algorithm; and the score itself on a small fan
whose true centres it must accept.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest
import shapely

import voroforge as vf
from voroforge.kernels.chainfit import fan_score
from voroforge.kernels.delaunay import triangulate_sorted
from voroforge.kernels.vertex import voronoi_vertex

CENTRE = (5e5, 4e6)


def _circle(n, phase):
    t = np.arange(n) * (2.0 * np.pi / n) + phase
    return np.column_stack((1e-7 * np.cos(t), 1e-7 * np.sin(t))) + CENTRE


@pytest.mark.parametrize("phase", [0.35, 0.90])
@pytest.mark.parametrize("algorithm", ["delaunay", "fortune", "halfplane"])
def test_chained_classes_keep_every_site(phase, algorithm):
    pts = _circle(257, phase)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        d = vf.voronoi(pts, None, algorithm=algorithm)
    assert d.unresolved.shape[0] == 0
    assert d.describe().euler_ok
    cells = np.asarray(d.cells, dtype=object)
    assert all(c is not None and not c.is_empty for c in cells)
    assert shapely.is_valid(cells).all()
    assert shapely.contains_xy(cells, pts[:, 0], pts[:, 1]).all()


def _fan(points):
    order, sx, sy, tri, he, _, ok = triangulate_sorted(points[:, 0].copy(), points[:, 1].copy())
    assert ok
    xs = np.ascontiguousarray(sx)
    ys = np.ascontiguousarray(sy)
    t = tri.shape[0] // 3
    cx = np.zeros(t)
    cy = np.zeros(t)
    for k in range(t):
        a, b, c = (np.int64(v) for v in tri[3 * k : 3 * k + 3])
        cx[k], cy[k] = voronoi_vertex(a, b, c, xs, ys)
    return xs, ys, tri, he, cx, cy


def test_fan_score_counts_turns_and_a_site_outside():
    # a site in a hexagon of neighbours: its fan of six triangles, their true centres
    ang = np.arange(6) * (np.pi / 3.0) + 0.1
    pts = np.vstack(([[0.0, 0.0]], np.column_stack((np.cos(ang), np.sin(ang))) * [1.0, 1.3]))
    xs, ys, tri, he, cx, cy = _fan(pts)
    s = int(np.flatnonzero((xs == 0.0) & (ys == 0.0))[0])
    t0 = int(np.flatnonzero(tri == s)[0]) // 3
    parent = np.arange(tri.shape[0] // 3)
    bx = np.zeros(parent.shape[0] + 2)
    by = np.zeros(parent.shape[0] + 2)
    args = (s, t0, tri, he, parent, t0)
    assert fan_score(*args, cx[t0], cy[t0], cx, cy, xs, ys, bx, by) == 0
    # the class's vertex moved through the site to the far side: the ring misses the site
    score = fan_score(*args, -3.0 * cx[t0], -3.0 * cy[t0], cx, cy, xs, ys, bx, by)
    assert score > 0
