"""Slow, obvious references for io/plotter: brute nearest neighbour + full 2-opt, segment sets."""

from __future__ import annotations

import math

import numpy as np


def _d(a, b) -> float:
    return math.hypot(a[0] - b[0], a[1] - b[1])


def tour_length(paths, order, flipped, start) -> float:
    """Pen-up travel of drawing ``paths`` in ``order`` (reversed where ``flipped``)."""
    pos = tuple(start)
    up = 0.0
    for i, f in zip(order, flipped, strict=True):
        p = np.asarray(paths[i])
        head, tail = (p[-1], p[0]) if f else (p[0], p[-1])
        up += _d(pos, head)
        pos = tail
    return up


def nn_two_opt(paths, start, *, reverse=True):
    """Nearest-neighbour tour (each path from its nearer end) then 2-opt over all pairs.

    The tour is open (no return home). A move reverses positions i+1..j and every path in
    them; the best improving j for each i is taken until no move improves.
    """
    paths = [np.asarray(p, dtype=float) for p in paths]
    n = len(paths)
    left = set(range(n))
    pos = tuple(start)
    order, flipped = [], []
    while left:
        best = None
        for i in sorted(left):
            for f in (False, True) if reverse else (False,):
                head = paths[i][-1] if f else paths[i][0]
                d = _d(pos, head)
                if best is None or d < best[0] - 1e-15:
                    best = (d, i, f)
        _, i, f = best
        left.remove(i)
        order.append(i)
        flipped.append(f)
        pos = tuple(paths[i][0] if f else paths[i][-1])

    def head(k):
        p = paths[order[k]]
        return p[-1] if flipped[k] else p[0]

    def tail(k):
        if k < 0:
            return np.asarray(start, dtype=float)
        p = paths[order[k]]
        return p[0] if flipped[k] else p[-1]

    improved = True
    while improved:
        improved = False
        for i in range(-1, n - 1):
            for j in range(i + 1, n):
                old = _d(tail(i), head(i + 1))
                new = _d(tail(i), tail(j))
                if j + 1 < n:
                    old += _d(tail(j), head(j + 1))
                    new += _d(head(i + 1), head(j + 1))
                if old - new > 1e-12:
                    order[i + 1 : j + 1] = order[i + 1 : j + 1][::-1]
                    flipped[i + 1 : j + 1] = [not f for f in flipped[i + 1 : j + 1][::-1]]
                    improved = True
    return order, flipped


def segment_multiset(paths, closed, digits=9):
    """Unordered segments of paths as a sorted list of rounded end-point pairs."""
    out = []
    for p, c in zip(paths, closed, strict=True):
        p = np.round(np.asarray(p, dtype=float), digits)
        pts = np.vstack((p, p[:1])) if c else p
        for a, b in zip(pts[:-1].tolist(), pts[1:].tolist(), strict=True):
            if a != b:
                out.append(tuple(sorted((tuple(a), tuple(b)))))
    return sorted(out)
