"""Voronoi cells from a Delaunay triangulation, clipped to an axis-aligned box.

Output contract (shared with the half-plane kernel):

``coords (K, 2) float64``
    Vertices of every cell's convex polygon (cell intersected with the box), counter-clockwise,
    without a repeated closing vertex and without consecutive duplicates.
``offsets (n + 1,) int64``
    Cell ``i`` is ``coords[offsets[i]:offsets[i + 1]]`` (empty when it misses the box).
``owner (K,) int32``
    ``owner[k] = j`` when the polygon edge from vertex ``k`` to the next vertex lies on the
    bisector of sites ``i`` and ``j``; -1 when it lies on the box.

Interior cells are rings of circumcentres (``kernels/centers``: each the Voronoi vertex named
by its triangle's sites). Triangles whose circumcircles coincide (exactly cocircular sites,
decided with the exact ``incircle``) share one circumcentre, so cocircular grids give clean
cells without zero-length edges. Cells of hull sites (unbounded before
clipping) and cells reaching past the box are cut out of the box by the bisectors of their
Delaunay neighbours, with their shared vertices named canonically (``kernels/cellcut``).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit, prange

from ..config import NJIT, NJIT_PARALLEL, REFLEX_SHORT_ULPS
from .cellcut import class_err, cut_cell, on_sides, side_reaches, spliced_cell
from .centers import circumcenters, merge_cocircular
from .clip import open_ring_convex, ring_corner
from .folds import risky_sites, unfold_cells
from .predicates import orient2d

_U = 2.0**-53

_CHUNK = 2048
_SPLICE_MIN = 48  # cut cells with more neighbours are built by cellcut.spliced_cell
_THIN_ULPS = 8.0  # a ring whose edge passes this close to its site is a strip (rings_astray)
# _pass's modes (np.int64, not literals: one compile for all of them)
_COUNT = np.int64(0)
_FILL = np.int64(1)
_LISTED = np.int64(2)
_NO_DEG = np.zeros(0, dtype=np.int64)  # (_pass's deg and cut, not read with _LISTED)
_NO_CUT = np.zeros(0, dtype=np.bool_)


@njit(**NJIT)
def _at_side_or_out(t, cx, cy, reach, box):
    """Whether triangle ``t``'s centre lies outside the box or is put on a side.

    A centre within reach of a side and not on it (:func:`.cellcut.on_sides`) is put on
    it, so every cell at it is cut: a ring of raw centres would keep it off the side.
    """
    x = cx[t]
    y = cy[t]
    e = max(reach[t], 0.0)  # (-1: never moved, so inside means inside)
    if box[0] + e < x < box[2] - e and box[1] + e < y < box[3] - e:
        return False  # most centres: one test, as before the sides' reach
    x, y, _ = on_sides(t, cx, cy, reach, box)
    return x != cx[t] or y != cy[t] or not (box[0] <= x <= box[2] and box[1] <= y <= box[3])


@njit(**NJIT)
def _outgoing(tri, he, cx, cy, reach, box, n):
    """Per point: one outgoing halfedge, its degree, and whether its cell must be cut.

    Hull points get their outgoing hull halfedge. A cell is cut when its point is on the hull
    or one of its circumcentres lies outside the box or within reach of a side and not on
    it (:func:`.cellcut.on_sides`: the cut puts such a vertex on the side, and every cell
    at it must).
    """
    out = np.full(n, -1, dtype=np.int64)
    deg = np.zeros(n, dtype=np.int64)
    cut = np.zeros(n, dtype=np.bool_)
    for e in range(tri.shape[0]):
        v = tri[e]
        out[v] = e
        deg[v] += 1
    for e in range(tri.shape[0]):
        if he[e] == -1:
            out[tri[e]] = e
            cut[tri[e]] = True
    for t in range(tri.shape[0] // 3):
        # most centres are inside by more than their reach: tested here, where the call
        # made this loop 5-15 times slower (1e5 uniform: 1 -> 5-15 ms)
        e = max(reach[t], 0.0)
        if box[0] + e < cx[t] < box[2] - e and box[1] + e < cy[t] < box[3] - e:
            continue
        if _at_side_or_out(t, cx, cy, reach, box):
            cut[tri[3 * t]] = True
            cut[tri[3 * t + 1]] = True
            cut[tri[3 * t + 2]] = True
    return out, deg, cut


@njit(**NJIT)
def _reflex_by_rounding(px, py, m):
    """Whether the open ring ``p[:m]`` is simple and turns right only beside short edges.

    A strip an ulp wide between sites a few ulps apart meets this cell along an edge a few
    ulps long, and rounding turns the ring the wrong way at its ends: the ring shares every
    vertex with its neighbours, where the spliced ring (:func:`.cellcut.spliced_cell`, no
    relabelling) would be convex but lack the strip's edge. Short: within
    ``REFLEX_SHORT_ULPS`` ulps of the vertex's coordinates. Rings of more than
    ``_SPLICE_MIN`` vertices are not tested (the simplicity test is quadratic).
    """
    if m > _SPLICE_MIN:
        return False
    area = 0.0
    for k in range(m):
        k0, k2, ex, ey, fx, fy = ring_corner(px, py, m, k)
        if (ex == 0.0 and ey == 0.0) or (fx == 0.0 and fy == 0.0):
            return False
        area += (px[k] - px[0]) * (py[k2] - py[0]) - (px[k2] - px[0]) * (py[k] - py[0])
        turn = orient2d(px[k0], py[k0], px[k], py[k], px[k2], py[k2])
        if turn <= 0.0:
            s = REFLEX_SHORT_ULPS * _U * (abs(px[k]) + abs(py[k]))
            if not (max(abs(ex), abs(ey)) <= s or max(abs(fx), abs(fy)) <= s):
                # a steep edge a few ulps wide is longer than that along the other axis
                # (the strip's end meets a bisector of slope 3 there): the vertex is still
                # within ``s`` of the line through its neighbours (``turn`` is twice the
                # triangle's area: that distance times the chord)
                chord = np.hypot(px[k2] - px[k0], py[k2] - py[k0])
                if not (turn < 0.0 and -turn <= s * chord):
                    return False
    if not area > 0.0:
        return False
    # a fold (a float circle's hull cells all reach its centre) also turns right beside
    # short edges: the ring must be simple, no two edges that are not neighbours meeting
    for a in range(m):
        a2 = a + 1 if a + 1 < m else 0
        for b in range(a + 2, m):
            if a == 0 and b == m - 1:
                continue
            b2 = b + 1 if b + 1 < m else 0
            o1 = orient2d(px[a], py[a], px[a2], py[a2], px[b], py[b])
            o2 = orient2d(px[a], py[a], px[a2], py[a2], px[b2], py[b2])
            if (o1 > 0.0 and o2 > 0.0) or (o1 < 0.0 and o2 < 0.0):
                continue
            o3 = orient2d(px[b], py[b], px[b2], py[b2], px[a], py[a])
            o4 = orient2d(px[b], py[b], px[b2], py[b2], px[a2], py[a2])
            if (o3 > 0.0 and o4 > 0.0) or (o3 < 0.0 and o4 < 0.0):
                continue
            if o1 == 0.0 and o2 == 0.0:  # on one line: they meet only if they overlap
                lo = min(px[a], px[a2]) if px[a] != px[a2] else min(py[a], py[a2])
                hi = max(px[a], px[a2]) if px[a] != px[a2] else max(py[a], py[a2])
                u = px[b] if px[a] != px[a2] else py[b]
                w = px[b2] if px[a] != px[a2] else py[b2]
                if max(u, w) < lo or min(u, w) > hi:
                    continue
            return False
    return True


@njit(**NJIT)
def _cell(i, xs, ys, ws, tri, he, cx, cy, err, reach, cls, out, box, bufs, nbrs, cl, tb, ss):
    """Polygon of site ``i`` into ``p``; returns the vertex count.

    A cell whose ring of circumcentres lies inside the box is that ring. Any other cell
    (hull sites, cells reaching past the box) is cut out of the box by the bisectors of its
    Delaunay neighbours: this never relies on far-away, ill-conditioned circumcentres of
    nearly flat triangles.
    """
    px, py, pw, qx, qy, qw = bufs
    o0 = out[i]
    if o0 == -1:
        return 0
    hull = he[o0] == -1
    o = o0
    m = 0
    k = 0
    inside = not hull
    while True:
        t = o // 3
        p = o - o % 3 + (o + 2) % 3  # previous halfedge: y -> i
        y = tri[p]
        nbrs[k] = tri[o - o % 3 + (o + 1) % 3]
        tb[k] = t
        k += 1
        if inside:
            if m > 0 and cls[t] == cl[m - 1]:
                pw[m - 1] = y  # same circumcentre as the previous vertex: no 0-length edge
            else:
                vx = cx[t]
                vy = cy[t]
                px[m] = vx
                py[m] = vy
                pw[m] = y
                cl[m] = cls[t]
                m += 1
                if _at_side_or_out(t, cx, cy, reach, box):
                    inside = False
        o = he[p]
        if o == -1:
            nbrs[k] = y
            tb[k] = -1
            k += 1
            break
        if o == o0:
            break
    if not inside:
        if k > _SPLICE_MIN:
            m = spliced_cell(i, xs, ys, ws, nbrs, tb, k, box, cx, cy, err, reach, bufs, cl, ss)
            if m >= 0:
                return m
        m = cut_cell(i, xs, ys, ws, nbrs, tb, k, box, cx, cy, reach, px, py, pw, qx, qy, qw, ss)
        if m < 3 or open_ring_convex(px, py, m) or _reflex_by_rounding(px, py, m):
            return m
        # the cut folded: bisectors that meet within their rounding of one point (a float
        # circle's hull cells all reach its centre) cut in the wrong order. The edges between
        # centres safely inside the box are final; cut by the others only and splice them in
        m = spliced_cell(i, xs, ys, ws, nbrs, tb, k, box, cx, cy, err, reach, bufs, cl, ss)
        if m >= 3 and open_ring_convex(px, py, m):
            return m
        return cut_cell(i, xs, ys, ws, nbrs, tb, k, box, cx, cy, reach, px, py, pw, qx, qy, qw, ss)
    if m > 1 and cl[m - 1] == cl[0]:
        m -= 1
    return m if m >= 3 else 0


@njit(**NJIT)
def _scratch(cap):
    """Per-chunk scratch of one cell: rings ``p``, ``q`` with owners, neighbour ring, values."""
    bufs = (
        np.zeros(cap),
        np.zeros(cap),
        np.zeros(cap, dtype=np.int64),
        np.zeros(cap),
        np.zeros(cap),
        np.zeros(cap, dtype=np.int64),
    )
    nbrs = np.zeros(cap, dtype=np.int64)
    cl = np.zeros(cap, dtype=np.int64)
    tb = np.zeros(cap, dtype=np.int64)
    return bufs, nbrs, cl, tb, np.zeros(cap)


@njit(**NJIT)
def _write_ring(i, tri, he, cx, cy, out, base, coords, owner, kmap):
    """The ring of uncut, unmerged cell ``i`` at ``coords[base:]``, closed (see :func:`_pass`)."""
    o0 = out[i]
    if o0 == -1:
        return
    o = o0
    m = 0
    while True:
        p = o - o % 3 + (o + 2) % 3  # previous halfedge: y -> i
        t = o // 3
        coords[base + m, 0] = cx[t]
        coords[base + m, 1] = cy[t]
        owner[base + m] = kmap[tri[p]]
        m += 1
        o = he[p]
        if o == o0 or o == -1:
            break
    if m < 3:
        return  # (not reached for an interior site: its count is its degree, >= 3)
    coords[base + m, 0] = cx[o0 // 3]
    coords[base + m, 1] = cy[o0 // 3]
    owner[base + m] = -2


@njit(**NJIT)
def _classed_ring(i, tri, he, cx, cy, cls, out, base, coords, owner, kmap):
    """:func:`_cell` of an uncut cell (interior site, every centre in the box), from the walk.

    Returns its vertex count, as :func:`_cell` does: one vertex per run of triangles of
    one class around the site, the last run dropped when it is the first one's class. With
    ``base >= 0`` the ring is also written closed at ``coords[base:]`` (what :func:`_pass`
    writes from :func:`_cell`'s ring, bit for bit: each vertex's owner is the neighbour
    after the last triangle of its run); only a cell of 3 or more vertices has room there.
    """
    o0 = out[i]
    if o0 == -1:
        return 0
    o = o0
    m = 0
    first = np.int64(-1)
    last = np.int64(-1)
    write = base >= 0
    while True:
        p = o - o % 3 + (o + 2) % 3  # previous halfedge: y -> i
        t = o // 3
        c = cls[t]
        if m > 0 and c == last:
            if write:
                owner[base + m - 1] = kmap[tri[p]]  # same vertex: the run's last owner
        else:
            if write:
                coords[base + m, 0] = cx[t]
                coords[base + m, 1] = cy[t]
                owner[base + m] = kmap[tri[p]]
            if m == 0:
                first = c
            last = c
            m += 1
        o = he[p]
        if o == -1 or o == o0:
            break
    if m > 1 and last == first:
        m -= 1
    if m < 3:
        return 0
    if write:
        coords[base + m, 0] = coords[base, 0]
        coords[base + m, 1] = coords[base, 1]
        owner[base + m] = -2
    return m


@njit(**NJIT)
def _put_ring(base, m, px, py, pw, coords, owner, kmap):
    """Write a built cell's ``m`` vertices at ``base`` as a closed ring, owners through ``kmap``."""
    for k in range(m):
        coords[base + k, 0] = px[k]
        coords[base + k, 1] = py[k]
        w = pw[k]
        owner[base + k] = kmap[w] if w >= 0 else w
    coords[base + m, 0] = px[0]
    coords[base + m, 1] = py[0]
    owner[base + m] = -2


