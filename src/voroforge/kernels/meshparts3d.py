"""Split and join the convex parts of a cell that a closed mesh cuts (:mod:`.meshcut3d`).

:func:`split_face` splits a face of a polyhedron along a plane (no T-junctions);
:func:`merge_parts` joins a split cell's convex parts into one closed polyhedron again.
Polyhedra are held as :mod:`kernels.polyhedron` holds them.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import NJIT
from .polyhedron import moments

#: the label of the faces where a cell is split into parts (dropped when they are joined)
SPLIT = -(1 << 50)


@njit(**NJIT)
def split_face(V, nv, F, nf, R, nr, f, S):
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
def fail():
    """The row of a cell left to manifold3d (:func:`.meshcut3d.convex_cells`): all zeros."""
    return 0, 0, 0, 0.0, 0.0, 0.0, 0.0, 0


@njit(**NJIT)
def merge_parts(PV, PF, PR, pnv, pnf, nparts, ms, o, tol, out):
    """The parts of a split cell joined into one closed polyhedron in ``out``.

    Split faces are dropped; the parts' vertices on them that coincide within ``tol`` become
    one. Checked closed (every edge has exactly one twin) and with positive volume, else the
    cell is left to manifold3d. Returns the row of :func:`convex_cells` (sizes, volume,
    centroid, pieces).
    """
    MV, gid, onsp, MF, MR, keys, par = ms
    oV, oF, oR = out
    nt = 0
    for p in range(nparts):
        if pnf[p] == 0:
            continue
        for v in range(pnv[p]):
            for c in range(3):
                MV[nt + v, c] = PV[p, v, c]
            gid[nt + v] = nt + v
            onsp[nt + v] = False
        for f in range(pnf[p]):
            if PF[p, f, 0] == SPLIT:
                for s in range(PF[p, f, 1], PF[p, f, 1] + PF[p, f, 2]):
                    onsp[nt + PR[p, s]] = True
        # vertices on split faces: the same as an earlier part's within tol
        for v in range(nt, nt + pnv[p]):
            if not onsp[v]:
                continue
            for w in range(nt):
                if not onsp[w] or gid[w] != w:
                    continue
                if (
                    abs(MV[v, 0] - MV[w, 0]) <= tol
                    and abs(MV[v, 1] - MV[w, 1]) <= tol
                    and abs(MV[v, 2] - MV[w, 2]) <= tol
                ):
                    gid[v] = w
                    break
        nt += pnv[p]
    # the faces, split faces left out
    nf = np.int64(0)  # not a literal: numba would compile moments() once more for it
    nr = 0
    base = 0
    for p in range(nparts):
        if pnf[p] == 0:
            continue
        for f in range(pnf[p]):
            if PF[p, f, 0] == SPLIT:
                continue
            if nf == MF.shape[0] or nr + PF[p, f, 2] > MR.shape[0]:
                return fail()
            MF[nf, 0] = PF[p, f, 0]
            MF[nf, 1] = nr
            MF[nf, 2] = PF[p, f, 2]
            nf += 1
            for s in range(PF[p, f, 1], PF[p, f, 1] + PF[p, f, 2]):
                MR[nr] = gid[base + PR[p, s]]
                nr += 1
        base += pnv[p]
    # vertices in use, numbered in order
    for v in range(nt):
        par[v] = -1
    for s in range(nr):
        par[MR[s]] = 0
    nv = 0
    for v in range(nt):
        if par[v] == 0:
            par[v] = nv
            for c in range(3):
                MV[nv, c] = MV[v, c]
            nv += 1
    for s in range(nr):
        MR[s] = par[MR[s]]
    if nv > oV.shape[0] or nf > oF.shape[0] or nr > oR.shape[0]:
        return fail()
    # closed: each directed edge once, and its reverse once. The edges leaving each vertex
    # in a list (counting sort: ``gid`` the offsets, ``par`` the cursors, ``keys`` the
    # heads; all free here); then each edge a -> b: b once in a's list, a in b's
    for v in range(nv + 1):
        gid[v] = 0
    for f in range(nf):
        st = MF[f, 1]
        ln = MF[f, 2]
        for j in range(ln):
            a = MR[st + j]
            b = MR[st + j + 1] if j + 1 < ln else MR[st]
            if a == b:
                return fail()
            gid[a + 1] += 1
    for v in range(nv):
        gid[v + 1] += gid[v]
        par[v] = gid[v]
    for f in range(nf):
        st = MF[f, 1]
        ln = MF[f, 2]
        for j in range(ln):
            a = MR[st + j]
            keys[par[a]] = MR[st + j + 1] if j + 1 < ln else MR[st]
            par[a] += 1
    for a in range(nv):
        for e in range(gid[a], gid[a + 1]):
            b = keys[e]
            twice = False
            for e2 in range(gid[a], gid[a + 1]):
                if e2 != e and keys[e2] == b:
                    twice = True
            back = False
            for e2 in range(gid[b], gid[b + 1]):
                if keys[e2] == a:
                    back = True
            if twice or not back:
                return fail()
    # the moments about the centre of the polyhedron's box (shifted copies of its rows in
    # the free rows after them): about the cell's first vertex, a part much thinner than the
    # cell (a rod 1e-6 thick in a cell 2e-2 wide) lost its volume to cancellation (1e-8)
    ref = np.zeros(3)
    for c in range(3):
        lo = MV[0, c]
        hi = MV[0, c]
        for v in range(1, nv):
            lo = min(lo, MV[v, c])
            hi = max(hi, MV[v, c])
        ref[c] = 0.5 * lo + 0.5 * hi
    if 2 * nv > MV.shape[0]:
        return fail()
    for v in range(nv):
        for c in range(3):
            MV[nv + v, c] = MV[v, c] - ref[c]
    vol, mx, my, mz = moments(MV[nv:], MF, nf, MR)
    if not vol > 0.0:
        return fail()
    # pieces: vertices joined by the faces (union-find)
    for v in range(nv):
        par[v] = v
    for f in range(nf):
        st = MF[f, 1]
        r0 = MR[st]
        while par[r0] != r0:
            r0 = par[r0]
        for j in range(1, MF[f, 2]):
            r1 = MR[st + j]
            while par[r1] != r1:
                r1 = par[r1]
            if r1 != r0:
                par[r1] = r0
    npc = 0
    for v in range(nv):
        if par[v] == v:
            npc += 1
    for v in range(nv):
        for c in range(3):
            oV[v, c] = MV[v, c] + o[c]
    q = 0
    for f in range(nf):
        oF[f, 0] = MF[f, 0]
        oF[f, 1] = MF[f, 2]
        for s in range(MF[f, 1], MF[f, 1] + MF[f, 2]):
            oR[q] = MR[s]
            q += 1
    return (
        nv,
        nf,
        nr,
        vol,
        mx / vol + ref[0] + o[0],
        my / vol + ref[1] + o[1],
        mz / vol + ref[2] + o[2],
        npc,
    )
