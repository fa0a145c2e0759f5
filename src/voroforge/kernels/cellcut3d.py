"""One 3D cell: the container cut by the bisector planes of nearby sites, nearest first.

The search and cut half of the cell builder (:mod:`kernels.cells3d` names the vertices and
writes the slots). :func:`one_cell` starts from the container polyhedron (relative to the
site), visits the buckets in the precomputed order of their least possible distance and
then shell by shell (:mod:`kernels.grid3d`), gathers the candidates of one distance, cuts by
them nearest first (:func:`_cut_batch`), and stops once no unscanned site can reach the cell
(:func:`.reach3d.far`: twice the cell's radius, widened by the weights' spread, or the local
bound of :func:`.reach3d.local_stop` when the grid carries the weights' pyramid).

The cell is held as a vertex graph (:mod:`kernels.graph3d`) when the template has one,
else (and as the fallback the caller runs when the graph reports ``BROKEN``) as face rings
cut by :func:`kernels.polyhedron.cut`. Vertex values farther from a plane than the float
filter's band are trusted; those within it are decided exactly on the vertex's owners
(:func:`.band3d.resolve`, :func:`kernels.predicates3d.bisector_side`). A cut's new vertex on an edge
nearly parallel to its plane is solved again exactly (:func:`kernels.vertex3d.resettle`).
"""

from __future__ import annotations

import numba
import numpy as np
from llvmlite import ir
from numba import njit, types
from numba.core import cgutils
from numba.extending import intrinsic

from ..config import (
    BIN_SORT_FROM,
    CELLCUT3D_PREFETCH_MOST,
    CELLCUT3D_RADIUS_PAD,
    CELLCUT3D_REFRESH_CUTS,
    CLIMB3D_LOCAL_FROM,
    NJIT,
    VORONOI3D_CUT_RTOL,
    VORONOI3D_STOP_RTOL,
)
from ..config import CELLCUT3D_OWN_ENTRIES as OWN_ENTRIES
from .band3d import offset_cache, owner_key, resolve  # noqa: F401 (re-exported: cells3d)
from .climb3d import FULL, MISS, clear_tops, list_removed, plane_local
from .graph3d import GCUT_DONE, cut_close, cut_listed, list_above, to_rings
from .grid3d import bucket3d, shell_buckets_in, shell_gap
from .polyhedron import CUT_DONE, CUT_EMPTY, CUT_OVERFLOW, cut
from .reach3d import gather_heavy, heavy_header, local_stop, shell_hit, shell_range
from .reach3d import reach_box as _reach_box
from .ties3d import retie
from .vertex3d import resettle, resettle_rings
from .walk3d import (
    bin_group,
    gap_rows,
    next_leaf,
    ordered_bucket,
    ordered_bucket_rows,
)

OK = 0
EMPTY = 1
OVERFLOW = 2
BROKEN = 3
UNNAMED = 4
#: the cell examined more sites than the grid's budget ``g[9]`` allows (engine.lists3d
#: rebuilds it from its Delaunay candidate list)
SLOW = 5

MAX_OWNERS = 32
#: small hot helpers are inlined into their callers (numba's own inliner): a call that
#: passes arrays costs reference counting, and the search makes ~100 such calls per cell
NJIT_INLINE = {**NJIT, "inline": "always"}
#: the per-cell functions allocate nothing (the caller passes every scratch array), so they
#: are compiled without reference counting: each call otherwise pays atomic count updates
#: for every array it is passed or takes a view of
NJIT_NO_NRT = {**NJIT, "_nrt": False}


@intrinsic
def prefetch_row(typingctx, arr, row):
    """Ask the cache for row ``row`` of the 2D array ``arr`` (a hint: no effect on results).

    The sites' rows ``P[j]`` are read by index (input order) once a plane cuts: at 1e6
    sites each first read was a miss that the cut waited for.
    """
    sig = types.void(arr, row)

    def codegen(context, builder, signature, args):
        aryty = signature.args[0]
        ary = context.make_array(aryty)(context, builder, args[0])
        idx = context.cast(builder, args[1], signature.args[1], types.intp)
        zero = context.get_constant(types.intp, 0)
        ptr = cgutils.get_item_pointer(context, builder, aryty, ary, [idx, zero], wraparound=False)
        i32 = ir.IntType(32)
        fnty = ir.FunctionType(ir.VoidType(), [ptr.type, i32, i32, i32])
        fn = cgutils.get_or_insert_function(builder.module, fnty, "llvm.prefetch.p0")
        builder.call(fn, [ptr, i32(0), i32(3), i32(1)])  # read, keep, data
        return context.get_dummy_value()

    return sig, codegen


