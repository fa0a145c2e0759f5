"""``Diagram3D.describe``: counts and checks of a 3D diagram."""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import CONVEX3D_RTOL, CONVEX3D_ULPS, NJIT

EPS = float(np.finfo(np.float64).eps)


def _norm(a: np.ndarray) -> float:
    """``|a|``, computed on ``a`` scaled by a power of two.

    Its square neither overflows nor underflows; the same bits as ``np.linalg.norm(a)``
    wherever that does not.
    """
    big = float(np.abs(a).max())
    if big == 0.0 or not np.isfinite(big):
        return big
    e = int(np.frexp(big)[1])
    return float(np.ldexp(np.linalg.norm(np.ldexp(a, -e)), e))


def _perimeter(r: np.ndarray) -> float:
    """The perimeter of the ring of points ``r (k, 3)`` (scaled as :func:`_norm`)."""
    e = r - np.roll(r, 1, axis=0)
    big = float(np.abs(e).max())
    if big == 0.0 or not np.isfinite(big):
        return big
    k = int(np.frexp(big)[1])
    return float(np.ldexp(np.linalg.norm(np.ldexp(e, -k), axis=1).sum(), k))


def unmatched_on_faces(d) -> int:
    """Vertices of a face between two cells that the cell across does not reference.

    The count behind ``Diagram3D.unmatched_vertices`` on a torus and for power cells with
    empty ones: a vertex's owner sites there include images (whose cells are other sites'
    cells, holding the vertex as another record, shifted) and sites whose cells are empty
    (no faces, no vertices), which the cell builder's count of references against owners
    took as missing. Here each cell face toward a site in the same frame (no shift) names
    the owners that must reference each of its vertices: the cell across, which owns them
    whenever it shares a face of positive area (a vertex named differently by two cells is
    counted, as before).
    """
    cf, lab, _, roff, ring = d.cell_face_table()
    shifted = np.zeros(len(lab), np.bool_)
    if d.face_shifts is not None:
        shifted = np.ascontiguousarray((d.face_shifts != 0).any(axis=1))
    order = np.argsort(lab, kind="stable")
    return int(_unmatched(cf, lab, roff, ring, shifted, order, len(d.vertices)))


@njit(**NJIT)
def _unmatched(cf, lab, roff, ring, shifted, order, nv):
    """Count of the vertices of unshifted site faces missing from the cell across.

    ``order`` sorts the faces by label: cell ``t``'s vertices are stamped, then every face
    labelled ``t`` is checked against the stamps.
    """
    stamp = np.full(nv, -1, np.int64)
    bad = np.zeros(nv, np.bool_)
    owner = np.zeros(lab.shape[0], np.int64)  # the cell of each face
    for i in range(cf.shape[0] - 1):
        for f in range(cf[i], cf[i + 1]):
            owner[f] = i
    q = 0
    while q < order.shape[0]:
        t = lab[order[q]]
        e = q
        while e < order.shape[0] and lab[order[e]] == t:
            e += 1
        if t >= 0:
            for f in range(cf[t], cf[t + 1]):
                for r in range(roff[f], roff[f + 1]):
                    stamp[ring[r]] = t
            for k in range(q, e):
                f = order[k]
                if shifted[f] or owner[f] == t:
                    continue
                for r in range(roff[f], roff[f + 1]):
                    if stamp[ring[r]] != t:
                        bad[ring[r]] = True
        q = e
    return np.count_nonzero(bad)


def _pieces(ring, roff, f0, f1) -> int:
    """Connected pieces of the faces ``f0:f1`` (faces sharing a vertex are connected)."""
    parent: dict = {}

    def root(v):
        while parent.setdefault(v, v) != v:
            parent[v] = parent[parent[v]]
            v = parent[v]
        return v

    for f in range(f0, f1):
        r = ring[roff[f] : roff[f + 1]].tolist()
        a = root(r[0])
        for v in r[1:]:
            b = root(v)
            if a != b:
                parent[b] = a
    return len({root(v) for v in list(parent)})


