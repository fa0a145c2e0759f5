"""3D Lloyd relaxation (lloyd3d): converges to centroidal cells, follows a density."""

from __future__ import annotations

import numpy as np

import voroforge as vf
from voroforge.engine.lloyd3d import lloyd3d


def test_lloyd3d_uniform_and_density():
    rng = np.random.default_rng(0)
    pts = rng.random((120, 3))
    r = lloyd3d(pts, (0, 0, 0, 1, 1, 1), iterations=15)
    assert r.moves[-1] < 0.2 * r.moves[0]
    c = np.asarray(r.diagram.centroids)
    assert np.abs(c - r.points).max() < 2 * r.moves[-1] + 1e-12
    assert abs(r.diagram.volumes.sum() - 1.0) < 1e-12
    # cells become rounder: the spread of volumes shrinks
    v0 = vf.voronoi3d(pts, (0, 0, 0, 1, 1, 1)).volumes
    assert r.diagram.volumes.std() < 0.6 * v0.std()
    dens = lloyd3d(pts, (0, 0, 0, 1, 1, 1), iterations=10, density=lambda x: np.exp(-8 * x[:, 0]))
    assert dens.points[:, 0].mean() < r.points[:, 0].mean() - 0.05
    # a constant density gives the plain centroids
    from voroforge.engine.lloyd3d import _density_centroids

    c1 = _density_centroids(r.diagram, lambda x: np.full(len(x), 3.0))
    np.testing.assert_allclose(c1, r.diagram.centroids, rtol=1e-12, atol=1e-14)
