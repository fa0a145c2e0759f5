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
def _push(px, py, po, c, x, y, o):
    """Append vertex ``c`` (an absolute index), or merge it into vertex ``c - 1`` if equal.

    Returns the index of the next free slot.
    """
    if px[c - 1] == x and py[c - 1] == y:
        po[c - 1] = o  # the zero-length edge goes; the later edge keeps its owner
        return c
    px[c] = x
    py[c] = y
    po[c] = o
    return c + 1


@njit(**NJIT)
def _cut(px, py, po, a, m, b, ss, j):
    """Cut the polygon at ``a:a + m`` where its signed values ``ss`` are positive.

    The result goes to ``b:``; returns its length and its squared radius (largest squared
    vertex norm). ``px, py, po`` hold both polygons (``a`` and ``b`` are their offsets).
    """
    c = b
    px[b - 1] = np.nan  # so that the first vertex is never merged
    for k in range(m):
        kn = k + 1 if k + 1 < m else 0
        sa = ss[k]
        sb = ss[kn]
        ax = px[a + k]
        ay = py[a + k]
        if sa <= 0.0:
            # a kept vertex on the line starts the new edge
            c = _push(px, py, po, c, ax, ay, j if sa == 0.0 and sb > 0.0 else po[a + k])
            if sa < 0.0 and sb > 0.0:  # leaving: the exit point starts the new edge
                t = sa / (sa - sb)
                c = _push(px, py, po, c, ax + t * (px[a + kn] - ax), ay + t * (py[a + kn] - ay), j)
        elif sb < 0.0:  # entering: the entry point continues along the old edge
            t = sb / (sb - sa)
            bx = px[a + kn]
            by = py[a + kn]
            c = _push(px, py, po, c, bx + t * (ax - bx), by + t * (ay - by), po[a + k])
    while c > b + 1 and px[c - 1] == px[b] and py[c - 1] == py[b]:
        c -= 1  # trailing vertices equal to the first one
    r2 = 0.0
    for k in range(b, c):
        r2 = max(r2, px[k] * px[k] + py[k] * py[k])
    return c - b, r2


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
def _emit(px, py, po, a, m, cx, cy, box, ox, oy, oo, pos):
    """Write the cell at ``a:a + m`` around site ``(cx, cy)`` to ``ox, oy, oo`` from ``pos``.

    Coordinates become absolute and vertices on box edges are snapped onto the box. Returns
    the length written (0 when rounding left fewer than three distinct vertices).
    """
    xmin, ymin, xmax, ymax = box[0], box[1], box[2], box[3]
    c = pos
    for t in range(a, a + m):
        x = min(max(px[t] + cx, xmin), xmax)
        y = min(max(py[t] + cy, ymin), ymax)
        o = po[t]
        op = po[t - 1] if t > a else po[a + m - 1]
        if o == _BOTTOM or op == _BOTTOM:
            y = ymin
        if o == _TOP or op == _TOP:
            y = ymax
        if o == _LEFT or op == _LEFT:
            x = xmin
        if o == _RIGHT or op == _RIGHT:
            x = xmax
        o = max(o, -1)
        if c > pos and ox[c - 1] == x and oy[c - 1] == y:
            oo[c - 1] = o
        else:
            ox[c] = x
            oy[c] = y
            oo[c] = o
            c += 1
    while c > pos + 1 and ox[c - 1] == ox[pos] and oy[c - 1] == oy[pos]:
        c -= 1
    return c - pos if c - pos >= 3 else 0


@njit(**NJIT)
def _scratch(cap):
    """Scratch arrays: two polygons (at offsets 1 and ``cap + 2``), signed values, a cell."""
    return (
        np.zeros(2 * cap + 2),
        np.zeros(2 * cap + 2),
        np.zeros(2 * cap + 2, np.int64),
        np.zeros(cap),
        np.zeros(cap),
        np.zeros(cap),
        np.zeros(cap, np.int64),
    )