@njit(**NJIT_PARALLEL)
def _pass(
    mode,
    sites,
    xs,
    ys,
    ws,
    tri,
    he,
    cx,
    cy,
    err,
    reach,
    cls,
    out,
    box,
    cap,
    deg,
    cut,
    merged,
    start,
    counts,
    coords,
    owner,
    kmap,
):
    """Count (``mode & _FILL == 0``) or write the cells of every site, or of ``sites`` only.

    One parallel pass for :func:`_build`'s two passes and :func:`_some`'s: numba links and
    optimises :func:`_cell`'s whole call tree into every function that calls it, twice for a
    parallel one (the outer function and its parfor body), so one pass carries it once
    instead of three times (group 1 of the suite's compile step: 65 + 12 s for two).

    ``mode`` (an np.int64, not a literal: one compile for all four) holds ``_FILL`` and
    ``_LISTED``. Counting writes ``counts``; filling writes each cell as a closed ring at
    ``start``, owners through ``kmap``. With ``_LISTED`` the cells of ``sites`` are built
    by :func:`_cell` at ``counts[s]`` / ``start[s]`` (``deg``, ``cut`` and ``merged`` are
    not read). Otherwise every site ``i``, at ``counts[i]`` / ``start[i]``: without
    cocircular merges an uncut cell has one vertex per incident triangle (its count is its
    degree) and is written straight from the halfedge walk (:func:`_write_ring`); with them,
    an uncut cell is counted and written from its walk (:func:`_classed_ring`); only cut
    cells need the full construction.
    """
    fill = (mode & _FILL) != 0
    listed = (mode & _LISTED) != 0
    n = sites.shape[0] if listed else xs.shape[0]
    if not fill and not listed and not merged:
        for i in prange(n):
            counts[i] = deg[i] if deg[i] >= 3 else 0
    nchunks = (n + _CHUNK - 1) // _CHUNK
    for ch in prange(nchunks):
        bufs, nbrs, cl, tb, ss = _scratch(cap[ch])
        px, py, pw = bufs[0], bufs[1], bufs[2]
        for s in range(ch * _CHUNK, min(n, (ch + 1) * _CHUNK)):
            i = np.int64(s)
            if listed:
                i = sites[s]
            elif not cut[i]:
                if not merged:  # (counted by its degree above)
                    if fill:
                        _write_ring(i, tri, he, cx, cy, out, start[i], coords, owner, kmap)
                elif not fill or counts[i] > 0:  # inside the box: the walk alone builds it
                    base = start[i] if fill else np.int64(-1)
                    m = _classed_ring(i, tri, he, cx, cy, cls, out, base, coords, owner, kmap)
                    if not fill:
                        counts[i] = m
                continue
            m = _cell(
                i, xs, ys, ws, tri, he, cx, cy, err, reach, cls, out, box, bufs, nbrs, cl, tb, ss
            )
            if not fill:
                counts[s] = m
            elif m > 0:
                _put_ring(start[s], m, px, py, pw, coords, owner, kmap)