def _components(n: int, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Component label of each of ``n`` nodes joined by the pairs ``(a[k], b[k])``."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    g = coo_matrix((np.ones(len(a), np.int8), (a, b)), shape=(n, n))
    return connected_components(g, directed=False)[1]


def _mates(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``(P, m)``: for each point of ring ``a[p]``, its partner's position in ring ``b[p]``.

    ``a``, ``b`` are ``(P, m, 3)``: pairs of rings that are the same polygon, rounded apart.
    Each pair is matched as a whole: the cyclic shift, in either direction, with the least
    summed squared distance (vertices closer than the rounding of a shift by the period
    keep their order).
    """
    m = a.shape[1]
    d = ((a[:, :, None, :] - b[:, None, :, :]) ** 2).sum(axis=3)  # (P, m, m)
    k = np.arange(m)
    shifts = np.concatenate([(k[:, None] + sign * k[None, :]) % m for sign in (-1, 1)])
    cost = d[:, k[None, :], shifts].sum(axis=2)  # (P, 2m): row c maps a[k] -> b[shifts[c, k]]
    return shifts[np.argmin(cost, axis=1)]


def torus_counts(d) -> tuple[int, int, int]:
    """``V, E, F`` of a periodic diagram counted on the 3-torus, not per image record.

    ``vertices`` holds a vertex once for each image of the box its cells reach it in, each
    rounded on its own, so records cannot be identified by their coordinates. The faces tell
    which records are one: face ``f`` of cell ``i`` toward the image of ``t`` shifted by
    ``s`` periods is, moved by ``-s`` periods, face ``g`` of cell ``t`` toward ``i``
    shifted by ``-s`` (its twin, the same polygon in ``t``'s frame). The vertices of ``g``
    moved back by ``s`` periods are matched to those of ``f`` (:func:`_mates`; a pair of
    rings of different lengths, where rounding shortened an edge to a point in one, by
    nearest points) and the matched records are united, and so are the edges between
    matched ends. A face and its twin count once.
    """
    cf, lab, _, roff, ring = d.cell_face_table()
    V = np.asarray(d.vertices)
    lo, hi = np.asarray(d.box, float).reshape(2, 3)
    period = hi - lo
    shifts = np.asarray(d.face_shifts, np.int64)
    owner = np.repeat(np.arange(len(cf) - 1), np.diff(cf))
    keys = np.column_stack([owner, lab, shifts])
    where = {k: f for f, k in enumerate(map(tuple, keys.tolist()))}
    twin = np.array(
        [where.get(k, -1) for k in map(tuple, keys[:, [1, 0, 2, 3, 4]] * [1, 1, -1, -1, -1])],
        np.int64,
    ).reshape(-1)
    f = np.flatnonzero(twin > np.arange(len(lab)))  # each pair once, from its first face
    faces = len(f) + int(np.count_nonzero(twin < 0))
    g = twin[f]
    length = np.diff(roff)
    va, vb, ea, eb = [], [], [], []  # united records: g's record, f's; g's edge, f's
    lf, lg = length[f], length[g]
    for m in np.unique(lf[lf == lg]).tolist():  # pairs of one length, matched by shifts
        pick = (lf == m) & (lg == m)
        pf, pg = f[pick], g[pick]
        rf = ring[roff[pf][:, None] + np.arange(m)]
        rg = ring[roff[pg][:, None] + np.arange(m)]
        at = _mates(V[rg] + (shifts[pf] * period)[:, None, :], V[rf])
        mate = np.take_along_axis(rf, at, axis=1)
        va.append(rg.ravel())
        vb.append(mate.ravel())
        ea.append(np.stack([rg, np.roll(rg, -1, axis=1)], axis=2).reshape(-1, 2))
        eb.append(np.stack([mate, np.roll(mate, -1, axis=1)], axis=2).reshape(-1, 2))
    for k in np.flatnonzero(lf != lg).tolist():  # rounding shortened an edge in one copy
        fi, gi = int(f[k]), int(g[k])
        rf, rg = ring[roff[fi] : roff[fi + 1]], ring[roff[gi] : roff[gi + 1]]
        dist = ((V[rg] + shifts[fi] * period)[:, None, :] - V[rf][None, :, :]) ** 2
        mate = rf[np.argmin(dist.sum(axis=2), axis=1)]
        va.append(rg)
        vb.append(mate)
        ea.append(np.column_stack([rg, np.roll(rg, -1)]))
        eb.append(np.column_stack([mate, np.roll(mate, -1)]))
    used = np.unique(ring)
    lab_v = _components(
        len(V),
        np.concatenate(va or [[]]).astype(np.int64),
        np.concatenate(vb or [[]]).astype(np.int64),
    )
    nv = len(np.unique(lab_v[used]))
    # every cell's edges, keyed by their two records
    nxt = np.arange(1, len(ring) + 1)
    nxt[roff[1:] - 1] = roff[:-1]
    cell_e = np.sort(np.column_stack([ring, ring[nxt]]), axis=1)
    ea = np.sort(np.concatenate(ea or [np.zeros((0, 2), np.int64)]), axis=1)
    eb = np.sort(np.concatenate(eb or [np.zeros((0, 2), np.int64)]), axis=1)
    keep = eb[:, 0] != eb[:, 1]  # an edge the twin's rounding shortened to a point
    ea, eb = ea[keep], eb[keep]
    nvx = np.int64(len(V))
    allk, inv = np.unique(
        np.concatenate([c[:, 0] * nvx + c[:, 1] for c in (cell_e, ea, eb)]), return_inverse=True
    )
    n1, n2 = len(cell_e), len(cell_e) + len(ea)
    lab_e = _components(len(allk), inv[n1:n2], inv[n2:])
    ne = len(np.unique(lab_e[inv[:n1]]))
    return nv, ne, faces


def _cell_convex(d, cf, farea, roff, ring, i, verts) -> bool:
    """Whether cell ``i`` passes :func:`describe3d`'s convexity test, face by face.

    The plain loop, and the rule itself: ``verts`` are the cell's vertex numbers. The
    vectorised pass (:func:`_convexity`) decides every cell it can decide to the same bits
    and hands the rest (a face within a few ulps of a threshold) to this.
    """
    V = d.vertices[list(verts)]
    size = float(np.ptp(V, axis=0).max()) if len(V) else 0.0
    # the resolution: a fraction of the cell, or a few ulps of its coordinates where
    # those are coarser (a cell 4 wide at 7e13 has vertices an ulp, 0.0078, apart)
    res = max(CONVEX3D_RTOL * size, CONVEX3D_ULPS * EPS * float(np.abs(V).max(initial=0)))
    for f in range(cf[i], cf[i + 1]):
        a = farea[f]
        na = _norm(a)
        if na <= res * size:
            continue  # a face thinner than the resolution has no normal to test
        r = d.vertices[ring[roff[f] : roff[f + 1]]]
        p0 = r[0]
        # the normal of vertices each within res is good to res * perimeter / area (a
        # wall's sliver beside a nearly coplanar wall of a hull at UTM offsets: 1.1e-8
        # of area, its rounded normal put the cell's far vertices 4e-8 past it)
        tol = res * (1.0 + size * _perimeter(r) / na)
        if ((V - p0) @ (a / na)).max() > tol:
            return False
    return True


def _scaled_norms(a: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Row norms of ``a (m, 3)`` scaled as :func:`_norm` (``(norms, exponents)``)."""
    big = np.abs(a).max(axis=1, initial=0.0)
    ok = (big > 0) & np.isfinite(big)
    e = np.where(ok, np.frexp(np.where(ok, big, 1.0))[1], 0)
    return np.where(ok, np.ldexp(np.sqrt((np.ldexp(a, -e[:, None]) ** 2).sum(axis=1)), e), big), e


def _convexity(d, cf, farea, roff, ring, cv_ptr, cv_idx):
    """Per cell: 1 convex, 0 not, -1 undecided (a face within rounding of a threshold).

    :func:`_cell_convex`'s test on all faces at once. Its norms, dot products and
    perimeters are summed in other orders here, so each decision carries a margin that
    bounds those few ulps (dozens of them); a face inside its margin leaves the cell to
    the plain loop, so the answer is the loop's, bit for bit.
    """
    n = len(cf) - 1
    Vall = np.asarray(d.vertices)
    out = np.ones(n, np.int8)
    has = np.flatnonzero(np.diff(cv_ptr) > 0)
    if not len(has):
        return out
    Vc = Vall[cv_idx]
    starts = cv_ptr[has]
    size = np.zeros(n)
    size[has] = (
        np.maximum.reduceat(Vc, starts, axis=0) - np.minimum.reduceat(Vc, starts, axis=0)
    ).max(axis=1)
    amax = np.zeros(n)
    amax[has] = np.maximum.reduceat(np.abs(Vc).max(axis=1), starts)
    res = np.maximum(CONVEX3D_RTOL * size, CONVEX3D_ULPS * EPS * amax)
    nfc = np.diff(cf)
    owner = np.repeat(np.arange(n), nfc)
    flen = np.diff(roff)
    na, _ = _scaled_norms(farea)
    thr = (res * size)[owner]
    live = na > thr
    unsure = np.abs(na - thr) <= 16 * EPS * np.maximum(na, thr)
    # perimeters (each face's edges scaled by its biggest, as :func:`_perimeter`)
    prev = np.arange(-1, len(ring) - 1)
    full = flen > 0
    prev[roff[:-1][full]] = roff[1:][full] - 1
    e = Vall[ring] - Vall[ring[prev]]
    rface = np.repeat(np.arange(len(flen)), flen)
    big = np.zeros(len(flen))
    big[full] = np.maximum.reduceat(np.abs(e).max(axis=1), roff[:-1][full])
    ok = (big > 0) & np.isfinite(big)
    k = np.where(ok, np.frexp(np.where(ok, big, 1.0))[1], 0)
    el = np.sqrt((np.ldexp(e, -k[rface][:, None]) ** 2).sum(axis=1))
    per = np.zeros(len(flen))
    per[full] = np.add.reduceat(el, roff[:-1][full])
    per = np.where(ok, np.ldexp(per, k), big)
    safe = np.where(live, na, 1.0)
    tol = np.where(live, res[owner] * (1.0 + size[owner] * per / safe), 0.0)
    u = farea / safe[:, None]
    # the largest signed distance of the cell's vertices past each face
    smax = np.full(len(flen), -np.inf)
    wmax = np.zeros(len(flen))
    go = np.ascontiguousarray(live & (flen > 0))
    # writeable int64/float64 copies: one compiled signature whatever the diagram's arrays
    V64, ring64, roff64 = Vall.astype(np.float64), ring.astype(np.int64), roff.astype(np.int64)
    _reach(
        V64,
        cv_ptr.astype(np.int64),
        cv_idx.astype(np.int64),
        owner.astype(np.int64),
        ring64,
        roff64,
        u.astype(np.float64),
        go,
        smax,
        wmax,
    )
    margin = 64 * EPS * wmax + 4 * (flen + 16) * EPS * np.abs(tol)
    bad = live & (smax > tol + margin)
    near = (live & ~bad & (smax >= tol - margin)) | unsure | ~np.isfinite(na)
    near |= live & ((flen == 0) | ~np.isfinite(smax + tol + margin))
    bad_c = np.bincount(owner[bad], minlength=n) > 0
    near_c = np.bincount(owner[near], minlength=n) > 0
    out[bad_c] = 0
    out[~bad_c & near_c] = -1
    return out


@njit(**NJIT)
def _reach(V, cv_ptr, cv_idx, owner, ring, roff, u, go, smax, wmax):
    """Per face ``go`` picks: how far its cell's vertices reach past it, along ``u``.

    From the face's first vertex: the largest signed offset (nan where one is nan) into
    ``smax``, the largest offset's 1-norm into ``wmax``.
    """
    for f in range(owner.shape[0]):
        if not go[f]:
            continue
        c = owner[f]
        p = ring[roff[f]]
        best = -np.inf
        big = 0.0
        for k in range(cv_ptr[c], cv_ptr[c + 1]):
            v = cv_idx[k]
            wx = V[v, 0] - V[p, 0]
            wy = V[v, 1] - V[p, 1]
            wz = V[v, 2] - V[p, 2]
            s = wx * u[f, 0] + wy * u[f, 1] + wz * u[f, 2]
            if s != s:
                best = np.nan
                break
            best = max(best, s)
            big = max(big, abs(wx) + abs(wy) + abs(wz))
        smax[f] = best
        wmax[f] = big


def _cell_counts(n, cf, roff, ring, nv):
    """Per cell: vertices, unique edges, and the cells' vertex lists (CSR); all edges.

    Returns ``(verts (n,), edges (n,), cv_ptr (n + 1,), cv_idx, total_edges)``.
    """
    flen = np.diff(roff)
    rface = np.repeat(np.arange(len(flen)), flen)
    rcell = np.repeat(np.arange(n), np.diff(cf))[rface]
    nxt = np.arange(1, len(ring) + 1)
    full = flen > 0
    nxt[roff[1:][full] - 1] = roff[:-1][full]
    a = ring.astype(np.int64)
    b = a[nxt] if len(a) else a
    nvx = np.int64(max(nv, 1))
    ekey, einv = np.unique(np.minimum(a, b) * nvx + np.maximum(a, b), return_inverse=True)
    ne = np.int64(max(len(ekey), 1))
    ce = np.unique(rcell * ne + einv.reshape(-1))
    edges = np.bincount(ce // ne, minlength=n)
    cv = np.unique(rcell * nvx + a)
    cv_cell = cv // nvx
    verts = np.bincount(cv_cell, minlength=n)
    cv_ptr = np.r_[0, np.cumsum(verts)]
    return verts, edges, cv_ptr, cv - cv_cell * nvx, len(ekey)


def describe3d(d) -> dict:
    """V, E, F, C; the Euler check per cell; convexity; cells cut by a non-convex container.

    Returns a dict: ``vertices``, ``edges`` (unique undirected edges), ``faces`` (unique),
    ``cells`` (non-empty), ``euler_ok`` (every non-empty cell has ``V - E + F = 2``; one a
    mesh container cuts, an even ``V - E + F`` of at most 2 per connected piece: it may be
    split into pieces, and a piece may have handles),
    ``euler_failures`` (cell numbers), ``convex`` (every face's vertices on the inner side of
    every other face of its cell, to ``CONVEX3D_RTOL`` of the cell's size or
    ``CONVEX3D_ULPS`` ulps of its coordinates, whichever is coarser, plus the error that
    resolution makes in the face's normal (times the cell's size and the face's perimeter
    over its area); faces thinner than that are left out; cells a mesh container cuts are
    tested too, so a torus's cut cells make it ``False``: ``nonconvex_cells`` lists them),
    ``cut_cells`` (cells cut by a mesh container, else 0), ``unmatched_vertices``,
    ``volume`` and ``container_volume``.
    """
    cf, _, farea, roff, ring = d.cell_face_table()
    n = len(d)
    nvc, nec, cv_ptr, cv_idx, ne = _cell_counts(n, cf, roff, ring, len(d.vertices))
    nfc = np.diff(cf)
    chi = nvc - nec + nfc
    has = nfc > 0
    cut = np.zeros(n, np.bool_)
    if d.container == "mesh" and d.cut_cells is not None:
        # a cell the mesh cuts may be several closed pieces, each with handles (a piece
        # of a torus): every closed orientable surface has an even chi <= 2
        cut = np.asarray(d.cut_cells, np.bool_) & has
    fails = np.flatnonzero(has & ~cut & (chi != 2)).tolist()
    for i in np.flatnonzero(cut).tolist():
        c = int(chi[i])
        if c % 2 or c > 2 * _pieces(ring, roff, cf[i], cf[i + 1]):
            fails.append(i)
    fails.sort()
    # convexity of cut cells too: a non-convex container's cut cells are not convex
    with np.errstate(all="ignore"):  # whatever overflows is undecided: the loop decides it
        conv = _convexity(d, cf, farea, roff, ring, cv_ptr, cv_idx)
    for i in np.flatnonzero(has & (conv < 0)).tolist():
        conv[i] = _cell_convex(d, cf, farea, roff, ring, i, cv_idx[cv_ptr[i] : cv_ptr[i + 1]])
    nonconvex = np.flatnonzero(has & (conv == 0)).tolist()
    nv, nf = len(d.vertices), len(d.faces)
    cells = int((np.diff(cf) > 0).sum())
    expected = 1  # the cells subdivide a ball (a box or a convex solid)
    if d.periodic:
        nv, ne, nf = torus_counts(d)
        expected = 0  # the 3-torus
    elif d.container == "mesh":
        expected = None  # cut cells may be several pieces, faces not discs
    euler = nv - ne + nf - cells
    return {
        "vertices": nv,
        "edges": ne,
        "faces": nf,
        "cells": cells,
        "vertex_records": len(d.vertices),
        "euler": euler,
        "euler_expected": expected,
        "euler_ok": not fails and (expected is None or euler == expected),
        "euler_failures": fails,
        "convex": not nonconvex,
        "nonconvex_cells": nonconvex,
        "cut_cells": 0 if d.cut_cells is None else int(np.count_nonzero(d.cut_cells)),
        "unmatched_vertices": d.unmatched_vertices,
        "volume": float(np.sum(d.volumes)),
        "container_volume": d.container_volume,
    }
