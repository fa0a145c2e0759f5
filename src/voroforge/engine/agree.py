"""Rings that share every Voronoi vertex in one float point (issue 15, sites ulps apart).

The half-plane cells settle each ring on its own, with exact predicates and the one merge
rule (:func:`.kernels.vertex.same_vertex`); where sites lie 1-4 ulps apart, the exact
Voronoi vertices are ulps apart too and the rule's answer depends on which vertex a cell
asks about, so one cell can keep an edge an ulp long that its neighbour merged away (one
vertex at two points: the rings meet with a gap or an overlap an ulp wide, and Euler's
count fails). The planar build keeps those rings where the Delaunay dual, whose rings
always agree, loses a site. :func:`agree` makes such rings agree, from the rings and the
sites alone (so every algorithm that returned the same rings gets the same answer):

1. an edge that one ring has and its neighbour lacks is given to the neighbour when its
   ends are apart and run the right way along the bisector (the ring that has it keeps
   the exact topology: the other merged it by a tolerance), between the neighbour's edges
   with the sites at the edge's two ends, or beside one of them where the neighbour has
   no edge with the other (rounded to nothing: four sites' vertices one float point);
2. the slots of one vertex are joined: the ends of each shared edge with the matching ends
   in the neighbour's ring, and the two ends of an edge the neighbour still lacks or that
   runs backwards (each join only within ``AGREE_JOIN_ULPS`` ulps of the coordinates plus
   ``AGREE_JOIN_RTOL`` of the distance to the site), and each joined group takes one of
   its slots' points: a box corner, then a crossing of a box side, then the smallest bits
   first, the others in turn (up to ``AGREE_POINT_TRIES`` choices for all groups) where
   that one fails step 3 or leaves a ring of the region beside its site (a group of four
   or five sites whose vertices lie an ulp or two apart: the smallest bits can leave a
   ring reflex or without its site where another of the group's points does not; of
   those step 3 keeps, the first with the fewest rings beside their site is taken);
3. the result is kept only when every ring it changed is still exactly convex, holds its
   site where it did, and every ring now shares every edge with its neighbours; else,
   without step 1, the same; else both again, with rings that turn right by rounding only
   (within ``VERTEX_STRAIGHT_ULPS`` of the chord, as ``describe()`` counts convexity) and
   stay simple polygons; else the rings are returned as they were.

Only rings that disagree (:func:`.kernels.ring_agree.rings_disagree`, one parallel pass)
and their neighbours are looked at.
"""

from __future__ import annotations

import itertools
from fractions import Fraction

import numpy as np
import shapely

from ..config import (
    AGREE_JOIN_RTOL,
    AGREE_JOIN_ULPS,
    AGREE_POINT_TRIES,
    AGREE_SHORT,
    VERTEX_STRAIGHT_ULPS,
)
from ..kernels.predicates import incircle, orient2d
from ..kernels.ring_agree import rings_disagree, rings_disagree_at
from ..kernels.vertex import voronoi_vertex


def agree(closed, lengths, owner, ring_id, n, sites):
    """Closed rings whose neighbours share every edge bit for bit (see the module).

    Parameters
    ----------
    closed : (k, 2) float64
        Closed rings (last vertex repeats the first).
    lengths : (u + 1,) int64
        Ring ``r`` is ``closed[lengths[r]:lengths[r + 1]]``.
    owner : (k,) int64
        Cell across each edge (negative: box, closing vertex).
    ring_id : (u,) int64
        Cell of ring ``r`` (the ids owners use).
    n : int
        Number of cells.
    sites : (n, 2) float64
        Each cell's site.

    Returns
    -------
    (closed, lengths, owner)
        The input arrays themselves when they agree already or cannot be made to.
    """
    if not len(closed):
        return closed, lengths, owner
    inv = np.full(n, -1, dtype=np.int64)
    inv[ring_id] = np.arange(len(ring_id))
    # a read-only view whoever's sites they are (a frozen Diagram's or a fresh array):
    # numba types the flag, and rings_disagree was compiled once for each
    ro = np.asarray(sites).view()
    ro.flags.writeable = False
    bad = rings_disagree(closed, lengths, owner, inv, ring_id, AGREE_SHORT, ro)
    if not bad.any():
        return closed, lengths, owner
    region = set(np.flatnonzero(bad).tolist())
    for r in list(region):
        for j in owner[lengths[r] : lengths[r + 1] - 1]:
            if j >= 0 and inv[j] >= 0:
                region.add(int(inv[j]))
    for lax, insert in ((False, True), (False, False), (True, True), (True, False)):
        got = _reconciled(closed, lengths, owner, ring_id, inv, sites, sorted(region), insert, lax)
        if got is not None:
            return got
    return closed, lengths, owner


