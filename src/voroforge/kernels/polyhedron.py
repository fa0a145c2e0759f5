"""The convex cut in 3D: a polyhedron against a half-space given by signed values per vertex.

The same cut as :mod:`kernels.clip` one dimension up. A convex polyhedron is held as

``V (cap, 3) float64``
    vertex coordinates (rows ``0:nv``), in whatever frame the caller likes (the cell
    builder keeps them relative to the cell's site);
``F (cap, 3) int64``
    faces ``0:nf`` as ``(label, start, length)``: the face's owner (a site, or ``-1 - w``
    for wall ``w``) and its ring ``R[start:start + length]`` of vertex numbers, counter
    clockwise seen from outside (outward normals by the right-hand rule);
``R (cap,) int64``
    the rings, one after the other.

:func:`cut` keeps the part where the caller's signed values ``S`` are ``<= 0``:

- a vertex with ``s <= 0`` is kept as it is (the caller snaps values within its tolerance of
  the plane to exactly 0, so a vertex on the plane is never moved or duplicated);
- an edge crossing the plane gets one new vertex, shared by the two faces of the edge,
  interpolated from the endpoint **nearer the plane** (as :func:`kernels.clip.crossing`);
- every face keeps its label; the new face along the plane gets the caller's ``label``. Its
  ring is made of the kept faces' edges that lie on the plane and have no twin: each such
  edge ``p -> q`` gives the cap's edge ``q -> p``;
- a plane that only touches the polyhedron (no value above 0) changes nothing; the vertices
  it touches are reported so the caller can add the plane to their owners (the vertex rule
  names a vertex by *all* the sites it is equidistant from).

Vertices no face uses any more are dropped and the rest renumbered (:func:`compact`).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import NJIT

#: status codes of :func:`cut`
CUT_NONE = 0  # the plane does not cut (maybe touches)
CUT_DONE = 1  # cut
CUT_EMPTY = 2  # nothing is left
CUT_OVERFLOW = 3  # a scratch array is too small
CUT_BROKEN = 4  # the cap's edges do not close into one ring (rounding trouble)


@njit(**NJIT)
def plane_values(V, nv, nx, ny, nz, h, tol, S):
    """Signed values ``n . v - h`` of vertices ``0:nv`` into ``S``; ``|s| <= tol`` -> 0.

    Returns ``(smin, smax)``.
    """
    smin = np.inf
    smax = -np.inf
    for v in range(nv):
        s = nx * V[v, 0] + ny * V[v, 1] + nz * V[v, 2] - h
        if abs(s) <= tol:
            s = 0.0
        S[v] = s
        if s < smin:
            smin = s
        if s > smax:
            smax = s
    return smin, smax


@njit(**NJIT)
def _crossing(V, a, sa, b, sb, out):
    """Write the crossing of edge ``a, b`` (values of opposite sign) into ``V[out]``."""
    if abs(sa) > abs(sb):  # from the endpoint nearer the plane
        a, b = b, a
        sa, sb = sb, sa
    t = sa / (sa - sb)
    V[out, 0] = V[a, 0] + t * (V[b, 0] - V[a, 0])
    V[out, 1] = V[a, 1] + t * (V[b, 1] - V[a, 1])
    V[out, 2] = V[a, 2] + t * (V[b, 2] - V[a, 2])


@njit(**NJIT)
def cut(V, nv, F, nf, R, R2, S, work, label):
    """Cut polyhedron ``(V, nv, F, nf, R)`` by the plane whose values are ``S[:nv]``.

    ``R2`` is scratch of ``R``'s size, ``work (k, 4) int64`` scratch for the crossings and
    the cap's edges. The result replaces the input in place (faces are rebuilt through
    ``R2`` and copied back). Returns ``(status, nv, nf)``.
    """
    vcap = V.shape[0]
    fcap = F.shape[0]
    rcap = R.shape[0]
    wcap = work.shape[0]
    smin = np.inf
    smax = -np.inf
    for v in range(nv):
        smin = min(smin, S[v])
        smax = max(smax, S[v])
    if smax <= 0.0:
        return CUT_NONE, nv, nf
    if smin >= 0.0:
        return CUT_EMPTY, 0, 0
    nv0 = nv
    ncross = 0  # work[k] = (lo, hi, new vertex, -) for the crossings made so far
    nr2 = np.int64(0)  # not a literal: numba would compile compact() once more for it
    nf2 = 0
    for f in range(nf):
        lab = F[f, 0]
        st = F[f, 1]
        ln = F[f, 2]
        b = nr2
        for k in range(ln):
            a = R[st + k]
            c = R[st + k + 1] if k + 1 < ln else R[st]
            sa = S[a]
            sc = S[c]
            if sa <= 0.0:
                if nr2 >= rcap:
                    return CUT_OVERFLOW, nv, nf
                R2[nr2] = a
                nr2 += 1
            if (sa < 0.0 and sc > 0.0) or (sa > 0.0 and sc < 0.0):
                lo = min(a, c)
                hi = max(a, c)
                x = -1
                for q in range(ncross):
                    if work[q, 0] == lo and work[q, 1] == hi:
                        x = work[q, 2]
                        break
                if x < 0:
                    if nv >= vcap or ncross >= wcap:
                        return CUT_OVERFLOW, nv, nf
                    x = nv
                    _crossing(V, lo, S[lo], hi, S[hi], x)
                    S[x] = 0.0
                    nv += 1
                    work[ncross, 0] = lo
                    work[ncross, 1] = hi
                    work[ncross, 2] = x
                    ncross += 1
                if nr2 >= rcap:
                    return CUT_OVERFLOW, nv, nf
                R2[nr2] = x
                nr2 += 1
        if nr2 - b >= 3:
            if nf2 >= fcap:
                return CUT_OVERFLOW, nv, nf
            F[nf2, 0] = lab  # nf2 <= f: rows already read are overwritten
            F[nf2, 1] = b
            F[nf2, 2] = nr2 - b
            nf2 += 1
        else:
            nr2 = b
    # the cap: kept edges on the plane without a twin, reversed
    ne = 0
    for f in range(nf2):
        st = F[f, 1]
        ln = F[f, 2]
        for k in range(ln):
            p = R2[st + k]
            q = R2[st + k + 1] if k + 1 < ln else R2[st]
            if S[p] == 0.0 and S[q] == 0.0:
                twin = -1
                for e in range(ne):
                    if work[e, 0] == q and work[e, 1] == p:
                        twin = e
                        break
                if twin >= 0:  # both directions kept: not on the cap's boundary
                    ne -= 1
                    work[twin, 0] = work[ne, 0]
                    work[twin, 1] = work[ne, 1]
                    continue
                if ne >= wcap:
                    return CUT_OVERFLOW, nv, nf
                work[ne, 0] = p  # cap edge q -> p: succ(q) = p
                work[ne, 1] = q
                ne += 1
    if ne >= 3:
        if nf2 >= fcap or nr2 + ne > rcap:
            return CUT_OVERFLOW, nv, nf
        b = nr2
        cur = work[0, 1]
        for _ in range(ne):
            R2[nr2] = cur
            nr2 += 1
            nxt = -1
            for e in range(ne):
                if work[e, 1] == cur:
                    nxt = work[e, 0]
                    break
            if nxt < 0:
                return CUT_BROKEN, nv, nf
            cur = nxt
        if cur != R2[b]:
            return CUT_BROKEN, nv, nf
        F[nf2, 0] = label
        F[nf2, 1] = b
        F[nf2, 2] = ne
        nf2 += 1
    elif ne > 0:
        return CUT_BROKEN, nv, nf
    if nf2 < 4:
        return CUT_EMPTY, 0, 0
    for t in range(nr2):
        R[t] = R2[t]
    nv = compact(V, nv, F, nf2, R, nr2, S, nv0)
    return CUT_DONE, nv, nf2


@njit(**NJIT)
def compact(V, nv, F, nf, R, nr, S, keep_below):
    """Drop vertices no ring uses; renumber the rings. ``S`` is reused as the map.

    Returns the new vertex count. Vertex order is kept (old vertices first, then new).
    """
    for v in range(nv):
        S[v] = -1.0
    for t in range(nr):
        S[R[t]] = 0.0
    m = 0
    for v in range(nv):
        if S[v] == 0.0:
            if m != v:
                V[m, 0] = V[v, 0]
                V[m, 1] = V[v, 1]
                V[m, 2] = V[v, 2]
            S[v] = m
            m += 1
    for t in range(nr):
        R[t] = int(S[R[t]])
    return m


@njit(**NJIT)
def ring_count(F, nf):
    """Total ring length of faces ``0:nf`` (they are stored contiguously from 0)."""
    t = 0
    for f in range(nf):
        t += F[f, 2]
    return t


@njit(**NJIT)
def moments(V, F, nf, R):
    """Volume and first moment of a closed outward polyhedron (tetrahedra from the origin).

    Returns ``(volume, mx, my, mz)``; the centroid is ``m / volume``.
    """
    vol = 0.0
    mx = 0.0
    my = 0.0
    mz = 0.0
    for f in range(nf):
        st = F[f, 1]
        ln = F[f, 2]
        a = R[st]
        ax = V[a, 0]
        ay = V[a, 1]
        az = V[a, 2]
        for k in range(1, ln - 1):
            b = R[st + k]
            c = R[st + k + 1]
            bx = V[b, 0]
            by = V[b, 1]
            bz = V[b, 2]
            cx = V[c, 0]
            cy = V[c, 1]
            cz = V[c, 2]
            d = ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx)
            vol += d
            mx += d * (ax + bx + cx)
            my += d * (ay + by + cy)
            mz += d * (az + bz + cz)
    return vol / 6.0, mx / 24.0, my / 24.0, mz / 24.0


@njit(**NJIT)
def face_vector(V, R, st, ln):
    """Area vector of ring ``R[st:st + ln]``: ``|a|`` is its area, ``a / |a|`` its normal."""
    a = R[st]
    ox = V[a, 0]
    oy = V[a, 1]
    oz = V[a, 2]
    sx = 0.0
    sy = 0.0
    sz = 0.0
    for k in range(1, ln - 1):
        b = R[st + k]
        c = R[st + k + 1]
        ux = V[b, 0] - ox
        uy = V[b, 1] - oy
        uz = V[b, 2] - oz
        wx = V[c, 0] - ox
        wy = V[c, 1] - oy
        wz = V[c, 2] - oz
        sx += uy * wz - uz * wy
        sy += uz * wx - ux * wz
        sz += ux * wy - uy * wx
    return 0.5 * sx, 0.5 * sy, 0.5 * sz
