"""Thin ``vf.Convex`` hulls and touching half-spaces (issue 12, checker33 F1, F2).

F1: ``Convex(points=)`` of a disk 1e-9 thin (200 points, above the 1e-10 refusal) came out
1.28e-5 above its exact hull: two top facets whose normals differed by 7.8e-13 were merged
(within 1e-12 of the extent, 1e-3 of the thickness) and the merged wall left a wedge outside
the hull. Unmerged, a rotated disk's walls were still 3e-8..1.5e-7 too big: each unit
normal, rounded, tilts its wall by an ulp. A thin hull now merges facets only within 1e-13
of its thickness and gives each wall the double nearest its exact normal's direction
(``engine/hullnormals.py``: ~1e-24 of tilt instead of 1e-16).

F2: unit-cube rows plus ``[1, 1, 1, 3]``, which touches the cube at (1, 1, 1) only, made a
face of three vertex records at that corner (the row divided by its norm and rounded passes
an ulp inside the corner). A row that makes no face of the exact polytope of the rows as
given is now left out of the template.

The reference hull is Qhull's triangles, each checked in rationals to hold every point, its
volume summed in rationals.
"""

import itertools
from fractions import Fraction

import numpy as np
import pytest
from scipy.spatial import ConvexHull

import voroforge as vf
from voroforge.engine.hullnormals import close_normal

ROT = (
    np.array([[0.6, -0.8, 0], [0.8, 0.6, 0], [0, 0, 1]]).T
    @ np.array([[1, 0, 0], [0, 0.6, -0.8], [0, 0.8, 0.6]]).T
)


def _exact_hull_volume(P):
    """The exact volume of the hull of ``P``: Qhull's triangles, checked exactly."""
    q = P - P.mean(axis=0)
    _, _, vt = np.linalg.svd(q, full_matrices=False)
    y = q @ vt.T
    simplices = ConvexHull(y / np.ptp(y, axis=0)).simplices  # (well conditioned)
    X = [[Fraction(float(c)) for c in p] for p in P]

    def sub(a, b):
        return [a[k] - b[k] for k in range(3)]

    def cross(a, b):
        return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]

    def dot(a, b):
        return sum(a[k] * b[k] for k in range(3))

    o = X[int(simplices[0, 0])]
    vol = Fraction(0)
    for s in simplices:
        a, b, c = (X[k] for k in s)
        n = cross(sub(b, a), sub(c, a))
        side = [dot(n, sub(p, a)) for p in X]
        assert max(side) <= 0 or min(side) >= 0  # a face of the exact hull
        vol += abs(dot(sub(a, o), cross(sub(b, o), sub(c, o))))
    return vol / 6


def _disk(seed, t, rotate=False, off=0.0, n=200):
    """``n`` points in a unit disk, ``t`` thick (checker33's f1_scan.py)."""
    rng = np.random.default_rng(100 + seed)
    th = rng.random(n) * 2 * np.pi
    r = np.sqrt(rng.random(n))
    P = np.c_[r * np.cos(th), r * np.sin(th), (rng.random(n) - 0.5) * t]
    return (P @ ROT if rotate else P) + off


@pytest.mark.parametrize(
    ("seed", "t", "rotate", "off"),
    [
        (2, 3e-10, False, 0.0),  # a merge: 1.15e-5 too big
        (1, 1e-9, True, 0.0),  # a merge and rounded normals: 2.5e-6
        (3, 3e-10, True, 0.0),  # rounded normals: 1.4e-7
        (4, 1e-8, True, 1e6),
        (5, 1e-9, False, 1e6),
    ],
)
def test_thin_hull_volume_is_the_exact_hull(seed, t, rotate, off):
    P = _disk(seed, t, rotate, off)
    exact = _exact_hull_volume(P - off) if off else _exact_hull_volume(P)
    c = vf.Convex(points=P)
    rel = (c.volume - float(exact)) / float(exact)
    assert -1e-15 <= rel <= 5e-13  # the exact polytope of the rows, rounded once
    # every point inside every wall (exactly), and every wall holding a point
    t_ = c._template
    rows = t_.WP[:, :4]
    o = t_.origin
    Q = [[Fraction(float(x)) - Fraction(float(y)) for x, y in zip(p, o, strict=True)] for p in P]
    for r in rows:
        fr = [Fraction(float(x)) for x in r]
        side = [sum(fr[k] * q[k] for k in range(3)) - fr[3] for q in Q]
        assert max(side) <= abs(fr[3]) * 2.0**-52 and max(side) >= -(abs(fr[3]) * 2.0**-52)
    sites = (P[:30] - P.mean(axis=0)) * 0.9 + P.mean(axis=0)
    d = vf.voronoi3d(sites, c)
    assert d.describe()["euler_ok"]
    s = d.volumes.sum()
    if not rotate:
        assert abs(s - float(exact)) <= 5e-13 * float(exact)
    else:
        # vertices rounded to ~1e-16 of the extent across a solid 1e-9 of it thick
        assert abs(s - c.volume) <= 1e-6 * c.volume


