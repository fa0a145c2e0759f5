"""A vertex of more than 1,024 owners with weights or in a mesh container (issue 12).

The 1,032 integer points of the sphere ``x^2 + y^2 + z^2 = 2966`` make one Delaunay
polytope whose centre is a Voronoi vertex of every cell. The plain box names it from the
Delaunay lists (``tests/test_issue12_sphere_big.py``); with ``weights=`` (lists off) or a
mesh container (lists off) every cell's owner table overflowed ("more than 98304
vertices"). Equal weights now build as the unweighted cells (only weight differences
enter), and a mesh container takes the lists for the cells whose vertex has more owners
than their table holds. Checked: bit-equal to the unweighted box, volumes summing to the
container, brute-force half-space cells (Qhull) and samples in their nearest site's cell.
"""

import sys
from pathlib import Path

import numpy as np
import pytest
from scipy.spatial import ConvexHull

import voroforge as vf

sys.path.insert(0, str(Path(__file__).parent))
from reference3d import brute_volumes  # noqa: E402

R2 = 2966


def _sphere_points(r2):
    m = int(np.sqrt(r2)) + 1
    r = np.arange(-m, m + 1)
    g = np.array(np.meshgrid(r, r, r, indexing="ij")).reshape(3, -1).T
    return g[(g**2).sum(1) == r2].astype(float)


@pytest.fixture(scope="module")
def pts():
    p = _sphere_points(R2)
    assert len(p) == 1032
    return p


@pytest.fixture(scope="module")
def plain(pts):
    R = np.sqrt(R2)
    return vf.voronoi3d(pts, (-2 * R,) * 3 + (2 * R,) * 3)


@pytest.mark.parametrize("w", [1.0, 7.5, -3.0])
def test_equal_weights_are_the_unweighted_cells(pts, plain, w):
    R = np.sqrt(R2)
    d = vf.voronoi3d(pts, (-2 * R,) * 3 + (2 * R,) * 3, weights=np.full(len(pts), w))
    assert d.describe()["unmatched_vertices"] == 0
    assert np.array_equal(d.volumes, plain.volumes)
    assert np.array_equal(d.vertices, plain.vertices)
    assert d.volumes.sum() == pytest.approx(64 * R**3, rel=1e-12)


def test_mesh_sphere_around_them(pts):
    import trimesh

    R = np.sqrt(R2)
    m = trimesh.creation.icosphere(2, radius=1.5 * R)
    d = vf.voronoi3d(pts, m)
    assert d.describe()["unmatched_vertices"] == 0
    assert d.volumes.sum() == pytest.approx(m.volume, rel=1e-9)
    # brute-force cells of a few sites in the mesh's convex hull (the mesh is convex)
    eq = ConvexHull(m.vertices).equations
    walls = np.hstack([eq[:, :3], -eq[:, 3:]])
    some = list(range(0, len(pts), 103))
    ref = brute_volumes(pts, walls, cells=some)
    assert np.abs(d.volumes[some] - ref).max() <= 1e-9 * m.volume / len(pts)
    # samples in their nearest site's cell
    x = np.random.default_rng(0).uniform(-1.5 * R, 1.5 * R, (3000, 3))
    x = x[(x @ walls[:, :3].T - walls[:, 3] < -1e-9 * R).all(axis=1)]
    near = np.argmin(((x[:, None, :] - pts[None]) ** 2).sum(-1), axis=1)
    for i in np.unique(near)[::7]:
        h = ConvexHull(np.asarray(d.cell(int(i)).vertices)).equations
        assert (x[near == i] @ h[:, :3].T + h[:, 3] <= 1e-9 * R).all(), int(i)
