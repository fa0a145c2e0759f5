"""Voronoi cells by cutting: each cell is the box cut by the bisectors of nearby sites.

This is the voro++ design in two dimensions. Every cell is built on its own, so cells are
computed in parallel and the same structure carries over to 3D (a polyhedron instead of a
polygon, the same grid, search and exact finishing):

1. The sites are counting-sorted into the bucket grid of :mod:`.grid` (about
   ``_PER_BUCKET`` sites per bucket, refined for clustered sites).
2. A cell starts as the box, in coordinates relative to its site (so 500000/4000000-style
   inputs keep their precision). Buckets are visited ring by ring around the site's bucket
   (:func:`.grid.ring_row`), and the cell is cut by the bisector of each site found there
   with the one convex cut of :mod:`.clip`.
3. The cell lies within ``r`` (:func:`_radius2`, its largest vertex distance) of the site,
   and the bisector of a site at distance ``d`` stays at least ``d / 2`` away, so only sites
   with ``d < 2 r`` can cut. Once the unscanned buckets are farther than ``2 r``
   (:func:`.grid.ring_gap`), or farther from every vertex than the vertex is from the site
   (:func:`_unscanned_clear`), the cut is final.
4. Exact finishing (:mod:`.halfplane_finish`, :mod:`.halfplane_settle`): the ring of
   neighbours is made exact and every vertex is computed from its name, the sorted owner
   triple (:mod:`.vertex`), so cells sharing a vertex get the same bits as each other and
   as the default algorithm's cells.

Output contract (that of ``cells.cells_from_triangulation``): closed counter-clockwise rings
``coords (K, 2)``, ``offsets (n + 1,)``, ``owner (K,)`` with the site across each edge, -1 on
the box, -2 on the closing vertex.

Output arrays are exact-size in one pass: chunks of cells are written to per-chunk slabs of
fixed capacity and then copied into place; the rare chunk that overflows its slab is simply
recomputed straight into the output.
"""

from __future__ import annotations

from concurrent.futures import ThreadPoolExecutor

import numba
import numpy as np
from numba import njit, prange

from ..config import (
    HALFPLANE_NEAR_RTOL,
    HALFPLANE_NODE_BAND,
    HALFPLANE_SLACK2,
    NJIT,
    NJIT_PARALLEL,
    SIDE_BOX_RTOL,
)
from .clip import cut_ring_inline, plane_values_inline
from .grid import (
    adaptive_grid,
    block_box,
    bucket_of,
    heap_pop,
    heap_push,
    kd_buckets,
    kd_slabs,
    outside_dist2,
    rect_dist2,
    ring_gap,
    ring_row,
    ring_rows,
    skip_lists,
    slab_dist2,
)
from .halfplane_finish import PAD, REACH, far_pad, finish_cell
from .halfplane_settle import BOTTOM, LEFT, RIGHT, TOP
from .predicates import orient2d

_PER_BUCKET = 2.0  # mean sites per grid bucket
_MAX_REFINE = 32.0  # most buckets per _PER_BUCKET sites that clustered input may get
_CHUNK = 512  # cells per parallel work item
_SLAB = 7  # slab vertices per cell of a chunk (the mean over a diagram is below 6)
_CAP = 64  # initial per-cell scratch capacity (doubled when a cell needs more)
_HARD_CAP = 1024  # a cell needing more scratch than this is hard (see _cells)
_BUDGET = 20000  # vertices and sites one cell's search and settling may visit before it is hard
_PROBE = 64  # cells tried first: when most of them are hard, the Delaunay dual builds all
_KD_LEAF = 8  # sites per k-d bucket
_KD_CROWDED = 4.0  # k-d buckets when the median site shares its grid bucket with more
# The k-d search's stop test per bucket (_node_clear) has an absolute margin, four times the
# float cut's vertex error: 2^-40 of the box's radius about the site (HALFPLANE_SLACK2's
# bound) and of the site's coordinates (the named vertices' rounding). A margin relative to
# the cell (HALFPLANE_REACH_RTOL) admits sites in proportion to n on a long line: a strip's
# far vertices are ~1 away and the line's sites at distance s along it pass within s^2 / 2
# of their circles, so 1e-9 kept ~45 sites on each side at 1e6 (issue 15):
# config.HALFPLANE_NODE_BAND, the same 2^-40 as HALFPLANE_SLACK2.

