"""The bucket walks of one 3D cell's search (:func:`.cellcut3d.one_cell`), and its batches.

The grid's precomputed order of buckets by least possible distance (:func:`ordered_bucket`:
one entry's bucket, or -1 when it lies outside the grid or beyond the stop test; with
:func:`gap_rows` once per cell, :func:`ordered_bucket_rows`), the k-d buckets' walk, nearest
box first from a heap (:func:`next_leaf`), and the grouping of a gathered batch by distance
before it is sorted (:func:`bin_group`).
"""

from __future__ import annotations

from numba import njit

from ..config import NJIT
from .grid import heap_pop, heap_push
from .reach3d import axis_gap as _axis_gap
from .reach3d import box_dist2 as _box_dist2
from .reach3d import box_near as _box_near
from .reach3d import far as _far
from .reach3d import local_stop

#: inlined into the cell's search (see kernels.cellcut3d)
_INLINE = {**NJIT, "inline": "always"}
#: allocates nothing: compiled without reference counting (see kernels.cellcut3d)
_NO_NRT = {**NJIT, "_nrt": False}


@njit(**_INLINE)
def ordered_bucket(order, o, ci, cj, ck, px, py, pz, g, wi, wmax, rmax2):
    """The bucket of ordered entry ``o`` around ``(ci, cj, ck)``, or -1 (outside, or too far)."""
    ox = int(order[o, 0])
    oy = int(order[o, 1])
    oz = int(order[o, 2])
    bx = ci + ox
    by = cj + oy
    bz = ck + oz
    nx = int(g[6])
    ny = int(g[7])
    if bx < 0 or by < 0 or bz < 0 or bx >= nx or by >= ny or bz >= int(g[8]):
        return -1
    if order[o, 3] > 0.0:
        gx = _axis_gap(px, g[0], g[3], bx, ox)
        gy = _axis_gap(py, g[1], g[4], by, oy)
        gz = _axis_gap(pz, g[2], g[5], bz, oz)
        if _far(gx * gx + gy * gy + gz * gz, wi, wmax, rmax2):
            return -1
    return (bz * ny + by) * nx + bx


@njit(**_NO_NRT)
def next_leaf(px, py, pz, tree, hk, hv, size, wi, wmax, rmax2, V, nv, eps, g, gs):
    """Pop k-d nodes off the heap ``hk[:size], hv[:size]`` to the next bucket that may cut.

    Nearest box first (keys: squared distances from the site to the boxes); the walk ends
    at the first node beyond the stop test (:func:`_far`: every later one is farther), a
    node whose box every vertex is nearer than (:func:`.reach3d.box_near`) is dropped.
    Returns ``(bucket or -1, size, gs)`` (``gs``: :func:`.reach3d.local_stop`'s). Kept out
    of line: :func:`.cellcut3d.one_cell`'s grid search compiles around a call, not around
    the walk (inlined, the walk cost uniform cells 4-7%).

    A heap entry's value is ``node + m * k`` (``m`` nodes): ``k`` the vertex found near its
    parent's box, where the test of its own box starts (the caller's root, 0: node 0 from
    vertex 0). The cell may have been cut since: ``k`` is then only a start, which changes
    no answer. From vertex 0 each box read ~360 of a three lines cell's ~1,000 vertices
    before one near it (12x the ~29 from the parent's).
    """
    m = tree.shape[0]
    while size > 0:
        key, e, size = heap_pop(hk, hv, size)
        v = e % m
        stop, gs2, gr2 = local_stop(key, wi, wmax, rmax2, px, py, pz, g, gs[0], gs[1])
        gs = (gs2, gr2)
        if stop:
            return -1, 0, gs
        k = _box_near(px, py, pz, tree[v], V, nv, wi, wmax, rmax2, eps, e // m)
        if k < 0:
            continue
        left = int(tree[v, 6])
        if left < 0:
            return int(tree[v, 7]), size, gs
        for c in range(left, left + 2):
            d2 = _box_dist2(px, py, pz, tree, c)
            if not _far(d2, wi, wmax, rmax2):
                size = heap_push(hk, hv, size, d2, c + m * k)
    return -1, size, gs


@njit(**_INLINE)
def gap_rows(px, py, pz, ci, cj, ck, r, g, tb):
    """Per axis, the squared gaps of :func:`ordered_bucket` at offsets ``-r..r`` into ``tb``.

    ``tb[a, r + off]``: the squared distance along axis ``a`` from the site to the bucket
    ``off`` away from its own, or -1 where that bucket is outside the grid. Once per cell:
    each ordered entry then adds three of them (the same sums, bit for bit).
    """
    c = (ci, cj, ck)
    p = (px, py, pz)
    for a in range(3):
        n = int(g[6 + a])
        for k in range(-r, r + 1):
            b = c[a] + k
            if b < 0 or b >= n:
                tb[a, r + k] = -1.0
            else:
                gap = _axis_gap(p[a], g[a], g[3 + a], b, k)
                tb[a, r + k] = gap * gap


@njit(**_INLINE)
def ordered_bucket_rows(order, o, ci, cj, ck, r, tb, g, wi, wmax, rmax2):
    """:func:`ordered_bucket` from :func:`gap_rows`' ``tb`` (the same bucket or -1)."""
    ox = int(order[o, 0])
    oy = int(order[o, 1])
    oz = int(order[o, 2])
    gx = tb[0, r + ox]
    gy = tb[1, r + oy]
    gz = tb[2, r + oz]
    if gx < 0.0 or gy < 0.0 or gz < 0.0:
        return -1
    if order[o, 3] > 0.0 and _far(gx + gy + gz, wi, wmax, rmax2):
        return -1
    nx = int(g[6])
    ny = int(g[7])
    return ((ck + oz) * ny + (cj + oy)) * nx + (ci + ox)


@njit(**_INLINE)
def bin_group(m, cand, cd2, S, work):
    """Group the batch ``cand[:m], cd2[:m]`` by bins of ``cd2``, in place, stably.

    The bin of a distance is a non-decreasing function of it, so the batch is then sorted
    but within bins, and the stable insertion sort after it gives the same order as on the
    batch as gathered (equal distances keep their order). ``S`` and ``work[:, :3]`` are
    scratch (free between cuts; the caller checks they hold ``m + 1`` rows).
    """
    lo = cd2[0]
    hi = cd2[0]
    for a in range(1, m):
        lo = min(lo, cd2[a])
        hi = max(hi, cd2[a])
    if not hi > lo:
        return
    nb = m
    scale = nb / (hi - lo)
    if not scale < 1e300:
        return
    for k in range(nb + 1):
        work[k, 1] = 0
    for a in range(m):
        k = min(int((cd2[a] - lo) * scale), nb - 1)
        work[a, 0] = k
        work[k + 1, 1] += 1
    for k in range(nb):
        work[k + 1, 1] += work[k, 1]
    for a in range(m):
        k = work[a, 0]
        p = work[k, 1]
        work[k, 1] = p + 1
        work[p, 2] = cand[a]
        S[p] = cd2[a]
    for a in range(m):
        cand[a] = work[a, 2]
        cd2[a] = S[a]
