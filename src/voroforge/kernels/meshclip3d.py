"""Convex cells against a closed triangle mesh: which cells the mesh's surface meets.

A convex cell (the intersection of its faces' half-spaces) that no triangle of a closed
surface meets lies wholly on one side of it. :func:`touching_cells` tells, for each cell,
whether some triangle meets the cell grown by ``tol``: the triangle is clipped by each face
plane moved out by ``tol`` (Sutherland-Hodgman on a convex polygon) and meets the cell when
something is left. Growing the cell makes the answer conservative: rounding in the clip
(far below ``tol``) can only call a cell touching that misses the surface by less than
``tol``, never the other way. Triangles are bucketed on a uniform grid by their boxes;
each cell tests the triangles of the buckets its box overlaps.
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

from ..config import NJIT, NJIT_PARALLEL
from .polyhedron import CUT_DONE, CUT_NONE, cut, moments, plane_values, ring_count


@njit(**NJIT)
def tri_grid(T, lo, h, dims):
    """Bucket triangles ``T (m, 3, 3)`` by their boxes on a grid: ``(start, items)`` CSR."""
    nx, ny, nz = dims[0], dims[1], dims[2]
    nb = nx * ny * nz
    count = np.zeros(nb + 1, np.int64)
    for rnd in range(2):
        if rnd == 1:
            for k in range(nb):
                count[k + 1] += count[k]
            items = np.zeros(count[nb], np.int64)
            fill = count[:-1].copy()
        for t in range(T.shape[0]):
            a0 = np.zeros(3, np.int64)
            a1 = np.zeros(3, np.int64)
            for c in range(3):
                x0 = min(T[t, 0, c], min(T[t, 1, c], T[t, 2, c]))
                x1 = max(T[t, 0, c], max(T[t, 1, c], T[t, 2, c]))
                a0[c] = min(dims[c] - 1, max(0, int((x0 - lo[c]) / h)))
                a1[c] = min(dims[c] - 1, max(0, int((x1 - lo[c]) / h)))
            for i in range(a0[0], a1[0] + 1):
                for j in range(a0[1], a1[1] + 1):
                    for k in range(a0[2], a1[2] + 1):
                        b = (i * ny + j) * nz + k
                        if rnd == 0:
                            count[b + 1] += 1
                        else:
                            items[fill[b]] = t
                            fill[b] += 1
    return count, items


@njit(**NJIT)
def _meets(T, t, cell_lo, cell_hi, f0, f1, farea, fpt, tol, buf_a, buf_b):
    """Whether triangle ``t`` meets the cell (faces ``f0:f1``) grown by ``tol``."""
    for c in range(3):
        x0 = min(T[t, 0, c], min(T[t, 1, c], T[t, 2, c]))
        x1 = max(T[t, 0, c], max(T[t, 1, c], T[t, 2, c]))
        if x1 < cell_lo[c] or x0 > cell_hi[c]:
            return False
    for k in range(3):
        for c in range(3):
            buf_a[k, c] = T[t, k, c]
    m = 3
    src = buf_a
    dst = buf_b
    for f in range(f0, f1):
        nx = farea[f, 0]
        ny = farea[f, 1]
        nz = farea[f, 2]
        nn = np.sqrt(nx * nx + ny * ny + nz * nz)
        if nn == 0.0:
            continue
        off = nx * fpt[f, 0] + ny * fpt[f, 1] + nz * fpt[f, 2] + tol * nn
        k = 0
        sp = nx * src[m - 1, 0] + ny * src[m - 1, 1] + nz * src[m - 1, 2] - off
        for q in range(m):
            sq = nx * src[q, 0] + ny * src[q, 1] + nz * src[q, 2] - off
            if (sp <= 0.0) != (sq <= 0.0):  # the edge crosses the plane
                p = q - 1 if q > 0 else m - 1
                r = sp / (sp - sq)
                for c in range(3):
                    dst[k, c] = src[p, c] + r * (src[q, c] - src[p, c])
                k += 1
            if sq <= 0.0:
                for c in range(3):
                    dst[k, c] = src[q, c]
                k += 1
            sp = sq
        if k == 0:
            return False
        m = k
        src, dst = dst, src
    return True


@njit(**NJIT_PARALLEL)
def touching_cells(cf, roff, ring, verts, farea, live, T, lo, h, dims, start, items, tol):
    """``(n,) bool``: the cells that some triangle of ``T (m, 3, 3)`` meets.

    Cells as :meth:`Diagram3D.cell_face_table` gives them (faces ``cf``, rings
    ``roff``/``ring`` into ``verts``, outward area vectors ``farea``), each grown by ``tol``;
    ``live`` marks the cells to test; triangles bucketed by :func:`tri_grid`.
    """
    n = cf.shape[0] - 1
    out = np.zeros(n, np.bool_)
    nf = farea.shape[0]
    fpt = np.zeros((nf, 3))
    for f in prange(nf):
        v = ring[roff[f]]
        for c in range(3):
            fpt[f, c] = verts[v, c]
    ny, nz = dims[1], dims[2]
    for i in prange(n):
        if not live[i]:
            continue
        f0, f1 = cf[i], cf[i + 1]
        cell_lo = np.full(3, np.inf)
        cell_hi = np.full(3, -np.inf)
        for s in range(roff[f0], roff[f1]):
            v = ring[s]
            for c in range(3):
                cell_lo[c] = min(cell_lo[c], verts[v, c])
                cell_hi[c] = max(cell_hi[c], verts[v, c])
        a0 = np.zeros(3, np.int64)
        a1 = np.zeros(3, np.int64)
        for c in range(3):
            cell_lo[c] -= tol
            cell_hi[c] += tol
            a0[c] = min(dims[c] - 1, max(0, int((cell_lo[c] - lo[c]) / h)))
            a1[c] = min(dims[c] - 1, max(0, int((cell_hi[c] - lo[c]) / h)))
        buf_a = np.zeros((3 + f1 - f0, 3))
        buf_b = np.zeros((3 + f1 - f0, 3))
        hit = False
        for a in range(a0[0], a1[0] + 1):
            for b in range(a0[1], a1[1] + 1):
                for k in range(a0[2], a1[2] + 1):
                    bk = (a * ny + b) * nz + k
                    for s in range(start[bk], start[bk + 1]):
                        t = items[s]
                        if _meets(T, t, cell_lo, cell_hi, f0, f1, farea, fpt, tol, buf_a, buf_b):
                            hit = True
                            break
                    if hit:
                        break
                if hit:
                    break
            if hit:
                break
        out[i] = hit
    return out


@njit(**NJIT)
def copy_runs(src, s0, s1, dst, d0):
    """``dst[d0[k]:d0[k] + s1[k] - s0[k]] = src[s0[k]:s1[k]]`` for each run ``k``."""
    for k in range(s0.shape[0]):
        o = d0[k] - s0[k]
        for j in range(s0[k], s1[k]):
            dst[j + o] = src[j]


@njit(**NJIT)
def colour_cells(cells, cf, roff, ring, nvert):
    """Greedy first-fit colours: no two cells of one colour share a vertex.

    Cells in order take the lowest colour that none of their vertices holds yet; after 63
    colours a cell gets one of its own (``63 + its position``), which only costs batches.
    """
    used = np.zeros(nvert, np.int64)  # bit k: a cell of colour k holds the vertex
    out = np.zeros(cells.shape[0], np.int64)
    for q in range(cells.shape[0]):
        i = cells[q]
        mask = 0
        for s in range(roff[cf[i]], roff[cf[i + 1]]):
            mask |= used[ring[s]]
        k = 0
        while k < 63 and (mask >> k) & 1:
            k += 1
        if k == 63:
            out[q] = 63 + q
            continue
        out[q] = k
        for s in range(roff[cf[i]], roff[cf[i + 1]]):
            used[ring[s]] |= np.int64(1) << k
    return out


#: labels of the faces a container plane group ``g`` adds while a cell is cut: ``GROUP - g``
GROUP = -(1 << 40)
#: per-cell scratch and output limits of :func:`convex_cells` (past them: manifold3d)
CC_TRIS = 64  # triangles meeting one cell
CC_SEEN = 512  # triangles looked at (each bucket's, before the duplicates are skipped)
CC_POLY = 64  # vertices of a triangle clipped by the cell
CC_V, CC_F, CC_R = 128, 64, 2048  # polyhedron scratch: vertices, faces, ring entries
CC_OUT_V, CC_OUT_F, CC_OUT_R = 96, 48, 384  # a finished cell's slots
CC_BLOCK = 32  # cells per parallel block (one set of scratch each)


@njit(**NJIT)
def _clip_tri(T, t, f0, f1, farea, fpt, tol, buf_a, buf_b):
    """Triangle ``t`` clipped by the cell's face planes moved out by ``tol``: ``(m, ring)``."""
    for k in range(3):
        for c in range(3):
            buf_a[k, c] = T[t, k, c]
    m = 3
    src = buf_a
    dst = buf_b
    for f in range(f0, f1):
        nx = farea[f, 0]
        ny = farea[f, 1]
        nz = farea[f, 2]
        nn = np.sqrt(nx * nx + ny * ny + nz * nz)
        if nn == 0.0:
            continue
        off = nx * fpt[f, 0] + ny * fpt[f, 1] + nz * fpt[f, 2] + tol * nn
        k = 0
        sp = nx * src[m - 1, 0] + ny * src[m - 1, 1] + nz * src[m - 1, 2] - off
        for q in range(m):
            sq = nx * src[q, 0] + ny * src[q, 1] + nz * src[q, 2] - off
            if (sp <= 0.0) != (sq <= 0.0):
                p = q - 1 if q > 0 else m - 1
                r = sp / (sp - sq)
                for c in range(3):
                    dst[k, c] = src[p, c] + r * (src[q, c] - src[p, c])
                k += 1
            if sq <= 0.0:
                for c in range(3):
                    dst[k, c] = src[q, c]
                k += 1
            sp = sq
        if k == 0:
            return 0, src
        m = k
        src, dst = dst, src
    return m, src