# The helpers called per cut or per bucket (these, clip's cut) are inlined into _cells'
# numba IR: a call costs an atomic reference-count update per array argument, about as
# much as the few flops they do (half-plane uniform 1e5: _first_pass ~15% faster).


@njit(inline="always", **NJIT)
def _radius2(px, py, a, m):
    """Largest squared distance of the cell's vertices from its site (the origin)."""
    r2 = 0.0
    for k in range(a, a + m):
        r2 = max(r2, px[k] * px[k] + py[k] * py[k])
    return r2


@njit(inline="always", **NJIT)
def _rect_clear(px, py, a, m, cx, cy, bx0, by0, bx1, by1, pad):
    """Whether every vertex is farther from the rectangle than from its site (with margin).

    Then no site in the rectangle can cut the cell, now or after later cuts (the cell only
    shrinks, and the points nearer to such a site form a half-plane the cell misses).
    ``4 pad`` bounds what the float vertices' rounding adds to their squared distances.
    """
    for u in range(a, a + m):
        own = REACH * 0.25 * (px[u] * px[u] + py[u] * py[u] + 4.0 * pad)
        if rect_dist2(px[u] + cx, py[u] + cy, bx0, by0, bx1, by1) <= own:
            return False
    return True


@njit(inline="always", **NJIT)
def _unscanned_clear(px, py, a, m, cx, cy, block, grid, pad):
    """Whether no site in the buckets not yet scanned can cut the cell.

    The scanned buckets form ``block`` (:func:`.grid.block_box`). A site ``q`` cuts only if
    some vertex ``v`` is nearer to ``q`` than to the site, so the cell is final once every
    vertex is farther from the unscanned part of the grid than from the site (with the same
    margin as the radius bound, and the rounding ``pad`` as :func:`_rect_clear`).
    """
    for u in range(a, a + m):
        own = REACH * 0.25 * (px[u] * px[u] + py[u] * py[u] + 4.0 * pad)  # |v - site|^2
        if outside_dist2(px[u] + cx, py[u] + cy, block, grid) <= own:
            return False
    return True


@njit(**NJIT)
def _node_clear(px, py, a, m, r2, cx, cy, boxes, slabs, v, band):
    """Whether no site in k-d bucket ``v`` can cut the cell (:func:`.grid.slab_dist2` bounds).

    As :func:`_rect_clear` (``r2`` the cell's squared radius), with an absolute margin
    ``band`` (four times the float cut's vertex error ``e``): every vertex ``p`` of the true
    cell is within ``e`` of a float vertex ``u``, so a site ``q`` in the bucket, farther
    than ``|u| + 4 e`` from ``u``, is farther than ``|p| + 2 e`` from ``p``. It misses every
    vertex's circle by more than rounding and the merge tolerance, so neither the cut nor
    the exact finishing needs it.
    """
    # (|u| + band)^2 <= |u|^2 + (2 r + band) band for r the cell's radius: one root a call
    pad = (2.0 * np.sqrt(r2) + band) * band
    for u in range(a, a + m):
        own = (px[u] * px[u] + py[u] * py[u] + pad) * (1.0 + 2.0**-50)
        if slab_dist2(px[u] + cx, py[u] + cy, boxes, slabs, v) <= own:
            return False
    return True


@njit(**NJIT)
def _holds(ox, oy, c, x, y):
    """Whether the counter-clockwise ring ``o[:c]`` holds ``(x, y)`` (exact turns)."""
    for u in range(c):
        un = u + 1 if u + 1 < c else 0
        if orient2d(ox[u], oy[u], ox[un], oy[un], x, y) < 0.0:
            return False
    return True