if numba.config.DISABLE_JIT:  # kernels run as Python (coverage): a hint has nothing to do

    def prefetch_row(arr, row):  # noqa: D103, ARG001
        return None


@njit(**NJIT_INLINE)
def radius2(V, nv):
    """The largest squared distance of the first ``nv`` vertices ``V`` from the site (origin)."""
    r = 0.0
    r1 = 0.0  # (odd vertices: two chains of max, which is exact)
    v = 0
    while v + 1 < nv:
        r = max(r, V[v, 0] * V[v, 0] + V[v, 1] * V[v, 1] + V[v, 2] * V[v, 2])
        w = v + 1
        r1 = max(r1, V[w, 0] * V[w, 0] + V[w, 1] * V[w, 1] + V[w, 2] * V[w, 2])
        v += 2
    if v < nv:
        r = max(r, V[v, 0] * V[v, 0] + V[v, 1] * V[v, 1] + V[v, 2] * V[v, 2])
    return max(r, r1)


@njit(**NJIT)
def cut_scratch(vcap, fcap, rcap, ncand, nbuck):
    """The face-ring arrays and candidate buffers of one cell's cut (see :func:`one_cell`)."""
    V = np.zeros((vcap, 3))
    F = np.zeros((fcap, 3), np.int64)
    R = np.zeros(rcap, np.int64)
    R2 = np.zeros(rcap, np.int64)
    S = np.zeros(vcap)
    work = np.zeros((max(vcap, rcap), 4), np.int64)
    T = np.zeros((4 * vcap, 1), np.int64)  # the sites whose planes cut or touched the cell
    own = max(MAX_OWNERS, min(vcap // 16, OWN_ENTRIES // max(vcap, 1)))
    OWN = np.zeros((vcap, own), np.int32)
    # the batch (_gather writes slot m before _cut_batch reads below m): 1 MB at 1e6 sites,
    # which zeroed cost ~0.65 ms a call (16 calls a chunk with two threads), mostly faults
    cand = np.empty(ncand, np.int64)  # noqa: TID251 - written before read
    cd2 = np.empty(ncand)  # noqa: TID251 - written before read
    buck = np.empty(nbuck, np.int64)  # noqa: TID251 (shell_buckets writes before reads)
    return V, F, R, R2, S, work, T, OWN, cand, cd2, buck


@njit(**NJIT)
def graph_scratch(vcap, degree):
    """The vertex-graph arrays of :mod:`kernels.graph3d`: ``(DEG, ED, BK, LB, CP, seen, FL)``.

    ``degree`` is the most edges a vertex may have (more: the cell is built with face rings).
    ``FL`` flags the vertices found exactly on a plane (more owners than their faces).
    """
    DEG = np.zeros(vcap, np.int32)
    ED = np.zeros((vcap, degree), np.int32)
    BK = np.zeros((vcap, degree), np.int32)
    LB = np.zeros((vcap, degree), np.int32)
    CP = np.zeros((vcap, 3), np.int64)
    seen = np.zeros((vcap, degree), np.bool_)
    FL = np.zeros(vcap, np.bool_)
    return DEG, ED, BK, LB, CP, seen, FL


@njit(**NJIT_INLINE)
def _values(V, nv, nx, ny, nz, h, S):
    """Signed values ``n . v - h`` of the cell's vertices (the float filter; inlined).

    Returns ``(smax, low)``: the largest value and the least ``|value|`` (one within the
    band ``tol`` of 0 when ``low <= tol``: :func:`.band3d.resolve` decides those exactly).
    """
    # two running maxima and minima (even and odd vertices): one chain of max/min through
    # every vertex bound the loop by their latency; max and min are exact, so the split
    # changes no result (a zero's sign aside, which no caller reads)
    smax = -np.inf
    low = np.inf
    smax1 = -np.inf
    low1 = np.inf
    v = 0
    while v + 1 < nv:
        s = nx * V[v, 0] + ny * V[v, 1] + nz * V[v, 2] - h
        s1 = nx * V[v + 1, 0] + ny * V[v + 1, 1] + nz * V[v + 1, 2] - h
        S[v] = s
        S[v + 1] = s1
        a = abs(s)
        a1 = abs(s1)
        if a < low:
            low = a
        if a1 < low1:
            low1 = a1
        if s > smax:
            smax = s
        if s1 > smax1:
            smax1 = s1
        v += 2
    if v < nv:
        s = nx * V[v, 0] + ny * V[v, 1] + nz * V[v, 2] - h
        S[v] = s
        a = abs(s)
        if a < low:
            low = a
        if s > smax:
            smax = s
    if smax1 > smax:
        smax = smax1
    if low1 < low:
        low = low1
    return smax, low


@njit(**NJIT_INLINE)
def _cut_batch(m, i, P, WP, X, px, py, pz, wi, W, SP, SW, sidx, cand, cd2, C, G, nv, nf, nt, rmax2):
    """Cut cell ``i`` by the ``m`` gathered candidates, nearest first.

    ``C = (V, F, R, R2, S, work, T)`` holds the cell (face rings) and the planes that cut or
    touched it; ``G`` its vertex graph when ``G[0]`` is non-empty (then the rings are read
    off at the end). ``X`` is the exact predicates' scratch. Returns
    ``(status, nv, nf, nt, rmax2)``.
    """
    V, F, R, R2, S, work, T = C
    graph = G[0].shape[0] > 0
    # after a graph cut the cell's radius is found only when needed (r2m: the last cut's
    # moved points, which the radius takes too): rmax2 is then an upper bound ("stale"),
    # enough for the skip test (a plane beyond the bound is beyond the cell) and, where no
    # value is within the bound's band, for the band test; the radius itself is that of
    # every cut (the largest |v|^2 left, or r2m if larger, as each cut found it before)
    stale = False
    r2m = 0.0
    cuts = 0  # graph cuts since the radius was last found (small cells: CELLCUT3D_REFRESH_CUTS)
    # the climb's start (kernels.climb3d): a point of the last cut's cap (int64, not a
    # literal 0: plane_local compiled once more for the loop's first, literal, type)
    hint = np.int64(0)
    hw = 0  # work[:hw, (0, 3)], the climb's marks, are clear (bin_group writes work)
    if BIN_SORT_FROM <= m < min(S.shape[0], work.shape[0]):
        bin_group(m, cand, cd2, S, work)
    for a in range(1, m):  # insertion sort (stable): batches are small, or grouped
        ta = cand[a]
        da = cd2[a]
        b = a - 1
        while b >= 0 and cd2[b] > da:
            cand[b + 1] = cand[b]
            cd2[b + 1] = cd2[b]
            b -= 1
        cand[b + 1] = ta
        cd2[b + 1] = da
    for a in range(min(m, CELLCUT3D_PREFETCH_MOST)):  # the nearest: the likeliest to cut
        prefetch_row(P, sidx[cand[a]])
    for a in range(m):
        t = cand[a]
        j = sidx[t]
        d2 = cd2[a]
        dx = SP[t, 0] - px
        dy = SP[t, 1] - py
        dz = SP[t, 2] - pz
        h = 0.5 * (d2 + (wi - SW[t]))
        if h > 0.0 and h * h > rmax2 * d2 * (1.0 + VORONOI3D_STOP_RTOL):
            continue  # the plane passes beyond every vertex
        if stale and cuts >= CELLCUT3D_REFRESH_CUTS and nv < CLIMB3D_LOCAL_FROM:
            # a small cell's radius, found again before a plane that the bound keeps: it
            # is found from as many vertices as one plane's values, and the batch's far
            # candidates (the first batch's bound is the container's) are then skipped
            stale = False
            cuts = 0
            rmax2 = max(radius2(V, nv), r2m)
            if h > 0.0 and h * h > rmax2 * d2 * (1.0 + VORONOI3D_STOP_RTOL):
                continue
        tol = VORONOI3D_CUT_RTOL * (np.sqrt(d2 * rmax2) + abs(h))
        mode = FULL
        # the values near and above the plane only, if decided
        if graph and nv >= CLIMB3D_LOCAL_FROM:
            while hw < nv:
                work[hw, 0] = 0
                work[hw, 3] = 0
                hw += 1
            mode, smax, low, nvl = plane_local(V, nv, G[0], G[1], S, work, dx, dy, dz, h, tol, hint)
            if mode == MISS:
                continue  # every vertex lies beyond the band below the plane
        if mode == FULL:
            nvl = np.int64(-1)  # (not a literal: resolve compiles once)
            smax, low = _values(V, nv, dx, dy, dz, h, S)
        if stale and low <= tol:  # the band test needs the radius (and so may the skip)
            stale = False
            cuts = 0
            rmax2 = max(radius2(V, nv), r2m)
            if h > 0.0 and h * h > rmax2 * d2 * (1.0 + VORONOI3D_STOP_RTOL):
                continue
            tol = VORONOI3D_CUT_RTOL * (np.sqrt(d2 * rmax2) + abs(h))
        near = low <= tol
        if near:
            X[2][0] = True
            smax = resolve(nv, tol, S, i, j, C, nf, G, P, W, WP, X, work, nvl)
        if smax == 0.0 or smax > 0.0:  # it cuts or touches: a possible owner of vertices
            if nt >= T.shape[0]:
                return OVERFLOW, 0, 0, 0, 0.0
            T[nt, 0] = j
            nt += 1
        nup = -1
        listed = True
        down = True
        if smax > 0.0 and nvl >= 0:
            nup, down = list_removed(nv, G[0], S, work, nvl, G[4])
        if (smax == 0.0 and near or smax > 0.0 and nup < 0) and nvl >= 0:
            _values(V, nv, dx, dy, dz, h, S)  # the tie test and the listing read every value
            nvl = np.int64(-1)  # (a variable holding -1 is a literal: resolve compiled twice)
            if near:
                smax = resolve(nv, tol, S, i, j, C, nf, G, P, W, WP, X, work, nvl)
        if smax <= 0.0:
            if smax == 0.0 and near:
                retie(i, j, nv, nf, S, C, G, P)
            continue
        if graph:
            if nup < 0:  # (cut_open's first pass)
                nup, down, listed = list_above(nv, S, G[4])
            if not down:
                return EMPTY, 0, 0, 0, 0.0
            st, nv2, w, nl = cut_listed(
                V, nv, G[0], G[1], G[2], G[3], G[6], S, G[4], j, nup, listed
            )
            hint = G[4][0, 2]
            if st != GCUT_DONE:  # out of vertex rows (nv2 is all of them): more, not rings
                return (OVERFLOW if nv2 >= V.shape[0] else BROKEN), 0, 0, 0, 0.0
            r2m = resettle(i, j, V, G[4], w, G[0], G[3], S, P, W, WP, X[1])
            st, nv2, _ = cut_close(V, nv2, G[0], G[1], G[2], G[3], G[6], S, G[4], nl, False)
            r2c = max(rmax2, r2m) * CELLCUT3D_RADIUS_PAD  # a bound: new points lie within the cell
            stale = True
            cuts += 1
            nf2 = 0
        else:
            r2c = -1.0
            st, nv2, nf2 = cut(V, nv, F, nf, R, R2, S, work, j)
            if st == CUT_EMPTY:
                return EMPTY, 0, 0, 0, 0.0
            if st != CUT_DONE:
                return (OVERFLOW if st == CUT_OVERFLOW else BROKEN), 0, 0, 0, 0.0
            resettle_rings(i, j, C[0], C[1], C[2], C[5][:, 3], nf2, P, W, WP, X)
        nv = nv2
        nf = nf2
        rmax2 = r2c if graph else radius2(V, nv)
    if stale:
        rmax2 = max(radius2(V, nv), r2m)
    return OK, nv, nf, nt, rmax2


@njit(**NJIT_INLINE)
def _gather(b, t, i, px, py, pz, wi, start, SP, SW, sidx, cand, cd2, m, mg, rmax2):
    """Add the sites of bucket ``b`` from its ``t``-th on to the candidates, until full.

    A site whose plane passes beyond every vertex of the cell as it is now (``rmax2``) is
    counted (``mg``: the candidates a batch holds, for when it is full) but not kept: the
    cell only shrinks, so :func:`_cut_batch` would skip it at its turn (the test here has
    twice the slack of that one, so rounding in the cell's radius cannot tell them apart).
    Each site is written at slot ``m`` and counted only if kept (no branches on the data:
    which sites are kept follows no pattern). Returns ``(m, mg, t)``: ``t < start[b + 1]``
    when the batch filled up first.
    """
    ncap = cand.shape[0]
    end = start[b + 1]
    reach = rmax2 * (1.0 + 2.0 * VORONOI3D_STOP_RTOL)
    while t < end and mg < ncap:  # (m <= mg: slot m is in the batch)
        dx = SP[t, 0] - px
        dy = SP[t, 1] - py
        dz = SP[t, 2] - pz
        d2 = dx * dx + dy * dy + dz * dz
        h = 0.5 * (d2 + (wi - SW[t]))
        other = sidx[t] != i and d2 != 0.0
        cand[m] = t
        cd2[m] = d2
        mg += other
        m += other and not (h > 0.0 and h * h > reach * d2)
        t += 1
    return m, mg, t


@njit(**NJIT_NO_NRT)
def one_cell(
    i,
    P,
    W,
    WP,
    X,
    wmax,
    start,
    SP,
    SW,
    sidx,
    g,
    order,
    tree,
    TV,
    TF,
    TR,
    TG,
    C,
    G,
    cand,
    cd2,
    buck,
    hk,
    ib,
    tb,
):
    """Cut cell ``i``; leaves it in ``C``'s ``(V, F, R)``. Returns ``(status, nv, nf, nt, rmax2)``.

    With a vertex graph ``G`` (``G[0]`` non-empty) the cell starts from the template's graph
    ``TG`` and is cut as a graph; its rings are read off at the end. With k-d buckets
    (``tree`` non-empty: :func:`.grid3d.kd_buckets3d`'s nodes, ``start`` its buckets) the
    buckets come nearest box first from a heap (keys ``hk``, nodes ``buck``) and each is cut
    by at once; the stop tests are :func:`.reach3d.far` on the box distance and
    :func:`.reach3d.box_misses`.
    ``g[9]`` (optional): the most sites to examine (past it ``SLOW``), or when negative
    candidate lists (bucket ``i`` of ``start`` holds cell ``i``'s sites: engine.lists3d).
    """
    V, F, R, R2, S, work, T = C
    graph = G[0].shape[0] > 0
    X[3][0, 0] += 1  # a new cell: band3d._cached_vertex's offsets and frame are stale
    if graph:
        clear_tops(work)  # (kernels.climb3d: the climbs' starts of the last cell)
    px = P[i, 0]
    py = P[i, 1]
    pz = P[i, 2]
    wi = W[i]
    # heavy sites (reach3d.weight_reach): the search bounds the light ones, then they cut
    hb, hn, wmax = heavy_header(g, wi, wmax)
    ntv = TV.shape[0]
    ntf = TF.shape[0]
    if ntv > V.shape[0] or ntf > F.shape[0] or TR.shape[0] > R.shape[0]:
        return OVERFLOW, 0, 0, 0, 0.0
    qx = px  # the template is relative to the walls' origin (engine.containers), if any
    qy = py
    qz = pz
    if WP.shape[1] > 4:
        qx = px - WP[0, 4]
        qy = py - WP[0, 5]
        qz = pz - WP[0, 6]
    for v in range(ntv):
        V[v, 0] = TV[v, 0] - qx
        V[v, 1] = TV[v, 1] - qy
        V[v, 2] = TV[v, 2] - qz
    if graph:
        DEG, ED, BK, LB = G[0], G[1], G[2], G[3]
        TDEG, TED, TBK, TLB = TG
        for v in range(ntv):
            G[6][v] = False
            d = TDEG[v]
            DEG[v] = d
            for k in range(d):
                ED[v, k] = TED[v, k]
                BK[v, k] = TBK[v, k]
                LB[v, k] = TLB[v, k]
    else:
        for f in range(ntf):
            F[f, 0] = TF[f, 0]
            F[f, 1] = TF[f, 1]
            F[f, 2] = TF[f, 2]
        for t in range(TR.shape[0]):
            R[t] = TR[t]
    nv = ntv
    nf = ntf
    nt = 0
    rmax2 = radius2(V, nv)
    ci, cj, ck = bucket3d(px, py, pz, g)
    st = OK
    # nearest buckets first, in the precomputed order of their least possible distance
    m = 0  # candidates kept, and gathered (kept or not: a batch is full at ncap of them)
    mg = 0
    level = 0.0  # buckets of one least distance are gathered, then cut by, together
    o = 0  # next entry of the ordered buckets; then shells r, r + 1, ... (buckets q of nb)
    r = int(order[order.shape[0] - 1, 4]) if order.shape[0] else -1
    # least squared distance to a bucket outside the ordered block (shells r + 1, ...):
    # the order's later entries can lie beyond it, so a far entry stops the search only
    # below it (else the shells go on from r)
    outside = (r * min(g[3], g[4], g[5])) ** 2 if r >= 0 else 0.0
    rows = r >= 0 and 2 * r + 1 <= tb.shape[1]  # the ordered entries' gaps from tb's rows
    if rows:  # (tb is the shells' scratch: free until they begin)
        gap_rows(px, py, pz, ci, cj, ck, r, g, tb)
    q = 0
    nb = 0
    shells = False
    rb = -1  # a crowded bucket to go on gathering from, at rt
    rt = 0
    kd = tree.shape[0] > 0  # k-d buckets: nearest box first from a heap (keys hk, nodes buck)
    size = 0
    eps = 0.0  # the coordinates' rounding relative to the site, for .reach3d.box_misses
    if kd:
        for a in range(6):
            eps = max(eps, abs(tree[0, a]))
        eps *= 4e-16
        hk[0] = 0.0
        buck[0] = 0
        size = 1
    # g[9], when there: > 0 the most sites to examine (then SLOW), < 0 candidate lists
    # (bucket i of start/SP/SW/sidx holds cell i's sites: its one batch, then done)
    budget = g[9] if g.shape[0] > 9 else 0.0
    lists = budget < 0.0
    seen = 0
    gs = (np.inf, -1.0)  # the local stop's bound and the radius it was found at (reach3d)
    # heavier than the light sites by rs2: cut first by those at sqrt(rs2) (reach3d.shell_range)
    rs2 = wi - g[hb + 1] if hn > 0 and not kd and not lists else 0.0
    light = True  # a light site may still reach the cell
    shell = (0, 0, 0, -1, -1, -1)  # the buckets cut by first (none)
    # the shell phase (sh): the buckets of shell's box that the sphere meets, z, y, x (u:
    # the next of total), gathered and cut by before the search (one inlined cut: a second
    # copy of it cost ~40 s of the 3D warm-up's compile)
    sh = False
    u = 0
    total = 0
    sx = 0
    sy = 0
    if rs2 > 0.0:
        light = rs2 <= rmax2 * (1.0 + 4.0 * VORONOI3D_STOP_RTOL)
        if light:
            shell = shell_range(px, py, pz, g, rs2)
            sx = shell[3] - shell[0] + 1
            sy = shell[4] - shell[1] + 1
            sz = shell[5] - shell[2] + 1
            total = sx * sy * sz if sx > 0 and sy > 0 and sz > 0 else 0
            sh = True
    nx = int(g[6])
    ny = int(g[7])
    while True:
        flush = False
        stop = False
        shend = False  # the shell phase ends with this flush
        b = -1
        if rb >= 0:
            b = rb
            rb = -1
        elif sh:  # the box's next bucket that the sphere meets, else cut by what is gathered
            while u < total:
                bx = shell[0] + u % sx
                by = shell[1] + (u // sx) % sy
                bz = shell[2] + u // (sx * sy)
                u += 1
                b = (bz * ny + by) * nx + bx
                if shell_hit(b, px, py, pz, g, rs2, shell):
                    break
                b = -1
            if b >= 0:
                rt = start[b]
            else:
                flush = True
                shend = True
        elif not light:  # no light site can reach the cell: the heavy ones, then done
            flush = True
            stop = True
        elif lists:  # the cell's list is one bucket: gathered once, then the search ends
            flush = True
            stop = seen > 0
            if not stop:
                b = i
                rt = start[i]
                seen = 1
        elif kd:  # each k-d bucket is cut by at once
            b, size, gs = next_leaf(
                px, py, pz, tree, hk, buck, size, wi, wmax, rmax2, V, nv, eps, g, gs
            )
            flush = True
            if b >= 0:
                rt = start[b]
            else:
                stop = True
        elif not shells:
            if o == order.shape[0]:
                shells = True
                flush = True
            elif mg > 0 and order[o, 3] > level:
                flush = True  # entry o is looked at again after the cut
            else:
                level = order[o, 3]
                far, gs2, gr2 = local_stop(level, wi, wmax, rmax2, px, py, pz, g, gs[0], gs[1])
                gs = (gs2, gr2)
                if far:
                    flush = True
                    if level <= outside:
                        stop = True
                    else:
                        shells = True
                    o += 1
                # the entries of this level in a row (the same level and radius: the same
                # stop test), until one is crowded
                while not far:
                    if rows:
                        b = ordered_bucket_rows(order, o, ci, cj, ck, r, tb, g, wi, wmax, rmax2)
                    else:
                        b = ordered_bucket(order, o, ci, cj, ck, px, py, pz, g, wi, wmax, rmax2)
                    o += 1
                    if b >= 0 and rs2 > 0.0 and shell_hit(b, px, py, pz, g, rs2, shell):
                        b = -1  # (cut by first)
                    if b >= 0:
                        m, mg, rt = _gather(
                            b,
                            start[b],
                            i,
                            px,
                            py,
                            pz,
                            wi,
                            start,
                            SP,
                            SW,
                            sidx,
                            cand,
                            cd2,
                            m,
                            mg,
                            rmax2,
                        )
                        if rt < start[b + 1]:  # crowded: cut by what is gathered, go on
                            rb = b
                            flush = True
                            break
                    if o == order.shape[0] or order[o, 3] != level:
                        break
                b = -1
        elif q < nb:
            b = buck[q]
            rt = start[b]
            q += 1
        else:  # a shell gathered (or none yet): cut by it, then the next shell if needed
            flush = True
            if m == 0:  # (else the shell's sites are cut by first, and this comes again)
                gap = shell_gap(px, py, pz, ci, cj, ck, r, g) if r >= 0 else 0.0
                far, gs2, gr2 = local_stop(gap * gap, wi, wmax, rmax2, px, py, pz, g, gs[0], gs[1])
                gs = (gs2, gr2)
                if gap == np.inf or (r >= 0 and far):
                    stop = True
                else:
                    r += 1
                    bound = _reach_box(px, py, pz, V, nv, wi, wmax, rmax2, g, ib, tb)
                    nb = shell_buckets_in(ci, cj, ck, r, ib, tb, bound, int(g[6]), int(g[7]), buck)
                    q = 0
                    stop = nb < 0
                    nb = max(nb, 0)
        if b >= 0 and not sh and rs2 > 0.0 and shell_hit(b, px, py, pz, g, rs2, shell):
            b = -1  # (cut by first)
        if b >= 0:
            m, mg, rt = _gather(
                b, rt, i, px, py, pz, wi, start, SP, SW, sidx, cand, cd2, m, mg, rmax2
            )
            if rt < start[b + 1]:  # a crowded neighbourhood: cut by what is gathered, go on
                rb = b
                flush = True
            elif sh and mg >= cand.shape[0]:  # (the shell phase cuts a full batch at once)
                flush = True
        for _ in range(2):  # (twice when the search stops and the heavy sites remain)
            if not flush:
                break
            if m > 0:
                st, nv, nf, nt, rmax2 = _cut_batch(
                    m,
                    i,
                    P,
                    WP,
                    X,
                    px,
                    py,
                    pz,
                    wi,
                    W,
                    SP,
                    SW,
                    sidx,
                    cand,
                    cd2,
                    C,
                    G,
                    nv,
                    nf,
                    nt,
                    rmax2,
                )
                if st != OK:
                    return st, 0, 0, 0, 0.0
            if not sh:  # (the shell phase's sites are not counted against the budget)
                seen += mg
            m = 0
            mg = 0
            if budget > 0.0 and seen > budget:
                return SLOW, 0, 0, 0, 0.0
            if not stop or hn == 0:
                break
            # the light sites cannot reach the cell: the heavy ones that can, then done
            m = gather_heavy(g, hb, hn, i, px, py, pz, wi, SP, SW, sidx, cand, cd2, rmax2)
            mg = m
            hn = 0
        if shend:  # the shell phase is done: can a light site still reach the cell?
            sh = False
            light = rs2 <= rmax2 * (1.0 + 4.0 * VORONOI3D_STOP_RTOL)
        if stop:
            break
    if graph:
        nf = to_rings(nv, G[0], G[1], G[2], G[3], F, R, G[5])
        if nf < 0:
            return BROKEN, 0, 0, 0, 0.0
    return OK, nv, nf, nt, rmax2
