"""Voronoi cells by cutting: each cell is the box cut by the bisectors of nearby sites.

This is the voro++ design in two dimensions. Every cell is built on its own, so cells are
computed in parallel and the same structure carries over to 3D (a polyhedron instead of a
polygon, the same grid, search and exact finishing):

1. The sites are counting-sorted into a uniform grid of buckets over their bounding box
   (about ``_PER_BUCKET`` sites per bucket, CSR layout: ``start`` and sorted coordinates).
2. A cell starts as the box, in coordinates relative to its site (so 500000/4000000-style
   inputs keep their precision). Buckets are visited in square rings of growing distance
   from the site's bucket, and the cell is cut by the bisector of each site found there
   (:func:`_plane_values`, :func:`_cut_by_plane`).
3. The cell lies within ``r`` (:func:`_radius2`, its largest vertex distance) of the site,
   and the bisector of a site at distance ``d`` stays at least ``d / 2`` away, so only sites
   with ``d < 2 r`` can cut. Once a ring of buckets is farther than ``2 r`` the cut is final.
4. Exact finishing (:func:`_settle`): the ring of neighbours is checked with the exact
   ``orient2d``/``incircle`` against every site met within ``2 r`` (zero-length edges of
   cocircular sites go, neighbours lost to coinciding float bisectors come back), and every
   vertex is recomputed from its sites in index order: the circumcentre of the first
   lowest-numbered triple of sites on its circle that is well-conditioned (not two sites a
   few ulps apart, whose bisector can put the centre anywhere along it), or the bisector's
   crossing with a box side computed as the default algorithm computes it. Cells sharing a
   vertex get the same bits. A site counts as on a circle by rounding only if its own
   vertices with the circle's sites are that vertex to rounding: near-duplicate sites make
   a tiny incircle value but long edges.

Output contract (that of ``cells.cells_from_triangulation``): closed counter-clockwise rings
``coords (K, 2)``, ``offsets (n + 1,)``, ``owner (K,)`` with the site across each edge, -1 on
the box, -2 on the closing vertex.

Output arrays are exact-size in one pass: chunks of cells are written to per-chunk slabs of
fixed capacity and then copied into place; the rare chunk that overflows its slab is simply
recomputed straight into the output.
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

from ..config import NJIT, NJIT_PARALLEL
from .cells import _box_crossing
from .predicates import circumcenter, incircle, orient2d

_PER_BUCKET = 2.0  # mean sites per grid bucket
_MAX_REFINE = 32.0  # most buckets per _PER_BUCKET sites that clustered input may get
_CHUNK = 512  # cells per parallel work item
_SLAB = 7  # slab vertices per cell of a chunk (the mean over a diagram is below 6)
_CAP = 64  # initial per-cell scratch capacity (doubled when a cell needs more)
_REACH = 4.0 * (1.0 + 1e-9)  # (2 r)^2 / r^2 with a margin against rounding in r

_NEAR = 1e-7  # relative band around a vertex's circle where candidates get the exact test
#: |d| (squared distance to a vertex's circle minus its radius squared) below which a site
#: counts as on the circle: 2 r times the default algorithm's 2**-46 vertex merge tolerance
_MERGE = 2.0**-45
_MAX_FIX = 64  # rounds of exact repair per cell before the float cut is kept as it is
#: Squared float edge length, relative to the squared cell radius, above which an edge is
#: taken as it is (rounding moves vertices by ~1e-16 of the radius)
_SURE = 1e-12
#: Squared sine of the angle between adjacent float edges below which neither is taken as
#: it is (their crossing is ill-conditioned)
_SURE_SIN2 = 1e-16
#: Vertices closer than this (L1, relative to their magnitude and the circle's size) are one
#: vertex: the default algorithm's ``_CC_MERGE_RTOL``. A site within ``_MERGE`` of a circle
#: joins its vertex only if the vertices it forms with the circle's sites are that close: a
#: small ``d`` alone does not make a short edge when the site is a few ulps from another one
#: (their bisector is ill-conditioned and its vertices can lie anywhere along it).
_CC_RTOL = 2.0**-46
_SNAP_RTOL = 2.0**-40
#: Squared distance between two sites, relative to the squared radius, below which their
#: triple is not a canonical vertex's (sites a few ulps apart: ill-conditioned)
_PAIR_RTOL = 2.0**-40  # the same for box crossings (the crossing is computed another way)

# Box sides as internal owner codes (those of cells.py's box crossings); all become -1.
_LEFT, _BOTTOM, _RIGHT, _TOP = -1, -2, -3, -4


@njit(**NJIT)
def _grid_shape(xs, ys, per_bucket):
    """Return ``(x0, y0, hx, hy, nx, ny)`` of a grid over the sites' bounding box.

    About ``per_bucket`` sites per bucket on average.
    """
    n = xs.shape[0]
    x0 = xs.min()
    y0 = ys.min()
    w = xs.max() - x0
    h = ys.max() - y0
    span = max(w, h)
    if span == 0.0:
        span = max(abs(x0), abs(y0), 1.0)
    w = max(w, 1e-6 * span)
    h = max(h, 1e-6 * span)
    nb = max(1.0, n / per_bucket)
    nx = int(min(max(np.sqrt(nb * w / h), 1.0), nb))
    ny = int(min(max(nb / nx, 1.0), nb))
    # a hair wider than the points so that int((x - x0) / hx) < nx for every site
    hx = w * (1.0 + 1e-12) / nx
    hy = h * (1.0 + 1e-12) / ny
    return x0, y0, hx, hy, nx, ny


@njit(**NJIT)
def _bucket(x, y, x0, y0, hx, hy, nx, ny):
    ix = min(max(int((x - x0) / hx), 0), nx - 1)
    iy = min(max(int((y - y0) / hy), 0), ny - 1)
    return ix, iy


@njit(**NJIT)
def _bucket_sort(xs, ys, x0, y0, hx, hy, nx, ny):
    """Counting sort of the sites into buckets: ``start``, sorted x, y and original index."""
    n = xs.shape[0]
    key = np.zeros(n, np.int64)
    start = np.zeros(nx * ny + 1, np.int64)
    for i in range(n):
        ix, iy = _bucket(xs[i], ys[i], x0, y0, hx, hy, nx, ny)
        key[i] = iy * nx + ix
        start[key[i] + 1] += 1
    for b in range(nx * ny):
        start[b + 1] += start[b]
    fill = start[:-1].copy()
    sx = np.zeros(n)
    sy = np.zeros(n)
    sidx = np.zeros(n, np.int64)
    for i in range(n):
        t = fill[key[i]]
        fill[key[i]] += 1
        sx[t] = xs[i]
        sy[t] = ys[i]
        sidx[t] = i
    return start, sx, sy, sidx


# ---------------------------------------------------------------------------------------------
# generic cell operations: a convex cell, a plane that cuts it, its radius. The 3D kernel swaps
# the polygon for a polyhedron and keeps the same three steps and the same search around them.
# ---------------------------------------------------------------------------------------------


@njit(**NJIT)
def _plane_values(px, py, a, m, qx, qy, h, ss):
    """Signed values ``p . q - h`` of the cell's vertices; returns the largest (> 0: a cut)."""
    smax = -np.inf
    for u in range(m):
        s = px[a + u] * qx + py[a + u] * qy - h
        ss[u] = s
        smax = max(smax, s)
    return smax


