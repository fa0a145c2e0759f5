"""3D Voronoi / power cells one by one: the container cut by nearby bisector planes.

For each cell (as voro++ does): start from the container polyhedron (relative to the site),
visit the grid's shells of buckets around the site's bucket, nearest candidates of a shell
first, cut by each candidate's power bisector, and stop once no unscanned site can reach the
cell (that search and cut is :mod:`kernels.cellcut3d`). Then every vertex is named by its
owners and recomputed from the name (:mod:`kernels.vertex3d`), so neighbouring cells share
its bits; local vertices with the same name are merged, faces left with fewer than three
vertices dropped, and the volume, centroid and face area vectors are taken from the named
coordinates.

Output slots are per cell with fixed capacities (``caps``); a cell that does not fit is
reported (status ``OVERFLOW``) and the engine runs it again alone with room to spare.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import CELLS3D_PLACE_CACHE, NJIT, VORONOI3D_CUT_RTOL, VORONOI3D_STOP_RTOL
from .cellcut3d import (
    BROKEN,
    EMPTY,
    NJIT_NO_NRT,
    OK,
    OVERFLOW,
    SLOW,
    UNNAMED,
    cut_scratch,
    graph_scratch,
    offset_cache,
    one_cell,
    owner_key,
    radius2,
)
from .containercut3d import container_cut
from .graph3d import from_rings
from .merge3d import merge_named
from .polyhedron import moments
from .predicates3d import bisector_side, scratch, wall_lift
from .star3d import DECLINE, merge_star, star_cell
from .vertex3d import CANCEL, axis_snap, name_key, name_vertex, place

# the status codes are :mod:`kernels.cellcut3d`'s; the engine reads them from here
__all__ = [
    "BROKEN",
    "EMPTY",
    "OK",
    "OVERFLOW",
    "UNNAMED",
    "build_cells",
    "cell_scratch",
    "container_cut",
]

PLACE_CACHE = CELLS3D_PLACE_CACHE


@njit(**{**NJIT_NO_NRT, "inline": "always"})
def _place_cached(name, P, W, WP, ns, y, x, X):
    """:func:`.vertex3d.place` of vertex ``name``, its exact points cached by name in ``X[5:7]``.

    A vertex near the origin among far sites (the centre of points on a sphere) is solved
    exactly (three expansion determinants) by each of its cells; the point depends on the
    name alone, so a cell built after a neighbour on the same thread reads its bits.
    """
    a = name[0]
    big = 0.0
    small = 0.0
    for q in range(3):
        x[q] = P[a, q] + y[q]
        big = max(big, abs(P[a, q]), abs(y[q]))
        small = max(small, abs(x[q]))
    if not small < CANCEL * big:
        return
    PK = X[5]
    PV = X[6]
    h = np.uint64(0x9E3779B97F4A7C15)
    for q in range(4):
        h ^= np.uint64(name[q])
        h *= np.uint64(0xBF58476D1CE4E5B9)
        h ^= h >> np.uint64(31)
    e = np.int64(h & np.uint64(PK.shape[0] - 1))
    if PK[e, 0] == name[0] and PK[e, 1] == name[1] and PK[e, 2] == name[2] and PK[e, 3] == name[3]:
        for q in range(3):
            x[q] = PV[e, q]
        return
    if place(name, P, W, WP, ns, y, x, X[1]):  # exact: a function of the name alone
        for q in range(4):
            PK[e, q] = name[q]
        for q in range(3):
            PV[e, q] = x[q]


@njit(**NJIT_NO_NRT)
def _on_plane(i, v, key, OWN, work, nfo, P, W, WP, ns, X):
    """Whether vertex ``v`` of cell ``i`` lies exactly on the plane of ``key``.

    The vertex is defined by the first independent triple of its ``nfo[v]`` face owners
    (``OWN[v, 1:]``, after ``i``); without one the float filter's answer (yes) stands.
    """
    m = nfo[v]
    for a in range(1, m):
        for b in range(a + 1, m):
            for c in range(b + 1, m):
                # int64 keys (OWN is int32): bisector_side's one signature
                r = bisector_side(
                    i,
                    np.int64(OWN[v, a]),
                    np.int64(OWN[v, b]),
                    np.int64(OWN[v, c]),
                    key,
                    P,
                    W,
                    WP,
                    ns,
                    X[0],
                    X[1],
                )
                if r != 2:
                    return r == 0
    return True


@njit(**NJIT_NO_NRT)
def _mark_owners(
    i, V, nv, nx, ny, nz, h, tol, key, OWN, work, nfo, todo, nd, P, W, WP, ns, X, past
):
    """Add owner ``key`` to every vertex of ``todo[:nd]`` on the plane ``n . v = h``.

    ``tol`` is the float filter; candidates within it are decided exactly (:func:`_on_plane`).
    Returns False when a vertex has more owners than ``OWN`` has room for, unless ``past``:
    then they are counted past its row (``work[v, 0]`` beyond its width), for a vertex that
    the cell's big polytope names (:func:`_name_cell`).
    """
    ok = True
    for t in range(nd):
        v = todo[t]
        s = nx * V[v, 0] + ny * V[v, 1] + nz * V[v, 2] - h
        if abs(s) <= tol and _on_plane(i, v, key, OWN, work, nfo, P, W, WP, ns, X):
            c = work[v, 0]
            if c < OWN.shape[1]:
                OWN[v, c] = key
                work[v, 0] = c + 1
            elif past:
                work[v, 0] = c + 1
            else:
                ok = False
    return ok


@njit(**NJIT_NO_NRT)
def _name_cell(
    i,
    P,
    W,
    WP,
    ns,
    V,
    nv,
    F,
    nf,
    R,
    T,
    nt,
    OWN,
    work,
    vnames,
    vabs,
    vrel,
    rows,
    y,
    name,
    x,
    keys,
    G,
    X,
    BG,
    bkeys,
    GN,
):
    """Owners, names and named coordinates of the cell's vertices; returns status.

    A vertex's owners are ``i``, the owners of its faces, and every other plane it lies on
    exactly. With a vertex graph ``G`` only the flagged vertices (found on a plane during the
    cut) can have those, so only they are tested against the planes that touched the cell
    and the walls; without one (face rings) every vertex is. ``rows (3, 4)``, ``y (3,)``,
    ``name (4,)``, ``x (3,)`` and ``keys`` (``OWN``'s width) are scratch; ``X`` the exact
    predicates'. ``BG = (bigof, bstart, bsite)``: a vertex named by four sites of cell
    ``i``'s big polytope is its centre, whose owners are all its sites (and the walls found
    here): named from them (:func:`_big_keys`, into ``bkeys``), as a cell that found every
    one of them names it. ``GN (ns,) bool`` (or empty): sites whose cells are empty (outside
    the container, touching it at most); they own no vertex, so they are not counted in
    the vertex's owner sites (its name is unchanged).
    """
    graph = G[0].shape[0] > 0
    nfo = work[:, 1]
    todo = work[:, 2]
    for v in range(nv):
        OWN[v, 0] = i
        work[v, 0] = 1
    if graph:
        DEG = G[0]
        LB = G[3]
        FL = G[6]
        nd = 0
        for v in range(nv):
            c = 1
            for k in range(DEG[v]):
                if c < OWN.shape[1]:
                    OWN[v, c] = owner_key(LB[v, k], ns)
                    c += 1
            work[v, 0] = c
            if FL[v]:
                todo[nd] = v
                nd += 1
    else:
        for f in range(nf):
            key = owner_key(F[f, 0], ns)
            for k in range(F[f, 2]):
                v = R[F[f, 1] + k]
                c = work[v, 0]
                if c < OWN.shape[1]:
                    OWN[v, c] = key
                    work[v, 0] = c + 1
        nd = nv
        for v in range(nv):
            todo[v] = v
    for v in range(nv):
        nfo[v] = work[v, 0]
    # every plane that cut or touched the cell, and every wall: on it exactly?
    px = P[i, 0]
    py = P[i, 1]
    pz = P[i, 2]
    # a vertex of more owners than OWN holds may be the cell's big polytope's centre
    past = BG[0].shape[0] > 0 and BG[0][i] >= 0
    if nd > 0:
        rmax2 = radius2(V, nv)
        for u in range(nt):
            j = T[u, 0]
            dx = P[j, 0] - px
            dy = P[j, 1] - py
            dz = P[j, 2] - pz
            d2 = dx * dx + dy * dy + dz * dz
            h = 0.5 * (d2 + (W[i] - W[j]))
            if h > 0.0 and h * h > rmax2 * d2 * (1.0 + VORONOI3D_STOP_RTOL):
                continue  # beyond every vertex of the finished cell
            tol = VORONOI3D_CUT_RTOL * (np.sqrt(d2 * rmax2) + abs(h))
            if not _mark_owners(
                i, V, nv, dx, dy, dz, h, tol, j, OWN, work, nfo, todo, nd, P, W, WP, ns, X, past
            ):
                return OVERFLOW
        for w in range(WP.shape[0]):
            nx = WP[w, 0]
            ny = WP[w, 1]
            nz = WP[w, 2]
            h = wall_lift(WP, w, px, py, pz)
            nn = np.sqrt(nx * nx + ny * ny + nz * nz)
            tol = VORONOI3D_CUT_RTOL * (nn * np.sqrt(rmax2) + abs(h))
            k = ns + w
            if not _mark_owners(
                i, V, nv, nx, ny, nz, h, tol, k, OWN, work, nfo, todo, nd, P, W, WP, ns, X, past
            ):
                return OVERFLOW
    for v in range(nv):
        c = min(work[v, 0], OWN.shape[1])
        cut_short = work[v, 0] > c  # owners past the table: named by the big polytope, or none
        # sort and dedupe the owners
        m = c
        if c == 4:  # the usual vertex (three faces): a sorting network, no branches
            k0 = min(OWN[v, 0], OWN[v, 1])
            k1 = max(OWN[v, 0], OWN[v, 1])
            k2 = min(OWN[v, 2], OWN[v, 3])
            k3 = max(OWN[v, 2], OWN[v, 3])
            keys[0] = min(k0, k2)
            keys[3] = max(k1, k3)
            k0 = max(k0, k2)
            k1 = min(k1, k3)
            keys[1] = min(k0, k1)
            keys[2] = max(k0, k1)
        else:
            for t in range(c):
                keys[t] = OWN[v, t]
            for a in range(1, m):
                ka = keys[a]
                b = a - 1
                while b >= 0 and keys[b] > ka:
                    keys[b + 1] = keys[b]
                    b -= 1
                keys[b + 1] = ka
        u = np.int64(0)  # not a literal: name_vertex and axis_snap compile once
        for t in range(m):
            if u == 0 or keys[t] != keys[u - 1]:
                keys[u] = keys[t]
                u += 1
        kk = keys  # then (a big polytope's centre) bkeys: one inlined name_vertex, not two
        r = 0
        for rep in range(2 if u >= 4 else 0):
            r = name_vertex(kk, u, P, W, WP, ns, rows, y, name, X[1])
            if rep == 1 or r == 0 or BG[0].shape[0] == 0 or BG[0][i] < 0:
                break
            u2 = _big_keys(BG, BG[0][i], name, keys, u, ns, bkeys)
            if u2 <= 0:  # (else the big polytope's centre: named from all its sites)
                break
            kk = bkeys
            u = u2
            cut_short = False
        if cut_short:
            return OVERFLOW
        if r == 0:
            return UNNAMED
        a = name[0]
        for q in range(4):
            vnames[v, q] = name[q]
        nsite = 0
        for t in range(u):
            if kk[t] < ns and not (GN.shape[0] > 0 and GN[kk[t]]):
                nsite += 1
        # the join's identity besides the coordinates, and the owner sites (osite)
        vnames[v, 4] = (name_key(u, name) << 8) | min(nsite, 255)
        _place_cached(name, P, W, WP, ns, y, x, X)  # x = p_a + y, or exact where that cancels
        if r == 2:  # solved exactly (walls at small angles): merge by name as exact cells do
            X[2][0] = True
        axis_snap(kk, u, ns, WP, x)
        for q in range(3):
            vabs[v, q] = x[q]
            if x[q] == P[a, q] + y[q]:
                vrel[v, q] = (P[a, q] - P[i, q]) + y[q]
            else:  # snapped onto a wall
                vrel[v, q] = x[q] - P[i, q]
    return OK


@njit(**NJIT_NO_NRT)
def _big_keys(BG, q, name, keys, u, ns, bkeys):
    """All owners of big polytope ``q``'s centre into ``bkeys``, if ``name`` names it.

    ``name`` (four keys) names the centre when all four are sites of the polytope: four
    independent sites on its empty sphere meet only there. The owners are then the
    polytope's sites (``BG[2]``, increasing) and the walls among ``keys[:u]`` (the found
    owners, sorted: walls last). Returns their number, or 0 (another vertex).
    """
    bstart = BG[1]
    bsite = BG[2]
    lo0 = bstart[q]
    hi0 = bstart[q + 1]
    for t in range(4):
        k = name[t]
        if k >= ns:
            return 0
        lo = lo0
        hi = hi0
        while lo < hi:  # binary search in the polytope's sorted sites
            mid = (lo + hi) // 2
            if bsite[mid] < k:
                lo = mid + 1
            else:
                hi = mid
        if lo == hi0 or bsite[lo] != k:
            return 0
    m = 0
    for t in range(lo0, hi0):
        bkeys[m] = bsite[t]
        m += 1
    for t in range(u):
        if keys[t] >= ns:
            bkeys[m] = keys[t]
            m += 1
    return m


@njit(**NJIT)
def cell_scratch(ns, g, tree, TV, TF, TR, caps):
    """The working space of :func:`build_cells` for ``ns`` sites, grid ``g``, template, ``caps``.

    Made once per thread and passed to every call of :func:`build_cells` on these inputs
    (zeroing ~1 MB of scratch cost ~0.13 ms a call: 3,900 calls at 1e6 sites on two
    threads). Every cell writes what it reads, so reuse does not change a result.
    """
    # the most buckets one shell holds (kernels.grid3d.shell_buckets): full rows on the
    # two z-planes and two y-rows, two ends of every other row; not the whole grid, which
    # at 1e7 cells made every block's scratch fault in hundreds of megabytes
    nx = int(g[6])
    ny = int(g[7])
    nz = int(g[8])
    nbuck = min(nx * ny * nz, 2 * (nx * ny + nx * nz + ny * nz))
    kd = tree.shape[0] > 0
    if kd:  # the k-d walk's heap: each node at most once
        nbuck = max(nbuck, tree.shape[0])
    V, F, R, R2, S, work, T, OWN, cand, cd2, buck = cut_scratch(
        caps[3], caps[4], caps[5], max(1024, min(ns, 1 << 16)), nbuck
    )
    hkey = np.empty(nbuck if kd else 0)  # noqa: TID251 (the k-d heap's keys: written first)
    ib = np.zeros(6, np.int64)  # the shells' reach (cellcut3d._reach_box)
    tb = np.zeros((3, max(nx, ny, nz, 8)))  # (8: the ordered entries' gap rows too)
    NM = (
        np.zeros((caps[3], 5), np.int64),  # vnames
        np.zeros((caps[3], 3)),  # vabs
        np.zeros((caps[3], 3)),  # vrel
        np.zeros(caps[3], np.int64),  # remap
        np.zeros((3, 4)),  # rows
        np.zeros(3),  # y
        np.zeros(4, np.int64),  # name
        np.zeros(3),  # x
        np.zeros(OWN.shape[1], np.int64),  # keys
    )
    C = (V, F, R, R2, S, work, T)
    G = graph_scratch(caps[3], caps[6])
    G0 = graph_scratch(np.int64(0), np.int64(1))  # no graph: face rings
    TDEG, TED, TBK, TLB, _, _, _ = graph_scratch(max(TV.shape[0], 1), caps[6])
    # the exact predicates' scratch, whether the cell needed them, _cached_vertex's cache
    XK, XF = offset_cache(caps[3])
    # (and the exact points of named vertices, by name: _place_cached)
    PK = np.full((PLACE_CACHE, 4), -1, np.int64)
    X = (
        np.zeros((2, 4, 4)),
        scratch(),
        np.zeros(1, np.bool_),
        XK,
        XF,
        PK,
        np.zeros((PLACE_CACHE, 3)),
    )
    if not from_rings(TV.shape[0], TF, TF.shape[0], TR, TDEG, TED, TBK, TLB):
        G = G0
    TG = (TDEG, TED, TBK, TLB)
    return C, OWN, cand, cd2, buck, hkey, ib, tb, NM, G, G0, TG, X


@njit(**NJIT)
def _build_cells(
    cells,
    P,
    W,
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
    WP,
    caps,
    wmax,
    status,
    counts,
    vol,
    cen,
    rad2,
    osite,
    ovabs,
    ofaces,
    oring,
    scr,
    big=None,
    done=None,
    gone=None,
):
    """Build the cells ``cells (k,)`` (site numbers); ``wmax`` is ``W``'s largest weight.

    Per cell ``c`` (position in ``cells``), with ``caps = (cv, cf, cr, scratch_v, scratch_f,
    scratch_r, graph_degree)``: its vertices' absolute coordinates ``ovabs[c * cv:...]`` and
    their numbers of owner sites ``osite`` (the cells that share the vertex); faces
    ``ofaces[c * cf:...] = (label, length)`` and their rings ``oring[c * cr:...]`` of local
    vertex numbers (outward); ``counts[c] = (nv, nf, nr)``; ``vol``, ``cen`` (absolute),
    ``rad2`` (squared radius from the site); a cell past its output slots is ``OVERFLOW``
    with the counts it needs (0 when its scratch overflowed first). ``scr`` is the working space of
    :func:`cell_scratch`, made once per thread for these sites, grid, template and caps.
    ``big``: ``(bigof, bstart, bsite)`` of candidate lists' big polytopes
    (:func:`.candidates3d.candidate_lists`; their centres named from all their sites), or
    None. A cell whose vertex has more owners than ``OWN`` holds is ``SLOW`` where the grid
    has a budget (``g[9] > 0``: the engine builds it from its list), else ``OVERFLOW``.
    ``done``: ``(k,) bool``, cells already built (read off their Delaunay star by
    :func:`_star_cells`, the caller's first pass), or empty/None. ``gone``:
    ``(ns,) bool``, sites whose cells are empty (not counted as owner sites), or empty/None.
    """
    k = cells.shape[0]
    ns = P.shape[0]
    C, OWN, cand, cd2, buck, hkey, ib, tb, NM, G, G0, TG, X = scr
    vnames, vabs, vrel, remap, rows, y, name, x, keys = NM
    V, F, R, _, _, work, T = C
    if big is None:
        BG = (np.full(0, -1, np.int64), np.zeros(1, np.int64), np.zeros(0, np.int64))
    else:
        BG = big
    GN = np.zeros(0, np.bool_) if gone is None else gone
    most = 0  # the largest big polytope: bkeys holds it and the walls
    for q in range(BG[1].shape[0] - 1):
        most = max(most, BG[1][q + 1] - BG[1][q])
    bkeys = np.zeros(most + WP.shape[0] + 1, np.int64)
    budget = g.shape[0] > 9 and g[9] > 0.0
    DN = np.zeros(0, np.bool_) if done is None else done
    for c in range(k):
        if DN.shape[0] > 0 and DN[c]:
            continue
        i = cells[c]
        X[2][0] = False
        Gu = G
        while True:
            st, nv, nf, nt, r2 = one_cell(
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
                Gu,
                cand,
                cd2,
                buck,
                hkey,
                ib,
                tb,
            )
            if st != BROKEN or Gu[0].shape[0] == 0:
                break
            Gu = G0  # the graph could not: face rings
        counts[c, 0] = 0
        counts[c, 1] = 0
        counts[c, 2] = 0
        vol[c] = 0.0
        cen[c, 0] = np.nan
        cen[c, 1] = np.nan
        cen[c, 2] = np.nan
        rad2[c] = r2
        if st != OK:
            status[c] = st
            continue
        st = _name_cell(
            i,
            P,
            W,
            WP,
            ns,
            V,
            nv,
            F,
            nf,
            R,
            T,
            nt,
            OWN,
            work,
            vnames,
            vabs,
            vrel,
            rows,
            y,
            name,
            x,
            keys,
            Gu,
            X,
            BG,
            bkeys,
            GN,
        )
        if st == OVERFLOW and budget:
            st = SLOW  # a vertex of more owners than OWN holds: from its list
        if st != OK:
            status[c] = st
            continue
        if X[2][0] or Gu[0].shape[0] == 0:
            nv, nf, nr = merge_named(nv, F, nf, R, vnames, vabs, vrel, remap, work)
        else:  # no vertex came within the filter's band of a plane: all are distinct
            nr = 0
            for f in range(nf):
                nr += F[f, 2]
        _finish(
            c,
            i,
            P,
            nv,
            nf,
            nr,
            F,
            R,
            vnames,
            vabs,
            vrel,
            caps,
            status,
            counts,
            vol,
            cen,
            rad2,
            osite,
            ovabs,
            ofaces,
            oring,
        )


@njit(**NJIT)
def _star_cells(
    cells,
    P,
    W,
    WP,
    start,
    caps,
    status,
    counts,
    vol,
    cen,
    rad2,
    osite,
    ovabs,
    ofaces,
    oring,
    scr,
    star,
    done,
):
    """The cells of long candidate lists read off their Delaunay stars (list mode, first).

    ``star``: every site's Delaunay star (:func:`.star3d.star_cell`'s ``ST``, its last entry
    ``[least]``): a cell whose list has at least ``least`` sites is read off its star where
    the container does not cut it; its outputs are written as :func:`_build_cells` writes
    them and ``done[c]`` set (the cut then skips it). A kernel of its own, so that only a
    process that builds such cells compiles it (star_cell and merge_star: ~10 of the 3D
    warm-up's 189 CPU s when this was a branch of :func:`_build_cells`, in every process).
    """
    k = cells.shape[0]
    ns = P.shape[0]
    C, _, _, _, _, _, _, _, NM, _, _, _, X = scr
    vnames, vabs, vrel, remap = NM[0], NM[1], NM[2], NM[3]
    V, F, R, _, _, _, T = C
    least = star[7][0]
    # its scratch (per polytope, per site)
    m = star[5].shape[0]
    mark = (np.zeros(m, np.int64), np.zeros(m, np.int64), np.zeros(ns, np.int64))
    scaps = np.array([V.shape[0], F.shape[0], R.shape[0]], np.int64)
    vbits = vabs.view(np.int64)
    for c in range(k):
        i = cells[c]
        if start[i + 1] - start[i] < least:
            continue
        X[2][0] = False
        st, nv, nf, nr = star_cell(i, P, W, WP, star, F, R, NM, X[1], mark, scaps)
        if st == DECLINE:
            continue  # cut as any other cell
        done[c] = True
        counts[c, 0] = nv
        counts[c, 1] = nf
        counts[c, 2] = nr
        vol[c] = 0.0
        cen[c, 0] = np.nan
        cen[c, 1] = np.nan
        cen[c, 2] = np.nan
        rad2[c] = 0.0
        if st != OK:
            status[c] = OVERFLOW  # its scratch: the engine's retry reads the counts
            continue
        nv, nf, nr = merge_star(nv, F, nf, R, vnames, vabs, vrel, remap, vbits, T[:, 0])
        rad2[c] = radius2(vrel, nv)
        _finish(
            c,
            i,
            P,
            nv,
            nf,
            nr,
            F,
            R,
            vnames,
            vabs,
            vrel,
            caps,
            status,
            counts,
            vol,
            cen,
            rad2,
            osite,
            ovabs,
            ofaces,
            oring,
        )


@njit(**{**NJIT_NO_NRT, "inline": "always"})
def _finish(
    c,
    i,
    P,
    nv,
    nf,
    nr,
    F,
    R,
    vnames,
    vabs,
    vrel,
    caps,
    status,
    counts,
    vol,
    cen,
    rad2,
    osite,
    ovabs,
    ofaces,
    oring,
):
    """Cell ``c`` (site ``i``), named and merged, into its output slots (or ``OVERFLOW``)."""
    cv = caps[0]
    cf = caps[1]
    cr = caps[2]
    if nv > cv or nf > cf or nr > cr:
        status[c] = OVERFLOW  # with the sizes it needs (the engine's retry reads them)
        counts[c, 0] = nv
        counts[c, 1] = nf
        counts[c, 2] = nr
        return
    if nf < 4:
        status[c] = EMPTY
        return
    status[c] = OK
    counts[c, 0] = nv
    counts[c, 1] = nf
    counts[c, 2] = nr
    v0, mx, my, mz = moments(vrel, F, nf, R)
    vol[c] = v0
    if v0 > 0.0:
        cen[c, 0] = P[i, 0] + mx / v0
        cen[c, 1] = P[i, 1] + my / v0
        cen[c, 2] = P[i, 2] + mz / v0
    bv = c * cv
    for v in range(nv):
        osite[bv + v] = vnames[v, 4]  # name key << 8 | owner sites
        for q in range(3):
            ovabs[bv + v, q] = vabs[v, q] + 0.0  # one zero: -0.0 + 0.0 == +0.0
    bf = c * cf
    br = c * cr
    t = 0
    for f in range(nf):
        ofaces[bf + f, 0] = F[f, 0]
        ofaces[bf + f, 1] = F[f, 2]
        for q in range(F[f, 2]):
            oring[br + t] = R[F[f, 1] + q]
            t += 1


#: ``build_cells``' stand-ins for None: no big polytopes, no cells built before the cut
_NO_BIG = (np.full(0, -1, np.int64), np.zeros(1, np.int64), np.zeros(0, np.int64))
_NO_DONE = np.zeros(0, np.bool_)
_NO_GONE = np.zeros(0, np.bool_)


class _OneSignature:
    """:func:`_build_cells` with ``big``, ``done`` and ``gone`` always arrays: one signature.

    None is passed as :data:`_NO_BIG` / an empty ``done`` / an empty ``gone`` (what the
    kernel made of None), so the grid's cells, the lists' and a big vertex's ``(big,
    None)`` share one compile of the kernel instead of three (~9 s each on a cold cache).
    A ``star`` (list mode, :mod:`.lists3d`) is read by :func:`_star_cells` first, only where
    a cell's list is long enough for it, so its compile is paid only where it is used.
    ``signatures`` is the kernel's.
    """

    def __call__(self, *args):
        fixed, opt = args[:26], (*args[26:], None, None, None)
        big, star, gone = opt[:3]
        big = _NO_BIG if big is None else big
        done = _NO_DONE
        cells, start, g = fixed[0], fixed[3], fixed[7]
        if star is not None and len(g) > 9 and g[9] < 0.0 and len(cells):
            least = star[7][0]
            if (start[cells + 1] - start[cells] >= least).any():
                done = np.zeros(len(cells), np.bool_)
                W, WP, caps = fixed[2], fixed[13], fixed[14]
                out = fixed[16:25]  # status, counts, vol, cen, rad2, osite, ovabs, ofaces, oring
                _star_cells(cells, fixed[1], W, WP, start, caps, *out, fixed[25], star, done)
        return _build_cells(*fixed, big, done, _NO_GONE if gone is None else gone)

    @property
    def signatures(self):
        return _build_cells.signatures


build_cells = _OneSignature()
