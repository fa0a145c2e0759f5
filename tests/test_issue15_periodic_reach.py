"""Issue 15, periodic margins: the exact disk test and the measured asks (perlines2).

A vertex of a kept cell is proved when no copy left out of the diagram (past the grown box)
lies in its empty disk: the cell is the hull of its vertices, and a copy cuts it only at a
vertex whose disk holds it. :func:`voroforge.engine.periodic_chord.disks_clear` searches the
copies left out near the grown box; a failing vertex whose disk holds a few of them asks for
the margins that take them in (:func:`voroforge.engine.periodic_chord.disk_asks`), not for
its whole radius (a vertical line of sites and one off it asked for 1.34 periods of y: 7 n
copies where 4 n are proved).
"""

from __future__ import annotations

import numpy as np
import pytest

from test_issue15_periodic import _check_torus
from voroforge.engine.periodic_chord import disk_asks, disks_clear

BOX = (0.0, 0.0, 3.0, 2.0)


def _brute(v, r, sites, box, margin):
    """Per disk, the copies (|shift| <= 4) outside the grown box within ``r``: brute force."""
    x0, y0, x1, y1 = box
    mx, my = margin
    w, h = x1 - x0, y1 - y0
    out = [[] for _ in range(len(v))]
    for a in range(-4, 5):
        for b in range(-4, 5):
            if not (a or b):
                continue
            img = sites + np.array([a * w, b * h])
            kept = (
                (img[:, 0] >= x0 - mx)
                & (img[:, 0] <= x1 + mx)
                & (img[:, 1] >= y0 - my)
                & (img[:, 1] <= y1 + my)
            )
            q = img[~kept]
            dist = np.hypot(q[:, 0] - v[:, None, 0], q[:, 1] - v[:, None, 1])
            for i, j in zip(*np.nonzero(dist <= r[:, None]), strict=True):
                out[i].append(q[j])
    return [np.array(o).reshape(-1, 2) for o in out]


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_disks_match_brute_force(seed):
    rng = np.random.default_rng(seed)
    sites = rng.random((40, 2)) * [3.0, 2.0]
    margin = (0.3 + 0.5 * rng.random(), 0.2 + 0.5 * rng.random())
    v = rng.random((200, 2)) * [3.0 + 2 * margin[0], 2.0 + 2 * margin[1]] - margin
    r = 0.05 + 0.6 * rng.random(200)
    want = _brute(v, r, sites, BOX, margin)
    clear = disks_clear(v, r, sites, BOX, margin, 0.0, np.ones(200, dtype=bool))
    np.testing.assert_array_equal(clear, [len(o) == 0 for o in want])
    count, asks = disk_asks(v, r, sites, BOX, margin, 0.0, np.arange(200), 16)
    np.testing.assert_array_equal(count, [min(len(o), 17) for o in want])
    few = [o for o in want if 0 < len(o) <= 16]
    if few:
        q = np.concatenate(few)
        past = [np.maximum(BOX[k] - q[:, k], q[:, k] - BOX[k + 2]).max() for k in (0, 1)]
        np.testing.assert_array_equal(asks, [max(p, 0.0) for p in past])


def _line_and_one(kind: str, n: int, seed: int):
    rng = np.random.default_rng(seed)
    t = np.unique(np.floor(rng.random(n) * 2.0**20) / 2.0**20)  # dyadic: exact copies
    if kind == "v":
        p = np.column_stack((np.full(len(t), 1.125), t * 2.0))
    else:  # a sloped line wrapped on the torus
        s = float(kind)
        p = np.column_stack((t * 3.0, np.mod(s * t * 3.0 + 0.1, 2.0)))
    return np.vstack((p, [[1.234375, 1.5625]]))


def test_vertical_line_and_one_asks_what_its_disks_hold(periodic_builds):
    p = _line_and_one("v", 400, 4)
    sizes = periodic_builds
    _check_torus(p, BOX, "delaunay", False, samples=300)
    # the off site's cell, cut off by the grown box's top, asked for 1.34 periods of y
    # (the last build 7 n): now the few copies in its disk, a quarter period
    assert sizes[-1] <= 4.5 * sizes[0], sizes


@pytest.mark.parametrize("kind", ["0.3", "0.7", "2"])
@pytest.mark.parametrize("wrap", [False, True])
def test_sloped_lines_torus_cells(kind, wrap):
    # every cell valid, areas summing to the box, nearest-site samples on the torus exact
    _check_torus(_line_and_one(kind, 300, 5), BOX, "delaunay", wrap, samples=300)
