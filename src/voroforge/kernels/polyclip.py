"""Convex cells clipped to a polygonal domain by the boundary segments near each cell.

A cell (a closed counter-clockwise convex ring) that meets the domain's boundary is cut by
the segments in the grid buckets its box covers (:func:`bucket_segments`), not by the whole
domain: a comb whose one outline meets every cell costs each cell the teeth it meets.
The domain's rings run with the domain on their left (shells counter-clockwise, holes
clockwise). Each segment is cut to the cell; the pieces inside it join into
chains along the rings, each entering the cell across one of its edges and leaving it
across another; the clipped cell's rings are the chains joined along the cell's boundary,
counter-clockwise from each chain's exit to the next entry (:func:`clip_cells`).

Every sign is exact (:func:`.predicates.orient2d`): a segment's ends against the cell's
edge lines, and the cell's vertices against the segment's line, whose chord in the cell
(entered where the vertices pass from its left to its right) gives the crossings. A line
through a cell's vertex crosses there, at the vertex itself; a vertex of the domain on a
cell's edge is the crossing itself (a chain touching the edge from inside goes on); a
boundary segment along a cell's edge, like the boundary along the sides of the domain's
bounding box (a comb's top and bottom rows, a zigzag's peaks on the box: :func:`box_sides`,
for cells inside the box), is pushed out of the cell by an infinitesimal: the domain in
the cell is the same, and the boundary leaves the edge only at its own vertices (floats:
nothing is rounded there). A ring of the domain wholly inside a cell comes back as a loop
(a hole or a part). The overlay is left only what the floats cannot order: two chain ends
within ``POLYCLIP_PARAM_EPS`` along the cell's boundary, a rounded crossing past an end
of its segments or onto a neighbour, a cell no segment enters whose first vertex the
boundary touches, a ring rounding bent. A crossing is computed as GEOS computes it
(``CGAlgorithmsDD::intersection``: homogeneous coordinates in double-double arithmetic),
symmetric in the two segments and their directions: two cells sharing an edge place a
crossing on it at the same point, the point GEOS's overlay gives, and so does the clip of
their shared edge (:mod:`.edgeclip`).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..config import NJIT, POLYCLIP_PARAM_EPS
from .predicates import orient2d

DONE = 0  # clipped here
NONE = 1  # no boundary segment meets the cell: wholly inside or wholly outside
HARD = 2  # left to the overlay (HARD + k: which test, k < 20)
LOOPS = -1  # clipped here, with rings of the domain wholly inside the cell (loops)


@njit(**NJIT)
def bucket_segments(seg, x0, y0, h, nx, ny):
    """Buckets ``(ny * nx + 1,)`` offsets and segment ids of every grid square a box meets.

    ``seg`` (m, 4) holds each segment ``(ax, ay, bx, by)``; square ``(r, c)`` is
    ``[x0 + c h, x0 + (c + 1) h] x [y0 + r h, ...]``, clamped to the grid.
    """
    m = seg.shape[0]
    count = np.zeros(ny * nx + 1, dtype=np.int64)
    for g in range(m):
        c0, c1, r0, r1 = _squares(seg, g, x0, y0, h, nx, ny)
        for r in range(r0, r1 + 1):
            for c in range(c0, c1 + 1):
                count[r * nx + c + 1] += 1
    off = np.cumsum(count)
    fill = off[:-1].copy()
    ids = np.zeros(off[-1], dtype=np.int64)
    for g in range(m):
        c0, c1, r0, r1 = _squares(seg, g, x0, y0, h, nx, ny)
        for r in range(r0, r1 + 1):
            for c in range(c0, c1 + 1):
                ids[fill[r * nx + c]] = g
                fill[r * nx + c] += 1
    return off, ids


@njit(**NJIT)
def _squares(seg, g, x0, y0, h, nx, ny):
    lo_x = min(seg[g, 0], seg[g, 2])
    hi_x = max(seg[g, 0], seg[g, 2])
    lo_y = min(seg[g, 1], seg[g, 3])
    hi_y = max(seg[g, 1], seg[g, 3])
    return (
        _clamp(math.floor((lo_x - x0) / h), nx),
        _clamp(math.floor((hi_x - x0) / h), nx),
        _clamp(math.floor((lo_y - y0) / h), ny),
        _clamp(math.floor((hi_y - y0) / h), ny),
    )


@njit(**NJIT)
def _clamp(v, n):
    if not v >= 0:  # (NaN too)
        return 0
    if v > n - 1:
        return n - 1
    return int(v)


# GEOS's double-double arithmetic (``geos::math::DD``), step for step
_SPLIT = 134217729.0


@njit(**NJIT)
def _dd_add(xhi, xlo, yhi, ylo):
    big_s = xhi + yhi
    big_t = xlo + ylo
    e = big_s - xhi
    f = big_t - xlo
    s = big_s - e
    t = big_t - f
    s = (yhi - e) + (xhi - s)
    t = (ylo - f) + (xlo - t)
    e = s + big_t
    big_h = big_s + e
    h = e + (big_s - big_h)
    e = t + h
    zhi = big_h + e
    return zhi, e + (big_h - zhi)


@njit(**NJIT)
def _dd_mul(xhi, xlo, yhi, ylo):
    big_c = _SPLIT * xhi
    hx = big_c - xhi
    c = _SPLIT * yhi
    hx = big_c - hx
    tx = xhi - hx
    hy = c - yhi
    big_c = xhi * yhi
    hy = c - hy
    ty = yhi - hy
    c = ((((hx * hy - big_c) + hx * ty) + tx * hy) + tx * ty) + (xhi * ylo + xlo * yhi)
    zhi = big_c + c
    hx = big_c - zhi
    return zhi, c + hx


@njit(**NJIT)
def _dd_div(xhi, xlo, yhi, ylo):
    big_c = xhi / yhi
    c = _SPLIT * big_c
    hc = c - big_c
    u = _SPLIT * yhi
    hc = c - hc
    tc = big_c - hc
    hy = u - yhi
    big_u = big_c * yhi
    hy = u - hy
    ty = yhi - hy
    u = (((hc * hy - big_u) + hc * ty) + tc * hy) + tc * ty
    c = ((((xhi - big_u) - u) + xlo) - big_c * ylo) / yhi
    u = big_c + c
    return u, (big_c - u) + c


@njit(**NJIT)
def _dd_det(ahi, alo, bhi, blo, chi, clo, dhi, dlo):
    """``a d - b c`` in double-double, as GEOS evaluates it."""
    l0, l1 = _dd_mul(ahi, alo, dhi, dlo)
    r0, r1 = _dd_mul(bhi, blo, chi, clo)
    return _dd_add(l0, l1, -r0, -r1)


@njit(**NJIT)
def geos_intersection(p1x, p1y, p2x, p2y, q1x, q1y, q2x, q2y):
    """The crossing of lines ``p1 p2`` and ``q1 q2`` as GEOS's ``CGAlgorithmsDD::intersection``."""
    px0, px1 = _dd_add(p1y, 0.0, -p2y, -0.0)
    py0, py1 = _dd_add(p2x, 0.0, -p1x, -0.0)
    pw0, pw1 = _dd_det(p1x, 0.0, p1y, 0.0, p2x, 0.0, p2y, 0.0)
    qx0, qx1 = _dd_add(q1y, 0.0, -q2y, -0.0)
    qy0, qy1 = _dd_add(q2x, 0.0, -q1x, -0.0)
    qw0, qw1 = _dd_det(q1x, 0.0, q1y, 0.0, q2x, 0.0, q2y, 0.0)
    x0, x1 = _dd_det(py0, py1, pw0, pw1, qy0, qy1, qw0, qw1)
    y0, y1 = _dd_det(qx0, qx1, qw0, qw1, px0, px1, pw0, pw1)
    w0, w1 = _dd_det(px0, px1, py0, py1, qx0, qx1, qy0, qy1)
    a0, a1 = _dd_div(x0, x1, w0, w1)
    b0, b1 = _dd_div(y0, y1, w0, w1)
    return a0 + a1, b0 + b1


