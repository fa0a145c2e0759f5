"""Issue 15: the fold test on a sloped float line with one site off it (checker23 F5).

The off-line site's ring has a vertex per line site; sites a few ulps apart on the line
round its vertices across each other, so the ring folds at a few turns and its fold test
stalls (no join within any reach). Each reach read the whole ring again, and the stalled
test read the whole fan at every bad turn. ``kernels.folds`` now matches the ring to its
fan once (``_matched``) and looks vertices up in the fan sorted by their bits
(``_sorted_by_bits``, ``_bits_range``). Checked here: the lookup against a plain scan
(ties, signed zeros, NaN), and a folded line's diagram against its own exact invariants
and the other algorithms.
"""

from __future__ import annotations

import numpy as np
import shapely

import voroforge as vf
from voroforge.kernels.folds import _bits_range, _sorted_by_bits


def test_bits_lookup_is_the_plain_scan():
    rng = np.random.default_rng(3)
    values = np.array([0.0, -0.0, 1.5, -2.25, 1e300, np.nan, 3.0])
    for _ in range(60):
        t = int(rng.integers(1, 200))
        cx = values[rng.integers(0, len(values), t)]
        cy = values[rng.integers(0, len(values), t)]
        fan = rng.permutation(t)[: int(rng.integers(1, t + 1))].astype(np.int64)
        by = _sorted_by_bits(fan, cx, cy)
        for x in values:
            for y in values:
                lo, hi = _bits_range(by, fan, cx, cy, x, y)
                got = [int(fan[by[q]]) for q in range(lo, hi) if cx[fan[by[q]]] == x]
                want = [int(f) for f in fan if cx[f] == x and cy[f] == y]
                assert got == want  # every match, in fan order
                assert hi - lo == len(want)


def _sloped_close(n, pairs, gap, slope=0.3, seed=0):
    """``n`` float sites on ``y = slope x + 100``, ``pairs`` of them with a partner ``gap``
    to ``2 gap`` further along, and one site off the line."""
    g = np.random.default_rng(seed)
    x = g.random(n) * 1000.0
    x = np.concatenate((x, x[:pairs] + gap * (1.0 + g.random(pairs))))
    off = [500.0, slope * 500.0 + 100.0 + 450.0 * np.hypot(1.0, slope)]
    return np.concatenate((np.column_stack((x, slope * x + 100.0)), [off]))


def test_folded_sloped_line_cells():
    # the off-line ring folds at 15 turns here (more than the plain scan's limit)
    p = _sloped_close(2000, 60, 3e-11)
    got = {a: vf.voronoi(p, algorithm=a) for a in ("delaunay", "fortune", "halfplane")}
    d = got["delaunay"]
    cells = np.asarray(d.cells, dtype=object)
    assert shapely.is_valid(cells).all()
    assert shapely.intersects_xy(cells, p[:, 0], p[:, 1]).all()  # each site in its cell
    x0, y0 = p.min(axis=0)
    x1, y1 = p.max(axis=0)
    box = (x1 - x0) * (y1 - y0) * 1.2**2  # the default box: 10% each side
    assert np.isclose(shapely.area(cells).sum(), box, rtol=1e-12)
    ind, idx = d.neighbors
    pairs = {(i, int(j)) for i in range(len(p)) for j in idx[ind[i] : ind[i + 1]]}
    assert all((j, i) in pairs for i, j in pairs)
    assert len(idx[ind[-2] : ind[-1]]) > 1800  # the off-line site meets the line's sites
    for a in ("fortune", "halfplane"):
        other = np.asarray(got[a].cells, dtype=object)
        assert np.allclose(shapely.area(other), shapely.area(cells), rtol=0, atol=1e-9 * box)
