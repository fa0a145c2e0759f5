"""lloyd3d(density=): each step's targets are the cells' density centroids, exact for a
linear density (checker20 F4), against closed-form tetrahedron moments of each cell."""

import numpy as np
import pytest
from scipy.spatial import ConvexHull

import voroforge as vf


def _linear_density_centroid(C, g):
    """Centroid of the convex hull of ``C`` under density 1 + g.x (exact tetra moments)."""
    hull = ConvexHull(C)
    o = C.mean(axis=0)
    mass, first = 0.0, np.zeros(3)
    for s in hull.simplices:
        P = np.vstack([o, C[s]])
        vol = abs(np.linalg.det(P[1:] - P[0])) / 6
        S = P.sum(axis=0)
        m1 = vol * P.mean(axis=0)  # int x
        m2 = vol / 20 * (np.outer(S, S) + P.T @ P)  # int x x^T
        mass += vol + g @ m1
        first += m1 + m2 @ g
    return first / mass


@pytest.mark.parametrize("n,seed", [(30, 3), (120, 4)])
def test_linear_density_targets_exact(n, seed):
    rng = np.random.default_rng(seed)
    S = rng.random((n, 3))
    g = np.array([1.5, -0.7, 0.4])
    box = (0, 0, 0, 1, 1, 1)
    T = np.asarray(vf.lloyd3d(S, box, iterations=1, density=lambda x: 1 + x @ g).points)
    d = vf.voronoi3d(S, box)
    for i in range(n):
        ref = _linear_density_centroid(np.asarray(d.cell(i).vertices), g)
        assert np.abs(T[i] - ref).max() <= 1e-13


def test_constant_density_is_the_uniform_centroid():
    S = np.random.default_rng(5).random((40, 3))
    box = (0, 0, 0, 1, 1, 1)
    T = np.asarray(vf.lloyd3d(S, box, iterations=1, density=lambda x: np.full(len(x), 2.0)).points)
    U = np.asarray(vf.lloyd3d(S, box, iterations=1).points)
    assert np.abs(T - U).max() <= 1e-13
