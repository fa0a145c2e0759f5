"""Issue 12: the k-d walk tests a box from the vertex found near its parent's box (s59).

:func:`reach3d.box_near` (was ``box_misses``) returns a vertex of the cell that a site in
the box may reach, or -1 where the box misses the cell, reading the vertices from a start
on, in blocks; :func:`walk3d.next_leaf` starts each child's test at the vertex found for
its parent (kept in the heap entry). Neither may change an answer: whatever the start, the
box misses exactly when no vertex passes the per-vertex test, and a vertex returned passes
it. The three lines (crowded: k-d buckets) still give their cells.
"""

from __future__ import annotations

import numpy as np

import voroforge as vf
from catalogue3d import three_lines
from reference3d import brute_volumes
from voroforge.config import VORONOI3D_STOP_RTOL
from voroforge.engine.build3d import search3d
from voroforge.kernels import reach3d


def _near_plain(p, box, V, wi, wmax, rmax2, eps):
    """The per-vertex test of ``box_near``, in Python, vertex by vertex."""
    lo = box[:3] - p - eps
    hi = box[3:] - p + eps
    slack = VORONOI3D_STOP_RTOL * (rmax2 + abs(wi) + abs(wmax)) + wmax - wi
    out = []
    for x in V:
        g = [max(lo[a] - x[a], 0.0, x[a] - hi[a]) for a in range(3)]
        d = (g[0] * g[0] + g[1] * g[1]) + g[2] * g[2]
        out.append(d <= (x[0] * x[0] + x[1] * x[1]) + x[2] * x[2] + slack)
    return np.array(out, bool)


def test_box_near_any_start():
    rng = np.random.default_rng(59)
    seen = [0, 0]
    for _ in range(400):
        nv = int(rng.integers(0, 30))
        V = rng.normal(size=(nv + 2, 3)) * rng.choice([1e-3, 1.0, 1e3])
        if rng.random() < 0.3:  # ties on the box's sides
            V = np.round(V, 1)
        c = rng.normal(size=3) * rng.choice([0.5, 2.0, 5.0])
        w = np.abs(rng.normal(size=3)) * rng.choice([0.0, 0.1, 1.0])
        box = np.r_[c - w, c + w]
        p = rng.normal(size=3) * 0.01
        wi, wmax = (0.0, 0.0) if rng.random() < 0.5 else (0.01, 0.02)
        rmax2 = float(rng.choice([0.0, 1.0]))
        eps = float(rng.choice([0.0, 1e-15, 1e-3]))
        near = _near_plain(p, box, V[:nv], wi, wmax, rmax2, eps)
        seen[bool(near.any())] += 1
        for first in (-1, 0, nv // 2, nv - 1, nv, nv + 5):
            k = reach3d.box_near(p[0], p[1], p[2], box, V, nv, wi, wmax, rmax2, eps, first)
            if near.any():
                assert 0 <= k < nv and near[k]
            else:
                assert k == -1
    assert min(seen) > 50  # both answers met


def test_three_lines_kd_cells():
    pts = three_lines(600)
    assert len(search3d(pts)[5]) > 0  # the k-d buckets' walk, not the grid's
    d = vf.voronoi3d(pts, None)
    cells = np.arange(0, 600, 97)
    ref = brute_volumes(pts, np.asarray(d.walls), None, cells=cells)
    np.testing.assert_allclose(d.volumes[cells], ref, rtol=1e-9, atol=0)