@njit(**NJIT)
def _push(px, py, po, c, x, y, o):
    """Append vertex ``c`` (an absolute index), or merge it into vertex ``c - 1`` if equal.

    Returns the index of the next free slot.
    """
    if px[c - 1] == x and py[c - 1] == y:
        po[c - 1] = o  # the zero-length edge goes; the later edge keeps its owner
        return c
    px[c] = x
    py[c] = y
    po[c] = o
    return c + 1


@njit(**NJIT)
def _cut_by_plane(px, py, po, a, m, b, ss, j):
    """Cut the cell at ``a:a + m`` where its plane values ``ss`` are positive.

    The new face (edge) gets owner ``j``. The result goes to ``b:``; returns its length.
    ``px, py, po`` hold both polygons (``a`` and ``b`` are their offsets).
    """
    c = b
    px[b - 1] = np.nan  # so that the first vertex is never merged
    for k in range(m):
        kn = k + 1 if k + 1 < m else 0
        sa = ss[k]
        sb = ss[kn]
        ax = px[a + k]
        ay = py[a + k]
        if sa <= 0.0:
            # a kept vertex on the line starts the new edge
            c = _push(px, py, po, c, ax, ay, j if sa == 0.0 and sb > 0.0 else po[a + k])
            if sa < 0.0 and sb > 0.0:  # leaving: the exit point starts the new edge
                t = sa / (sa - sb)
                c = _push(px, py, po, c, ax + t * (px[a + kn] - ax), ay + t * (py[a + kn] - ay), j)
        elif sb < 0.0:  # entering: the entry point continues along the old edge
            t = sb / (sb - sa)
            bx = px[a + kn]
            by = py[a + kn]
            c = _push(px, py, po, c, bx + t * (ax - bx), by + t * (ay - by), po[a + k])
    while c > b + 1 and px[c - 1] == px[b] and py[c - 1] == py[b]:
        c -= 1  # trailing vertices equal to the first one
    return c - b


@njit(**NJIT)
def _radius2(px, py, a, m):
    """Largest squared distance of the cell's vertices from its site (the origin)."""
    r2 = 0.0
    for k in range(a, a + m):
        r2 = max(r2, px[k] * px[k] + py[k] * py[k])
    return r2


@njit(**NJIT)
def _ring_gap(ix, iy, ring, fx0, fx1, fy0, fy1, hx, hy, nx, ny):
    """Least distance from the site to any bucket of ``ring``; -1 when the ring is off-grid."""
    gap = np.inf
    if ix - ring >= 0:
        gap = min(gap, fx0 + (ring - 1) * hx)
    if ix + ring < nx:
        gap = min(gap, fx1 + (ring - 1) * hx)
    if iy - ring >= 0:
        gap = min(gap, fy0 + (ring - 1) * hy)
    if iy + ring < ny:
        gap = min(gap, fy1 + (ring - 1) * hy)
    return -1.0 if gap == np.inf else gap


@njit(**NJIT)
def _rect_dist2(x, y, x0, y0, x1, y1):
    """Squared distance from ``(x, y)`` to the rectangle ``[x0, x1] x [y0, y1]`` (inf if empty)."""
    if x0 >= x1 or y0 >= y1:
        return np.inf
    dx = max(x0 - x, 0.0, x - x1)
    dy = max(y0 - y, 0.0, y - y1)
    return dx * dx + dy * dy


@njit(**NJIT)
def _rect_clear(px, py, a, m, cx, cy, bx0, by0, bx1, by1):
    """Whether every vertex is farther from the rectangle than from its site (with margin).

    Then no site in the rectangle can cut the cell, now or after later cuts (the cell only
    shrinks, and the points nearer to such a site form a half-plane the cell misses).
    """
    for u in range(a, a + m):
        own = _REACH * 0.25 * (px[u] * px[u] + py[u] * py[u])
        if _rect_dist2(px[u] + cx, py[u] + cy, bx0, by0, bx1, by1) <= own:
            return False
    return True


