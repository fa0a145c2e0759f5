"""Findings of the ninth independent check (checker9) that are not covered elsewhere.

F1: periodic 3D cells in a thin box. Images were taken within a margin that doubled until
every cell closed, with ``margin / L`` shifts along each axis: cells wide across a thin
box (1 x 1 x 1e-6) never passed the closing test along its thin axis and the build did not
return. A torus cell lies within half a period of its site on every axis, so shifts of -1,
0, 1 always suffice; an axis whose margin reaches its period takes all of them.
"""

from __future__ import annotations

import numpy as np
import pytest

import voroforge as vf


def _brute_volumes(p, box, samples):
    """Monte Carlo cell volumes of the torus: each sample to its nearest site over the 27
    images (independent of the builder)."""
    lo, hi = np.array(box[:3]), np.array(box[3:])
    L = hi - lo
    rng = np.random.default_rng(0)
    x = lo + rng.random((samples, 3)) * L
    shifts = np.array(np.meshgrid(*[[-1, 0, 1]] * 3, indexing="ij")).reshape(3, -1).T * L
    best = np.full(samples, np.inf)
    own = np.zeros(samples, dtype=np.int64)
    for s in shifts:
        d = ((x[:, None, :] - (p + s)[None]) ** 2).sum(-1)
        k = d.argmin(1)
        v = d[np.arange(samples), k]
        better = v < best
        best[better], own[better] = v[better], k[better]
    return np.bincount(own, minlength=len(p)) / samples * np.prod(L)


@pytest.mark.parametrize("aspect", [1e-3, 1e-4, 1e-6])
def test_thin_periodic_box_returns_and_tiles(aspect):
    rng = np.random.default_rng(1)
    p = rng.random((8, 3)) * [1.0, 1.0, aspect]
    box = (0.0, 0.0, 0.0, 1.0, 1.0, aspect)
    d = vf.voronoi3d(p, box, periodic=True)
    assert (d.volumes > 0).all()
    # every cell spans the thin axis: its volume is its 2D torus cell's area times the
    # height, to ~(aspect / spacing)**2 (the bisectors' tilt)
    flat = vf.voronoi(p[:, :2], (0, 0, 1, 1), periodic=True).areas * aspect
    np.testing.assert_allclose(d.volumes, flat, rtol=1e-5)
    np.testing.assert_allclose(d.volumes, _brute_volumes(p, box, 20000), atol=0.02 * aspect)
    n = d.neighbors
    for i in range(len(p)):
        for j in n[1][n[0][i] : n[0][i + 1]]:
            assert i in n[1][n[0][j] : n[0][j + 1]]