def cells_from_triangulation(xs, ys, tri, he, box, order, kmap, *, astray=False):
    """Clipped Voronoi cells of distinct sites from their Delaunay triangulation.

    Parameters
    ----------
    xs, ys : (u,) float64
        Sites in the kernel's numbering (for locality, the sweep order of the triangulation).
    tri, he : (3 t,) int32
        Flat triangles and halfedges in that numbering.
    box : (4,) float64
        ``(xmin, ymin, xmax, ymax)`` every cell is clipped to.
    order : (u,) int64
        ``order[k]`` is the output position of kernel site ``k``.
    kmap : (u,) int64
        Output owner id of kernel site ``k``.
    astray : bool
        Also return, in output order, :func:`rings_astray`'s code of each site's ring (1:
        misses its site, 2: a strip a few ulps wide at it, 0: neither or not tested),
        tested where merged or short-edged vertices can have moved a ring past its site
        (the cells checked for folds); the others hold their sites.

    Returns
    -------
    coords : (K, 2) float64
        Closed rings (last vertex repeats the first) in output order.
    lengths : (u + 1,) int64
        Output cell ``j`` is ``coords[lengths[j]:lengths[j + 1]]`` (empty when equal).
    owner : (K,) int64
        ``owner[v]`` is the site across the edge from vertex ``v`` to ``v + 1``, -1 on the box,
        -2 on each closing vertex.
    codes : (u,) uint8
        With ``astray=True`` only, returned after the three: ``((coords, lengths, owner),
        codes)``.

    Every ring is certified convex (exact turns, :func:`.clip.ring_convex`); a ring that
    rounding folded across edges that are not neighbours (the vertices of a float circle far
    from the origin are spaced like the ulps there) has its short edges around the fold
    contracted (:func:`.folds.fold_pairs`, :func:`.centers.contract`: classes of triangles, so
    every cell holding those vertices gets the one named vertex), the cells at the changed
    vertices are built again (:func:`.folds.unfold_cells`: the best round is kept).
    """
    state = dual_prepare(xs, ys, tri, he, box, order, kmap)
    xs, ys, tri, he, box, order, kmap, cx, cy, err, cls, risk, merged, terr, reach = state
    out, cells = _build(xs, ys, tri, he, cx, cy, terr, reach, cls, box, order, kmap, merged)
    cells, tested = unfold_cells(state, out, cells, rebuild_cells)
    if not astray:
        return cells
    n = xs.shape[0]
    miss = astray_of(xs, ys, cells, box, order, tested) if tested.any() else np.zeros(n, np.uint8)
    return cells, miss


