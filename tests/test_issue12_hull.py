"""Convex(points=): the hull's planes (issue 12, checker4 t3/scan*.py, m1, m7).

Qhull ran on the raw points and its float planes were the walls: a slab 1e-9 thin had side
normals off by ~1e-7 (the container "open" or "unbounded"; a flat one was reported by
Qhull's "initial simplex is flat" or not at all), and a tetrahedron at 1e4 had its volume
3.8e-12 off. Qhull now sees the points on their principal axes scaled to unit extent (the
facets are an affine invariant) and each plane is computed exactly from the raw points.
"""

import sys
from pathlib import Path

import numpy as np
import pytest

import voroforge as vf

sys.path.insert(0, str(Path(__file__).parent))
from reference3d import brute_volumes  # noqa: E402


def _check(d, c, sites):
    assert d.volumes.sum() == pytest.approx(c.volume, rel=1e-12, abs=0)
    assert d.describe()["euler_ok"]
    ref = brute_volumes(sites, c.halfspaces)
    assert np.abs(d.volumes - ref).max() <= 1e-12 * c.volume


@pytest.mark.parametrize("thick", [1e-3, 1e-6, 1e-9])
def test_thin_hull_works(thick):
    # Qhull on the raw points gave side facets' normals off by ~1e-7 at thickness 1e-9: the
    # container was "open" (1e-9, 1e-10) or "unbounded" (1e-11..1e-13)
    rng = np.random.default_rng(0)
    pts = rng.random((30, 3)) * [1, 1, thick]
    c = vf.Convex(points=pts)
    from scipy.spatial import ConvexHull

    # the reference hull of the slab stretched to unit thickness (volumes scale by thick)
    ref = ConvexHull(pts / [1, 1, thick]).volume * thick
    assert c.volume == pytest.approx(ref, rel=1e-9)
    sites = rng.random((5, 3)) * [1, 1, thick]
    d = vf.voronoi3d(sites, c)
    assert d.volumes.sum() == pytest.approx(c.volume, rel=1e-10)
    assert d.describe()["euler_ok"]


@pytest.mark.parametrize("thick", [1e-11, 1e-13, 1e-16, 0.0])
def test_flat_hull_says_so(thick):
    pts = np.random.default_rng(0).random((30, 3)) * [1, 1, thick]
    with pytest.raises(ValueError, match="Convex points are coplanar to within"):
        vf.Convex(points=pts)


def test_collinear_and_coincident_hulls_say_so():
    with pytest.raises(ValueError, match="collinear"):
        vf.Convex(points=np.outer(np.arange(5.0), [1, 2, 3]))
    with pytest.raises(ValueError, match="same point"):
        vf.Convex(points=np.ones((4, 3)))


def test_hull_with_nearly_coplanar_points_on_a_face():
    # checker4 m1: a cube with two points 1e-10 above its top face (roof walls at 1e-10)
    cube = np.array([[i, j, k] for i in (0, 1) for j in (0, 1) for k in (0, 1)], float)
    c = vf.Convex(points=np.vstack([cube, [[0.5, 0.5, 1 + 1e-10], [0.3, 0.6, 1 + 1e-10]]]))
    for n in (1, 2, 30):
        sites = np.random.default_rng(n).random((n, 3))
        _check(vf.voronoi3d(sites, c), c, sites)


def test_hull_planes_exact_off_the_origin():
    # Qhull's planes of a unit tetrahedron at 1e4 put its volume 3.8e-12 off; exactly
    # rounded planes 1.2e-14 (at UTM offsets the offsets' rounding, 2e-10, still shows:
    # walls are absolute planes, open)
    tet = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
    c = vf.Convex(points=tet + 1e4)
    assert c.volume == pytest.approx(1 / 6, rel=1e-13)
    # a plane through three float points: the exact cross product, scaled by a power of two
    # where it is a double (containers._exact_normals), else its unit normal rounded once
    c = vf.Convex(points=tet)
    want = np.array([[-1, 0, 0, 0], [0, -1, 0, 0], [0, 0, -1, 0], [1, 1, 1, 1]])
    got = c.halfspaces[np.lexsort(c.halfspaces.T[::-1])]
    assert (got == want[np.lexsort(want.T[::-1])]).all()
    c = vf.Convex(points=tet * (1 + 2**-52))  # normal (c^2, c^2, c^2): 105 bits, no double
    want = np.array([[-1, 0, 0, 0], [0, -1, 0, 0], [0, 0, -1, 0], [3**-0.5] * 4])
    got = c.halfspaces[np.lexsort(c.halfspaces.T[::-1])]
    assert np.abs(got - want[np.lexsort(want.T[::-1])]).max() <= 4e-16