@njit(**NJIT)
def _sign(ax, ay, bx, by, px, py):
    """The exact sign (-1, 0, 1) of ``(b - a) x (p - a)``, and its float value."""
    d = orient2d(ax, ay, bx, by, px, py)
    return (1 if d > 0.0 else (-1 if d < 0.0 else 0)), d


@njit(**NJIT)
def clip_cells(ring_xy, ring_off, seg, nxt, boff, bids, grid, box, sides):
    """Each convex ring cut to the domain: status, and the clipped rings of the DONE ones.

    Parameters
    ----------
    ring_xy : (k, 2) float64
        Closed counter-clockwise convex rings, ring ``i`` at ``ring_off[i]:ring_off[i + 1]``.
    ring_off : (u + 1,) int64
    seg : (m, 4) float64
        The domain's boundary segments ``(ax, ay, bx, by)``, the domain on their left.
    nxt : (m,) int64
        The segment after each one along its ring.
    boff, bids : int64
        :func:`bucket_segments` of ``seg`` over ``grid = (x0, y0, h, nx, ny)``.
    box : (4,) float64
        The domain's bounding box ``(x0, y0, x1, y1)``.
    sides : (m, 3) int64
        :func:`box_sides` of ``seg``.

    Returns
    -------
    status : (u,) int8
        DONE, LOOPS, NONE or HARD (and up) per ring.
    out_xy : (j, 2) float64
        The clipped rings (closed, counter-clockwise), each a polygon with no hole.
    out_off : (r + 1,) int64
    out_cell : (r,) int64
        The input ring of each output ring.
    out_loop : (r,) bool
        Whether an output ring is a ring of the domain wholly inside the cell (oriented as
        in the domain: a shell counter-clockwise, a hole clockwise); a LOOPS cell's loops
        follow its other rings, which are then its polygons' shells (none: the cell's own
        ring may be one, see :func:`.engine.polyclip.clip_convex`).
    """
    m = seg.shape[0]
    u = ring_off.shape[0] - 1
    stamp = np.full(m, -1, dtype=np.int64)
    prv = np.zeros(m, dtype=np.int64)
    for g in range(m):
        prv[nxt[g]] = g
    loc = np.full(m, -1, dtype=np.int64)
    status = np.zeros(u, dtype=np.int8)
    out_xy = np.zeros((max(16, ring_xy.shape[0] * 2), 2))
    out_off = np.zeros(max(16, u + 1), dtype=np.int64)
    out_cell = np.zeros(max(16, u + 1), dtype=np.int64)
    out_loop = np.zeros(max(16, u + 1), dtype=np.bool_)
    n_out = 0
    n_ring = 0
    cand = np.zeros(64, dtype=np.int64)
    for i in range(u):
        a0 = ring_off[i]
        nc = ring_off[i + 1] - a0 - 1
        if nc < 3:
            status[i] = HARD
            continue
        cx = ring_xy[a0 : a0 + nc + 1, 0]
        cy = ring_xy[a0 : a0 + nc + 1, 1]
        bx0, bx1 = cx.min(), cx.max()
        by0, by1 = cy.min(), cy.max()
        # in the domain's box, the cell's edges on its sides and the boundary along them
        # are set apart (see :func:`box_sides`)
        in_box = bx0 >= box[0] and by0 >= box[1] and bx1 <= box[2] and by1 <= box[3]
        edge_side = _edge_sides(cx, cy, nc, box, in_box)
        # the candidates: segments in the buckets of the cell's box whose boxes meet it
        # (in the box, none along its sides: they are pushed out)
        cand, n_cand = segment_candidates(
            seg, boff, bids, grid, (bx0, by0, bx1, by1), stamp, loc, i, cand, sides, in_box
        )
        got = _clip_one(cx, cy, nc, seg, nxt, prv, cand[:n_cand], stamp, loc, i, edge_side, sides)
        st, xy, off, n_loop = got
        status[i] = st if n_loop == 0 else LOOPS
        if st != DONE:
            continue
        k = off.shape[0] - 1
        while n_out + xy.shape[0] > out_xy.shape[0]:
            out_xy = np.concatenate((out_xy, np.zeros_like(out_xy)))
        while n_ring + k + 1 > out_off.shape[0]:
            out_off = np.concatenate((out_off, np.zeros_like(out_off)))
            out_cell = np.concatenate((out_cell, np.zeros_like(out_cell)))
            out_loop = np.concatenate((out_loop, np.zeros_like(out_loop)))
        out_xy[n_out : n_out + xy.shape[0]] = xy
        for j in range(k):
            out_off[n_ring + j + 1] = n_out + off[j + 1]
            out_cell[n_ring + j] = i
            out_loop[n_ring + j] = j >= k - n_loop
        n_out += xy.shape[0]
        n_ring += k
    return (
        status,
        out_xy[:n_out].copy(),
        out_off[: n_ring + 1].copy(),
        out_cell[:n_ring].copy(),
        out_loop[:n_ring].copy(),
    )


