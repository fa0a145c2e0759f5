"""Restricted Voronoi diagram on a triangle mesh: each triangle cut by bisector planes.

A site's restricted cell is the part of the surface nearer to it (3D distance) than to any
other site, the way geogram's RVD defines it. Each triangle is handled on its own, in a 2D
frame of its plane (``A`` at the origin, ``AB`` along ``x``, ``C`` above it): a bisector plane
of two sites meets the plane in a line whose signed function is affine there, so the shared
convex cut (:func:`voroforge.kernels.clip.cut_ring`, values per vertex from
:func:`~voroforge.kernels.clip.plane_values`) cuts the triangle exactly as it cuts 2D cells,
owners carried per edge. A Voronoi cell is convex, so a triangle whose three corners have one
nearest site lies in that cell whole (most triangles when the mesh is finer than the cells).

Edge owners of a piece: ``j >= 0`` is the bisector with site ``j``; ``-1 - k`` is the
triangle's edge ``k`` (from corner ``k`` to ``k + 1``). The caller names each piece vertex
from its two edges' owners (mesh vertex, mesh edge x bisector, or three sites in a triangle).

Candidates per triangle come from a bucket grid of the sites (shell search for each mesh
vertex's nearest site, then a box query with a reach no owner of the triangle can exceed).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import NJIT
from .clip import cut_ring, plane_values
from .moments import ring_sums


@njit(**NJIT)
def _grow_f(a, n):
    """``a`` when slot ``n`` fits, else a copy twice as long."""
    if n < a.shape[0]:
        return a
    b = np.zeros(2 * a.shape[0])
    b[: a.shape[0]] = a
    return b


@njit(**NJIT)
def _grow_i(a, n):
    """``a`` when slot ``n`` fits, else a copy twice as long."""
    if n < a.shape[0]:
        return a
    b = np.zeros(2 * a.shape[0], a.dtype)
    b[: a.shape[0]] = a
    return b


@njit(**NJIT)
def site_grid(sites, lo, hi, h):
    """Sites counting-sorted into cubic buckets of side ``h`` over the box ``lo..hi`` (CSR)."""
    dims = np.zeros(3, np.int64)
    for d in range(3):
        dims[d] = max(1, int((hi[d] - lo[d]) / h) + 1)
    nb = dims[0] * dims[1] * dims[2]
    start = np.zeros(nb + 1, np.int64)
    ids = np.zeros(sites.shape[0], np.int64)
    for j in range(sites.shape[0]):
        b = _bucket(sites[j, 0], sites[j, 1], sites[j, 2], lo, h, dims)
        ids[j] = b
        start[b + 1] += 1
    for b in range(nb):
        start[b + 1] += start[b]
    fill = start[:-1].copy()
    items = np.zeros(sites.shape[0], np.int64)
    for j in range(sites.shape[0]):
        items[fill[ids[j]]] = j
        fill[ids[j]] += 1
    return dims, start, items


@njit(**NJIT)
def _cell(x, lo, h, n):
    k = int(np.floor((x - lo) / h))
    return min(max(k, 0), n - 1)


@njit(**NJIT)
def _bucket(x, y, z, lo, h, dims):
    i = _cell(x, lo[0], h, dims[0])
    j = _cell(y, lo[1], h, dims[1])
    k = _cell(z, lo[2], h, dims[2])
    return (i * dims[1] + j) * dims[2] + k


@njit(**NJIT)
def nearest_site(x, y, z, sites, lo, h, dims, start, items):
    """The site nearest to ``(x, y, z)`` and its squared distance.

    Shells of buckets outwards until no unscanned bucket can hold a nearer one (the stop test).
    """
    ci = _cell(x, lo[0], h, dims[0])
    cj = _cell(y, lo[1], h, dims[1])
    ck = _cell(z, lo[2], h, dims[2])
    best = -1
    bd = np.inf
    rmax = max(dims[0], max(dims[1], dims[2]))
    for r in range(rmax + 1):
        for i in range(max(ci - r, 0), min(ci + r, dims[0] - 1) + 1):
            ei = abs(i - ci) == r
            for j in range(max(cj - r, 0), min(cj + r, dims[1] - 1) + 1):
                ej = ei or abs(j - cj) == r
                for k in range(max(ck - r, 0), min(ck + r, dims[2] - 1) + 1):
                    if not (ej or abs(k - ck) == r):
                        continue
                    b = (i * dims[1] + j) * dims[2] + k
                    for q in range(start[b], start[b + 1]):
                        s = items[q]
                        dx = sites[s, 0] - x
                        dy = sites[s, 1] - y
                        dz = sites[s, 2] - z
                        dd = dx * dx + dy * dy + dz * dz
                        if dd < bd or (dd == bd and s < best):
                            bd = dd
                            best = s
        # a bucket of the next shell is at least r * h away (the point may sit anywhere in
        # its own bucket, or outside the grid, which only makes the others farther)
        if best >= 0 and bd <= (r * h) ** 2:
            break
    return best, bd


@njit(**NJIT)
def _prepare(v, sites, h):
    """The sites' grid over the box of mesh and sites, and each mesh vertex's nearest site."""
    lo = np.zeros(3)
    hi = np.zeros(3)
    for d in range(3):
        lo[d] = np.inf
        hi[d] = -np.inf
        for a in range(v.shape[0]):
            lo[d] = min(lo[d], v[a, d])
            hi[d] = max(hi[d], v[a, d])
        for a in range(sites.shape[0]):
            lo[d] = min(lo[d], sites[a, d])
            hi[d] = max(hi[d], sites[a, d])
    dims, start, items = site_grid(sites, lo, hi, h)
    vnear = np.zeros(v.shape[0], np.int64)
    vd = np.zeros(v.shape[0])
    for a in range(v.shape[0]):
        s, dd = nearest_site(v[a, 0], v[a, 1], v[a, 2], sites, lo, h, dims, start, items)
        vnear[a] = s
        vd[a] = np.sqrt(dd)
    return lo, dims, start, items, vnear, vd


@njit(**NJIT)
def _gather(gx, gy, gz, reach, sites, lo, h, dims, start, items, cand, cdist):
    """Sites within ``reach`` of ``g``, nearest first, into ``cand``/``cdist`` (grown as needed).

    Returns the count and the (possibly new) arrays.
    """
    i0 = _cell(gx - reach, lo[0], h, dims[0])
    i1 = _cell(gx + reach, lo[0], h, dims[0])
    j0 = _cell(gy - reach, lo[1], h, dims[1])
    j1 = _cell(gy + reach, lo[1], h, dims[1])
    k0 = _cell(gz - reach, lo[2], h, dims[2])
    k1 = _cell(gz + reach, lo[2], h, dims[2])
    m = 0
    r2 = reach * reach
    for i in range(i0, i1 + 1):
        for j in range(j0, j1 + 1):
            for k in range(k0, k1 + 1):
                b = (i * dims[1] + j) * dims[2] + k
                for q in range(start[b], start[b + 1]):
                    s = items[q]
                    dx = sites[s, 0] - gx
                    dy = sites[s, 1] - gy
                    dz = sites[s, 2] - gz
                    dd = dx * dx + dy * dy + dz * dz
                    if dd > r2:
                        continue
                    cand = _grow_i(cand, m)
                    cdist = _grow_f(cdist, m)
                    p = m
                    while p > 0 and (cdist[p - 1] > dd or (cdist[p - 1] == dd and cand[p - 1] > s)):
                        cand[p] = cand[p - 1]
                        cdist[p] = cdist[p - 1]
                        p -= 1
                    cand[p] = s
                    cdist[p] = dd
                    m += 1
    return m, cand, cdist


@njit(**NJIT)
def _relevant(v, ia, ib, ic, vnear, sites, cand, m):
    """Keep the candidates that can own a point of triangle ``ia ib ic``; returns the count.

    A site ``j`` owns none of it when some corner owner ``o`` is nearer than ``j`` to all three
    corners (the triangle lies in ``o``'s half-space against ``j``, a convex set). Cutting
    only by the kept ones is exact: a point nearer to ``i`` than to every kept site is
    nearer to ``i`` than to any site, since its nearest site owns it and is kept.
    """
    out = 0
    for q in range(m):
        j = cand[q]
        keep = True
        for oc in range(3):
            o = vnear[ia] if oc == 0 else (vnear[ib] if oc == 1 else vnear[ic])
            if o == j:
                continue
            beaten = True
            for w in range(3):
                a = ia if w == 0 else (ib if w == 1 else ic)
                do = 0.0
                dj = 0.0
                for d in range(3):
                    do += (v[a, d] - sites[o, d]) ** 2
                    dj += (v[a, d] - sites[j, d]) ** 2
                if not do < dj:
                    beaten = False
                    break
            if beaten:
                keep = False
                break
        if keep:
            cand[out] = j
            out += 1
    return out


@njit(**NJIT)
def _cut_by_others(q, cand, m_c, sites, frame, rx, ry, ro, sx, sy, so, ss):
    """The triangle cut to candidate ``q``'s side of every other candidate's bisector.

    The caller sets the triangle in ``rx, ry, ro[:3]``. Returns the vertex count (0: empty).
    """
    ax, ay, az, e1x, e1y, e1z, e2x, e2y, e2z = frame
    i = cand[q]
    six, siy, siz = sites[i, 0], sites[i, 1], sites[i, 2]
    m = 3
    for w in range(m_c):
        j = cand[w]
        if j == i:
            continue
        gx = sites[j, 0] - six
        gy = sites[j, 1] - siy
        gz = sites[j, 2] - siz
        hh = -(
            gx * (ax - 0.5 * (sites[j, 0] + six))
            + gy * (ay - 0.5 * (sites[j, 1] + siy))
            + gz * (az - 0.5 * (sites[j, 2] + siz))
        )
        px = gx * e1x + gy * e1y + gz * e1z
        py = gx * e2x + gy * e2y + gz * e2z
        if plane_values(rx, ry, 0, m, px, py, 0.0, 0.0, hh, ss) <= 0.0:
            continue
        m = cut_ring(rx, ry, ro, 0, m, ss, sx, sy, so, 0, j)
        if m < 3:
            return 0
        for k in range(m):
            rx[k] = sx[k]
            ry[k] = sy[k]
            ro[k] = so[k]
    return m


@njit(**NJIT)
def rvd(v, f, sites, h, store):
    """Cut every triangle of mesh ``(v, f)`` into the restricted cells of ``sites``.

    Parameters
    ----------
    v : (V, 3) float64
    f : (F, 3) int64, triangles (any consistent orientation; degenerate ones are skipped)
    sites : (n, 3) float64
    h : float, bucket side of the site grid (about the sites' spacing)
    store : bool, also return every piece's vertices (3D) and edge owners

    Returns
    -------
    mass (n,), first (n, 3) (∫ x dA), energy (n,) (∫ |x - s|^2 dA), piece_cell (p,),
    piece_tri (p,), piece_area (p,), offsets (p + 1,), coords (q, 3), codes (q,)
    (the last two empty unless ``store``; see :func:`_store` for the codes).

    Candidates of a triangle: every site ``s`` with ``|s - c| <= R + U``, ``c`` the centroid,
    ``R`` the largest distance from it to a corner and ``U = min_a (r_a + l_a)`` a bound on the
    distance from any point of the triangle to its nearest site (``r_a`` corner ``a``'s nearest
    distance, ``l_a`` its longer edge): no other site can own a point of the triangle.
    """
    n = sites.shape[0]
    lo, dims, gstart, gitems, vnear, vd = _prepare(v, sites, h)
    mass = np.zeros(n)
    first = np.zeros((n, 3))
    energy = np.zeros(n)
    cap = max(16, f.shape[0] + f.shape[0] // 2)
    pc = np.zeros(cap, np.int64)
    pt = np.zeros(cap, np.int64)
    pa = np.zeros(cap)
    off = np.zeros(cap + 1, np.int64)
    qcap = 4 * cap if store else 1
    qxyz = np.zeros((qcap, 3))
    qown = np.zeros(qcap, np.int64)
    np_ = 0
    nq = 0
    cand = np.zeros(64, np.int64)
    cdist = np.zeros(64)
    rx = np.zeros(72)
    ry = np.zeros(72)
    ro = np.zeros(72, np.int64)
    sx = np.zeros(72)
    sy = np.zeros(72)
    so = np.zeros(72, np.int64)
    ss = np.zeros(72)
    for t in range(f.shape[0]):
        ia = f[t, 0]
        ib = f[t, 1]
        ic = f[t, 2]
        ax, ay, az = v[ia, 0], v[ia, 1], v[ia, 2]
        abx, aby, abz = v[ib, 0] - ax, v[ib, 1] - ay, v[ib, 2] - az
        acx, acy, acz = v[ic, 0] - ax, v[ic, 1] - ay, v[ic, 2] - az
        nx = aby * acz - abz * acy
        ny = abz * acx - abx * acz
        nz = abx * acy - aby * acx
        nn = np.sqrt(nx * nx + ny * ny + nz * nz)
        lab = np.sqrt(abx * abx + aby * aby + abz * abz)
        if nn == 0.0 or lab == 0.0:
            continue
        nx /= nn
        ny /= nn
        nz /= nn
        e1x, e1y, e1z = abx / lab, aby / lab, abz / lab
        e2x = ny * e1z - nz * e1y
        e2y = nz * e1x - nx * e1z
        e2z = nx * e1y - ny * e1x
        frame = (ax, ay, az, e1x, e1y, e1z, e2x, e2y, e2z)
        # the triangle in its plane's frame
        cxx = acx * e1x + acy * e1y + acz * e1z
        cyy = acx * e2x + acy * e2y + acz * e2z
        if vnear[ia] == vnear[ib] and vnear[ib] == vnear[ic]:
            m_c = 1  # a convex cell holds the triangle of its three corners whole
            cand[0] = vnear[ia]
        else:
            gx = ax + (abx + acx) / 3.0
            gy = ay + (aby + acy) / 3.0
            gz = az + (abz + acz) / 3.0
            rad = 0.0
            for k in range(3):
                w = f[t, k]
                rad = max(
                    rad, np.sqrt((v[w, 0] - gx) ** 2 + (v[w, 1] - gy) ** 2 + (v[w, 2] - gz) ** 2)
                )
            lbc = np.sqrt(
                (v[ic, 0] - v[ib, 0]) ** 2 + (v[ic, 1] - v[ib, 1]) ** 2 + (v[ic, 2] - v[ib, 2]) ** 2
            )
            lac = np.sqrt(acx * acx + acy * acy + acz * acz)
            reach = min(vd[ia] + max(lab, lac), vd[ib] + max(lab, lbc), vd[ic] + max(lac, lbc))
            reach = (reach + rad) * (1.0 + 1e-12)
            m_c, cand, cdist = _gather(
                gx, gy, gz, reach, sites, lo, h, dims, gstart, gitems, cand, cdist
            )
            m_c = _relevant(v, ia, ib, ic, vnear, sites, cand, m_c)
            if m_c + 8 > rx.shape[0]:
                rx = np.zeros(2 * m_c + 8)
                ry = np.zeros(2 * m_c + 8)
                ro = np.zeros(2 * m_c + 8, np.int64)
                sx = np.zeros(2 * m_c + 8)
                sy = np.zeros(2 * m_c + 8)
                so = np.zeros(2 * m_c + 8, np.int64)
                ss = np.zeros(2 * m_c + 8)
        for q in range(m_c):
            i = cand[q]
            rx[0] = 0.0
            ry[0] = 0.0
            rx[1] = lab
            ry[1] = 0.0
            rx[2] = cxx
            ry[2] = cyy
            ro[0] = -1
            ro[1] = -2
            ro[2] = -3
            m = _cut_by_others(q, cand, m_c, sites, frame, rx, ry, ro, sx, sy, so, ss)
            if m < 3:
                continue
            # area, centroid and ∫|x - s|^2 in the plane's frame (s projected, plus height^2)
            dsx, dsy, dsz = sites[i, 0] - ax, sites[i, 1] - ay, sites[i, 2] - az
            ox = dsx * e1x + dsy * e1y + dsz * e1z
            oy = dsx * e2x + dsy * e2y + dsz * e2z
            hz = dsx * nx + dsy * ny + dsz * nz
            a2, mx, my, m2 = ring_sums(rx, ry, 0, m, ox, oy, False)
            area = 0.5 * a2
            if area <= 0.0:
                continue
            cgx = ox + mx / 6.0 / area
            cgy = oy + my / 6.0 / area
            mass[i] += area
            first[i, 0] += area * (ax + cgx * e1x + cgy * e2x)
            first[i, 1] += area * (ay + cgx * e1y + cgy * e2y)
            first[i, 2] += area * (az + cgx * e1z + cgy * e2z)
            energy[i] += m2 / 12.0 + hz * hz * area
            pc = _grow_i(pc, np_)
            pt = _grow_i(pt, np_)
            pa = _grow_f(pa, np_)
            off = _grow_i(off, np_ + 1)
            pc[np_] = i
            pt[np_] = t
            pa[np_] = area
            if store:
                nq = _store(qxyz, qown, nq, rx, ry, ro, m, frame, lab, cxx, cyy)
                if nq < 0:
                    qxyz = _grow_xyz(qxyz)
                    qown = _grow_i(qown, qown.shape[0])
                    nq = _store(qxyz, qown, -nq - 1, rx, ry, ro, m, frame, lab, cxx, cyy)
            np_ += 1
            off[np_] = nq
    return (
        mass,
        first,
        energy,
        pc[:np_].copy(),
        pt[:np_].copy(),
        pa[:np_].copy(),
        off[: np_ + 1].copy(),
        qxyz[:nq].copy(),
        qown[:nq].copy(),
    )


@njit(**NJIT)
def _grow_xyz(a):
    b = np.zeros((2 * a.shape[0] + 64, 3))
    b[: a.shape[0]] = a
    return b


@njit(**NJIT)
def _store(qxyz, qown, nq, rx, ry, ro, m, frame, lab, cxx, cyy):
    """Append a piece's vertices (mapped back to 3D) and codes; ``-1 - nq`` when full.

    The code of vertex ``k`` is ``4 * owner + corner + 1``: the owner of the edge from it to the
    next vertex, and which triangle corner it is (exactly: a vertex on a cut line is kept
    unmoved), ``-1`` for a cut vertex.
    """
    if nq + m > qxyz.shape[0] or nq + m > qown.shape[0]:
        return -1 - nq
    ax, ay, az, e1x, e1y, e1z, e2x, e2y, e2z = frame
    for k in range(m):
        qxyz[nq + k, 0] = ax + rx[k] * e1x + ry[k] * e2x
        qxyz[nq + k, 1] = ay + rx[k] * e1y + ry[k] * e2y
        qxyz[nq + k, 2] = az + rx[k] * e1z + ry[k] * e2z
        corner = -1
        if ry[k] == 0.0 and rx[k] == 0.0:
            corner = 0
        elif ry[k] == 0.0 and rx[k] == lab:
            corner = 1
        elif rx[k] == cxx and ry[k] == cyy:
            corner = 2
        qown[nq + k] = 4 * ro[k] + corner + 1
    return nq + m


@njit(**NJIT)
def _dot(ax, ay, az, bx, by, bz):
    return ax * bx + ay * by + az * bz


@njit(**NJIT)
def closest_on_triangle(px, py, pz, v, ia, ib, ic):
    """The point of triangle ``v[ia] v[ib] v[ic]`` nearest to ``p`` (Ericson's regions)."""
    ax, ay, az = v[ia, 0], v[ia, 1], v[ia, 2]
    abx, aby, abz = v[ib, 0] - ax, v[ib, 1] - ay, v[ib, 2] - az
    acx, acy, acz = v[ic, 0] - ax, v[ic, 1] - ay, v[ic, 2] - az
    d1 = _dot(abx, aby, abz, px - ax, py - ay, pz - az)
    d2 = _dot(acx, acy, acz, px - ax, py - ay, pz - az)
    if d1 <= 0.0 and d2 <= 0.0:
        return ax, ay, az
    bx, by, bz = v[ib, 0], v[ib, 1], v[ib, 2]
    d3 = _dot(abx, aby, abz, px - bx, py - by, pz - bz)
    d4 = _dot(acx, acy, acz, px - bx, py - by, pz - bz)
    if d3 >= 0.0 and d4 <= d3:
        return bx, by, bz
    vc = d1 * d4 - d3 * d2
    if vc <= 0.0 and d1 >= 0.0 and d3 <= 0.0:
        t = d1 / (d1 - d3)
        return ax + t * abx, ay + t * aby, az + t * abz
    cx, cy, cz = v[ic, 0], v[ic, 1], v[ic, 2]
    d5 = _dot(abx, aby, abz, px - cx, py - cy, pz - cz)
    d6 = _dot(acx, acy, acz, px - cx, py - cy, pz - cz)
    if d6 >= 0.0 and d5 <= d6:
        return cx, cy, cz
    vb = d5 * d2 - d1 * d6
    if vb <= 0.0 and d2 >= 0.0 and d6 <= 0.0:
        t = d2 / (d2 - d6)
        return ax + t * acx, ay + t * acy, az + t * acz
    va = d3 * d6 - d5 * d4
    if va <= 0.0 and (d4 - d3) >= 0.0 and (d5 - d6) >= 0.0:
        t = (d4 - d3) / ((d4 - d3) + (d5 - d6))
        return bx + t * (cx - bx), by + t * (cy - by), bz + t * (cz - bz)
    den = 1.0 / (va + vb + vc)
    s = vb * den
    t = vc * den
    return ax + abx * s + acx * t, ay + aby * s + acy * t, az + abz * s + acz * t


@njit(**NJIT)
def project_pieces(v, f, points, owner, tris, out):
    """Each ``points[i]`` moved to the nearest point of the triangles listed for it.

    ``owner[k]``/``tris[k]``: triangle ``tris[k]`` is a candidate of point ``owner[k]``; points
    without a triangle keep their place. Writes ``out`` and returns the distance moved.
    """
    n = points.shape[0]
    best = np.full(n, np.inf)
    for i in range(n):
        out[i, 0] = points[i, 0]
        out[i, 1] = points[i, 1]
        out[i, 2] = points[i, 2]
    for k in range(owner.shape[0]):
        i = owner[k]
        t = tris[k]
        qx, qy, qz = closest_on_triangle(
            points[i, 0], points[i, 1], points[i, 2], v, f[t, 0], f[t, 1], f[t, 2]
        )
        dd = (qx - points[i, 0]) ** 2 + (qy - points[i, 1]) ** 2 + (qz - points[i, 2]) ** 2
        if dd < best[i]:
            best[i] = dd
            out[i, 0] = qx
            out[i, 1] = qy
            out[i, 2] = qz
    return np.sqrt(best)


@njit(**NJIT)
def chain_rings(cell, start, end, n):
    """Boundary segments of each cell chained into closed rings.

    ``(cell, start, end)`` sorted by ``(cell, start)``: segment ``start -> end`` (vertex ids) of
    a cell's boundary. Returns ``ring_vertex`` (ids in ring order), ``ring_off`` (CSR into it)
    and ``cell_ring_off`` (``n + 1``: the rings of each cell). A chain that does not close
    (a degenerate piece) ends where it stops.
    """
    s = cell.shape[0]
    used = np.zeros(s, np.bool_)
    rv = np.zeros(s, np.int64)
    roff = np.zeros(s + 1, np.int64)
    coff = np.zeros(n + 1, np.int64)
    nv = 0
    nr = 0
    lo = 0
    for c in range(n):
        hi = lo
        while hi < s and cell[hi] == c:
            hi += 1
        for k0 in range(lo, hi):
            if used[k0]:
                continue
            k = k0
            while True:
                used[k] = True
                rv[nv] = start[k]
                nv += 1
                target = end[k]
                if target == start[k0]:
                    break
                # binary search for the segment that starts at target
                a = lo
                b = hi
                while a < b:
                    mid = (a + b) // 2
                    if start[mid] < target:
                        a = mid + 1
                    else:
                        b = mid
                found = -1
                while a < hi and start[a] == target:
                    if not used[a]:
                        found = a
                        break
                    a += 1
                if found < 0:
                    break
                k = found
            nr += 1
            roff[nr] = nv
        coff[c + 1] = nr
        lo = hi
    return rv[:nv].copy(), roff[: nr + 1].copy(), coff