@njit(**NJIT)
def _split_face(V, nv, F, nf, R, nr, f, S):
    """Split face ``f`` along the plane of values ``S`` (both sides strictly present).

    Each crossing edge gets a new vertex, put also into the ring of the face across that
    edge (no T-junctions); ``f`` keeps its ``S >= 0`` part, a new face (same label) the
    rest. Rings are rewritten at the end of ``R``. Returns ``(ok, nv, nf, nr)``.
    """
    vcap = V.shape[0]
    st = F[f, 1]
    ln = F[f, 2]
    if nf + 1 > F.shape[0] or nr + 2 * ln + 4 > R.shape[0]:
        return False, nv, nf, nr
    xs = np.zeros((2, 3), np.int64)  # (vertex, lower end, upper end) per crossing
    nx_ = 0
    # new vertices on the crossing edges, and into the twin faces
    for k in range(ln):
        a = R[st + k]
        c = R[st + k + 1] if k + 1 < ln else R[st]
        if (S[a] < 0.0 and S[c] > 0.0) or (S[a] > 0.0 and S[c] < 0.0):
            if nx_ == 2 or nv >= vcap:
                return False, nv, nf, nr
            lo_, hi_ = (a, c) if abs(S[a]) <= abs(S[c]) else (c, a)
            t = S[lo_] / (S[lo_] - S[hi_])
            for q in range(3):
                V[nv, q] = V[lo_, q] + t * (V[hi_, q] - V[lo_, q])
            S[nv] = 0.0
            xs[nx_, 0] = nv
            xs[nx_, 1] = min(a, c)
            xs[nx_, 2] = max(a, c)
            nx_ += 1
            # the twin: the face holding c -> a
            done = False
            for g in range(nf):
                if g == f or done:
                    continue
                gs = F[g, 1]
                gl = F[g, 2]
                for j in range(gl):
                    u = R[gs + j]
                    w = R[gs + j + 1] if j + 1 < gl else R[gs]
                    if u == c and w == a:
                        if nr + gl + 1 > R.shape[0]:
                            return False, nv, nf, nr
                        b = nr
                        for jj in range(gl):
                            R[nr] = R[gs + jj]
                            nr += 1
                            if jj == j:
                                R[nr] = nv
                                nr += 1
                        F[g, 1] = b
                        F[g, 2] = gl + 1
                        done = True
                        break
            if not done:
                return False, nv, nf, nr
            nv += 1
    # the two sides
    for side in range(2):
        b = nr
        for k in range(ln):
            a = R[st + k]
            c = R[st + k + 1] if k + 1 < ln else R[st]
            sa = S[a] if side == 0 else -S[a]
            sc = S[c] if side == 0 else -S[c]
            if sa >= 0.0:
                R[nr] = a
                nr += 1
            if (sa < 0.0 and sc > 0.0) or (sa > 0.0 and sc < 0.0):
                # the crossing made for this edge
                cr = -1
                for q in range(nx_):
                    if xs[q, 1] == min(a, c) and xs[q, 2] == max(a, c):
                        cr = xs[q, 0]
                if cr < 0:
                    return False, nv, nf, nr
                R[nr] = cr
                nr += 1
        if nr - b < 3:
            return False, nv, nf, nr
        if side == 0:
            F[f, 1] = b
            F[f, 2] = nr - b
        else:
            F[nf, 0] = F[f, 0]
            F[nf, 1] = b
            F[nf, 2] = nr - b
            nf += 1
    return True, nv, nf, nr