@njit(**NJIT)
def _scratch(cap):
    """Scratch arrays of one worker.

    Two polygons (at offsets 1 and ``cap + 2``), plane values, an output cell, the label
    ring, canonical vertices, the candidate list (``4 cap`` sites) with their squared
    distances, the watch list (sites that cut the cell or came near to), and the k-d
    search's heap (``8 cap`` buckets with their squared distances).
    """
    return (
        np.zeros(2 * cap + 2),
        np.zeros(2 * cap + 2),
        np.zeros(2 * cap + 2, np.int64),
        np.zeros(cap),
        np.zeros(cap),
        np.zeros(cap),
        np.zeros(cap, np.int64),
        np.zeros(cap, np.int64),
        np.zeros(cap),
        np.zeros(cap),
        np.zeros(4 * cap, np.int64),
        np.zeros(4 * cap),
        np.zeros(4 * cap, np.int64),
        np.zeros(8 * cap),
        np.zeros(8 * cap, np.int64),
    )


@njit(inline="always", **NJIT)
def _insert(cand, cd, base, nc, t, q2):
    """Insert site ``t`` at squared distance ``q2`` into ``cand[base:nc]`` (sorted); shifts."""
    u = nc
    while u > base and cd[u - 1] > q2:
        cand[u] = cand[u - 1]
        cd[u] = cd[u - 1]
        u -= 1
    cand[u] = t
    cd[u] = q2
    return nc - u


@njit(inline="always", **NJIT)
def _cut_batch(
    base, nc, cand, cd, sx, sy, sidx, cx, cy, px, py, po, ss, a, b, m, r2, watch, nw, cap, slack2
):
    """Cut the cell by the candidates ``cand[base:nc]`` (nearest first).

    ``px, py, po`` hold two polygons and ``ss`` their plane values (separate arrays, not a
    tuple: a tuple built and unpacked per cell costs an atomic reference-count update per
    array); the cell is polygon ``a`` (``m`` vertices, squared radius ``r2``); each cut
    writes polygon ``b`` and the two swap. Sites that cut, or pass within
    the verification band of a vertex's circle or within the float cell's rounding of it
    (``slack2``: ulps of the box, squared), join the watch list (the only sites the
    exact finishing must look at: the others stay clear of every later vertex, which lies
    inside today's cell). Returns ``(a, b, m, r2, nw, grow, work)``; ``grow`` when a list
    or the polygon ran out of room, ``work`` the vertices visited.
    """
    grow = False
    work = 0
    for c in range(base, nc):
        if m < 3 or cd[c] > REACH * (r2 + PAD * slack2):
            break  # sorted: the rest are farther still
        t = cand[c]
        qx = sx[t] - cx
        qy = sy[t] - cy
        smax = plane_values_inline(px, py, a, m, qx, qy, 0.0, 0.0, 0.5 * cd[c], ss)
        work += m
        # (or within the plane values' rounding, ulps of the box times |q|: a 1e-10
        # cluster in a 1e6 box, whose float cell is off by a tenth of itself)
        if smax > -0.5 * HALFPLANE_NEAR_RTOL * r2 or smax * smax < slack2 * cd[c]:
            if nw == watch.shape[0]:
                grow = True
                break
            watch[nw] = t
            nw += 1
        if smax <= 0.0:
            continue
        if m + m // 2 + 2 > cap:  # each run of cut vertices adds at most one
            grow = True
            break
        m = cut_ring_inline(px, py, po, a, m, ss, px, py, po, b, sidx[t])
        work += m
        r2 = _radius2(px, py, b, m)
        a, b = b, a
    return a, b, m, r2, nw, grow, work