def astray_of(xs, ys, cells, box, order, picked):
    """:func:`rings_astray` codes of the rings of ``picked`` (kernel order, like ``xs``)."""
    n = xs.shape[0]
    which = np.zeros(n, dtype=np.bool_)
    which[order[picked]] = True
    sx = np.zeros(n)
    sy = np.zeros(n)
    sx[order] = xs
    sy[order] = ys
    return rings_astray(sx, sy, cells[0], cells[1], box, which)


def dual_prepare(xs, ys, tri, he, box, order, kmap):
    """What :func:`cells_from_triangulation` builds cells from (``tri``/``he`` flipped in place)."""
    # the sweeps hand over strided views of their sorted points: one layout for every
    # caller, or numba compiles this whole kernel a second time for the other one
    xs = np.ascontiguousarray(xs)
    ys = np.ascontiguousarray(ys)
    box = np.asarray(box, dtype=np.float64)
    order = np.asarray(order, dtype=np.int64)
    cx, cy, err, flag = circumcenters(xs, ys, tri, he)
    cls, near = merge_cocircular(xs, ys, tri, he, cx, cy, err, flag, kmap, box)
    merged = bool(flag.any()) or bool((cls != np.arange(cls.shape[0])).any())
    risk = risky_sites(tri, near, xs.shape[0])
    terr = class_err(cls, err) if merged else err
    reach = side_reaches(xs, ys, tri, cls, cx, cy, terr, box)
    return xs, ys, tri, he, box, order, kmap, cx, cy, err, cls, risk, merged, terr, reach


