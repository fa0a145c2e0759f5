"""Issue 10: the half-plane settling skips the exact incircle at a rectangle's corners.

``halfplane_settle._edge_ok`` answers "no edge" for four corners of an axis-aligned rectangle
without the exact ``incircle`` (they are exactly cocircular: its value is 0). The answer must
be the one the exact predicate gives, for every order of the points.
"""

from __future__ import annotations

import itertools

import numpy as np

from voroforge.kernels.halfplane_settle import _edge_ok, _rectangle
from voroforge.kernels.predicates import incircle, orient2d


def _reference_edge_ok(i, j, p, q, xs, ys):
    """``_edge_ok`` as it was: both turns, then the exact incircle."""
    if orient2d(xs[i], ys[i], xs[j], ys[j], xs[p], ys[p]) >= 0.0:
        return False
    if orient2d(xs[i], ys[i], xs[j], ys[j], xs[q], ys[q]) <= 0.0:
        return False
    return incircle(xs[i], ys[i], xs[j], ys[j], xs[q], ys[q], xs[p], ys[p]) < 0.0


def test_rectangle_corners_in_every_order():
    rng = np.random.default_rng(7)
    for scale, offset in ((1.0, 0.0), (1e-9, 0.0), (1e3, 5e13), (0.1, -7.0)):
        for _ in range(5):
            x0, x1 = offset + scale * rng.random(2)
            y0, y1 = offset + scale * rng.random(2)
            corners = [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]
            for perm in itertools.permutations(corners):
                args = [v for pt in perm for v in pt]
                assert _rectangle(*args)
                assert incircle(*args) == 0.0


def test_not_rectangles():
    cases = [
        [(0.0, 0.0), (1.0, 1.0), (0.0, 2.0), (-1.0, 1.0)],  # a square turned 45 degrees
        [(0.0, 0.0), (2.0, 0.0), (1.0, 1.0), (0.0, 1.0)],  # a trapezoid: corner moved
        [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.5)],  # shares both axes, not closed
        [(0.0, 0.0), (0.0, 0.0), (1.0, 1.0), (1.0, 1.0)],  # repeated points
        [(0.0, 0.0), (0.0, 1.0), (0.0, 2.0), (1.0, 0.0)],  # three on one vertical line
        [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (0.0, 1.0)],  # three corners and a repeat
    ]
    for pts in cases:
        for perm in itertools.permutations(pts):
            assert not _rectangle(*[v for pt in perm for v in pt])


def test_edge_ok_unchanged_on_a_lattice():
    """Quadruples of a small lattice (many rectangles, many other cocircular sets)."""
    axis = (np.arange(5, dtype=np.float64) + 0.5) / 5
    gx, gy = np.meshgrid(axis, axis)
    xs = np.ascontiguousarray(gx.ravel())
    ys = np.ascontiguousarray(gy.ravel())
    rng = np.random.default_rng(11)
    taken = 0
    for _ in range(20000):
        i, j, p, q = (int(v) for v in rng.choice(xs.shape[0], 4, replace=False))
        want = _reference_edge_ok(i, j, p, q, xs, ys)
        assert _edge_ok(i, j, p, q, xs, ys) == want
        turns = orient2d(xs[i], ys[i], xs[j], ys[j], xs[p], ys[p]) < 0.0
        turns = turns and orient2d(xs[i], ys[i], xs[j], ys[j], xs[q], ys[q]) > 0.0
        taken += turns and _rectangle(xs[i], ys[i], xs[j], ys[j], xs[q], ys[q], xs[p], ys[p])
    assert taken > 10  # the fast path was taken