@njit(**NJIT)
def _cells(k0, k1, sites, orig, grid, tree, box, budget, counts, where, hard, dx, dy, do):
    """Build the cells of sorted sites ``k0:k1`` and write them one after another to ``d``.

    ``sites = (start, sx, sy, sidx, rownext, bnext)`` are the sorted sites, ``orig = (xs,
    ys)`` the sites by index (for the exact predicates). With a k-d ``tree``
    (:func:`.grid.kd_buckets`, non-empty) its buckets are searched, otherwise the bucket
    ``grid``. Sets ``counts[sidx[k]]`` to each cell's length and ``where[k]`` to its
    position in ``dx, dy, do``. Cells that no longer fit are only counted. A cell whose
    search visits more than ``budget`` vertices and sites, or grows past ``_HARD_CAP``
    vertices, is left empty and flagged in ``hard`` (its neighbours are not local: sites on
    one circle, a site with thousands of neighbours). Returns whether all cells fit.

    The whole loop lives in this one function: a call per cell would cost a dozen atomic
    reference-count updates, more than the geometry of a typical cell.
    """
    start, sx, sy, sidx, rownext, bnext = sites
    xs, ys = orig
    x0, y0, hx, hy, nx, ny = grid
    tlo, thi, tleft, tboxes, tslabs = tree
    use_tree = tlo.shape[0] > 0
    # integers that change later start as np.int64, not as literals: numba would compile
    # every callee they reach once more for a Literal[int] argument while inferring types
    cap = np.int64(_CAP)
    scratch = _scratch(cap)
    px, py, po, ss, ox, oy, oo, lab, vx, vy, cand, cd, watch, hk, hv = scratch
    pos = 0
    fits = True
    k = k0
    while k < k1:
        cx = sx[k]
        cy = sy[k]
        # the box, relative to the site, as polygon a (polygon b receives the next cut)
        a = np.int64(1)
        b = cap + 2
        px[a], py[a], po[a] = box[0] - cx, box[1] - cy, BOTTOM
        px[a + 1], py[a + 1], po[a + 1] = box[2] - cx, box[1] - cy, RIGHT
        px[a + 2], py[a + 2], po[a + 2] = box[2] - cx, box[3] - cy, TOP
        px[a + 3], py[a + 3], po[a + 3] = box[0] - cx, box[3] - cy, LEFT
        m = np.int64(4)
        r2 = _radius2(px, py, a, m)
        slack2 = HALFPLANE_SLACK2 * r2  # the float cell's rounding, squared, from the box's radius
        pad = PAD * slack2  # (r + e)^2 - r^2 for that rounding e: the true cell's radius is r + e
        pad += far_pad(r2, cx, cy)  # (and a site on a vertex's circle to the merge band)
        nc = np.int64(0)
        nw = np.int64(0)
        work = 0
        if np.spacing(np.sqrt(r2)) > SIDE_BOX_RTOL * max(box[2] - box[0], box[3] - box[1]):
            # a box far smaller than the site's distance's ulp: its corners in the site's
            # frame, and the float cut, are off by a visible part of the box (issue 15: a
            # float circle of radius 1e17 through a unit window gave one cell the whole
            # box); the Delaunay dual cuts such cells with exact signs (``power.box_cell``)
            work = budget + 1
        grow = False
        # one loop for both searches, so that the cut (inlined) is compiled once
        ix = bucket_of(cx, x0, hx, nx)
        iy = bucket_of(cy, y0, hy, ny)
        ring = np.int64(0)
        hs = np.int64(0)
        band = 0.0
        if use_tree:
            band = HALFPLANE_NODE_BAND * (np.sqrt(r2) + abs(cx) + abs(cy))  # r2: the box's, here
            root = np.int64(0)
            hs = heap_push(hk, hv, root, slab_dist2(cx, cy, tboxes, tslabs, root), root)
        while m >= 3 and not grow and work <= budget:
            base = nc
            if use_tree:
                if hs == 0:
                    break
                key, v, hs = heap_pop(hk, hv, hs)
                if key > REACH * (r2 + pad):
                    break  # every bucket left is farther still
                work += m
                if key > 0.0 and _node_clear(px, py, a, m, r2, cx, cy, tboxes, tslabs, v, band):
                    continue
                if tleft[v] >= 0:
                    if hs + 2 > hk.shape[0]:
                        grow = True
                        break
                    c = tleft[v]
                    hs = heap_push(hk, hv, hs, slab_dist2(cx, cy, tboxes, tslabs, c), c)
                    c1 = c + 1
                    hs = heap_push(hk, hv, hs, slab_dist2(cx, cy, tboxes, tslabs, c1), c1)
                    continue
                for t in range(tlo[v], thi[v]):
                    qx = sx[t] - cx
                    qy = sy[t] - cy
                    q2 = qx * qx + qy * qy
                    if t == k or q2 > REACH * (r2 + pad):
                        continue
                    if nc == cand.shape[0]:
                        grow = True
                        break
                    work += _insert(cand, cd, base, nc, t, q2)
                    nc += 1
            else:
                if ring > 0:
                    # voro++'s stop radius: a site farther than 2 r cannot cut the cell
                    gap = ring_gap(cx, cx, cy, cy, ix, iy, ring - 1, grid)
                    if gap * gap > REACH * (r2 + pad):
                        break
                    # a cell reaching far past the sites (a hull site in a big box) never
                    # meets that bound: ask each vertex whether the unscanned buckets come
                    # nearer
                    block = block_box(ix, iy, ring - 1, grid)
                    if _unscanned_clear(px, py, a, m, cx, cy, block, grid, pad):
                        break
                # gather the ring's sites that can still cut, nearest first, then cut with
                # them: near bisectors shrink the cell early, so far ones fail the cheap
                # radius test
                # rows, and on the ring's top and bottom rows runs of buckets, without any
                # site are skipped (rownext, bnext): long thin cells cross many nearly empty
                # rings
                j0, j1 = ring_rows(iy, ring, ny)
                jy = rownext[j0]
                while jy <= j1:
                    i0, i1, step = ring_row(ix, iy, ring, jy, nx)
                    edge_row = step == 1
                    gy = max(y0 + jy * hy - cy, cy - (y0 + (jy + 1) * hy), 0.0)
                    row = jy * (nx + 1)
                    jx = bnext[row + i0] if edge_row else i0
                    while jx <= i1:
                        bucket = jy * nx + jx
                        gx = max(x0 + jx * hx - cx, cx - (x0 + (jx + 1) * hx), 0.0)
                        scan = not grow and start[bucket] < start[bucket + 1]
                        scan = scan and gx * gx + gy * gy <= REACH * (r2 + pad)
                        if scan and ring >= 2:
                            # far rings: skip a bucket that no vertex is nearer to than its
                            # site
                            bx = x0 + jx * hx
                            by = y0 + jy * hy
                            scan = not _rect_clear(
                                px, py, a, m, cx, cy, bx, by, bx + hx, by + hy, pad
                            )
                            work += m
                        t0 = start[bucket] if scan else 0
                        t1 = start[bucket + 1] if scan else 0
                        for t in range(t0, t1):
                            qx = sx[t] - cx
                            qy = sy[t] - cy
                            q2 = qx * qx + qy * qy
                            work += 1
                            if t == k or q2 > REACH * (r2 + pad):
                                continue
                            if nc == cand.shape[0]:
                                grow = True
                                break
                            work += _insert(cand, cd, base, nc, t, q2)
                            nc += 1
                        jx = bnext[row + jx + 1] if edge_row else jx + step
                    jy = rownext[jy + 1]
                ring += 1
            if grow:
                break
            a, b, m, r2, nw, grow, w = _cut_batch(
                base,
                nc,
                cand,
                cd,
                sx,
                sy,
                sidx,
                cx,
                cy,
                px,
                py,
                po,
                ss,
                a,
                b,
                m,
                r2,
                watch,
                nw,
                cap,
                slack2,
            )
            work += w
            pad = PAD * slack2 + far_pad(r2, cx, cy)
        if grow and 2 * cap <= _HARD_CAP:  # many vertices: build it again with more room
            cap *= 2
            scratch = _scratch(cap)
            px, py, po, ss, ox, oy, oo, lab, vx, vy, cand, cd, watch, hk, hv = scratch
            continue
        c = np.int64(0)
        if m >= 3 and not grow and work <= budget:
            left = budget - work
            c = finish_cell(
                k,
                sx,
                sy,
                sidx,
                xs,
                ys,
                box,
                px,
                py,
                po,
                ss,
                ox,
                oy,
                oo,
                lab,
                vx,
                vy,
                cand,
                nc,
                watch,
                a,
                m,
                r2,
                nw,
                left,
                budget,
            )
        # a site in the box always has a cell: one cut away to nothing lost it to the float
        # cut's rounding (a 1e-12 cluster beside a 1e6 one: the crossings far out round by
        # more than the cell's width near its site), and the dual builds it
        # (with k-d buckets, a cell is also checked to hold its site, exactly: the same
        # rounding can leave a ring of the wrong place)
        lost = box[0] <= cx <= box[2] and box[1] <= cy <= box[3]
        lost = lost and (m < 3 or use_tree and c > 0 and not _holds(ox, oy, c, cx, cy))
        if grow or work > budget or c == -2 or lost:
            c = 0
            hard[sidx[k]] = True
        elif fits and pos + c <= dx.shape[0]:
            for t in range(c):
                dx[pos + t] = ox[t]
                dy[pos + t] = oy[t]
                do[pos + t] = oo[t]
        else:
            fits = False
        counts[sidx[k]] = c
        where[k] = pos
        pos += c
        k += 1
    return fits