def _build(xs, ys, tri, he, cx, cy, err, reach, cls, box, order, kmap, merged):
    """One construction of every cell from the classes ``cls``.

    Returns ``(out, (coords, lengths, owner))``, ``out`` each site's outgoing halfedge.
    """
    n = xs.shape[0]
    out, deg, cut = _outgoing(tri, he, cx, cy, reach, box, n)
    # scratch per chunk for its own largest degree: one site with n neighbours must not
    # make every chunk allocate (and zero) rings of n vertices (quadratic at 1e6)
    starts = np.arange(0, n, _CHUNK)
    cap = (np.maximum.reduceat(deg, starts) + 16) if n else np.zeros(0, np.int64)
    ws = np.zeros(n)
    counts = np.zeros(n, dtype=np.int64)
    none = np.zeros(0, dtype=np.int64)
    merged = bool(merged)
    args = (tri, he, cx, cy, err, reach, cls, out, box, cap, deg, cut, merged)
    _pass(_COUNT, none, xs, ys, ws, *args, none, counts, np.zeros((0, 2)), none, kmap)
    closed = np.where(counts > 0, counts + 1, 0)
    lengths = np.zeros(n + 1, dtype=np.int64)
    lengths[1:][order] = closed
    np.cumsum(lengths, out=lengths)
    start = lengths[:-1][order]
    total = int(lengths[-1])
    coords = np.zeros((total, 2))
    owner = np.zeros(total, dtype=np.int64)
    _pass(_FILL, none, xs, ys, ws, *args, start, counts, coords, owner, kmap)
    return out, (coords, lengths, owner)


