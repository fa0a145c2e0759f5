"""Cells in a big :class:`Convex` hull: built in the hull's box, the cells that reach a wall again.

A hull of thousands of facets as every cell's starting polyhedron made each cell cost the
template's size (and past the builder's scratch, 1,024 vertices, a retry that allocated its
working space cell by cell: 2,000 sites in the hull of 2,000 points on a sphere took ~60 s).
Here (issue 12):

1. every cell is built in a box around the hull (:func:`.build3d.build_cells3d`), fast;
2. the cells with a vertex on or past a hull wall (a float test with a wide margin: a cell
   marked in vain is only built twice) are built again from the hull's template, each from
   a candidate list: the sites that own a vertex of its box cell. That list holds every
   site whose plane bounds the cell or touches it (a plane that bounds or touches the hull
   cell supports the box cell, which contains it, so it passes through one of the box
   cell's vertices, and that vertex's owners are the cells sharing it), so the cell and its
   vertex names are the template path's; the kernel is the builder's own
   (:func:`.kernels.cells3d.build_cells` in candidate-list mode, as :mod:`.lists3d`), with
   scratch sized for the template and made once per thread;
3. the cells that stay strictly inside keep their box cells; vertices are joined by their
   bits and name key (the builder's join identity), the box cells' shared vertices keyed
   by naming them from their owner sites.

Only the order of vertices and faces (the cuts' history) differs from the template path.
A vertex of more owners than the second pass's owner table holds (144 at its slots: sites
on a sphere about it) is a big polytope of every cell (:mod:`.bigvertex3d`), found from the
first pass's vertices or from the first cell that overflows (growing the slots never held
1,032 owners: "overflowed its biggest slots", or killed for memory).
"""

from __future__ import annotations

import threading

import numpy as np
from numba import njit, prange

from ..config import (
    CELLCUT3D_OWN_ENTRIES,
    HULL3D_BIG,
    HULL3D_CHUNK,
    HULL3D_DOP_PAD,
    HULL3D_REACH_RTOL,
    HULL3D_SLOTS,
    NJIT,
    NJIT_PARALLEL,
)
from ..kernels.cellcut3d import MAX_OWNERS
from ..kernels.cells3d import OVERFLOW, build_cells, cell_scratch
from ..kernels.predicates3d import scratch
from ..kernels.vertex3d import axis_snap, name_key, name_vertex, place
from .bigvertex3d import BigVertices
from .build3d import CAPS, PER_BUCKET, Cells3D, build_cells3d, csr_take, grid3d_shape
from .containers import Template, cut_template
from .threads import serial_below

#: no site's cell known empty (build_cells' ``gone``, as :mod:`.build3d` passes it)
_NONE_GONE = np.zeros(0, np.bool_)


def takes_hull_path(t: Template) -> bool:
    """Whether :func:`.voronoi3d.voronoi3d` builds the cells of Convex template ``t`` here.

    When the template is past the cell builder's scratch (:data:`.build3d.CAPS`: 512 faces,
    so a hull of ~260 points on a sphere, where every cell was built again alone and the
    template path turned ~10x slower: 2,000 sites, 300 points: 3.2 s, here 0.39 s) or past
    :data:`HULL3D_BIG` vertices. Smaller hulls keep the template path (as fast there, and its
    vertex and face order: the 3D hashes' 60-point hull).
    """
    if t.kind != "convex":
        return False
    big = len(t.TV) > CAPS[3] or len(t.TF) > CAPS[4] or len(t.TR) > CAPS[5]
    return big or len(t.TV) > HULL3D_BIG