def _rings_of(closed, lengths, owner, region):
    """Ring ``r`` of ``region`` as lists ``[xs, ys, owners]`` without the closing vertex."""
    out = {}
    for r in region:
        a, b = lengths[r], lengths[r + 1] - 1
        out[r] = [closed[a:b, 0].tolist(), closed[a:b, 1].tolist(), owner[a:b].tolist()]
    return out


def _edge_of(ring, me):
    """Slots of the edges of ``ring`` owned by cell ``me``."""
    return [u for u, o in enumerate(ring[2]) if o == me]


def _pt(ring, v):
    m = len(ring[0])
    v %= m
    return ring[0][v], ring[1][v]


def _backwards(p, q, si, sj):
    """Whether edge ``p -> q`` of the cell of site ``si`` runs against its bisector with ``sj``."""
    return (q[0] - p[0]) * (sj[1] - si[1]) - (q[1] - p[1]) * (sj[0] - si[0]) > 0.0


def _insert_missing(rings, ring_id, inv, sites):
    """Give each ring the edges its neighbours have with it and it lacks (step 1, in place)."""
    for r in sorted(rings):
        ring = rings[r]
        me = int(ring_id[r])
        m = len(ring[0])
        for v in range(m):
            j = ring[2][v]
            s = int(inv[j]) if j >= 0 else -1
            if s not in rings or _edge_of(rings[s], me):
                continue
            p = _pt(ring, v)
            q = _pt(ring, v + 1)
            if p == q or _backwards(p, q, sites[me], sites[j]):
                continue
            a = ring[2][v - 1]
            b = ring[2][(v + 1) % m]
            if (a < 0 and b < 0) or a == b:
                continue  # (both ends on the box: which corner is not named; joined instead)
            other = rings[s]
            w = _slot_for(other[2], a, b)
            if w >= 0:
                # j's vertex between its edges with b and a becomes q, then p
                other[0][w : w + 1] = [q[0], p[0]]
                other[1][w : w + 1] = [q[1], p[1]]
                other[2][w : w + 1] = [me, other[2][w]]


def _slot_for(owners, a, b):
    """The vertex of a ring (its edges' ``owners``) between its edges with ``b`` and ``a``.

    Else the vertex after its edge with ``b`` where it has none with ``a``, or the one
    before its edge with ``a`` where it has none with ``b``: the edge between this ring and
    ``a`` (or ``b``) is rounded to nothing there (four sites' vertices one float point);
    -1 where none is.
    """
    mo = len(owners)
    for w in range(mo):
        if owners[w - 1] == b and owners[w] == a:
            return w
    for w in range(mo):
        if (owners[w - 1] == b and a not in owners) or (owners[w] == a and b not in owners):
            return w
    return -1


def _close(p, q, site):
    d = abs(p[0] - q[0]) + abs(p[1] - q[1])
    if d == 0.0:
        return True
    mag = max(abs(p[0]), abs(p[1]), abs(q[0]), abs(q[1]))
    ulp = float(np.spacing(mag))
    scale = abs(p[0] - site[0]) + abs(p[1] - site[1])
    return d <= AGREE_JOIN_ULPS * ulp + AGREE_JOIN_RTOL * scale


