"""power_fit is scale invariant: the same sites, targets and domain scaled by any factor fit.

checker7 R3: 60 sites on a MultiPolygon with holes (seed 1) fitted at s = 1 and 1024 but
raised "did not reach tol" at s = 1e3 and 1e6. Scaling by 1e3 rounds the input, and the
shrink start's pole of inaccessibility (four tied corners of a square with a square hole)
fell elsewhere; from there the bridge across the gap doubled its raise from "no gain" to
"a cell of the other part emptied" and gave up. It now bisects between the two, and
rounding-level gains (1e-16 of the area) no longer count as a crossing.
"""

import numpy as np
import pytest
import shapely

import voroforge as vf


def _holed_parts(s=1.0, off=0.0):
    a = shapely.Polygon(
        [(0, 0), (1, 0), (1, 1), (0, 1)], [[(0.3, 0.3), (0.7, 0.3), (0.7, 0.7), (0.3, 0.7)]]
    )
    b = shapely.Polygon([(1.5, 0), (2.5, 0), (2.0, 0.9)], [[(1.9, 0.2), (2.1, 0.2), (2.0, 0.4)]])
    return shapely.affinity.affine_transform(shapely.MultiPolygon([a, b]), [s, 0, 0, s, off, off])


def _instance(seed, s=1.0, off=0.0):
    rng = np.random.default_rng(seed)
    p0 = rng.random((60, 2)) * [2.5, 1]
    t0 = rng.random(60) + 0.5
    dom = _holed_parts(s, off)
    return p0 * s + off, t0 * dom.area / t0.sum(), dom


@pytest.mark.parametrize(
    ("seed", "s", "off"),
    [(1, 1.0, 0.0), (1, 1e3, 0.0), (1, 1e6, 0.0), (1, 1.0, 5e5), (8, 1.0, 0.0), (11, 1.0, 0.0)],
)
def test_power_fit_converges_at_every_scale(seed, s, off):
    """Seeds 8 and 11 had stalled at s = 1 too (area errors 2.7 and 1.9), same cause."""
    pts, t, dom = _instance(seed, s, off)
    d = vf.power_fit(pts, t, dom)
    assert np.max(np.abs(d.areas - t) / t) <= 1e-6
    assert d.areas.sum() == pytest.approx(dom.area, rel=1e-9)
    # the cells are the power diagram of the reported weights, inside the domain
    again = vf.power(pts, d.weights, dom)
    assert np.allclose(again.areas, d.areas, rtol=1e-9, atol=1e-12 * dom.area)
    d_est = d.describe()
    assert d_est.euler_ok and d_est.convex_ok