def _first_pass(sites, orig, grid, tree, box, budget, counts, where, hard, slabs, fits):
    """Build every cell into its chunk's slab; ``fits[ch]`` tells whether the slab held it.

    The chunks go to Python threads, each calling :func:`_cells` (compiled ``nogil``), as
    many as numba's thread count (one on the calling thread for small inputs, see
    ``engine.threads.serial_below``). Not a ``parallel=True`` kernel: numba links and
    optimises a kernel's whole call tree into each compiled function that calls it, twice
    in a parallel one (the function and its parfor body), and :func:`_cells`' tree is the
    2D suite's largest (the half-plane kernels' first compile, the rest cached: 30.8 -> 15.1 s
    of CPU; a call from Python costs ~30 us next to ~2 ms for a chunk of 512 cells). Each chunk
    writes its own slab and its own sites' entries, so the result does not depend on the
    order the chunks run in.
    """
    slab_x, slab_y, slab_o = slabs
    n = sites[1].shape[0]
    nchunks = fits.shape[0]
    per = slab_x.shape[0] // nchunks if nchunks else 0

    def run(ch):
        lo = ch * per
        k0 = ch * _CHUNK
        k1 = min(k0 + _CHUNK, n)
        args = (counts, where, hard, slab_x[lo : lo + per], slab_y[lo : lo + per])
        fits[ch] = _cells(
            k0, k1, sites, orig, grid, tree, box, budget, *args, slab_o[lo : lo + per]
        )

    threads = min(numba.get_num_threads(), nchunks)
    if threads <= 1:
        for ch in range(nchunks):
            run(ch)
        return
    with ThreadPoolExecutor(threads) as pool:
        list(pool.map(run, range(nchunks)))


