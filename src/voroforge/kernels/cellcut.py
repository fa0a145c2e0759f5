"""Cut cells: a Delaunay-dual cell cut out of the box by its neighbours' bisectors.

The cut half of the Delaunay-dual cell builder (:mod:`kernels.cells` walks the halfedges,
keeps the rings of cells inside the box and writes every ring). A cell that reaches past the
box, or whose site is on the hull, is the box cut by the bisectors of its Delaunay
neighbours (:func:`cut_cell`; the cut itself is the power cell's, ``kernels/power.box_cell``,
with zero weights). Its vertices are then named so that every cell sharing one computes it
bit for bit:

- :func:`_relabel_edges` gives each bisector edge the neighbour nearest to its ends
  (:func:`_nearest_label`), for neighbours whose bisectors floats cannot separate;
- :func:`_canonical_vertices` replaces a vertex between two bisectors by the circumcentre of
  its Delaunay triangle (the chain of them when the clip lost short edges,
  :func:`_chain`), a vertex on a box side by the canonical crossing
  (``kernels/vertex.box_crossing``) and a vertex between two sides by the exact corner;
  a circumcentre past one side by the crossings of its two edges with that side
  (:func:`_past_side_crossings`), and the edges a cut lost between a bisector and a side
  are put back from the triangles whose centres lie inside the box (:func:`_lost_at_side`).

Which vertices are put on a box side is :mod:`kernels.cellsides`' (re-exported here).

A cut cell with many neighbours is built in linear time by :func:`spliced_cell`: only the
neighbours whose edges are not safely inside the box (:func:`_interior`) cut it, and the
runs of interior edges are put back in rotation order (:func:`_splice`).

Rings are held in scratch arrays ``p`` (``px, py, pw``: coordinates and the owner of the
edge that starts at each vertex) and ``q`` (same, the second buffer); ``nbrs[:nn]`` are the
site's Delaunay neighbours in rotation order and ``tris[k]`` the triangle between
neighbours ``k`` and ``k + 1`` (-1 past a hull end).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import NJIT, RELABEL_RTOL, RELABEL_ULPS
from .cellsides import (  # noqa: F401  (re-exported: cells, folds, halfplane_settle)
    class_err,
    end_past,
    near_sides,
    on_side,
    on_sides,
    onto_sides,
    past_side,
    side_reach,
    side_reaches,
    vertex_at,
)
from .clip import dedupe_ring
from .cornercut import corner_cut, near_corner
from .power import box_cell
from .sidegap import restore_side_vertices
from .vertex import box_crossing

_U = 2.0**-53


@njit(**NJIT)
def _index_of(nbrs, nn, a, hint):
    """Position of ``a`` in ``nbrs[:nn]``, searched outward from ``hint`` (-1 if absent).

    Consecutive vertices of a ring have neighbours next to each other in rotation order, so
    the search usually ends at once; a cell with many neighbours stays linear.
    """
    if nn == 0:
        return -1
    hint = min(max(hint, 0), nn - 1)
    for d in range(nn // 2 + 1):
        k = hint + d
        if k >= nn:
            k -= nn
        if nbrs[k] == a:
            return k
        k = hint - d
        if k < 0:
            k += nn
        if nbrs[k] == a:
            return k
    return -1


@njit(**NJIT)
def _chain(nbrs, tris, nn, a, b, hint):
    """Where neighbour ``a`` is, and how many Delaunay triangles lead from it to ``b``.

    Returns ``(ka, steps)`` in rotation order; ``steps`` is -1 when either is missing, ``b``
    does not follow ``a``, or a triangle between them does not exist (past a hull end).
    ``hint`` is where to start looking for ``a``.
    """
    ka = _index_of(nbrs, nn, a, hint)
    kb = _index_of(nbrs, nn, b, ka + 1)
    if ka < 0 or kb < 0:
        return ka, -1
    steps = (kb - ka) % nn if tris[nn - 1] >= 0 else kb - ka
    for s in range(max(steps, 0)):
        if tris[(ka + s) % nn] < 0:
            return ka, -1
    return ka, steps if steps >= 1 else -1


@njit(**NJIT)
def _chain_in_box(nbrs, tris, nn, ka, steps, cx, cy, box):
    """Whether the circumcentres of the ``steps`` triangles after ``ka`` lie in ``box``."""
    for s in range(steps):
        t = tris[(ka + s) % nn]
        if not (box[0] <= cx[t] <= box[2] and box[1] <= cy[t] <= box[3]):
            return False
    return True


@njit(**NJIT)
def _emit_chain(nbrs, tris, nn, ka, steps, cx, cy, reach, box, qx, qy, qw, out):
    """Write the circumcentres of the ``steps`` triangles after neighbour ``ka`` to ``q``.

    Each is followed by the edge of the next neighbour; returns the new vertex count. A
    centre within reach of a box side is put on it (:func:`on_sides`).
    """
    for s in range(steps):
        k = (ka + s) % nn
        t = tris[k]
        qx[out], qy[out] = vertex_at(t, cx, cy, reach, box)
        qw[out] = nbrs[(k + 1) % nn]
        out += 1
    return out


@njit(**NJIT)
def _crossing_at_vertex(kj, nbrs, tris, nn, cx, cy, reach, side, box, x, y):
    """Crossing ``(x, y)`` of ``side`` by neighbour ``kj``'s edge, or its end on that side.

    An end of the edge (the centre of the triangle before or after ``kj`` in rotation
    order) within reach of the side is put on it (:func:`on_sides`), and the edge's
    crossing is that point: every cell at the vertex computes it from the vertex's name,
    whichever way its own cut rounded. With both ends there, the nearer along the side.
    """
    best = np.inf
    bx = x
    by = y
    for s in range(2):
        k = kj - 1 + s
        if k < 0:
            k += nn
        t = tris[k]
        if t < 0:
            continue
        vx, vy, hit = on_sides(t, cx, cy, reach, box)
        if not (hit and on_side(vx, vy, side, box)):
            continue
        d = abs(vx - x) + abs(vy - y)
        if d < best:
            best = d
            bx = vx
            by = vy
    return bx, by


@njit(**NJIT)
def _past_side_crossings(i, a, b, t, xs, ys, cx, cy, reach, box):
    """The side crossings that stand for triangle ``t``'s centre where it lies past one side.

    Returns ``(ok, x1, y1, x2, y2, side)``. The centre of ``(i, a, b)`` strictly past one
    box side (not put on it: :func:`on_sides`) is no vertex of cell ``i``: its edges with
    ``a`` then ``b`` cross that side, and a side edge joins the crossings. When the cut's
    own crossings rounded to one point (a float circle's hull cells ~10 ulps apart, the
    exact side edge 0.07 ulp long), the cut met the bisectors without the side and the
    centre became the ring's vertex, off the box and beside the crossings its neighbours
    use (issue 15). The canonical crossings (:func:`.vertex.box_crossing`, the neighbours'
    bits) are used when both lie on the side in the ring's order; else ``ok`` is False.
    A centre past two sides (a corner; a lone sliver's centre of a float circle far out,
    issue 15) has ``a``'s crossing on the side before the corner or after it and ``b``'s
    after it or before; ``side2`` is the side of ``b``'s crossing (the ring turns at the
    corner between when it differs from ``side``).
    """
    x, y = vertex_at(t, cx, cy, reach, box)
    sv = -1 if x < box[0] else (-3 if x > box[2] else 0)  # past a vertical side
    sh = -2 if y < box[1] else (-4 if y > box[3] else 0)  # past a horizontal side
    if sv == 0 and sh == 0:
        return False, x, y, x, y, 0, 0
    # the sides in counter-clockwise order around the corner (one side: both that one)
    first = sv if sh == 0 else (sh if sv == 0 else (sv if (sv == -1) == (sh == -2) else sh))
    last = sv + sh - first if sv != 0 and sh != 0 else first
    side = first
    x1, y1 = box_crossing(i, a, xs, ys, side, box)
    if not (box[0] <= x1 <= box[2] and box[1] <= y1 <= box[3]) and last != first:
        side = last
        x1, y1 = box_crossing(i, a, xs, ys, side, box)
    side2 = last
    x2, y2 = box_crossing(i, b, xs, ys, side2, box)
    if not (box[0] <= x2 <= box[2] and box[1] <= y2 <= box[3]) and side == first:
        side2 = first
        x2, y2 = box_crossing(i, b, xs, ys, side2, box)
    ok = (
        box[0] <= x1 <= box[2]
        and box[1] <= y1 <= box[3]
        and box[0] <= x2 <= box[2]
        and box[1] <= y2 <= box[3]
        and (side2 != side or _along_side(x1, y1, side) <= _along_side(x2, y2, side))
    )
    return ok, x1, y1, x2, y2, side, side2


@njit(**NJIT)
def _inside_box(t, cx, cy, reach, box):
    """Whether triangle ``t``'s centre lies inside ``box`` by more than its side reach.

    A centre never put on a side (a negative reach, :func:`side_reaches`) is every cell's
    vertex where it lies, so it is inside when strictly inside: the one rule the uncut
    rings apply to it (``cells._at_side_or_out``), decided by the centre alone. A float
    circle's vertex 2.75 ulps inside a side, its sites an ulp apart, was dropped by the one
    cell whose cut lost its edge to the side; one 2 ulps inside, under its rounding bound
    (300 at phase 0.75, a box side there, issue 15), was written by the uncut cell of its
    middle site and by neither cut cell beside it (a hole of 620 units^2, Euler failed).
    """
    if t < 0:
        return False
    e = reach[t]
    if e < 0.0:
        return box[0] < cx[t] < box[2] and box[1] < cy[t] < box[3]
    return box[0] + e < cx[t] < box[2] - e and box[1] + e < cy[t] < box[3] - e


@njit(**NJIT)
def _lost_at_side(kj, forward, tris, nn, cx, cy, reach, box):
    """The run of Delaunay triangles beside neighbour ``kj``'s edge with centres in the box.

    Returns ``(k0, steps)``: the triangles ``tris[k0 : k0 + steps]`` (rotation order). An
    edge of the cell that meets a box side (``forward``: leaving the box; else entering it)
    ends at the centre of the triangle after it (before it) when that centre lies inside the
    box: exactly, a segment cannot leave a convex box and end inside it. Floats meet two
    nearly parallel bisectors past the side instead (sites a few ulps apart on a float circle
    far out, issue 15: an edge 13 ulps long lost), and the cell loses the edges between them.
    Centres within their reach of a side (:func:`side_reaches`) end the run.
    """
    steps = np.int64(0)
    k = kj
    while steps < nn - 1:
        if forward:
            t = tris[(kj + steps) % nn]
        else:
            k = kj - steps - 1
            if k < 0:
                k += nn
            t = tris[k]
        if not _inside_box(t, cx, cy, reach, box):
            break
        steps += 1
    if forward:
        return kj, steps
    k = kj - steps
    if k < 0:
        k += nn
    return k, steps


@njit(**NJIT)
def _side_vertex(
    i, j, kj, nbrs, tris, nn, xs, ys, cx, cy, reach, side, box, x, y, owner, qx, qy, qw, out
):
    """Write the crossing of ``side`` by the edge of neighbour ``j`` (at ``kj``) to ``q``.

    The canonical crossing (:func:`.vertex.box_crossing`), or the cut's ``(x, y)`` where
    it is not on the side inside the box; an end of the edge on the side is used instead
    (:func:`_crossing_at_vertex`). Its edge is owned by ``owner``; returns the new count.
    """
    bx, by = box_crossing(i, j, xs, ys, side, box)
    if bx == bx and box[0] <= bx <= box[2] and box[1] <= by <= box[3]:
        x = bx
        y = by
    x, y = _crossing_at_vertex(kj, nbrs, tris, nn, cx, cy, reach, side, box, x, y)
    qx[out] = x
    qy[out] = y
    qw[out] = owner
    return out + 1


@njit(**NJIT)
def _drop_outside_edges(i, xs, ys, pw, m, nbrs, tris, nn, cx, cy, reach, box):
    """Give an edge that meets a box side the owner whose edge does; in place on ``pw``.

    An edge entering the box from a side (or leaving it) whose two ends, the centres of
    the triangles before and after its neighbour, both lie past that side by more than
    their reach lies outside the box, exactly (a segment between two points past a side).
    Floats kept it: nearly parallel bisectors of sites a few ulps apart on a float circle
    far out met inside the box (issue 15: site 47 of 1,000 at r = 1e-7, (5e5, 4e6),
    phase 0.05 kept 51's neighbour 52 and lost 51's 13-ulp edge). An end past a hull end is
    the ray's, at infinity (:func:`.cellsides.end_past`; phase 0.95: hull site 352's ray with 355, 5
    ulps left of the left side and running left, kept its 1-ulp neighbour 354 off the
    side). A centre never put on a side counts by its rounding bound. The owner passes to the
    next neighbour in rotation order (entering; the previous one leaving) until the edge
    does reach the box; :func:`_canonical_vertices` then names its side crossing and the
    chain after it.
    """
    hint = np.int64(0)
    for v in range(m):
        j = pw[v]
        if j < 0:
            continue
        before = pw[v - 1] if v > 0 else pw[m - 1]
        after = pw[v + 1] if v + 1 < m else pw[0]
        if before >= 0 and after >= 0:
            continue
        kj = _index_of(nbrs, nn, j, hint)
        if kj < 0:
            continue
        hint = kj
        for _ in range(nn):
            k0 = kj - 1 if kj > 0 else nn - 1
            k1 = kj + 1 if kj + 1 < nn else 0
            t0 = tris[k0]
            t1 = tris[kj]
            if before < 0 and past_side(t1, before, cx, cy, reach, box):
                if end_past(i, nbrs[kj], nbrs[k1], t0, before, xs, ys, cx, cy, reach, box):
                    kj = k1
                    continue
            if after < 0 and past_side(t0, after, cx, cy, reach, box):
                if end_past(i, nbrs[kj], nbrs[k0], t1, after, xs, ys, cx, cy, reach, box):
                    kj = k0
                    continue
            break
        pw[v] = nbrs[kj]


@njit(**NJIT)
def _canonical_vertices(i, xs, ys, px, py, pw, m, nbrs, tris, nn, cx, cy, reach, box, qx, qy, qw):
    """Replace computed vertices by values every cell sharing them computes identically.

    A vertex between the bisectors with neighbours ``a`` then ``b`` is the circumcentre of
    the Delaunay triangle ``(i, a, b)``. When ``a`` and ``b`` are not consecutive neighbours
    the clip lost edges too short for floats to separate (neighbours whose bisectors coincide
    in floating point); the chain of circumcentres between them is put back from the
    triangulation. A vertex on a box side is the canonical crossing of the bisector with that
    side; two box sides meet at an exact corner. Owners of box sides (-1..-4) become -1.
    Sides the cut lost between two parallel bisectors (sites on one line) are put back
    first (:func:`.sidegap.restore_side_vertices`).
    """
    # counters start as np.int64: a literal 0 would make numba compile each callee they
    # reach once more, for the literal
    m = restore_side_vertices(i, px, py, pw, m, nbrs, tris, nn, xs, ys, box)
    _drop_outside_edges(i, xs, ys, pw, m, nbrs, tris, nn, cx, cy, reach, box)
    out = np.int64(0)
    hint = np.int64(0)
    for v in range(m):
        a = pw[v - 1] if v > 0 else pw[m - 1]
        b = pw[v]
        x = px[v]
        y = py[v]
        if a >= 0 and a == b:
            # two edges on one bisector: not a Voronoi vertex. A cut vertex of two nearly
            # parallel bisectors (sites far from this one, close to each other) is off the
            # true vertex along them by rounding over their angle, far more than its distance
            # to either line: _relabel_edges puts the true vertices in from the chain and
            # leaves the cut one between two edges of one owner (a T-junction on the
            # neighbour's edge, 1e-14 off it, issue 15)
            continue
        if a >= 0 and b >= 0:
            ka, steps = _chain(nbrs, tris, nn, a, b, hint)
            hint = max(ka, 0)
            # the chain's vertices are in order: swapped ones were merged (centers._unfold)
            ok = steps >= 1 and out + steps + (m - v) <= qx.shape[0]
            if ok and steps > 1:
                # lost edges lie where the cut's vertex is, inside the box: a chain that
                # leaves it went round the wrong way (sites near a box side whose images
                # wrap, issue 15); the cut's own vertex is kept instead
                ok = _chain_in_box(nbrs, tris, nn, ka, steps, cx, cy, box)
            if ok and steps == 1 and out + 2 + (m - v) <= qx.shape[0]:
                got = _past_side_crossings(i, a, b, tris[ka], xs, ys, cx, cy, reach, box)
                if got[0] and (got[5] == got[6] or out + 3 + (m - v) <= qx.shape[0]):
                    _, x1, y1, x2, y2, side, side2 = got
                    qx[out], qy[out], qw[out] = x1, y1, side
                    out += 1
                    if side2 != side:  # the corner between the two sides
                        qx[out] = box[0] if -1 in (side, side2) else box[2]
                        qy[out] = box[1] if -2 in (side, side2) else box[3]
                        qw[out] = side2
                        out += 1
                    qx[out], qy[out], qw[out] = x2, y2, b
                    out += 1
                    continue
            if ok:
                out = _emit_chain(nbrs, tris, nn, ka, steps, cx, cy, reach, box, qx, qy, qw, out)
                continue
        elif a >= 0 or b >= 0:
            j = a if a >= 0 else b
            side = b if a >= 0 else a
            kj = _index_of(nbrs, nn, j, hint)
            if kj >= 0:
                # edges the cut lost between the bisector and the side: the Delaunay
                # triangles beyond ``j`` whose centres lie inside the box are vertices of
                # the cell (nearly parallel bisectors met past the side in floats)
                k0, steps = _lost_at_side(kj, a >= 0, tris, nn, cx, cy, reach, box)
                if steps > 0 and out + steps + 1 + (m - v) <= qx.shape[0]:
                    j = nbrs[(k0 + steps) % nn] if a >= 0 else nbrs[k0]
                    # the chain, then the side vertex (leaving the box) or the other way round
                    if a >= 0:
                        out = _emit_chain(
                            nbrs, tris, nn, k0, steps, cx, cy, reach, box, qx, qy, qw, out
                        )
                        hint = (k0 + steps) % nn
                        at, label = hint, b
                    else:
                        at, label = k0, j
                    out = _side_vertex(
                        i,
                        j,
                        at,
                        nbrs,
                        tris,
                        nn,
                        xs,
                        ys,
                        cx,
                        cy,
                        reach,
                        side,
                        box,
                        x,
                        y,
                        label,
                        qx,
                        qy,
                        qw,
                        out,
                    )
                    if a < 0:
                        out = _emit_chain(
                            nbrs, tris, nn, k0, steps, cx, cy, reach, box, qx, qy, qw, out
                        )
                    continue
            bx, by = box_crossing(i, j, xs, ys, side, box)
            if bx == bx and box[0] <= bx <= box[2] and box[1] <= by <= box[3]:
                x = bx
                y = by
            kj = _index_of(nbrs, nn, j, hint)
            if kj >= 0:
                hint = kj
                x, y = _crossing_at_vertex(kj, nbrs, tris, nn, cx, cy, reach, side, box, x, y)
        else:
            vert = a if (a == -1 or a == -3) else b
            horz = b if vert == a else a
            if (vert == -1 or vert == -3) and (horz == -2 or horz == -4):
                x = box[0] if vert == -1 else box[2]
                y = box[1] if horz == -2 else box[3]
        qx[out] = x
        qy[out] = y
        qw[out] = b
        out += 1
    out = _drop_side_slivers(i, xs, ys, qx, qy, qw, out, box)
    for v in range(out):
        px[v] = qx[v]
        py[v] = qy[v]
        pw[v] = qw[v] if qw[v] >= 0 else -1
    return dedupe_ring(px, py, pw, out)


@njit(**NJIT)
def _beyond_side(x, y, side, box):
    """-1 inside box side ``side`` (-1..-4), 0 on it, 1 strictly past it."""
    if side == -1:
        d = box[0] - x
    elif side == -2:
        d = box[1] - y
    elif side == -3:
        d = x - box[2]
    else:
        d = y - box[3]
    return 1 if d > 0.0 else (0 if d == 0.0 else -1)


@njit(**NJIT)
def _along_side(x, y, side):
    """Position along box side ``side`` in the direction a counter-clockwise ring runs."""
    if side == -1:
        return -y
    if side == -2:
        return x
    if side == -3:
        return y
    return -x


@njit(**NJIT)
def _remove(qx, qy, qw, m, k):
    """Remove vertex ``k`` of ring ``q[:m]``; returns the new count."""
    for v in range(k, m - 1):
        qx[v] = qx[v + 1]
        qy[v] = qy[v + 1]
        qw[v] = qw[v + 1]
    return m - 1


@njit(**NJIT)
def _to_crossing(i, j, xs, ys, side, box, qx, qy, qw, m, at, owner, drop):
    """Vertex ``at`` becomes the canonical crossing of ``side`` by the bisector of ``i, j``.

    Its edge is owned by ``owner`` and vertex ``drop`` goes. Returns the new count, or 0
    (nothing changed) when the bisector does not cross the side inside the box.
    """
    cx, cy = box_crossing(i, j, xs, ys, side, box)
    if not (cx == cx and box[0] <= cx <= box[2] and box[1] <= cy <= box[3]):
        return 0
    qx[at] = cx
    qy[at] = cy
    qw[at] = owner
    return _remove(qx, qy, qw, m, drop)


@njit(**NJIT)
def _drop_side_slivers(i, xs, ys, qx, qy, qw, m, box):
    """Drop a bisector edge between a box side and a named vertex on or past that side.

    The cut crosses the box sides with the computed bisectors; the vertex between two
    bisectors is then named by its circumcentre. When that centre lies past a side (a
    Voronoi vertex on the box's side, rounded out), the edge from it to the side has no
    inside: the ring went out to it and back. That edge is dropped and its neighbour meets
    the side at its own canonical crossing, as the cell beyond computes it. When the centre
    lies on the side but the crossing is past it along the side (a spike of an ulp), the
    crossing is dropped and the side runs to the centre. ``q[:m]`` still has the sides'
    owners -1..-4; returns the new count.
    """
    k = np.int64(0)
    while k < m and m > 3:
        a = qw[k - 1] if k > 0 else qw[m - 1]
        b = qw[k]
        if a < 0 or b < 0:
            k += 1
            continue
        p = k - 1 if k > 0 else m - 1
        s = qw[p - 1] if p > 0 else qw[m - 1]
        nx = k + 1 if k + 1 < m else 0
        t = qw[nx]
        x = qx[k]
        y = qy[k]
        if s < 0:
            past = _beyond_side(x, y, s, box)
            if past > 0:
                got = _to_crossing(i, b, xs, ys, s, box, qx, qy, qw, m, p, b, k)
                if got > 0:
                    m = got
                    k = np.int64(0)
                    continue
            elif past == 0 and _along_side(x, y, s) < _along_side(qx[p], qy[p], s):
                m = _remove(qx, qy, qw, m, p)
                k = np.int64(0)
                continue
        if t < 0:
            past = _beyond_side(x, y, t, box)
            if past > 0:
                got = _to_crossing(i, a, xs, ys, t, box, qx, qy, qw, m, k, t, nx)
                if got > 0:
                    m = got
                    k = np.int64(0)
                    continue
            elif past == 0 and _along_side(qx[nx], qy[nx], t) < _along_side(x, y, t):
                qw[k] = t
                m = _remove(qx, qy, qw, m, nx)
                k = np.int64(0)
                continue
        k += 1
    return m


@njit(**NJIT)
def _nearest_label(xs, ys, x, y, b, nbrs, nn, box):
    """The neighbour nearest to ``(x, y)``, starting from ``b``.

    It moves only on a decisive comparison: the point must be clearly (``RELABEL_RTOL`` of
    the coordinates' size) off the bisector of the two candidates. A coordinate on a side
    of the ``box`` is exact (the cut's crossing keeps the side's value), so only the other
    coordinate's error counts: the cell at the end of a strip an ulp wide along a side
    meets the strip there, and a tolerance in both coordinates gave the strip's edge to
    the neighbour beyond it.
    """
    ex = 0.0 if (x == box[0] or x == box[2]) else 1.0
    ey = 0.0 if (y == box[1] or y == box[3]) else 1.0
    for k in range(nn):
        j = nbrs[k]
        if j == b:
            continue
        # |P - s_j|^2 - |P - s_b|^2 = (s_j - s_b) . (s_j + s_b - 2P)
        dx = xs[j] - xs[b]
        dy = ys[j] - ys[b]
        # in the frame of P: the local spacing, not the coordinates' magnitude, sets the
        # tolerance; P's own representation error adds a few ulps of its magnitude
        jx = xs[j] - x
        jy = ys[j] - y
        bx = xs[b] - x
        by = ys[b] - y
        d = dx * (jx + bx) + dy * (jy + by)
        size = abs(jx) + abs(bx) + abs(jy) + abs(by)
        tol = (RELABEL_RTOL * size + RELABEL_ULPS * _U * (abs(x) + abs(y))) * (
            ex * abs(dx) + ey * abs(dy)
        )
        if d < -tol:
            b = j
    return b


@njit(**NJIT)
def _relabel_edges(xs, ys, px, py, pw, m, nbrs, tris, nn, cx, cy, reach, qx, qy, qw, box):
    """Fix the owners of bisector edges that floats could not separate; result in ``p``.

    Neighbours closer to each other than the float resolution of their bisectors (sites
    1e-17 of the extent apart, say) cut the cell along the same float line, and the clip
    labels the whole edge with whichever came last. Each end of the edge is given its
    nearest neighbour; when the ends disagree, the Delaunay chain of circumcentres between
    the two neighbours is inserted, so the edge is split where the true vertices are.
    """
    out = np.int64(0)
    for v in range(m):
        b = pw[v]
        qx[out] = px[v]
        qy[out] = py[v]
        qw[out] = b
        out += 1
        if b < 0:
            continue
        w = v + 1 if v + 1 < m else 0
        lp = _nearest_label(xs, ys, px[v], py[v], b, nbrs, nn, box)
        lq = _nearest_label(xs, ys, px[w], py[w], b, nbrs, nn, box)
        if lp == lq:
            qw[out - 1] = lp
            continue
        kp, steps = _chain(nbrs, tris, nn, lp, lq, np.int64(0))
        if not (
            steps >= 1
            and out + steps + (m - v) <= qx.shape[0]
            and _chain_in_box(nbrs, tris, nn, kp, steps, cx, cy, box)
        ):
            qw[out - 1] = _nearest_label(
                xs, ys, 0.5 * (px[v] + px[w]), 0.5 * (py[v] + py[w]), b, nbrs, nn, box
            )
            continue
        qw[out - 1] = lp
        out = _emit_chain(nbrs, tris, nn, kp, steps, cx, cy, reach, box, qx, qy, qw, out)
    for v in range(out):
        px[v] = qx[v]
        py[v] = qy[v]
        pw[v] = qw[v]
    return out


@njit(**NJIT)
def cut_cell(i, xs, ys, ws, nbrs, tris, nn, box, cx, cy, reach, px, py, pw, qx, qy, qw, ss):
    """Cell of site ``i`` as the box cut by the bisectors with ``nbrs[:nn]``; result in ``p``.

    The cut is the power cell's (``kernels/power.box_cell``) with the zero weights ``ws``:
    Voronoi is the equal-weight case. ``tris[k]`` is the Delaunay triangle between
    neighbours ``k`` and ``k + 1`` (or -1); it lets :func:`_canonical_vertices` make shared
    vertices bit-identical across cells. ``ss`` is scratch.
    """
    if near_corner(i, xs, ys, tris, nn, cx, cy, box):
        # Voronoi vertices crowding a box corner closer than the float cut resolves: the
        # exact cut, whose owners need no relabelling
        m = corner_cut(i, xs, ys, nbrs, nn, box, px, py, pw, qx, qy, qw, ss)
        if m == 0:
            return 0
        return _canonical_vertices(
            i, xs, ys, px, py, pw, m, nbrs, tris, nn, cx, cy, reach, box, qx, qy, qw
        )
    m = box_cell(i, xs, ys, ws, nbrs, nn, box, px, py, pw, qx, qy, qw, ss)
    if m == 0:
        return 0
    m = _relabel_edges(xs, ys, px, py, pw, m, nbrs, tris, nn, cx, cy, reach, qx, qy, qw, box)
    return _canonical_vertices(
        i, xs, ys, px, py, pw, m, nbrs, tris, nn, cx, cy, reach, box, qx, qy, qw
    )


@njit(**NJIT)
def _safe_inside(t, cx, cy, err, box):
    """Whether triangle ``t``'s centre lies inside ``box`` by more than its rounding bound."""
    if t < 0:
        return False
    e = 4.0 * err[t] + 8.0 * _U * (abs(cx[t]) + abs(cy[t]))
    return box[0] + e < cx[t] < box[2] - e and box[1] + e < cy[t] < box[3] - e


@njit(**NJIT)
def _interior(q, tris, nn, cx, cy, err, box):
    """Whether neighbour ``q``'s edge runs between two centres safely inside the box.

    Its two ends are the centres of the triangles before and after it in rotation order;
    a hull site's first edge has no triangle before it (``tris[nn - 1] == -1``).
    """
    qp = q - 1 if q > 0 else nn - 1
    return _safe_inside(tris[qp], cx, cy, err, box) and _safe_inside(tris[q], cx, cy, err, box)


@njit(**NJIT)
def _splice(px, py, pw, m, nbrs, tris, nn, cx, cy, err, box, qx, qy, qw):
    """Put the runs of interior edges back into ring ``p``, cut by the other neighbours only.

    ``p[:m]`` is the box cut by the neighbours whose edges are not interior
    (:func:`_interior`). Between the edges of neighbours ``a`` and ``c`` that bound a run of
    interior edges, that ring has whatever the missing neighbours would have cut away; the
    run's edges replace it, starting and ending at the run's centres. Result in ``q``;
    returns its vertex count, or -1 when the ring does not have the expected edges (the
    caller then cuts by every neighbour).
    """
    v0 = -1
    for v in range(m):
        if pw[v] >= 0:
            k = _index_of(nbrs, nn, pw[v], np.int64(0))
            if k >= 0 and _interior((k + 1) % nn, tris, nn, cx, cy, err, box):
                v0 = v
                break
    if v0 < 0:
        return -1
    out = np.int64(0)
    v = v0
    first = True
    pend = False
    ox = 0.0
    oy = 0.0
    hint = np.int64(0)
    while True:
        if not first and v == v0:
            if pend:
                qx[0] = ox
                qy[0] = oy
            break
        first = False
        if out >= qx.shape[0]:
            return -1
        o = pw[v]
        qx[out] = ox if pend else px[v]
        qy[out] = oy if pend else py[v]
        qw[out] = o
        out += 1
        pend = False
        k = _index_of(nbrs, nn, o, hint) if o >= 0 else -1
        if k < 0 or not _interior((k + 1) % nn, tris, nn, cx, cy, err, box):
            v = v + 1 if v + 1 < m else 0
            continue
        hint = k
        q = (k + 1) % nn
        while _interior(q, tris, nn, cx, cy, err, box):
            t = tris[q - 1 if q > 0 else nn - 1]
            if out >= qx.shape[0] or q == k:
                return -1
            qx[out] = cx[t]
            qy[out] = cy[t]
            qw[out] = nbrs[q]
            out += 1
            q = (q + 1) % nn
        t = tris[q - 1 if q > 0 else nn - 1]
        ox = cx[t]
        oy = cy[t]
        pend = True
        target = nbrs[q]
        v = v + 1 if v + 1 < m else 0
        while pw[v] != target:
            if v == v0:
                return -1
            v = v + 1 if v + 1 < m else 0
    return out


@njit(**NJIT)
def spliced_cell(i, xs, ys, ws, nbrs, tris, nn, box, cx, cy, err, reach, bufs, gl, ss):
    """A cut cell with many neighbours in linear time; -1 when it must be cut the usual way.

    Cutting the box by ``nn`` bisectors one after another costs ``nn`` times the ring, and
    the ring grows with every edge inside the box: quadratic for a site with thousands of
    neighbours (sites on a line and one off it). Edges whose two ends are centres safely
    inside the box are final Voronoi edges, so only the other neighbours cut the box (their
    ring stays small: a convex cell crosses the box's sides a few times only), and the runs
    of interior edges are spliced back in rotation order (:func:`_splice`).
    """
    px, py, pw, qx, qy, qw = bufs
    if near_corner(i, xs, ys, tris, nn, cx, cy, box):
        return -1  # cut exactly (cut_cell)
    ng = np.int64(0)
    for q in range(nn):
        if not _interior(q, tris, nn, cx, cy, err, box):
            gl[ng] = nbrs[q]
            ng += 1
    if ng == 0 or ng == nn:
        return -1
    m = box_cell(i, xs, ys, ws, gl, ng, box, px, py, pw, qx, qy, qw, ss)
    if m == 0:
        return -1
    # (no _relabel_edges: its nearest-neighbour test would see the spliced-out neighbours'
    # territory; a many-neighbour cell whose cut needs relabelling fails the splice instead)
    m = _splice(px, py, pw, m, nbrs, tris, nn, cx, cy, err, box, qx, qy, qw)
    if m < 3:
        return -1
    for v in range(m):
        px[v] = qx[v]
        py[v] = qy[v]
        pw[v] = qw[v]
    return _canonical_vertices(
        i, xs, ys, px, py, pw, m, nbrs, tris, nn, cx, cy, reach, box, qx, qy, qw
    )
