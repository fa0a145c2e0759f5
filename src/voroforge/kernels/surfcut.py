"""One triangle of a surface mesh cut to one site's restricted cell (for :mod:`kernels.surface`).

Each cut is the bisector plane of sites ``i`` and ``j`` met with the triangle's plane: a line
in the triangle's 2D frame (``A`` at the origin, ``AB`` along ``x``), its offset from ``A``
summed in double-double so a site far from a small surface still places it to ``D eps^2``
(:func:`cut_by`). A triangle with few candidate sites cuts each candidate's piece by all the
others (:func:`cut_by_others`). A big triangle holding many sites (a flat CAD facet, a box of
12 triangles) would make that quadratic in its sites: there each piece is cut by its site's
``k`` nearest sites first, and only when the piece so far reaches farther than half the
distance to the next site are the sites within twice its reach taken from the bucket grid,
shell by shell outwards until no site left can reach (:func:`cut_local`). Both give the
same piece: a site ``j`` removes a point ``x`` of site ``i``'s piece only when
``|x - s_j| < |x - s_i|``, so ``|s_j - s_i| < 2 |x - s_i|``.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import NJIT
from .clip import cut_ring, plane_values
from .expansion import two_diff, two_product, two_sum
from .grid3d import bucket3d, shell_buckets, shell_gap

_EPS = np.finfo(np.float64).eps


@njit(inline="always", **NJIT)
def _dd_add(ah, al, bh, bl):
    """Double-double ``(ah + al) + (bh + bl)`` (relative error ~ eps^2)."""
    s, e = two_sum(ah, bh)
    e += al + bl
    h = s + e
    return h, e - (h - s)


@njit(inline="always", **NJIT)
def _offset(sj, si, a):
    """One coordinate's term ``(sj - si) * ((si + sj) / 2 - a)`` in double-double.

    Summed over the coordinates: the bisector's offset from triangle corner ``a``.
    The sites' differences and sums are exact pairs, so a site far from a small surface
    (``|s| = D``) places the bisector to ~ ``D eps^2``, not ``D eps`` (checker14 F6); the
    result is the exact negative when ``si`` and ``sj`` swap, so two sites' pieces tile.
    """
    gh, gl = two_diff(sj, si)
    mh, ml = two_sum(si, sj)
    wh, wl = _dd_add(0.5 * mh, 0.5 * ml, -a, 0.0)
    p, e = two_product(gh, wh)
    e += gh * wl + gl * wh
    h = p + e
    return h, e - (h - p)


@njit(**NJIT)
def cut_by(i, js, count, m, sites, frame, rx, ry, ro, sx, sy, so, ss):
    """Ring ``rx, ry, ro[:m]`` cut to site ``i``'s side of the bisectors with ``js[:count]``.

    The ring is rewritten in place (``sx, sy, so, ss`` scratch, room for one more vertex
    per cut); ``i`` itself is skipped. Returns the vertex count, 0 when nothing is left.
    """
    ax, ay, az, e1x, e1y, e1z, e2x, e2y, e2z = frame
    six, siy, siz = sites[i, 0], sites[i, 1], sites[i, 2]
    zero = np.int64(0)  # not a literal: numba would compile the clip once more for it
    for w in range(count):
        j = js[w]
        if j == i:
            continue
        gx = sites[j, 0] - six
        gy = sites[j, 1] - siy
        gz = sites[j, 2] - siz
        xh, xl = _offset(sites[j, 0], six, ax)
        yh, yl = _offset(sites[j, 1], siy, ay)
        zh, zl = _offset(sites[j, 2], siz, az)
        xh, xl = _dd_add(xh, xl, yh, yl)
        xh, xl = _dd_add(xh, xl, zh, zl)
        hh = xh + xl
        px = gx * e1x + gy * e1y + gz * e1z
        py = gx * e2x + gy * e2y + gz * e2z
        if plane_values(rx, ry, zero, m, px, py, 0.0, 0.0, hh, ss) <= 0.0:
            continue
        m = cut_ring(rx, ry, ro, zero, m, ss, sx, sy, so, zero, j)
        if m < 3:
            return 0
        for k in range(m):
            rx[k] = sx[k]
            ry[k] = sy[k]
            ro[k] = so[k]
    return m


@njit(**NJIT)
def cut_by_others(q, cand, m_c, sites, frame, rx, ry, ro, sx, sy, so, ss):
    """The triangle cut to candidate ``q``'s side of every other candidate's bisector.

    The caller sets the triangle in ``rx, ry, ro[:3]``. Returns the vertex count (0: empty).
    """
    m = np.int64(3)
    return cut_by(cand[q], cand, m_c, m, sites, frame, rx, ry, ro, sx, sy, so, ss)


@njit(**NJIT)
def _reach(i, m, sites, frame, rx, ry):
    """Twice the largest distance from site ``i`` to the ring, widened for rounding."""
    ax, ay, az, e1x, e1y, e1z, e2x, e2y, e2z = frame
    r2 = 0.0
    for k in range(m):
        dx = ax + rx[k] * e1x + ry[k] * e2x - sites[i, 0]
        dy = ay + rx[k] * e1y + ry[k] * e2y - sites[i, 1]
        dz = az + rx[k] * e1z + ry[k] * e2z - sites[i, 2]
        r2 = max(r2, dx * dx + dy * dy + dz * dz)
    big = max(abs(ax), max(abs(ay), abs(az)))
    big = max(big, max(abs(sites[i, 0]), max(abs(sites[i, 1]), abs(sites[i, 2]))))
    for k in range(m):
        big = max(big, max(abs(rx[k]), abs(ry[k])))
    return 2.0 * (np.sqrt(r2) + 64.0 * _EPS * big) * (1.0 + 1e-9)


@njit(**NJIT)
def _listed(nbr, i, j):
    """Whether ``j`` is in ``i``'s neighbour list."""
    for w in range(nbr.shape[1]):
        if nbr[i, w] == j:
            return True
    return False


