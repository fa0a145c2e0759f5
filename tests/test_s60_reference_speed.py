"""The faster test oracles give what their plain forms give, bit for bit.

``reference.brute_voronoi`` screens the half-planes in one numpy step and ``exact_area``
sums the shoelace in integers; both must stay equal to the one-at-a-time loop and to the
area of ``exact_polygon_moments`` they replaced.
"""

from __future__ import annotations

import numpy as np
import pytest
import shapely

from reference import _clip_halfplane, brute_voronoi, exact_area, exact_polygon_moments


def _plain_cell(p, others, domain):
    """Every bisector in turn, nearest first, until none can reach the polygon."""
    xmin, ymin, xmax, ymax = domain.bounds
    poly = np.array([[xmin, ymin], [xmax, ymin], [xmax, ymax], [xmin, ymax]]) - p
    q_all = others - p
    for j in np.argsort((q_all**2).sum(1), kind="stable"):
        if len(poly) == 0:
            break
        q = q_all[j]
        if 0.5 * np.hypot(q[0], q[1]) > np.sqrt((poly**2).sum(1).max()) * (1 + 1e-12):
            break
        poly = _clip_halfplane(poly, q, 0.5 * float(q @ q))
    if len(poly) < 3:
        return shapely.Polygon()
    return shapely.intersection(shapely.make_valid(shapely.Polygon(poly + p)), domain)


def _circle(n, r, off):
    t = np.arange(n) * (2.0 * np.pi / n)
    return np.column_stack((r * np.cos(t), r * np.sin(t))) + off


@pytest.mark.parametrize(
    "pts",
    [
        _circle(60, 2.0, [1e4, 1e4]),  # every bisector within rounding of the centre
        np.random.default_rng(3).random((80, 2)),
        np.round(np.random.default_rng(4).random((80, 2)) * 6) / 6,  # ties and duplicates
    ],
    ids=["far_circle", "random", "grid"],
)
def test_screened_cells_are_the_plain_loops(pts):
    lo, hi = pts.min(0), pts.max(0)
    dom = shapely.box(*(lo - 0.1 * (hi - lo)), *(hi + 0.1 * (hi - lo)))
    got = brute_voronoi(pts, dom)
    uniq = np.unique(pts, axis=0, return_index=True)[1]
    for i in sorted(uniq.tolist()):
        others = pts[sorted(set(uniq.tolist()) - {i})]
        want = _plain_cell(pts[i], others, dom)
        assert shapely.to_wkb(got[i]) == shapely.to_wkb(want), i


def test_integer_shoelace_is_the_moments_area():
    rng = np.random.default_rng(0)
    geoms = [
        shapely.Polygon([(0, 0), (4, 0), (4, 4), (0, 4)], [[(1, 1), (1, 2), (2, 2), (2, 1)]]),
        shapely.Polygon([(0, 0), (0, 4), (4, 4), (4, 0)], [[(1, 1), (2, 1), (2, 2), (1, 2)]]),
        shapely.MultiPolygon([shapely.box(0, 0, 1, 1), shapely.box(2, 2, 3.5, 3.25)]),
        shapely.Polygon(),
    ]
    for k in range(60):
        scale = 10.0 ** rng.uniform(-150, 150) if k % 3 == 0 else 10.0 ** rng.uniform(-8, 8)
        pts = rng.random((int(rng.integers(3, 12)), 2)) * scale + rng.normal(size=2) * 1e6
        geoms.append(shapely.convex_hull(shapely.multipoints(pts)))
    for g in geoms:
        if g.geom_type in ("Polygon", "MultiPolygon"):
            assert exact_area(g) == exact_polygon_moments(g)[0], g.wkt[:80]