@njit(**NJIT)
def _unscanned_clear(px, py, a, m, cx, cy, ix, iy, ring, grid):
    """Whether no site in the buckets not yet scanned can cut the cell.

    The scanned buckets form the square of rings ``< ring`` around the site's bucket; the
    rest of the grid is four strips around it. A site ``q`` cuts only if some vertex ``v``
    is nearer to ``q`` than to the site, so the cell is final once every vertex is farther
    from all four strips than from the site (with the same margin as the radius bound).
    """
    x0, y0, hx, hy, nx, ny = grid
    gx1 = x0 + nx * hx
    gy1 = y0 + ny * hy
    sx0 = max(x0 + (ix - ring + 1) * hx, x0)
    sx1 = min(x0 + (ix + ring) * hx, gx1)
    sy0 = max(y0 + (iy - ring + 1) * hy, y0)
    sy1 = min(y0 + (iy + ring) * hy, gy1)
    for u in range(a, a + m):
        vx = px[u] + cx
        vy = py[u] + cy
        own = _REACH * 0.25 * (px[u] * px[u] + py[u] * py[u])  # |v - site|^2, with margin
        if _rect_dist2(vx, vy, x0, y0, sx0, gy1) <= own:  # left strip
            return False
        if _rect_dist2(vx, vy, sx1, y0, gx1, gy1) <= own:  # right strip
            return False
        if _rect_dist2(vx, vy, sx0, y0, sx1, sy0) <= own:  # bottom strip
            return False
        if _rect_dist2(vx, vy, sx0, sy1, sx1, gy1) <= own:  # top strip
            return False
    return True


# ---------------------------------------------------------------------------------------------
# exact finishing: the ring of neighbours is checked with exact predicates, then every vertex
# is computed from its sites in a fixed order, so the cells sharing it agree bit for bit
# ---------------------------------------------------------------------------------------------


@njit(**NJIT)
def _edge_ok(i, j, p, q, xs, ys):
    """Whether neighbour ``j`` between ``p`` (before) and ``q`` (after) has an edge of length > 0.

    Around site ``i`` counter-clockwise, ``p`` lies right of ``i -> j`` and ``q`` left of it;
    the edge's ends are the circumcentres of ``(i, p, j)`` and ``(i, j, q)``, in that order
    exactly when ``p`` is strictly outside the circle through ``i, j, q`` (exact predicates).
    """
    ix = xs[i]
    iy = ys[i]
    jx = xs[j]
    jy = ys[j]
    if orient2d(ix, iy, jx, jy, xs[p], ys[p]) >= 0.0:
        return False
    if orient2d(ix, iy, jx, jy, xs[q], ys[q]) <= 0.0:
        return False
    return incircle(ix, iy, jx, jy, xs[q], ys[q], xs[p], ys[p]) < 0.0


@njit(**NJIT)
def _shadowed_at_box(i, j, k, side, xs, ys, box):
    """Whether neighbour ``j`` between box side ``side`` and site ``k`` has no edge.

    Only for ``k`` a few ulps from ``j`` (their bisectors with ``i`` are nearly parallel,
    their crossing and the float cut are ill-conditioned): ``j``'s edge starts where its
    bisector meets the side, and is empty when ``k`` is nearer there than ``j``, i.e.
    ``|c - j|^2 - |c - k|^2 = (k - j) . (2 c - j - k) > 0`` (``k - j`` is exact).
    """
    dx = xs[k] - xs[j]
    dy = ys[k] - ys[j]
    ex = xs[j] - xs[i]
    ey = ys[j] - ys[i]
    if dx * dx + dy * dy > _PAIR_RTOL * (ex * ex + ey * ey):
        return False
    cx, cy = _box_crossing(i, j, xs, ys, side, box)
    if not (np.isfinite(cx) and np.isfinite(cy)):
        return False
    return dx * (2.0 * cx - xs[j] - xs[k]) + dy * (2.0 * cy - ys[j] - ys[k]) > 0.0


@njit(**NJIT)
def _vertex(a, b, c, xs, ys):
    """Circumcentre of sites ``a, b, c`` computed in increasing index order (canonical bits)."""
    if a > b:
        a, b = b, a
    if b > c:
        b, c = c, b
    if a > b:
        a, b = b, a
    return circumcenter(xs[a], ys[a], xs[b], ys[b], xs[c], ys[c])


@njit(**NJIT)
def _remove(lab, m, u):
    for k in range(u, m - 1):
        lab[k] = lab[k + 1]
    return m - 1


@njit(**NJIT)
def _drop_invalid(i, lab, m, xs, ys, sure, trust, box):
    """Remove repeated labels and neighbours whose edge has no positive length.

    With ``trust``, labels whose float edge is long (``sure[u]``) are kept without the exact
    test: the float cut is off by rounding only, so such an edge exists. A label next to a
    box side and to a site a few ulps from its own goes when the other one is nearer where
    its bisector meets the box (:func:`_shadowed_at_box`).
    """
    u = 0
    while u < m and m >= 3:
        j = lab[u]
        p = lab[u - 1] if u > 0 else lab[m - 1]
        q = lab[u + 1] if u + 1 < m else lab[0]
        check = j >= 0 and p >= 0 and q >= 0 and p != q and not (trust and sure[u] > 0.0)
        shadowed = j >= 0 and (p < 0) != (q < 0)
        if shadowed:
            shadowed = _shadowed_at_box(i, j, q if p < 0 else p, p if p < 0 else q, xs, ys, box)
        if j == p or shadowed or (check and not _edge_ok(i, j, p, q, xs, ys)):
            m = _remove(lab, m, u)
            u = max(u - 1, 0)
            trust = False  # sure[] is indexed by the ring as it was: no longer aligned
            continue
        u += 1
    return m