def _reconciled(closed, lengths, owner, ring_id, inv, sites, region, insert, lax):
    """Steps 1 (with ``insert``) to 3 of the module; None where the result is refused.

    With ``lax``, a changed ring may turn right by rounding (:func:`_kept`).
    """
    rings = _rings_of(closed, lengths, owner, region)
    if insert:
        _insert_missing(rings, ring_id, inv, sites)
    parent = {}

    def root(k):
        while parent.get(k, k) != k:
            k = parent[k]
        return k

    def join(k1, k2, site):
        p = _pt(rings[k1[0]], k1[1])
        q = _pt(rings[k2[0]], k2[1])
        if not _close(p, q, site):
            return
        a, b = root(k1), root(k2)
        if a != b:
            parent[max(a, b)] = min(a, b)

    for r, ring in rings.items():
        me = int(ring_id[r])
        m = len(ring[0])
        for v in range(m):
            j = ring[2][v]
            if j < 0:
                continue
            here, there = (r, v), (r, (v + 1) % m)
            s = int(inv[j])
            if s not in rings or not len(rings[s][0]):
                # an empty neighbour (a cell floats cannot hold: a corner's sliver whose
                # crossings rounded together) has no edge to agree with: the ring keeps
                # its edge (joining its ends gave the box corner's sliver to no cell)
                continue
            p, q = _pt(ring, v), _pt(ring, v + 1)
            if _backwards(p, q, sites[me], sites[j]):
                join(here, there, sites[me])
            us = _edge_of(rings[s], me)
            if not us:
                join(here, there, sites[me])
                continue
            other = rings[s]
            mo = len(other[0])
            # the neighbour's edge nearest this one (one, but for two on one bisector)
            u = min(
                us,
                key=lambda u: (
                    abs(_pt(other, u)[0] - q[0])
                    + abs(_pt(other, u)[1] - q[1])
                    + abs(_pt(other, u + 1)[0] - p[0])
                    + abs(_pt(other, u + 1)[1] - p[1])
                ),
            )
            join(here, (s, (u + 1) % mo), sites[me])
            join(there, (s, u), sites[me])
    # each class's candidate points: those of its slots of the most box sides (a box corner,
    # then a crossing of a side), in order of their bits; the first choice of every class
    # is tried first, then the others until every changed ring keeps its checks
    cand = {}
    for r, ring in rings.items():
        m = len(ring[0])
        for v in range(m):
            k = root((r, v))
            kind = (ring[2][v - 1] < 0) + (ring[2][v] < 0)
            cand.setdefault(k, set()).add((-kind, ring[0][v], ring[1][v]))
    first = {}
    open_ = []
    for k, keys in cand.items():
        keys = sorted(keys)
        keys = [key for key in keys if key[0] == keys[0][0]]
        first[k] = keys[0]
        if len(keys) > 1:
            open_.append((k, keys))
    tries = itertools.product(*(keys for _, keys in open_))
    kept = None
    for choice in itertools.islice(tries, AGREE_POINT_TRIES):
        best = dict(first)
        best.update({k: key for (k, _), key in zip(open_, choice, strict=True)})
        got = _placed(closed, lengths, owner, ring_id, inv, sites, rings, root, best, lax)
        if got is not None and got[1] == 0:
            return got[0]
        if got is not None and (kept is None or got[1] < kept[1]):
            kept = got  # (a ring beside its site: another choice may give it back)
    return None if kept is None else kept[0]


def _placed(closed, lengths, owner, ring_id, inv, sites, rings, root, best, lax):
    """The rings with every slot at its class's point ``best[root(slot)]``, and a count.

    The count is of the rings (of ``rings``) that miss their site. None where a changed
    ring is not convex or loses its site, or the rings still disagree.
    """
    changed = set()
    placed = {}
    missing = 0
    for r, ring in rings.items():
        m = len(ring[0])
        xs, ys, os_ = [], [], []
        for v in range(m):
            _, x, y = best[root((r, v))]
            if xs and xs[-1] == x and ys[-1] == y:
                os_[-1] = ring[2][v]
                continue
            xs.append(x)
            ys.append(y)
            os_.append(ring[2][v])
        while len(xs) > 1 and xs[-1] == xs[0] and ys[-1] == ys[0]:
            xs.pop()
            ys.pop()
            os_.pop()
        a, b = lengths[r], lengths[r + 1] - 1
        site = sites[int(ring_id[r])]
        held = _holds(closed[a:b, 0].tolist(), closed[a:b, 1].tolist(), site)
        if xs != closed[a:b, 0].tolist() or ys != closed[a:b, 1].tolist():
            changed.add(r)
            now = _kept(xs, ys, site, lax)
            if now is None or (held and not now):
                return None
            held = now
        missing += not held
        placed[r] = [xs, ys, [max(o, -1) for o in os_]]
    if not changed:
        return None
    out = _rebuilt(closed, lengths, owner, placed)
    # the changed rings and every ring beside them share each edge now (rings keep their
    # places, so ``inv`` holds)
    near = set(changed)
    for r in changed:
        near.update(int(inv[j]) for j in placed[r][2] if j >= 0 and inv[j] >= 0)
    which = np.array(sorted(near), dtype=np.int64)
    if rings_disagree_at(*out, inv, ring_id, which).any():
        return None
    return out, missing


