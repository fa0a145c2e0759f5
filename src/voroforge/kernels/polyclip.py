"""Convex cells clipped to a polygonal domain by the boundary segments near each cell.

A cell (a closed counter-clockwise convex ring) that meets the domain's boundary is cut by
the segments in the grid buckets its box covers (:func:`bucket_segments`), not by the whole
domain: a comb whose one outline meets every cell costs each cell the teeth it meets.
The domain's rings run with the domain on their left (shells counter-clockwise, holes
clockwise). Each segment is cut to the cell (Cyrus-Beck); the pieces inside it join into
chains along the rings, each entering the cell across one of its edges and leaving it
across another; the clipped cell's rings are the chains joined along the cell's boundary,
counter-clockwise from each chain's exit to the next entry (:func:`clip_cells`).

Every sign is a filtered float orientation: where one is within its error bound (a vertex
of the domain on a cell's edge line, a boundary segment along a cell's edge, a crossing
near a cell's vertex, two crossings nearly at one point) the cell is not clipped here but
flagged for the overlay. The boundary along the sides of the domain's bounding box (a
comb's top and bottom rows, a zigzag's peaks on the box) is pushed out of the box by an
infinitesimal for cells inside the box (:func:`box_sides`): the domain inside the box is
the same, and a segment leaves a cell's edge on the box only at its own vertex. A ring of
the domain wholly inside a cell comes back as a loop (a hole or a part). A crossing is
computed as GEOS computes it (``CGAlgorithmsDD::intersection``: homogeneous coordinates in
double-double arithmetic), symmetric in the two segments and their directions: two cells
sharing an edge place a crossing on it at the same point, the point GEOS's overlay (and its
clip of the shared edge) gives.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..config import NJIT, POLYCLIP_ORIENT_EPS, POLYCLIP_PARAM_EPS, POLYCLIP_ULPS

DONE = 0  # clipped here
NONE = 1  # no boundary segment meets the cell: wholly inside or wholly outside
HARD = 2  # left to the overlay (a near-degenerate sign; HARD + k: which test, k < 20)
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
def _orient(ax, ay, bx, by, px, py):
    """``(b - a) x (p - a)`` and its error bound."""
    left = (bx - ax) * (py - ay)
    right = (by - ay) * (px - ax)
    return left - right, POLYCLIP_ORIENT_EPS * (abs(left) + abs(right))


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
    x0, y0, h = grid[0], grid[1], grid[2]
    nx, ny = int(grid[3]), int(grid[4])
    m = seg.shape[0]
    u = ring_off.shape[0] - 1
    stamp = np.full(m, -1, dtype=np.int64)
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
                    if stamp[g] == i:
                        continue
                    stamp[g] = i
                    loc[g] = -1
                    if in_box and sides[g, 0] >= 0:
                        continue  # (along a side of the box: outside, pushed out)
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
        got = _clip_one(cx, cy, nc, seg, nxt, cand[:n_cand], stamp, loc, i, edge_side, sides)
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
def _clip_one(cx, cy, nc, seg, nxt, cand, stamp, loc, cell, edge_side, sides):
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
    dp = np.zeros(nc)
    dq = np.zeros(nc)
    # rounding a crossing moves it by under an ulp: every feature the clipped rings keep
    # (a vertex off a cell's edge, a cell's vertex off a segment, two crossings on one
    # edge) must be farther than POLYCLIP_ULPS ulps of the cell's coordinates, or the
    # rounded rings could touch or cross themselves (a comb far out, where teeth are a
    # few ulps wide)
    mag = 0.0
    length = np.zeros(nc)
    for k in range(nc):
        mag = max(mag, abs(cx[k]), abs(cy[k]))
        length[k] = math.hypot(cx[k + 1] - cx[k], cy[k + 1] - cy[k])
    gap = POLYCLIP_ULPS * np.spacing(mag)
    # (only a segment's end near the cell can be a vertex of the clipped cell)
    lo_x, hi_x = cx.min() - 2 * gap, cx.max() + 2 * gap
    lo_y, hi_y = cy.min() - 2 * gap, cy.max() + 2 * gap
    n_piece = 0
    for j in range(q):
        g = cand[j]
        px, py, qx, qy = seg[g, 0], seg[g, 1], seg[g, 2], seg[g, 3]
        outside = False
        near = False
        p_near = lo_x <= px <= hi_x and lo_y <= py <= hi_y
        q_near = lo_x <= qx <= hi_x and lo_y <= qy <= hi_y
        for k in range(nc):
            v, e = _orient(cx[k], cy[k], cx[k + 1], cy[k + 1], px, py)
            w, f = _orient(cx[k], cy[k], cx[k + 1], cy[k + 1], qx, qy)
            s = edge_side[k]
            if s >= 0:
                # (the box's side: every vertex is on it or inside, the sign exact)
                v = -1.0 if (sides[g, 1] >> s) & 1 else max(v, 1.0)
                w = -1.0 if (sides[g, 2] >> s) & 1 else max(w, 1.0)
                dp[k] = v
                dq[k] = w
                if v < 0.0 and w < 0.0:
                    outside = True
                    break
                continue
            dp[k] = v
            dq[k] = w
            if v < -e and w < -f:
                outside = True
                break
            if abs(v) <= e or abs(w) <= f:
                near = True
            if (p_near and abs(v) <= gap * length[k]) or (q_near and abs(w) <= gap * length[k]):
                near = True
        if outside:
            continue
        if near:
            return HARD + 0, nothing[0], nothing[1], 0
        # the last entry and first exit along the segment, and their runners-up (a
        # segment through a cell's vertex enters or leaves by two edges at one point)
        t_in, t_in2, t_out, t_out2 = -1.0, -1.0, 2.0, 2.0
        for k in range(nc):
            if dp[k] < 0.0 or dq[k] < 0.0:
                t = dp[k] / (dp[k] - dq[k])
                if edge_side[k] >= 0:
                    t = 0.0 if dp[k] < 0.0 else 1.0  # (at the pushed vertex itself)
                if dp[k] < 0.0:
                    if t > t_in:
                        t_in, t_in2 = t, t_in
                        k_in[j] = k
                    elif t > t_in2:
                        t_in2 = t
                else:
                    if t < t_out:
                        t_out, t_out2 = t, t_out
                        k_out[j] = k
                    elif t < t_out2:
                        t_out2 = t
        if k_in[j] >= 0 and t_in - t_in2 <= POLYCLIP_PARAM_EPS:
            return HARD + 1, nothing[0], nothing[1], 0
        if k_out[j] >= 0 and t_out2 - t_out <= POLYCLIP_PARAM_EPS:
            return HARD + 2, nothing[0], nothing[1], 0
        t_in = max(t_in, 0.0)
        t_out = min(t_out, 1.0)
        if t_in > t_out + POLYCLIP_PARAM_EPS:
            k_in[j] = -1
            k_out[j] = -1
            continue  # (it passes by a corner of the cell)
        if t_in >= t_out - POLYCLIP_PARAM_EPS:
            return HARD + 3, nothing[0], nothing[1], 0
        for side in range(2):
            k = k_in[j] if side == 0 else k_out[j]
            if k < 0:
                continue
            ax, ay, bx, by = cx[k], cy[k], cx[k + 1], cy[k + 1]
            if edge_side[k] >= 0:
                # the pushed vertex, strictly between the edge's ends (exact, on an axis)
                x, y = (px, py) if side == 0 else (qx, qy)
                a, b, c = (ax, bx, x) if edge_side[k] % 2 == 1 else (ay, by, y)
                if not (min(a, b) < c < max(a, b)):
                    return HARD + 4, nothing[0], nothing[1], 0
                t = (c - a) / (b - a)
                if side == 0:
                    u_in[j] = t
                    x_in[j, 0], x_in[j, 1] = x, y
                else:
                    u_out[j] = t
                    x_out[j, 0], x_out[j, 1] = x, y
                continue
            da, ea = _orient(px, py, qx, qy, ax, ay)
            db, eb = _orient(px, py, qx, qy, bx, by)
            far = gap * math.hypot(qx - px, qy - py)
            if abs(da) <= max(ea, far) or abs(db) <= max(eb, far) or (da < 0.0) == (db < 0.0):
                return HARD + 5, nothing[0], nothing[1], 0
            t = da / (da - db)
            if t <= POLYCLIP_PARAM_EPS or t >= 1.0 - POLYCLIP_PARAM_EPS:
                return HARD + 6, nothing[0], nothing[1], 0
            if min(t, 1.0 - t) * length[k] <= gap:
                return HARD + 7, nothing[0], nothing[1], 0
            x, y = geos_intersection(ax, ay, bx, by, px, py, qx, qy)
            if not (
                min(ax, bx) <= x <= max(ax, bx)
                and min(ay, by) <= y <= max(ay, by)
                and min(px, qx) <= x <= max(px, qx)
                and min(py, qy) <= y <= max(py, qy)
            ):
                return HARD + 8, nothing[0], nothing[1], 0  # (GEOS moves it to an end point)
            if side == 0:
                u_in[j] = t
                x_in[j, 0], x_in[j, 1] = x, y
            else:
                u_out[j] = t
                x_out[j, 0], x_out[j, 1] = x, y
        has[j] = True
        n_piece += 1
    if n_piece == 0:
        return NONE, nothing[0], nothing[1], 0
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
    for e in range(n_ev - 1):
        d = key[order[e + 1]] - key[order[e]]
        k = int(key[order[e]])
        if d <= POLYCLIP_PARAM_EPS * nc:
            return HARD + 12, nothing[0], nothing[1], 0
        if int(key[order[e + 1]]) == k and d * length[k] <= gap and edge_side[k] < 0:
            return HARD + 13, nothing[0], nothing[1], 0
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
