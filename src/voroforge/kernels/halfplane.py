"""Voronoi cells by cutting: each cell is the box cut by the bisectors of nearby sites.

This is the voro++ design in two dimensions. Every cell is built on its own, so cells are
computed in parallel and the same structure carries over to 3D (a polyhedron instead of a
polygon, the same grid and search):

1. The sites are counting-sorted into a uniform grid of buckets over their bounding box
   (about ``_PER_BUCKET`` sites per bucket, CSR layout: ``start`` and sorted coordinates).
2. A cell starts as the box, in coordinates relative to its site (so 500000/4000000-style
   inputs keep their precision). Buckets are visited in square rings of growing distance
   from the site's bucket, and the polygon is cut by the bisector of each site found there.
3. The polygon lies within ``r`` (its largest vertex distance) of the site, and the bisector
   of a site at distance ``d`` stays at least ``d / 2`` away, so only sites with
   ``d < 2 r`` can cut. Once a ring is farther than ``2 r`` the cell is final.

The cut keeps the vertices with signed value ``p . q - |q|^2 / 2 <= 0`` (each value computed
once), inserts the two crossing points and never stores two equal consecutive vertices, so
the result stays a consistent ring without any tolerance. Output contract (shared with
``cells.py``): ``coords (K, 2)`` counter-clockwise vertices per cell, ``offsets (n + 1,)``,
``owner (K,)`` with the site across each edge, -1 on the box.

Output arrays are exact-size in one pass: chunks of cells are written to per-chunk slabs of
fixed capacity and then copied into place; the rare chunk that overflows its slab is simply
recomputed straight into the output.
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

from ..config import NJIT, NJIT_PARALLEL

_PER_BUCKET = 2.0  # mean sites per grid bucket
_CHUNK = 512  # cells per parallel work item
_SLAB = 7  # slab vertices per cell of a chunk (the mean over a diagram is below 6)
_CAP = 64  # initial per-cell scratch capacity (doubled when a cell needs more)
_REACH = 4.0 * (1.0 + 1e-9)  # (2 r)^2 / r^2 with a margin against rounding in r

# Box sides as internal owner codes, counter-clockwise from the bottom; all become -1.
_BOTTOM, _RIGHT, _TOP, _LEFT = -1, -2, -3, -4


@njit(**NJIT)
def _grid_shape(xs, ys):
    """Return ``(x0, y0, hx, hy, nx, ny)`` of a grid over the sites' bounding box."""
    n = xs.shape[0]
    x0 = xs.min()
    y0 = ys.min()
    w = xs.max() - x0
    h = ys.max() - y0
    span = max(w, h)
    if span == 0.0:
        span = max(abs(x0), abs(y0), 1.0)
    w = max(w, 1e-6 * span)
    h = max(h, 1e-6 * span)
    nb = max(1.0, n / _PER_BUCKET)
    nx = int(min(max(np.sqrt(nb * w / h), 1.0), nb))
    ny = int(min(max(nb / nx, 1.0), nb))
    # a hair wider than the points so that int((x - x0) / hx) < nx for every site
    hx = w * (1.0 + 1e-12) / nx
    hy = h * (1.0 + 1e-12) / ny
    return x0, y0, hx, hy, nx, ny


@njit(**NJIT)
def _bucket(x, y, x0, y0, hx, hy, nx, ny):
    ix = min(max(int((x - x0) / hx), 0), nx - 1)
    iy = min(max(int((y - y0) / hy), 0), ny - 1)
    return ix, iy


@njit(**NJIT)
def _bucket_sort(xs, ys, x0, y0, hx, hy, nx, ny):
    """Counting sort of the sites into buckets: ``start``, sorted x, y and original index."""
    n = xs.shape[0]
    key = np.zeros(n, np.int64)
    start = np.zeros(nx * ny + 1, np.int64)
    for i in range(n):
        ix, iy = _bucket(xs[i], ys[i], x0, y0, hx, hy, nx, ny)
        key[i] = iy * nx + ix
        start[key[i] + 1] += 1
    for b in range(nx * ny):
        start[b + 1] += start[b]
    fill = start[:-1].copy()
    sx = np.zeros(n)
    sy = np.zeros(n)
    sidx = np.zeros(n, np.int64)
    for i in range(n):
        t = fill[key[i]]
        fill[key[i]] += 1
        sx[t] = xs[i]
        sy[t] = ys[i]
        sidx[t] = i
    return start, sx, sy, sidx


