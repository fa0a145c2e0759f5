"""Findings of the ninth independent check (checker9) that are not covered elsewhere.

F1: periodic 3D cells in a thin box. Images were taken within a margin that doubled until
every cell closed, with ``margin / L`` shifts along each axis: cells wide across a thin
box (1 x 1 x 1e-6) never passed the closing test along its thin axis and the build did not
return. A torus cell lies within half a period of its site on every axis, so shifts of -1,
0, 1 always suffice; an axis whose margin reaches its period takes all of them. Then the
volumes: the vertices of quadruples as flat as the box were solved in floating point with an
error growing as 1 / the determinant's ratio (2e-2 of the volumes at 1e-8); they are solved
exactly now.
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


@pytest.mark.parametrize("aspect", [1e-3, 1e-4, 1e-6, 1e-8])
def test_thin_periodic_box_returns_and_tiles(aspect):
    rng = np.random.default_rng(1)
    p = rng.random((8, 3)) * [1.0, 1.0, aspect]
    box = (0.0, 0.0, 0.0, 1.0, 1.0, aspect)
    d = vf.voronoi3d(p, box, periodic=True)
    assert (d.volumes > 0).all()
    # every cell spans the thin axis: its volume is its 2D torus cell's area times the
    # height, to ~(aspect / spacing)**2 (the bisectors' tilt)
    flat = vf.voronoi(p[:, :2], (0, 0, 1, 1), periodic=True).areas * aspect
    np.testing.assert_allclose(d.volumes, flat, rtol=1e-9)
    # the flat quadruples' vertices are solved exactly (config.VORONOI3D_EXACT_DET_RTOL):
    # the float solve's error put the volumes 2% off at 1e-8
    assert abs(d.volumes.sum() / aspect - 1.0) < 1e-12
    np.testing.assert_allclose(d.volumes, _brute_volumes(p, box, 20000), atol=0.02 * aspect)
    n = d.neighbors
    for i in range(len(p)):
        for j in n[1][n[0][i] : n[0][i + 1]]:
            assert i in n[1][n[0][j] : n[0][j + 1]]


# F4: surface.voronoi on a mesh past ~1e+-77 returned areas 0 (1e80), 81% off (1e-80) or
# hung (1e-100) without an error: the kernels square areas. In 1e+-60 the areas scale as
# s**2 exactly enough; beyond, a ValueError names the range.
@pytest.mark.parametrize("s", [1e-60, 1e60])
def test_surface_voronoi_at_the_ends_of_its_range(s):
    trimesh = pytest.importorskip("trimesh")
    from voroforge import surface

    sph = trimesh.creation.icosphere(2)
    sites = sph.vertices[np.random.default_rng(2).choice(len(sph.vertices), 12, replace=False)]
    unit = surface.voronoi(
        surface.mesh(trimesh.Trimesh(sph.vertices, sph.faces, process=False)), sites
    )
    far = surface.voronoi(
        surface.mesh(trimesh.Trimesh(sph.vertices * s, sph.faces, process=False)), sites * s
    )
    np.testing.assert_allclose(far.areas / s**2, unit.areas, rtol=1e-12)


@pytest.mark.parametrize("s", [1e-80, 1e80, 1e-100])
def test_surface_past_its_range_is_refused(s):
    trimesh = pytest.importorskip("trimesh")
    from voroforge import surface

    sph = trimesh.creation.icosphere(1)
    with pytest.raises(ValueError, match="surface vertices (reach|span)"):
        surface.mesh(trimesh.Trimesh(sph.vertices * s, sph.faces, process=False))
    S = surface.mesh(sph)
    with pytest.raises(ValueError, match="points reach"):
        surface.voronoi(S, sph.vertices[:5] * 1e80)