def _some(sites, xs, ys, ws, tri, he, cx, cy, err, reach, cls, out, box, cap, counts, start, *rest):
    """Count (``start`` empty) or write (``coords, owner, kmap`` in ``rest``) ``sites``' cells.

    :func:`_pass` with ``_LISTED``: every cell built by :func:`_cell`, ``counts[s]`` and
    ``start[s]`` those of ``sites[s]``.
    """
    mode = _LISTED | (_FILL if start.shape[0] else _COUNT)
    args = (tri, he, cx, cy, err, reach, cls, out, box, cap, _NO_DEG, _NO_CUT, True)
    _pass(mode, sites, xs, ys, ws, *args, start, counts, *rest)


@njit(**NJIT_PARALLEL)
def _keep(lengths, new, keep, coords, owner, ncoords, nowner):
    """Copy the rings of the output cells marked in ``keep`` to their new places."""
    for j in prange(keep.shape[0]):
        if not keep[j]:
            continue
        a = lengths[j]
        d = new[j] - a
        for k in range(a, lengths[j + 1]):
            ncoords[k + d, 0] = coords[k, 0]
            ncoords[k + d, 1] = coords[k, 1]
            nowner[k + d] = owner[k]


def rebuild_cells(xs, ys, tri, he, cx, cy, err, reach, cls, box, order, kmap, cells, redo):
    """:func:`_build` (classes merged) that builds only the cells marked in ``redo`` again.

    The other cells keep their rings from ``cells``; a cell depends only on the centres and
    classes of its own triangles, so this is :func:`_build`'s answer when those of the other
    cells did not change. Returns ``(out, (coords, lengths, owner))``.
    """
    n = xs.shape[0]
    sites = np.flatnonzero(redo).astype(np.int64)
    if 8 * sites.shape[0] > n:
        return _build(xs, ys, tri, he, cx, cy, err, reach, cls, box, order, kmap, True)
    coords, lengths, owner = cells
    out, deg, _ = _outgoing(tri, he, cx, cy, reach, box, n)
    starts = np.arange(0, sites.shape[0], _CHUNK)
    cap = np.maximum.reduceat(deg[sites], starts) + 16 if sites.shape[0] else np.zeros(0, np.int64)
    ws = np.zeros(n)
    counts = np.zeros(sites.shape[0], dtype=np.int64)
    none = np.zeros(0, dtype=np.int64)
    args = (cls, out, box, cap, counts)
    _some(sites, xs, ys, ws, tri, he, cx, cy, err, reach, *args, none, coords, owner, kmap)
    closed = np.diff(lengths)
    closed[order[sites]] = np.where(counts > 0, counts + 1, 0)
    new = np.zeros(n + 1, dtype=np.int64)
    np.cumsum(closed, out=new[1:])
    ncoords = np.zeros((int(new[-1]), 2))
    nowner = np.zeros(int(new[-1]), dtype=np.int64)
    keep = np.ones(n, dtype=np.bool_)
    keep[order[sites]] = False
    _keep(lengths, new, keep, coords, owner, ncoords, nowner)
    start = new[:-1][order[sites]]
    _some(sites, xs, ys, ws, tri, he, cx, cy, err, reach, *args, start, ncoords, nowner, kmap)
    return out, (ncoords, new, nowner)


