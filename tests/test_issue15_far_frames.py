"""Sites far tighter than the domain or the queries (checker5 F3, F4).

The working frame scales the sites to about 1 and keeps the domain's box below 2**900:
areas and centroids (squares and cubes of coordinates) overflowed there (areas inf and
NaN for sites 1e-154 apart in a box 10 wide), and a query scaled into the sites' frame
overflowed (sites 1e-100 apart, a query at 1e300: the wrong site, with RuntimeWarnings).
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

import voroforge as vf


def _exact_nearest(sites, q):
    qx, qy = Fraction(float(q[0])), Fraction(float(q[1]))
    d = [(Fraction(float(x)) - qx) ** 2 + (Fraction(float(y)) - qy) ** 2 for x, y in sites]
    return min(range(len(sites)), key=lambda i: (d[i], i))


@pytest.mark.parametrize("gap", [1e-100, 1e-154, 1e-200, 1e-300])
@pytest.mark.parametrize("algorithm", ["delaunay", "fortune"])
def test_areas_of_tight_sites_in_a_wide_box(gap, algorithm):
    p = np.array([[0.0, 0.0], [gap, 0.0], [0.0, gap]])
    d = vf.voronoi(p, (-1, -1, 10, 10), algorithm=algorithm)
    assert np.array_equal(d.areas, [1.0, 60.0, 60.0])
    shp = np.array([c.centroid.coords[0] for c in d.cells])
    assert np.allclose(d.centroids, shp, rtol=1e-14, atol=0)
    assert d.describe().euler_ok


@pytest.mark.filterwarnings("error::RuntimeWarning")
@pytest.mark.parametrize(
    ("sites", "queries"),
    [
        ([[0.0, 0.0], [1e-100, 1e-100]], [[1e300, 1e300], [-1e300, -1e300], [1e300, -1e300]]),
        ([[0.0, 0.0], [1e-310, 1e-310]], [[1.0, 1.0], [-1.0, 1e-300], [5e-324, 0.0]]),
        ([[0.0, 0.0], [1e-100, 0.0], [0.0, 1e-100]], [[1e300, 1.0], [1.0, 1e300], [-1e300, 0]]),
        ([[3.0, 4.0], [3.0, 4.000000000000001]], [[1e308, 1e308], [0.0, -1e308], [0, 4e0]]),
    ],
)
def test_locate_far_from_tight_sites_is_exact(sites, queries):
    sites = np.array(sites)
    want = [_exact_nearest(sites, q) for q in queries]
    assert vf.locate(sites, queries).tolist() == want
    vals = np.arange(len(sites), dtype=float)
    # every query is outside the sites' hull: the nearest site's value
    got = vf.natural_neighbor(sites, vals, queries, extrapolate="nearest")
    assert got.tolist() == vals[want].tolist()