def _kept(xs, ys, site, lax):
    """Whether a changed open ring holds ``site``; None where it is refused.

    It must be exactly convex (with ``lax``, a simple polygon whose right turns are
    rounding, as ``describe()`` counts them).
    """
    if not lax:
        return _holds(xs, ys, site) if _convex(xs, ys) else None
    if not _convex(xs, ys, VERTEX_STRAIGHT_ULPS):
        return None
    poly = shapely.polygons(np.column_stack((xs + xs[:1], ys + ys[:1])))
    if not shapely.is_valid(poly):
        return None
    return bool(shapely.intersects(poly, shapely.points(site)))


def _convex(xs, ys, ulps=0.0):
    """Whether the open ring turns left or goes straight at every vertex, with positive area.

    With ``ulps``, a right turn at a vertex within ``ulps`` ulps (of the three points'
    largest coordinate) of the chord between its neighbours counts as straight.
    """
    m = len(xs)
    if m < 3:
        return False
    area = 0
    for v in range(m):
        x0, y0, x2, y2 = xs[v - 1], ys[v - 1], xs[(v + 1) % m], ys[(v + 1) % m]
        t = orient2d(x0, y0, xs[v], ys[v], x2, y2)
        if t < 0:
            big = max(abs(x0), abs(y0), abs(xs[v]), abs(ys[v]), abs(x2), abs(y2))
            if not -t <= ulps * float(np.spacing(big)) * np.hypot(x2 - x0, y2 - y0):
                return False
        area += t > 0
    return area > 0


def _holds(xs, ys, site):
    """Whether the open convex ring holds ``site`` (its edges included), by exact turns."""
    m = len(xs)
    if m < 3:
        return False
    for v in range(m):
        w = (v + 1) % m
        if orient2d(xs[v], ys[v], xs[w], ys[w], float(site[0]), float(site[1])) < 0:
            return False
    return True


def _rebuilt(closed, lengths, owner, rings):
    """The arrays with the rings of ``rings`` replaced (each closed again)."""
    u = len(lengths) - 1
    parts_c, parts_o = [], []
    new_len = np.zeros(u + 1, dtype=np.int64)
    for r in range(u):
        if r in rings:
            xs, ys, os_ = rings[r]
            c = np.column_stack((xs + xs[:1], ys + ys[:1])) if xs else closed[:0]
            o = np.array(os_ + [-2] if xs else [], dtype=owner.dtype)
        else:
            c = closed[lengths[r] : lengths[r + 1]]
            o = owner[lengths[r] : lengths[r + 1]]
        parts_c.append(c)
        parts_o.append(o)
        new_len[r + 1] = new_len[r] + len(c)
    return np.concatenate(parts_c), new_len, np.concatenate(parts_o)


def split_merged(closed, lengths, owner, ring_id, n, sites, astray, *, tolerate=False):
    """Rings ``astray`` (indices) that miss their site, given it back by splitting a vertex.

    Where the cells merged four sites' Voronoi vertices ulps apart into one point (their
    centres within rounding bounds of each other, :func:`.kernels.vertex.same_vertex`),
    the point the group takes can leave a site outside its ring by an ulp, though floats
    hold the two exact vertices apart (issue 15's cluster c354). For a vertex of ring ``i``
    between its edges with ``a`` and ``b`` whose circle holds a fourth site ``c`` (exact
    ``incircle``) that has the same point between its edges with ``b`` and ``a``, the
    point is split as the exact diagram has it: ``i`` and ``c`` get their shared edge
    between the vertices of ``(i, a, c)`` and ``(i, c, b)``, each named by its triple
    (:func:`.kernels.vertex.voronoi_vertex`), ``a`` and ``b`` the one of theirs. Kept only
    where every changed ring stays exactly convex, holds its site where it did and ring
    ``i`` holds its own, and the rings still share every edge (else again with rings that
    turn right by rounding only, as in :func:`agree`); else the next such vertex is tried.
    With ``tolerate``, a ring beside the changed ones that disagreed with a neighbour before
    may still (the Delaunay dual's rings of a lost site: two cells an ulp apart at a box
    side elsewhere on the ring); no ring may disagree that did not.
    Returns ``(closed, lengths, owner)``, the input arrays where none is kept.
    """
    xs = np.ascontiguousarray(sites[:, 0])
    ys = np.ascontiguousarray(sites[:, 1])
    inv = np.full(n, -1, dtype=np.int64)
    inv[ring_id] = np.arange(len(ring_id))
    for r in astray:
        i = int(ring_id[r])
        a0, b0 = lengths[r], lengths[r + 1] - 1
        m = b0 - a0
        for v in range(m):
            a = int(owner[a0 + (v - 1) % m])
            b = int(owner[a0 + v])
            p = (float(closed[a0 + v, 0]), float(closed[a0 + v, 1]))
            if a < 0 or b < 0 or inv[a] < 0 or inv[b] < 0:
                continue
            got = _split_at(closed, lengths, owner, ring_id, inv, xs, ys, (i, a, b), p, tolerate)
            if got is not None:
                closed, lengths, owner = got
                break
    return closed, lengths, owner


