"""power_fit on far MultiPolygon parts (issue 15, fit6).

Three or more far parts share the sites by a transport of their targets to the parts' areas
at cost ``|p_i - c_k|^2``. HiGHS's dual simplex solves it to a tolerance of 1e-7 on costs
scaled to 1, and sites of one cluster whose costs differ by less than that (nearly tied
across a gap of 1e6) could be left on the wrong side of the split. The answer is now checked
and mended in exact arithmetic. The test checks optimality independently: a transport is
optimal exactly when no cycle of parts ``a -> b -> ... -> a``, each arc's cost change
``min over sites i sending to a of -2 p_i . (c_b - c_a)``, sums below zero (exact Fractions).
"""

from __future__ import annotations

from fractions import Fraction
from itertools import permutations

import numpy as np
import pytest
import shapely
from shapely.geometry import MultiPolygon, box

from voroforge.engine.farparts import transport


def _squares(gap, k=3):
    offs = [(0.0, 0.0), (gap, 0.0), (0.0, gap), (gap, gap)][:k]
    return MultiPolygon([box(x, y, x + 1, y + 1) for x, y in offs])


def _worst_cycle(pts, share, cent, t):
    """The most negative exact cost change around a cycle of 2 or 3 parts (0 if none)."""
    k = len(cent)
    p = [(Fraction(float(x)), Fraction(float(y))) for x, y in pts]
    c = [(Fraction(float(x)), Fraction(float(y))) for x, y in cent]
    arc = {}
    for a in range(k):
        sends = np.flatnonzero(share[:, a] > 1e-9 * t)
        for b in range(k):
            if a != b and len(sends):
                dx, dy = c[b][0] - c[a][0], c[b][1] - c[a][1]
                arc[a, b] = min(-2 * (p[i][0] * dx + p[i][1] * dy) for i in sends)
    worst = Fraction(0)
    for m in (2, 3):
        for cyc in permutations(range(k), m):
            pairs = list(zip(cyc, cyc[1:] + cyc[:1], strict=True))
            if all(q in arc for q in pairs):
                worst = min(worst, sum(arc[q] for q in pairs))
    return worst


@pytest.mark.parametrize("seed", range(6))
@pytest.mark.parametrize("k", [3, 4])
def test_parts_transport_is_exactly_optimal_with_nearly_tied_sites(seed, k):
    # sites on a coarse grid, each jittered by 1e-9: across a gap of 1e6 their costs tie to
    # ~1e-9 relative, under HiGHS's tolerance (9 of these 10 draws had a negative cycle)
    dom = _squares(1e6, k)
    parts = shapely.get_parts(dom)
    cent = shapely.get_coordinates(shapely.centroid(parts))
    areas = shapely.area(parts)
    rng = np.random.default_rng(seed)
    pts = np.round(rng.random((24, 2)) * 8) / 8 + rng.random((24, 2)) * 1e-9
    t = rng.random(24) + 0.5
    t = t / t.sum() * areas.sum()
    share = transport(pts, t, cent, areas)
    assert (share >= 0.0).all()
    assert np.allclose(share.sum(axis=1), t, rtol=1e-9, atol=0.0)
    assert np.allclose(share.sum(axis=0), areas, rtol=1e-9, atol=0.0)
    assert _worst_cycle(pts, share, cent, t) >= 0


def test_far_parts_at_float_limit_fail_fast_with_why(monkeypatch):
    # sites in both squares 5,000 apart, random targets: a cell straddles the gap from the far
    # side, its weight ~2.5e7 from its neighbours' (float64 holds it to ~4e-9, the areas to
    # a few 1e-6; not refused up front: the median cell's limit is 1.6e-6). The joined
    # parts' weights are returned unpolished (a polish's steps round back to them) and no
    # other start runs
    import voroforge as vf
    import voroforge.engine.capacity as capacity

    n = 200
    dom = MultiPolygon([box(0, 0, 1, 1), box(5000, 0, 5001, 1)])
    rng = np.random.default_rng(8)
    pts = rng.random((n, 2)) + np.array([[0.0, 0.0], [5000.0, 0.0]])[np.arange(n) % 2]
    t = rng.random(n) + 0.5
    t = t / t.sum() * 2.0
    plain = capacity.fit_weights

    def parts_only(p, *args, **kw):
        assert len(p) < n, "the joined weights were polished"
        return plain(p, *args, **kw)

    def fail(*args):
        raise AssertionError("another start ran")

    monkeypatch.setattr(capacity, "fit_weights", parts_only)
    monkeypatch.setattr(capacity, "_gap_continuation", fail)
    monkeypatch.setattr(capacity, "_continuation", fail)
    with pytest.raises(RuntimeError, match="a cell that must straddle far parts"):
        vf.power_fit(pts, t, dom)
