"""Issue 12's speed work on the 3D path keeps the results (not timings).

- ``build3d.build_order``: for the first ``k`` sites (all of them, or a periodic build's sites
  before their images) the build order is taken from the sites' bucket sort instead of a
  second stable sort of their keys; it must be the same permutation.
"""

from __future__ import annotations

import numpy as np
import pytest

from voroforge.engine.build3d import bucket_keys3d, build_order, search3d


@pytest.mark.parametrize("n", [1, 7, 500, 3001])
@pytest.mark.parametrize("kind", ["uniform", "grid", "layer"])
def test_build_order_first_sites(n, kind):
    rng = np.random.default_rng(n)
    if kind == "uniform":
        P = rng.random((n, 3))
    elif kind == "grid":  # many equal keys: ties keep the sites' order
        P = np.floor(rng.random((n, 3)) * 16) / 16 + 1 / 32
    else:  # a flat layer (one bucket thick)
        P = np.column_stack([rng.random(n), rng.random(n), np.full(n, 0.5)])
    g, start, SP, sidx, order, tree = search3d(P)
    assert len(tree) == 0
    for k in sorted({1, n // 3, n - 1, n} - {0}):
        cells = np.arange(k)
        want = np.argsort(bucket_keys3d(P[cells], g), kind="stable")
        got = build_order(P, cells, g, sidx, tree)
        assert np.array_equal(got, want)
    # any other list of cells takes the general sort
    cells = np.arange(n)[::-1].copy()
    want = np.argsort(bucket_keys3d(P[cells], g), kind="stable")
    assert np.array_equal(build_order(P, cells, g, sidx, tree), want)
