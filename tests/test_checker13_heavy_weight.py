"""3D power cells with a few heavy sites: the search's local stop (checker13 F4, issue 12).

One heavy site used to widen every cell's search by the global weight spread (quadratic).
The search now also stops on a local bound read off a max pyramid of the weights per bucket
(:mod:`voroforge.kernels.reach3d`). The bound is checked against every site directly, and
the cells against a brute-force power cell (every other site's halfspace, scipy).
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import linprog
from scipy.spatial import ConvexHull, HalfspaceIntersection

import voroforge as vf
from voroforge.engine.build3d import PER_BUCKET, grid3d_shape, search3d
from voroforge.kernels.reach3d import far, local_reach, weight_reach

BOX = (0.0, 0.0, 0.0, 1.0, 1.0, 1.0)


def _brute_volumes(P, W):
    """Power cell volumes in the unit box from all halfspaces (0 for an empty cell)."""
    n = len(P)
    box = np.array(
        [[-1, 0, 0, 0], [0, -1, 0, 0], [0, 0, -1, 0], [1, 0, 0, -1], [0, 1, 0, -1], [0, 0, 1, -1]],
        float,
    )
    out = np.zeros(n)
    for i in range(n):
        q = np.delete(np.arange(n), i)
        # |x - p|^2 - wp <= |x - q|^2 - wq  <=>  2 (q - p) . x - (|q|^2 - |p|^2 - wq + wp) <= 0
        A = 2.0 * (P[q] - P[i])
        b = (P[q] ** 2).sum(1) - (P[i] ** 2).sum() - W[q] + W[i]
        hs = np.vstack([np.column_stack([A, -b]), box])
        norm = np.linalg.norm(hs[:, :3], axis=1)
        # the deepest point: max t with A x + t |a| <= b
        res = linprog(
            np.r_[0, 0, 0, -1.0],
            A_ub=np.column_stack([hs[:, :3], norm]),
            b_ub=-hs[:, 3],
            bounds=[(None, None)] * 3 + [(None, 1.0)],
        )
        if res.status != 0 or res.x[3] < 1e-7:
            out[i] = 0.0 if res.status != 0 or res.x[3] < 1e-9 else np.nan
            continue
        h = HalfspaceIntersection(hs, res.x[:3])
        out[i] = ConvexHull(h.intersections).volume
    return out


def _cases():
    rng = np.random.default_rng(12)
    n = 160
    P = rng.random((n, 3))
    one = np.zeros(n)
    one[0] = 0.1
    heavy = np.zeros(n)
    heavy[7] = 1.0
    near = np.linalg.norm(P - P[3], axis=1) < 0.25
    clusters = np.where(near, 0.02 + 0.01 * rng.random(n), 0.0)
    neg = np.zeros(n)
    neg[:5] = -0.3  # a few very light sites among level ones
    spread = np.zeros(n)
    spread[11] = 1e4  # a spread far past the box: every other cell empty
    mixed = rng.normal(size=n) * 0.004
    mixed[20] = 0.05
    return {
        "one": (P, one),
        "heavy": (P, heavy),
        "clusters": (P, clusters),
        "negative": (P, neg),
        "spread": (P, spread),
        "mixed": (P, mixed),
        "random": (P, rng.random(n) * 0.01),
    }


@pytest.mark.parametrize("name", list(_cases()))
def test_power_cells_match_brute_force(name):
    P, W = _cases()[name]
    d = vf.voronoi3d(P, BOX, weights=W)
    ref = _brute_volumes(P, W)
    ok = ~np.isnan(ref)  # (cells thinner than the LP's tolerance are left out)
    assert ok.sum() > len(P) - 3
    np.testing.assert_allclose(d.volumes[ok], ref[ok], rtol=0, atol=1e-12)
    assert abs(d.volumes.sum() - 1.0) < 1e-12


def test_clustered_sites_kd_buckets_match_brute_force():
    """Crowded sites take the k-d search; a heavy site inside and one outside the cluster."""
    rng = np.random.default_rng(5)
    P = np.vstack([0.5 + 0.01 * rng.standard_normal((150, 3)), rng.random((30, 3))])
    g, *_, tree = search3d(P)
    assert tree.shape[0] > 0  # the k-d search is the one tested
    W = np.zeros(len(P))
    W[0] = 2e-4
    W[160] = 0.02
    d = vf.voronoi3d(P, BOX, weights=W)
    ref = _brute_volumes(P, W)
    ok = ~np.isnan(ref)
    np.testing.assert_allclose(d.volumes[ok], ref[ok], rtol=0, atol=1e-12)


def _check_bound(P, W, rmax2, cells):
    """No site beyond the local bound could cut a cell of radius sqrt(rmax2) around p."""
    g = weight_reach(P, W, grid3d_shape(P, PER_BUCKET))
    assert g.shape[0] > 10
    out = []
    for i in cells:
        gs2 = local_reach(P[i, 0], P[i, 1], P[i, 2], W[i], rmax2, g)
        d2 = ((P - P[i]) ** 2).sum(1)
        beyond = d2 >= gs2
        for q in np.flatnonzero(beyond):
            assert far(d2[q], W[i], max(W[q], W[i]), rmax2), (i, q, gs2, d2[q])
        # and a site just inside the bound that the bound is there for: it could cut
        out.append(gs2)
    return np.array(out)


def test_local_bound_holds_for_every_site():
    rng = np.random.default_rng(8)
    for trial in range(6):
        n = 3000
        P = rng.random((n, 3)) * rng.uniform(0.5, 20.0, 3)
        W = np.where(rng.random(n) < 0.01, rng.uniform(-1, 4, n), 0.0) * P.max()
        if trial % 2:
            W += rng.normal(size=n) * 0.01 * P.max()
        for rmax2 in (1e-4, 0.01, 1.0):
            _check_bound(P, W, rmax2 * P.max() ** 2, rng.integers(0, n, 40))


def test_local_bound_is_local():
    """Far from the one heavy site the bound is the equal-weights one, near it the heavy one."""
    rng = np.random.default_rng(2)
    n = 20000
    P = rng.random((n, 3))
    W = np.zeros(n)
    W[0] = 0.1
    P[0] = (0.1, 0.1, 0.1)
    rmax2 = 0.03**2
    d0 = np.linalg.norm(P - P[0], axis=1)
    far_cells = np.flatnonzero(d0 > 0.6)[:50]
    near_cells = np.flatnonzero((d0 > 0.05) & (d0 < 0.2))[:50]
    gs_far = _check_bound(P, W, rmax2, far_cells)
    gs_near = _check_bound(P, W, rmax2, near_cells)
    # equal weights need 4 rmax2 (twice the radius); the global spread would need > 0.1
    assert gs_far.max() < 0.01
    assert gs_near.min() > 0.1