@njit(**NJIT)
def segment_candidates(seg, boff, bids, grid, rect, stamp, loc, mark, cand, sides, in_box):
    """The segments in the grid buckets over ``rect = (x0, y0, x1, y1)`` whose boxes meet it.

    Returns ``(cand, count)`` (``cand`` grown as needed); each segment met is stamped
    ``mark`` once and ``loc`` holds its place in ``cand`` (-1: not kept). Where ``in_box``,
    segments along a side of the domain's box (``sides[g, 0] >= 0``) are not kept.
    """
    x0, y0, h = grid[0], grid[1], grid[2]
    nx, ny = int(grid[3]), int(grid[4])
    bx0, by0, bx1, by1 = rect
    n_cand = 0
    c0 = _clamp(math.floor((bx0 - x0) / h), nx)
    c1 = _clamp(math.floor((bx1 - x0) / h), nx)
    r0 = _clamp(math.floor((by0 - y0) / h), ny)
    r1 = _clamp(math.floor((by1 - y0) / h), ny)
    for r in range(r0, r1 + 1):
        for c in range(c0, c1 + 1):
            b = r * nx + c
            for t in range(boff[b], boff[b + 1]):
                g = bids[t]
                if stamp[g] == mark:
                    continue
                stamp[g] = mark
                loc[g] = -1
                if in_box and sides[g, 0] >= 0:
                    continue
                if (
                    max(seg[g, 0], seg[g, 2]) < bx0
                    or min(seg[g, 0], seg[g, 2]) > bx1
                    or max(seg[g, 1], seg[g, 3]) < by0
                    or min(seg[g, 1], seg[g, 3]) > by1
                ):
                    continue
                if n_cand == cand.shape[0]:
                    cand = np.concatenate((cand, np.zeros(n_cand, dtype=np.int64)))
                loc[g] = n_cand
                cand[n_cand] = g
                n_cand += 1
    return cand, n_cand