@njit(**NJIT)
def _settle(i, lab, m, sure, cand, nc, sidx, xs, ys, vx, vy, on, box):
    """Make the ring of neighbour labels ``lab[:m]`` exactly right; returns its length.

    Float cutting can keep an edge of zero length (cocircular sites), or lose a neighbour
    whose bisector coincides with another one in floating point. Labels without a positive
    edge are dropped (:func:`_edge_ok`); then each vertex between neighbours ``a, b`` is
    checked against every candidate site: one strictly inside the circle through ``i, a, b``
    is inserted between them (float filter, exact ``incircle`` near the circle). Candidates
    exactly on the circle are cocircular: the vertex is then the circumcentre of the three
    lowest-numbered sites on it, which every cell around the vertex finds the same.
    Returns -1 when the ring cannot be settled (the caller keeps the float cut).

    A site within rounding of the circle is taken as on it (never inserted) only if its
    vertices with the circle's sites are the vertex to rounding (:func:`_joins`); a site a
    few ulps from ``i``, ``a`` or ``b`` gets the exact test. The canonical centre is that of
    the first well-conditioned triple of the sites on the circle (:func:`_canonical`).
    ``on`` is scratch for those sites (int64, any size).

    ``sure[u]`` flags labels whose float edge is long; until the ring changes they skip the
    exact tests (their edge and the orientation at its ends are beyond rounding).
    """
    cap = lab.shape[0]
    trust = True
    for _ in range(_MAX_FIX):
        m0 = m
        m = _drop_invalid(i, lab, m, xs, ys, sure, trust, box)
        if m < 3:
            return -1
        trust = trust and m == m0
        inserted = False
        for u in range(m):
            a = lab[u - 1] if u > 0 else lab[m - 1]
            b = lab[u]
            if a < 0 or b < 0:
                continue
            ix = xs[i]
            iy = ys[i]
            both = trust and sure[u] > 0.0 and sure[u - 1 if u > 0 else m - 1] > 0.0
            if not both and orient2d(ix, iy, xs[a], ys[a], xs[b], ys[b]) <= 0.0:
                return -1
            vx_, vy_ = _vertex(i, a, b, xs, ys)
            r2 = (ix - vx_) * (ix - vx_) + (iy - vy_) * (iy - vy_)
            tol = _NEAR * r2
            # a site this close to the circle is on it: the edge it would add or keep is
            # shorter than floats can order (the default algorithm merges such vertices too)
            r = np.sqrt(r2)
            merge = _MERGE * r * (abs(vx_) + abs(vy_) + r)
            nxt = lab[u + 1] if u + 1 < m else lab[0]
            prv = lab[u - 2] if u >= 2 else lab[u - 2 + m]
            non = 0  # other sites on the circle, to rounding
            for c in range(nc):
                x = sidx[cand[c]]
                if x == a or x == b:
                    continue
                dx = xs[x] - vx_
                dy = ys[x] - vy_
                d = dx * dx + dy * dy - r2
                if d > tol:
                    continue
                if abs(d) <= merge and _joins(i, a, b, x, vx_, vy_, xs, ys, _CC_RTOL):
                    if x == nxt or x == prv:
                        # the edge of b (or a) between this vertex and x's is noise: drop it
                        m = _remove(lab, m, u if x == nxt else (u - 1 if u > 0 else m - 1))
                        inserted = True
                        break
                    s = 0.0
                elif d < -tol and abs(d) > merge:
                    s = 1.0
                else:
                    s = incircle(ix, iy, xs[a], ys[a], xs[b], ys[b], xs[x], ys[x])
                if s > 0.0:
                    # x strictly inside the circle and on the line through i and a (or b)
                    # lies between them: a's bisector is beyond x's, so x replaces a
                    ua = u - 1 if u > 0 else m - 1
                    if orient2d(ix, iy, xs[a], ys[a], xs[x], ys[x]) == 0.0:
                        if not _has(lab, m, x):
                            lab[ua] = x
                            inserted = True
                            break
                    if orient2d(ix, iy, xs[b], ys[b], xs[x], ys[x]) == 0.0:
                        if not _has(lab, m, x):
                            lab[u] = x
                            inserted = True
                            break
                    if m < cap and not _has(lab, m, x):
                        for k in range(m, u, -1):
                            lab[k] = lab[k - 1]
                        lab[u] = x
                        m += 1
                        inserted = True
                        break
                elif (s == 0.0 or abs(d) <= merge) and non + 3 < on.shape[0]:
                    on[non] = x  # on the circle, or off it by rounding only
                    non += 1
            if inserted:
                break
            if non == 0:
                vx[u] = vx_  # no other site on the circle: the centre computed above
                vy[u] = vy_
            else:
                on[non] = i
                on[non + 1] = a
                on[non + 2] = b
                vx[u], vy[u] = _canonical(on, non + 3, vx_, vy_, ix, iy, xs, ys)
        if not inserted:
            return m
        trust = False  # the ring changed: every label gets the exact tests from now on
    return -1


@njit(**NJIT)
def _close(x, y, px, py, sx, sy, rtol):
    """Whether ``(px, py)`` is within ``rtol`` of vertex ``(x, y)`` of site ``(sx, sy)``.

    L1 distance relative to the vertex's magnitude and its distance from the site (the
    default algorithm's test for circumcentres that are one vertex).
    """
    scale = abs(x) + abs(y) + abs(x - sx) + abs(y - sy)
    return abs(px - x) + abs(py - y) <= rtol * scale


@njit(**NJIT)
def _joins(i, a, b, x, vx, vy, xs, ys, rtol):
    """Whether site ``x`` near the circle of ``i, a, b`` (centre ``vx, vy``) is on its vertex.

    True when the circumcentres of ``x`` with ``i, a`` and with ``i, b`` both lie within
    ``rtol`` of the vertex: the edges that ``x`` would add or shorten are then rounding
    noise. A site a few ulps from ``i``, ``a`` or ``b`` fails: its triangle with that
    site is ill-conditioned and its centre lies far along their bisector.
    """
    ix = xs[i]
    iy = ys[i]
    px, py = _vertex(i, a, x, xs, ys)
    if not (np.isfinite(px) and np.isfinite(py)):
        return False
    if not _close(vx, vy, px, py, ix, iy, rtol):
        return False
    px, py = _vertex(i, x, b, xs, ys)
    if not (np.isfinite(px) and np.isfinite(py)):
        return False
    return _close(vx, vy, px, py, ix, iy, rtol)


