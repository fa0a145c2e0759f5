"""Pen-up travel kernels for :mod:`voroforge.io.plotter`: a nearest-neighbour tour, 2-opt, Or-opt.

The paths are given by their two end points ("ports": path ``i`` runs from port ``2 i`` to
``2 i + 1``); a tour visits every path once, each entered from either end where it may flip.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..config import NJIT


@njit(**NJIT)
def nearest_tour(ports, can_flip, home):
    """Greedy nearest-neighbour tour over path ends, with a bucket grid of the ends."""
    n = len(ports) // 2
    tour = np.zeros(n, dtype=np.int64)
    flip = np.zeros(n, dtype=np.bool_)
    xmin = min(ports[:, 0].min(), home[0])
    ymin = min(ports[:, 1].min(), home[1])
    xmax = max(ports[:, 0].max(), home[0])
    ymax = max(ports[:, 1].max(), home[1])
    side = max(1, int(math.sqrt(n / 2.0)))
    h = max(xmax - xmin, ymax - ymin) / side
    if not h > 0:
        h = 1.0
    gx = min(side, int((xmax - xmin) / h) + 1)
    gy = min(side, int((ymax - ymin) / h) + 1)
    m = len(ports)
    bucket = np.zeros(m, dtype=np.int64)
    for i in range(m):
        cx = min(gx - 1, int((ports[i, 0] - xmin) / h))
        cy = min(gy - 1, int((ports[i, 1] - ymin) / h))
        bucket[i] = cy * gx + cx
    count = np.zeros(gx * gy + 1, dtype=np.int64)
    for i in range(m):
        count[bucket[i] + 1] += 1
    for b in range(gx * gy):
        count[b + 1] += count[b]
    fill = count[:-1].copy()
    items = np.zeros(m, dtype=np.int64)
    for i in range(m):
        items[fill[bucket[i]]] = i
        fill[bucket[i]] += 1
    alive = np.ones(n, dtype=np.bool_)
    left_in = np.zeros(gx * gy, dtype=np.int64)
    for b in range(gx * gy):
        left_in[b] = count[b + 1] - count[b]
    x, y = home[0], home[1]
    for step in range(n):
        cx = min(gx - 1, max(0, int((x - xmin) / h)))
        cy = min(gy - 1, max(0, int((y - ymin) / h)))
        best = -1
        best_d = np.inf
        r = 0
        while True:
            for by in range(cy - r, cy + r + 1):
                if by < 0 or by >= gy:
                    continue
                edge_row = by == cy - r or by == cy + r
                bx = cx - r
                while bx <= cx + r:
                    if 0 <= bx < gx:
                        b = by * gx + bx
                        if left_in[b] > 0:
                            for t in range(count[b], count[b + 1]):
                                port = items[t]
                                p = port // 2
                                if not alive[p] or (port % 2 == 1 and not can_flip[p]):
                                    continue
                                d = (ports[port, 0] - x) ** 2 + (ports[port, 1] - y) ** 2
                                if d < best_d or (d == best_d and port < best):
                                    best_d = d
                                    best = port
                    if edge_row or r == 0:
                        bx += 1
                    else:
                        bx += 2 * r
            if best >= 0 and math.sqrt(best_d) <= r * h:
                break
            if r > gx + gy:
                break
            r += 1
        p = best // 2
        alive[p] = False
        for port in (2 * p, 2 * p + 1):
            cxp = min(gx - 1, int((ports[port, 0] - xmin) / h))
            cyp = min(gy - 1, int((ports[port, 1] - ymin) / h))
            left_in[cyp * gx + cxp] -= 1
        tour[step] = p
        flip[step] = best % 2 == 1
        other = best + 1 if best % 2 == 0 else best - 1
        x, y = ports[other, 0], ports[other, 1]
    return tour, flip


@njit(**NJIT)
def _dist(ports, a, b):
    return math.sqrt((ports[a, 0] - ports[b, 0]) ** 2 + (ports[a, 1] - ports[b, 1]) ** 2)


@njit(**NJIT)
def two_opt(ports, tour, flip, can_flip, nb, home, eps, max_passes, window):
    """2-opt on the tour of paths in place: a move reverses positions i+1..j.

    Ports: ``2p`` is path p's first point, ``2p + 1`` its last. At position k the path is
    entered at ``head(k)`` and left at ``tail(k)``; position -1 is the pen's home, and
    nothing follows the last path (the tour is open).
    """
    n = len(tour)
    pos = np.zeros(n, dtype=np.int64)
    for k in range(n):
        pos[tour[k]] = k
    hx, hy = home[0], home[1]
    or_rounds = 0
    for _ in range(max_passes):
        improved = False
        for k in range(n):
            for side in range(2):  # 0: this position's tail, 1: its head
                p = tour[k]
                x = 2 * p + (1 - int(flip[k]) if side == 0 else int(flip[k]))
                for c in range(nb.shape[1]):
                    y = nb[x, c]
                    q = y // 2
                    if q == p:
                        continue
                    kq = pos[q]
                    y_is_tail = (y % 2 == 1) != flip[kq]
                    if side == 0 and y_is_tail:
                        i, j = k, kq
                    elif side == 1 and not y_is_tail:
                        i, j = k - 1, kq - 1
                    else:
                        continue
                    if i > j:
                        i, j = j, i
                    if i == j:
                        continue
                    # removed: (tail i, head i+1), (tail j, head j+1); added (tail i, tail j),
                    # (head i+1, head j+1)
                    hi1 = 2 * tour[i + 1] + int(flip[i + 1])
                    tj = 2 * tour[j] + 1 - int(flip[j])
                    if i >= 0:
                        ti = 2 * tour[i] + 1 - int(flip[i])
                        d_old = _dist(ports, ti, hi1)
                        d_new = _dist(ports, ti, tj)
                    else:
                        d_old = math.sqrt((ports[hi1, 0] - hx) ** 2 + (ports[hi1, 1] - hy) ** 2)
                        d_new = math.sqrt((ports[tj, 0] - hx) ** 2 + (ports[tj, 1] - hy) ** 2)
                    if j + 1 < n:
                        hj1 = 2 * tour[j + 1] + int(flip[j + 1])
                        d_old += _dist(ports, tj, hj1)
                        d_new += _dist(ports, hi1, hj1)
                    if d_old - d_new <= eps:
                        continue
                    # closed rings cannot be reversed; a run with one reverses in place (its
                    # head and tail are the same point, so the gain above still holds)
                    a, b = i + 1, j
                    while a < b:
                        ta, fa = tour[a], flip[a]
                        tour[a], flip[a] = tour[b], not flip[b]
                        tour[b], flip[b] = ta, not fa
                        pos[tour[a]] = a
                        pos[tour[b]] = b
                        a += 1
                        b -= 1
                    if a == b:
                        flip[a] = not flip[a]
                    improved = True
                    p = tour[k]
                    x = 2 * p + (1 - int(flip[k]) if side == 0 else int(flip[k]))
        if not improved and or_rounds < 2:  # Or-opt twice at most: its moves shift the tour
            or_rounds += 1
            improved = _or_opt(ports, tour, flip, can_flip, pos, nb, home, eps, window)
        if not improved:
            break
    for k in range(n):
        if not can_flip[tour[k]]:
            flip[k] = False
    return tour, flip


@njit(**NJIT)
def _gap(ports, tour, flip, a, home):
    """Travel from position ``a``'s tail to position ``a + 1``'s head (-1: home; n: none)."""
    n = len(tour)
    if a + 1 >= n:
        return 0.0
    h = 2 * tour[a + 1] + int(flip[a + 1])
    if a < 0:
        return math.sqrt((ports[h, 0] - home[0]) ** 2 + (ports[h, 1] - home[1]) ** 2)
    return _dist(ports, 2 * tour[a] + 1 - int(flip[a]), h)


@njit(**NJIT)
def _port_gap(ports, tour, flip, a, port, home, into):
    """Travel from position ``a``'s tail to ``port`` (into), or from ``port`` to its head.

    Position -1 is home; past the last position nothing follows (0).
    """
    n = len(tour)
    if into:
        if a < 0:
            return math.sqrt((ports[port, 0] - home[0]) ** 2 + (ports[port, 1] - home[1]) ** 2)
        return _dist(ports, 2 * tour[a] + 1 - int(flip[a]), port)
    if a >= n:
        return 0.0
    return _dist(ports, port, 2 * tour[a] + int(flip[a]))


@njit(**NJIT)
def _or_opt(ports, tour, flip, can_flip, pos, nb, home, eps, window):
    """One pass of moves of a single path to a gap next to one of its near neighbours.

    Only gaps at most ``window`` positions away are tried, so a move shifts few entries.
    """
    n = len(tour)
    improved = False
    for p in range(n):
        k = pos[p]
        # what removing p from position k saves
        before = _gap(ports, tour, flip, k - 1, home) + _gap(ports, tour, flip, k, home)
        if k + 1 < n:
            h_next = 2 * tour[k + 1] + int(flip[k + 1])
            if k - 1 >= 0:
                bridge = _dist(ports, 2 * tour[k - 1] + 1 - int(flip[k - 1]), h_next)
            else:
                bridge = math.sqrt(
                    (ports[h_next, 0] - home[0]) ** 2 + (ports[h_next, 1] - home[1]) ** 2
                )
        else:
            bridge = 0.0
        saved = before - bridge
        if saved <= eps:
            continue
        best = 0.0
        best_gap = -2
        best_flip = False
        for side in range(2):
            x = 2 * p + side
            for c in range(nb.shape[1]):
                q = nb[x, c] // 2
                if q == p:
                    continue
                kq = pos[q]
                for g in (kq - 1, kq):  # the gaps on either side of q
                    if g == k or g == k - 1 or abs(g - k) > window:
                        continue
                    for f in range(2):
                        if f == 1 and not can_flip[p]:
                            continue
                        h = 2 * p + f
                        t = 2 * p + 1 - f
                        old = _gap(ports, tour, flip, g, home)
                        add = _port_gap(ports, tour, flip, g, h, home, True)
                        add += _port_gap(ports, tour, flip, g + 1, t, home, False)
                        gain = saved - (add - old)
                        if gain > best + eps:
                            best = gain
                            best_gap = g
                            best_flip = f == 1
        if best_gap == -2:
            continue
        # move p from position k into the gap after position best_gap
        g = best_gap
        if g > k:
            for t in range(k, g):
                tour[t] = tour[t + 1]
                flip[t] = flip[t + 1]
                pos[tour[t]] = t
            tour[g] = p
            flip[g] = best_flip
            pos[p] = g
        else:
            for t in range(k, g + 1, -1):
                tour[t] = tour[t - 1]
                flip[t] = flip[t - 1]
                pos[tour[t]] = t
            tour[g + 1] = p
            flip[g + 1] = best_flip
            pos[p] = g + 1
        improved = True
    return improved


# --- a layer, ready to write ------------------------------------------------------------------