@njit(**NJIT)
def box_sides(seg, nxt, box):
    """Per segment: the side of ``box`` it runs along, and the sides its ends are pushed out to.

    ``(m, 3)``: column 0 the side (0: x0, 1: y0, 2: x1, 3: y1) both ends of the segment lie
    on, else -1; columns 1 and 2 bit masks (``1 << side``) of the sides the segment's
    first and last vertex are pushed out across, those of the side-running segments that
    meet it there. A cell inside the box is clipped as if the boundary along the box's
    sides were pushed out of it by an infinitesimal: the domain's part inside the box, and
    so its part inside the cell, is the same, but the boundary no longer runs along the
    cell's sides on the box. It leaves the cell where a segment's pushed end crosses such a
    side, at the segment's own vertex (a float: nothing is rounded on the box's sides).
    """
    m = seg.shape[0]
    out = np.full((m, 3), -1, dtype=np.int64)
    for g in range(m):
        for s in range(4):
            v = box[s]
            a = seg[g, 0] if s % 2 == 0 else seg[g, 1]
            b = seg[g, 2] if s % 2 == 0 else seg[g, 3]
            if a == v and b == v:
                out[g, 0] = s
    for g in range(m):
        out[g, 1] = 0
        out[g, 2] = 0
    for g in range(m):
        h = nxt[g]
        if out[g, 0] >= 0 and out[h, 0] < 0:
            out[h, 1] |= 1 << out[g, 0]
        if out[h, 0] >= 0 and out[g, 0] < 0:
            out[g, 2] |= 1 << out[h, 0]
    return out