@njit(**NJIT)
def _canonical(on, k, vx, vy, sx, sy, xs, ys):
    """The canonical centre of vertex ``(vx, vy)`` of site ``(sx, sy)``; sorts ``on[:k]``.

    ``on[:k]`` are the sites on its circle to rounding (every cell around the vertex finds
    the same ones). The centre is that of the first triple of them, in lexicographic order
    of their numbers, whose circumcentre is the vertex to rounding: two sites a few ulps
    apart make an ill-conditioned triple (its centre lies far along their bisector), which
    is passed over. Without such a triple the vertex stays as it is.
    """
    r2 = (vx - sx) * (vx - sx) + (vy - sy) * (vy - sy)
    for p in range(1, k):  # insertion sort of the few sites on the circle
        x = on[p]
        q = p
        while q > 0 and on[q - 1] > x:
            on[q] = on[q - 1]
            q -= 1
        on[q] = x
    for p in range(k):
        for q in range(p + 1, k):
            for r in range(q + 1, k):
                x0, x1, x2 = on[p], on[q], on[r]
                if x0 == x1 or x1 == x2:
                    continue
                if _near_pair(x0, x1, r2, xs, ys) or _near_pair(x1, x2, r2, xs, ys):
                    continue
                if _near_pair(x0, x2, r2, xs, ys):
                    continue
                cx, cy = circumcenter(xs[x0], ys[x0], xs[x1], ys[x1], xs[x2], ys[x2])
                if np.isfinite(cx) and np.isfinite(cy):
                    if _close(vx, vy, cx, cy, sx, sy, _SNAP_RTOL):
                        return cx, cy
    return vx, vy


@njit(**NJIT)
def _near_pair(a, b, r2, xs, ys):
    """Whether sites ``a, b`` are too close for a well-conditioned circumcentre.

    ``r2`` is the squared radius of the circle they are on.
    """
    dx = xs[a] - xs[b]
    dy = ys[a] - ys[b]
    return dx * dx + dy * dy <= _PAIR_RTOL * r2


@njit(**NJIT)
def _has(lab, m, x):
    for k in range(m):
        if lab[k] == x:
            return True
    return False


@njit(**NJIT)
def _snap_crossing(i, j, x, y, xs, ys, near, nn, sidx, on):
    """The canonical vertex at box crossing ``(x, y)`` of the bisector of ``i, j``, if any.

    When other sites are as far from the crossing as ``i`` and ``j`` (to the merge
    tolerance), the crossing is a Voronoi vertex lying on the box: it becomes the
    canonical centre of those sites (:func:`_canonical`), as in :func:`_settle`. ``on`` is
    scratch (int64, any size).
    """
    r2 = (xs[i] - x) * (xs[i] - x) + (ys[i] - y) * (ys[i] - y)
    r = np.sqrt(r2)
    merge = _MERGE * r * (abs(x) + abs(y) + r)
    on[0] = i
    on[1] = j
    k = 2
    for c in range(nn):
        q = sidx[near[c]]
        if q == i or q == j:
            continue
        dx = xs[q] - x
        dy = ys[q] - y
        if abs(dx * dx + dy * dy - r2) <= merge and k < on.shape[0]:
            on[k] = q
            k += 1
    if k == 2:
        return x, y
    return _canonical(on, k, x, y, xs[i], ys[i], xs, ys)


@njit(**NJIT)
def _emit_exact(i, lab, m, vx, vy, xs, ys, box, near, nn, sidx, ox, oy, oo, pos, on):
    """Write the settled ring with canonical vertices from ``pos``; -1 when one is undefined.

    Bisector-bisector vertices come from :func:`_settle`; a bisector meets a box side at the
    crossing computed from the pair in index order (as the default algorithm does), and two
    box sides meet at the exact corner. A crossing that is also a Voronoi vertex (a site
    among ``near[:nn]`` as far from it as the pair, to rounding) is that vertex's canonical
    circumcentre instead, which the cells meeting there inside compute too. ``on`` is
    scratch (int64, any size).
    """
    c = pos
    for u in range(m):
        a = lab[u - 1] if u > 0 else lab[m - 1]
        b = lab[u]
        if a >= 0 and b >= 0:
            x = vx[u]
            y = vy[u]
        elif a >= 0 or b >= 0:
            j = a if a >= 0 else b
            x, y = _box_crossing(i, j, xs, ys, b if a >= 0 else a, box)
            if np.isfinite(x) and np.isfinite(y):
                x, y = _snap_crossing(i, j, x, y, xs, ys, near, nn, sidx, on)
        else:
            vert = a if (a == _LEFT or a == _RIGHT) else b
            horz = b if vert == a else a
            if not ((vert == _LEFT or vert == _RIGHT) and (horz == _BOTTOM or horz == _TOP)):
                return -1
            x = box[0] if vert == _LEFT else box[2]
            y = box[1] if horz == _BOTTOM else box[3]
        if not (np.isfinite(x) and np.isfinite(y)):
            return -1
        x = min(max(x, box[0]), box[2])
        y = min(max(y, box[1]), box[3])
        o = b if b >= 0 else -1
        if c > pos and ox[c - 1] == x and oy[c - 1] == y:
            oo[c - 1] = o
        else:
            ox[c] = x
            oy[c] = y
            oo[c] = o
            c += 1
    while c > pos + 1 and ox[c - 1] == ox[pos] and oy[c - 1] == oy[pos]:
        c -= 1
    return c - pos if c - pos >= 3 else 0


@njit(**NJIT)
def _emit(px, py, po, a, m, cx, cy, box, ox, oy, oo, pos):
    """Write the float cell at ``a:a + m`` around site ``(cx, cy)`` to ``ox, oy, oo``.

    The fallback when the exact ring cannot be settled. Coordinates become absolute and
    vertices on box edges are snapped onto the box. Returns the length written (0 when
    rounding left fewer than three distinct vertices).
    """
    xmin, ymin, xmax, ymax = box[0], box[1], box[2], box[3]
    c = pos
    for t in range(a, a + m):
        x = min(max(px[t] + cx, xmin), xmax)
        y = min(max(py[t] + cy, ymin), ymax)
        o = po[t]
        op = po[t - 1] if t > a else po[a + m - 1]
        if o == _BOTTOM or op == _BOTTOM:
            y = ymin
        if o == _TOP or op == _TOP:
            y = ymax
        if o == _LEFT or op == _LEFT:
            x = xmin
        if o == _RIGHT or op == _RIGHT:
            x = xmax
        o = max(o, -1)
        if c > pos and ox[c - 1] == x and oy[c - 1] == y:
            oo[c - 1] = o
        else:
            ox[c] = x
            oy[c] = y
            oo[c] = o
            c += 1
    while c > pos + 1 and ox[c - 1] == ox[pos] and oy[c - 1] == oy[pos]:
        c -= 1
    return c - pos if c - pos >= 3 else 0