@njit(**NJIT_PARALLEL)
def _second_pass(sidx, counts, offsets, where, slab, fits, over, obase, kmap, coords, owner):
    """Copy every cell to its place in the output, closing rings and mapping owners.

    A chunk that fit its slab is read from there; the others were rebuilt into ``over`` (at
    ``obase[ch]``). Rings are closed on the way (first vertex repeated, owner -2 there) and
    owners mapped through ``kmap``.
    """
    n = sidx.shape[0]
    slab_x, slab_y, slab_o = slab
    over_x, over_y, over_o = over
    per = slab_x.shape[0] // fits.shape[0]
    for ch in prange(fits.shape[0]):
        k0 = ch * _CHUNK
        k1 = min((ch + 1) * _CHUNK, n)
        if fits[ch]:
            _copy_cells(
                k0,
                k1,
                sidx,
                counts,
                offsets,
                where,
                ch * per,
                slab_x,
                slab_y,
                slab_o,
                kmap,
                coords,
                owner,
            )
        else:
            _copy_cells(
                k0,
                k1,
                sidx,
                counts,
                offsets,
                where,
                obase[ch],
                over_x,
                over_y,
                over_o,
                kmap,
                coords,
                owner,
            )


@njit(**NJIT)
def _copy_cells(k0, k1, sidx, counts, offsets, where, base, xs, ys, os, kmap, coords, owner):
    for k in range(k0, k1):
        i = sidx[k]
        m = counts[i]
        if m == 0:
            continue
        dst = offsets[i]
        src = base + where[k]
        for t in range(m):
            coords[dst + t, 0] = xs[src + t]
            coords[dst + t, 1] = ys[src + t]
            o = os[src + t]
            owner[dst + t] = kmap[o] if o >= 0 else -1
        coords[dst + m, 0] = xs[src]
        coords[dst + m, 1] = ys[src]
        owner[dst + m] = -2