@njit(**NJIT)
def cut_local(i, sites, frame, nbr, bound, grid, ring):
    """The triangle (set by the caller in ``ring``'s first arrays) cut to site ``i``'s cell.

    Cut by ``i``'s neighbour list ``nbr[i]`` (:func:`.surface.site_knn`) first. When the ring
    left reaches (:func:`_reach`) past ``bound[i]`` (no unlisted site is nearer), the bucket
    grid ``grid = (start, sidx, g, buf, js)`` is scanned in shells around the site, the
    sites within the reach cutting (``js``: room for every site), until
    :func:`~voroforge.kernels.grid3d.shell_gap` puts every site left beyond the (shrinking)
    reach. ``ring = (rx, ry, ro, sx, sy, so, ss)``. Returns the vertex count (0: empty), or
    -1 when the scan passes ``4 * len(rx)`` buckets or the ring could outgrow the buffers:
    the caller then cuts by all of the triangle's candidates.
    """
    rx, ry, ro, sx, sy, so, ss = ring
    start, sidx, g, buf, js = grid
    k = 0
    while k < nbr.shape[1] and nbr[i, k] >= 0:
        k += 1
    m = cut_by(i, nbr[i], k, np.int64(3), sites, frame, rx, ry, ro, sx, sy, so, ss)
    if m < 3:
        return 0
    reach = _reach(i, m, sites, frame, rx, ry)
    if reach < bound[i]:
        return m
    x, y, z = sites[i, 0], sites[i, 1], sites[i, 2]
    ci, cj, ck = bucket3d(x, y, z, g)
    rmax = max(int(g[6]), max(int(g[7]), int(g[8])))
    scanned = 0
    for r in range(rmax + 1):
        nb = shell_buckets(ci, cj, ck, r, g, buf)
        scanned += nb
        if scanned > 4 * rx.shape[0]:
            return -1
        r2 = reach * reach
        c = 0
        for u in range(nb):
            b = buf[u]
            for q in range(start[b], start[b + 1]):
                j = sidx[q]
                dd = (sites[j, 0] - x) ** 2 + (sites[j, 1] - y) ** 2 + (sites[j, 2] - z) ** 2
                if dd < r2 and not _listed(nbr, i, j):
                    js[c] = j
                    c += 1
        if m + c + 1 > rx.shape[0]:
            return -1
        m = cut_by(i, js, c, m, sites, frame, rx, ry, ro, sx, sy, so, ss)
        if m < 3:
            return 0
        reach = _reach(i, m, sites, frame, rx, ry)
        if reach <= shell_gap(x, y, z, ci, cj, ck, r, g):
            break
    return m


@njit(**NJIT)
def insert_by_distance(cand, cdist, m, s, dd):
    """Site ``s`` at squared distance ``dd`` into the list ``cand[:m]`` kept by (distance, index).

    Writes slots ``0..m`` (the caller makes room).
    """
    p = m
    while p > 0 and (cdist[p - 1] > dd or (cdist[p - 1] == dd and cand[p - 1] > s)):
        cand[p] = cand[p - 1]
        cdist[p] = cdist[p - 1]
        p -= 1
    cand[p] = s
    cdist[p] = dd


@njit(**NJIT)
def gather(gx, gy, gz, reach, sites, start, sidx, g, cand, cdist):
    """Sites within ``reach`` of ``g`` into ``cand``/``cdist`` by (distance, index); the count.

    The arrays hold a slot per site. Collected in bucket order, then sorted: by insertion
    when few, else by index and then stably by distance (``n log n``; inserting each of a
    big triangle's thousands of sites in order was quadratic).
    """
    i0, j0, k0 = bucket3d(gx - reach, gy - reach, gz - reach, g)
    i1, j1, k1 = bucket3d(gx + reach, gy + reach, gz + reach, g)
    nx = int(g[6])
    ny = int(g[7])
    m = 0
    r2 = reach * reach
    for k in range(k0, k1 + 1):
        for j in range(j0, j1 + 1):
            row = (k * ny + j) * nx
            for b in range(row + i0, row + i1 + 1):
                for q in range(start[b], start[b + 1]):
                    s = sidx[q]
                    dd = (sites[s, 0] - gx) ** 2 + (sites[s, 1] - gy) ** 2 + (sites[s, 2] - gz) ** 2
                    if dd <= r2:
                        cand[m] = s
                        cdist[m] = dd
                        m += 1
    if m <= 64:  # few: sorted in place (no arrays to allocate)
        for a in range(1, m):
            insert_by_distance(cand, cdist, a, cand[a], cdist[a])
    else:
        o = np.argsort(cand[:m])
        c1 = cand[:m][o]
        d1 = cdist[:m][o]
        o = np.argsort(d1, kind="mergesort")
        cand[:m] = c1[o]
        cdist[:m] = d1[o]
    return m
