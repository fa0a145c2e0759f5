"""The face planes that the mesh cut clips by: thin faces take their normals from the sites.

:func:`mesh3d.cut_by_mesh` clips container triangles by each cell's face planes (normal: the
face's area vector, through its first vertex). A face that is a sliver or a segment (cells
meeting along one edge: k >= 5 sites on a circle around it, e.g. on a torus's centre circle,
give faces between sites that are not neighbours, rings of near-equal vertices along the
circle's axis) has an area vector made of rounding: its direction is noise, and the plane
through the axis that it gives cut away the part of a triangle inside the cell (a cell the
torus crossed counted as untouched and kept whole: the cells filled 2.75 of a 1.68 torus).
The plane of a face between sites ``i`` and ``j`` is normal to ``p_j - p_i`` (a power
bisector too), a box wall's normal is its axis: :func:`steady_normals` uses those where the
area vector is too small to carry a direction.
"""

from __future__ import annotations

import numpy as np

from ..config import FACE_NOISE_ULPS, FACE_THIN_RTOL, LOCAL_VERTEX_ULPS
from .readonly import readonly

#: outward normals of the box walls, label ``-1 - w`` (:func:`containers.box_template`)
_WALLS = np.array([[-1, 0, 0], [1, 0, 0], [0, -1, 0], [0, 1, 0], [0, 0, -1], [0, 0, 1]], float)


def steady_normals(farea, cf, lab, roff, ring, verts, sites):
    """``farea`` with each thin face's row replaced by its exact plane's normal.

    ``farea (f, 3)``: the faces' area vectors (:meth:`Diagram3D.cell_face_table`, cell ``i``'s
    faces ``cf[i]:cf[i + 1]``, labels ``lab``: a neighbour site ``>= 0`` or box wall
    ``-1 - w``); ``verts``: the vertices the rings ``roff``/``ring`` index; ``sites (n, 3)``
    in the same cell order. A thin face's new row points from its cell's site to the
    neighbour's (or along the wall's axis), scaled to its largest component in ``[0.5, 1)``.
    Other rows are returned as they were (the same bits; ``farea`` itself, as a contiguous
    float64 array, when no face is thin; else a copy).
    """
    farea = np.ascontiguousarray(farea, np.float64)
    if not len(farea):
        return farea.copy()
    thin = _thin(farea, roff, ring, verts, len(cf) - 1)
    if not thin.any():
        return farea
    return plane_rows(farea.copy(), np.flatnonzero(thin), cf, lab, sites)


def cut_planes(farea, cf, lab, roff, ring, verts, sites):
    """:func:`steady_normals`, each row then scaled by a power of two (exact).

    The row's largest component in ``[0.5, 1)`` (zero rows and rows with a non-finite entry
    as they were): the mesh cut squares these normals (their lengths), and a power of two
    per face keeps that from overflowing past sides ~1e77 and from underflowing below
    ~1e-77 with the same decisions. The same bits as ``steady_normals`` followed by
    ``np.ldexp(a, -np.frexp(np.abs(a).max(axis=1))[1][:, None])`` (a thin face's new row
    is already so scaled), in one pass over the rows and the rings in their own integer
    type (an int64 copy of a 100,000-cell table's 4.5M ring entries cost ~0.1 s).
    """
    from ..kernels.meshclip3d import pow2_rows
    from .threads import serial_below

    farea = np.ascontiguousarray(farea, np.float64)
    if not len(farea):
        return farea.copy()
    thin = _thin(farea, roff, ring, verts, len(cf) - 1)
    with serial_below(len(cf) - 1):
        out = pow2_rows(readonly(farea))  # (a frozen table's, as the engine passes it)
    if thin.any():
        plane_rows(out, np.flatnonzero(thin), cf, lab, sites)
    return out


def _thin(farea, roff, ring, verts, n):
    """:func:`kernels.meshclip3d.thin_faces` of ``n`` cells' faces (rings in their own type)."""
    from ..kernels.meshclip3d import thin_faces
    from .threads import serial_below

    with serial_below(n):
        return thin_faces(
            farea,
            np.ascontiguousarray(roff),
            np.ascontiguousarray(ring),
            np.ascontiguousarray(verts, np.float64),
            FACE_THIN_RTOL,
            FACE_NOISE_ULPS * np.finfo(np.float64).eps,
        )


def plane_rows(farea, f, cf, lab, sites):
    """``farea`` with rows ``f`` set to their exact planes' normals (in place; returned).

    A face between sites ``i`` and ``j`` gets ``p_j - p_i``, a box wall its axis, scaled to
    the largest component in ``[0.5, 1)``; a face of another kind, or between equal sites,
    keeps its row.
    """
    owner = np.repeat(np.arange(len(cf) - 1), np.diff(cf))[f]
    lf = np.asarray(lab)[f]
    nrm = np.zeros((len(f), 3))
    site = lf >= 0
    nrm[site] = sites[lf[site]] - sites[owner[site]]
    wall = (lf < 0) & (lf >= -6)
    nrm[wall] = _WALLS[-1 - lf[wall]]
    big = np.abs(nrm).max(axis=1)
    ok = big > 0
    nrm[ok] = np.ldexp(nrm[ok], -np.frexp(big[ok])[1][:, None])
    # a face of unknown kind or between equal sites keeps its row (no better plane)
    farea[f[ok]] = nrm[ok]
    return farea