def test_close_normal():
    rng = np.random.default_rng(0)
    for _ in range(200):
        bits = rng.choice([1, 20, 60, 110, 200], 3)
        m = [int(rng.integers(1 << 62)) << int(b) for b in bits]
        m = [x * int(rng.choice([-1, 1])) for x in m]
        n = close_normal(m)
        assert 1 <= np.abs(n).max() < 2
        k = [int(Fraction(float(x)) * 2**1100) for x in n]
        c = [k[1] * m[2] - k[2] * m[1], k[2] * m[0] - k[0] * m[2], k[0] * m[1] - k[1] * m[0]]
        tilt = Fraction(sum(x * x for x in c), sum(x * x for x in k) * sum(x * x for x in m))
        assert sum(int(a) * b for a, b in zip(k, m, strict=True)) > 0
        assert tilt <= Fraction(1, 2**140)  # 2**-70; rounding gives ~2**-53
    assert close_normal([3, 5, 7]).tolist() == [0.75, 1.25, 1.75]  # exact where it fits
    assert close_normal([0, 0, -5]).tolist() == [0, 0, -1]


_CUBE = np.array(
    [[-1, 0, 0, 0], [1, 0, 0, 1], [0, -1, 0, 0], [0, 1, 0, 1], [0, 0, -1, 0], [0, 0, 1, 1]], float
)
# rows touching the unit cube in a corner or an edge only; [1, 1, 1, 3] made a face
_TOUCH = [[1, 1, 1, 3], [2, 2, 2, 6], [1, 2, 3, 6], [-1, 1, 1, 2], [1, 1, 0, 2], [4, 3, 0, 7]]
_TOUCH += [[-1, 1, 7, 8], [5, 2, 0, 7], [-7, 3, 3, 6]]


def _moved(H, off):
    H = np.array(H, float)
    H[:, 3] += H[:, :3] @ np.full(3, off)  # exact: small integers
    return H


def _same(d, ref):
    assert np.array_equal(d.volumes, ref.volumes)
    assert np.array_equal(d.vertices, ref.vertices)
    assert len(np.unique(d.vertices, axis=0)) == len(d.vertices)  # each vertex once
    assert len(d.faces) == len(ref.faces)
    assert np.array_equal(d.faces.cells, ref.faces.cells)


@pytest.mark.parametrize("off", [0.0, 5e5])
def test_touching_rows_make_no_face(off):
    p = np.random.default_rng(9).random((60, 3)) + off
    box = vf.Convex(halfspaces=_moved(_CUBE, off))
    ref = vf.voronoi3d(p, box)
    one = vf.voronoi3d(p[:1], box)
    for row in _TOUCH:
        c = vf.Convex(halfspaces=_moved(np.vstack([_CUBE, [row]]), off))
        t = c._template
        assert len(t.TV) == 8 and len(t.TF) == 6 and c.volume == box.volume
        assert sorted(map(tuple, t.TV.tolist())) == sorted(map(tuple, box._template.TV.tolist()))
        _same(vf.voronoi3d(p, c), ref)
        d = vf.voronoi3d(p[:1], c)  # the template itself: V 8, not 10
        _same(d, one)
        assert len(d.vertices) == 8
        assert -7 not in d.cell(0).neighbors


def test_octahedron_vertex_rows_and_a_real_cut():
    octa = np.array([[*s, 1] for s in itertools.product((-1, 1), repeat=3)], float)
    p = np.random.default_rng(3).random((80, 3)) * 0.6 - 0.3
    ref = vf.voronoi3d(p, vf.Convex(halfspaces=octa))
    for row in ([1, 0, 0, 1], [2, 1, 0, 2], [1, 0.5, 0.25, 1], [3, 1, 1, 3]):
        _same(vf.voronoi3d(p, vf.Convex(halfspaces=np.vstack([octa, [row]]))), ref)
    # a row past the corner by a hair still cuts it: the exact polytope's face
    c = vf.Convex(halfspaces=np.vstack([_CUBE, [[1, 1, 1, 3 - 2.0**-50]]]))
    assert -7 in c._template.TF[:, 0] and len(c._template.TV) == 10
