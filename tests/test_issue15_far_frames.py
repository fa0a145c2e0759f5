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


@pytest.mark.parametrize("gap", [1e-100, 1e-154, 1e-200, 1e-250, 1e-300])
@pytest.mark.parametrize("algorithm", ["delaunay", "fortune", "halfplane"])
def test_areas_of_tight_sites_in_a_wide_box(gap, algorithm):
    # (the half-plane did not return for 1e-154: the frame put the box near 2**900;
    # sites closer than ~1e-206 of the domain are one site for every algorithm)
    p = np.array([[0.0, 0.0], [gap, 0.0], [0.0, gap]])
    d = vf.voronoi(p, (-1, -1, 10, 10), algorithm=algorithm)
    if gap < 1e-206:
        assert d.duplicate_of.tolist() == [-1, 0, 0]
        assert d.areas.tolist() == [121.0, 0.0, 0.0]
        return
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


def _exact_power_nearest(sites, w, q):
    qx, qy = Fraction(float(q[0])), Fraction(float(q[1]))
    d = [
        (Fraction(float(x)) - qx) ** 2 + (Fraction(float(y)) - qy) ** 2 - Fraction(float(v))
        for (x, y), v in zip(sites, w, strict=True)
    ]
    return min(range(len(sites)), key=lambda i: (d[i], i))


def test_power_locate_far_and_near_ties():
    """checker5 F5: an IndexError for a query at 1e300 (squared distances overflowed and
    cKDTree answered its sentinel), and float ties an ulp off a bisector given to the
    lower index (zero weights: 12 of 42 queries)."""
    p = np.array([[0.0, 0.0], [1e-100, 1e-100]])
    d = vf.power(p, [0.0, 0.0], (-1e300, -1e300, 1e300, 1e300))
    assert d.locate([[1e300, 1e300]]).tolist() == [0]  # site 1 is a duplicate there
    d = vf.power(p, [0.0, 0.0], (-1, -1, 1, 1))
    assert d.locate([[0.5, 0.5]]).tolist() == [1]
    sq = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]])
    rng = np.random.default_rng(3)
    for w in (np.zeros(4), np.array([0.0, 1e-3, 0.0, 1e-3]), rng.random(4)):
        d = vf.power(sq, w, (-10, -10, 1e4, 1e4))
        q = []
        for y in (7.0, -3.0, 0.25, 1e3):
            for k in range(-3, 4):
                x = np.nextafter(0.5, 1.0 if k > 0 else 0.0) if k else 0.5
                for _ in range(abs(k) - 1):
                    x = np.nextafter(x, 1.0 if k > 0 else 0.0)
                q.append([x, y])
        q.append([1e300, -1e300])
        q.append([-1e299, 5.0])
        want = [_exact_power_nearest(sq, w, t) for t in q]
        assert d.locate(q).tolist() == want


@pytest.mark.parametrize("gap", [1e-60, 1e-110, 1e-120, 1e-160, 1e-300])
def test_3d_volumes_of_tight_sites_in_a_wide_box(gap):
    """checker5 F3 in 3D: volumes inf (1e-110) or NaN (1e-160) while Euler checked out. The
    container now stays below 2**FRAME3D_CAP_EXP in the working frame; sites its resolution
    rounds together (below ~1e-128 of the container here) are duplicates, not three
    overlapping boxes."""
    p = np.array([[0.0, 0.0, 0.0], [gap, 0.0, 0.0], [0.0, gap, 0.0]])
    c = vf.voronoi3d(p, (-1, -1, -1, 10, 10, 10))
    assert np.isfinite(c.volumes).all()
    assert c.volumes.sum() == pytest.approx(1331.0, rel=1e-12)
    if gap >= 1e-120:
        assert c.volumes.tolist() == [11.0, 660.0, 660.0]
        assert np.allclose(c.centroids[1], [115 / 18, 97 / 36, 4.5], rtol=1e-14)
    else:
        assert c.duplicate_of.tolist() == [-1, 0, 0]
        assert c.volumes.tolist() == [1331.0, 0.0, 0.0]