@njit(**NJIT)
def _edge_sides(cx, cy, nc, box, in_box):
    """The side of the box each edge of a cell inside it lies on (-1: none, or not inside)."""
    out = np.full(nc, -1, dtype=np.int64)
    if not in_box:
        return out
    for k in range(nc):
        for s in range(4):
            v = box[s]
            a = cx[k] if s % 2 == 0 else cy[k]
            b = cx[k + 1] if s % 2 == 0 else cy[k + 1]
            if a == v and b == v:
                out[k] = s
    return out


@njit(**NJIT)
def _clip_one(cx, cy, nc, seg, nxt, prv, cand, stamp, loc, cell, edge_side, sides):
    """One cell: (status, closed rings' coordinates, their offsets).

    On an edge along a side of the box (``edge_side``) a vertex is inside unless it is
    pushed out across that side (:func:`box_sides`); a segment crosses the edge only at
    such a vertex.
    """
    nothing = (np.zeros((0, 2)), np.zeros(1, dtype=np.int64))
    q = cand.shape[0]
    # per candidate: its piece inside the cell (-1 none), entry / exit edge and parameter
    has = np.zeros(q, dtype=np.bool_)
    k_in = np.full(q, -1, dtype=np.int64)
    k_out = np.full(q, -1, dtype=np.int64)
    u_in = np.zeros(q)
    u_out = np.zeros(q)
    x_in = np.zeros((q, 2))
    x_out = np.zeros((q, 2))
    at_p = np.zeros(q, dtype=np.bool_)  # entering at its own first vertex (on the boundary)
    at_q = np.zeros(q, dtype=np.bool_)  # leaving at its own last vertex
    sp = np.zeros(nc, dtype=np.int64)
    push_p = np.zeros(nc, dtype=np.bool_)  # the end pushed out across the edge
    push_q = np.zeros(nc, dtype=np.bool_)
    sq = np.zeros(nc, dtype=np.int64)
    sv = np.zeros(nc, dtype=np.int64)
    dv = np.zeros(nc)
    contact = False  # a segment meets the closed cell only at its first vertex
    n_piece = 0
    for j in range(q):
        g = cand[j]
        px, py, qx, qy = seg[g, 0], seg[g, 1], seg[g, 2], seg[g, 3]
        # exact sides of the segment's ends against each edge's line (on the box's sides:
        # inside unless pushed out across it, see :func:`box_sides`)
        outside = False
        touch = False
        for k in range(nc):
            s = edge_side[k]
            push_p[k] = False
            push_q[k] = False
            if s >= 0:
                a = -1 if (sides[g, 1] >> s) & 1 else 1
                b = -1 if (sides[g, 2] >> s) & 1 else 1
                push_p[k] = a < 0
                push_q[k] = b < 0
            else:
                a = _sign(cx[k], cy[k], cx[k + 1], cy[k + 1], px, py)[0]
                b = _sign(cx[k], cy[k], cx[k + 1], cy[k + 1], qx, qy)[0]
                if a == 0 and b == 0:
                    # along the edge's line: pushed out of the cell by an infinitesimal, as
                    # on the box's sides (the domain in the cell is the same), and so are
                    # the ends on it of the segments before and after it
                    contact = contact or _on_segment(px, py, qx, qy, cx[0], cy[0])
                    outside = True
                    break
                if a == 0:
                    h = prv[g]
                    if _sign(cx[k], cy[k], cx[k + 1], cy[k + 1], seg[h, 0], seg[h, 1])[0] == 0:
                        a = -1
                        push_p[k] = True
                if b == 0:
                    h = nxt[g]
                    if _sign(cx[k], cy[k], cx[k + 1], cy[k + 1], seg[h, 2], seg[h, 3])[0] == 0:
                        b = -1
                        push_q[k] = True
            sp[k] = a
            sq[k] = b
            if a < 0 and b < 0:
                outside = True
                break
            if a <= 0 and b <= 0:
                touch = True  # (in the closed half-plane beyond: a point at most)
        if outside:
            continue
        if touch:
            # (only a point on the cell's first vertex can mislead the engine's test of
            # whether a cell no segment enters is inside: that vertex's)
            contact = contact or _on_segment(px, py, qx, qy, cx[0], cy[0])
            continue
        p_in = True
        q_in = True
        p_out = False
        q_out = False
        for k in range(nc):
            p_in = p_in and sp[k] > 0
            q_in = q_in and sq[k] > 0
            p_out = p_out or sp[k] < 0
            q_out = q_out or sq[k] < 0
        if not (p_in and q_in):
            # the chord of the segment's line in the cell, from the cell's vertices' exact
            # sides: entered where they pass from its left to its right (counter-clockwise),
            # at a vertex on the line or inside an edge
            for k in range(nc):
                sv[k], dv[k] = _sign(px, py, qx, qy, cx[k], cy[k])
            e_in = -1
            e_out = -1
            v_in = False
            v_out = False
            n_in = 0
            n_out = 0
            for k in range(nc):
                a, b = sv[k], sv[(k + 1) % nc]
                if a == 0:
                    before = sv[(k - 1) % nc]
                    if before == 0 or b == 0:
                        return HARD + 1, nothing[0], nothing[1], 0  # (the line on an edge)
                    if before > 0 and b < 0:
                        e_in, v_in, n_in = k, True, n_in + 1
                    elif before < 0 and b > 0:
                        e_out, v_out, n_out = k, True, n_out + 1
                elif a > 0 and b < 0:
                    e_in, v_in, n_in = k, False, n_in + 1
                elif a < 0 and b > 0:
                    e_out, v_out, n_out = k, False, n_out + 1
            if n_in != n_out or n_in > 1:
                return HARD + 2, nothing[0], nothing[1], 0  # (a ring rounding bent)
            if n_in == 0:
                # (the line meets the closed cell at a vertex at most)
                contact = contact or (sv[0] == 0 and _on_segment(px, py, qx, qy, cx[0], cy[0]))
                continue
        if not p_in:
            if p_out:
                own = not v_in and push_p[e_in]
                if not v_in and edge_side[e_in] >= 0 and not own:
                    return HARD + 7, nothing[0], nothing[1], 0
                got = _end(cx, cy, e_in, v_in, dv, True, px, py, qx, qy, own)
            elif (v_in and px == cx[e_in] and py == cy[e_in]) or (not v_in and sp[e_in] == 0):
                got = _on_edge(cx, cy, e_in, v_in, True, px, py)
                at_p[j] = True
            elif (v_out and px == cx[e_out] and py == cy[e_out]) or (not v_out and sp[e_out] == 0):
                contact = contact or (px == cx[0] and py == cy[0])  # (it leaves where it starts)
                continue
            else:
                return HARD + 3, nothing[0], nothing[1], 0
            if got[0] < 0:
                return HARD + 4, nothing[0], nothing[1], 0
            k_in[j], u_in[j], x_in[j, 0], x_in[j, 1] = got
        if not q_in:
            if q_out:
                own = not v_out and push_q[e_out]
                if not v_out and edge_side[e_out] >= 0 and not own:
                    return HARD + 8, nothing[0], nothing[1], 0
                got = _end(cx, cy, e_out, v_out, dv, False, qx, qy, px, py, own)
            elif (v_out and qx == cx[e_out] and qy == cy[e_out]) or (not v_out and sq[e_out] == 0):
                got = _on_edge(cx, cy, e_out, v_out, False, qx, qy)
                at_q[j] = True
            elif (v_in and qx == cx[e_in] and qy == cy[e_in]) or (not v_in and sq[e_in] == 0):
                contact = contact or (qx == cx[0] and qy == cy[0])  # (it enters where it ends)
                k_in[j] = -1
                at_p[j] = False
                continue
            else:
                return HARD + 5, nothing[0], nothing[1], 0
            if got[0] < 0:
                return HARD + 6, nothing[0], nothing[1], 0
            k_out[j], u_out[j], x_out[j, 0], x_out[j, 1] = got
        has[j] = True
        n_piece += 1
    # a chain that touches the cell's boundary at one of its vertices from inside goes on
    for j in range(q):
        if has[j] and at_q[j]:
            g2 = nxt[cand[j]]
            nj = loc[g2] if stamp[g2] == cell else -1
            if nj >= 0 and has[nj] and at_p[nj]:
                k_out[j] = -1
                k_in[nj] = -1
    if n_piece == 0:
        return (HARD + 17 if contact else NONE), nothing[0], nothing[1], 0
    # chains: from each entering piece along the ring to the piece that leaves
    seen = np.zeros(q, dtype=np.bool_)
    n_chain = 0
    for j in range(q):
        if has[j] and k_in[j] >= 0:
            n_chain += 1
    head = np.zeros(n_chain, dtype=np.int64)
    tail = np.zeros(n_chain, dtype=np.int64)
    chain_at = np.zeros(n_chain + 1, dtype=np.int64)
    pts = np.zeros((n_piece + n_chain, 2))
    n_pts = 0
    c = 0
    for j in range(q):
        if not (has[j] and k_in[j] >= 0):
            continue
        head[c] = j
        pts[n_pts] = x_in[j]
        n_pts += 1
        cur = j
        seen[j] = True
        while k_out[cur] < 0:
            g = cand[cur]
            pts[n_pts, 0], pts[n_pts, 1] = seg[g, 2], seg[g, 3]
            n_pts += 1
            g2 = nxt[g]
            nj = loc[g2] if stamp[g2] == cell else -1
            if nj < 0 or not has[nj] or k_in[nj] >= 0 or seen[nj]:
                return HARD + 10, nothing[0], nothing[1], 0
            seen[nj] = True
            cur = nj
        pts[n_pts] = x_out[cur]
        n_pts += 1
        tail[c] = cur
        c += 1
        chain_at[c] = n_pts
    # the domain's rings wholly inside the cell, each closed on itself
    loop_xy = np.zeros((n_piece + q, 2))
    loop_at = np.zeros(q + 1, dtype=np.int64)
    n_loop = 0
    for j in range(q):
        if not has[j] or seen[j]:
            continue
        n = loop_at[n_loop]
        cur = j
        while True:
            if k_in[cur] >= 0 or k_out[cur] >= 0 or seen[cur]:
                return HARD + 11, nothing[0], nothing[1], 0
            seen[cur] = True
            g = cand[cur]
            loop_xy[n, 0], loop_xy[n, 1] = seg[g, 0], seg[g, 1]
            n += 1
            g2 = nxt[g]
            nj = loc[g2] if stamp[g2] == cell else -1
            if nj == j:
                break
            if nj < 0 or not has[nj]:
                return HARD + 9, nothing[0], nothing[1], 0
            cur = nj
        loop_xy[n] = loop_xy[loop_at[n_loop]]
        n_loop += 1
        loop_at[n_loop] = n + 1
    if n_chain == 0:
        return DONE, loop_xy[: loop_at[n_loop]].copy(), loop_at[: n_loop + 1].copy(), n_loop
    # the chains' ends along the cell's boundary, counter-clockwise
    n_ev = 2 * n_chain
    key = np.zeros(n_ev)
    for c in range(n_chain):
        key[2 * c] = k_in[head[c]] + u_in[head[c]]
        key[2 * c + 1] = k_out[tail[c]] + u_out[tail[c]]
    order = np.argsort(key)
    for e in range(n_ev):
        # (keys run over [0, nc]: an entry at vertex 0 has key nc, an exit there 0)
        d = key[order[(e + 1) % n_ev]] - key[order[e]] + (nc if e == n_ev - 1 else 0)
        if d <= POLYCLIP_PARAM_EPS * nc:
            return HARD + 12, nothing[0], nothing[1], 0
    rank = np.zeros(n_ev, dtype=np.int64)
    for e in range(n_ev):
        rank[order[e]] = e
    after = np.zeros(n_chain, dtype=np.int64)  # the chain entered next after each exit
    for c in range(n_chain):
        ev = order[(rank[2 * c + 1] + 1) % n_ev]
        if ev % 2 == 1:
            return HARD + 14, nothing[0], nothing[1], 0  # (an exit after an exit)
        after[c] = ev // 2
    xy = np.zeros((n_pts + n_chain * (nc + 1) + n_chain, 2))
    off = np.zeros(n_chain + 1, dtype=np.int64)
    used = np.zeros(n_chain, dtype=np.bool_)
    n_xy = 0
    n_r = 0
    for s in range(n_chain):
        if used[s]:
            continue
        c = s
        start = n_xy
        while not used[c]:
            used[c] = True
            for t in range(chain_at[c], chain_at[c + 1]):
                xy[n_xy] = pts[t]
                n_xy += 1
            nc2 = after[c]
            ko = k_out[tail[c]]
            ki = k_in[head[nc2]]
            steps = (ki - ko) % nc
            if steps == 0 and key[2 * nc2] < key[2 * c + 1]:
                steps = nc
            for t in range(steps):
                v = (ko + 1 + t) % nc
                xy[n_xy, 0], xy[n_xy, 1] = cx[v], cy[v]
                n_xy += 1
            c = nc2
        if c != s:
            return HARD + 15, nothing[0], nothing[1], 0
        for t in range(start + 1, n_xy):
            if xy[t, 0] == xy[t - 1, 0] and xy[t, 1] == xy[t - 1, 1]:
                return HARD + 16, nothing[0], nothing[1], 0  # (a safeguard: none should round so)
        xy[n_xy] = xy[start]
        n_xy += 1
        n_r += 1
        off[n_r] = n_xy
    if n_loop == 0:
        return DONE, xy[:n_xy].copy(), off[: n_r + 1].copy(), 0
    # the loops after the chains' rings
    m = loop_at[n_loop]
    xy2 = np.zeros((n_xy + m, 2))
    xy2[:n_xy] = xy[:n_xy]
    xy2[n_xy:] = loop_xy[:m]
    off2 = np.zeros(n_r + n_loop + 1, dtype=np.int64)
    off2[: n_r + 1] = off[: n_r + 1]
    off2[n_r + 1 :] = n_xy + loop_at[1 : n_loop + 1]
    return DONE, xy2, off2, n_loop