@njit(**NJIT)
def _cells(k0, k1, sites, grid, box, counts, where, dx, dy, do):
    """Build the cells of sorted sites ``k0:k1`` and write them one after another to ``d``.

    ``sites = (start, sx, sy, sidx)`` is the bucket grid. Sets ``counts[sidx[k]]`` to each
    cell's length and ``where[k]`` to its position in ``dx, dy, do``. Cells that no longer
    fit are only counted. Returns whether all of them fit.

    The whole loop lives in this one function: a call per cell would cost a dozen atomic
    reference-count updates, more than the geometry of a typical cell.
    """
    start, sx, sy, sidx = sites
    x0, y0, hx, hy, nx, ny = grid
    cap = _CAP
    px, py, po, ss, ox, oy, oo = _scratch(cap)
    pos = 0
    fits = True
    k = k0
    while k < k1:
        cx = sx[k]
        cy = sy[k]
        # the box, relative to the site, as polygon a (polygon b receives the next cut)
        a = 1
        b = cap + 2
        px[a], py[a], po[a] = box[0] - cx, box[1] - cy, _BOTTOM
        px[a + 1], py[a + 1], po[a + 1] = box[2] - cx, box[1] - cy, _RIGHT
        px[a + 2], py[a + 2], po[a + 2] = box[2] - cx, box[3] - cy, _TOP
        px[a + 3], py[a + 3], po[a + 3] = box[0] - cx, box[3] - cy, _LEFT
        m = 4
        r2 = 0.0
        for t in range(a, a + 4):
            r2 = max(r2, px[t] * px[t] + py[t] * py[t])
        ix, iy = _bucket(cx, cy, x0, y0, hx, hy, nx, ny)
        fx0 = cx - (x0 + ix * hx)
        fx1 = x0 + (ix + 1) * hx - cx
        fy0 = cy - (y0 + iy * hy)
        fy1 = y0 + (iy + 1) * hy - cy
        ring = 0
        grow = False
        while m >= 3 and not grow:
            if ring > 0:
                gap = _ring_gap(ix, iy, ring, fx0, fx1, fy0, fy1, hx, hy, nx, ny)
                if gap < 0.0 or gap * gap > _REACH * r2:
                    break
            for jy in range(max(iy - ring, 0), min(iy + ring, ny - 1) + 1):
                step = 1 if jy == iy - ring or jy == iy + ring else 2 * ring
                gy = max(y0 + jy * hy - cy, cy - (y0 + (jy + 1) * hy), 0.0)
                for jx in range(ix - ring, ix + ring + 1, step):
                    if jx < 0 or jx >= nx or m < 3 or grow:
                        continue
                    gx = max(x0 + jx * hx - cx, cx - (x0 + (jx + 1) * hx), 0.0)
                    if gx * gx + gy * gy > _REACH * r2:
                        continue
                    bucket = jy * nx + jx
                    for t in range(start[bucket], start[bucket + 1]):
                        qx = sx[t] - cx
                        qy = sy[t] - cy
                        h = 0.5 * (qx * qx + qy * qy)
                        if t == k or 2.0 * h > _REACH * r2:
                            continue
                        out = False
                        for u in range(m):
                            s = px[a + u] * qx + py[a + u] * qy - h
                            ss[u] = s
                            out |= s > 0.0
                        if not out:
                            continue
                        if m + m // 2 + 2 > cap:  # each run of cut vertices adds at most one
                            grow = True
                            break
                        m, r2 = _cut(px, py, po, a, m, b, ss, sidx[t])
                        a, b = b, a
                        if m < 3:
                            break
            ring += 1
        if grow:  # rare: a cell with many vertices; start it again with more room
            cap *= 2
            px, py, po, ss, ox, oy, oo = _scratch(cap)
            continue
        c = 0
        if m >= 3:
            if fits and pos + m <= dx.shape[0]:
                c = _emit(px, py, po, a, m, cx, cy, box, dx, dy, do, pos)
            else:
                fits = False
                c = _emit(px, py, po, a, m, cx, cy, box, ox, oy, oo, 0)
        counts[sidx[k]] = c
        where[k] = pos
        pos += c
        k += 1
    return fits


@njit(**NJIT_PARALLEL)
def _first_pass(sites, grid, box, counts, where, slab_x, slab_y, slab_o, fits):
    """Build every cell into its chunk's slab; ``fits[ch]`` tells whether the slab held it."""
    n = sites[1].shape[0]
    per = slab_x.shape[0] // fits.shape[0]
    for ch in prange(fits.shape[0]):
        lo = ch * per
        fits[ch] = _cells(
            ch * _CHUNK,
            min((ch + 1) * _CHUNK, n),
            sites,
            grid,
            box,
            counts,
            where,
            slab_x[lo : lo + per],
            slab_y[lo : lo + per],
            slab_o[lo : lo + per],
        )


@njit(**NJIT_PARALLEL)
def _second_pass(sites, grid, box, counts, offsets, where, slab, fits, coords, owner):
    """Copy every cell to its place in the output; rebuild the chunks that overflowed."""
    sidx = sites[3]
    n = sidx.shape[0]
    slab_x, slab_y, slab_o = slab
    per = slab_x.shape[0] // fits.shape[0]
    for ch in prange(fits.shape[0]):
        k0 = ch * _CHUNK
        k1 = min((ch + 1) * _CHUNK, n)
        lo = ch * per
        xs, ys, os = slab_x[lo : lo + per], slab_y[lo : lo + per], slab_o[lo : lo + per]
        if not fits[ch]:  # rebuild the chunk into buffers of the size now known
            total = 0
            for k in range(k0, k1):
                total += counts[sidx[k]]
            xs = np.zeros(total)
            ys = np.zeros(total)
            os = np.zeros(total, np.int64)
            _cells(k0, k1, sites, grid, box, counts, where, xs, ys, os)
        for k in range(k0, k1):
            i = sidx[k]
            dst = offsets[i]
            src = where[k]
            for t in range(offsets[i + 1] - dst):
                coords[dst + t, 0] = xs[src + t]
                coords[dst + t, 1] = ys[src + t]
                owner[dst + t] = os[src + t]


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
    sites = _bucket_sort(xs, ys, *grid)
    nchunks = (n + _CHUNK - 1) // _CHUNK
    per = _SLAB * min(_CHUNK, n) + 16
    counts = np.zeros(n, np.int64)
    where = np.zeros(n, np.int64)
    slab_x = np.zeros(nchunks * per)
    slab_y = np.zeros(nchunks * per)
    slab_o = np.zeros(nchunks * per, np.int64)
    fits = np.zeros(nchunks, np.bool_)
    _first_pass(sites, grid, boxa, counts, where, slab_x, slab_y, slab_o, fits)
    offsets = np.zeros(n + 1, np.int64)
    np.cumsum(counts, out=offsets[1:])
    k = int(offsets[-1])
    coords = np.empty((k, 2))  # noqa: TID251 - every slot is written by _second_pass
    owner = np.empty(k, np.int32)  # noqa: TID251 - every slot is written by _second_pass
    slab = (slab_x, slab_y, slab_o)
    _second_pass(sites, grid, boxa, counts, offsets, where, slab, fits, coords, owner)
    return coords, offsets, owner
