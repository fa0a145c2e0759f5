"""One bucket grid: sites counting-sorted into uniform buckets, ring search, stop test.

Every kernel that looks for the sites near a point or a rectangle uses this grid: the
half-plane cells (the sites that can cut a cell) and the exact raster (the sites that can
be nearest to a tile of pixels). Three concepts:

The grid
    ``grid = (x0, y0, hx, hy, nx, ny)``: origin, bucket size and bucket count per axis over
    the sites' bounding box (:func:`grid_shape`). Bucket ``(ix, iy)`` is number
    ``iy * nx + ix``; along each axis a coordinate falls in bucket :func:`bucket_of`
    (clamped, so points outside the box use the nearest bucket). :func:`counting_sort`
    gives the CSR layout: the sites of bucket ``b`` are ``order[start[b]:start[b + 1]]``,
    in increasing index (the sort is stable). :func:`adaptive_grid` refines the buckets for
    clustered sites.
Ring search
    Ring ``r`` around bucket ``(ci, cj)`` is the set of buckets at Chebyshev distance ``r``
    from it, clipped to the grid; rings ``0..r`` tile the block of buckets within ``r``.
    Rows ``j`` of ring ``r`` are ``ring_rows``; the columns of row ``j`` are
    ``range(i0, i1 + 1, step)`` with ``(i0, i1, step) = ring_row(...)`` (the whole run on
    the ring's first and last rows, its two ends on the others).
Stop test
    Once the block of rings ``0..r`` is scanned, every unscanned site lies outside it:
    :func:`ring_gap` is a lower bound on the distance from a rectangle inside the block to
    any such site (``inf`` once the block covers the grid), :func:`outside_dist2` the exact
    squared distance from a point to the unscanned part of the grid. A search stops when
    the bound it is looking within (a cell's reach, a tile's k-th nearest) is below them.

In 3D the same three concepts carry over axis by axis: a grid ``(x0, y0, z0, hx, hy, hz,
nx, ny, nz)`` with bucket ``(iz * ny + iy) * nx + ix`` (:func:`bucket_of` and
:func:`counting_sort` are already per axis and per key), shells of buckets at Chebyshev
distance ``r`` instead of rings (their first and last layers whole, the others rings of
2D), and the stop test with one more pair of sides (six slabs around the block instead of
four strips). A tiled scale layer's halo is the same test: the sites of the neighbouring
tiles within the gap of the tile's block.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import GRID_DEGENERATE_RTOL, GRID_WIDEN_RTOL, NJIT


@njit(**NJIT)
def grid_shape(xs, ys, per_bucket):
    """Uniform grid over the sites' bounding box, about ``per_bucket`` sites per bucket.

    Parameters
    ----------
    xs, ys : (n,) float64
        The sites (n >= 1).
    per_bucket : float
        Mean number of sites per bucket wanted.

    Returns
    -------
    grid : tuple
        ``(x0, y0, hx, hy, nx, ny)``: lower-left corner, bucket width and height, bucket
        counts. The grid is a hair wider than the sites, so every site's bucket index is
        below ``nx`` (``ny``) without clamping.
    """
    n = xs.shape[0]
    x0 = xs.min()
    y0 = ys.min()
    w = xs.max() - x0
    h = ys.max() - y0
    span = max(w, h)
    if span == 0.0:
        span = max(abs(x0), abs(y0), 1.0)
    w = max(w, GRID_DEGENERATE_RTOL * span)
    h = max(h, GRID_DEGENERATE_RTOL * span)
    nb = max(1.0, n / per_bucket)
    nx = int(min(max(np.sqrt(nb * w / h), 1.0), nb))
    ny = int(min(max(nb / nx, 1.0), nb))
    hx = w * (1.0 + GRID_WIDEN_RTOL) / nx
    hy = h * (1.0 + GRID_WIDEN_RTOL) / ny
    return x0, y0, hx, hy, nx, ny


@njit(**NJIT)
def bucket_of(v, origin, size, count):
    """Bucket index of coordinate ``v`` along one axis, clamped into ``[0, count)``.

    NaN and values below the grid give 0, values past it ``count - 1``.
    """
    f = (v - origin) / size
    if not f >= 0.0:  # also catches NaN
        return 0
    if f >= count - 1:
        return count - 1
    return int(f)


@njit(**NJIT)
def counting_sort(key, nb):
    """Stable counting sort of ``key (n,)`` with values in ``[0, nb)``.

    Returns ``start (nb + 1,)`` and ``order (n,)``: the items with key ``b`` are
    ``order[start[b]:start[b + 1]]``, in increasing index. Any dimension: the key is the
    flattened bucket number.
    """
    n = key.shape[0]
    start = np.zeros(nb + 1, np.int64)
    for i in range(n):
        start[key[i] + 1] += 1
    for b in range(nb):
        start[b + 1] += start[b]
    fill = start[:-1].copy()
    order = np.zeros(n, np.int64)
    for i in range(n):
        order[fill[key[i]]] = i
        fill[key[i]] += 1
    return start, order


@njit(**NJIT)
def bucket_sort(xs, ys, grid):
    """Sites sorted into the buckets of ``grid``.

    Returns
    -------
    start : (nx * ny + 1,) int64
        The sites of bucket ``b`` are ``start[b]:start[b + 1]`` in the arrays below.
    sx, sy : (n,) float64
        Site coordinates in bucket order.
    sidx : (n,) int64
        Index (into ``xs``) of each sorted site; increasing within a bucket.
    """
    x0, y0, hx, hy, nx, ny = grid
    n = xs.shape[0]
    key = np.zeros(n, np.int64)
    for i in range(n):
        key[i] = bucket_of(ys[i], y0, hy, ny) * nx + bucket_of(xs[i], x0, hx, nx)
    start, sidx = counting_sort(key, nx * ny)
    sx = np.zeros(n)
    sy = np.zeros(n)
    for t in range(n):
        sx[t] = xs[sidx[t]]
        sy[t] = ys[sidx[t]]
    return start, sx, sy, sidx


def adaptive_grid(xs, ys, per_bucket, max_refine):
    """Bucket grid refined for clustered sites, and the sites sorted into it.

    A uniform grid with ``per_bucket`` sites per bucket on average, refined when the sites
    are clustered: if the median site shares its bucket with many more (the dense parts
    hold most sites), the buckets shrink until it shares with about ``per_bucket``, up to
    ``max_refine`` times as many buckets. Sparse regions then scan more (empty) buckets, but
    dense ones no longer test hundreds of sites each.

    Returns
    -------
    grid : tuple
        ``(x0, y0, hx, hy, nx, ny)`` (see :func:`grid_shape`).
    sites : tuple
        ``(start, sx, sy, sidx)`` of :func:`bucket_sort`.
    """
    grid = grid_shape(xs, ys, per_bucket)
    sites = bucket_sort(xs, ys, grid)
    occ = np.diff(sites[0])
    median = float(np.median(np.repeat(occ, occ)))
    if median > 2.0 * per_bucket:
        refine = min(median / per_bucket, max_refine)
        grid = grid_shape(xs, ys, per_bucket / refine)
        sites = bucket_sort(xs, ys, grid)
    return grid, sites


def skip_lists(start, nx, ny):
    """Skip lists over empty buckets, so a ring search passes empty stretches in O(1).

    Returns
    -------
    rownext : (ny + 1,) int64
        ``rownext[j]``: the first row ``>= j`` holding a site (``ny`` when none).
    bnext : (ny * (nx + 1),) int32
        ``bnext[j * (nx + 1) + i]``: the first column ``>= i`` of row ``j`` holding a site
        (``nx`` when none).
    """
    occ = np.diff(start).reshape(ny, nx)
    rows = np.where(occ.sum(1) > 0, np.arange(ny), ny)
    rownext = np.full(ny + 1, ny, dtype=np.int64)
    rownext[:ny] = np.minimum.accumulate(rows[::-1])[::-1]
    cols = np.where(occ > 0, np.arange(nx, dtype=np.int32), np.int32(nx))
    bnext = np.full((ny, nx + 1), nx, dtype=np.int32)
    bnext[:, :nx] = np.minimum.accumulate(cols[:, ::-1], axis=1)[:, ::-1]
    return rownext, bnext.ravel()


@njit(**NJIT)
def ring_rows(cj, r, ny):
    """First and last row (inclusive) of ring ``r`` around row ``cj``, clipped to the grid."""
    return max(cj - r, 0), min(cj + r, ny - 1)


@njit(**NJIT)
def ring_row(ci, cj, r, j, nx):
    """Columns of row ``j`` in ring ``r`` around bucket ``(ci, cj)``: ``(i0, i1, step)``.

    The ring's buckets in that row are ``range(i0, i1 + 1, step)`` (empty when ``i0 > i1``):
    the whole clipped run on the ring's first and last rows, its two ends on the others.
    """
    if j == cj - r or j == cj + r:
        return max(ci - r, 0), min(ci + r, nx - 1), 1
    i0 = ci - r if ci - r >= 0 else ci + r
    i1 = ci + r if ci + r < nx else ci - r
    return i0, i1, 2 * r


@njit(**NJIT)
def ring_gap(rx0, rx1, ry0, ry1, ci, cj, r, grid):
    """Lower bound on the distance from rectangle ``[rx0, rx1] x [ry0, ry1]`` to unscanned sites.

    The scanned buckets are the block of rings ``0..r`` around ``(ci, cj)`` and the rectangle
    lies inside it (a point is a rectangle of no size). Every unscanned site lies beyond one
    of the block's sides that are not on the grid's boundary, so at least this far along
    that axis. ``inf`` when the block covers the grid (nothing left to scan); negative when
    the rectangle reaches past the block.
    """
    x0, y0, hx, hy, nx, ny = grid
    gap = np.inf
    if ci - r > 0:
        gap = min(gap, rx0 - (x0 + (ci - r) * hx))
    if ci + r < nx - 1:
        gap = min(gap, x0 + (ci + r + 1) * hx - rx1)
    if cj - r > 0:
        gap = min(gap, ry0 - (y0 + (cj - r) * hy))
    if cj + r < ny - 1:
        gap = min(gap, y0 + (cj + r + 1) * hy - ry1)
    return gap


@njit(**NJIT)
def rect_dist2(x, y, x0, y0, x1, y1):
    """Squared distance from ``(x, y)`` to the rectangle ``[x0, x1] x [y0, y1]`` (inf if empty)."""
    if x0 >= x1 or y0 >= y1:
        return np.inf
    dx = max(x0 - x, 0.0, x - x1)
    dy = max(y0 - y, 0.0, y - y1)
    return dx * dx + dy * dy


@njit(**NJIT)
def block_box(ci, cj, r, grid):
    """Rectangle ``(bx0, by0, bx1, by1)`` of the block of rings ``0..r``, clipped to the grid."""
    x0, y0, hx, hy, nx, ny = grid
    bx0 = max(x0 + (ci - r) * hx, x0)
    bx1 = min(x0 + (ci + r + 1) * hx, x0 + nx * hx)
    by0 = max(y0 + (cj - r) * hy, y0)
    by1 = min(y0 + (cj + r + 1) * hy, y0 + ny * hy)
    return bx0, by0, bx1, by1


@njit(**NJIT)
def outside_dist2(x, y, block, grid):
    """Squared distance from ``(x, y)`` to the part of the grid outside ``block``.

    ``block`` is :func:`block_box`'s rectangle; the rest of the grid is four strips around
    it (left and right ones full height). ``inf`` when the block covers the grid. The point
    may lie anywhere, inside the grid or not.
    """
    x0, y0, hx, hy, nx, ny = grid
    bx0, by0, bx1, by1 = block
    gx1 = x0 + nx * hx
    gy1 = y0 + ny * hy
    d = rect_dist2(x, y, x0, y0, bx0, gy1)  # left strip
    d = min(d, rect_dist2(x, y, bx1, y0, gx1, gy1))  # right strip
    d = min(d, rect_dist2(x, y, bx0, y0, bx1, by0))  # bottom strip
    return min(d, rect_dist2(x, y, bx0, by1, bx1, gy1))  # top strip


# -- k-d buckets: the grid's adaptive form, for clustered sites ---------------------------
#
# A uniform grid fits uniform sites; three tight clusters in a wide domain put thousands of
# sites in one bucket, and every cell there scans them all. The k-d buckets split the sites
# at the median along the longer side of their box until at most ``leaf`` remain, so each
# bucket holds a few sites at any density. The search around a point visits buckets
# nearest first (a heap keyed by the squared distance to each bucket's tight box), with
# the same stop test as the ring search: a bucket farther than the search's bound, and
# everything after it, is skipped.


@njit(**NJIT)
def _select(key, other, perm, lo, hi, kth):
    """Reorder ``lo:hi`` of ``key``, ``other``, ``perm`` so ``key[kth]`` is its ``kth`` smallest.

    Keys before it are no larger, keys after it no smaller (Hoare's quickselect); the
    three arrays move together. The pivot is the median of three keys a third of the range
    apart from a start that a hash of the range picks: the ends and the middle, the usual
    choice, make it quadratic on a sorted run whose smallest key is last, which the median
    splits of sites on a line produce at every level (7.1 s for 3e5 sites on a line + 1).
    """
    while hi - lo > 1:
        span = hi - lo
        h = (lo * 2654435761 + span * 40503) % span
        a = key[lo + h]
        b = key[lo + (h + span // 3) % span]
        c = key[lo + (h + 2 * (span // 3)) % span]
        pivot = max(min(a, b), min(max(a, b), c))
        i = lo
        j = hi - 1
        while i <= j:
            while key[i] < pivot:
                i += 1
            while key[j] > pivot:
                j -= 1
            if i <= j:
                key[i], key[j] = key[j], key[i]
                other[i], other[j] = other[j], other[i]
                perm[i], perm[j] = perm[j], perm[i]
                i += 1
                j -= 1
        if kth <= j:
            hi = j + 1
        elif kth >= i:
            lo = i
        else:
            return


@njit(**NJIT)
def _tight_box(sx, sy, lo, hi, boxes, node):
    x0 = np.inf
    y0 = np.inf
    x1 = -np.inf
    y1 = -np.inf
    for t in range(lo, hi):
        x0 = min(x0, sx[t])
        x1 = max(x1, sx[t])
        y0 = min(y0, sy[t])
        y1 = max(y1, sy[t])
    boxes[node, 0] = x0
    boxes[node, 1] = y0
    boxes[node, 2] = x1
    boxes[node, 3] = y1


@njit(**NJIT)
def kd_buckets(xs, ys, leaf):
    """Sites split into k-d buckets of at most ``leaf`` sites (``leaf >= 2``).

    Returns
    -------
    tree : tuple
        ``(lo, hi, left, boxes)``: node ``v`` holds the sorted sites ``lo[v]:hi[v]``, its
        children are ``left[v]`` and ``left[v] + 1`` (``left[v] == -1`` for a bucket), and
        ``boxes[v] = (x0, y0, x1, y1)`` is the tight box of its sites. Node 0 is the root.
    sites : tuple
        ``(sx, sy, sidx)``: coordinates in bucket order and the index of each sorted site.
    """
    n = xs.shape[0]
    half = (leaf + 1) // 2
    cap = 2 * (n // half + 1) + 1
    lo = np.zeros(cap, np.int64)
    hi = np.zeros(cap, np.int64)
    left = np.full(cap, -1, np.int64)
    boxes = np.zeros((cap, 4))
    perm = np.arange(n)
    sx = xs.copy()
    sy = ys.copy()
    hi[0] = n
    # np.int64, not literals: numba would compile _tight_box once for each literal
    _tight_box(sx, sy, np.int64(0), n, boxes, np.int64(0))
    stack = np.zeros(128, np.int64)
    top = 1
    count = np.int64(1)
    while top > 0:
        top -= 1
        v = stack[top]
        a = lo[v]
        b = hi[v]
        if b - a <= leaf:
            continue
        mid = (a + b) // 2
        if boxes[v, 2] - boxes[v, 0] >= boxes[v, 3] - boxes[v, 1]:
            _select(sx, sy, perm, a, b, mid)
        else:
            _select(sy, sx, perm, a, b, mid)
        c = count
        count += 2
        left[v] = c
        lo[c] = a
        hi[c] = mid
        lo[c + 1] = mid
        hi[c + 1] = b
        _tight_box(sx, sy, a, mid, boxes, c)
        _tight_box(sx, sy, mid, b, boxes, c + 1)
        stack[top] = c
        stack[top + 1] = c + 1
        top += 2
    return (lo[:count], hi[:count], left[:count], boxes[:count]), (sx, sy, perm)


@njit(**NJIT)
def heap_push(hk, hv, size, key, val):
    """Push ``(key, val)`` on the binary min-heap ``hk[:size], hv[:size]``; returns the size."""
    u = size
    while u > 0:
        p = (u - 1) // 2
        if hk[p] <= key:
            break
        hk[u] = hk[p]
        hv[u] = hv[p]
        u = p
    hk[u] = key
    hv[u] = val
    return size + 1


@njit(**NJIT)
def heap_pop(hk, hv, size):
    """Remove the smallest entry of the heap; returns ``(key, val, new size)``."""
    key = hk[0]
    val = hv[0]
    size -= 1
    lk = hk[size]
    lv = hv[size]
    u = 0
    while True:
        c = 2 * u + 1
        if c >= size:
            break
        if c + 1 < size and hk[c + 1] < hk[c]:
            c += 1
        if hk[c] >= lk:
            break
        hk[u] = hk[c]
        hv[u] = hv[c]
        u = c
    if size > 0:
        hk[u] = lk
        hv[u] = lv
    return key, val, size


@njit(**NJIT)
def box_dist2(x, y, boxes, v):
    """Squared distance from ``(x, y)`` to the closed box ``boxes[v]`` (0 inside; may be flat)."""
    dx = max(boxes[v, 0] - x, 0.0, x - boxes[v, 2])
    dy = max(boxes[v, 1] - y, 0.0, y - boxes[v, 3])
    return dx * dx + dy * dy


# -- oriented slabs of k-d buckets: tight bounds for sites along a sloped line ------------
#
# A k-d bucket's axis-aligned box is loose for sites on a sloped line: the box of a run of
# the line is as wide across it as along it, so the search near a cell of the line (whose
# vertices are far from its site, across the line) cannot clear buckets until they are
# about sqrt(length across / bucket size) buckets away: O(sqrt n) buckets per cell. Each
# node also keeps the range of its sites along and across its principal direction: a
# rectangle that is flat for sites on a line at any slope.


@njit(**NJIT)
def kd_slabs(tree, sx, sy):
    """Oriented bounds of every k-d node: ``(n_nodes, 7)`` rows ``(ux, uy, a0, a1, b0, b1, 0)``.

    ``(ux, uy)`` is the unit principal direction of the node's sites; a site ``(x, y)``
    projects to ``a = (x - x0) * ux + (y - y0) * uy`` and ``b = (y - y0) * ux - (x - x0) *
    uy`` about the node's box corner ``(x0, y0)`` (``tree``'s boxes), and every site's
    projections lie in ``[a0, a1] x [b0, b1]`` (widened by their rounding).
    """
    lo, hi, left, boxes = tree
    cnt = lo.shape[0]
    out = np.zeros((cnt, 7))
    eps = 2.0**-50
    for v in range(cnt):
        x0 = boxes[v, 0]
        y0 = boxes[v, 1]
        k = hi[v] - lo[v]
        mx = 0.0
        my = 0.0
        for t in range(lo[v], hi[v]):
            mx += sx[t] - x0
            my += sy[t] - y0
        mx /= k
        my /= k
        cxx = 0.0
        cyy = 0.0
        cxy = 0.0
        for t in range(lo[v], hi[v]):
            dx = sx[t] - x0 - mx
            dy = sy[t] - y0 - my
            cxx += dx * dx
            cyy += dy * dy
            cxy += dx * dy
        ang = 0.5 * np.arctan2(2.0 * cxy, cxx - cyy)
        ux = np.cos(ang)
        uy = np.sin(ang)
        a0 = np.inf
        a1 = -np.inf
        b0 = np.inf
        b1 = -np.inf
        big = 0.0
        for t in range(lo[v], hi[v]):
            px = sx[t] - x0
            py = sy[t] - y0
            a = px * ux + py * uy
            b = py * ux - px * uy
            a0 = min(a0, a)
            a1 = max(a1, a)
            b0 = min(b0, b)
            b1 = max(b1, b)
            big = max(big, abs(px) + abs(py))
        pad = eps * big  # the projections' rounding (the subtraction's is within it)
        out[v, 0] = ux
        out[v, 1] = uy
        out[v, 2] = a0 - pad
        out[v, 3] = a1 + pad
        out[v, 4] = b0 - pad
        out[v, 5] = b1 + pad
    return out


@njit(**NJIT)
def slab_dist2(x, y, boxes, slabs, v):
    """A lower bound on the squared distance from ``(x, y)`` to the sites of k-d node ``v``.

    The larger of :func:`box_dist2` and the distance to the node's oriented rectangle
    (:func:`kd_slabs`), the latter less its rounding (a few ulps of the point's offset).
    """
    d2 = box_dist2(x, y, boxes, v)
    px = x - boxes[v, 0]
    py = y - boxes[v, 1]
    ux = slabs[v, 0]
    uy = slabs[v, 1]
    a = px * ux + py * uy
    b = py * ux - px * uy
    da = max(slabs[v, 2] - a, 0.0, a - slabs[v, 3])
    db = max(slabs[v, 4] - b, 0.0, b - slabs[v, 5])
    d = np.sqrt(da * da + db * db) - 2.0**-48 * (abs(px) + abs(py))
    if d > 0.0:
        d2 = max(d2, d * d)
    return d2