@njit(**NJIT)
def _end(cx, cy, e, vertex, dv, entering, px, py, qx, qy, own):
    """Where a segment from outside end ``p`` (towards ``q``) crosses the cell's boundary.

    ``e`` is the chord's end: a vertex of the cell on the segment's line (its exact
    point), or the edge its line crosses inside: ``p`` itself where ``own`` (``p`` pushed
    out across that edge), else the crossing as GEOS computes it. Returns ``(edge,
    parameter along it, x, y)``; an entry at a vertex is the end of the edge before it.
    Edge -1: undecided (the rounded crossing past an end of either segment).
    """
    nc = cx.shape[0] - 1
    if vertex:
        if entering:
            return (e - 1) % nc, 1.0, cx[e], cy[e]
        return e, 0.0, cx[e], cy[e]
    if own:
        return _on_edge(cx, cy, e, False, entering, px, py)
    ax, ay, bx, by = cx[e], cy[e], cx[e + 1], cy[e + 1]
    x, y = geos_intersection(ax, ay, bx, by, px, py, qx, qy)
    if not (
        min(ax, bx) <= x <= max(ax, bx)
        and min(ay, by) <= y <= max(ay, by)
        and min(px, qx) <= x <= max(px, qx)
        and min(py, qy) <= y <= max(py, qy)
    ):
        return -1, 0.0, 0.0, 0.0  # (GEOS moves it to an end point)
    d0 = dv[e]
    d1 = dv[(e + 1) % nc]
    return e, d0 / (d0 - d1), x, y


@njit(**NJIT)
def _on_edge(cx, cy, e, vertex, entering, px, py):
    """The chord's end ``e`` where it is the segment's own end ``p`` (on the cell's boundary)."""
    nc = cx.shape[0] - 1
    if vertex:
        if entering:
            return (e - 1) % nc, 1.0, px, py
        return e, 0.0, px, py
    ax, ay, bx, by = cx[e], cy[e], cx[e + 1], cy[e + 1]
    dx, dy = bx - ax, by - ay
    u = ((px - ax) * dx + (py - ay) * dy) / (dx * dx + dy * dy)
    return e, min(max(u, 0.0), 1.0), px, py


@njit(**NJIT)
def _on_segment(px, py, qx, qy, x, y):
    """Whether point ``(x, y)`` lies on segment ``p q`` (exact)."""
    if not (min(px, qx) <= x <= max(px, qx) and min(py, qy) <= y <= max(py, qy)):
        return False
    return orient2d(px, py, qx, qy, x, y) == 0.0
