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

import math

import numpy as np
from numba import njit, prange

from ..config import NJIT, NJIT_PARALLEL


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
def _meets(T, t, cell_lo, cell_hi, f0, f1, farea, fpt, tol, buf_a, buf_b, at, a0, lo, h, dims):
    """Whether triangle ``t`` meets the cell (faces ``f0:f1``) grown by ``tol``.

    ``at``: the bucket being scanned; ``a0``: the cell's first bucket (per axis). A triangle
    listed in several of the cell's buckets is clipped in the first of them only (the
    least corner of its buckets and the cell's: the scan meets it first), False elsewhere.
    """
    first = True
    for c in range(3):
        x0 = min(T[t, 0, c], min(T[t, 1, c], T[t, 2, c]))
        x1 = max(T[t, 0, c], max(T[t, 1, c], T[t, 2, c]))
        if x1 < cell_lo[c] or x0 > cell_hi[c]:
            return False
        ta = min(dims[c] - 1, max(0, int((x0 - lo[c]) / h)))  # as tri_grid placed it
        first = first and at[c] == max(a0[c], ta)
    if not first:
        return False
    m, _ = clip_triangle(T, t, f0, f1, farea, fpt, tol, buf_a, buf_b)
    return m > 0


@njit(**NJIT)
def cell_buckets(f0, f1, roff, ring, verts, tol, lo, h, dims):
    """A cell's box grown by ``tol`` and its bucket range ``a0..a1`` (per axis, inclusive).

    The cell is faces ``f0:f1`` of the rings ``roff``/``ring`` into ``verts``; the grid is
    :func:`tri_grid`'s (origin ``lo``, bucket side ``h``, ``dims`` buckets per axis).
    Returns ``(cell_lo, cell_hi, a0, a1)``.
    """
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
    return cell_lo, cell_hi, a0, a1


@njit(**NJIT_PARALLEL)
def face_points(roff, ring, verts):
    """``(f, 3)``: the first vertex of each ring ``ring[roff[f]:roff[f + 1]]`` of ``verts``."""
    nf = roff.shape[0] - 1
    fpt = np.zeros((nf, 3))
    for f in prange(nf):
        v = ring[roff[f]]
        for c in range(3):
            fpt[f, c] = verts[v, c]
    return fpt


@njit(**NJIT_PARALLEL)
def touching_cells(cf, roff, ring, verts, farea, fpt, cells, T, lo, h, dims, start, items, tol):
    """``(n,) bool``: the cells that some triangle of ``T (m, 3, 3)`` meets.

    Cells as :meth:`Diagram3D.cell_face_table` gives them (faces ``cf``, rings
    ``roff``/``ring`` into ``verts``, outward area vectors ``farea``, a point of each face
    ``fpt``: :func:`face_points`), each grown by ``tol``; ``cells`` lists the cells to
    test, in the order to test them (near ones together: their vertices stay in the
    caches); triangles bucketed by :func:`tri_grid`.
    """
    n = cf.shape[0] - 1
    out = np.zeros(n, np.bool_)
    ny, nz = dims[1], dims[2]
    for j in prange(cells.shape[0]):
        i = cells[j]
        f0, f1 = cf[i], cf[i + 1]
        cell_lo, cell_hi, a0, a1 = cell_buckets(f0, f1, roff, ring, verts, tol, lo, h, dims)
        buf_a = np.zeros((3 + f1 - f0, 3))
        buf_b = np.zeros((3 + f1 - f0, 3))
        at = np.zeros(3, np.int64)
        hit = False
        for a in range(a0[0], a1[0] + 1):
            at[0] = a
            for b in range(a0[1], a1[1] + 1):
                at[1] = b
                for k in range(a0[2], a1[2] + 1):
                    at[2] = k
                    bk = (a * ny + b) * nz + k
                    for s in range(start[bk], start[bk + 1]):
                        t = items[s]
                        if _meets(
                            T,
                            t,
                            cell_lo,
                            cell_hi,
                            f0,
                            f1,
                            farea,
                            fpt,
                            tol,
                            buf_a,
                            buf_b,
                            at,
                            a0,
                            lo,
                            h,
                            dims,
                        ):
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
def mark_runs(src, s0, s1, used):
    """``used[src[s0[k]:s1[k]]] = True`` for each run ``k``."""
    for k in range(s0.shape[0]):
        for j in range(s0[k], s1[k]):
            used[src[j]] = True


@njit(**NJIT)
def map_runs(src, s0, s1, dst, d0, remap):
    """``dst[d0[k]:d0[k] + s1[k] - s0[k]] = remap[src[s0[k]:s1[k]]]`` for each run ``k``."""
    for k in range(s0.shape[0]):
        o = d0[k] - s0[k]
        for j in range(s0[k], s1[k]):
            dst[j + o] = remap[src[j]]


@njit(**NJIT_PARALLEL)
def pow2_rows(a):
    """``a (m, 3)``, each row scaled by a power of two: its largest ``|x|`` in ``[0.5, 1)``.

    ``np.ldexp(a, -np.frexp(np.abs(a).max(axis=1))[1][:, None])`` in one pass, the same
    bits (zero rows and rows with a non-finite entry as they were).
    """
    out = np.zeros(a.shape)
    for f in prange(a.shape[0]):
        e = 0
        if np.isfinite(a[f, 0]) and np.isfinite(a[f, 1]) and np.isfinite(a[f, 2]):
            mx = max(abs(a[f, 0]), max(abs(a[f, 1]), abs(a[f, 2])))
            if mx > 0.0:
                e = math.frexp(mx)[1]
        for c in range(3):
            out[f, c] = math.ldexp(a[f, c], -e)
    return out


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


@njit(**NJIT)
def clip_triangle(T, t, f0, f1, farea, fpt, tol, buf_a, buf_b):
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


@njit(**NJIT_PARALLEL)
def thin_faces(farea, roff, ring, verts, rtol, noise):
    """``(f,) bool``: faces whose area is at most ``rtol D^2 + noise M D``.

    ``D``: the largest extent of the face's ring (``roff``/``ring`` into ``verts``) along an
    axis, ``M``: its vertices' largest coordinate; ``farea (f, 3)``: the area vectors. Both
    sides are divided by ``D`` and the area's norm is taken scaled by its largest component
    (no squares: no overflow at sides ~1e154, no underflow below ~1e-154). A face with no
    extent is thin; one with no ring is not.
    """
    nf = farea.shape[0]
    out = np.zeros(nf, np.bool_)
    for f in prange(nf):
        a, b = roff[f], roff[f + 1]
        if b == a:
            continue
        D = 0.0
        M = 0.0
        for c in range(3):
            lo = np.inf
            hi = -np.inf
            for s in range(a, b):
                x = verts[ring[s], c]
                lo = min(lo, x)
                hi = max(hi, x)
            D = max(D, hi - lo)
            M = max(M, max(abs(lo), abs(hi)))
        if not D > 0.0:
            out[f] = True
            continue
        mx = max(abs(farea[f, 0]), max(abs(farea[f, 1]), abs(farea[f, 2])))
        size = 0.0
        if mx > 0.0:
            x, y, z = farea[f, 0] / mx, farea[f, 1] / mx, farea[f, 2] / mx
            size = mx * np.sqrt(x * x + y * y + z * z)
        out[f] = size / D <= rtol * D + noise * M
    return out