def _slot_between(closed, lengths, owner, r, before, after, p):
    """The slot of ring ``r`` at point ``p`` between its edges with ``before`` and ``after``."""
    a0, b0 = lengths[r], lengths[r + 1] - 1
    m = b0 - a0
    for w in range(m):
        if owner[a0 + (w - 1) % m] == before and owner[a0 + w] == after:
            if (closed[a0 + w, 0], closed[a0 + w, 1]) == p:
                return w
    return -1


def _split_at(closed, lengths, owner, ring_id, inv, xs, ys, iab, p, tolerate=False):
    """:func:`split_merged` at ring ``inv[i]``'s vertex ``p`` between ``a`` and ``b``; or None."""
    i, a, b = iab
    ra = int(inv[a])
    for c in sorted(set(owner[lengths[ra] : lengths[ra + 1] - 1].tolist())):
        if c < 0 or c in (i, a, b) or inv[c] < 0:
            continue
        w = _slot_between(closed, lengths, owner, int(inv[c]), b, a, p)
        if w < 0:
            continue
        if incircle(xs[i], ys[i], xs[a], ys[a], xs[b], ys[b], xs[c], ys[c]) <= 0.0:
            continue  # (i, a, b) is the exact diagram's vertex: nothing to split
        # each ring's slot at p and what replaces it: [(x, y, owner after), ...]
        new = {}
        for ring_site, before, after, tris in (
            (i, a, b, ((i, a, c, c), (i, c, b, b))),
            (c, b, a, ((c, b, i, i), (c, i, a, a))),
            (a, c, i, ((a, c, i, i),)),
            (b, i, c, ((b, i, c, c),)),
        ):
            r = int(inv[ring_site])
            u = _slot_between(closed, lengths, owner, r, before, after, p)
            if u < 0:
                return None
            pts = []
            for t0, t1, t2, after_ in tris:
                x, y = voronoi_vertex(t0, t1, t2, xs, ys)
                if not (np.isfinite(x) and np.isfinite(y)):
                    return None
                pts.append((x, y, after_))
            new[r] = (u, pts)
        for lax in (False, True):
            got = _split_rings(
                closed, lengths, owner, ring_id, inv, (xs, ys), new, int(inv[i]), lax, tolerate
            )
            if got is not None:
                return got
        return None
    return None


