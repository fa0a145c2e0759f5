"""Power (Laguerre) cells by cutting a box with power bisectors; Voronoi is the equal-weight case.

Cell ``i`` is ``{x : |x - p_i|^2 - w_i <= |x - p_j|^2 - w_j}`` for every neighbour ``j``. With
``u = x - p_i`` and ``d = p_j - p_i`` the constraint reads ``d.u <= (|d|^2 + w_i - w_j) / 2``,
so every test is made relative to the cell's own site and large coordinates keep their
precision. :func:`box_cell` makes that cut (through ``kernels/clip``); with equal weights its
signed values are the Voronoi bisectors' bit for bit, and the Delaunay-dual cell builder
(``kernels/cells``) uses it for the cells it cuts.

After the cut every vertex is replaced by the one computed from its name
(``kernels/vertex``): the power centre of the cell's site and its two edges' owners, or the
power bisector's crossing with a box side, whatever its distance from the cut. Where four or
more cells meet within rounding the cells' float cuts can disagree on which tiny edges
exist; :func:`_reconcile` then makes the rings agree (an edge one cell lacks is given to it
when the names order its ends, merged to one point when they do not), so neighbouring
cells share every vertex bit for bit at any distance from the origin.

Output contract (the same closed-ring layout the Voronoi assembly consumes):

``coords (K, 2) float64``
    Closed counter-clockwise rings (last vertex repeats the first), in site order.
``lengths (n + 1,) int64``
    Cell ``i`` is ``coords[lengths[i]:lengths[i + 1]]``; empty when the cell misses the box.
``owner (K,) int64``
    ``owner[k] = j`` when the edge from vertex ``k`` to ``k + 1`` lies on the power bisector of
    sites ``i`` and ``j``, -1 on the box, -2 on the closing vertex.
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

from ..config import NJIT, NJIT_PARALLEL, POWER_CROWDED_RTOL, POWER_CROWDED_ULPS, SIDE_BOX_RTOL
from .clip import cut_ring, plane_values
from .distance_exact import compare
from .power_tiny import crossing, exact_power_signs, tiny_ring_area, vertex
from .sidecross import power_side

_U = 2.0**-53  # unit roundoff of float64


@njit(inline="always", **NJIT)  # per cut cell: no call (reference counts) in the hot path
def _box_ring(box, px, py, pw):
    """The box as a ring in ``p`` (owners -2 bottom, -3 right, -4 top, -1 left); returns 4."""
    px[0] = box[0]
    py[0] = box[1]
    px[1] = box[2]
    py[1] = box[1]
    px[2] = box[2]
    py[2] = box[3]
    px[3] = box[0]
    py[3] = box[3]
    pw[0] = -2  # bottom
    pw[1] = -3  # right
    pw[2] = -4  # top
    pw[3] = -1  # left
    return np.int64(4)


@njit(**NJIT)
def box_cell(i, xs, ys, ws, nbrs, nn, box, px, py, pw, qx, qy, qw, ss):
    """Box cut by the power bisectors of site ``i`` with ``nbrs[:nn]``; result in ``p``.

    Returns the vertex count (0 when less than a polygon is left). Edge owners are the
    neighbours, and -1 (left), -2 (bottom), -3 (right), -4 (top) on the box sides. All
    buffers need room for ``nn + 5`` vertices; ``q`` and ``ss`` are scratch.
    """
    # np.int64, not literals: numba would compile the clip's callees once more for them
    m = _box_ring(box, px, py, pw)
    zero = np.int64(0)
    sx = xs[i]
    sy = ys[i]
    swapped = False
    w = np.empty((0, 0))  # noqa: TID251  (scratch of the exact signs, made when needed)
    # a box far smaller than the sites' ulp (the regime of ``sidecross``): the cut's
    # interpolated crossings are off by a visible part of the box
    tiny = SIDE_BOX_RTOL * max(box[2] - box[0], box[3] - box[1])
    for k in range(nn):
        j = nbrs[k]
        dx = xs[j] - sx
        dy = ys[j] - sy
        # the weight difference first: |d|^2 + w_i would round |d|^2 away when the weights
        # are large, and sites i and j would then see two different bisectors (a gap)
        h = 0.5 * (dx * dx + dy * dy + (ws[i] - ws[j]))
        smax = plane_values(px, py, zero, m, dx, dy, sx, sy, h, ss)
        if ws[i] == ws[j]:
            smax, w = _exact_signs(i, j, xs, ys, px, py, m, dx, dy, h, ss, smax, w)
        else:
            smax = exact_power_signs(i, j, xs, ys, ws, px, py, m, dx, dy, h, ss, smax)
        if smax <= 0.0:
            continue
        m = cut_ring(px, py, pw, zero, m, ss, qx, qy, qw, zero, j)
        if m < 3:
            return 0
        px, qx = qx, px
        py, qy = qy, py
        pw, qw = qw, pw
        swapped = not swapped
        big = max(max(abs(sx), abs(sy)), max(abs(xs[j]), abs(ys[j])))
        if np.spacing(big) > tiny and _outside(sx, sy, xs[j], ys[j], box):
            # name the two new vertices now, so the next cuts' exact signs see them where
            # they are (issue 15: a float circle at 1e12 seen through a unit window lost
            # a cell whose exact area was 3e-9 of the box); not for sites in the box (a
            # circle of 1,000 sites an ulp apart at 4e6 in its 256-ulp box: named early, the
            # cells' edges no longer matched). Power bisectors too (power6: sites on a
            # circle of radius 5 in a box 1e-300 wide, weights of the box's size)
            _name_new(i, j, xs, ys, ws, px, py, pw, m, box)
    m = _corner_crossings(i, xs, ys, ws, px, py, pw, m, box)
    if swapped:
        for v in range(m):
            qx[v] = px[v]
            qy[v] = py[v]
            qw[v] = pw[v]
    return m


@njit(**NJIT)
def _exact_signs(i, j, xs, ys, px, py, m, dx, dy, h, ss, smax, w):
    """Correct the float values ``ss[:m]`` of the bisector of ``i, j`` whose sign is unsure.

    The value ``d.(x - p_i) - h`` is rounded at the sites' magnitude: a box far smaller
    than the sites' spacing (issue 15: sites (+-1, 0) in a box 1e-16 wide) sees every
    vertex at value 0 and no cut, both cells the whole box. A value within its rounding
    bound of 0 is given the exact side of its vertex (:func:`.distance_exact.compare`):
    kept where its sign is right, else that sign times the bound (the crossing then falls
    between the vertices, and is named afterwards). Returns the largest value and the
    exact test's scratch.
    """
    smax = -np.inf
    for v in range(m):
        sv = ss[v]
        e = 8.0 * _U * (abs(dx * (px[v] - xs[i])) + abs(dy * (py[v] - ys[i])) + abs(h))
        if abs(sv) <= e:
            if w.shape[0] == 0:
                w = np.empty((9, 64))  # noqa: TID251  (every slot read is written first)
            t = compare(px[v], py[v], xs[i], ys[i], xs[j], ys[j], np.int64(0), w)
            if t == 0:
                sv = 0.0
            elif (t > 0) != (sv > 0.0) or sv == 0.0:
                sv = max(e, 1e-300) if t > 0 else -max(e, 1e-300)
            ss[v] = sv
        smax = max(smax, sv)
    return smax, w


@njit(**NJIT)
def _side_corner(side, start, box):
    """The corner where box side ``side`` (-1..-4) starts (``start``) or ends, counter-clockwise."""
    if side == -2:
        return (box[0], box[1]) if start else (box[2], box[1])
    if side == -3:
        return (box[2], box[1]) if start else (box[2], box[3])
    if side == -4:
        return (box[2], box[3]) if start else (box[0], box[3])
    return (box[0], box[3]) if start else (box[0], box[1])


@njit(**NJIT)
def _corner_crossings(i, xs, ys, ws, px, py, pw, m, box):
    """Put back the corner a cut's crossing rounded onto, where it is exactly in the cell.

    A bisector passing within rounding of a box corner crosses one of the corner's two
    sides an ulp or less from it; the cut's crossing then lands on the corner and merges
    with it, the later edge keeping its owner, so the vertex names the crossing of
    whichever side the ring leaves by, not of the side the bisector crosses (issue 15:
    sites (5e5, 4e6 + 0.003) and (5e5 + 0.003, 4e6), corners an ulp from their bisector:
    one cell named the top side's crossing, an ulp left of the corner, the other the
    corner; a gap of 7e-8 of the box). Where the ring meets the corner between a bisector
    and a side, the corner's exact side of the bisector (equal weights:
    :func:`.distance_exact.compare`, unequal: :func:`.sidecross.power_side`, which leaves
    the vertex where underflow hides it) decides: strictly in the cell, the bisector crosses
    the other side at the corner and the corner is a vertex of its own (inserted); else the
    vertex stays the crossing of its side. A corner exactly on the bisector is the
    lower-numbered site's. Both cells of the bisector decide by the one exact sign.
    Returns the new count.
    """
    w = np.empty((0, 0))  # noqa: TID251  (scratch of the exact test, made when needed)
    v = np.int64(0)
    while v < m:
        a = pw[v - 1 if v > 0 else m - 1]
        b = pw[v]
        x = px[v]
        y = py[v]
        if (a >= 0) == (b >= 0) or not (
            (x == box[0] or x == box[2]) and (y == box[1] or y == box[3])
        ):
            v += 1
            continue
        j = a if a >= 0 else b
        side = b if a >= 0 else a
        # entering the side at its start (the ring's corner), or leaving it at its end
        cx, cy = _side_corner(side, a >= 0, box)
        if cx != x or cy != y or m + 1 > px.shape[0]:
            v += 1
            continue
        if ws[i] == ws[j]:
            if w.shape[0] == 0:
                w = np.empty((9, 64))  # noqa: TID251  (every slot read is written first)
            s = compare(x, y, xs[i], ys[i], xs[j], ys[j], np.int64(0), w)
        else:
            s = power_side(xs[i], ys[i], ws[i], xs[j], ys[j], ws[j], x, y)
        # on the bisector exactly: the corner is the lower-numbered site's (one decision)
        if s == 2 or s > 0 or (s == 0 and i > j):
            v += 1
            continue
        for k in range(m, v, -1):
            px[k] = px[k - 1]
            py[k] = py[k - 1]
            pw[k] = pw[k - 1]
        # the side before (entering) or after (leaving) the corner, counter-clockwise
        if a >= 0:
            other = side + 1 if side <= -3 else (-1 if side == -2 else -4)
        else:
            other = -1 if side == -4 else (-2 if side == -1 else side - 1)
        if a >= 0:
            pw[v] = other  # the crossing of the side before, then the corner
            pw[v + 1] = side
        else:
            pw[v] = other  # the corner, then the crossing of the side after
            pw[v + 1] = j
        m += 1
        v += 2
    return m


@njit(**NJIT)
def _named_vertices(i, xs, ys, ws, px, py, pw, m, box):
    """Replace each vertex of ring ``p[:m]`` by the one computed from its name (in place).

    A vertex between two bisector edges is the power vertex of ``i`` and their owners; one
    between a bisector and a box side is the bisector's crossing with that side; box
    corners are exact already. Always the name, never the cut: a cut vertex is cell ``i``'s
    alone, and keeping one (where the name looked far from it by a tolerance of the box's
    size, less than an ulp far from the origin) left its neighbours' copies in other bits.
    Only a name that is not finite (a bisector parallel to the side) keeps the cut; a
    crossing that rounded past the side's end is put on the box's corner.
    """
    for v in range(m):
        a = pw[v - 1 if v > 0 else m - 1]
        b = pw[v]
        if a == b or (a < 0 and b < 0):
            continue
        if a >= 0 and b >= 0:
            nx, ny = vertex(i, a, b, xs, ys, ws, box)
        else:
            nx, ny = crossing(i, a if a >= 0 else b, xs, ys, ws, b if a >= 0 else a, box)
            # rounded past a corner: the corner (from the name's bits alone, so both cells
            # of the bisector agree)
            if abs(nx) < np.inf and abs(ny) < np.inf:
                nx = min(max(nx, box[0]), box[2])
                ny = min(max(ny, box[1]), box[3])
        if abs(nx) < np.inf and abs(ny) < np.inf:
            px[v] = nx
            py[v] = ny


@njit(**NJIT)
def _root(parent, k):
    """Representative of slot ``k`` (with path halving)."""
    while parent[k] != k:
        parent[k] = parent[parent[k]]
        k = parent[k]
    return k


@njit(**NJIT)
def _close(a, b, sx, sy, px, py, rtol):
    """Whether slots ``a`` and ``b`` hold one vertex up to rounding.

    Equal bits, or within ``rtol`` of their L1 distance from the cell's site ``(sx, sy)``
    (the local spacing) plus 16 ulps of their coordinates (the rounding of a vertex far
    from the origin): never a tolerance of the box's size.
    """
    d = abs(px[a] - px[b]) + abs(py[a] - py[b])
    if d == 0.0:
        return True
    scale = abs(px[a] - sx) + abs(py[a] - sy) + abs(px[b] - sx) + abs(py[b] - sy)
    mag = abs(px[a]) + abs(py[a]) + abs(px[b]) + abs(py[b])
    return d <= rtol * scale + POWER_CROWDED_ULPS * _U * mag


@njit(**NJIT)
def _join(parent, a, b, sx, sy, px, py, rtol):
    """Put slots ``a`` and ``b`` in one class when they are :func:`_close`."""
    if not _close(a, b, sx, sy, px, py, rtol):
        return
    ra = _root(parent, a)
    rb = _root(parent, b)
    if ra != rb:
        parent[max(ra, rb)] = min(ra, rb)


@njit(**NJIT)
def _backwards(px, py, p, q, xs, ys, i, j):
    """Whether edge ``p -> q`` of cell ``i`` runs against its bisector with ``j``.

    A counter-clockwise edge of cell ``i`` on that bisector runs along
    ``(-(y_j - y_i), x_j - x_i)``.
    """
    return (px[q] - px[p]) * (ys[j] - ys[i]) - (py[q] - py[p]) * (xs[j] - xs[i]) > 0.0


@njit(**NJIT)
def _side_backwards(px, py, p, q, side):
    """Whether edge ``p -> q`` on box side ``side`` (-1 left .. -4 top) runs clockwise."""
    if side == -2:
        return px[q] < px[p]
    if side == -3:
        return py[q] < py[p]
    if side == -4:
        return px[q] > px[p]
    return py[q] > py[p]


@njit(**NJIT)
def _insert_missing(xs, ys, px, py, po, cap, cnt, rtol):
    """Give a cell the edges its neighbour has with it and it lacks (in place).

    Cell ``i`` has an edge on its bisector with ``j``, from ``P`` (named ``i, a, j``) to
    ``Q`` (``i, j, b``), that ``j`` lacks: ``j`` went from its edge with ``b`` straight to
    its edge with ``a`` at one vertex (``j, b, a``). Which of the quadrilateral's diagonals
    ``i-j`` and ``a-b`` is the power edge is decided by the order of the two named vertices
    along the bisector of ``i`` and ``j``: ``P`` before ``Q`` by more than their rounding
    means ``i-j``, and ``j``'s cut (rounded ring vertices, bisectors nearly parallel near a
    float circle's centre) was wrong: that vertex becomes ``Q`` and ``P``, with the edge
    between them, in the same bits. Shorter or backwards edges are merged by
    :func:`_reconcile` instead.
    """
    n = xs.shape[0]
    for i in range(n):
        b0 = cap[i]
        for v in range(cnt[i]):
            j = po[b0 + v]
            if j < 0 or _edge_to(po, cap[j], cnt[j], i) >= 0:
                continue
            m = cnt[i]
            p = b0 + v
            q = b0 + (v + 1 if v + 1 < m else 0)
            if _backwards(px, py, p, q, xs, ys, i, j) or _close(p, q, xs[i], ys[i], px, py, rtol):
                continue
            a = po[b0 + v - 1] if v > 0 else po[b0 + m - 1]
            b = po[q]
            bj = cap[j]
            mj = cnt[j]
            if mj + 2 > cap[j + 1] - bj:
                continue  # no room (cannot happen: a ring has at most deg + 4 vertices)
            for u in range(mj):
                if po[bj + u] == a and po[bj + (u - 1 if u > 0 else mj - 1)] == b:
                    for k in range(mj, u, -1):
                        px[bj + k] = px[bj + k - 1]
                        py[bj + k] = py[bj + k - 1]
                        po[bj + k] = po[bj + k - 1]
                    px[bj + u] = px[q]
                    py[bj + u] = py[q]
                    po[bj + u] = i
                    px[bj + u + 1] = px[p]
                    py[bj + u + 1] = py[p]
                    cnt[j] = mj + 1
                    break


@njit(**NJIT)
def _edge_to(po, b, m, j):
    """Slot of the first edge of ring ``po[b:b + m]`` owned by ``j``, or -1."""
    for u in range(m):
        if po[b + u] == j:
            return b + u
    return -1


@njit(**NJIT)
def _same(px, py, a, b):
    """Whether slots ``a`` and ``b`` hold the same bits."""
    return px[a] == px[b] and py[a] == py[b]


@njit(**NJIT_PARALLEL)
def _agreed(xs, ys, px, py, po, cap, cnt):
    """Whether the named rings already agree, so that :func:`_reconcile` would change nothing.

    True when every bisector edge is in the neighbour's ring too, with the same end points
    in the same bits, and no edge runs backwards (along its bisector or box side) between
    two different points: then no edge is inserted and :func:`_reconcile`'s classes only
    join slots with equal bits. The usual case: each vertex is computed from its name.
    """
    n = xs.shape[0]
    bad = np.zeros(n, dtype=np.bool_)
    for i in prange(n):
        m = cnt[i]
        b = cap[i]
        for v in range(m):
            j = po[b + v]
            p = b + v
            q = b + (v + 1 if v + 1 < m else 0)
            if j < 0:
                if _side_backwards(px, py, p, q, j) and not _same(px, py, p, q):
                    bad[i] = True
                    break
                continue
            u = _edge_to(po, cap[j], cnt[j], i)
            if u < 0 or (_backwards(px, py, p, q, xs, ys, i, j) and not _same(px, py, p, q)):
                bad[i] = True
                break
            uq = cap[j] + (u - cap[j] + 1 if u - cap[j] + 1 < cnt[j] else 0)
            if not (_same(px, py, p, uq) and _same(px, py, q, u)):
                bad[i] = True
                break
    return not bad.any()


@njit(**NJIT)
def _reconcile(xs, ys, px, py, po, cap, cnt, rtol):
    """Make the named rings agree: one point for each vertex, shared bit for bit (in place).

    Each cell decided in floats which bisectors cut it. Where an edge is shorter than that
    rounding (four or more cells meeting within an ulp or so: a lattice far from the
    origin, a float circle), neighbours can disagree: one cell has a tiny edge that the
    other lacks, or keeps the edge reversed, and names the ends by other triples. The slots
    of one point are joined: the ends of each edge with the matching ends of the same edge
    in the neighbour's ring, and the two ends of an edge the neighbour lacks or that runs
    backwards (a bisector's, or a box side's where a crossing rounded past a corner), each
    join only within rounding of the local spacing (:func:`_close`). Edges that one cell
    lacks but whose named ends are ordered and apart are first given to that cell
    (:func:`_insert_missing`). Every slot then takes the coordinates of one member of its
    class, chosen by what it is (a box corner, then a crossing of a box side, then a power
    vertex) and then by its bits, so the choice does not depend on the cells' order.
    """
    n = xs.shape[0]
    _insert_missing(xs, ys, px, py, po, cap, cnt, rtol)
    parent = np.arange(cap[n])
    for i in range(n):
        m = cnt[i]
        b = cap[i]
        sx = xs[i]
        sy = ys[i]
        for v in range(m):
            j = po[b + v]
            p = b + v
            q = b + (v + 1 if v + 1 < m else 0)
            if j < 0:
                if _side_backwards(px, py, p, q, j):  # a crossing rounded past a corner
                    _join(parent, p, q, sx, sy, px, py, rtol)
                continue
            u = _edge_to(po, cap[j], cnt[j], i)
            if u < 0:
                _join(parent, p, q, sx, sy, px, py, rtol)  # the neighbour lacks the edge
                continue
            if _backwards(px, py, p, q, xs, ys, i, j):  # two ends swapped by rounding
                _join(parent, p, q, sx, sy, px, py, rtol)
            if i < j:
                uq = cap[j] + (u - cap[j] + 1 if u - cap[j] + 1 < cnt[j] else 0)
                _join(parent, p, uq, sx, sy, px, py, rtol)
                _join(parent, q, u, sx, sy, px, py, rtol)
    best = np.full(cap[n], -1, dtype=np.int64)
    rank = np.zeros(cap[n], dtype=np.int64)
    for i in range(n):
        m = cnt[i]
        b = cap[i]
        for v in range(m):
            k = b + v
            r = _root(parent, k)
            # 2: box corner, 1: crossing of a side, 0: power vertex
            prev = po[b + v - 1] if v > 0 else po[b + m - 1]
            kind = np.int64(prev < 0) + np.int64(po[k] < 0)
            c = best[r]
            if (
                c < 0
                or kind > rank[r]
                or (kind == rank[r] and (px[k] < px[c] or (px[k] == px[c] and py[k] < py[c])))
            ):
                best[r] = k
                rank[r] = kind
    for i in range(n):
        b = cap[i]
        for v in range(cnt[i]):
            c = best[_root(parent, b + v)]
            px[b + v] = px[c]
            py[b + v] = py[c]


@njit(**NJIT)
def _compact(i, xs, ys, px, py, po, b, m):
    """Ring ``b:b + m`` of cell ``i`` without repeated points; its new count (0: no cell).

    A vertex equal to the previous one is dropped and the edge that leaves it is the kept
    vertex's; box sides become -1.
    """
    k = 0
    for v in range(m):
        if k > 0 and px[b + v] == px[b + k - 1] and py[b + v] == py[b + k - 1]:
            po[b + k - 1] = po[b + v]
            continue
        px[b + k] = px[b + v]
        py[b + k] = py[b + v]
        po[b + k] = po[b + v]
        k += 1
    while k > 1 and px[b + k - 1] == px[b] and py[b + k - 1] == py[b]:
        k -= 1
    if k < 3:
        return 0
    ox = xs[i]
    oy = ys[i]
    area2 = 0.0
    for v in range(k):
        vn = v + 1 if v + 1 < k else 0
        area2 += (px[b + v] - ox) * (py[b + vn] - oy) - (px[b + vn] - ox) * (py[b + v] - oy)
        if po[b + v] < 0:
            po[b + v] = -1
    if not area2 > 0.0 and not tiny_ring_area(px, py, b, k, ox, oy) > 0.0:
        return 0
    return k


@njit(**NJIT)
def _careful_values(i, j, xs, ys, ws, px, py, pw, m, ss):
    """Half the power difference of sites ``i`` and ``j`` at each vertex of ``p[:m]``.

    At a vertex on the bisector of ``i`` and ``o`` (one of its edges' owners) the power of
    ``o`` equals that of ``i``: the value is taken from the pair ``o, j`` when ``o`` is
    nearer ``j`` than ``i`` is. Its rounding then scales with ``|p_j - p_o|``: sites 1e-9
    apart 1e6 from ``i`` have bisectors with ``i`` that differ by 1e-15 in angle, and the
    plain value ``(p_j - p_i).(x - p_i)`` cannot order them. Returns the largest value.
    """
    smax = -np.inf
    for v in range(m):
        o = i
        dx = xs[j] - xs[i]
        dy = ys[j] - ys[i]
        best = dx * dx + dy * dy
        for t in range(2):
            c = pw[v - 1 if v > 0 else m - 1] if t == 0 else pw[v]
            if c < 0 or c == j:
                continue
            ex = xs[j] - xs[c]
            ey = ys[j] - ys[c]
            if ex * ex + ey * ey < best:
                o = c
                best = ex * ex + ey * ey
        dx = xs[j] - xs[o]
        dy = ys[j] - ys[o]
        h = 0.5 * (dx * dx + dy * dy + (ws[o] - ws[j]))
        sv = dx * (px[v] - xs[o]) + dy * (py[v] - ys[o]) - h
        ss[v] = sv
        smax = max(smax, sv)
    return smax


@njit(**NJIT)
def _careful_cell(i, xs, ys, ws, nbrs, nn, box, px, py, pw, qx, qy, qw, ss):
    """:func:`box_cell` naming the two new vertices after every cut.

    A cut's crossings are interpolated along the ring's edges, whose ends may lie as far
    as the box: their rounding (ulps of the box's coordinates) is then larger than a cell
    of a cluster 1e-9 wide at 1e6, and the next cuts decide which bisectors bound the cell
    on that noise (a named vertex of two bisectors that are not adjacent lies off the cell:
    a self-intersecting ring). A named vertex is rounded at its own coordinates, so the
    later cuts see the cell to its own resolution. Used where the lift could not resolve
    the sites (the checked path); elsewhere the cells are far wider than the rounding.
    """
    m = _box_ring(box, px, py, pw)
    zero = np.int64(0)
    for k in range(nn):
        j = nbrs[k]
        if _careful_values(i, j, xs, ys, ws, px, py, pw, m, ss) <= 0.0:
            continue
        m = cut_ring(px, py, pw, zero, m, ss, qx, qy, qw, zero, j)
        if m < 3:
            return 0
        for v in range(m):
            px[v] = qx[v]
            py[v] = qy[v]
            pw[v] = qw[v]
        _name_new(i, j, xs, ys, ws, px, py, pw, m, box)
    return m


@njit(**{**NJIT, "inline": "always"})
def _outside(ax, ay, bx, by, box):
    """Whether points ``a`` and ``b`` both lie outside ``box`` (window onto far sites)."""
    a = ax < box[0] or ax > box[2] or ay < box[1] or ay > box[3]
    return a and (bx < box[0] or bx > box[2] or by < box[1] or by > box[3])


@njit(**NJIT)
def _name_new(i, j, xs, ys, ws, px, py, pw, m, box):
    """Replace the vertices of ring ``p[:m]`` at an edge owned by ``j`` by their names."""
    for v in range(m):
        a = pw[v - 1 if v > 0 else m - 1]
        b = pw[v]
        if a != j and b != j:
            continue
        if a >= 0 and b >= 0:
            nx, ny = vertex(i, a, b, xs, ys, ws, box)
        elif a >= 0 or b >= 0:
            nx, ny = crossing(i, a if a >= 0 else b, xs, ys, ws, b if a >= 0 else a, box)
            if abs(nx) < np.inf and abs(ny) < np.inf:
                nx = min(max(nx, box[0]), box[2])
                ny = min(max(ny, box[1]), box[3])
        else:
            continue
        if abs(nx) < np.inf and abs(ny) < np.inf:
            px[v] = nx
            py[v] = ny


@njit(**NJIT)
def _cell(i, xs, ys, ws, indptr, indices, box, px, py, po, qx, qy, qo, ss, careful=False):
    """Power cell of site ``i`` cut from ``box`` with named vertices; its count (in ``p``).

    Edge owners keep the box sides' codes (-1..-4) for :func:`_reconcile`. ``careful``:
    :func:`_careful_cell`'s cut.
    """
    nb = indices[indptr[i] : indptr[i + 1]]
    if careful:
        m = _careful_cell(i, xs, ys, ws, nb, nb.shape[0], box, px, py, po, qx, qy, qo, ss)
    else:
        m = box_cell(i, xs, ys, ws, nb, nb.shape[0], box, px, py, po, qx, qy, qo, ss)
    if m == 0:
        return 0
    _named_vertices(i, xs, ys, ws, px, py, po, m, box)
    return m


@njit(**NJIT)  # no prange: its two parallel kernels run in parallel from a plain caller
def power_cells(xs, ys, ws, indptr, indices, box, active):
    """Closed rings of the power cells of all sites (see the module docstring).

    Parameters
    ----------
    xs, ys, ws : (n,) float64
        Sites and weights.
    indptr, indices : CSR int64
        Candidate neighbours of each site (a superset of its power neighbours).
    box : (4,) float64
        ``(xmin, ymin, xmax, ymax)``.
    active : (n,) bool
        Sites whose cell is computed; the others get an empty cell.

    Returns
    -------
    coords, lengths, owner
        As in the module docstring.
    """
    none = np.zeros(0, dtype=np.bool_)
    zf = np.zeros(0)
    zi = np.zeros(0, dtype=np.int64)
    slab_x, slab_y, slab_o, cap, cnt = cut_rings(
        xs, ys, ws, indptr, indices, box, active, none, zf, zf, zi, zi, zi
    )
    return finish_rings(xs, ys, slab_x, slab_y, slab_o, cap, cnt)


@njit(**NJIT_PARALLEL)
def cut_rings(xs, ys, ws, indptr, indices, box, todo, careful, ox, oy, oo, ocap, ocnt):
    """Named rings (before :func:`finish_rings`) of the cells in ``todo``; the others copied.

    Parameters
    ----------
    xs, ys, ws, indptr, indices, box
        As for :func:`power_cells`.
    todo : (n,) bool
        Cells to cut.
    careful : (n,) bool or (0,) bool
        Cells cut by :func:`_careful_cell` (none when empty).
    ox, oy, oo, ocap, ocnt
        Rings of an earlier call (``ocnt`` empty: none); cells not in ``todo`` keep theirs.

    Returns
    -------
    slab_x, slab_y, slab_o, cap, cnt
        Cell ``i``'s ring is ``slab[cap[i]:cap[i] + cnt[i]]`` (no closing vertex), with room
        for :func:`finish_rings`' insertions.
    """
    n = xs.shape[0]
    cap = np.zeros(n + 1, dtype=np.int64)
    for i in range(n):
        cap[i + 1] = cap[i] + 2 * (indptr[i + 1] - indptr[i]) + 9
    slab_x = np.zeros(cap[n])
    slab_y = np.zeros(cap[n])
    slab_o = np.zeros(cap[n], dtype=np.int64)
    cnt = np.zeros(n, dtype=np.int64)
    old = ocnt.shape[0] > 0
    some = careful.shape[0] > 0
    for i in prange(n):
        b = cap[i]
        if not todo[i]:
            if old:
                c = ocap[i]
                for k in range(ocnt[i]):
                    slab_x[b + k] = ox[c + k]
                    slab_y[b + k] = oy[c + k]
                    slab_o[b + k] = oo[c + k]
                cnt[i] = ocnt[i]
            continue
        size = cap[i + 1] - cap[i]
        px = np.zeros(size)
        py = np.zeros(size)
        po = np.zeros(size, dtype=np.int64)
        qx = np.zeros(size)
        qy = np.zeros(size)
        qo = np.zeros(size, dtype=np.int64)
        ss = np.zeros(size)
        # prange's index is unsigned: as np.int64 the callees are compiled once, not twice
        m = _cell(
            np.int64(i),
            xs,
            ys,
            ws,
            indptr,
            indices,
            box,
            px,
            py,
            po,
            qx,
            qy,
            qo,
            ss,
            some and careful[i],
        )
        for k in range(m):
            slab_x[b + k] = px[k]
            slab_y[b + k] = py[k]
            slab_o[b + k] = po[k]
        cnt[i] = m
    return slab_x, slab_y, slab_o, cap, cnt


@njit(**NJIT_PARALLEL)
def finish_rings(xs, ys, slab_x, slab_y, slab_o, cap, cnt):
    """:func:`cut_rings`' rings reconciled, compacted and closed: :func:`power_cells`' result."""
    n = xs.shape[0]
    if not _agreed(xs, ys, slab_x, slab_y, slab_o, cap, cnt):
        _reconcile(xs, ys, slab_x, slab_y, slab_o, cap, cnt, POWER_CROWDED_RTOL)
    counts = np.zeros(n + 1, dtype=np.int64)
    for i in prange(n):
        m = _compact(np.int64(i), xs, ys, slab_x, slab_y, slab_o, cap[i], cnt[i])
        if m > 0:
            b = cap[i]
            slab_x[b + m] = slab_x[b]
            slab_y[b + m] = slab_y[b]
            slab_o[b + m] = -2
            counts[i + 1] = m + 1
    for i in range(n):
        counts[i + 1] += counts[i]
    coords = np.zeros((counts[n], 2))
    owner = np.zeros(counts[n], dtype=np.int64)
    for i in prange(n):
        b = cap[i]
        o = counts[i]
        for k in range(counts[i + 1] - o):
            coords[o + k, 0] = slab_x[b + k]
            coords[o + k, 1] = slab_y[b + k]
            owner[o + k] = slab_o[b + k]
    return coords, counts, owner