@njit(**NJIT)
def _scratch(cap):
    """Scratch arrays of one worker.

    Two polygons (at offsets 1 and ``cap + 2``), plane values, an output cell, the label
    ring, canonical vertices, the candidate list (``4 cap`` sites) with their squared
    distances, and the watch list (sites that cut the cell or came near to).
    """
    return (
        np.zeros(2 * cap + 2),
        np.zeros(2 * cap + 2),
        np.zeros(2 * cap + 2, np.int64),
        np.zeros(cap),
        np.zeros(cap),
        np.zeros(cap),
        np.zeros(cap, np.int64),
        np.zeros(cap, np.int64),
        np.zeros(cap),
        np.zeros(cap),
        np.zeros(4 * cap, np.int64),
        np.zeros(4 * cap),
        np.zeros(4 * cap, np.int64),
    )


@njit(**NJIT)
def _cells(k0, k1, sites, orig, grid, box, counts, where, dx, dy, do):
    """Build the cells of sorted sites ``k0:k1`` and write them one after another to ``d``.

    ``sites = (start, sx, sy, sidx)`` is the bucket grid, ``orig = (xs, ys)`` the sites by
    index (for the exact predicates). Sets ``counts[sidx[k]]`` to each cell's length and
    ``where[k]`` to its position in ``dx, dy, do``. Cells that no longer fit are only
    counted. Returns whether all of them fit.

    The whole loop lives in this one function: a call per cell would cost a dozen atomic
    reference-count updates, more than the geometry of a typical cell.
    """
    start, sx, sy, sidx, rownext, bnext = sites
    xs, ys = orig
    x0, y0, hx, hy, nx, ny = grid
    cap = _CAP
    px, py, po, ss, ox, oy, oo, lab, vx, vy, cand, cd, watch = _scratch(cap)
    pos = 0
    fits = True
    k = k0
    while k < k1:
        cx = sx[k]
        cy = sy[k]
        # the box, relative to the site, as polygon a (polygon b receives the next cut)
        a = 1
        b = cap + 2
        px[a], py[a], po[a] = box[0] - cx, box[1] - cy, _BOTTOM
        px[a + 1], py[a + 1], po[a + 1] = box[2] - cx, box[1] - cy, _RIGHT
        px[a + 2], py[a + 2], po[a + 2] = box[2] - cx, box[3] - cy, _TOP
        px[a + 3], py[a + 3], po[a + 3] = box[0] - cx, box[3] - cy, _LEFT
        m = 4
        r2 = _radius2(px, py, a, m)
        nc = 0
        nw = 0
        ix, iy = _bucket(cx, cy, x0, y0, hx, hy, nx, ny)
        fx0 = cx - (x0 + ix * hx)
        fx1 = x0 + (ix + 1) * hx - cx
        fy0 = cy - (y0 + iy * hy)
        fy1 = y0 + (iy + 1) * hy - cy
        ring = 0
        grow = False
        while m >= 3 and not grow:
            if ring > 0:
                # voro++'s stop radius: a site farther than 2 r cannot cut the cell
                gap = _ring_gap(ix, iy, ring, fx0, fx1, fy0, fy1, hx, hy, nx, ny)
                if gap < 0.0 or gap * gap > _REACH * r2:
                    break
                # a cell reaching far past the sites (a hull site in a big box) never meets
                # that bound: ask each vertex whether the unscanned buckets come nearer
                if _unscanned_clear(px, py, a, m, cx, cy, ix, iy, ring, grid):
                    break
            # gather the ring's sites that can still cut, nearest first, then cut with them:
            # near bisectors shrink the cell early, so far ones fail the cheap radius test
            base = nc
            # rows, and on the ring's top and bottom rows runs of buckets, without any site
            # are skipped (rownext, bnext): long thin cells cross many nearly empty rings
            jy = rownext[max(iy - ring, 0)]
            jend = min(iy + ring, ny - 1)
            while jy <= jend:
                edge_row = jy == iy - ring or jy == iy + ring
                gy = max(y0 + jy * hy - cy, cy - (y0 + (jy + 1) * hy), 0.0)
                row = jy * (nx + 1)
                jx = bnext[row + max(ix - ring, 0)] if edge_row else ix - ring
                while jx <= ix + ring and jx < nx:
                    bucket = jy * nx + jx
                    gx = max(x0 + jx * hx - cx, cx - (x0 + (jx + 1) * hx), 0.0)
                    scan = jx >= 0 and not grow and start[bucket] < start[bucket + 1]
                    scan = scan and gx * gx + gy * gy <= _REACH * r2
                    if scan and ring >= 2:
                        # far rings: skip a bucket that no vertex is nearer to than its site
                        bx = x0 + jx * hx
                        by = y0 + jy * hy
                        scan = not _rect_clear(px, py, a, m, cx, cy, bx, by, bx + hx, by + hy)
                    t0 = start[bucket] if scan else 0
                    t1 = start[bucket + 1] if scan else 0
                    for t in range(t0, t1):
                        qx = sx[t] - cx
                        qy = sy[t] - cy
                        q2 = qx * qx + qy * qy
                        if t == k or q2 > _REACH * r2:
                            continue
                        if nc == cand.shape[0]:
                            grow = True
                            break
                        # insertion into the ring's part of the list, sorted by distance
                        u = nc
                        while u > base and cd[u - 1] > q2:
                            cand[u] = cand[u - 1]
                            cd[u] = cd[u - 1]
                            u -= 1
                        cand[u] = t
                        cd[u] = q2
                        nc += 1
                    jx = bnext[row + jx + 1] if edge_row else jx + 2 * ring
                jy = rownext[jy + 1]
            for c in range(base, nc):
                if grow or m < 3 or cd[c] > _REACH * r2:
                    break  # sorted: the rest are farther still
                t = cand[c]
                qx = sx[t] - cx
                qy = sy[t] - cy
                smax = _plane_values(px, py, a, m, qx, qy, 0.5 * cd[c], ss)
                if smax > -0.5 * _NEAR * r2:
                    # it cuts, or passes within the verification band of a vertex's circle:
                    # the only sites the exact finishing must look at (the others stay
                    # clear of every later vertex, which lies inside today's cell)
                    if nw == watch.shape[0]:
                        grow = True
                        break
                    watch[nw] = t
                    nw += 1
                if smax <= 0.0:
                    continue
                if m + m // 2 + 2 > cap:  # each run of cut vertices adds at most one
                    grow = True
                    break
                m = _cut_by_plane(px, py, po, a, m, b, ss, sidx[t])
                r2 = _radius2(px, py, b, m)
                a, b = b, a
            ring += 1
        if grow:  # rare: a cell with many vertices; start it again with more room
            cap *= 2
            px, py, po, ss, ox, oy, oo, lab, vx, vy, cand, cd, watch = _scratch(cap)
            continue
        c = 0
        if m >= 3:
            for u in range(m):
                lab[u] = po[a + u]
                un = u + 1 if u + 1 < m else 0
                vx[u] = px[a + un] - px[a + u]  # edge vectors (vx, vy are free until _settle)
                vy[u] = py[a + un] - py[a + u]
            for u in range(m):
                # a long float edge is a true edge (rounding moves its ends by ulps only),
                # unless an end is where nearly parallel bisectors cross (sites a few ulps
                # apart): that crossing can be anywhere along them, and so can the edge
                un = u + 1 if u + 1 < m else 0
                e2 = vx[u] * vx[u] + vy[u] * vy[u]
                ss[u] = 1.0 if e2 > _SURE * r2 else 0.0
                for w in (u - 1 if u > 0 else m - 1, un):
                    f2 = vx[w] * vx[w] + vy[w] * vy[w]
                    cr = vx[u] * vy[w] - vy[u] * vx[w]
                    if cr * cr <= _SURE_SIN2 * e2 * f2:
                        ss[u] = 0.0
            # only sites within 2 r of the final cell can matter to its vertices
            keep = 0
            for c in range(nw):
                t = watch[c]
                qx = sx[t] - cx
                qy = sy[t] - cy
                if qx * qx + qy * qy <= _REACH * r2:
                    watch[keep] = t
                    keep += 1
            # cand (the search's list) is free now: _settle's scratch for sites on a circle
            ms = _settle(sidx[k], lab, m, ss, watch, keep, sidx, xs, ys, vx, vy, cand, box)
            # emitted to scratch first: only then is the exact length known, and a rebuilt
            # chunk's output (see _second_pass) has exactly the room the first pass counted
            c = -1
            if ms >= 3:
                c = _emit_exact(
                    sidx[k], lab, ms, vx, vy, xs, ys, box, watch, keep, sidx, ox, oy, oo, 0, cand
                )
            if c < 0:
                c = _emit(px, py, po, a, m, cx, cy, box, ox, oy, oo, 0)
            if fits and pos + c <= dx.shape[0]:
                for t in range(c):
                    dx[pos + t] = ox[t]
                    dy[pos + t] = oy[t]
                    do[pos + t] = oo[t]
            else:
                fits = False
        counts[sidx[k]] = c
        where[k] = pos
        pos += c
        k += 1
    return fits