def _split_rings(closed, lengths, owner, ring_id, inv, xys, new, mine, lax, tolerate=False):
    """The rings with slots replaced as ``new`` says; None where a check fails.

    With ``lax``, a changed ring may turn right by rounding (:func:`_kept`); with
    ``tolerate``, a ring that disagreed with a neighbour before may still.
    """
    xs, ys = xys
    placed = {}
    for r, (u, pts) in new.items():
        a0, b0 = lengths[r], lengths[r + 1] - 1
        slots = [(closed[k, 0], closed[k, 1], owner[k]) for k in range(a0, b0)]
        slots[u : u + 1] = pts
        rx, ry, ro = [], [], []
        for x, y, o in slots:
            if rx and rx[-1] == x and ry[-1] == y:
                ro[-1] = o  # an edge of length 0 goes
                continue
            rx.append(float(x))
            ry.append(float(y))
            ro.append(int(o))
        while len(rx) > 1 and rx[-1] == rx[0] and ry[-1] == ry[0]:
            rx.pop()
            ry.pop()
            ro.pop()
        site = (xs[ring_id[r]], ys[ring_id[r]])
        held = _holds(closed[a0:b0, 0].tolist(), closed[a0:b0, 1].tolist(), site)
        now = _kept(rx, ry, site, lax)
        if now is None or (held and not now) or (r == mine and not now):
            return None
        placed[r] = [rx, ry, [max(o, -1) for o in ro]]
    out = _rebuilt(closed, lengths, owner, placed)
    near = set(placed)
    for r in placed:
        near.update(int(inv[j]) for j in placed[r][2] if j >= 0 and inv[j] >= 0)
    which = np.array(sorted(near), dtype=np.int64)
    bad = rings_disagree_at(*out, inv, ring_id, which)
    if tolerate and bad.any():
        bad &= ~rings_disagree_at(closed, lengths, owner, inv, ring_id, which)
    if bad.any():
        return None
    return out


def nudge_vertex(closed, lengths, owner, ring_id, n, sites, astray):
    """Rings ``astray`` (indices) that miss their site, given it back by a vertex rounded up.

    Or down: a vertex of ring ``i`` between its edges with ``a`` and ``b`` is the centre of
    ``i, a, b`` rounded to nearest; where that point takes the edge across the site (sites
    an ulp apart: issue 15's cluster c202, by 1.6e-16 ulps), another of the four floats
    around the exact centre (rationals: a rare path) can keep it. The point moves in the rings of
    ``i, a, b`` alike, and is kept only with the checks of :func:`split_merged`.
    Returns ``(closed, lengths, owner)``, the input arrays where none is kept.
    """
    xs = np.ascontiguousarray(sites[:, 0])
    ys = np.ascontiguousarray(sites[:, 1])
    inv = np.full(n, -1, dtype=np.int64)
    inv[ring_id] = np.arange(len(ring_id))
    for r in astray:
        i = int(ring_id[r])
        a0, b0 = lengths[r], lengths[r + 1] - 1
        m = b0 - a0
        done = False
        for v in range(m):
            a = int(owner[a0 + (v - 1) % m])
            b = int(owner[a0 + v])
            if a < 0 or b < 0 or inv[a] < 0 or inv[b] < 0:
                continue
            p = (float(closed[a0 + v, 0]), float(closed[a0 + v, 1]))
            centre = _exact_centre((i, a, b), xs, ys)
            if centre is None:
                continue
            for q in itertools.product(_floats_around(centre[0]), _floats_around(centre[1])):
                if q == p:
                    continue
                new = {}
                for s, before, after in ((i, a, b), (a, b, i), (b, i, a)):
                    rs = int(inv[s])
                    u = _slot_between(closed, lengths, owner, rs, before, after, p)
                    if u >= 0:
                        new[rs] = (u, [(q[0], q[1], after)])
                for lax in (False, True):
                    got = _split_rings(closed, lengths, owner, ring_id, inv, (xs, ys), new, r, lax)
                    if got is not None:
                        closed, lengths, owner = got
                        done = True
                        break
                if done:
                    break
            if done:
                break
    return closed, lengths, owner


def _exact_centre(tri, xs, ys):
    """The circumcentre of sites ``tri`` in rationals, or None where they are collinear."""
    (ax, ay), (bx, by), (cx, cy) = ((Fraction(float(xs[t])), Fraction(float(ys[t]))) for t in tri)
    d = 2 * (ax * (by - cy) + bx * (cy - ay) + cx * (ay - by))
    if d == 0:
        return None
    sa, sb, sc = ax * ax + ay * ay, bx * bx + by * by, cx * cx + cy * cy
    x = (sa * (by - cy) + sb * (cy - ay) + sc * (ay - by)) / d
    y = (sa * (cx - bx) + sb * (ax - cx) + sc * (bx - ax)) / d
    return x, y


def _floats_around(f):
    """The float nearest the rational ``f`` and its neighbour on ``f``'s other side."""
    near = float(f)
    if Fraction(near) == f:
        return [near]
    other = np.nextafter(near, np.inf if Fraction(near) < f else -np.inf)
    return [near, float(other)]