def hull_cells(P: np.ndarray, W: np.ndarray, t: Template, progress=None) -> Cells3D:
    """Cells of all sites ``P`` (weights ``W``) in the big Convex template ``t`` (working frame)."""
    u = len(P)
    A = build_cells3d(P, W, _around(t), progress=progress, short=True)
    bad = np.flatnonzero((A.status != 0) & (A.status != 1))
    if len(bad):
        return A  # the caller reports the failed cell
    bcell = np.empty(u, np.int64)  # noqa: TID251 - a permutation: every slot written
    bcell[A.pos] = np.arange(u)
    with serial_below(u):
        reach = _reaching(
            A.vertices, A.voff, A.vid, A.cell_faces, A.flabel, P, bcell, t.WP, _ball(t)
        )
    rpos = np.flatnonzero(reach)
    ipos = np.flatnonzero(~reach)
    if len(rpos) == 0:
        return A
    # each vertex's cells (its owner sites), CSR
    nvA = np.diff(A.voff)
    owner = np.repeat(bcell, nvA)
    byv = np.argsort(A.vid, kind="stable")
    vstart = np.zeros(len(A.vertices) + 1, np.int64)
    np.cumsum(np.bincount(A.vid, minlength=len(A.vertices)), out=vstart[1:])
    vcells = np.ascontiguousarray(owner[byv])
    start, sites = _lists(rpos, bcell, A.voff, A.vid, vstart, vcells, u)
    B = _second_pass(P, W, t, bcell[rpos], start, sites, _wide(P, W, t, vstart, vcells))
    return _combine(P, W, t, A, bcell, ipos, rpos, B, vstart, vcells)


def _around(t: Template) -> Template:
    """The first pass's container: the template's support in 26 directions (a k-DOP), padded.

    Any solid holding the hull would do (the cells it bounds are built again); its box left
    empty corners around a round hull, where the cells grow long and their searches slow
    (1e5 sites in a ball: 18 s in its box, 5 s in a box just holding them). Cut from a box
    in floating point (:func:`.containers.cut_template`, about the centre), as hull
    templates are: no linear programs, at any magnitude.
    """
    dirs = np.array(
        [(a, b, c) for a in (-1, 0, 1) for b in (-1, 0, 1) for c in (-1, 0, 1) if a or b or c],
        np.float64,
    )
    dirs /= np.linalg.norm(dirs, axis=1)[:, None]
    V = t.TV + t.origin
    lo, hi = V.min(axis=0), V.max(axis=0)
    pad = HULL3D_DOP_PAD * float((hi - lo).max())
    c = 0.5 * (lo + hi)
    d = ((V - c) @ dirs.T).max(axis=0) + pad
    TV, TF, TR, vol = cut_template(dirs, d, lo - c - 2 * pad, hi - c + 2 * pad)
    WP = np.column_stack([dirs, d + dirs @ c])
    TV = TV + c
    return Template(TV, TF, TR, WP, "convex", float(vol), np.array([TV.min(0), TV.max(0)]))


def _ball(t: Template) -> np.ndarray:
    """``(cx, cy, cz, r)``: a ball about the template's mean vertex inside every wall."""
    c = t.TV.mean(axis=0)
    WP = t.WP
    r = float((WP[:, 3] - WP[:, :3] @ c).min())
    return np.array([c[0], c[1], c[2], max(r, 0.0)])


@njit(**NJIT_PARALLEL)
def _reaching(V, voff, vid, cf, flabel, P, bcell, WP, ball):
    """Per build position: whether the box cell has a wall face or a vertex near a hull wall.

    ``ball = (cx, cy, cz, r)``: a ball inside every wall (in the walls' frame); a cell whose
    bounding sphere about its site lies inside it by the margin is inside. Else a wall whose
    plane the sphere stays inside of by the margin is skipped, and every vertex is tested
    against the others. Cells in parallel.
    """
    n = voff.shape[0] - 1
    out = np.zeros(n, np.bool_)
    far = WP.shape[1] > 4
    ox = WP[0, 4] if far else 0.0
    oy = WP[0, 5] if far else 0.0
    oz = WP[0, 6] if far else 0.0
    for b in prange(n):
        if voff[b + 1] == voff[b]:
            continue  # empty (power) cell
        hit = False
        for f in range(cf[b], cf[b + 1]):
            if flabel[f] < 0:
                hit = True
        c = bcell[b]
        px = P[c, 0] - ox
        py = P[c, 1] - oy
        pz = P[c, 2] - oz
        r2 = 0.0
        for e in range(voff[b], voff[b + 1]):
            g = vid[e]
            dx = V[g, 0] - ox - px
            dy = V[g, 1] - oy - py
            dz = V[g, 2] - oz - pz
            r2 = max(r2, dx * dx + dy * dy + dz * dz)
        r = np.sqrt(r2) * (1.0 + HULL3D_REACH_RTOL)
        size = abs(px) + abs(py) + abs(pz) + r
        qx = px - ball[0]
        qy = py - ball[1]
        qz = pz - ball[2]
        if hit or np.sqrt(qx * qx + qy * qy + qz * qz) + r >= ball[3] - HULL3D_REACH_RTOL * (
            size + abs(ball[3]) + abs(ball[0]) + abs(ball[1]) + abs(ball[2])
        ):
            for w in range(WP.shape[0]):
                if hit:
                    break
                nx = WP[w, 0]
                ny = WP[w, 1]
                nz = WP[w, 2]
                d = WP[w, 3]
                marg = HULL3D_REACH_RTOL * (abs(d) + size)
                if nx * px + ny * py + nz * pz - d + r < -marg:
                    continue
                for e in range(voff[b], voff[b + 1]):
                    g = vid[e]
                    x = V[g, 0] - ox
                    y = V[g, 1] - oy
                    z = V[g, 2] - oz
                    if nx * x + ny * y + nz * z - d >= -marg:
                        hit = True
                        break
        out[b] = hit
    return out


