"""The compile step's workloads compile the signatures that the tests then meet.

A cold suite (session 59) compiled ``kernels.centers.contract_by``, ``kernels.plotter.two_opt``,
``engine.describe3d._unmatched`` and ``io.parquet._pairs_csr`` in both pytest workers
(~13, 8, 6 and 4 s each time): no workload of :data:`voroforge.warmup.SUITE_GROUPS`
reached them. Each now is reached by one; here each workload runs (from the cache after
``make test``'s compile step), and then the public call the tests make on other inputs
must find its kernel's signature already there (no compile of its own).
"""

from __future__ import annotations

import numba
import numpy as np
import pytest

import voroforge as vf
from voroforge import warmup
from voroforge.engine import describe3d
from voroforge.io import parquet
from voroforge.io.plotter import order_paths
from voroforge.kernels import centers, plotter

from catalogue import CATALOGUE

pytestmark = pytest.mark.skipif(numba.config.DISABLE_JIT, reason="signatures need the JIT")


def _sigs(*dispatchers):
    return [len(d.signatures) for d in dispatchers]


def test_paths_workload_compiles_two_opt_and_pairs_csr_as_used():
    warmup._suite_paths()
    before = _sigs(plotter.two_opt, parquet._pairs_csr)
    assert min(before) >= 1
    rng = np.random.default_rng(3)
    paths = [rng.random((k % 4 + 1, 2)) * 50.0 for k in range(20)]
    order, flip = order_paths(paths, start=(0.0, 50.0), closed=[k % 3 == 0 for k in range(20)])
    assert sorted(order) == list(range(20)) and len(flip) == 20
    d = vf.voronoi(rng.random((30, 2)))
    off, nb = parquet.neighbor_lists(d.edges.pairs, 30)
    assert off[-1] == len(nb) == 2 * len(d.edges.pairs)
    assert _sigs(plotter.two_opt, parquet._pairs_csr) == before


def test_delaunay_workload_compiles_contract_by_as_used():
    warmup._suite_2d_delaunay()
    before = _sigs(centers.contract_by)
    assert before[0] >= 1
    d = vf.voronoi(CATALOGUE["float_circle_100_far"][0])
    assert np.isfinite(d.areas).all()
    assert _sigs(centers.contract_by) == before


def test_3d_workload_compiles_unmatched_as_used():
    warmup._suite_3d()
    before = _sigs(describe3d._unmatched)
    assert before[0] >= 1
    p = np.random.default_rng(4).random((50, 3))
    d = vf.voronoi3d(p, (0.0, 0.0, 0.0, 1.0, 1.0, 1.0), periodic=True)
    assert d.unmatched_vertices == 0
    assert _sigs(describe3d._unmatched) == before
