"""Shared edges of cells cut to a polygonal domain by the boundary segments near each edge.

The companion of :func:`.polyclip.clip_cells` for a diagram's edges: an edge ``a b`` (two
cells' common side) is cut where the boundary crosses it, every decision an exact
orientation, and each crossing computed as the cells' clip computes it
(:func:`.polyclip.geos_intersection`, symmetric in the two segments and their
directions): the pieces' ends are the clipped cells' vertices bit for bit. A cell's vertex
on the boundary is a crossing at that vertex (into the domain or out of it, by the
boundary's turn there where it is a vertex of the domain too), a vertex of the domain on
the edge a crossing at that vertex (where the boundary passes through, not where it only
touches); a boundary segment along the edge, two crossings at one parameter and a rounded
crossing past a segment's end are left to the overlay.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import NJIT, POLYCLIP_PARAM_EPS
from .polyclip import geos_intersection, segment_candidates
from .predicates import orient2d

DONE = 0  # cut here (its pieces, maybe none)
NONE = 1  # no boundary segment meets the edge: wholly inside or wholly outside
HARD = 2  # left to the overlay


@njit(**NJIT)
def _sgn(d):
    return 1 if d > 0.0 else (-1 if d < 0.0 else 0)


@njit(**NJIT)
def _into(rx, ry, px, py, qx, qy, ox, oy):
    """Whether direction ``o - p`` leaves boundary vertex ``p`` into the domain (exact).

    The boundary runs ``r -> p -> q``, the domain on its left: 1 into it, -1 out of it, 0
    along a segment.
    """
    s1 = _sgn(orient2d(rx, ry, px, py, ox, oy))
    s2 = _sgn(orient2d(px, py, qx, qy, ox, oy))
    if s1 == 0 or s2 == 0:
        return 0
    if _sgn(orient2d(rx, ry, px, py, qx, qy)) >= 0:
        return 1 if s1 > 0 and s2 > 0 else -1  # (a convex corner, or straight on)
    return 1 if s1 > 0 or s2 > 0 else -1


@njit(**NJIT)
def clip_edges(edges, seg, nxt, boff, bids, grid):
    """Each edge cut to the domain: status, and the pieces inside it of the DONE ones.

    Parameters
    ----------
    edges : (u, 2, 2) float64
        The edges ``((ax, ay), (bx, by))``.
    seg : (m, 4) float64
        The domain's boundary segments ``(ax, ay, bx, by)``, the domain on their left.
    nxt : (m,) int64
        The segment after each one along its ring.
    boff, bids : int64
        :func:`.polyclip.bucket_segments` of ``seg`` over ``grid = (x0, y0, h, nx, ny)``.

    Returns
    -------
    status : (u,) int8
        DONE, NONE or HARD per edge.
    pieces : (r, 2, 2) float64
        The pieces of the DONE edges in the domain, in order along each edge.
    owner : (r,) int64
        The edge of each piece.
    """
    m = seg.shape[0]
    u = edges.shape[0]
    prv = np.zeros(m, dtype=np.int64)
    for g in range(m):
        prv[nxt[g]] = g
    stamp = np.full(m, -1, dtype=np.int64)
    loc = np.full(m, -1, dtype=np.int64)
    sides = np.zeros((1, 1), dtype=np.int64)
    status = np.zeros(u, dtype=np.int8)
    pieces = np.zeros((max(16, u), 2, 2))
    owner = np.zeros(max(16, u), dtype=np.int64)
    n_out = 0
    cand = np.zeros(64, dtype=np.int64)
    ev_t = np.zeros(16)
    ev_x = np.zeros((16, 2))
    ev_d = np.zeros(16, dtype=np.int64)
    for i in range(u):
        ax, ay, bx, by = edges[i, 0, 0], edges[i, 0, 1], edges[i, 1, 0], edges[i, 1, 1]
        lo_x, hi_x = min(ax, bx), max(ax, bx)
        lo_y, hi_y = min(ay, by), max(ay, by)
        rect = (lo_x, lo_y, hi_x, hi_y)
        cand, n_cand = segment_candidates(
            seg, boff, bids, grid, rect, stamp, loc, i, cand, sides, False
        )
        n_ev = 0
        hard = False
        touch = False
        for c in range(n_cand):
            g = cand[c]
            px, py, qx, qy = seg[g, 0], seg[g, 1], seg[g, 2], seg[g, 3]
            d_p = orient2d(ax, ay, bx, by, px, py)
            d_q = orient2d(ax, ay, bx, by, qx, qy)
            sp, sq = _sgn(d_p), _sgn(d_q)
            if sp * sq > 0:
                continue
            if sp == 0 and sq == 0:
                hard = True  # (along the edge's line)
                break
            if sp != 0 and sq != 0:
                d_a = orient2d(px, py, qx, qy, ax, ay)
                d_b = orient2d(px, py, qx, qy, bx, by)
                sa, sb = _sgn(d_a), _sgn(d_b)
                if sa * sb > 0:
                    continue
                if sa == 0:
                    t, x, y, d = 0.0, ax, ay, sb  # (the boundary through the edge's end)
                elif sb == 0:
                    t, x, y, d = 1.0, bx, by, -sa
                else:
                    x, y = geos_intersection(ax, ay, bx, by, px, py, qx, qy)
                    if not (
                        lo_x <= x <= hi_x
                        and lo_y <= y <= hi_y
                        and min(px, qx) <= x <= max(px, qx)
                        and min(py, qy) <= y <= max(py, qy)
                    ):
                        hard = True  # (GEOS moves it to an end point)
                        break
                    t, d = d_a / (d_a - d_b), sb
            elif sp == 0:
                # a vertex of the domain on the edge's line: a crossing where the boundary
                # passes through it (the segment before it on the other side)
                if not (lo_x <= px <= hi_x and lo_y <= py <= hi_y):
                    continue
                h = prv[g]
                at_a = px == ax and py == ay
                if at_a or (px == bx and py == by):
                    # an end of the edge at the vertex: does the edge leave it into the domain?
                    ox, oy = (bx, by) if at_a else (ax, ay)
                    into = _into(seg[h, 0], seg[h, 1], px, py, qx, qy, ox, oy)
                    if into == 0:
                        hard = True  # (along a segment)
                        break
                    t, x, y = (0.0, ax, ay) if at_a else (1.0, bx, by)
                    d = into if at_a else -into
                else:
                    sr = _sgn(orient2d(ax, ay, bx, by, seg[h, 0], seg[h, 1]))
                    if sr == 0:
                        hard = True
                        break
                    if sr == sq:
                        touch = True
                        continue
                    dx, dy = bx - ax, by - ay
                    t = ((px - ax) * dx + (py - ay) * dy) / (dx * dx + dy * dy)
                    x, y, d = px, py, -sq
            else:
                continue  # (its last vertex on the line: met as the next segment's first)
            if n_ev == ev_t.shape[0]:
                ev_t = np.concatenate((ev_t, np.zeros(n_ev)))
                ev_x = np.concatenate((ev_x, np.zeros((n_ev, 2))))
                ev_d = np.concatenate((ev_d, np.zeros(n_ev, dtype=np.int64)))
            ev_t[n_ev], ev_x[n_ev, 0], ev_x[n_ev, 1], ev_d[n_ev] = t, x, y, d
            n_ev += 1
        if hard:
            status[i] = HARD
            continue
        if n_ev == 0:
            status[i] = HARD if touch else NONE
            continue
        order = np.argsort(ev_t[:n_ev])
        for e in range(n_ev - 1):
            if ev_t[order[e + 1]] - ev_t[order[e]] <= POLYCLIP_PARAM_EPS:
                hard = True
            if ev_d[order[e + 1]] == ev_d[order[e]]:
                hard = True  # (in after in: not one boundary)
        if hard:
            status[i] = HARD
            continue
        # inside from each entry (+1) to the next exit (-1); from ``a`` if the first exits
        while n_out + n_ev + 1 > pieces.shape[0]:
            pieces = np.concatenate((pieces, np.zeros_like(pieces)))
            owner = np.concatenate((owner, np.zeros_like(owner)))
        start_x, start_y = ax, ay
        inside = ev_d[order[0]] < 0
        for e in range(n_ev):
            k = order[e]
            if ev_d[k] > 0:
                start_x, start_y = ev_x[k, 0], ev_x[k, 1]
                inside = True
                continue
            if start_x != ev_x[k, 0] or start_y != ev_x[k, 1]:
                pieces[n_out, 0, 0], pieces[n_out, 0, 1] = start_x, start_y
                pieces[n_out, 1, 0], pieces[n_out, 1, 1] = ev_x[k, 0], ev_x[k, 1]
                owner[n_out] = i
                n_out += 1
            inside = False
        if inside and (start_x != bx or start_y != by):
            pieces[n_out, 0, 0], pieces[n_out, 0, 1] = start_x, start_y
            pieces[n_out, 1, 0], pieces[n_out, 1, 1] = bx, by
            owner[n_out] = i
            n_out += 1
    return status, pieces[:n_out].copy(), owner[:n_out].copy()