def local_vertices(cells, cf, lab, roff, ring, verts, sites, weights, box, o):
    """``verts - o`` with the vertices of ``cells`` recomputed about the origin ``o``.

    For a mesh far from the origin (:func:`containers.far_origin`): a vertex in absolute
    doubles is placed only to half an ulp of its distance from the origin (2.3e-10 at 4e6,
    2.3e-7 of a 1e-3 cell), which made a cut cell's faces non-planar by that much and a
    1e-3 cube's two cells sum 2.2e-8 off its volume. Each vertex of ``cells`` is recomputed
    from three of the face planes of one cell ``c`` through it, about ``c``'s site (sites
    ``s = sites - o``, exact near the mesh: ``o`` is a multiple of a power of two above its
    extent): the bisector ``n . y = (n . n + w_c - w_j) / 2`` with ``n = s_j - s_c``, or a
    box wall ``box (2, 3)`` (absolute, ``-1 - w`` in voro++'s order). The three are the best
    conditioned of its planes; the result replaces ``verts[v] - o`` only where it lies
    within :data:`LOCAL_VERTEX_ULPS` ulps of ``verts[v]`` (the rounding the absolute vertex
    carries: an ulp of its largest coordinate, on every axis), so a vertex whose planes are ill
    conditioned keeps its place.
    """
    vl = verts - o
    cells = np.asarray(cells, np.int64)
    if not len(cells) or not len(verts):
        return vl
    nf = cf[cells + 1] - cf[cells]
    fidx = np.repeat(cf[cells], nf) + _ranks(nf)
    owner = np.repeat(cells, nf)
    lens = roff[fidx + 1] - roff[fidx]
    fv = ring[np.repeat(roff[fidx], lens) + _ranks(lens)]  # (v, face, cell) rows
    ff = np.repeat(fidx, lens)
    fc = np.repeat(owner, lens)
    order = np.lexsort((ff, fc, fv))
    fv, ff, fc = fv[order], ff[order], fc[order]
    first = np.r_[True, fv[1:] != fv[:-1]]
    start = np.flatnonzero(first)
    # one cell per vertex (its first): the faces of that cell through the vertex
    c0 = np.repeat(fc[start], np.diff(np.r_[start, len(fv)]))
    mine = fc == c0
    fv, ff, fc = fv[mine], ff[mine], fc[mine]
    start = np.flatnonzero(np.r_[True, fv[1:] != fv[:-1]])
    cnt = np.diff(np.r_[start, len(fv)])
    K = 8  # planes per vertex looked at (a vertex of more faces: its first eight)
    rank = _ranks(cnt)
    sel = rank < K
    nv = len(start)
    s = np.asarray(sites, np.float64) - o
    w = np.zeros(len(s)) if weights is None else np.asarray(weights, np.float64)
    lab = np.asarray(lab, np.int64)
    lo, hi = np.asarray(box, np.float64) - o
    N = np.zeros((nv, K, 3))
    H = np.zeros((nv, K))
    known = np.zeros((nv, K), bool)
    row = np.repeat(np.arange(nv), cnt)[sel]
    col = rank[sel]
    lf = lab[ff[sel]]
    c = fc[sel]
    site = lf >= 0
    j = np.where(site, lf, 0)
    n = s[j] - s[c]
    N[row[site], col[site]] = n[site]
    H[row[site], col[site]] = 0.5 * (np.einsum("ij,ij->i", n, n) + w[c] - w[j])[site]
    wall = (lf < 0) & (lf >= -6)
    wi = -1 - lf[wall]
    ax = wi // 2
    bound = np.where(wi % 2 == 1, hi[ax], lo[ax])
    sign = np.where(wi % 2 == 1, 1.0, -1.0)
    N[row[wall], col[wall]] = _WALLS[wi]
    H[row[wall], col[wall]] = sign * (bound - s[c[wall], ax])
    known[row[site | wall], col[site | wall]] = True
    ok = known.sum(axis=1) >= 3
    with np.errstate(invalid="ignore", divide="ignore"):
        U = N / np.linalg.norm(N, axis=2, keepdims=True)
    U = np.where(known[:, :, None], U, 0.0)
    a = np.argmax(known, axis=1)  # the first known plane
    ua = U[np.arange(nv), a]
    b = np.argmax(np.linalg.norm(np.cross(ua[:, None, :], U), axis=2), axis=1)
    ub = U[np.arange(nv), b]
    det = np.abs(np.einsum("ij,ikj->ik", np.cross(ua, ub), U))
    e = np.argmax(det, axis=1)
    ok &= det[np.arange(nv), e] > 0.0
    idx = np.stack([a, b, e], axis=1)
    A = np.take_along_axis(N, idx[:, :, None], axis=1)
    rhs = np.take_along_axis(H, idx, axis=1)
    A[~ok] = np.eye(3)
    rhs[~ok] = 0.0
    y = np.linalg.solve(A, rhs[:, :, None])[:, :, 0]
    v = fv[start]
    x = s[fc[start]] + y
    # the absolute vertex carries the rounding of its largest coordinate on every axis (a
    # mesh far along x only: y and z near 0 are still computed from x's ~1e10 products)
    ulp = np.spacing(np.abs(verts[v]).max(axis=1, keepdims=True))
    near = np.abs(x - vl[v]) <= LOCAL_VERTEX_ULPS * ulp
    ok &= near.all(axis=1) & np.isfinite(x).all(axis=1)
    vl[v[ok]] = x[ok]
    return vl


def _ranks(lens):
    """``0 .. len - 1`` for each run length in ``lens``, concatenated."""
    total = int(lens.sum())
    return np.arange(total) - np.repeat(np.cumsum(lens) - lens, lens)
