"""3D cells: the bucket search's stop test, thin periodic boxes and ``locate`` on the torus.

Found by an independent check (session 39): a site in a layered input (columns of sites
0.01 apart) lost two neighbours beyond the ordered block of buckets (its cell 0.6% too
big, the volumes 1.7e-5 over the box); periodic boxes 1 x 1 x 0.01 took (2K + 1)**3 image
shifts with K from the thinnest side (5 sites: no result in minutes); ``locate`` on a
periodic diagram ignored the wrap.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
from scipy.spatial import ConvexHull

import voroforge as vf
from reference3d import brute_cell


def _columns(seed):
    """Sites in columns: random (x, y), layers 0.01 apart in z (periodic images look so)."""
    g = np.random.default_rng(seed)
    m = g.integers(20, 80)
    layers = g.integers(5, 40)
    xy = g.random((m, 2))
    z0 = g.random(m) * 0.01
    P = np.concatenate([np.c_[xy, z0 + k * 0.01] for k in range(layers)])
    return P, (-0.05, -0.05, -0.01, 1.05, 1.05, layers * 0.01 + 0.01)


def _walls(box):
    lo, hi = np.asarray(box[:3]), np.asarray(box[3:])
    e = np.eye(3)
    return np.vstack([np.c_[-e, -lo], np.c_[e, hi]])


@pytest.mark.parametrize("seed", [32, 0, 4])
def test_layered_sites_keep_neighbours_beyond_the_ordered_buckets(seed):
    P, box = _columns(seed)
    d = vf.voronoi3d(P, box)
    V = float(np.prod(np.subtract(box[3:], box[:3])))
    assert abs(d.volumes.sum() / V - 1) < 1e-12
    # the largest cells against a brute-force cut (seed 32: cell 407 was 0.6% too big)
    for i in np.argsort(d.volumes)[-5:]:
        near = np.flatnonzero(np.linalg.norm(P - P[i], axis=1) < 4 * np.cbrt(d.volumes[i]))
        v = brute_cell(P[near], int(np.flatnonzero(near == i)[0]), _walls(box))
        assert d.volumes[i] == pytest.approx(ConvexHull(v).volume, rel=1e-9)


def _brute_torus_volume(P, i, L):
    """Volume of cell ``i`` of the torus ``[0, L)`` from the 27 images of every site."""
    shifts = np.array([(a, b, c) for a in (-1, 0, 1) for b in (-1, 0, 1) for c in (-1, 0, 1)])
    imgs = (P[None, :, :] + shifts[:, None, :] * L).reshape(-1, 3)
    imgs = np.vstack([P[i], np.delete(imgs, 13 * len(P) + i, axis=0)])
    big = (*(-L), *(2 * L))
    return ConvexHull(brute_cell(imgs, 0, _walls(big))).volume


@pytest.mark.parametrize(("L", "n", "seed"), [((1, 1, 0.01), 200, 4), ((1, 1, 0.01), 200, 5)])
def test_thin_periodic_box_cells(L, n, seed):
    L = np.array(L, float)
    P = np.random.default_rng(seed).random((n, 3)) * L
    d = vf.voronoi3d(P, (0, 0, 0, *L), periodic=True)
    assert abs(d.volumes.sum() / L.prod() - 1) < 1e-12
    for i in np.argsort(d.volumes)[-3:]:
        assert d.volumes[i] == pytest.approx(_brute_torus_volume(P, i, L), rel=1e-9)


@pytest.mark.parametrize(("L", "seed"), [((1, 1, 0.01), 0), ((1, 1, 1e-3), 1), ((1e-3, 1, 1), 6)])
def test_thin_periodic_box_few_sites_returns(L, seed):
    L = np.array(L, float)
    P = np.random.default_rng(seed).random((5, 3)) * L
    d = vf.voronoi3d(P, (0, 0, 0, *L), periodic=True)
    assert abs(d.volumes.sum() / L.prod() - 1) < 1e-10
    assert (d.volumes > 0).all()


def _torus_nearest(Q, P, w, L):
    """Exact minimum-image power-nearest site (lowest index on ties), in rationals."""
    out = []
    for q in Q:
        keys = []
        for j, p in enumerate(P):
            t = Fraction(0)
            for a in range(3):
                dl = (Fraction(float(q[a])) - Fraction(float(p[a]))) % Fraction(float(L[a]))
                dl = min(dl, Fraction(float(L[a])) - dl)
                t += dl * dl
            keys.append((t - Fraction(float(w[j])), j))
        out.append(min(keys)[1])
    return np.array(out)


def test_locate_wraps_on_the_torus():
    d = vf.voronoi3d([[0.05, 0.5, 0.5], [0.5, 0.5, 0.5]], (0, 0, 0, 1, 1, 1), periodic=True)
    assert d.locate([0.9, 0.5, 0.5]) == 0  # 0.15 across the wrap against 0.4
    assert d.locate([-3.1, 0.5, 0.5]) == 0  # queries outside the box wrap too
    g = np.random.default_rng(1)
    L = np.array([1.0, 3.0, 0.5])
    P = g.random((100, 3)) * L  # over 64 sites: unweighted, a periodic KD-tree first
    Q = g.random((150, 3)) * L * 3 - L
    for w in (None, g.random(100) * 0.01):
        d = vf.voronoi3d(P, (0, 0, 0, *L), periodic=True, weights=w)
        want = _torus_nearest(Q, P, np.zeros(100) if w is None else w, L)
        assert (d.locate(Q) == want).all()


def test_locate_exact_ties_across_the_wrap():
    P = np.array([[0.875, 0.5, 0.5], [0.125, 0.5, 0.5], [0.5, 0.5, 0.5]])
    d = vf.voronoi3d(P, (0, 0, 0, 1, 1, 1), periodic=True)
    # x = 0 and x = 1 are one point, equidistant from sites 0 and 1: the lowest index
    Q = np.array([[0.0, 0.5, 0.5], [1.0, 0.5, 0.5], [0.3125, 0.5, 0.5], [0.6875, 0.5, 0.5]])
    assert d.locate(Q).tolist() == _torus_nearest(Q, P, np.zeros(3), np.ones(3)).tolist()
    assert d.locate(Q).tolist() == [0, 0, 1, 0]


def test_locate_lattice_ties_on_the_torus():
    # 4 x 4 x 5 lattice (80 sites, the KD-tree path): a query at a lattice cell's centre, or
    # its image across the wrap, is equidistant to 8 sites (more than the tree's 8 nearest
    # can settle: scanned in full), a face centre to 4: the lowest index
    g = (np.arange(4) + 0.5) / 4
    gz = (np.arange(5) + 0.5) / 5
    P = np.stack(np.meshgrid(g, g, gz, indexing="ij"), -1).reshape(-1, 3)
    d = vf.voronoi3d(P, (0, 0, 0, 1, 1, 1), periodic=True)
    Q = np.array([[0.0, 0.0, 0.0], [1.0, 0.25, 0.2], [0.5, 0.5, 0.4], [0.125, 0.5, 0.5]])
    assert d.locate(Q).tolist() == _torus_nearest(Q, P, np.zeros(len(P)), np.ones(3)).tolist()