def _median_occupancy(occ):
    """``np.median(np.repeat(occ, occ))`` without the repeat: the site-weighted median count."""
    weight = np.bincount(occ) * np.arange(int(occ.max()) + 1)  # sites per occupancy (ints)
    cum = np.cumsum(weight)
    total = int(cum[-1])
    lo = int(np.searchsorted(cum, (total - 1) // 2, side="right"))
    hi = int(np.searchsorted(cum, total // 2, side="right"))
    return 0.5 * (lo + hi)


def _search_grid(xs, ys):
    """The search structure of the sites: ``grid``, ``(*sites, rownext, bnext)`` and ``tree``.

    :func:`.grid.adaptive_grid` with ``_PER_BUCKET`` sites per bucket, refined up to
    ``_MAX_REFINE`` times for clustered sites, and its skip lists. When the median site
    still shares its bucket with more than ``_KD_CROWDED`` times that many (tight clusters
    in a wide domain), the sites go into k-d buckets instead (:func:`.grid.kd_buckets`),
    which hold a few sites at any density; ``tree`` is empty otherwise.
    """
    grid, sites = adaptive_grid(xs, ys, _PER_BUCKET, _MAX_REFINE)
    occ = np.diff(sites[0])
    median = _median_occupancy(occ)
    if median > _KD_CROWDED * _PER_BUCKET:
        tree, (sx, sy, sidx) = kd_buckets(xs, ys, _KD_LEAF)
        tree = (*tree, kd_slabs(tree, sx, sy))
        none = np.zeros(1, np.int64)
        return grid, (none, sx, sy, sidx, none, np.zeros(1, np.int32)), tree
    rownext, bnext = skip_lists(sites[0], grid[4], grid[5])
    empty = np.zeros(0, np.int64)
    return grid, (*sites, rownext, bnext), (empty, empty, empty, np.zeros((0, 4)), np.zeros((0, 7)))


def _probe_hard(sites, orig, grid, tree, box, budget):
    """Whether most of ``_PROBE`` cells spread over the sites are hard (see :func:`_cells`).

    Then the cells' neighbours are not local (most sites on one circle, say) and the
    Delaunay dual builds every cell in ``O(n log n)``; trying each cell first would cost
    the budget ``n`` times.
    """
    n = sites[1].shape[0]
    if n <= 4 * _PROBE:
        return False
    runs = 8
    counts = np.zeros(n, np.int64)
    where = np.zeros(n, np.int64)
    hard = np.zeros(n, np.bool_)
    per = _SLAB * _PROBE + 16
    out = (np.zeros(per), np.zeros(per), np.zeros(per, np.int64))
    for r in range(runs):
        k0 = (r * n) // runs
        k1 = k0 + _PROBE // runs
        _cells(k0, k1, sites, orig, grid, tree, box, budget, counts, where, hard, *out)
    return int(hard.sum()) > _PROBE // 2


def halfplane_cells(xs, ys, box, kmap=None, budget=_BUDGET):
    """Voronoi cells of distinct sites clipped to ``box``, by half-plane cutting.

    The output layout is that of ``cells.cells_from_triangulation`` (closed rings), plus
    the cells left to the caller.

    Parameters
    ----------
    xs, ys : (n,) float64
        Distinct sites (the engine removes duplicates); they may lie outside the box.
    box : (4,) float64
        ``(xmin, ymin, xmax, ymax)``.
    kmap : (n,) int64, optional
        Output id of each site, used for the edge owners (default: the site's index).
    budget : int, optional
        Most vertices and sites one cell's search and settling may visit.

    Returns
    -------
    coords : (K, 2) float64
        Closed counter-clockwise rings (last vertex repeats the first), no consecutive
        duplicates otherwise.
    offsets : (n + 1,) int64
        Cell ``i`` is ``coords[offsets[i]:offsets[i + 1]]``; empty when it misses the box.
    owner : (K,) int64
        ``kmap`` of the site across the edge from vertex ``k`` to the next one, -1 on the
        box boundary, -2 on each closing vertex.
    hard : (n,) bool
        Cells not built (left empty) because their neighbours are not local: more than
        ``budget`` work, or more vertices than the scratch holds (sites on one circle, a
        site with thousands of neighbours). The caller takes them from the Delaunay dual.
        All true when most of a sample of cells is hard (nothing is built then).

    Examples
    --------
    >>> import numpy as np
    >>> coords, offsets, owner, hard = halfplane_cells(
    ...     np.array([0.25, 0.75]), np.array([0.5, 0.5]), np.array([0.0, 0.0, 1.0, 1.0])
    ... )
    >>> offsets.tolist(), sorted(owner[:5].tolist()), hard.any()
    ([0, 5, 10], [-2, -1, -1, -1, 1], False)
    """
    xs = np.ascontiguousarray(xs, dtype=np.float64)
    ys = np.ascontiguousarray(ys, dtype=np.float64)
    n = xs.shape[0]
    kmap = np.arange(n) if kmap is None else np.ascontiguousarray(kmap, dtype=np.int64)
    hard = np.zeros(n, np.bool_)
    if n == 0:
        return np.zeros((0, 2)), np.zeros(1, np.int64), np.zeros(0, np.int64), hard
    boxa = np.ascontiguousarray(box, dtype=np.float64).reshape(4)
    grid, sites, tree = _search_grid(xs, ys)
    orig = (xs, ys)
    if _probe_hard(sites, orig, grid, tree, boxa, budget):
        hard[:] = True
        return np.zeros((0, 2)), np.zeros(n + 1, np.int64), np.zeros(0, np.int64), hard
    nchunks = (n + _CHUNK - 1) // _CHUNK
    per = _SLAB * min(_CHUNK, n) + 16
    counts = np.zeros(n, np.int64)
    where = np.zeros(n, np.int64)
    slabs = (np.zeros(nchunks * per), np.zeros(nchunks * per), np.zeros(nchunks * per, np.int64))
    fits = np.zeros(nchunks, np.bool_)
    _first_pass(sites, orig, grid, tree, boxa, budget, counts, where, hard, slabs, fits)
    # the rare chunks that overflowed their slab are built again, now that their size
    # is known, one after another into one overflow buffer
    sidx = sites[3]
    obase = np.zeros(nchunks, np.int64)
    total = 0
    for ch in np.flatnonzero(~fits):
        obase[ch] = total
        total += int(counts[sidx[ch * _CHUNK : (ch + 1) * _CHUNK]].sum())
    over = (np.zeros(total), np.zeros(total), np.zeros(total, np.int64))
    for ch in np.flatnonzero(~fits):
        k0 = ch * _CHUNK
        k1 = min((ch + 1) * _CHUNK, n)
        lo = obase[ch]
        hi = lo + int(counts[sidx[k0:k1]].sum())
        views = (over[0][lo:hi], over[1][lo:hi], over[2][lo:hi])
        _cells(k0, k1, sites, orig, grid, tree, boxa, budget, counts, where, hard, *views)
    offsets = np.zeros(n + 1, np.int64)
    np.cumsum(np.where(counts > 0, counts + 1, 0), out=offsets[1:])
    k = int(offsets[-1])
    coords = np.empty((k, 2))  # noqa: TID251 - every slot is written by _second_pass
    owner = np.empty(k, np.int64)  # noqa: TID251 - every slot is written by _second_pass
    _second_pass(sidx, counts, offsets, where, slabs, fits, over, obase, kmap, coords, owner)
    return coords, offsets, owner, hard