@njit(**NJIT)
def _push(wx, wy, wo, c, x, y, o):
    """Append a vertex, merging it into the previous one when they coincide."""
    if c > 0 and wx[c - 1] == x and wy[c - 1] == y:
        wo[c - 1] = o  # the zero-length edge goes; the later edge keeps its owner
        return c
    wx[c] = x
    wy[c] = y
    wo[c] = o
    return c + 1


@njit(**NJIT)
def _close(wx, wy, c):
    """Drop trailing vertices equal to the first one (zero-length closing edges)."""
    while c > 1 and wx[c - 1] == wx[0] and wy[c - 1] == wy[0]:
        c -= 1
    return c


@njit(**NJIT)
def _cut(vx, vy, vo, m, wx, wy, wo, ss, qx, qy, j):
    """Cut polygon ``v[:m]`` by the half-plane closer to the origin than to ``q``.

    The result goes to ``w``; returns its length, or -1 when no vertex is cut away.
    """
    h = 0.5 * (qx * qx + qy * qy)
    cut = False
    for k in range(m):
        s = vx[k] * qx + vy[k] * qy - h
        ss[k] = s
        if s > 0.0:
            cut = True
    if not cut:
        return -1
    c = 0
    for k in range(m):
        kn = k + 1 if k + 1 < m else 0
        sa = ss[k]
        sb = ss[kn]
        if sa <= 0.0:
            if sb <= 0.0:
                c = _push(wx, wy, wo, c, vx[k], vy[k], vo[k])
            elif sa == 0.0:
                c = _push(wx, wy, wo, c, vx[k], vy[k], j)
            else:  # leaving: keep the vertex, then the exit point starts the new edge
                c = _push(wx, wy, wo, c, vx[k], vy[k], vo[k])
                t = sa / (sa - sb)
                x = vx[k] + t * (vx[kn] - vx[k])
                y = vy[k] + t * (vy[kn] - vy[k])
                c = _push(wx, wy, wo, c, x, y, j)
        elif sb < 0.0:  # entering: the entry point continues along the old edge
            t = sb / (sb - sa)
            x = vx[kn] + t * (vx[k] - vx[kn])
            y = vy[kn] + t * (vy[k] - vy[kn])
            c = _push(wx, wy, wo, c, x, y, vo[k])
    return _close(wx, wy, c)


@njit(**NJIT)
def _radius2(vx, vy, m):
    r2 = 0.0
    for k in range(m):
        d = vx[k] * vx[k] + vy[k] * vy[k]
        if d > r2:
            r2 = d
    return r2


@njit(**NJIT)
def _ring_gap(ix, iy, ring, fx0, fx1, fy0, fy1, hx, hy, nx, ny):
    """Least distance from the site to any bucket of ``ring``; -1 when the ring is off-grid."""
    gap = np.inf
    if ix - ring >= 0:
        gap = min(gap, fx0 + (ring - 1) * hx)
    if ix + ring < nx:
        gap = min(gap, fx1 + (ring - 1) * hx)
    if iy - ring >= 0:
        gap = min(gap, fy0 + (ring - 1) * hy)
    if iy + ring < ny:
        gap = min(gap, fy1 + (ring - 1) * hy)
    return -1.0 if gap == np.inf else gap


@njit(**NJIT)
def _cut_bucket(b, k, px, py, st, r2, m, a, bx, by, bo, ss):
    """Cut the cell of sorted site ``k`` by every site of bucket ``b``.

    ``st = (start, sx, sy, sidx)``. Returns ``(m, a, r2)``: the new length (0 when the cell
    vanished, -1 when the scratch is too small), the row holding it and the new radius.
    """
    start, sx, sy, sidx = st
    cap = bx.shape[1]
    for t in range(start[b], start[b + 1]):
        if t == k:
            continue
        qx = sx[t] - px
        qy = sy[t] - py
        if qx * qx + qy * qy > _REACH * r2:
            continue
        if 2 * m + 2 > cap:
            return -1, a, r2
        c = _cut(bx[a], by[a], bo[a], m, bx[1 - a], by[1 - a], bo[1 - a], ss, qx, qy, sidx[t])
        if c < 0:
            continue
        a = 1 - a
        m = c
        if m < 3:
            return 0, a, r2
        r2 = _radius2(bx[a], by[a], m)
    return m, a, r2