@njit(**NJIT)
def _convex_cell(
    i, cf, roff, ring, verts, lab, farea, fpt, T, TN, TO, lo, h, dims, start, items, tol, sc, out
):
    """One cell of :func:`convex_cells` (scratch ``sc``, outputs ``out`` for its slot)."""
    ids, seen, grp, pm, polys, buf_a, buf_b, V, F, R, R2, S, work, vmap = sc
    oV, oF, oR = out
    ny, nz = dims[1], dims[2]
    f0, f1 = cf[i], cf[i + 1]
    cell_lo = np.full(3, np.inf)
    cell_hi = np.full(3, -np.inf)
    for s in range(roff[f0], roff[f1]):
        v = ring[s]
        for c in range(3):
            cell_lo[c] = min(cell_lo[c], verts[v, c])
            cell_hi[c] = max(cell_hi[c], verts[v, c])
    a0 = np.zeros(3, np.int64)
    a1 = np.zeros(3, np.int64)
    for c in range(3):
        cell_lo[c] -= tol
        cell_hi[c] += tol
        a0[c] = min(dims[c] - 1, max(0, int((cell_lo[c] - lo[c]) / h)))
        a1[c] = min(dims[c] - 1, max(0, int((cell_hi[c] - lo[c]) / h)))
    if f1 - f0 + 3 > polys.shape[1]:
        return 0, 0, 0, 0.0, 0.0, 0.0, 0.0
    # the triangles that meet the cell grown by tol, clipped by it
    k = 0
    ns = 0
    for a in range(a0[0], a1[0] + 1):
        for b in range(a0[1], a1[1] + 1):
            for kk in range(a0[2], a1[2] + 1):
                bk = (a * ny + b) * nz + kk
                for s in range(start[bk], start[bk + 1]):
                    t = items[s]
                    dup = False
                    for q in range(ns):
                        if seen[q] == t:
                            dup = True
                            break
                    if dup:
                        continue
                    if ns == seen.shape[0]:
                        return 0, 0, 0, 0.0, 0.0, 0.0, 0.0
                    seen[ns] = t
                    ns += 1
                    out_ = False
                    for c in range(3):
                        x0 = min(T[t, 0, c], min(T[t, 1, c], T[t, 2, c]))
                        x1 = max(T[t, 0, c], max(T[t, 1, c], T[t, 2, c]))
                        if x1 < cell_lo[c] or x0 > cell_hi[c]:
                            out_ = True
                    if out_:
                        continue
                    m, src = _clip_tri(T, t, f0, f1, farea, fpt, tol, buf_a, buf_b)
                    if m == 0:
                        continue
                    if k == ids.shape[0] or not np.isfinite(TO[t]):  # no room, no plane
                        return 0, 0, 0, 0.0, 0.0, 0.0, 0.0
                    ids[k] = t
                    pm[k] = m
                    for q in range(m):
                        for c in range(3):
                            polys[k, q, c] = src[q, c]
                    k += 1
    if k == 0:
        return 0, 0, 0, 0.0, 0.0, 0.0, 0.0
    # every clipped triangle inside every other triangle's half-space: the surface is
    # convex from the cell's side
    for a in range(k):
        for b in range(k):
            if a == b:
                continue
            tb = ids[b]
            for q in range(pm[a]):
                sv = (
                    TN[tb, 0] * polys[a, q, 0]
                    + TN[tb, 1] * polys[a, q, 1]
                    + TN[tb, 2] * polys[a, q, 2]
                    - TO[tb]
                )
                if sv > tol:
                    return 0, 0, 0, 0.0, 0.0, 0.0, 0.0
    # plane groups: triangles whose corners lie within tol of an earlier one's plane
    ng = 0
    for a in range(k):
        ta = ids[a]
        grp[a] = -1
        for b in range(a):
            if grp[b] != b:  # compare with each group's first triangle only
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
        if grp[a] < 0:
            grp[a] = a
            ng += 1
    # the cell as a polyhedron, relative to its first vertex
    nv = 0
    nr = 0
    nf = 0
    o0 = verts[ring[roff[f0]], 0]
    o1 = verts[ring[roff[f0]], 1]
    o2 = verts[ring[roff[f0]], 2]
    for f in range(f0, f1):
        if nf == F.shape[0]:
            return 0, 0, 0, 0.0, 0.0, 0.0, 0.0
        F[nf, 0] = lab[f]
        F[nf, 1] = nr
        F[nf, 2] = roff[f + 1] - roff[f]
        nf += 1
        for s in range(roff[f], roff[f + 1]):
            v = ring[s]
            x = -1
            for q in range(nv):
                if vmap[q] == v:
                    x = q
                    break
            if x < 0:
                if nv == V.shape[0]:
                    return 0, 0, 0, 0.0, 0.0, 0.0, 0.0
                vmap[nv] = v
                V[nv, 0] = verts[v, 0] - o0
                V[nv, 1] = verts[v, 1] - o1
                V[nv, 2] = verts[v, 2] - o2
                x = nv
                nv += 1
            if nr == R.shape[0]:
                return 0, 0, 0, 0.0, 0.0, 0.0, 0.0
            R[nr] = x
            nr += 1
    # cut by each group's plane
    for a in range(k):
        if grp[a] != a:
            continue
        t = ids[a]
        h0 = (
            TN[t, 0] * (T[t, 0, 0] - o0)
            + TN[t, 1] * (T[t, 0, 1] - o1)
            + TN[t, 2] * (T[t, 0, 2] - o2)
        )
        plane_values(V, nv, TN[t, 0], TN[t, 1], TN[t, 2], h0, tol, S)
        st, nv, nf = cut(V, nv, F, nf, R, R2, S, work, GROUP - a)
        if st != CUT_NONE and st != CUT_DONE:
            return 0, 0, 0, 0.0, 0.0, 0.0, 0.0
        nr = ring_count(F, nf)
    # a face of the cell lying in a group's plane (not made by the cut): left to manifold3d
    has = False
    for f in range(nf):
        if F[f, 0] <= GROUP:
            has = True
            continue
        for a in range(k):
            if grp[a] != a:
                continue
            t = ids[a]
            h0 = (
                TN[t, 0] * (T[t, 0, 0] - o0)
                + TN[t, 1] * (T[t, 0, 1] - o1)
                + TN[t, 2] * (T[t, 0, 2] - o2)
            )
            allon = True
            for s in range(F[f, 1], F[f, 1] + F[f, 2]):
                v = R[s]
                sv = TN[t, 0] * V[v, 0] + TN[t, 1] * V[v, 1] + TN[t, 2] * V[v, 2] - h0
                if abs(sv) > tol:
                    allon = False
                    break
            if allon:
                return 0, 0, 0, 0.0, 0.0, 0.0, 0.0
    if not has:
        return 0, 0, 0, 0.0, 0.0, 0.0, 0.0
    # split each group's faces along its triangles' edges, then name each piece's triangle
    for a in range(k):
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
                return 0, 0, 0, 0.0, 0.0, 0.0, 0.0
            ex /= en
            ey /= en
            ez /= en
            h0 = ex * (p0[0] - o0) + ey * (p0[1] - o1) + ez * (p0[2] - o2)
            f = 0
            while f < nf:
                if F[f, 0] == GROUP - g:
                    plane_values(V, nv, ex, ey, ez, h0, tol, S)
                    lo_ = 0.0
                    hi_ = 0.0
                    for s in range(F[f, 1], F[f, 1] + F[f, 2]):
                        lo_ = min(lo_, S[R[s]])
                        hi_ = max(hi_, S[R[s]])
                    if lo_ < 0.0 and hi_ > 0.0:
                        ok, nv, nf, nr = _split_face(V, nv, F, nf, R, nr, f, S)
                        if not ok:
                            return 0, 0, 0, 0.0, 0.0, 0.0, 0.0
                f += 1
    for f in range(nf):
        if F[f, 0] > GROUP:
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
                h0 = (ex * (p0[0] - o0) + ey * (p0[1] - o1) + ez * (p0[2] - o2)) / en
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
            return 0, 0, 0, 0.0, 0.0, 0.0, 0.0
        F[f, 0] = -1 - found
    vol, mx, my, mz = moments(V, F, nf, R)
    if not vol > 0.0:
        return 0, 0, 0, 0.0, 0.0, 0.0, 0.0
    nr = ring_count(F, nf)
    if nv > oV.shape[0] or nf > oF.shape[0] or nr > oR.shape[0]:
        return 0, 0, 0, 0.0, 0.0, 0.0, 0.0
    for v in range(nv):
        oV[v, 0] = V[v, 0] + o0
        oV[v, 1] = V[v, 1] + o1
        oV[v, 2] = V[v, 2] + o2
    q = 0
    for f in range(nf):
        oF[f, 0] = F[f, 0]
        oF[f, 1] = F[f, 2]
        for s in range(F[f, 1], F[f, 1] + F[f, 2]):
            oR[q] = R[s]
            q += 1
    return nv, nf, nr, vol, mx / vol + o0, my / vol + o1, mz / vol + o2