@njit(**NJIT_PARALLEL)
def _cut_all(xs, ys, indptr, indices, box, cap, counts, offsets, coords, owner, fill):
    """Cut cells of all sites from their neighbour lists (count pass, then ``fill`` pass)."""
    n = xs.shape[0]
    ws = np.zeros(n)
    nchunks = (n + _CHUNK - 1) // _CHUNK
    for ch in prange(nchunks):
        px = np.zeros(cap)
        py = np.zeros(cap)
        pw = np.zeros(cap, dtype=np.int64)
        qx = np.zeros(cap)
        qy = np.zeros(cap)
        qw = np.zeros(cap, dtype=np.int64)
        no_tris = np.full(cap, -1, dtype=np.int64)
        none = np.zeros(0)
        ss = np.zeros(cap)
        for i in range(ch * _CHUNK, min(n, (ch + 1) * _CHUNK)):
            nb = indices[indptr[i] : indptr[i + 1]]
            m = cut_cell(
                i,
                xs,
                ys,
                ws,
                nb,
                no_tris,
                nb.shape[0],
                box,
                none,
                none,
                none,
                px,
                py,
                pw,
                qx,
                qy,
                qw,
                ss,
            )
            if not fill:
                counts[i] = m
                continue
            base = offsets[i]
            for k in range(m):
                coords[base + k, 0] = px[k]
                coords[base + k, 1] = py[k]
                owner[base + k] = pw[k]


def cells_from_neighbors(xs, ys, indptr, indices, box):
    """Clipped cells when the neighbours are known but there are no triangles (collinear)."""
    n = xs.shape[0]
    box = np.asarray(box, dtype=np.float64)
    deg = np.diff(indptr)
    cap = int(deg.max() if n else 0) + 16
    counts = np.zeros(n, dtype=np.int64)
    dummy_c = np.zeros((0, 2))
    dummy_o = np.zeros(0, dtype=np.int32)
    offsets = np.zeros(n + 1, dtype=np.int64)
    _cut_all(xs, ys, indptr, indices, box, cap, counts, offsets, dummy_c, dummy_o, False)
    np.cumsum(counts, out=offsets[1:])
    coords = np.zeros((int(offsets[-1]), 2))
    owner = np.zeros(int(offsets[-1]), dtype=np.int32)
    _cut_all(xs, ys, indptr, indices, box, cap, counts, offsets, coords, owner, True)
    return coords, offsets, owner


@njit(**NJIT)
def _holds(sx, sy, coords, a, b):
    """Whether the closed ring ``coords[a:b]`` holds the point ``s`` (its edges included).

    The crossing number of a ray from ``s`` along +x, each crossing decided by an exact
    turn (:func:`.predicates.orient2d`), so a ring that rounding left reflex by an ulp is
    tested as the polygon it is. Only the edges that straddle the point's height are turned.
    """
    inside = False
    for k in range(a, b - 1):
        ax, ay = coords[k, 0], coords[k, 1]
        bx, by = coords[k + 1, 0], coords[k + 1, 1]
        if (ay > sy) != (by > sy):
            o = orient2d(ax, ay, bx, by, sx, sy)
            if o == 0.0:
                return True  # on the edge
            if (o > 0.0) == (by > ay):
                inside = not inside
        elif ay == sy and (ax == sx or (by == sy and min(ax, bx) <= sx <= max(ax, bx))):
            return True  # at a vertex, or on an edge along the point's height
    return inside