@njit(**NJIT)
def _build(k, st, grid, box, bx, by, bo, ss):
    """Build the cell of sorted site ``k`` in scratch rows ``bx/by/bo``, relative to the site.

    Returns ``(m, a)``: the vertex count (0 if empty, -1 if the scratch is too small) and the
    scratch row that holds the polygon.
    """
    sx = st[1]
    sy = st[2]
    x0, y0, hx, hy, nx, ny = grid
    px = sx[k]
    py = sy[k]
    xmin = box[0] - px
    ymin = box[1] - py
    xmax = box[2] - px
    ymax = box[3] - py
    a = 0
    bx[0, 0], by[0, 0], bo[0, 0] = xmin, ymin, _BOTTOM
    bx[0, 1], by[0, 1], bo[0, 1] = xmax, ymin, _RIGHT
    bx[0, 2], by[0, 2], bo[0, 2] = xmax, ymax, _TOP
    bx[0, 3], by[0, 3], bo[0, 3] = xmin, ymax, _LEFT
    m = 4
    r2 = _radius2(bx[0], by[0], m)
    ix, iy = _bucket(px, py, x0, y0, hx, hy, nx, ny)
    fx0 = px - (x0 + ix * hx)
    fx1 = x0 + (ix + 1) * hx - px
    fy0 = py - (y0 + iy * hy)
    fy1 = y0 + (iy + 1) * hy - py
    m, a, r2 = _cut_bucket(iy * nx + ix, k, px, py, st, r2, m, a, bx, by, bo, ss)
    ring = 1
    while m >= 3:
        gap = _ring_gap(ix, iy, ring, fx0, fx1, fy0, fy1, hx, hy, nx, ny)
        if gap < 0.0 or gap * gap > _REACH * r2:
            break
        for jy in range(max(iy - ring, 0), min(iy + ring, ny - 1) + 1):
            edge_row = jy == iy - ring or jy == iy + ring
            step = 1 if edge_row else 2 * ring
            dy = max(y0 + jy * hy - py, py - (y0 + (jy + 1) * hy), 0.0)
            for jx in range(ix - ring, ix + ring + 1, step):
                if jx < 0 or jx >= nx:
                    continue
                dx = max(x0 + jx * hx - px, px - (x0 + (jx + 1) * hx), 0.0)
                if dx * dx + dy * dy > _REACH * r2:
                    continue
                m, a, r2 = _cut_bucket(jy * nx + jx, k, px, py, st, r2, m, a, bx, by, bo, ss)
                if m < 3:
                    break
            if m < 3:
                break
        ring += 1
    if m < 0:
        return -1, a
    return (m if m >= 3 else 0), a


@njit(**NJIT)
def _emit(vx, vy, vo, m, px, py, box, ox, oy, oo):
    """Write the cell in absolute coordinates, snapped onto the box; returns its length."""
    xmin, ymin, xmax, ymax = box[0], box[1], box[2], box[3]
    c = 0
    for t in range(m):
        x = min(max(vx[t] + px, xmin), xmax)
        y = min(max(vy[t] + py, ymin), ymax)
        o = vo[t]
        op = vo[t - 1] if t > 0 else vo[m - 1]
        for side in (o, op):
            if side == _BOTTOM:
                y = ymin
            elif side == _RIGHT:
                x = xmax
            elif side == _TOP:
                y = ymax
            elif side == _LEFT:
                x = xmin
        c = _push(ox, oy, oo, c, x, y, o if o >= 0 else -1)
    c = _close(ox, oy, c)
    return c if c >= 3 else 0


@njit(**NJIT)
def _cell(k, st, grid, box, scratch):
    """Build and emit the cell of sorted site ``k``; returns ``(length, scratch)``.

    ``scratch = (bx, by, bo, ss, ox, oy, oo)`` is replaced by a larger one when needed; the
    emitted polygon is in ``ox, oy, oo``.
    """
    bx, by, bo, ss, ox, oy, oo = scratch
    while True:
        m, a = _build(k, st, grid, box, bx, by, bo, ss)
        if m >= 0:
            break
        cap = 2 * bx.shape[1]
        bx = np.zeros((2, cap))
        by = np.zeros((2, cap))
        bo = np.zeros((2, cap), np.int64)
        ss = np.zeros(cap)
        ox = np.zeros(cap)
        oy = np.zeros(cap)
        oo = np.zeros(cap, np.int64)
    c = _emit(bx[a], by[a], bo[a], m, st[1][k], st[2][k], box, ox, oy, oo)
    return c, (bx, by, bo, ss, ox, oy, oo)


@njit(**NJIT)
def _scratch(cap):
    return (
        np.zeros((2, cap)),
        np.zeros((2, cap)),
        np.zeros((2, cap), np.int64),
        np.zeros(cap),
        np.zeros(cap),
        np.zeros(cap),
        np.zeros(cap, np.int64),
    )