@njit(**NJIT)
def _lists(rpos, bcell, voff, vid, vstart, vcells, u):
    """Candidate lists of the cells at build positions ``rpos``: the owners of their vertices.

    Returns ``start (u + 1,)`` (cell ``c``'s list is ``sites[start[c]:start[c + 1]]``; empty
    for the others) and ``sites``.
    """
    mark = np.full(u, -1, np.int64)
    cnt = np.zeros(u + 1, np.int64)
    tot = 0
    for q in range(rpos.shape[0]):
        b = rpos[q]
        c = bcell[b]
        mark[c] = q
        for e in range(voff[b], voff[b + 1]):
            g = vid[e]
            for t in range(vstart[g], vstart[g + 1]):
                s = vcells[t]
                if mark[s] != q:
                    mark[s] = q
                    cnt[c + 1] += 1
        tot += cnt[c + 1]
    start = np.cumsum(cnt)
    sites = np.zeros(tot, np.int64)
    mark[:] = -1
    for q in range(rpos.shape[0]):
        b = rpos[q]
        c = bcell[b]
        mark[c] = q
        k = start[c]
        for e in range(voff[b], voff[b + 1]):
            g = vid[e]
            for t in range(vstart[g], vstart[g + 1]):
                s = vcells[t]
                if mark[s] != q:
                    mark[s] = q
                    sites[k] = s
                    k += 1
    return start, sites


def _caps(t: Template, slots) -> np.ndarray:
    """The kernel's caps: output ``slots``, scratch for the template and its first cuts."""
    ntv, ntf, ntr = len(t.TV), len(t.TF), len(t.TR)
    return np.array(
        [
            slots[0],
            slots[1],
            slots[2],
            2 * ntv + 4 * slots[0],
            2 * ntf + 4 * slots[1],
            2 * ntr + 4 * slots[2],
            24,
        ],
        np.int64,
    )


