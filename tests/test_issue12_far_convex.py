"""Issue 12: a ``vf.Convex`` far from the origin is as exact as one near it.

Its walls are kept about an origin near the solid (``engine.containers.far_origin``), through
the template, the cell kernel's float filters and its exact predicates. Before, each wall's
offset was one double in absolute coordinates (at 4e6 a wall was placed to 2.3e-10): the
unit tetrahedron at (5e5, 4e6, 100) measured ``.volume`` 3.1e-10 off and its cells summed
1.2e-9 off ``.volume``; a 50-point hull there 1.8e-10 and 1.5e-10.
"""

import sys
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from scipy.spatial import ConvexHull

import voroforge as vf

sys.path.insert(0, str(Path(__file__).parent))
from test_voronoi3d import check3d  # noqa: E402

UTM = (5e5, 4e6, 100.0)
OFFSETS = [UTM, (1e7, 1e7, 1e7), (1e9, -1e9, 1e9)]


def _shape(kind):
    r = np.random.default_rng(5)
    if kind == "tet":
        return np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1.0]])
    if kind == "hull50":
        return r.normal(size=(50, 3)) * 0.5
    slab = r.random((40, 3))
    slab[:, 2] *= 1e-3
    return slab


def _exact_hull_volume(P):
    """The exact volume of the hull of the doubles ``P`` (Qhull's facets, exact determinants)."""
    q = P - P.mean(axis=0)
    h = ConvexHull(q / np.abs(q).max())
    o = [Fraction(float(v)) for v in P[h.vertices[0]]]
    tot = Fraction(0)
    for s in h.simplices:
        a, b, c = ([Fraction(float(v)) - o[k] for k, v in enumerate(P[i])] for i in s)
        tot += abs(
            a[0] * (b[1] * c[2] - b[2] * c[1])
            - a[1] * (b[0] * c[2] - b[2] * c[0])
            + a[2] * (b[0] * c[1] - b[1] * c[0])
        )
    return float(tot / 6)


def _sites(local, n, seed):
    """``n`` points strictly inside the hull of ``local``."""
    r = np.random.default_rng(seed)
    eq = ConvexHull(local).equations
    lo, hi = local.min(axis=0), local.max(axis=0)
    out = np.zeros((0, 3))
    while len(out) < n:
        x = lo + (hi - lo) * r.random((4 * n + 20, 3))
        ok = (x @ eq[:, :3].T + eq[:, 3] < -1e-3 * np.ptp(local, axis=0).min()).all(axis=1)
        out = np.vstack([out, x[ok]])
    return out[:n]


@pytest.mark.parametrize("kind", ["tet", "hull50", "slab"])
@pytest.mark.parametrize("off", OFFSETS)
def test_far_hull_volumes(kind, off):
    local = _shape(kind)
    P = np.array(off) + local
    c = vf.Convex(points=P)
    exact = _exact_hull_volume(P)
    assert abs(c.volume - exact) <= 1e-12 * exact
    for n in (1, 50):
        d = vf.voronoi3d(np.array(off) + _sites(local, n, n), c)
        assert abs(d.volumes.sum() - c.volume) <= 1e-12 * c.volume
        assert d.describe()["euler_ok"]


@pytest.mark.parametrize("kind", ["tet", "hull50"])
@pytest.mark.parametrize("scale", [1e-3, 1.0, 1e3])
def test_far_hull_cells_are_the_near_cells_translated(kind, scale):
    # the same input moved exactly by the offset: every cell keeps its volume (before, the
    # walls' rounding at 4e6 moved them by up to 1.2e-9 of the container)
    off = np.array(UTM)
    local = scale * _shape(kind)
    P = off + local
    S = off + scale * _sites(_shape(kind), 50, 3)
    far = vf.voronoi3d(S, vf.Convex(points=P))
    cn = vf.Convex(points=P - off)  # exact differences
    near = vf.voronoi3d(S - off, cn)
    assert np.abs(far.volumes - near.volumes).max() <= 1e-12 * cn.volume
    assert abs(far.container_volume - cn.volume) <= 1e-13 * cn.volume


def test_far_tetrahedron_samples():
    off = np.array(UTM)
    local = _shape("tet")
    c = vf.Convex(points=off + local)
    d = vf.voronoi3d(off + _sites(local, 50, 7), c)
    assert check3d(d, volume=c.volume, samples=600) > 60  # the tetrahedron: 1/6 of its box


@pytest.mark.parametrize("off", OFFSETS)
def test_far_halfspaces_of_a_hull(off):
    # Convex(halfspaces=) with the rounded absolute rows of a far hull: its walls about an
    # origin are computed from those rows exactly, so the cells tile it to 1e-12
    for kind in ("tet", "hull50"):
        c = vf.Convex(points=np.array(off) + _shape(kind))
        c2 = vf.Convex(halfspaces=c.halfspaces)
        d = vf.voronoi3d(np.array(off) + _sites(_shape(kind), 50, 11), c2)
        assert abs(d.volumes.sum() - c2.volume) <= 1e-12 * c2.volume
        # the rows' own rounding (an ulp of the offset, on every wall)
        assert abs(c2.volume - c.volume) <= 1e-6 * c.volume
    # the tetrahedron of the rounded rows: its exact volume from its four exact corners
    c = vf.Convex(points=np.array(off) + _shape("tet"))
    H = [[Fraction(float(v)) for v in r] for r in c.halfspaces]
    corners = []
    for skip in range(4):
        rows = [H[w] for w in range(4) if w != skip]
        M = [r[:3] for r in rows]

        def det(M):
            return (
                M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1])
                - M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0])
                + M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0])
            )

        D = det(M)
        x = []
        for k in range(3):
            N = [list(r) for r in M]
            for i in range(3):
                N[i][k] = rows[i][3]
            x.append(det(N) / D)
        corners.append(x)
    a, b, e, f = corners
    u = [[p[k] - f[k] for k in range(3)] for p in (a, b, e)]
    exact = float(abs(det(u)) / 6)
    assert abs(vf.Convex(halfspaces=c.halfspaces).volume - exact) <= 1e-12 * exact


def test_near_convex_keeps_absolute_walls():
    # a solid near the origin keeps its rows as they were (and its bits)
    c = vf.Convex(points=_shape("hull50"))
    assert c._template.WP.shape[1] == 4
    far = vf.Convex(points=np.array(UTM) + _shape("hull50"))
    assert far._template.WP.shape[1] == 7


@pytest.mark.parametrize("seed", range(4))
@pytest.mark.parametrize("off", [(1e6, 1e6, 1e6), UTM, (1e9, 1e9, 1e9)])
def test_far_rotated_cube(seed, off):
    # the corners' rounding splits each face into nearly coplanar walls: the cells are exact,
    # and .volume (the hull's triangles about the origin) too; the template's float cut had
    # measured 1.5e-12 off at 1e6
    from scipy.spatial.transform import Rotation

    rot = Rotation.random(random_state=seed)
    cube = np.array([[i, j, k] for i in (0, 1) for j in (0, 1) for k in (0, 1)], float)
    P = np.array(off) + rot.apply(cube)
    c = vf.Convex(points=P)
    exact = _exact_hull_volume(P)
    assert abs(c.volume - exact) <= 1e-14 * exact
    S = np.array(off) + rot.apply(0.1 + 0.8 * np.random.default_rng(seed).random((60, 3)))
    d = vf.voronoi3d(S, c)
    assert abs(d.volumes.sum() - exact) <= 1e-13 * exact
    assert d.describe()["euler_ok"]
