"""Convex cells cut by a closed triangle mesh, exactly, where the surface allows it.

:func:`convex_cells` takes the cells that the surface meets (:mod:`kernels.meshclip3d`) and
cuts each by the planes of the triangles that meet it, when that is provably the cell ∩ the
solid: every triangle, clipped by the cell, lies inside every other one's half-space. A
cell where that fails (reflex edges, saddles) is first split into convex parts where it
holds, by the plane bisecting the wedge outside an inconsistent pair; the parts are joined
again. Each cell is checked (new faces lie in their triangles, the result is closed) and
left to the caller (manifold3d) otherwise. Polyhedra are held as :mod:`kernels.polyhedron`
holds them, relative to the cell's first vertex.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..config import MESH_MOMENT_SAFE, NJIT
from .meshclip3d import cell_buckets, clip_triangle
from .meshparts3d import SPLIT, merge_parts, split_face
from .meshparts3d import fail as _fail
from .polyhedron import (
    CUT_BROKEN,
    CUT_DONE,
    CUT_EMPTY,
    CUT_NONE,
    CUT_OVERFLOW,
    cut,
    plane_values,
    ring_count,
)

#: labels of the faces a container plane group ``g`` adds while a cell is cut: ``GROUP - g``
GROUP = -(1 << 40)
#: per-cell scratch and output limits of :func:`convex_cells` (past them: manifold3d)
CC_TRIS = 64  # triangles meeting one cell
CC_SEEN = 512  # distinct triangles looked at (in the cell's buckets)
CC_POLY = 64  # vertices of a triangle clipped by the cell
CC_V, CC_F, CC_R = 128, 64, 1024  # polyhedron scratch: vertices, faces, ring entries
CC_PARTS, CC_DEPTH = 6, 4  # parts a cell may be split into, split planes per part
CC_OUT_V, CC_OUT_F, CC_OUT_R = 96, 48, 384  # a finished cell's slots
CC_BLOCK = 64  # cells per parallel block (one set of scratch each)


@njit(**NJIT)
def _gather(i, cf, roff, ring, verts, farea, fpt, T, TO, lo, h, dims, start, items, tol, sc):
    """The triangles meeting cell ``i`` grown by ``tol``, clipped by it: their count, or -1.

    ``seen`` (one slot per triangle) holds the call (``tick``) that last looked at each
    triangle: a triangle in several of the cell's buckets is looked at once, without a
    search through those seen before (up to ``CC_SEEN`` of them: past that, -1).
    """
    ids, seen, pm, polys, buf_a, buf_b, tick = sc
    ny, nz = dims[1], dims[2]
    f0, f1 = cf[i], cf[i + 1]
    if f1 - f0 + 3 > polys.shape[1]:
        return -1
    tick[0] += 1
    stamp = tick[0]
    cell_lo, cell_hi, a0, a1 = cell_buckets(f0, f1, roff, ring, verts, tol, lo, h, dims)
    k = 0
    ns = 0
    for a in range(a0[0], a1[0] + 1):
        for b in range(a0[1], a1[1] + 1):
            for kk in range(a0[2], a1[2] + 1):
                bk = (a * ny + b) * nz + kk
                for s in range(start[bk], start[bk + 1]):
                    t = items[s]
                    if seen[t] == stamp:
                        continue
                    if ns == CC_SEEN:
                        return -1
                    seen[t] = stamp
                    ns += 1
                    away = False
                    for c in range(3):
                        x0 = min(T[t, 0, c], min(T[t, 1, c], T[t, 2, c]))
                        x1 = max(T[t, 0, c], max(T[t, 1, c], T[t, 2, c]))
                        if x1 < cell_lo[c] or x0 > cell_hi[c]:
                            away = True
                    if away:
                        continue
                    m, src = clip_triangle(T, t, f0, f1, farea, fpt, tol, buf_a, buf_b)
                    if m == 0:
                        continue
                    if k == ids.shape[0] or not np.isfinite(TO[t]):  # no room, no plane
                        return -1
                    ids[k] = t
                    pm[k] = m
                    for q in range(m):
                        for c in range(3):
                            polys[k, q, c] = src[q, c]
                    k += 1
    return k


@njit(**NJIT)
def _clip_poly(P, m, nx, ny, nz, hh, tol, dst):
    """Polygon ``P[:m]`` clipped to ``n . x <= hh + tol`` into ``dst``: its size."""
    k = 0
    sp = nx * P[m - 1, 0] + ny * P[m - 1, 1] + nz * P[m - 1, 2] - hh - tol
    for q in range(m):
        sq = nx * P[q, 0] + ny * P[q, 1] + nz * P[q, 2] - hh - tol
        if (sp <= 0.0) != (sq <= 0.0):
            p = q - 1 if q > 0 else m - 1
            r = sp / (sp - sq)
            for c in range(3):
                dst[k, c] = P[p, c] + r * (P[q, c] - P[p, c])
            k += 1
        if sq <= 0.0:
            for c in range(3):
                dst[k, c] = P[q, c]
            k += 1
        sp = sq
    return k


@njit(**NJIT)
def _beyond(sub, m, a, n, hh, tol):
    """Whether a vertex of polygon ``sub[a, :m]`` lies beyond ``n . x = hh`` by ``tol``."""
    for q in range(m):
        if n[0] * sub[a, q, 0] + n[1] * sub[a, q, 1] + n[2] * sub[a, q, 2] - hh > tol:
            return True
    return False


@njit(**NJIT)
def _finish_part(V, nv, F, nf, R, R2, S, work, k, use, grp, ids, T, TN, toff, o, tol):
    """Part ``(V, F, R)`` cut by the planes of its triangles (``use``), new faces labelled.

    Each new face is split along its triangles' edges and named by the one it lies in.
    Returns ``(ok, nv, nf)`` (``ok`` False: leave the cell to manifold3d).
    """
    for a in range(k):
        if grp[a] != a:
            continue
        inpart = False
        for b in range(k):
            if use[b] and grp[b] == a:
                inpart = True
        if not inpart:
            continue
        t = ids[a]
        plane_values(V, nv, TN[t, 0], TN[t, 1], TN[t, 2], toff[a], tol, S)
        st, nv, nf = cut(V, nv, F, nf, R, R2, S, work, GROUP - a)
        if st != CUT_NONE and st != CUT_DONE:
            return False, nv, nf
    # a face lying in a group's plane (not made by its cut): left to manifold3d
    has = False
    for f in range(nf):
        if SPLIT < F[f, 0] <= GROUP:
            has = True
            continue
        for a in range(k):
            if grp[a] != a:
                continue
            t = ids[a]
            allon = True
            for s in range(F[f, 1], F[f, 1] + F[f, 2]):
                v = R[s]
                sv = TN[t, 0] * V[v, 0] + TN[t, 1] * V[v, 1] + TN[t, 2] * V[v, 2] - toff[a]
                if abs(sv) > tol:
                    allon = False
                    break
            if allon:
                return False, nv, nf
    if not has:
        return False, nv, nf
    nr = ring_count(F, nf)
    # split each group's faces along its triangles' edges, then name each piece's triangle
    for a in range(k):
        if not use[a]:
            continue
        g = grp[a]
        t = ids[a]
        for e in range(3):
            p0 = T[t, e]
            p1 = T[t, (e + 1) % 3]
            dx = p1[0] - p0[0]
            dy = p1[1] - p0[1]
            dz = p1[2] - p0[2]
            ex = TN[t, 1] * dz - TN[t, 2] * dy  # inward, in the triangle's plane
            ey = TN[t, 2] * dx - TN[t, 0] * dz
            ez = TN[t, 0] * dy - TN[t, 1] * dx
            en = np.sqrt(ex * ex + ey * ey + ez * ez)
            if en == 0.0:
                return False, nv, nf
            ex /= en
            ey /= en
            ez /= en
            h0 = ex * (p0[0] - o[0]) + ey * (p0[1] - o[1]) + ez * (p0[2] - o[2])
            f = np.int64(0)  # not a literal: numba would compile split_face once more
            while f < nf:
                if F[f, 0] == GROUP - g:
                    plane_values(V, nv, ex, ey, ez, h0, tol, S)
                    lo_ = 0.0
                    hi_ = 0.0
                    for s in range(F[f, 1], F[f, 1] + F[f, 2]):
                        lo_ = min(lo_, S[R[s]])
                        hi_ = max(hi_, S[R[s]])
                    if lo_ < 0.0 and hi_ > 0.0:
                        ok, nv, nf, nr = split_face(V, nv, F, nf, R, nr, f, S)
                        if not ok:
                            return False, nv, nf
                f += 1
    for f in range(nf):
        if F[f, 0] > GROUP or F[f, 0] == SPLIT:
            continue
        g = GROUP - F[f, 0]
        found = -1
        for a in range(k):
            if grp[a] != g:
                continue
            t = ids[a]
            inside = True
            for e in range(3):
                p0 = T[t, e]
                p1 = T[t, (e + 1) % 3]
                dx = p1[0] - p0[0]
                dy = p1[1] - p0[1]
                dz = p1[2] - p0[2]
                ex = TN[t, 1] * dz - TN[t, 2] * dy
                ey = TN[t, 2] * dx - TN[t, 0] * dz
                ez = TN[t, 0] * dy - TN[t, 1] * dx
                en = np.sqrt(ex * ex + ey * ey + ez * ez)
                h0 = (ex * (p0[0] - o[0]) + ey * (p0[1] - o[1]) + ez * (p0[2] - o[2])) / en
                for s in range(F[f, 1], F[f, 1] + F[f, 2]):
                    v = R[s]
                    sv = (ex * V[v, 0] + ey * V[v, 1] + ez * V[v, 2]) / en - h0
                    if sv < -tol:
                        inside = False
                        break
                if not inside:
                    break
            if inside:
                found = t
                break
        if found < 0:
            return False, nv, nf
        F[f, 0] = -1 - found
    return True, nv, nf


@njit(**NJIT)
def _convex_cell(
    i, cf, roff, ring, verts, lab, farea, fpt, T, TN, TO, lo, h, dims, start, items, tol, sc, out
):
    """One cell of :func:`convex_cells` (scratch ``sc``, outputs ``out`` for its slot)."""
    (
        gsc,
        grp,
        toff,
        use,
        sub,
        subm,
        bufc,
        PV,
        PF,
        PR,
        pnv,
        pnf,
        pspl,
        pdep,
        R2,
        S,
        S2,
        work,
        vmap,
        ms,
    ) = sc
    ids, seen, pm, polys, buf_a, buf_b, tick = gsc
    oV, oF, oR = out
    k = _gather(i, cf, roff, ring, verts, farea, fpt, T, TO, lo, h, dims, start, items, tol, gsc)
    if k <= 0:
        return _fail()
    f0, f1 = cf[i], cf[i + 1]
    o = np.zeros(3)
    for c in range(3):
        o[c] = verts[ring[roff[f0]], c]
    # everything relative to the cell's first vertex
    for a in range(k):
        t = ids[a]
        toff[a] = TN[t, 0] * (T[t, 0, 0] - o[0]) + TN[t, 1] * (T[t, 0, 1] - o[1])
        toff[a] += TN[t, 2] * (T[t, 0, 2] - o[2])
        for q in range(pm[a]):
            for c in range(3):
                polys[a, q, c] -= o[c]
    # plane groups: triangles whose corners lie within tol of an earlier group's plane
    for a in range(k):
        ta = ids[a]
        grp[a] = a
        for b in range(a):
            if grp[b] != b:
                continue
            tb = ids[b]
            if TN[ta, 0] * TN[tb, 0] + TN[ta, 1] * TN[tb, 1] + TN[ta, 2] * TN[tb, 2] <= 0.0:
                continue
            on = True
            for q in range(3):
                sv = TN[tb, 0] * T[ta, q, 0] + TN[tb, 1] * T[ta, q, 1] + TN[tb, 2] * T[ta, q, 2]
                if abs(sv - TO[tb]) > tol:
                    on = False
            if on:
                grp[a] = b
                break
    # part 0: the cell as a polyhedron
    nv = 0
    nr = 0
    nf = 0
    for f in range(f0, f1):
        if nf == PF.shape[1]:
            return _fail()
        PF[0, nf, 0] = lab[f]
        PF[0, nf, 1] = nr
        PF[0, nf, 2] = roff[f + 1] - roff[f]
        nf += 1
        for s in range(roff[f], roff[f + 1]):
            v = ring[s]
            x = -1
            for q in range(nv):
                if vmap[q] == v:
                    x = q
                    break
            if x < 0:
                if nv == PV.shape[1]:
                    return _fail()
                vmap[nv] = v
                for c in range(3):
                    PV[0, nv, c] = verts[v, c] - o[c]
                x = nv
                nv += 1
            if nr == PR.shape[1]:
                return _fail()
            PR[0, nr] = x
            nr += 1
    pnv[0] = nv
    pnf[0] = nf
    pdep[0] = 0
    nparts = np.int64(1)  # not a literal: numba would compile merge_parts once more
    done = np.zeros(PV.shape[0], np.bool_)
    while True:
        p = -1
        for q in range(nparts):
            if not done[q]:
                p = q
                break
        if p < 0:
            break
        # the triangles meeting this part: clipped by its split planes too
        for a in range(k):
            m = pm[a]
            for q in range(m):
                for c in range(3):
                    sub[a, q, c] = polys[a, q, c]
            for d in range(pdep[p]):  # shrunk by tol: a triangle that only touches a split
                # plane (the other one of the pair, along their meeting line) is not the part's
                m2 = _clip_poly(
                    sub[a],
                    m,
                    pspl[p, d, 0],
                    pspl[p, d, 1],
                    pspl[p, d, 2],
                    pspl[p, d, 3],
                    -tol,
                    bufc,
                )
                for q in range(m2):
                    for c in range(3):
                        sub[a, q, c] = bufc[q, c]
                m = m2
                if m == 0:
                    break
            use[a] = m > 0
            subm[a] = m
        # a pair of inconsistent triangles whose bisecting plane (below) separates them
        anybad = False
        bad_a = -1
        bad_b = -1
        for a in range(k):
            if not use[a] or bad_a >= 0:
                continue
            for b in range(k):
                if a == b or not use[b]:
                    continue
                if not _beyond(sub, subm[a], a, TN[ids[b]], toff[b], tol):
                    continue
                anybad = True
                ta = ids[a]
                tb = ids[b]
                nn = np.sqrt(
                    (TN[ta, 0] - TN[tb, 0]) ** 2
                    + (TN[ta, 1] - TN[tb, 1]) ** 2
                    + (TN[ta, 2] - TN[tb, 2]) ** 2
                )
                if nn < 1e-6:
                    continue
                nvec = (TN[ta] - TN[tb]) / nn
                hh = (toff[a] - toff[b]) / nn
                if _beyond(sub, subm[a], a, nvec, hh, tol):
                    continue
                if _beyond(sub, subm[b], b, -nvec, -hh, tol):
                    continue
                bad_a = a
                bad_b = b
                break
        if anybad and bad_a < 0:
            return _fail()
        if bad_a < 0:
            ok, pnv[p], pnf[p] = _finish_part(
                PV[p],
                pnv[p],
                PF[p],
                pnf[p],
                PR[p],
                R2,
                S,
                work,
                k,
                use,
                grp,
                ids,
                T,
                TN,
                toff,
                o,
                tol,
            )
            if not ok:
                return _fail()
            done[p] = True
            continue
        # split the part where the two planes' signed distances are equal (the plane through
        # their meeting line that bisects the wedge outside both); a's side keeps a
        if nparts == PV.shape[0] or pdep[p] == pspl.shape[1]:
            return _fail()
        ta = ids[bad_a]
        tb = ids[bad_b]
        nx = TN[ta, 0] - TN[tb, 0]
        ny = TN[ta, 1] - TN[tb, 1]
        nz = TN[ta, 2] - TN[tb, 2]
        nn = np.sqrt(nx * nx + ny * ny + nz * nz)
        if nn < 1e-6:
            return _fail()
        nx /= nn
        ny /= nn
        nz /= nn
        hh = (toff[bad_a] - toff[bad_b]) / nn
        for a in range(k):  # a triangle in the split plane would be lost on both sides
            if not use[a]:
                continue
            far = False
            for j in range(subm[a]):
                if abs(nx * sub[a, j, 0] + ny * sub[a, j, 1] + nz * sub[a, j, 2] - hh) > tol:
                    far = True
                    break
            if not far:
                return _fail()
        q = nparts
        nparts += 1
        nv = pnv[p]
        nf = pnf[p]
        nr = ring_count(PF[p], nf)
        for v in range(nv):
            for c in range(3):
                PV[q, v, c] = PV[p, v, c]
        for f in range(nf):
            for c in range(3):
                PF[q, f, c] = PF[p, f, c]
        for s in range(nr):
            PR[q, s] = PR[p, s]
        plane_values(PV[p], nv, nx, ny, nz, hh, tol, S)
        for v in range(nv):
            S2[v] = -S[v]
        st, pnv[p], pnf[p] = cut(PV[p], nv, PF[p], nf, PR[p], R2, S, work, np.int64(SPLIT))
        if st == CUT_OVERFLOW or st == CUT_BROKEN:
            return _fail()
        if st == CUT_EMPTY:
            done[p] = True  # nothing of it is left
            pnf[p] = 0
        st, pnv[q], pnf[q] = cut(PV[q], nv, PF[q], nf, PR[q], R2, S2, work, np.int64(SPLIT))
        if st == CUT_OVERFLOW or st == CUT_BROKEN:
            return _fail()
        pnf[q] = 0 if st == CUT_EMPTY else pnf[q]
        done[q] = st == CUT_EMPTY
        for d in range(pdep[p]):
            for c in range(4):
                pspl[q, d, c] = pspl[p, d, c]
        pspl[p, pdep[p], 0] = nx
        pspl[p, pdep[p], 1] = ny
        pspl[p, pdep[p], 2] = nz
        pspl[p, pdep[p], 3] = hh
        pspl[q, pdep[p], 0] = -nx
        pspl[q, pdep[p], 1] = -ny
        pspl[q, pdep[p], 2] = -nz
        pspl[q, pdep[p], 3] = -hh
        pdep[q] = pdep[p] + 1
        pdep[p] += 1
    return _merge_scaled(PV, PF, PR, pnv, pnf, nparts, ms, o, tol, out)


@njit(**NJIT)
def _merge_scaled(PV, PF, PR, pnv, pnf, nparts, ms, o, tol, out):
    """:func:`.meshparts3d.merge_parts` on the parts scaled by a power of two near 1.

    Its moments are cubes and fourth powers of the cell-local coordinates: past 2**256 they
    overflowed (centroids inf or NaN), below 2**-256 they underflowed. The parts, ``o`` and
    ``tol`` are scaled by ``2**-e`` (``2**e`` near the largest local coordinate), merged,
    and the outputs scaled back: exact, so the same bits wherever nothing over- or
    underflowed before.
    """
    big = 0.0
    for p in range(nparts):
        if pnf[p] == 0:
            continue
        for v in range(pnv[p]):
            for c in range(3):
                big = max(big, abs(PV[p, v, c]))
    e = 0
    if big > 0.0 and (big > MESH_MOMENT_SAFE or big < 1.0 / MESH_MOMENT_SAFE):
        e = math.frexp(big)[1]
    if e == 0:
        return merge_parts(PV, PF, PR, pnv, pnf, nparts, ms, o, tol, out)
    for p in range(nparts):
        for v in range(pnv[p]):
            for c in range(3):
                PV[p, v, c] = math.ldexp(PV[p, v, c], -e)
    os = np.zeros(3)
    for c in range(3):
        os[c] = math.ldexp(o[c], -e)
    r = merge_parts(PV, PF, PR, pnv, pnf, nparts, ms, os, math.ldexp(tol, -e), out)
    oV = out[0]
    for v in range(r[0]):
        for c in range(3):
            oV[v, c] = math.ldexp(oV[v, c], e)
    if r[0] == 0:
        return r
    return (
        r[0],
        r[1],
        r[2],
        math.ldexp(r[3], 3 * e),
        math.ldexp(r[4], e),
        math.ldexp(r[5], e),
        math.ldexp(r[6], e),
        r[7],
    )


@njit(**NJIT)
def convex_cells(
    cells,
    cf,
    roff,
    ring,
    verts,
    lab,
    farea,
    fpt,
    T,
    TN,
    TO,
    lo,
    h,
    dims,
    start,
    items,
    tol,
    oV,
    oF,
    oR,
    counts,
    vol,
    cen,
    npc,
):
    """The cells ``cells`` ∩ the solid, cut here where that is provably exact.

    One thread (callers run slices of the cells on threads; it releases the GIL; ``fpt``:
    a point of each face). For each cell (a :meth:`Diagram3D.cell_face_table` cell): the
    triangles that meet it
    grown by ``tol`` (bucketed by :func:`kernels.meshclip3d.tri_grid`; unit normals ``TN``,
    offsets ``TO``), each clipped by the cell. When every clipped triangle lies inside
    every other one's half-space (within ``tol``), the cell ∩ the solid is the cell cut by
    those planes (coplanar triangles, within ``tol``, are one plane): the surface inside
    the cell is then the cut's new faces, the solid is on their inner side, and the rest of
    the cell, cut off by them, outside. Where a pair is inconsistent (a reflex edge, a
    saddle), the cell is split by the plane where the two planes' signed distances are
    equal (it bisects the wedge outside both and separates the pair) and each part is
    treated alike, with the triangles that meet it by more than ``tol``; the parts are then
    joined (split faces dropped, their vertices merged within ``tol``). Checked: each new
    face, split along its triangles' edges (new vertices also put into the neighbouring
    faces' rings), must lie inside one of them (within ``tol``), which it is then labelled
    by (``-1 - t``), and the joined cell must be closed (each edge exactly one twin); a
    face of the cell lying in such a plane, a pair no bisector separates, or any limit
    passed leaves the cell to the caller (``counts[j] = 0``). Outputs per cell ``j``: its
    rows of ``oV`` (vertices), ``oF`` (``label, ring length``), ``oR`` (rings, local vertex
    numbers), written one cell after another from the start (a cell left to the caller
    writes none; room for ``CC_OUT_*`` rows a cell; only the rows written are touched, so
    fresh zeroed pages past them cost nothing), ``counts[j] = (nv, nf, nr)``, ``vol[j]``,
    ``cen[j]``, ``npc[j]`` (pieces).
    """
    n = cells.shape[0]
    cv = oV.shape[0] // max(n, 1)
    cfa = oF.shape[0] // max(n, 1)
    cr = oR.shape[0] // max(n, 1)
    nblk = (n + CC_BLOCK - 1) // CC_BLOCK
    pv = 0
    pf = 0
    pr = 0
    seen = np.zeros(T.shape[0], np.int64)  # per triangle: the last gather that saw it
    tick = np.zeros(1, np.int64)
    for blk in range(nblk):
        gsc = (
            np.zeros(CC_TRIS, np.int64),
            seen,
            np.zeros(CC_TRIS, np.int64),
            np.zeros((CC_TRIS, CC_POLY, 3)),
            np.zeros((CC_POLY, 3)),
            np.zeros((CC_POLY, 3)),
            tick,
        )
        nm = CC_PARTS * CC_V
        ms = (
            np.zeros((nm, 3)),
            np.zeros(nm, np.int64),
            np.zeros(nm, np.bool_),
            np.zeros((CC_PARTS * CC_F, 3), np.int64),
            np.zeros(4 * CC_R, np.int64),
            np.zeros(4 * CC_R, np.int64),
            np.zeros(nm, np.int64),
        )
        sc = (
            gsc,
            np.zeros(CC_TRIS, np.int64),
            np.zeros(CC_TRIS),
            np.zeros(CC_TRIS, np.bool_),
            np.zeros((CC_TRIS, CC_POLY, 3)),
            np.zeros(CC_TRIS, np.int64),
            np.zeros((CC_POLY, 3)),
            np.zeros((CC_PARTS, CC_V, 3)),
            np.zeros((CC_PARTS, CC_F, 3), np.int64),
            np.zeros((CC_PARTS, CC_R), np.int64),
            np.zeros(CC_PARTS, np.int64),
            np.zeros(CC_PARTS, np.int64),
            np.zeros((CC_PARTS, CC_DEPTH, 4)),
            np.zeros(CC_PARTS, np.int64),
            np.zeros(CC_R, np.int64),
            np.zeros(CC_V),
            np.zeros(CC_V),
            np.zeros((CC_R, 4), np.int64),
            np.zeros(CC_V, np.int64),
            ms,
        )
        for j in range(blk * CC_BLOCK, min(n, (blk + 1) * CC_BLOCK)):
            out = (
                oV[pv : pv + cv],
                oF[pf : pf + cfa],
                oR[pr : pr + cr],
            )
            r = _convex_cell(
                cells[j],
                cf,
                roff,
                ring,
                verts,
                lab,
                farea,
                fpt,
                T,
                TN,
                TO,
                lo,
                h,
                dims,
                start,
                items,
                tol,
                sc,
                out,
            )
            counts[j, 0] = r[0]
            counts[j, 1] = r[1]
            counts[j, 2] = r[2]
            vol[j] = r[3]
            cen[j, 0] = r[4]
            cen[j, 1] = r[5]
            cen[j, 2] = r[6]
            npc[j] = r[7]
            pv += r[0]  # the next cell's output follows this one's (a failed one: nothing)
            pf += r[1]
            pr += r[2]