@njit(**NJIT_PARALLEL)
def _first_pass(st, grid, box, counts, where, slab_x, slab_y, slab_o, full):
    """Build every cell; store it in its chunk's slab, or mark the chunk full."""
    n = st[1].shape[0]
    sidx = st[3]
    per = slab_x.shape[0] // full.shape[0]
    for ch in prange(full.shape[0]):
        scratch = _scratch(_CAP)
        pos = ch * per
        end = pos + per
        for k in range(ch * _CHUNK, min((ch + 1) * _CHUNK, n)):
            c, scratch = _cell(k, st, grid, box, scratch)
            counts[sidx[k]] = c
            if full[ch] == 0 and pos + c <= end:
                ox, oy, oo = scratch[4], scratch[5], scratch[6]
                where[k] = pos
                for t in range(c):
                    slab_x[pos + t] = ox[t]
                    slab_y[pos + t] = oy[t]
                    slab_o[pos + t] = oo[t]
                pos += c
            else:
                full[ch] = 1


@njit(**NJIT_PARALLEL)
def _second_pass(st, grid, box, offsets, where, slab_x, slab_y, slab_o, full, coords, owner):
    """Move every cell to its place in the output; rebuild the cells of full chunks."""
    n = st[1].shape[0]
    sidx = st[3]
    for ch in prange(full.shape[0]):
        scratch = _scratch(_CAP if full[ch] else 1)
        for k in range(ch * _CHUNK, min((ch + 1) * _CHUNK, n)):
            i = sidx[k]
            dst = offsets[i]
            c = offsets[i + 1] - dst
            if full[ch]:
                c, scratch = _cell(k, st, grid, box, scratch)
                ox, oy, oo = scratch[4], scratch[5], scratch[6]
                for t in range(c):
                    coords[dst + t, 0] = ox[t]
                    coords[dst + t, 1] = oy[t]
                    owner[dst + t] = oo[t]
            else:
                src = where[k]
                for t in range(c):
                    coords[dst + t, 0] = slab_x[src + t]
                    coords[dst + t, 1] = slab_y[src + t]
                    owner[dst + t] = slab_o[src + t]


def halfplane_cells(points, box):
    """Voronoi cells of ``points`` clipped to ``box``, by half-plane cutting.

    Parameters
    ----------
    points : (n, 2) float64
        Distinct sites (the engine removes duplicates); they may lie outside the box.
    box : tuple of 4 float
        ``(xmin, ymin, xmax, ymax)``.

    Returns
    -------
    coords : (K, 2) float64
        Counter-clockwise vertices of every non-empty cell, no closing repeat, no
        consecutive duplicates.
    offsets : (n + 1,) int64
        Cell ``i`` is ``coords[offsets[i]:offsets[i + 1]]``; empty when it misses the box.
    owner : (K,) int32
        Site across the edge from vertex ``k`` to the next one, or -1 on the box boundary.

    Examples
    --------
    >>> import numpy as np
    >>> coords, offsets, owner = halfplane_cells(np.array([[0.25, 0.5], [0.75, 0.5]]),
    ...                                          (0.0, 0.0, 1.0, 1.0))
    >>> offsets.tolist(), owner[:4].tolist()
    ([0, 4, 8], [-1, 1, -1, -1])
    """
    pts = np.ascontiguousarray(points, dtype=np.float64).reshape(-1, 2)
    n = pts.shape[0]
    if n == 0:
        return np.zeros((0, 2)), np.zeros(1, np.int64), np.zeros(0, np.int32)
    boxa = np.asarray(box, dtype=np.float64).reshape(4)
    xs = np.ascontiguousarray(pts[:, 0])
    ys = np.ascontiguousarray(pts[:, 1])
    grid = _grid_shape(xs, ys)
    st = _bucket_sort(xs, ys, *grid)
    nchunks = (n + _CHUNK - 1) // _CHUNK
    per = _SLAB * min(_CHUNK, n) + 16
    counts = np.zeros(n, np.int64)
    where = np.zeros(n, np.int64)
    slab_x = np.zeros(nchunks * per)
    slab_y = np.zeros(nchunks * per)
    slab_o = np.zeros(nchunks * per, np.int64)
    full = np.zeros(nchunks, np.int8)
    _first_pass(st, grid, boxa, counts, where, slab_x, slab_y, slab_o, full)
    offsets = np.zeros(n + 1, np.int64)
    np.cumsum(counts, out=offsets[1:])
    k = int(offsets[-1])
    coords = np.empty((k, 2))  # noqa: TID251 - every slot is written by _second_pass
    owner = np.empty(k, np.int32)  # noqa: TID251 - every slot is written by _second_pass
    _second_pass(st, grid, boxa, offsets, where, slab_x, slab_y, slab_o, full, coords, owner)
    return coords, offsets, owner