@njit(**NJIT_PARALLEL)
def convex_cells(
    cells,
    cf,
    roff,
    ring,
    verts,
    lab,
    farea,
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
):
    """Cells the surface meets only where it is convex from their side, cut here exactly.

    For each cell of ``cells`` (a :meth:`Diagram3D.cell_face_table` cell): the triangles
    that meet it grown by ``tol`` (bucketed by :func:`tri_grid`; unit normals ``TN``,
    offsets ``TO``), each clipped by the cell. When every clipped triangle lies inside
    every other one's half-space (within ``tol``), the cell ∩ the solid is the cell cut by
    those planes (coplanar triangles, within ``tol``, are one plane): the surface inside
    the cell is then the cut's new faces, the solid is on their inner side, and the rest of
    the cell, cut off by them, outside. It is checked: each new face, split along its
    triangles' edges (new vertices also put into the neighbouring faces' rings), must lie
    inside one of them (within ``tol``), which it is then labelled by (``-1 - t``); a face
    of the cell lying in such a plane, or any limit passed, leaves the cell to the caller
    (``counts[j] = 0``). Outputs per cell ``j``: slots of ``oV`` (vertices), ``oF``
    (``label, ring length``), ``oR`` (rings, local vertex numbers), ``counts[j] = (nv, nf,
    nr)``, ``vol[j]``, ``cen[j]``.
    """
    n = cells.shape[0]
    nfc = farea.shape[0]
    fpt = np.zeros((nfc, 3))
    for f in prange(nfc):
        v = ring[roff[f]]
        for c in range(3):
            fpt[f, c] = verts[v, c]
    cv = oV.shape[0] // max(n, 1)
    cfa = oF.shape[0] // max(n, 1)
    cr = oR.shape[0] // max(n, 1)
    nblk = (n + CC_BLOCK - 1) // CC_BLOCK
    for blk in prange(nblk):
        sc = (
            np.zeros(CC_TRIS, np.int64),
            np.zeros(CC_SEEN, np.int64),
            np.zeros(CC_TRIS, np.int64),
            np.zeros(CC_TRIS, np.int64),
            np.zeros((CC_TRIS, CC_POLY, 3)),
            np.zeros((CC_POLY, 3)),
            np.zeros((CC_POLY, 3)),
            np.zeros((CC_V, 3)),
            np.zeros((CC_F, 3), np.int64),
            np.zeros(CC_R, np.int64),
            np.zeros(CC_R, np.int64),
            np.zeros(CC_V),
            np.zeros((CC_R, 4), np.int64),
            np.zeros(CC_V, np.int64),
        )
        for j in range(blk * CC_BLOCK, min(n, (blk + 1) * CC_BLOCK)):
            out = (
                oV[j * cv : (j + 1) * cv],
                oF[j * cfa : (j + 1) * cfa],
                oR[j * cr : (j + 1) * cr],
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