@njit(**NJIT_PARALLEL)
def _first_pass(sites, orig, grid, box, counts, where, slab_x, slab_y, slab_o, fits):
    """Build every cell into its chunk's slab; ``fits[ch]`` tells whether the slab held it."""
    n = sites[1].shape[0]
    per = slab_x.shape[0] // fits.shape[0]
    for ch in prange(fits.shape[0]):
        lo = ch * per
        fits[ch] = _cells(
            ch * _CHUNK,
            min((ch + 1) * _CHUNK, n),
            sites,
            orig,
            grid,
            box,
            counts,
            where,
            slab_x[lo : lo + per],
            slab_y[lo : lo + per],
            slab_o[lo : lo + per],
        )


@njit(**NJIT_PARALLEL)
def _second_pass(sidx, counts, offsets, where, slab, fits, over, obase, kmap, coords, owner):
    """Copy every cell to its place in the output, closing rings and mapping owners.

    A chunk that fit its slab is read from there; the others were rebuilt into ``over`` (at
    ``obase[ch]``). Rings are closed on the way (first vertex repeated, owner -2 there) and
    owners mapped through ``kmap``.
    """
    n = sidx.shape[0]
    slab_x, slab_y, slab_o = slab
    over_x, over_y, over_o = over
    per = slab_x.shape[0] // fits.shape[0]
    for ch in prange(fits.shape[0]):
        k0 = ch * _CHUNK
        k1 = min((ch + 1) * _CHUNK, n)
        if fits[ch]:
            _copy_cells(
                k0,
                k1,
                sidx,
                counts,
                offsets,
                where,
                ch * per,
                slab_x,
                slab_y,
                slab_o,
                kmap,
                coords,
                owner,
            )
        else:
            _copy_cells(
                k0,
                k1,
                sidx,
                counts,
                offsets,
                where,
                obase[ch],
                over_x,
                over_y,
                over_o,
                kmap,
                coords,
                owner,
            )


@njit(**NJIT)
def _copy_cells(k0, k1, sidx, counts, offsets, where, base, xs, ys, os, kmap, coords, owner):
    for k in range(k0, k1):
        i = sidx[k]
        m = counts[i]
        if m == 0:
            continue
        dst = offsets[i]
        src = base + where[k]
        for t in range(m):
            coords[dst + t, 0] = xs[src + t]
            coords[dst + t, 1] = ys[src + t]
            o = os[src + t]
            owner[dst + t] = kmap[o] if o >= 0 else -1
        coords[dst + m, 0] = xs[src]
        coords[dst + m, 1] = ys[src]
        owner[dst + m] = -2


