"""Raster Voronoi kernels: exact nearest site per pixel, and Jump Flooding.

Sites arrive deduplicated (``xs, ys`` are first occurrences, in increasing input order), so
"lowest position" equals "lowest input index" and every other site is a distinct one. Pixel
centres arrive as ``pxs (w,)`` and ``pys (h,)``; the kernels never recompute them, so the
engine, the kernels and any reference agree bit for bit.

Metric codes: 0 Euclidean, 1 Manhattan, 2 Chebyshev. Comparisons use a *key* (squared
distance for Euclidean, the distance itself otherwise) computed as a brute-force ``argmin``
over all sites would compute it; where the two smallest keys of a pixel lie within their
rounding of each other, the sites in that band are compared exactly
(:mod:`.distance_exact`), so a label is the exactly nearest site of the float pixel centre
(exact ties to the lowest position) and distances are the float keys' roots.

Exact method
    The bucket grid of :mod:`.grid` over the sites; the image is cut into tiles. For a tile
    (the rectangle of its pixel centres) ``u`` is the k-th smallest *largest* distance from a
    site to the rectangle (k = 1, or 2 with F2), found by ring search with the grid's stop
    test. Every pixel's nearest (and second nearest) site lies within ``u`` of the pixel, so
    only sites whose *smallest* distance to the rectangle is <= ``u`` can win. Those
    candidates are collected from the grid and each pixel is brute-forced over them. Tiles
    with too many candidates (e.g. far from a dense cluster) are split in four.
    :func:`nearest_tiles` may also be given a bound per pixel (below: the flood's distances);
    a tile's bound is then its largest, and the ring search runs only where that leaves too
    many candidates.
Delaunay walk (Euclidean, nearest only; the engine picks it where sites crowd)
    Each pixel walks the Delaunay graph to a site no neighbour of which is nearer, and a
    rectangle whose four corners prove one unique nearest site is filled (see the section
    below): about linear in the pixels however the sites lie, where the tile search above
    scans every empty bucket within a pixel's nearest distance (inside a circle of sites:
    the whole grid, for every small tile).
Jump Flooding
    Rong & Tan (2006): seed each site's pixel, then passes with the steps given by the
    caller (N/2, ..., 1); each pixel keeps the best of the sites held by its 9 neighbours at
    the current step, measured to the real site position. The flood loses sites where they
    crowd: one pixel holds one site, and a cell thinner than a pixel breaks the chain of
    jumps that would carry its site (sites along a circle: 16% of the labels wrong at 41
    pixels per site). Its distances are to real sites, so they bound each pixel's nearest
    (and, with two layers, second nearest) distance: the engine passes them to
    :func:`nearest_tiles`, which makes the result exact.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit, prange

from ..config import NJIT, NJIT_PARALLEL, RASTER_BOUND_RTOL, RASTER_SLACK_FLOOR, RASTER_SLACK_RTOL
from .distance_exact import BAND_REL, BAND_TINY, settle
from .distance_exact import float_key as _key
from .grid import bucket_of, bucket_sort, grid_shape, ring_gap, ring_row, ring_rows

_BIG = 1 << 62
_PER_BUCKET = 2.0  # mean sites per bucket of the exact method's grid


@njit(**NJIT)
def _key_to_distance(key, metric):
    """Distance from a comparison key."""
    if metric == 0:
        return math.sqrt(key)
    return key


@njit(**NJIT)
def _rect_distances(sx, sy, tx0, tx1, ty0, ty1, metric):
    """Smallest and largest distance from site ``(sx, sy)`` to the rectangle."""
    ax = max(tx0 - sx, sx - tx1, 0.0)
    ay = max(ty0 - sy, sy - ty1, 0.0)
    bx = max(abs(sx - tx0), abs(sx - tx1))
    by = max(abs(sy - ty0), abs(sy - ty1))
    if metric == 0:
        return math.sqrt(ax * ax + ay * ay), math.sqrt(bx * bx + by * by)
    if metric == 1:
        return ax + ay, bx + by
    return max(ax, ay), max(bx, by)


@njit(**NJIT)
def _upper_bound(rect, k, grid, start, gx, gy, metric):
    """k-th smallest (k = 1 or 2) largest-distance from a site to ``rect``; inf if < k sites.

    Any value returned is a valid bound (it is some site's largest distance); the ring search
    only makes it small, and stops once the unscanned sites lie farther than it
    (:func:`.grid.ring_gap`).
    """
    tx0, tx1, ty0, ty1 = rect[0], rect[1], rect[2], rect[3]
    x0, y0, cw, ch, nx, ny = grid
    ci = bucket_of(0.5 * (tx0 + tx1), x0, cw, nx)
    cj = bucket_of(0.5 * (ty0 + ty1), y0, ch, ny)
    u1 = np.inf
    u2 = np.inf
    ring = np.int64(0)  # not a literal: numba would compile the ring helpers once more
    while True:
        j0, j1 = ring_rows(cj, ring, ny)
        for j in range(j0, j1 + 1):
            i0, i1, step = ring_row(ci, cj, ring, j, nx)
            for i in range(i0, i1 + 1, step):
                b = j * nx + i
                for s in range(start[b], start[b + 1]):
                    far = _rect_distances(gx[s], gy[s], tx0, tx1, ty0, ty1, metric)[1]
                    if far < u1:
                        u2 = u1
                        u1 = far
                    elif far < u2:
                        u2 = far
        uk = u1 if k == 1 else u2
        # sites not yet visited lie outside the block of rings searched so far
        lb = ring_gap(tx0, tx1, ty0, ty1, ci, cj, ring, grid)
        if lb == np.inf or lb > uk:
            return uk
        ring += 1


@njit(**NJIT)
def _collect(rect, u, grid, start, gx, gy, gi, metric, cx, cy, cid):
    """Sites whose smallest distance to ``rect`` is <= ``u``; fills at most ``len(cx)``.

    Returns the total count (which may exceed the buffers' length).
    """
    tx0, tx1, ty0, ty1 = rect[0], rect[1], rect[2], rect[3]
    x0, y0, cw, ch, nx, ny = grid
    if math.isfinite(u):
        i0 = max(bucket_of(tx0 - u, x0, cw, nx) - 1, 0)
        i1 = min(bucket_of(tx1 + u, x0, cw, nx) + 1, nx - 1)
        j0 = max(bucket_of(ty0 - u, y0, ch, ny) - 1, 0)
        j1 = min(bucket_of(ty1 + u, y0, ch, ny) + 1, ny - 1)
    else:
        i0, i1, j0, j1 = 0, nx - 1, 0, ny - 1
    cap = cx.shape[0]
    count = 0
    for j in range(j0, j1 + 1):
        for i in range(i0, i1 + 1):
            b = j * nx + i
            for s in range(start[b], start[b + 1]):
                near = _rect_distances(gx[s], gy[s], tx0, tx1, ty0, ty1, metric)[0]
                if near <= u:
                    if count < cap:
                        cx[count] = gx[s]
                        cy[count] = gy[s]
                        cid[count] = gi[s]
                    count += 1
    return count


@njit(**NJIT)
def _grown(count, rect, u, grid, start, gx, gy, gi, metric, cx, cy, cid):
    """The candidate buffers, collected again into bigger ones when ``count`` overflowed them."""
    if count <= cx.shape[0]:
        return cx, cy, cid
    cx = np.zeros(count)
    cy = np.zeros(count)
    cid = np.zeros(count, dtype=np.int64)
    _collect(rect, u, grid, start, gx, gy, gi, metric, cx, cy, cid)
    return cx, cy, cid


@njit(**NJIT)
def _settle_pixel(r, c, px, py, cx, cy, cid, count, metric, b1, want_f2, lab, d1, d2):
    """Pixel ``(r, c)`` whose smallest keys tie to rounding: decided exactly (:func:`settle`)."""
    t, k1, k2 = settle(px, py, cx, cy, cid, count, metric, b1)
    lab[r, c] = cid[t]
    d1[r, c] = _key_to_distance(k1, metric)
    if want_f2:
        d2[r, c] = _key_to_distance(k2, metric)


@njit(**NJIT)
def _brute_tile(r0, r1, c0, c1, pxs, pys, cx, cy, cid, count, metric, want_f2, lab, d1, d2):
    """Nearest (and second nearest) candidate of every pixel of a tile; ties -> lowest id.

    Where the two smallest float keys lie within their rounding of each other (a float tie
    included) the candidates in that band are compared exactly (:mod:`.distance_exact`), so
    the label is the exactly nearest site of the pixel centre, exact ties to the lowest id.
    """
    for r in range(r0, r1):
        py = pys[r]
        for c in range(c0, c1):
            px = pxs[c]
            b1 = np.inf
            b2 = np.inf
            i1 = _BIG
            for t in range(count):
                key = _key(px - cx[t], py - cy[t], metric)
                if key < b1 or (key == b1 and cid[t] < i1):
                    b2 = b1
                    b1 = key
                    i1 = cid[t]
                elif key < b2:
                    b2 = key
            if b2 <= b1 * (1.0 + BAND_REL) + BAND_TINY and b1 < np.inf:
                _settle_pixel(r, c, px, py, cx, cy, cid, count, metric, b1, want_f2, lab, d1, d2)
                continue
            lab[r, c] = i1
            d1[r, c] = _key_to_distance(b1, metric)
            if want_f2:
                d2[r, c] = _key_to_distance(b2, metric)


@njit(**NJIT)
def _split(stack, top, r0, r1, c0, c1):
    """Push the (up to) four quarters of rows ``r0:r1``, columns ``c0:c1``; the new top."""
    rm = (r0 + r1 + 1) // 2 if r1 - r0 > 1 else r1
    cm = (c0 + c1 + 1) // 2 if c1 - c0 > 1 else c1
    for ra, rb in ((r0, rm), (rm, r1)):
        for ca, cb in ((c0, cm), (cm, c1)):
            if ra < rb and ca < cb:
                stack[top, 0] = ra
                stack[top, 1] = rb
                stack[top, 2] = ca
                stack[top, 3] = cb
                top += 1
    return top


@njit(**NJIT)
def _tile_bound(bound, r0, r1, c0, c1):
    """Largest of ``bound`` over rows ``r0:r1``, columns ``c0:c1`` (inf if any is not finite)."""
    u = 0.0
    for r in range(r0, r1):
        for c in range(c0, c1):
            v = bound[r, c]
            if not v <= u:  # also takes a nan, which then fails the finiteness test below
                u = v
    return u if math.isfinite(u) else np.inf


@njit(**NJIT_PARALLEL)
def nearest_tiles(xs, ys, pxs, pys, metric, want_f2, tile, max_cand, bound):
    """Exact nearest site of every pixel centre, tile by tile.

    Parameters
    ----------
    xs, ys : (m,) float64
        Distinct sites, in increasing input order (m >= 1).
    pxs : (w,) float64
        Pixel-centre x of each column (increasing).
    pys : (h,) float64
        Pixel-centre y of each row (decreasing: row 0 at the top).
    metric : int
        0 Euclidean, 1 Manhattan, 2 Chebyshev.
    want_f2 : bool
        Also compute the distance to the second nearest site.
    tile : (2,) int64
        Initial tile size ``(rows, cols)`` in pixels.
    max_cand : int
        Tiles with more candidates than this are split (down to single pixels).
    bound : (h, w) float64, or (0, 0)
        Optional upper bound, per pixel, on the distance to its nearest site (second
        nearest with ``want_f2``), e.g. the distance to any site (two distinct sites) found
        for it. A tile's bound is then its largest value, and the ring search runs only
        where that is not finite or leaves too many candidates. Any valid bound gives the
        same result; a tight one only makes it faster.

    Returns
    -------
    lab : (h, w) int32
        Position (into ``xs``) of the nearest site.
    d1 : (h, w) float64
        Distance to it.
    d2 : (h, w) float64, or (0, 0) when ``want_f2`` is false
        Distance to the second nearest site (inf when m == 1).
    """
    h = pys.shape[0]
    w = pxs.shape[0]
    m = xs.shape[0]
    lab = np.zeros((h, w), dtype=np.int32)
    d1 = np.zeros((h, w))
    d2 = np.zeros((h, w)) if want_f2 else np.zeros((0, 0))
    grid = grid_shape(xs, ys, _PER_BUCKET)
    start, gx, gy, gi = bucket_sort(xs, ys, grid)
    scale = max(abs(pxs[0]), abs(pxs[-1]), abs(pys[0]), abs(pys[-1]))
    scale = max(scale, np.abs(xs).max(), np.abs(ys).max())
    slack = RASTER_SLACK_RTOL * scale + RASTER_SLACK_FLOOR  # rounding in the test
    k = 2 if want_f2 else 1
    th, tw = tile[0], tile[1]
    ntr = (h + th - 1) // th
    ntc = (w + tw - 1) // tw
    cap0 = min(m, max(4 * max_cand, 64))
    given = bound.shape[0] > 0
    for tr in prange(ntr):
        cx = np.zeros(cap0)
        cy = np.zeros(cap0)
        cid = np.zeros(cap0, dtype=np.int64)
        stack = np.zeros((256, 4), dtype=np.int64)
        rect = np.zeros(4)
        for tc in range(ntc):
            stack[0, 0] = tr * th
            stack[0, 1] = min(h, (tr + 1) * th)
            stack[0, 2] = tc * tw
            stack[0, 3] = min(w, (tc + 1) * tw)
            top = 1
            while top > 0:
                top -= 1
                r0, r1, c0, c1 = stack[top, 0], stack[top, 1], stack[top, 2], stack[top, 3]
                rect[0] = pxs[c0]
                rect[1] = pxs[c1 - 1]
                rect[2] = pys[r1 - 1]
                rect[3] = pys[r0]
                u = _tile_bound(bound, r0, r1, c0, c1) if given else np.inf
                searched = u == np.inf
                if searched:
                    u = _upper_bound(rect, k, grid, start, gx, gy, metric)
                u = u * (1.0 + RASTER_BOUND_RTOL) + slack
                count = _collect(rect, u, grid, start, gx, gy, gi, metric, cx, cy, cid)
                if count > max_cand and not searched:  # the ring search may do better
                    ur = _upper_bound(rect, k, grid, start, gx, gy, metric)
                    ur = ur * (1.0 + RASTER_BOUND_RTOL) + slack
                    if ur < u:
                        u = ur
                        count = _collect(rect, u, grid, start, gx, gy, gi, metric, cx, cy, cid)
                splittable = r1 - r0 > 1 or c1 - c0 > 1
                if count > max_cand and splittable and top + 4 <= stack.shape[0]:
                    top = _split(stack, top, r0, r1, c0, c1)
                    continue
                # (not an `if` here: numba's parallel loops lose arrays reassigned in a
                # branch, so the brute force saw only the first buffer's candidates)
                cx, cy, cid = _grown(count, rect, u, grid, start, gx, gy, gi, metric, cx, cy, cid)
                _brute_tile(
                    r0, r1, c0, c1, pxs, pys, cx, cy, cid, count, metric, want_f2, lab, d1, d2
                )
    return lab, d1, d2


@njit(**NJIT)
def exact_nearest(xs, ys, pxs, pys, metric, want_f2, tile, max_cand):
    """Exact nearest site of every pixel centre: :func:`nearest_tiles` with no bound."""
    return nearest_tiles(xs, ys, pxs, pys, metric, want_f2, tile, max_cand, np.zeros((0, 0)))


# ---------------------------------------------------------------------------------------
# Delaunay walk (Euclidean nearest site only)
# ---------------------------------------------------------------------------------------
#
# A site ``s`` is a pixel's nearest exactly when no Delaunay neighbour of ``s`` is nearer
# (its cell is the intersection of the half-planes of its neighbours), so a greedy walk on
# the triangulation finds it with a few distance evaluations, however the sites crowd (the
# tile search above scans every bucket within the nearest distance: inside a circle of
# sites that is the whole grid for every pixel). For a point ``q`` strictly inside the cell
# of ``s`` the second nearest site is also a neighbour of ``s``. ``f_t(q) = |q - t|^2 -
# |q - s|^2`` is affine in ``q``, so its minimum over a rectangle of pixel centres is at a
# corner: when the four corners walk to the same ``s`` and every neighbour's margin there
# exceeds the keys' rounding, every pixel of the rectangle has ``s`` as its unique nearest
# site (exactly, and in the floats a brute-force argmin computes), and is filled without evaluating
# anything but its own distance. Rectangles that fail are split; single pixels that fail
# (a true tie, or one within rounding) are brute-forced over the sites within their bound.


@njit(**NJIT)
def _walk(px, py, xs, ys, nptr, nidx, s):
    """Greedy walk from site ``s`` to one no Delaunay neighbour of which has a smaller key.

    Returns the site, its key and the margin ``k_t (1 - r) - k_s (1 + r)`` of its nearest
    neighbour ``t`` (inf without neighbours, -inf on nan): a lower bound on the exact
    ``|q - t|^2 - |q - s|^2`` over all neighbours (``r`` covers the keys' rounding).
    """
    ks = _key(px - xs[s], py - ys[s], 0)
    while True:
        best = s
        bk = ks
        kt = np.inf
        for e in range(nptr[s], nptr[s + 1]):
            t = nidx[e]
            k = _key(px - xs[t], py - ys[t], 0)
            if k < kt:
                kt = k
            if k < bk:
                bk = k
                best = t
        if best == s:
            margin = kt * (1.0 - BAND_REL) - ks * (1.0 + BAND_REL)
            if margin != margin:
                margin = -np.inf
            return s, ks, margin
        s = best
        ks = bk


@njit(**NJIT)
def _safe(margin, key):
    """Whether ``margin`` (from :func:`_walk`) proves a unique nearest at keys up to ``key``."""
    return margin > 2.0 * BAND_REL * key + BAND_TINY


@njit(**NJIT_PARALLEL)
def walk_tiles(xs, ys, pxs, pys, nptr, nidx, tile, hint):
    """Nearest site (Euclidean) of every pixel centre by walking the Delaunay graph.

    Parameters
    ----------
    xs, ys : (m,) float64
        Distinct sites, in increasing input order (m >= 1).
    pxs, pys : (w,), (h,) float64
        Pixel centres (columns increasing, rows top to bottom).
    nptr, nidx : CSR int64 / int32
        Delaunay neighbours of each site (for collinear sites: the previous and next site
        along the line).
    tile : (2,) int64
        Initial tile size ``(rows, cols)``.
    hint : (h, w) int32, or (0, 0)
        Optional site to start each pixel's walk from (e.g. a flood's labels; values
        ``>= m`` are ignored).

    Returns
    -------
    lab : (h, w) int32
        Position of the nearest site where ``hard`` is false.
    d1 : (h, w) float64
        Distance to it, computed as a brute-force argmin computes it.
    hard : (h, w) bool
        Pixels whose nearest site is tied or within rounding of a tie: not decided here
        (:func:`fix_pixels` decides them).
    """
    h = pys.shape[0]
    w = pxs.shape[0]
    m = xs.shape[0]
    lab = np.zeros((h, w), dtype=np.int32)
    d1 = np.zeros((h, w))
    hard = np.zeros((h, w), dtype=np.bool_)
    th, tw = tile[0], tile[1]
    ntr = (h + th - 1) // th
    ntc = (w + tw - 1) // tw
    given = hint.shape[0] > 0
    for tr in prange(ntr):
        stack = np.zeros((256, 4), dtype=np.int64)
        cur = 0
        for tc in range(ntc):
            stack[0, 0] = tr * th
            stack[0, 1] = min(h, (tr + 1) * th)
            stack[0, 2] = tc * tw
            stack[0, 3] = min(w, (tc + 1) * tw)
            top = 1
            while top > 0:
                top -= 1
                r0, r1, c0, c1 = stack[top, 0], stack[top, 1], stack[top, 2], stack[top, 3]
                if (r1 - r0) * (c1 - c0) <= 16 or top + 4 > stack.shape[0]:
                    for r in range(r0, r1):
                        for c in range(c0, c1):
                            st = cur
                            if given and hint[r, c] < m:
                                st = hint[r, c]
                            s, ks, mg = _walk(pxs[c], pys[r], xs, ys, nptr, nidx, st)
                            cur = s
                            lab[r, c] = s
                            d1[r, c] = math.sqrt(ks)
                            if not _safe(mg, ks):
                                hard[r, c] = True
                    continue
                same = True
                s0 = -1
                kmax = 0.0
                mgmin = np.inf
                for corner in range(4):
                    r = r0 if corner < 2 else r1 - 1
                    c = c0 if corner % 2 == 0 else c1 - 1
                    st = cur
                    if given and hint[r, c] < m:
                        st = hint[r, c]
                    s, ks, mg = _walk(pxs[c], pys[r], xs, ys, nptr, nidx, st)
                    cur = s
                    if s0 < 0:
                        s0 = s
                    elif s != s0:
                        same = False
                        break
                    if not ks <= kmax:
                        kmax = ks
                    if not mg >= mgmin:
                        mgmin = mg
                if same and _safe(mgmin, kmax):
                    sx = xs[s0]
                    sy = ys[s0]
                    for r in range(r0, r1):
                        py = pys[r]
                        for c in range(c0, c1):
                            lab[r, c] = s0
                            d1[r, c] = math.sqrt(_key(pxs[c] - sx, py - sy, 0))
                    continue
                top = _split(stack, top, r0, r1, c0, c1)
    return lab, d1, hard


@njit(**NJIT_PARALLEL)
def fix_pixels(xs, ys, pxs, pys, rows, cols, lab, d1):
    """Brute-force pixels ``(rows[k], cols[k])`` over the sites within their ``d1``.

    ``d1`` holds the distance to some site for each of them (the walk's), a bound on the
    nearest distance; ``lab`` and ``d1`` are overwritten there with the exact answer (ties
    to the lowest position), as :func:`nearest_tiles` computes it.
    """
    m = xs.shape[0]
    grid = grid_shape(xs, ys, _PER_BUCKET)
    start, gx, gy, gi = bucket_sort(xs, ys, grid)
    scale = max(abs(pxs[0]), abs(pxs[-1]), abs(pys[0]), abs(pys[-1]))
    scale = max(scale, np.abs(xs).max(), np.abs(ys).max())
    slack = RASTER_SLACK_RTOL * scale + RASTER_SLACK_FLOOR
    d2 = np.zeros((0, 0))
    for k in prange(rows.shape[0]):
        r = rows[k]
        c = cols[k]
        rect = np.array([pxs[c], pxs[c], pys[r], pys[r]])
        u = d1[r, c] * (1.0 + RASTER_BOUND_RTOL) + slack
        if not math.isfinite(u):
            u = np.inf
        cap = min(m, 64)
        cx = np.zeros(cap)
        cy = np.zeros(cap)
        cid = np.zeros(cap, dtype=np.int64)
        count = _collect(rect, u, grid, start, gx, gy, gi, 0, cx, cy, cid)
        cx, cy, cid = _grown(count, rect, u, grid, start, gx, gy, gi, 0, cx, cy, cid)
        _brute_tile(r, r + 1, c, c + 1, pxs, pys, cx, cy, cid, count, 0, False, lab, d1, d2)


# ---------------------------------------------------------------------------------------
# Jump Flooding
# ---------------------------------------------------------------------------------------
#
# Labels hold site positions; position ``m`` (one past the last site) means "no site yet" and
# the coordinate arrays carry an extra ``+inf`` entry for it, so its distance is inf and the
# flooding passes need no branch for empty pixels.


_SEED_REACH = 3  # pixels around its own a site that lost its pixel may be seeded at


@njit(**NJIT)
def _seed_index(v, origin, size, count):
    """Pixel index along one axis holding coordinate ``v`` (clamped to the image)."""
    f = (v - origin) / size
    if not f >= 0.0:
        return 0
    if f >= count:
        return count - 1
    return int(f)


@njit(**NJIT)
def _d2(px, py, xs, ys, lab):
    """Squared distance from ``(px, py)`` to site ``lab``."""
    dx = px - xs[lab]
    dy = py - ys[lab]
    return dx * dx + dy * dy


@njit(**NJIT)
def _jfa_seed(xs, ys, pxs, pys, geom, second):
    """Seed each site at the pixel containing it (sites outside: nearest border pixel).

    ``geom`` is ``(xmin, ymax, pixel_width, pixel_height)``; ``xs, ys`` end with the
    sentinel. When two sites share a pixel the nearer to its centre wins (ties: lower
    position); with ``second`` the runner-up is kept in the second layer. A site that lost
    its pixel is seeded at the free pixel nearest to it within ``_SEED_REACH`` pixels:
    labels carry the site, not the pixel, so a seed one pixel off is as good, and dense
    sites (a few dozen pixels each) no longer lose whole cells to a neighbour.
    """
    h = pys.shape[0]
    w = pxs.shape[0]
    m = xs.shape[0] - 1
    a1 = np.full((h, w), m, dtype=np.int32)
    a2 = np.full((h, w) if second else (0, 0), m, dtype=np.int32)
    lost = np.zeros(m, dtype=np.int64)
    nl = 0
    for s in range(m):
        c = _seed_index(xs[s], geom[0], geom[2], w)
        r = _seed_index(geom[1] - ys[s], 0.0, geom[3], h)
        d = _d2(pxs[c], pys[r], xs, ys, s)
        old = a1[r, c]
        if d < _d2(pxs[c], pys[r], xs, ys, old):
            a1[r, c] = s
            if old < m:
                lost[nl] = old
                nl += 1
            if second:
                a2[r, c] = old
        else:
            lost[nl] = s
            nl += 1
            if second and d < _d2(pxs[c], pys[r], xs, ys, a2[r, c]):
                a2[r, c] = s
    for k in range(nl):
        s = lost[k]
        c0 = _seed_index(xs[s], geom[0], geom[2], w)
        r0 = _seed_index(geom[1] - ys[s], 0.0, geom[3], h)
        best = -1
        bd = np.inf
        for r in range(max(r0 - _SEED_REACH, 0), min(r0 + _SEED_REACH + 1, h)):
            for c in range(max(c0 - _SEED_REACH, 0), min(c0 + _SEED_REACH + 1, w)):
                if a1[r, c] == m:
                    d = _d2(pxs[c], pys[r], xs, ys, s)
                    if d < bd:
                        bd = d
                        best = r * w + c
        if best >= 0:
            a1[best // w, best % w] = s
    return a1, a2


@njit(**NJIT)
def _take(lab, px, py, xs, ys, best, bd):
    """The better of ``(bd, best)`` and site ``lab`` (ties: lower position)."""
    if lab == best:  # the common case once cells have formed: no distance to compute
        return best, bd
    d = _d2(px, py, xs, ys, lab)
    if d < bd or (d == bd and lab < best):
        return lab, d
    return best, bd


@njit(**NJIT_PARALLEL)
def _jfa_pass(src, dst, xs, ys, pxs, pys, step):
    """One flooding pass: each pixel takes the nearest of its 9 neighbours' sites.

    Neighbours outside the image are replaced by the pixel itself (a no-op candidate), which
    keeps the inner loop free of bounds tests.
    """
    h, w = src.shape
    for row in prange(h):
        r = np.int64(row)
        py = pys[r]
        ru = r - step
        if ru < 0:
            ru = r
        rd = r + step
        if rd >= h:
            rd = r
        for c in range(w):
            px = pxs[c]
            cl = c - step
            if cl < 0:
                cl = c
            cr = c + step
            if cr >= w:
                cr = c
            best = src[r, c]
            bd = _d2(px, py, xs, ys, best)
            best, bd = _take(src[ru, cl], px, py, xs, ys, best, bd)
            best, bd = _take(src[ru, c], px, py, xs, ys, best, bd)
            best, bd = _take(src[ru, cr], px, py, xs, ys, best, bd)
            best, bd = _take(src[r, cl], px, py, xs, ys, best, bd)
            best, bd = _take(src[r, cr], px, py, xs, ys, best, bd)
            best, bd = _take(src[rd, cl], px, py, xs, ys, best, bd)
            best, bd = _take(src[rd, c], px, py, xs, ys, best, bd)
            best, bd = _take(src[rd, cr], px, py, xs, ys, best, bd)
            dst[r, c] = best


@njit(**NJIT_PARALLEL)
def _jfa2_pass(s1, s2, t1, t2, xs, ys, pxs, pys, step):
    """Flooding pass keeping the two nearest distinct sites per pixel (18 candidates).

    Candidates are both layers of the 9 pixels at offsets ``{-step, 0, step}``; as in
    :func:`_jfa_pass`, neighbours outside the image are replaced by the pixel itself. The
    result, the two smallest ``(distance, position)`` among the distinct sites offered, does
    not depend on the order of the offers. (Written as a loop rather than unrolled: the
    unrolled form took numba 15 s to compile.)
    """
    h, w = s1.shape
    m = xs.shape[0] - 1
    for row in prange(h):
        r = np.int64(row)
        py = pys[r]
        ru = r - step if r >= step else r
        rd = r + step if r + step < h else r
        rows = (ru, r, rd)
        for c in range(w):
            px = pxs[c]
            cols = (c - step if c >= step else c, c, c + step if c + step < w else c)
            l1 = np.int64(s1[r, c])
            e1 = _d2(px, py, xs, ys, l1)
            l2 = np.int64(m)
            e2 = np.inf
            for k in range(9):
                rr = rows[k // 3]
                cc = cols[k % 3]
                for layer in range(2):
                    lab = np.int64(s1[rr, cc]) if layer == 0 else np.int64(s2[rr, cc])
                    if lab == l1 or lab == l2:
                        continue
                    d = _d2(px, py, xs, ys, lab)
                    if d < e1 or (d == e1 and lab < l1):
                        l2 = l1
                        e2 = e1
                        l1 = lab
                        e1 = d
                    elif d < e2 or (d == e2 and lab < l2):
                        l2 = lab
                        e2 = d
            t1[r, c] = l1
            t2[r, c] = l2


@njit(**NJIT_PARALLEL)
def _jfa_distances(a, xs, ys, pxs, pys, out):
    """Euclidean distance from each pixel centre to the site it holds (inf if none)."""
    h, w = a.shape
    for r in prange(h):
        py = pys[r]
        for c in range(w):
            out[r, c] = math.sqrt(_d2(pxs[c], py, xs, ys, a[r, c]))


@njit(**NJIT)
def jfa_nearest(xs, ys, pxs, pys, geom, steps, want_f2):
    """Approximate nearest (and second nearest) site per pixel by Jump Flooding.

    Not exact where sites crowd (see the module docstring): a bound for
    :func:`nearest_tiles`, not a result.

    Parameters
    ----------
    xs, ys : (m,) float64
        Distinct sites, in increasing input order (m >= 1).
    pxs, pys : (w,), (h,) float64
        Pixel centres (columns increasing, rows top to bottom).
    geom : (4,) float64
        ``xmin, ymax, pixel_width, pixel_height``.
    steps : (p,) int64
        Step of each pass, e.g. ``N/2, ..., 2, 1, 2, 1`` (JFA+2).
    want_f2 : bool
        Keep the two nearest sites per pixel (about twice the work).

    Returns
    -------
    lab : (h, w) int32
        Position of the site found for each pixel (``m`` if none was found).
    d1 : (h, w) float64
        Euclidean distance to it (inf if none).
    d2 : (h, w) float64, or (0, 0) when ``want_f2`` is false
        Distance to the second site found (inf if none).
    """
    h = pys.shape[0]
    w = pxs.shape[0]
    m = xs.shape[0]
    sx = np.full(m + 1, np.inf)
    sy = np.full(m + 1, np.inf)
    sx[:m] = xs
    sy[:m] = ys
    a1, a2 = _jfa_seed(sx, sy, pxs, pys, geom, want_f2)
    b1 = np.full((h, w), m, dtype=np.int32)
    b2 = np.full((h, w) if want_f2 else (0, 0), m, dtype=np.int32)
    for p in range(steps.shape[0]):
        if want_f2:
            _jfa2_pass(a1, a2, b1, b2, sx, sy, pxs, pys, steps[p])
            a2, b2 = b2, a2
        else:
            _jfa_pass(a1, b1, sx, sy, pxs, pys, steps[p])
        a1, b1 = b1, a1
    d1 = np.zeros((h, w))
    _jfa_distances(a1, sx, sy, pxs, pys, d1)
    d2 = np.zeros((0, 0))
    if want_f2:
        d2 = np.zeros((h, w))
        _jfa_distances(a2, sx, sy, pxs, pys, d2)
    return a1, d1, d2
