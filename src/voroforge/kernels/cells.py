"""Voronoi cells from a Delaunay triangulation, clipped to an axis-aligned box.

Output contract (shared with the half-plane kernel):

``coords (K, 2) float64``
    Vertices of every cell's convex polygon (cell intersected with the box), counter-clockwise,
    without a repeated closing vertex and without consecutive duplicates.
``offsets (n + 1,) int64``
    Cell ``i`` is ``coords[offsets[i]:offsets[i + 1]]`` (empty when it misses the box).
``owner (K,) int32``
    ``owner[k] = j`` when the polygon edge from vertex ``k`` to the next vertex lies on the
    bisector of sites ``i`` and ``j``; -1 when it lies on the box.

Interior cells are rings of circumcentres. Triangles whose circumcircles coincide (exactly
cocircular sites, decided with the exact ``incircle``) share one circumcentre, so cocircular
grids give clean cells without zero-length edges. Cells of hull sites (unbounded before
clipping) are cut out of the box by the bisectors of their Delaunay neighbours.
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

from ..config import NJIT, NJIT_PARALLEL
from .predicates import circumcenter, incircle, incircle_fast

_CHUNK = 2048


@njit(**NJIT)
def _find(parent, a):
    while parent[a] != a:
        parent[a] = parent[parent[a]]
        a = parent[a]
    return a


@njit(**NJIT_PARALLEL)
def circumcenters(xs, ys, tri):
    """Circumcentres of all triangles of a flat triangle array."""
    t = tri.shape[0] // 3
    cx = np.zeros(t)
    cy = np.zeros(t)
    for k in prange(t):
        a = tri[3 * k]
        b = tri[3 * k + 1]
        c = tri[3 * k + 2]
        cx[k], cy[k] = circumcenter(xs[a], ys[a], xs[b], ys[b], xs[c], ys[c])
    return cx, cy


@njit(**NJIT)
def _quad(tri, e, f):
    a = tri[e]
    b = tri[e - e % 3 + (e + 1) % 3]
    c = tri[e - e % 3 + (e + 2) % 3]
    d = tri[f - f % 3 + (f + 2) % 3]
    return a, b, c, d


@njit(**NJIT)
def _maybe_cocircular(xs, ys, tri, he):
    """Interior halfedges whose quadrilateral the fast incircle filter cannot call."""
    cnt = 0
    for e in range(tri.shape[0]):
        f = he[e]
        if f > e:
            a, b, c, d = _quad(tri, e, f)
            v = incircle_fast(xs[a], ys[a], xs[b], ys[b], xs[c], ys[c], xs[d], ys[d])
            if v != v:
                cnt += 1
    out = np.zeros(cnt, dtype=np.int64)
    cnt = 0
    for e in range(tri.shape[0]):
        f = he[e]
        if f > e:
            a, b, c, d = _quad(tri, e, f)
            v = incircle_fast(xs[a], ys[a], xs[b], ys[b], xs[c], ys[c], xs[d], ys[d])
            if v != v:
                out[cnt] = e
                cnt += 1
    return out


@njit(**NJIT)
def _merge_exact(xs, ys, tri, he, cand, cx, cy):
    t = tri.shape[0] // 3
    parent = np.arange(t)
    merged = False
    for k in range(cand.shape[0]):
        e = cand[k]
        f = he[e]
        a, b, c, d = _quad(tri, e, f)
        if incircle(xs[a], ys[a], xs[b], ys[b], xs[c], ys[c], xs[d], ys[d]) == 0.0:
            ra = _find(parent, e // 3)
            rb = _find(parent, f // 3)
            if ra != rb:
                parent[max(ra, rb)] = min(ra, rb)
                merged = True
    if merged:
        for k in range(t):
            r = _find(parent, k)
            parent[k] = r
            cx[k] = cx[r]
            cy[k] = cy[r]
    return parent


def merge_cocircular(xs, ys, tri, he, cx, cy):
    """Give triangles with the same circumcircle one circumcentre; return each one's class.

    Two triangles sharing an edge have the same circumcircle exactly when the fourth point is
    on the first one's circle (exact incircle == 0). Classes are the connected components of
    that relation; the centre of the class representative is copied to all its members. A
    filtered pass finds the few candidate edges, so the exact code runs only on those.
    """
    cand = _maybe_cocircular(xs, ys, tri, he)
    if cand.shape[0] == 0:
        return np.arange(tri.shape[0] // 3)
    return _merge_exact(xs, ys, tri, he, cand, cx, cy)


@njit(**NJIT)
def _outgoing(tri, he, n):
    """One outgoing halfedge per point; for hull points the outgoing hull halfedge."""
    out = np.full(n, -1, dtype=np.int64)
    for e in range(tri.shape[0]):
        out[tri[e]] = e
    for e in range(tri.shape[0]):
        if he[e] == -1:
            out[tri[e]] = e
    return out


@njit(**NJIT)
def _clip(px, py, pw, m, qx, qy, qw, nx, ny, c, ox, oy, w, axis, value):
    """Clip polygon ``p`` (m vertices, edge owners ``pw``) to ``nx*(x-ox) + ny*(y-oy) <= c``.

    The result goes to ``q``; returns its vertex count. New edges along the line get owner
    ``w``. ``axis`` 0/1 marks a box line ``x = value`` / ``y = value``, whose crossings get that
    coordinate exactly; ``axis`` -1 is a general line. Vertices on the line are kept as they
    are, so no near-duplicate vertex is created there.
    """
    if m == 0:
        return 0
    out = 0
    sk = nx * (px[0] - ox) + ny * (py[0] - oy) - c
    for k in range(m):
        nxt = k + 1 if k + 1 < m else 0
        sn = nx * (px[nxt] - ox) + ny * (py[nxt] - oy) - c
        if sk <= 0.0:
            qx[out] = px[k]
            qy[out] = py[k]
            qw[out] = w if (sk == 0.0 and sn > 0.0) else pw[k]
            out += 1
            if sk < 0.0 and sn > 0.0:
                t = sk / (sk - sn)
                qx[out] = value if axis == 0 else px[k] + t * (px[nxt] - px[k])
                qy[out] = value if axis == 1 else py[k] + t * (py[nxt] - py[k])
                qw[out] = w
                out += 1
        elif sn < 0.0:
            t = sk / (sk - sn)
            qx[out] = value if axis == 0 else px[k] + t * (px[nxt] - px[k])
            qy[out] = value if axis == 1 else py[k] + t * (py[nxt] - py[k])
            qw[out] = pw[k]
            out += 1
        sk = sn
    return _dedupe_ring(qx, qy, qw, out)


@njit(**NJIT)
def _dedupe_ring(qx, qy, qw, m):
    """Drop consecutive equal vertices (keeping the later edge owner); < 3 vertices -> 0."""
    out = 0
    for k in range(m):
        if out > 0 and qx[k] == qx[out - 1] and qy[k] == qy[out - 1]:
            qw[out - 1] = qw[k]
            continue
        qx[out] = qx[k]
        qy[out] = qy[k]
        qw[out] = qw[k]
        out += 1
    while out > 1 and qx[out - 1] == qx[0] and qy[out - 1] == qy[0]:
        out -= 1
    return out if out >= 3 else 0


@njit(**NJIT)
def _clip_box(px, py, pw, m, qx, qy, qw, box):
    """Clip a convex polygon to the box with four half-plane cuts; the result ends in ``p``."""
    m = _clip(px, py, pw, m, qx, qy, qw, -1.0, 0.0, -box[0], 0.0, 0.0, -1, 0, box[0])
    m = _clip(qx, qy, qw, m, px, py, pw, 0.0, -1.0, -box[1], 0.0, 0.0, -1, 1, box[1])
    m = _clip(px, py, pw, m, qx, qy, qw, 1.0, 0.0, box[2], 0.0, 0.0, -1, 0, box[2])
    m = _clip(qx, qy, qw, m, px, py, pw, 0.0, 1.0, box[3], 0.0, 0.0, -1, 1, box[3])
    return m


@njit(**NJIT)
def _cut_cell(i, xs, ys, nbrs, nn, box, px, py, pw, qx, qy, qw):
    """Cell of site ``i`` as the box cut by the bisectors with ``nbrs[:nn]``; result in ``p``."""
    px[0] = box[0]
    py[0] = box[1]
    px[1] = box[2]
    py[1] = box[1]
    px[2] = box[2]
    py[2] = box[3]
    px[3] = box[0]
    py[3] = box[3]
    for k in range(4):
        pw[k] = -1
    m = 4
    sx = xs[i]
    sy = ys[i]
    for k in range(nn):
        j = nbrs[k]
        dx = xs[j] - sx
        dy = ys[j] - sy
        # |v - s_i| <= |v - s_j|  <=>  dx * (vx - sx) + dy * (vy - sy) <= (dx^2 + dy^2) / 2
        c = 0.5 * (dx * dx + dy * dy)
        m = _clip(px, py, pw, m, qx, qy, qw, dx, dy, c, sx, sy, j, -1, 0.0)
        for v in range(m):
            px[v] = qx[v]
            py[v] = qy[v]
            pw[v] = qw[v]
        if m == 0:
            break
    return m


@njit(**NJIT)
def _cell(i, xs, ys, tri, he, cx, cy, cls, out, box, px, py, pw, qx, qy, qw, nbrs):
    """Polygon of site ``i`` into ``p``; returns the vertex count."""
    o0 = out[i]
    if o0 == -1:
        return 0
    hull = he[o0] == -1
    o = o0
    m = 0
    inside = True
    while True:
        t = o // 3
        p = o - o % 3 + (o + 2) % 3  # previous halfedge: y -> i
        y = tri[p]
        if hull:
            nbrs[m] = tri[o - o % 3 + (o + 1) % 3]
            m += 1
        else:
            if m > 0 and cls[t] == nbrs[m - 1]:
                pw[m - 1] = y  # same circumcentre as the previous vertex: skip the 0-length edge
            else:
                px[m] = cx[t]
                py[m] = cy[t]
                pw[m] = y
                nbrs[m] = cls[t]  # for interior sites nbrs holds each vertex's class
                vx = cx[t]
                vy = cy[t]
                if not (box[0] <= vx <= box[2] and box[1] <= vy <= box[3]):
                    inside = False
                m += 1
        o = he[p]
        if o == -1:
            if hull:
                nbrs[m] = y
                m += 1
            break
        if o == o0:
            break
    if hull:
        return _cut_cell(i, xs, ys, nbrs, m, box, px, py, pw, qx, qy, qw)
    if m > 1 and nbrs[m - 1] == nbrs[0]:
        m -= 1
    if m < 3:
        return 0
    if inside:
        return m
    return _clip_box(px, py, pw, m, qx, qy, qw, box)


@njit(**NJIT_PARALLEL)
def _count(xs, ys, tri, he, cx, cy, cls, out, box, cap):
    n = xs.shape[0]
    counts = np.zeros(n, dtype=np.int64)
    nchunks = (n + _CHUNK - 1) // _CHUNK
    for ch in prange(nchunks):
        px = np.zeros(cap)
        py = np.zeros(cap)
        pw = np.zeros(cap, dtype=np.int64)
        qx = np.zeros(cap)
        qy = np.zeros(cap)
        qw = np.zeros(cap, dtype=np.int64)
        nbrs = np.zeros(cap, dtype=np.int64)
        for i in range(ch * _CHUNK, min(n, (ch + 1) * _CHUNK)):
            counts[i] = _cell(
                i, xs, ys, tri, he, cx, cy, cls, out, box, px, py, pw, qx, qy, qw, nbrs
            )
    return counts


@njit(**NJIT_PARALLEL)
def _fill(xs, ys, tri, he, cx, cy, cls, out, box, cap, offsets, coords, owner):
    n = xs.shape[0]
    nchunks = (n + _CHUNK - 1) // _CHUNK
    for ch in prange(nchunks):
        px = np.zeros(cap)
        py = np.zeros(cap)
        pw = np.zeros(cap, dtype=np.int64)
        qx = np.zeros(cap)
        qy = np.zeros(cap)
        qw = np.zeros(cap, dtype=np.int64)
        nbrs = np.zeros(cap, dtype=np.int64)
        for i in range(ch * _CHUNK, min(n, (ch + 1) * _CHUNK)):
            m = _cell(i, xs, ys, tri, he, cx, cy, cls, out, box, px, py, pw, qx, qy, qw, nbrs)
            base = offsets[i]
            for k in range(m):
                coords[base + k, 0] = px[k]
                coords[base + k, 1] = py[k]
                owner[base + k] = pw[k]


@njit(**NJIT)
def _max_degree(tri, n):
    deg = np.zeros(n, dtype=np.int64)
    for e in range(tri.shape[0]):
        deg[tri[e]] += 1
    return deg.max() if n > 0 else 0


def cells_from_triangulation(xs, ys, tri, he, box):
    """Clipped convex cells of distinct sites from their Delaunay triangulation (flat arrays).

    Returns ``(coords, offsets, owner, centers, cls)``; ``centers`` are the (merged)
    circumcentres of the triangles and ``cls`` their cocircularity class.
    """
    n = xs.shape[0]
    box = np.asarray(box, dtype=np.float64)
    cx, cy = circumcenters(xs, ys, tri)
    cls = merge_cocircular(xs, ys, tri, he, cx, cy)
    out = _outgoing(tri, he, n)
    cap = int(_max_degree(tri, n)) + 16
    counts = _count(xs, ys, tri, he, cx, cy, cls, out, box, cap)
    offsets = np.zeros(n + 1, dtype=np.int64)
    np.cumsum(counts, out=offsets[1:])
    k = int(offsets[-1])
    coords = np.zeros((k, 2))
    owner = np.zeros(k, dtype=np.int32)
    _fill(xs, ys, tri, he, cx, cy, cls, out, box, cap, offsets, coords, owner)
    return coords, offsets, owner, np.stack((cx, cy), axis=1), cls


@njit(**NJIT_PARALLEL)
def _cut_all(xs, ys, indptr, indices, box, cap, counts, offsets, coords, owner, fill):
    n = xs.shape[0]
    nchunks = (n + _CHUNK - 1) // _CHUNK
    for ch in prange(nchunks):
        px = np.zeros(cap)
        py = np.zeros(cap)
        pw = np.zeros(cap, dtype=np.int64)
        qx = np.zeros(cap)
        qy = np.zeros(cap)
        qw = np.zeros(cap, dtype=np.int64)
        for i in range(ch * _CHUNK, min(n, (ch + 1) * _CHUNK)):
            nb = indices[indptr[i] : indptr[i + 1]]
            m = _cut_cell(i, xs, ys, nb, nb.shape[0], box, px, py, pw, qx, qy, qw)
            if not fill:
                counts[i] = m
                continue
            base = offsets[i]
            for k in range(m):
                coords[base + k, 0] = px[k]
                coords[base + k, 1] = py[k]
                owner[base + k] = pw[k]


def cells_from_neighbors(xs, ys, indptr, indices, box):
    """Clipped cells when the neighbours are known but there are no triangles (collinear)."""
    n = xs.shape[0]
    box = np.asarray(box, dtype=np.float64)
    deg = np.diff(indptr)
    cap = int(deg.max() if n else 0) + 16
    counts = np.zeros(n, dtype=np.int64)
    dummy_c = np.zeros((0, 2))
    dummy_o = np.zeros(0, dtype=np.int32)
    offsets = np.zeros(n + 1, dtype=np.int64)
    _cut_all(xs, ys, indptr, indices, box, cap, counts, offsets, dummy_c, dummy_o, False)
    np.cumsum(counts, out=offsets[1:])
    coords = np.zeros((int(offsets[-1]), 2))
    owner = np.zeros(int(offsets[-1]), dtype=np.int32)
    _cut_all(xs, ys, indptr, indices, box, cap, counts, offsets, coords, owner, True)
    return coords, offsets, owner
