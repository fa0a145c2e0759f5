"""A heavy site's own 3D power cell, cut first by the light sites at ``sqrt(w - wl)`` (issue 12).

A site heavier than every light site by ``c`` is cut by no light plane nearer than
``sqrt(c)`` to it, and by the nearest ones at sites that far: its cell is cut by the sites
of the buckets meeting that sphere first (``reach3d.shell_range``, ``shell_hit``), then its
search skips those buckets; a cell inside the sphere takes no light site at all. Checked
against brute-force power cells (every other site's halfspace, Qhull), a brute-force power
labelling of sample points, exact powers (fractions) beside the faces where two planes
coincide, and the same cells from both sides (neighbours symmetric, equal face areas).
"""

from __future__ import annotations

import itertools
from fractions import Fraction

import numpy as np
import pytest
from scipy.spatial import ConvexHull

import voroforge as vf
from reference3d import brute_volumes
from test_issue12_power3d import _exact_nearest, _faces_of
from voroforge.engine.build3d import search3d
from voroforge.kernels.reach3d import heavy_sites

BOX = (0.0, 0.0, 0.0, 1.0, 1.0, 1.0)
WALLS = np.array(
    [[-1, 0, 0, 0], [1, 0, 0, 1], [0, -1, 0, 0], [0, 1, 0, 1], [0, 0, -1, 0], [0, 0, 1, 1]],
    np.float64,
)


def _power_labels(x, P, W):
    """Least-power site of each point and its margin to the second least (brute force)."""
    lab = np.zeros(len(x), np.int64)
    gap = np.zeros(len(x))
    for a in range(0, len(x), 2000):
        pw = ((x[a : a + 2000, None, :] - P[None]) ** 2).sum(-1) - W[None]
        two = np.partition(pw, 1, axis=1)[:, :2]
        lab[a : a + 2000] = np.argmin(pw, axis=1)
        gap[a : a + 2000] = two[:, 1] - two[:, 0]
    return lab, gap


def _symmetric(d, cells):
    """Each face of ``cells`` toward a site is that site's face toward it (same area)."""
    indptr, nb = d.neighbors
    pairs = {(i, int(j)) for i in range(len(d)) for j in nb[indptr[i] : indptr[i + 1]]}
    assert all((j, i) in pairs for i, j in pairs), "neighbours not symmetric"
    memo = {}  # each cell's faces once (a cell is the neighbour of many)

    def faces_of(k):
        if k not in memo:
            memo[k] = _faces_of(d, k, centroid=False)
        return memo[k]

    for i in cells:
        for j, _, area, _, _ in faces_of(i):
            if j >= 0:
                back = [a for k, _, a, _, _ in faces_of(j) if k == i]
                assert back and min(abs(b - area) for b in back) <= 1e-12 * (1 + area), (i, j)


def _heavy_case(name):
    rng = np.random.default_rng(5)
    if name == "one":  # weight 1 among 2,500 of 0: 85% of the cells empty
        P = rng.random((2500, 3))
        W = np.zeros(len(P))
        W[5] = 1.0
    elif name == "small":  # a sphere of root 0.2 inside the box, its buckets cut first
        P = rng.random((3000, 3))
        W = np.zeros(len(P))
        W[5] = 0.04
    elif name == "corner":  # the sphere mostly outside the box
        P = rng.random((2000, 3))
        P[5] = (0.03, 0.02, 0.01)
        W = np.zeros(len(P))
        W[5] = 0.3
    else:  # light sites with weights of their own, the heavy site among them
        P = rng.random((2500, 3))
        W = rng.random(len(P)) * 1e-3
        W[5] = 0.1
    return P, W


@pytest.mark.parametrize("name", ["one", "small", "corner", "spread"])
def test_heavy_cell_against_brute_force(name):
    P, W = _heavy_case(name)
    assert heavy_sites(W, search3d(P)[0]).tolist() == [5]  # (the case is what it tests)
    d = vf.voronoi3d(P, BOX, weights=W)
    assert d.volumes.sum() == pytest.approx(1.0, rel=1e-12)
    near = np.argsort(((P - P[5]) ** 2).sum(1))[:6].tolist()  # the heavy one and around it
    np.testing.assert_allclose(d.volumes[near], brute_volumes(P, WALLS, W, near), atol=1e-10)
    # sample points: those of the heavy site's least power inside its cell, the rest outside
    x = np.random.default_rng(1).random((6000, 3))
    lab, gap = _power_labels(x, P, W)
    h = ConvexHull(np.asarray(d.cell(5).vertices)).equations
    side = (x @ h[:, :3].T + h[:, 3]).max(1)  # < 0 inside
    sure = gap > 1e-9
    assert (side[sure & (lab == 5)] < 1e-9).all()
    assert (side[sure & (lab != 5)] > -1e-9).all()
    assert (sure & (lab == 5)).sum() > 0
    _symmetric(d, [5])