def _adaptive_grid(xs, ys):
    """The bucket grid and the sites sorted into it.

    A uniform grid with ``_PER_BUCKET`` sites per bucket on average, refined when the sites
    are clustered: if the median site shares its bucket with many more (the dense parts
    hold most sites), the buckets shrink until it shares with about ``_PER_BUCKET``, up to
    ``_MAX_REFINE`` times as many buckets. Sparse regions then scan more (empty) buckets,
    but dense ones no longer test hundreds of sites per cell.
    """
    grid = _grid_shape(xs, ys, _PER_BUCKET)
    sites = _bucket_sort(xs, ys, *grid)
    occ = np.diff(sites[0])
    median = float(np.median(np.repeat(occ, occ)))
    if median > 2.0 * _PER_BUCKET:
        refine = min(median / _PER_BUCKET, _MAX_REFINE)
        grid = _grid_shape(xs, ys, _PER_BUCKET / refine)
        sites = _bucket_sort(xs, ys, *grid)
    nx, ny = grid[4], grid[5]
    occ = np.diff(sites[0]).reshape(ny, nx)
    # rownext[j]: first row >= j with a site; bnext[r (nx + 1) + i]: first column >= i of
    # row r with a site (nx when none), so rings skip empty stretches in O(1)
    rows = np.where(occ.sum(1) > 0, np.arange(ny), ny)
    rownext = np.full(ny + 1, ny, dtype=np.int64)
    rownext[:ny] = np.minimum.accumulate(rows[::-1])[::-1]
    cols = np.where(occ > 0, np.arange(nx, dtype=np.int32), np.int32(nx))
    bnext = np.full((ny, nx + 1), nx, dtype=np.int32)
    bnext[:, :nx] = np.minimum.accumulate(cols[:, ::-1], axis=1)[:, ::-1]
    return grid, (*sites, rownext, bnext.ravel())


def halfplane_cells(xs, ys, box, kmap=None):
    """Voronoi cells of distinct sites clipped to ``box``, by half-plane cutting.

    The output layout is that of ``cells.cells_from_triangulation`` (closed rings).

    Parameters
    ----------
    xs, ys : (n,) float64
        Distinct sites (the engine removes duplicates); they may lie outside the box.
    box : (4,) float64
        ``(xmin, ymin, xmax, ymax)``.
    kmap : (n,) int64, optional
        Output id of each site, used for the edge owners (default: the site's index).

    Returns
    -------
    coords : (K, 2) float64
        Closed counter-clockwise rings (last vertex repeats the first), no consecutive
        duplicates otherwise.
    offsets : (n + 1,) int64
        Cell ``i`` is ``coords[offsets[i]:offsets[i + 1]]``; empty when it misses the box.
    owner : (K,) int64
        ``kmap`` of the site across the edge from vertex ``k`` to the next one, -1 on the
        box boundary, -2 on each closing vertex.

    Examples
    --------
    >>> import numpy as np
    >>> coords, offsets, owner = halfplane_cells(np.array([0.25, 0.75]), np.array([0.5, 0.5]),
    ...                                          np.array([0.0, 0.0, 1.0, 1.0]))
    >>> offsets.tolist(), sorted(owner[:5].tolist())
    ([0, 5, 10], [-2, -1, -1, -1, 1])
    """
    xs = np.ascontiguousarray(xs, dtype=np.float64)
    ys = np.ascontiguousarray(ys, dtype=np.float64)
    n = xs.shape[0]
    kmap = np.arange(n) if kmap is None else np.ascontiguousarray(kmap, dtype=np.int64)
    if n == 0:
        return np.zeros((0, 2)), np.zeros(1, np.int64), np.zeros(0, np.int64)
    boxa = np.ascontiguousarray(box, dtype=np.float64).reshape(4)
    grid, sites = _adaptive_grid(xs, ys)
    orig = (xs, ys)
    nchunks = (n + _CHUNK - 1) // _CHUNK
    per = _SLAB * min(_CHUNK, n) + 16
    counts = np.zeros(n, np.int64)
    where = np.zeros(n, np.int64)
    slab_x = np.zeros(nchunks * per)
    slab_y = np.zeros(nchunks * per)
    slab_o = np.zeros(nchunks * per, np.int64)
    fits = np.zeros(nchunks, np.bool_)
    _first_pass(sites, orig, grid, boxa, counts, where, slab_x, slab_y, slab_o, fits)
    # the rare chunks that overflowed their slab are built again, now that their size
    # is known, one after another into one overflow buffer
    sidx = sites[3]
    obase = np.zeros(nchunks, np.int64)
    total = 0
    for ch in np.flatnonzero(~fits):
        obase[ch] = total
        total += int(counts[sidx[ch * _CHUNK : (ch + 1) * _CHUNK]].sum())
    over = (np.zeros(total), np.zeros(total), np.zeros(total, np.int64))
    for ch in np.flatnonzero(~fits):
        k0 = ch * _CHUNK
        k1 = min((ch + 1) * _CHUNK, n)
        lo = obase[ch]
        hi = lo + int(counts[sidx[k0:k1]].sum())
        views = (over[0][lo:hi], over[1][lo:hi], over[2][lo:hi])
        _cells(k0, k1, sites, orig, grid, boxa, counts, where, *views)
    offsets = np.zeros(n + 1, np.int64)
    np.cumsum(np.where(counts > 0, counts + 1, 0), out=offsets[1:])
    k = int(offsets[-1])
    coords = np.empty((k, 2))  # noqa: TID251 - every slot is written by _second_pass
    owner = np.empty(k, np.int64)  # noqa: TID251 - every slot is written by _second_pass
    slab = (slab_x, slab_y, slab_o)
    _second_pass(sidx, counts, offsets, where, slab, fits, over, obase, kmap, coords, owner)
    return coords, offsets, owner