def _wide(P, W, t, vstart, vcells) -> BigVertices:
    """The first pass's vertices of more owners than a cell's owner table holds.

    Found before the second pass (else every cell on one overflowed and was built twice: the
    1,032 integer points of a sphere in a ball, ~8 -> ~5.5 CPU s): each from its first-pass
    cells, whose owners are then tested exactly (:meth:`.bigvertex3d.BigVertices.add`).
    """
    bv = BigVertices(P, W, t.WP)
    vcap = int(_caps(t, HULL3D_SLOTS)[3])  # the owner table's width at the second pass's caps
    width = max(MAX_OWNERS, min(vcap // 16, CELLCUT3D_OWN_ENTRIES // vcap))  # (as cut_scratch)
    wide = np.flatnonzero(np.diff(vstart) > width - 2)
    if len(wide):
        rows, buf = np.zeros((2, 4, 4)), scratch()
        for g in wide:
            own = vcells[vstart[g] : vstart[g + 1]]
            bv.add(int(own[0]), own[1:], width, rows, buf)
    return bv


def _second_pass(P, W, t, cells, start, sites, bv):
    """Build ``cells`` from the template ``t`` and their lists; per cell its slot records.

    Returns ``(status, counts, vol, cen, rad2, osite, ovabs, ofaces, oring)``: per cell the
    kernel's results, and the concatenated records of the cells that built (``counts``
    rows in order).
    """
    import numba

    g = np.append(grid3d_shape(P, PER_BUCKET), -1.0)  # -1: candidate lists
    SP = np.ascontiguousarray(P[sites])
    SW = np.ascontiguousarray(W[sites])
    tree = np.zeros((0, 8))
    order = np.zeros((0, 5))
    wmax = float(W.max()) if len(W) else 0.0
    k = len(cells)
    status = np.zeros(k, np.int64)
    counts = np.zeros((k, 3), np.int64)
    vol = np.zeros(k)
    cen = np.zeros((k, 3))
    rad2 = np.zeros(k)
    recs = [None] * k

    # ``bv``: vertices of more owners than a cell's owner table holds (sites on a sphere
    # about it), big polytopes of every cell (named from all their owners, as the first
    # pass's Delaunay lists name them); found from the first pass (:func:`_wide`), or here
    # exactly from the first cell whose table overflows
    lock = threading.Lock()

    def run(few, caps, scr, big=None):
        m = len(few)
        cv, cf, cr = (int(x) for x in caps[:3])
        st = np.zeros(m, np.int64)
        ct = np.zeros((m, 3), np.int64)
        v = np.zeros(m)
        c = np.zeros((m, 3))
        r2 = np.zeros(m)
        osite = np.zeros(m * cv, np.int32)
        ovabs = np.zeros((m * cv, 3))
        ofaces = np.zeros((m * cf, 2), np.int32)
        oring = np.zeros(m * cr, np.int32)
        build_cells(
            few,
            P,
            W,
            start,
            SP,
            SW,
            sites,
            g,
            order,
            tree,
            t.TV,
            t.TF,
            t.TR,
            t.WP,
            caps,
            wmax,
            st,
            ct,
            v,
            c,
            r2,
            osite,
            ovabs,
            ofaces,
            oring,
            scr,
            # big and star as build3d passes them (None, or a big vertex's (big, None)),
            # gone none known empty (build_cells passes every None to its one compiled
            # kernel as an empty array of the lists' types)
            *((None, None) if big is None else big),
            _NONE_GONE,
        )
        return st, ct, v, c, r2, osite, ovabs, ofaces, oring

    def part(a, b):
        caps = _caps(t, HULL3D_SLOTS)
        scr = cell_scratch(len(P), g, tree, t.TV, t.TF, t.TR, caps)
        for c0 in range(a, b, HULL3D_CHUNK):
            c1 = min(c0 + HULL3D_CHUNK, b)
            few = cells[c0:c1]
            big = _every(bv, lock)
            st, ct, v, c, r2, osite, ovabs, ofaces, oring = run(few, caps, scr, big)
            over = np.flatnonzero(st == OVERFLOW)
            if len(over) and big is None and _found(run, few[over[0]], caps, scr, bv, lock):
                # its cells again with the vertex: every cell on it overflowed, and each
                # alone cost a scratch (1,032 sites on a sphere: 1,032 calls)
                st, ct, v, c, r2, osite, ovabs, ofaces, oring = run(
                    few, caps, scr, _every(bv, lock)
                )
            cv, cf, cr = HULL3D_SLOTS
            for q in range(c1 - c0):
                x = c0 + q
                s = st[q]
                nv, nf, nr = ct[q]
                if s == OVERFLOW:
                    s, (nv, nf, nr), v1, cn1, r21, rec = _alone(
                        run, cells[x], t, g, len(P), ct[q], bv, lock
                    )
                    vol[x], cen[x], rad2[x] = v1, cn1, r21
                    recs[x] = rec
                else:
                    vol[x], cen[x], rad2[x] = v[q], c[q], r2[q]
                    recs[x] = (
                        osite[q * cv : q * cv + nv].copy(),
                        ovabs[q * cv : q * cv + nv].copy(),
                        ofaces[q * cf : q * cf + nf].copy(),
                        oring[q * cr : q * cr + nr].copy(),
                    )
                status[x] = s
                counts[x] = (nv, nf, nr)

    with serial_below(k):
        nth = numba.get_num_threads()
    nth = max(1, min(nth, k // 64 or 1))
    if nth == 1:
        part(0, k)
    else:  # the kernel releases the GIL: one slice a thread, each with its own scratch
        from concurrent.futures import ThreadPoolExecutor

        bounds = np.linspace(0, k, nth + 1).astype(int)
        with ThreadPoolExecutor(nth) as pool:
            list(pool.map(part, bounds[:-1], bounds[1:]))
    return status, counts, vol, cen, rad2, recs


def _every(bv, lock):
    """The big vertices found so far as :func:`.cells3d.build_cells`'s ``(big, star)``, or None.

    Every cell may take them: a site on none (``of[i] < 0``) builds as without them.
    """
    with lock:
        if not bv.sets:
            return None
        return bv.search(int(np.flatnonzero(bv.of >= 0)[0]))


def _found(run, i, caps, scr, bv, lock) -> bool:
    """Whether cell ``i`` is on a big vertex, found now from its overflowing owner table."""
    if run(np.array([i]), caps, scr)[0][0] != OVERFLOW:
        return False
    with lock:
        return bool(bv.of[i] >= 0 or bv.find(i, {threading.get_ident(): scr}))


def _alone(run, i, t, g, ns, need, bv, lock):
    """Cell ``i`` alone with slots for its counts ``need`` (grown until it fits).

    A cell whose owner table overflowed at a vertex of more owners than it holds (not its
    slots: larger slots do not widen the table) finds that vertex (:mod:`.bigvertex3d`) and
    is built again with it as a big polytope; growing the slots for it allocated gigabytes.
    """
    slots = [max(HULL3D_SLOTS[q], int(need[q])) for q in range(3)]
    big = _every(bv, lock)
    for _ in range(8):
        caps = _caps(t, slots)
        scr = cell_scratch(ns, g, np.zeros((0, 8)), t.TV, t.TF, t.TR, caps)
        st, ct, v, c, r2, osite, ovabs, ofaces, oring = run(np.array([i]), caps, scr, big)
        if st[0] != OVERFLOW:
            nv, nf, nr = (int(x) for x in ct[0])
            rec = (osite[:nv].copy(), ovabs[:nv].copy(), ofaces[:nf].copy(), oring[:nr].copy())
            return st[0], ct[0], v[0], c[0], r2[0], rec
        if big is None or bv.of[i] < 0:
            with lock:
                found = bv.of[i] >= 0 or bv.find(i, {threading.get_ident(): scr})
            if found:
                big = _every(bv, lock)
                continue
        slots = [max(4 * slots[q], int(ct[0, q])) for q in range(3)]
    raise RuntimeError(f"3D cell {int(i)} overflowed its biggest slots")


@njit(**NJIT)
def _shared_keys(S, vstart, vcells, P, W, WP, V):
    """Name keys of the box cells' vertices ``S``, named from their owner sites (their cells).

    Returns ``(key, ok)``: ``ok`` where the name's coordinates are the vertex's bits (else
    the key is 0, which no vertex has: the vertex stays unmatched and is counted).
    """
    ns = P.shape[0]
    most = 4
    for q in range(S.shape[0]):
        most = max(most, vstart[S[q] + 1] - vstart[S[q]])
    keys = np.zeros(most, np.int64)
    rows = np.zeros((3, 4))
    y = np.zeros(3)
    name = np.zeros(4, np.int64)
    x = np.zeros(3)
    buf = scratch()
    out = np.zeros(S.shape[0], np.int64)
    ok = np.zeros(S.shape[0], np.bool_)
    for q in range(S.shape[0]):
        g = S[q]
        m = vstart[g + 1] - vstart[g]
        for t in range(m):
            keys[t] = vcells[vstart[g] + t]
        keys[:m].sort()
        if m < 4 or name_vertex(keys, m, P, W, WP, ns, rows, y, name, buf) == 0:
            continue
        place(name, P, W, WP, ns, y, x, buf)
        axis_snap(keys, m, ns, WP, x)
        if x[0] + 0.0 == V[g, 0] and x[1] + 0.0 == V[g, 1] and x[2] + 0.0 == V[g, 2]:
            out[q] = name_key(m, name)
            ok[q] = True
    return out, ok


def _rows_unique(R: np.ndarray):
    """``np.unique(R, axis=0, return_index=True, return_inverse=True)`` by one lexsort.

    (``np.unique`` on rows sorts them as opaque records: seconds for the joins of 1e5 sites.)
    """
    if len(R) == 0:
        return R, np.zeros(0, np.int64), np.zeros(0, np.int64)
    order = np.lexsort(R.T[::-1])
    S = R[order]
    new = np.ones(len(R), bool)
    new[1:] = (S[1:] != S[:-1]).any(axis=1)
    group = np.cumsum(new) - 1
    inv = np.empty(len(R), np.int64)  # noqa: TID251 - a permutation: every slot written
    inv[order] = group
    return S[new], order[new], inv


def _ring_type(most):
    """The ring's local index type for cells of up to ``most`` vertices."""
    return np.uint8 if most <= 256 else (np.uint16 if most <= 65536 else np.int32)


def _combine(P, W, t, A, bcell, ipos, rpos, B, vstart, vcells):
    """The cells: the box cells at ``ipos``, the second pass's at ``rpos``, vertices joined."""
    status, counts, vol, cen, rad2, recs = B
    u = len(P)
    nvA = np.diff(A.voff)
    nfA = np.diff(A.cell_faces)
    rlA = np.diff(A.roff)
    gI = A.vid[csr_take(nvA, ipos)]
    # (masks, not np.unique: 1.4 s of hashing for 1e5 sites)
    inI = np.zeros(len(A.vertices), bool)
    inI[gI] = True
    inR = np.zeros(len(A.vertices), bool)
    inR[A.vid[csr_take(nvA, rpos)]] = True
    usedA = np.flatnonzero(inI)
    newA = np.cumsum(inI) - 1  # the kept box vertices' new numbers
    S = np.flatnonzero(inI & inR)
    keyS, okS = _shared_keys(S, vstart, vcells, P, W, t.WP, A.vertices)
    osite = np.concatenate([r[0] for r in recs]) if recs else np.zeros(0, np.int32)
    ovabs = np.concatenate([r[1] for r in recs]) if recs else np.zeros((0, 3))
    ofaces = np.concatenate([r[2] for r in recs]) if recs else np.zeros((0, 2), np.int32)
    oring = np.concatenate([r[3] for r in recs]) if recs else np.zeros(0, np.int32)
    RA = np.column_stack([np.ascontiguousarray(A.vertices[S]).view(np.int64), keyS])
    RB = np.column_stack([np.ascontiguousarray(ovabs).view(np.int64), osite >> 8])
    uq, first, inv = _rows_unique(np.vstack([RA, RB]))
    gid = np.full(len(uq), -1, np.int64)
    gid[inv[: len(S)]] = newA[S]
    fresh = np.flatnonzero(gid < 0)
    gid[fresh] = len(usedA) + np.arange(len(fresh))
    vertices = np.concatenate([A.vertices[usedA], ovabs[first[fresh] - len(S)]])
    # owner sites each vertex should be referenced by, against the cells that do
    nsite = np.zeros(len(vertices), np.int64)
    nsite[: len(usedA)] = np.diff(vstart)[usedA] + A.short[usedA]
    np.maximum.at(nsite, gid[inv[len(S) :]], osite & 255)
    vid = np.concatenate([newA[gI], gid[inv[len(S) :]]])
    refs = np.bincount(vid, minlength=len(vertices))
    unmatched = int(np.count_nonzero(refs < nsite))
    fI = csr_take(nfA, ipos)
    nv = np.concatenate([nvA[ipos], counts[:, 0]])
    nf = np.concatenate([nfA[ipos], counts[:, 1]])
    rl = np.concatenate([rlA[fI], ofaces[:, 1]])
    ring = np.concatenate([A.ring[csr_take(rlA, fI)], oring]).astype(
        _ring_type(int(nv.max()) if len(nv) else 0)
    )
    flabel = np.concatenate([A.flabel[fI], ofaces[:, 0]]).astype(np.int32)
    pos = np.empty(u, np.int64)  # noqa: TID251 - a permutation: every slot written
    pos[bcell[ipos]] = np.arange(len(ipos))
    pos[bcell[rpos]] = len(ipos) + np.arange(len(rpos))
    st, v, c, r2 = A.status.copy(), A.volume.copy(), A.centroid.copy(), A.rad2.copy()
    rc = bcell[rpos]
    st[rc], v[rc], c[rc], r2[rc] = status, vol, cen, rad2
    zero = np.zeros(1, np.int64)
    return Cells3D(
        A.cells,
        st,
        v,
        c,
        r2,
        vertices,
        pos,
        np.concatenate([zero, np.cumsum(nf)]),
        flabel,
        # build3d's offset type (int32 below 2**30 entries): one compiled signature of the
        # face-table kernels (diagram3d's) for both builders, not a second for int64
        np.concatenate([zero, np.cumsum(rl)]).astype(np.int32 if len(ring) < 2**30 else np.int64),
        ring,
        np.concatenate([zero, np.cumsum(nv)]),
        vid.astype(np.int32 if len(vertices) < 2**31 else np.int64),
        unmatched,
    )
