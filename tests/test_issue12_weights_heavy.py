"""A few heavy sites among light ones: searched apart, cut by last (issue 12).

One site of weight 1 among n of weight 0 empties most cells, and each light cell near it
searched every site nearer than the heavy one (quadratic; the max-weight pyramid bounds
its own buckets only). Sites heavier than the lightest by more than a few squared bucket
sides (at most ``REACH3D_HEAVY_MOST``) now leave the pyramid: the search bounds the light
sites and the cell is then cut by every heavy site that can reach it
(:mod:`voroforge.kernels.reach3d`). Checked against voro++'s radical tessellation (``-r``),
brute-force power cells (every other site's halfspace) and power-distance samples.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial import ConvexHull

import voroforge as vf
from reference3d import brute_volumes
from test_issue12_weights_owners import VOROPP, voropp_radical
from voroforge.engine.build3d import search3d
from voroforge.kernels.reach3d import heavy_sites, weight_reach

BOX = (0.0, 0.0, 0.0, 1.0, 1.0, 1.0)
WALLS = np.array(
    [[-1, 0, 0, 0], [0, -1, 0, 0], [0, 0, -1, 0], [1, 0, 0, 1], [0, 1, 0, 1], [0, 0, 1, 1]],
    float,
)


def _cases():
    rng = np.random.default_rng(21)
    n = 1500
    P = rng.random((n, 3))
    one = np.zeros(n)
    one[5] = 1.0  # most cells empty
    corner = np.zeros(n)
    P2 = P.copy()
    P2[9] = (0.02, 0.03, 0.01)
    corner[9] = 0.3  # a heavy site in a corner: a ball of empty cells, the rest cut by it
    few = rng.normal(size=n) * 1e-4  # light sites with weights of their own
    few[[3, 400, 1200]] = (0.06, 0.2, 0.12)
    negative = np.zeros(n)
    negative[:40] = -0.05  # the light ones are these: 1,460 heavy, too many to list
    clustered = np.vstack([0.5 + 0.01 * rng.standard_normal((800, 3)), rng.random((700, 3))])
    cw = np.zeros(len(clustered))
    cw[[0, 900]] = (0.01, 0.08)  # the k-d search
    return {
        "one": (P, one),
        "corner": (P2, corner),
        "few": (P, few),
        "negative": (P, negative),
        "clustered": (clustered, cw),
    }


CASES = _cases()


@pytest.mark.parametrize("name", list(CASES))
def test_volumes_match_references(name):
    P, W = CASES[name]
    d = vf.voronoi3d(P, BOX, weights=W)
    assert d.volumes.sum() == pytest.approx(1.0, rel=1e-12)
    if VOROPP is not None:
        np.testing.assert_allclose(d.volumes, voropp_radical(P, W, BOX), rtol=1e-5, atol=1e-9)
    # brute-force power cells of the heavy sites and of some cells around them
    some = set(np.argsort(W)[-3:].tolist())
    for h in list(some):
        some |= set(np.argsort(((P - P[h]) ** 2).sum(1))[1:4].tolist())
    some = sorted(some)
    ref = brute_volumes(P, WALLS, W, cells=some)
    np.testing.assert_allclose(d.volumes[some], ref, rtol=0, atol=1e-10)
    # samples lie in the cell of their least-power site
    x = np.random.default_rng(1).random((2000, 3))
    near = np.argmin(((x[:, None, :] - P[None]) ** 2).sum(-1) - W[None], axis=1)
    for i in np.unique(near)[::13]:
        h = ConvexHull(np.asarray(d.cell(int(i)).vertices)).equations
        assert (x[near == i] @ h[:, :3].T + h[:, 3] <= 1e-9).all(), int(i)


def test_heavy_sites_leave_the_pyramid():
    P, W = CASES["few"]
    g, _, _, sidx, *_ = search3d(P)
    assert heavy_sites(W, g).tolist() == [3, 400, 1200]
    G = weight_reach(P, W, g, sidx)
    hb = 12 + int(G[10])
    assert int(G[hb]) == 3 and G[hb + 1] == np.delete(W, [3, 400, 1200]).max()
    assert sorted(sidx[G[hb + 2 : hb + 5].astype(int)].tolist()) == [3, 400, 1200]
    top = G[int(G[11 + int(G[10])])]  # the pyramid's top: the light sites' heaviest
    assert top == G[hb + 1]
    # too many heavy sites: none listed, the pyramid holds them all
    Pn, Wn = CASES["negative"]
    gn, _, _, sn, *_ = search3d(Pn)
    assert len(heavy_sites(Wn, gn)) == 0
    Gn = weight_reach(Pn, Wn, gn, sn)
    assert int(Gn[12 + int(Gn[10])]) == 0
