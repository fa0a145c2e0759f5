"""``Convex(points=)``'s volume against the exact hull of its points (issue 12).

A hull whose facets are coplanar only to rounding has them merged into one wall
(``containers._hull_planes``: within 1e-12), each wall's offset the largest of its corners':
the container the cells tile is the polytope of those rows, which holds every point. Its
volume (``Convex.volume``, the exact polytope of the rows) is what the cells sum to, and it
lies above the exact volume of the points' hull by the merge (measured up to 5.1e-13
relative on unit cubes jittered by 1e-13..1e-12). Reference: the hull found by brute force
in rationals (every triple of points whose plane has all points on one side).
"""

from __future__ import annotations

import itertools
import sys
import warnings
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest

import voroforge as vf

sys.path.insert(0, str(Path(__file__).parent))
from reference3d import brute_volumes  # noqa: E402
from test_solid_subdivide_far import LOST  # noqa: E402

CUBE = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)


def _sub(a, b):
    return [a[k] - b[k] for k in range(3)]


def _cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def _dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _wrap(pts, nrm):
    """The corners of the convex polygon of coplanar ``pts`` in order (gift wrapping, exact)."""
    cur = min(pts)
    ring = []
    while True:
        ring.append(cur)
        nxt = None
        for p in pts:
            if p == cur:
                continue
            if nxt is None:
                nxt = p
                continue
            turn = _dot(nrm, _cross(_sub(nxt, cur), _sub(p, cur)))
            farther = _dot(_sub(p, cur), _sub(p, cur)) > _dot(_sub(nxt, cur), _sub(nxt, cur))
            if turn < 0 or (turn == 0 and farther):
                nxt = p
        cur = nxt
        if cur == ring[0]:
            return ring


def _exact_hull_volume(V) -> Fraction:
    """The volume of the hull of ``V`` in rationals (facets by brute force; few points)."""
    X = [[Fraction(float(x)) for x in p] for p in V]
    n = len(X)
    c = [sum(p[k] for p in X) / n for k in range(3)]
    faces = {}
    for i, j, k in itertools.combinations(range(n), 3):
        nrm = _cross(_sub(X[j], X[i]), _sub(X[k], X[i]))
        if not any(nrm):
            continue
        s = [_dot(nrm, _sub(X[m], X[i])) for m in range(n)]
        if all(x <= 0 for x in s) or all(x >= 0 for x in s):
            faces[frozenset(m for m in range(n) if s[m] == 0)] = nrm
    vol = Fraction(0)
    for on, nrm in faces.items():
        ring = _wrap([X[m] for m in sorted(on)], nrm)
        q = ring[0]
        for a, b in zip(ring[1:-1], ring[2:], strict=True):  # a fan from the first corner
            vol += abs(_dot(_sub(q, c), _cross(_sub(a, c), _sub(b, c)))) / 6
    return vol


def test_exact_hull_reference():
    # the reference itself: a unit cube with face points, a tetrahedron
    assert _exact_hull_volume(np.vstack([CUBE, [[0.5, 0.5, 0], [1, 0.25, 0.5]]])) == 1
    tet = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
    assert _exact_hull_volume(tet) == Fraction(1, 6)


@pytest.mark.parametrize("eps", [1e-15, 1e-13, 1e-12, 1e-11])
def test_jittered_cube_volume(eps):
    rng = np.random.default_rng(0)
    for _ in range(4):
        V = CUBE + rng.normal(size=CUBE.shape) * eps
        F = rng.random((6, 3))
        F[np.arange(6), rng.integers(0, 3, 6)] = rng.integers(0, 2, 6)
        V = np.vstack([V, F + rng.normal(size=F.shape) * eps])
        S = rng.random((5, 3)) * 0.8 + 0.1
        c = vf.Convex(points=V)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            d = vf.voronoi3d(S, c)
        exact = _exact_hull_volume(V)
        # the cells tile the container reported
        assert abs(d.volumes.sum() - c.volume) <= 4 * np.finfo(float).eps * c.volume
        # which holds the hull (every point is inside its rows) and is within the merge of it
        rel = float(Fraction(c.volume) / exact - 1)
        assert -4 * np.finfo(float).eps <= rel <= 1e-12


def test_points_past_a_triangle_of_a_merged_qhull_facet():
    # 16 points at 1e5 (solidfix's LOST): one of Qhull's triangles (of a facet it merged in
    # the principal-axes frame) has five points 4e-3..6e-3 past its plane; the row through
    # its corners cut them off and the container was 8.4e-4 smaller than the hull (three
    # cells too small). Each row's offset now holds every point.
    v, seeds = (np.asarray(x, float) for x in LOST)
    c = vf.Convex(points=v)
    exact = _exact_hull_volume(v)
    assert abs(float(Fraction(c.volume) / exact - 1)) <= 1e-12
    hs = c.halfspaces
    o = np.round(v.mean(axis=0))
    assert ((v - o) @ hs[:, :3].T - (hs[:, 3] - o @ hs[:, :3].T)).max() <= 1e-9
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        d = vf.voronoi3d(seeds, c)
    assert abs(d.volumes.sum() - c.volume) <= 1e-12 * c.volume
    ref = brute_volumes(seeds, hs)
    assert np.abs(d.volumes - ref).max() <= 1e-9 * c.volume
