"""3D ``describe()``: V, E, F, C and the Euler characteristic, on the 3-torus too.

A periodic diagram's ``vertices`` hold a vertex once per image record; ``describe()``
counts vertices, edges and faces on the torus (records united through each face and its
twin across the seam), so ``V - E + F - C`` is the 3-torus's 0; cells in a box or a convex
solid subdivide a ball: 1. References: the exact counts of the cubic and BCC lattices, and
for random sites the records wrapped into the box and clustered (an independent count).
"""

import numpy as np
import pytest

import voroforge as vf
from catalogue3d import CATALOGUE3D


def _lattice(k, centred):
    g = np.stack(np.meshgrid(*[np.arange(k, dtype=float)] * 3, indexing="ij"), -1).reshape(-1, 3)
    return np.vstack([g, g + 0.5]) if centred else g + 0.5


@pytest.mark.parametrize("k", [2, 3])
def test_torus_counts_of_lattices(k):
    box = (0, 0, 0, k, k, k)
    r = vf.voronoi3d(_lattice(k, False), box, periodic=True).describe()
    n = k**3  # cubes: a vertex per corner, three edges and three faces per cell
    assert (r["vertices"], r["edges"], r["faces"], r["cells"]) == (n, 3 * n, 3 * n, n)
    r = vf.voronoi3d(_lattice(k, True), box, periodic=True).describe()
    # truncated octahedra: 24 vertices (4 cells each), 36 edges (3), 14 faces (2)
    assert (r["vertices"], r["edges"], r["faces"], r["cells"]) == (
        12 * n,
        24 * n,
        14 * n,
        2 * n,
    )
    assert r["euler"] == r["euler_expected"] == 0 and r["euler_ok"]
    assert r["vertex_records"] > r["vertices"]


def _wrapped_counts(c, tol=1e-9):
    """V and E on the torus by wrapping every record into the box and clustering."""
    lo, hi = np.asarray(c.box, float).reshape(2, 3)
    size = hi - lo
    w = np.mod(np.asarray(c.vertices) - lo, size)
    w[np.isclose(w, size, rtol=0, atol=tol)] = 0.0
    key = np.round(w / tol).astype(np.int64)
    _, cls = np.unique(key, axis=0, return_inverse=True)
    cls = cls.reshape(-1)
    cf, _, _, roff, ring = c.cell_face_table()
    edges = set()
    for f in range(len(roff) - 1):
        r = cls[ring[roff[f] : roff[f + 1]]].tolist()
        edges.update((min(a, b), max(a, b)) for a, b in zip(r, r[1:] + r[:1], strict=True))
    return len(np.unique(cls[np.unique(ring)])), len(edges)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_torus_counts_against_wrapped_clusters(seed):
    p = np.random.default_rng(seed).random((80, 3))
    c = vf.voronoi3d(p, (0, 0, 0, 1, 1, 1), periodic=True)
    r = c.describe()
    assert (r["vertices"], r["edges"]) == _wrapped_counts(c)
    assert r["faces"] == len(c.faces) and r["euler"] == 0 and r["euler_ok"]


@pytest.mark.parametrize("name", sorted(CATALOGUE3D))
def test_euler_characteristic_of_catalogue(name):
    p, box = CATALOGUE3D[name]
    assert vf.voronoi3d(p, box).describe()["euler"] == 1  # a ball
    lo, hi = np.asarray(p).min(0), np.asarray(p).max(0)
    if box is not None and np.all(lo >= box[:3]) and np.all(hi < box[3:]):
        r = vf.voronoi3d(p, box, periodic=True).describe()
        assert (r["euler"], r["euler_expected"], r["euler_ok"]) == (0, 0, True)


def test_euler_of_a_convex_solid_and_weights():
    rng = np.random.default_rng(5)
    p = rng.random((60, 3))
    r = vf.voronoi3d(p, vf.Convex(points=rng.random((30, 3)) * 2 - 0.5)).describe()
    assert r["euler"] == r["euler_expected"] == 1 and r["euler_ok"]
    w = rng.random(60) * 0.01
    r = vf.voronoi3d(p, (0, 0, 0, 1, 1, 1), weights=w, periodic=True).describe()
    assert r["euler"] == 0 and r["euler_ok"]