@njit(**NJIT)
def _thin(sx, sy, coords, a, b, box):
    """Whether a ring's edge passes within ``_THIN_ULPS`` ulps of the point ``s``.

    The closed ring is ``coords[a:b]``; edges along the box's sides are not counted. Such a
    ring is a strip a few ulps wide at its site.
    """
    tol = _THIN_ULPS * _U * (abs(sx) + abs(sy))
    for k in range(a, b - 1):
        ax, ay = coords[k, 0], coords[k, 1]
        bx, by = coords[k + 1, 0], coords[k + 1, 1]
        if (ax == bx and (ax == box[0] or ax == box[2])) or (
            ay == by and (ay == box[1] or ay == box[3])
        ):
            continue
        if not (min(ax, bx) - tol <= sx <= max(ax, bx) + tol):
            continue
        if not (min(ay, by) - tol <= sy <= max(ay, by) + tol):
            continue
        ex = bx - ax
        ey = by - ay
        if abs(ex * (sy - ay) - ey * (sx - ax)) <= tol * np.hypot(ex, ey):
            return True
    return False


@njit(**NJIT_PARALLEL)
def rings_astray(xs, ys, coords, lengths, box, which):
    """Per site: 1 where its non-empty ring misses it (exact), 2 where it is a strip at it.

    A strip: the ring holds its site within ``_THIN_ULPS`` ulps of an edge (:func:`_thin`).
    Site ``j`` is ``(xs[j], ys[j])`` and its ring ``coords[lengths[j]:lengths[j + 1]]``;
    only the sites marked in ``which`` and inside ``box`` are tested (a cell clipped to the
    box misses a site outside it). Three sites 1-4 ulps apart on a line: the middle one's
    cell is a strip an ulp or two wide whose two vertices at one end merged by rounding,
    and its ring, a triangle, passed the site by a fraction of an ulp.
    """
    n = xs.shape[0]
    out = np.zeros(n, dtype=np.uint8)
    for j in prange(n):
        a = lengths[j]
        b = lengths[j + 1]
        sx, sy = xs[j], ys[j]
        if which[j] and b > a and box[0] <= sx <= box[2] and box[1] <= sy <= box[3]:
            if not _holds(sx, sy, coords, a, b):
                out[j] = 1
            elif _thin(sx, sy, coords, a, b, box):
                out[j] = 2
    return out


@njit(**NJIT_PARALLEL)
def rings_miss(xs, ys, coords, lengths, box):
    """Per site: whether its non-empty ring misses it (exact), the code 1 of :func:`rings_astray`.

    Without the strip test, so about one exact turn per ring (the two edges that straddle
    the site's height): for rings whose vertices are all named and none merged away by
    the dual (the half-plane cells), where only code 1 counts.
    """
    n = xs.shape[0]
    out = np.zeros(n, dtype=np.bool_)
    for j in prange(n):
        a = lengths[j]
        b = lengths[j + 1]
        sx, sy = xs[j], ys[j]
        if b > a and box[0] <= sx <= box[2] and box[1] <= sy <= box[3]:
            out[j] = not _holds(sx, sy, coords, a, b)
    return out


@njit(**NJIT)
def rings_nearly_convex(coords, lengths, ulps):
    """Whether every closed ring is convex up to the rounding of its vertices.

    A ring may turn right only at a vertex within ``ulps`` ulps (of the three points'
    largest coordinate) of the chord between its neighbours, as ``describe()`` counts
    convexity. The turn's side is exact (:func:`.predicates.orient2d`).
    """
    for j in range(lengths.shape[0] - 1):
        a = lengths[j]
        m = lengths[j + 1] - a - 1  # the closing vertex repeats the first
        for k in range(m):
            k0 = a + (k - 1 if k > 0 else m - 1)
            k1 = a + k
            k2 = a + (k + 1 if k + 1 < m else 0)
            x0, y0 = coords[k0, 0], coords[k0, 1]
            x1, y1 = coords[k1, 0], coords[k1, 1]
            x2, y2 = coords[k2, 0], coords[k2, 1]
            turn = orient2d(x0, y0, x1, y1, x2, y2)
            if turn >= 0.0:
                continue
            big = max(max(abs(x0), abs(y0)), max(max(abs(x1), abs(y1)), max(abs(x2), abs(y2))))
            ulp = math.ldexp(1.0, math.frexp(big)[1] - 53)  # numpy's spacing(big)
            reach = ulps * ulp * np.hypot(x2 - x0, y2 - y0)
            if not -turn <= reach:
                return False
    return True