@pytest.mark.parametrize(
    "r2", [(17 / 48) ** 2, (3 / 8) ** 2, 2 * (17 / 48) ** 2, 3 * (17 / 48) ** 2]
)
def test_heavy_cell_sphere_on_bucket_sides(r2):
    """Light sites on a lattice of side 1/8 (its search grid: buckets of 7/48 from 1/16), one
    heavy site at 27/48 whose weight's root reaches a bucket side (10/48, the last one at
    45/48), edge or corner: the sphere whose buckets are cut by first touches them, where
    the first cut and the search must not both skip (or both take) a bucket."""
    c = (np.arange(8) + 0.5) / 8
    P = np.array([[x, y, z] for z in c for y in c for x in c])
    h = 4 * 64 + 4 * 8 + 4  # (27/48, 27/48, 27/48) + 1/48
    W = np.zeros(len(P))
    W[h] = r2
    d = vf.voronoi3d(P, BOX, weights=W)
    assert d.volumes.sum() == pytest.approx(1.0, rel=1e-12)
    near = np.argsort(((P - P[h]) ** 2).sum(1), kind="stable")[:40].tolist()
    ref = brute_volumes(P, WALLS, W, near)
    np.testing.assert_allclose(d.volumes[near], ref, rtol=1e-9, atol=1e-12)
    _symmetric(d, [h])


def test_heavy_cell_no_light_site_reaches():
    """A site heavy enough that no light plane reaches its cell (the whole box): its search
    takes no light site, and every light cell is empty."""
    rng = np.random.default_rng(2)
    P = rng.random((400, 3))
    W = np.zeros(400)
    W[7] = 4.0
    d = vf.voronoi3d(P, BOX, weights=W)
    assert d.volumes[7] == pytest.approx(1.0, rel=1e-14)
    assert (np.delete(d.volumes, 7) == 0.0).all()
    assert d.neighbors[0][-1] == 0


def test_many_heavy_sites():
    """Heavy sites of unequal weights: each heavy cell is cut first by the light sites at its
    own root, then by the heavy ones (listed apart)."""
    rng = np.random.default_rng(8)
    P = rng.random((2000, 3))
    W = np.zeros(len(P))
    heavy = rng.choice(len(P), 12, replace=False)
    W[heavy] = 0.06 + 0.1 * rng.random(12)
    assert len(heavy_sites(W, search3d(P)[0])) == 12
    d = vf.voronoi3d(P, BOX, weights=W)
    assert d.volumes.sum() == pytest.approx(1.0, rel=1e-12)
    np.testing.assert_allclose(
        d.volumes[heavy], brute_volumes(P, WALLS, W, heavy.tolist()), atol=1e-10
    )
    _symmetric(d, heavy.tolist())


def test_heavy_cell_on_a_torus():
    """Periodic: the heavy cell's sphere crosses the box's sides (the sites' images)."""
    rng = np.random.default_rng(4)
    P = rng.random((800, 3))
    P[3] = (0.05, 0.5, 0.95)
    W = np.zeros(len(P))
    W[3] = 0.06
    d = vf.voronoi3d(P, BOX, weights=W, periodic=True)
    assert d.volumes.sum() == pytest.approx(1.0, rel=1e-12)
    shifts = np.array(list(itertools.product((-1, 0, 1), repeat=3)), np.float64)
    first = shifts[np.argsort((shifts != 0).sum(1), kind="stable")]  # own image first
    allp = np.vstack([P + s for s in first])
    walls = np.column_stack([WALLS[:, :3], [1, 2, 1, 2, 1, 2]])
    near = np.argsort(((P - P[3]) ** 2).sum(1))[:4].tolist()
    ref = brute_volumes(allp, walls, np.tile(W, 27), near)
    np.testing.assert_allclose(d.volumes[near], ref, atol=1e-10)


def test_heavy_cell_exact_tie():
    """Two light sites on one ray from the heavy site whose planes coincide (weight ``t |s|^2``
    for sites at ``s`` and ``t s``): the face goes to the farther one whatever the cut order
    (``ties3d.retie``), checked on exact powers just inside and outside each face."""
    rng = np.random.default_rng(6)
    P = np.round(rng.random((3000, 3)) * 64) / 64  # dyadic: the planes coincide exactly
    P = np.unique(np.clip(P, 1 / 128, 1 - 1 / 128), axis=0)
    h = np.array([0.25, 0.5, 0.5])
    s = np.array([0.125, 0.0, 0.0])
    f = h + 2.5 * s  # on both planes: no other site nearer in power than the two (0.1875)
    P = P[(((P - f) ** 2).sum(1) > 0.2**2) & (np.abs(P - h).max(1) > 0.01)]
    P = np.vstack([h, h + s, h + 4 * s, P])
    W = np.zeros(len(P))
    W[0] = 4 * (s @ s)  # its planes with sites 1 and 2 both at x = 0.25 + 0.3125
    assert heavy_sites(W, search3d(P)[0]).tolist() == [0]
    d = vf.voronoi3d(P, BOX, weights=W)
    assert d.volumes[1] == 0.0  # the nearer one's cell lies beyond the plane: empty
    labels = [f[0] for f in _faces_of(d, 0)]
    assert 2 in labels and 1 not in labels
    images = np.zeros((1, 3))
    for i in (0, 2):
        for lab, _, _, cen, nrm in _faces_of(d, i):
            if lab < 0:
                continue
            delta = Fraction(1, 2**20)
            for sign, want in ((1, (lab, 0)), (-1, (i, 0))):
                q = [cen[a] + sign * delta * Fraction(float(nrm[a])) for a in range(3)]
                assert _exact_nearest(q, P, W, images) == [want], (i, lab, sign)
    _symmetric(d, [0, 2])
    near = [0, 1, 2]
    np.testing.assert_allclose(d.volumes[near], brute_volumes(P, WALLS, W, near), atol=1e-10)
