"""io.snap: near pairs, clusters and k nearest without a KD-tree, checked against scipy."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

from voroforge.io.snap import NEAREST_BRUTE, close_pairs, cluster_labels, nearest, nearest_to


def _scipy_pairs(pts, tol):
    pairs = cKDTree(pts).query_pairs(tol, output_type="ndarray").astype(np.int64)
    pairs = np.sort(pairs, axis=1).reshape(-1, 2)
    return pairs[np.lexsort((pairs[:, 1], pairs[:, 0]))]


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_close_pairs_match_query_pairs(seed):
    rng = np.random.default_rng(seed)
    base = rng.random((400, 2)) * 10.0 ** rng.integers(-3, 4)
    # clusters of near copies, exact duplicates and points on a cell-sized lattice
    tol = 1e-6 * float(np.ptp(base))
    near = base[:60] + rng.normal(size=(60, 2)) * tol * 0.6
    lattice = np.stack(np.meshgrid(np.arange(6), np.arange(6)), -1).reshape(-1, 2) * tol
    pts = np.vstack((base, near, base[:10], lattice + base[0]))
    got = close_pairs(pts, tol)
    want = _scipy_pairs(pts, tol)
    assert len(want) > 60  # the test has pairs to find
    np.testing.assert_array_equal(got, want)


def test_close_pairs_edge_cases():
    pts = np.array([[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]])
    assert close_pairs(pts, 0.0).shape == (0, 2)
    assert close_pairs(pts[:1], 5.0).shape == (0, 2)
    np.testing.assert_array_equal(close_pairs(pts, 1.0), [[0, 1], [1, 2]])  # <= tol counts
    np.testing.assert_array_equal(close_pairs(pts, 2.5), [[0, 1], [0, 2], [1, 2]])
    # an extent of more than 2**30 cells goes to scipy and gives the same answer
    far = np.array([[0.0, 0.0], [1e-12, 0.0], [1e6, 0.0]])
    np.testing.assert_array_equal(close_pairs(far, 1e-9), [[0, 1]])
    with pytest.raises(ValueError, match="tol"):
        close_pairs(pts, -1.0)
    with pytest.raises(ValueError, match="NaN"):
        close_pairs([[0.0, np.nan]], 1.0)


@pytest.mark.parametrize("seed", [0, 1])
def test_cluster_labels_match_connected_components(seed):
    rng = np.random.default_rng(seed)
    n = 300
    pairs = rng.integers(0, n, size=(220, 2))
    pairs = pairs[pairs[:, 0] != pairs[:, 1]]
    graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
    _, want = connected_components(graph, directed=False)
    np.testing.assert_array_equal(cluster_labels(n, pairs), want)
    # a long chain given backwards needs many rounds of label passing
    chain = np.stack((np.arange(1, 200), np.arange(0, 199)), axis=1)[::-1]
    assert set(cluster_labels(200, chain).tolist()) == {0}
    np.testing.assert_array_equal(cluster_labels(3, np.zeros((0, 2))), [0, 1, 2])


@pytest.mark.parametrize("n", [1, 7, 500, NEAREST_BRUTE + 5])
def test_nearest_gives_the_k_nearest_distances(n):
    rng = np.random.default_rng(n)
    pts = rng.random((n, 2))
    pts[n // 2 :: 7] = pts[n // 3]  # ties at distance 0 too
    k = min(n, 6)
    nb = nearest(pts, k)
    assert nb.shape == (n, k) and nb.dtype == np.int64
    got = np.linalg.norm(pts[nb] - pts[:, None, :], axis=2)
    want, _ = cKDTree(pts).query(pts, k=k)
    np.testing.assert_allclose(got, np.asarray(want).reshape(n, k), rtol=0, atol=1e-15)
    assert all(len(set(row)) == k for row in nb.tolist())  # k different points
    with pytest.raises(ValueError, match="k must be"):
        nearest(pts, n + 1)


@pytest.mark.parametrize("m", [1, 300])
def test_nearest_to_matches_a_kd_tree(m, monkeypatch):
    import voroforge.io.snap as snap

    rng = np.random.default_rng(m)
    pts = rng.random((m, 2))
    q = np.vstack((rng.random((500, 2)), pts[:3]))
    want_d, _ = cKDTree(pts).query(q, k=1)
    for budget in (snap.NEAREST_TO_BRUTE, 0):  # every pair, then the KD-tree route
        monkeypatch.setattr(snap, "NEAREST_TO_BRUTE", budget)
        d, i = nearest_to(pts, q)
        np.testing.assert_allclose(d, want_d, rtol=0, atol=1e-15)
        np.testing.assert_allclose(np.hypot(*(pts[i] - q).T), want_d, rtol=0, atol=1e-15)
    with pytest.raises(ValueError, match="at least one"):
        nearest_to(np.zeros((0, 2)), q)
