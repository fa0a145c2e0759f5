"""Restricted Voronoi diagram on a triangle mesh: each triangle cut by bisector planes.

A site's restricted cell is the part of the surface nearer to it (3D distance) than to any
other site, the way geogram's RVD defines it. Each triangle is handled on its own, in a 2D
frame of its plane (``A`` at the origin, ``AB`` along ``x``, ``C`` above it; the frames are
computed once per mesh by :func:`tri_frames`): a bisector plane of two sites meets the plane
in a line whose signed function is affine there, so the shared convex cut
(:func:`voroforge.kernels.clip.cut_ring`, values per vertex from
:func:`~voroforge.kernels.clip.plane_values`) cuts the triangle exactly as it cuts 2D cells,
owners carried per edge. A Voronoi cell is convex, so a triangle whose three corners have one
nearest site lies in that cell whole (most triangles when the mesh is finer than the cells):
its area, centroid and second moment come from the frames without any cut.

Edge owners of a piece: ``j >= 0`` is the bisector with site ``j``; ``-1 - k`` is the
triangle's edge ``k`` (from corner ``k`` to ``k + 1``). The caller names each piece vertex
from its two edges' owners (mesh vertex, mesh edge x bisector, or three sites in a triangle).

Candidates per triangle come from the sites' bucket grid of :mod:`kernels.grid3d` (shell
search for each mesh vertex's nearest site, started from a hint such as the previous
relaxation step's answer, then a box query with a reach no owner of the triangle can exceed).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import NJIT, SURFACE_LOCAL_CUT
from .grid3d import bucket3d, shell_buckets, shell_gap
from .moments import ring_sums
from .surfcut import cut_by_others, cut_local, gather, insert_by_distance

#: columns of :func:`tri_frames`
_E1, _E2, _N, _LAB, _CX, _CY, _AREA, _G, _J, _RAD, _LC = 0, 3, 6, 9, 10, 11, 12, 13, 16, 17, 18
FRAME_COLUMNS = 21


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
def tri_frames(v, f):
    """Per triangle, what every relaxation step needs of it (one row of ``FRAME_COLUMNS``).

    ``e1 (3)``, ``e2 (3)``, ``n (3)``: the plane's frame (``e1`` along ``AB``); ``|AB|`` and
    ``C``'s frame coordinates; the area, centroid ``g (3)`` and ``J = ∫ |x - g|^2 dA``
    (``A / 12`` times the corners' squared distances to ``g``); the largest distance from
    ``g`` to a corner; per corner the longer of its two edges. A degenerate triangle has area
    0 and is skipped by :func:`rvd`.
    """
    out = np.zeros((f.shape[0], FRAME_COLUMNS))
    for t in range(f.shape[0]):
        ia, ib, ic = f[t, 0], f[t, 1], f[t, 2]
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
        r = out[t]
        r[0], r[1], r[2] = e1x, e1y, e1z
        r[3] = ny * e1z - nz * e1y
        r[4] = nz * e1x - nx * e1z
        r[5] = nx * e1y - ny * e1x
        r[6], r[7], r[8] = nx, ny, nz
        r[_LAB] = lab
        r[_CX] = acx * e1x + acy * e1y + acz * e1z
        r[_CY] = acx * r[3] + acy * r[4] + acz * r[5]
        area = 0.5 * lab * r[_CY]
        r[_AREA] = area
        gx = ax + (abx + acx) / 3.0
        gy = ay + (aby + acy) / 3.0
        gz = az + (abz + acz) / 3.0
        r[13], r[14], r[15] = gx, gy, gz
        j = 0.0
        rad = 0.0
        for k in range(3):
            w = f[t, k]
            d2 = (v[w, 0] - gx) ** 2 + (v[w, 1] - gy) ** 2 + (v[w, 2] - gz) ** 2
            j += d2
            rad = max(rad, np.sqrt(d2))
        r[_J] = area * j / 12.0
        r[_RAD] = rad
        lbc = np.sqrt(
            (v[ic, 0] - v[ib, 0]) ** 2 + (v[ic, 1] - v[ib, 1]) ** 2 + (v[ic, 2] - v[ib, 2]) ** 2
        )
        lac = np.sqrt(acx * acx + acy * acy + acz * acz)
        r[_LC] = max(lab, lac)
        r[_LC + 1] = max(lab, lbc)
        r[_LC + 2] = max(lac, lbc)
    return out


@njit(**NJIT)
def nearest_site(x, y, z, sites, start, sidx, g, best, buf):
    """The site nearest to ``(x, y, z)`` (ties: the lower index) and its squared distance.

    ``best``: a hint (a site index, or -1). With a hint, the sites nearer than it lie in the
    box of half-side its distance around the point: that box is scanned when it spans few
    buckets (the usual case when the hint is the last relaxation step's answer). Otherwise
    shells of the grid ``g`` (:mod:`kernels.grid3d`; ``sidx`` the sites in bucket order,
    ``start`` the buckets' CSR) outwards until :func:`~voroforge.kernels.grid3d.shell_gap`
    shows no unscanned bucket can hold a nearer one, ``buf`` (room for every bucket)
    holding a shell's buckets.
    """
    bd = np.inf
    if best >= 0:
        bd = (sites[best, 0] - x) ** 2 + (sites[best, 1] - y) ** 2 + (sites[best, 2] - z) ** 2
        w = np.sqrt(bd) * (1.0 + 1e-12)
        i0, j0, k0 = bucket3d(x - w, y - w, z - w, g)
        i1, j1, k1 = bucket3d(x + w, y + w, z + w, g)
        if (i1 - i0 + 1) * (j1 - j0 + 1) * (k1 - k0 + 1) <= 27:
            nx = int(g[6])
            ny = int(g[7])
            for k in range(k0, k1 + 1):
                for j in range(j0, j1 + 1):
                    row = (k * ny + j) * nx
                    for b in range(row + i0, row + i1 + 1):
                        best, bd = _nearer(x, y, z, sites, start, sidx, b, best, bd)
            return best, bd
    ci, cj, ck = bucket3d(x, y, z, g)
    rmax = max(int(g[6]), max(int(g[7]), int(g[8])))
    for r in range(rmax + 1):
        nb = _shell(ci, cj, ck, r, g, buf)
        for u in range(nb):
            best, bd = _nearer(x, y, z, sites, start, sidx, buf[u], best, bd)
        gap = shell_gap(x, y, z, ci, cj, ck, r, g)
        if best >= 0 and bd <= gap * gap:
            break
    return best, bd


@njit(**NJIT)
def _nearer(x, y, z, sites, start, sidx, b, best, bd):
    """``(best, bd)`` updated by the sites of bucket ``b`` (ties: the lower index)."""
    for q in range(start[b], start[b + 1]):
        s = sidx[q]
        dd = (sites[s, 0] - x) ** 2 + (sites[s, 1] - y) ** 2 + (sites[s, 2] - z) ** 2
        if dd < bd or (dd == bd and s < best):
            bd = dd
            best = s
    return best, bd


@njit(**NJIT)
def site_knn(sites, start, sidx, g, k):
    """Each site's ``k`` nearest other sites, and a bound on the distance of all the others.

    Returns ``nbr (n, k)`` (by distance, then index; -1 past the last when there are fewer)
    and ``bound (n,)``: every site not listed for ``i`` is at least ``bound[i]`` from it
    (the ``k + 1``-th distance, found by the same shell search and stop test as
    :func:`nearest_site`; ``inf`` when every other site is listed).
    """
    n = sites.shape[0]
    nbr = np.full((n, k), -1, np.int64)
    bound = np.full(n, np.inf)
    buf = np.zeros(int(g[6] * g[7] * g[8]), np.int64)  # any shell fits
    cand = np.zeros(k + 2, np.int64)
    cdist = np.zeros(k + 2)
    rmax = max(int(g[6]), max(int(g[7]), int(g[8])))
    for i in range(n):
        x, y, z = sites[i, 0], sites[i, 1], sites[i, 2]
        ci, cj, ck = bucket3d(x, y, z, g)
        m = np.int64(0)
        for r in range(rmax + 1):
            nb = _shell(ci, cj, ck, r, g, buf)
            for u in range(nb):
                b = buf[u]
                for q in range(start[b], start[b + 1]):
                    s = sidx[q]
                    if s == i:
                        continue
                    dd = (sites[s, 0] - x) ** 2 + (sites[s, 1] - y) ** 2 + (sites[s, 2] - z) ** 2
                    if m < k + 1:
                        insert_by_distance(cand, cdist, m, s, dd)
                        m += 1
                    elif dd < cdist[k] or (dd == cdist[k] and s < cand[k]):
                        insert_by_distance(cand, cdist, k, s, dd)
            gap = shell_gap(x, y, z, ci, cj, ck, r, g)
            if m == k + 1 and cdist[k] <= gap * gap:
                break
        for q in range(min(m, k)):
            nbr[i, q] = cand[q]
        if m == k + 1:
            bound[i] = np.sqrt(cdist[k])
    return nbr, bound


@njit(**NJIT)
def _shell(ci, cj, ck, r, g, buf):
    """:func:`~voroforge.kernels.grid3d.shell_buckets` into ``buf``, which holds any shell."""
    return shell_buckets(ci, cj, ck, r, g, buf)


@njit(**NJIT)
def _take(s, gx, gy, gz, r2, sites, cand, cdist, m):
    """Site ``s`` into the sorted list ``cand[:m]`` when within ``sqrt(r2)``; the new count."""
    dd = (sites[s, 0] - gx) ** 2 + (sites[s, 1] - gy) ** 2 + (sites[s, 2] - gz) ** 2
    if dd <= r2:
        insert_by_distance(cand, cdist, m, s, dd)
        m += 1
    return m


@njit(**NJIT)
def _near_list(gx, gy, gz, reach, o, sites, nbr, bound, cand, cdist):
    """:func:`.surfcut.gather` from site ``o``'s neighbour list, or -1 when the list may miss one.

    Every site within ``reach`` of ``g`` is within ``reach + |g - s_o|`` of ``s_o``: when that
    is below ``bound[o]``, all of them are ``o`` or in ``o``'s list, and the result (the same
    sites in the same order) is :func:`.surfcut.gather`'s.
    """
    d0 = (sites[o, 0] - gx) ** 2 + (sites[o, 1] - gy) ** 2 + (sites[o, 2] - gz) ** 2
    if not (reach + np.sqrt(d0)) * (1.0 + 1e-12) < bound[o]:
        return -1
    r2 = reach * reach
    m = _take(o, gx, gy, gz, r2, sites, cand, cdist, np.int64(0))
    for q in range(nbr.shape[1]):
        if nbr[o, q] < 0:
            break
        m = _take(nbr[o, q], gx, gy, gz, r2, sites, cand, cdist, m)
    return m


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
def rvd(v, f, tf, sites, start, sidx, g, hint, mode, knn):
    """Cut every triangle of mesh ``(v, f)`` into the restricted cells of ``sites``.

    Parameters
    ----------
    v : (V, 3) float64
    f : (F, 3) int64, triangles (any consistent orientation; degenerate ones are skipped)
    tf : (F, FRAME_COLUMNS) float64, :func:`tri_frames` of the mesh
    sites : (n, 3) float64
    start, sidx, g : the sites' bucket grid (:mod:`kernels.grid3d`'s layout, covering the
        mesh and the sites; ``sidx`` the site numbers in bucket order)
    hint : (V,) int64, a guess of each mesh vertex's nearest site (-1: none)
    mode : 0 moments only, 1 also the pieces (cell, triangle, area), 2 also every piece's
        vertices (3D) and edge owners
    knn : int, length of each site's neighbour list (:func:`site_knn`): a triangle's
        candidates come from a corner owner's list when it provably holds them all, else
        from the grid (:func:`.surfcut.gather`); with more than
        ``SURFACE_LOCAL_CUT`` candidates each piece is cut by its own site's neighbours
        (:func:`.surfcut.cut_local`)

    Returns
    -------
    mass (n,), first (n, 3) (∫ x dA), energy (n,) (∫ |x - s|^2 dA), piece_cell (p,),
    piece_tri (p,), piece_area (p,), offsets (p + 1,), coords (q, 3), codes (q,) (see
    :func:`_store` for the codes), vnear (V,) (each mesh vertex's nearest site: the next
    call's hint).

    Candidates of a triangle: every site ``s`` with ``|s - c| <= R + U``, ``c`` the centroid,
    ``R`` the largest distance from it to a corner and ``U = min_a (r_a + l_a)`` a bound on the
    distance from any point of the triangle to its nearest site (``r_a`` corner ``a``'s nearest
    distance, ``l_a`` its longer edge): no other site can own a point of the triangle.
    """
    n = sites.shape[0]
    vnear = np.zeros(v.shape[0], np.int64)
    vd = np.zeros(v.shape[0])
    buf = np.zeros(int(g[6] * g[7] * g[8]), np.int64)  # any shell fits
    for a in range(v.shape[0]):
        s, dd = nearest_site(v[a, 0], v[a, 1], v[a, 2], sites, start, sidx, g, hint[a], buf)
        vnear[a] = s
        vd[a] = np.sqrt(dd)
    nbr, bound = site_knn(sites, start, sidx, g, knn)
    mass = np.zeros(n)
    first = np.zeros((n, 3))
    energy = np.zeros(n)
    cap = max(16, f.shape[0] + f.shape[0] // 2) if mode > 0 else 1
    pc = np.zeros(cap, np.int64)
    pt = np.zeros(cap, np.int64)
    pa = np.zeros(cap)
    off = np.zeros(cap + 1, np.int64)
    qcap = 4 * cap if mode > 1 else 1
    qxyz = np.zeros((qcap, 3))
    qown = np.zeros(qcap, np.int64)
    np_ = 0
    nq = np.int64(0)
    cand = np.zeros(n + 1, np.int64)
    js = np.zeros(n + 1, np.int64)
    cdist = np.zeros(n + 1)
    rx = np.zeros(72)
    ry = np.zeros(72)
    ro = np.zeros(72, np.int64)
    sx = np.zeros(72)
    sy = np.zeros(72)
    so = np.zeros(72, np.int64)
    ss = np.zeros(72)
    for t in range(f.shape[0]):
        r = tf[t]
        if r[_AREA] <= 0.0:
            continue
        ia = f[t, 0]
        ib = f[t, 1]
        ic = f[t, 2]
        ax, ay, az = v[ia, 0], v[ia, 1], v[ia, 2]
        frame = (ax, ay, az, r[0], r[1], r[2], r[3], r[4], r[5])
        o = vnear[ia]
        if o == vnear[ib] and o == vnear[ic]:
            m_c = 1  # a convex cell holds the triangle of its three corners whole
            cand[0] = o
        else:
            reach = min(vd[ia] + r[_LC], min(vd[ib] + r[_LC + 1], vd[ic] + r[_LC + 2]))
            reach = (reach + r[_RAD]) * (1.0 + 1e-12)
            m_c = -1
            for oc in range(3):
                m_c = _near_list(
                    r[13], r[14], r[15], reach, vnear[f[t, oc]], sites, nbr, bound, cand, cdist
                )
                if m_c >= 0:
                    break
            if m_c < 0:
                m_c = gather(r[13], r[14], r[15], reach, sites, start, sidx, g, cand, cdist)
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
            rx[0], ry[0], ro[0] = 0.0, 0.0, -1
            rx[1], ry[1], ro[1] = r[_LAB], 0.0, -2
            rx[2], ry[2], ro[2] = r[_CX], r[_CY], -3
            m = 3
            if m_c == 1:  # the whole triangle: its moments from the frames
                area = r[_AREA]
                cx, cy, cz = r[13], r[14], r[15]
                dg = (cx - sites[i, 0]) ** 2 + (cy - sites[i, 1]) ** 2 + (cz - sites[i, 2]) ** 2
                en = r[_J] + area * dg
            else:
                m = -1
                if m_c > SURFACE_LOCAL_CUT:  # many sites: each piece by its site's neighbours
                    ring = (rx, ry, ro, sx, sy, so, ss)
                    m = cut_local(i, sites, frame, nbr, bound, (start, sidx, g, buf, js), ring)
                if m < 0:
                    rx[0], ry[0], ro[0] = 0.0, 0.0, -1
                    rx[1], ry[1], ro[1] = r[_LAB], 0.0, -2
                    rx[2], ry[2], ro[2] = r[_CX], r[_CY], -3
                    m = cut_by_others(q, cand, m_c, sites, frame, rx, ry, ro, sx, sy, so, ss)
                if m < 3:
                    continue
                # area, centroid, ∫|x - s|^2 in the plane's frame. The shoelace sums run
                # about the piece's first vertex (relative to the site's projection, a far
                # site's distance squared swamped the area: checker14 F6); the energy about
                # the site from the one about the centroid (parallel axis theorem).
                x0, y0 = rx[0], ry[0]
                a2, mx, my, m2 = ring_sums(rx, ry, 0, m, x0, y0, False)
                area = 0.5 * a2
                if area <= 0.0:
                    continue
                lx = mx / 6.0 / area
                ly = my / 6.0 / area
                cgx = x0 + lx
                cgy = y0 + ly
                cx = ax + cgx * r[0] + cgy * r[3]
                cy = ay + cgx * r[1] + cgy * r[4]
                cz = az + cgx * r[2] + cgy * r[5]
                jg = max(m2 / 12.0 - area * (lx * lx + ly * ly), 0.0)  # about the centroid
                dg = (cx - sites[i, 0]) ** 2 + (cy - sites[i, 1]) ** 2 + (cz - sites[i, 2]) ** 2
                en = jg + area * dg
            mass[i] += area
            first[i, 0] += area * cx
            first[i, 1] += area * cy
            first[i, 2] += area * cz
            energy[i] += en
            if mode == 0:
                continue
            if np_ + 1 >= pc.shape[0]:
                pc, pt, pa, off = _grow_pieces(pc, pt, pa, off)
            pc[np_] = i
            pt[np_] = t
            pa[np_] = area
            if mode > 1:
                if nq + m > qxyz.shape[0]:
                    qxyz, qown = _room(qxyz, qown, nq + m)
                nq = _store(qxyz, qown, nq, rx, ry, ro, m, frame, r[_LAB], r[_CX], r[_CY])
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
        vnear,
    )


@njit(**NJIT)
def _grow_pieces(pc, pt, pa, off):
    """The piece arrays copied twice as long."""
    return (
        _grow_i(pc, pc.shape[0]),
        _grow_i(pt, pt.shape[0]),
        _grow_f(pa, pa.shape[0]),
        _grow_i(off, off.shape[0]),
    )


@njit(**NJIT)
def _room(qxyz, qown, need):
    """The vertex arrays copied, with room for ``need`` vertices at least."""
    size = 2 * need + 64
    b = np.zeros((size, 3))
    b[: qxyz.shape[0]] = qxyz
    c = np.zeros(size, np.int64)
    c[: qown.shape[0]] = qown
    return b, c


@njit(**NJIT)
def _store(qxyz, qown, nq, rx, ry, ro, m, frame, lab, cxx, cyy):
    """Append a piece's vertices (mapped back to 3D) and codes (room made by the caller).

    The code of vertex ``k`` is ``4 * owner + corner + 1``: the owner of the edge from it to the
    next vertex, and which triangle corner it is (exactly: a vertex on a cut line is kept
    unmoved), ``-1`` for a cut vertex.
    """
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
def _dots(ab, ac, px, py, pz, q):
    """``(AB . (p - q), AC . (p - q))``."""
    dx, dy, dz = px - q[0], py - q[1], pz - q[2]
    return ab[0] * dx + ab[1] * dy + ab[2] * dz, ac[0] * dx + ac[1] * dy + ac[2] * dz


@njit(**NJIT)
def _along(q, d, t):
    """The point ``q + t d``."""
    return q[0] + t * d[0], q[1] + t * d[1], q[2] + t * d[2]


@njit(**NJIT)
def closest_on_triangle(px, py, pz, v, ia, ib, ic):
    """The point of triangle ``v[ia] v[ib] v[ic]`` nearest to ``p`` (Ericson's regions)."""
    a = (v[ia, 0], v[ia, 1], v[ia, 2])
    b = (v[ib, 0], v[ib, 1], v[ib, 2])
    c = (v[ic, 0], v[ic, 1], v[ic, 2])
    ab = (b[0] - a[0], b[1] - a[1], b[2] - a[2])
    ac = (c[0] - a[0], c[1] - a[1], c[2] - a[2])
    d1, d2 = _dots(ab, ac, px, py, pz, a)
    if d1 <= 0.0 and d2 <= 0.0:
        return a
    d3, d4 = _dots(ab, ac, px, py, pz, b)
    if d3 >= 0.0 and d4 <= d3:
        return b
    vc = d1 * d4 - d3 * d2
    if vc <= 0.0 and d1 >= 0.0 and d3 <= 0.0:
        return _along(a, ab, d1 / (d1 - d3))
    d5, d6 = _dots(ab, ac, px, py, pz, c)
    if d6 >= 0.0 and d5 <= d6:
        return c
    vb = d5 * d2 - d1 * d6
    if vb <= 0.0 and d2 >= 0.0 and d6 <= 0.0:
        return _along(a, ac, d2 / (d2 - d6))
    va = d3 * d6 - d5 * d4
    if va <= 0.0 and (d4 - d3) >= 0.0 and (d5 - d6) >= 0.0:
        bc = (c[0] - b[0], c[1] - b[1], c[2] - b[2])
        return _along(b, bc, (d4 - d3) / ((d4 - d3) + (d5 - d6)))
    den = 1.0 / (va + vb + vc)
    s = vb * den
    t = vc * den
    return (
        a[0] + ab[0] * s + ac[0] * t,
        a[1] + ab[1] * s + ac[1] * t,
        a[2] + ab[2] * s + ac[2] * t,
    )


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
