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
   the exact topology: the other merged it by a tolerance);
2. the slots of one vertex are joined: the ends of each shared edge with the matching ends
   in the neighbour's ring, and the two ends of an edge the neighbour still lacks or that
   runs backwards (each join only within ``AGREE_JOIN_ULPS`` ulps of the coordinates plus
   ``AGREE_JOIN_RTOL`` of the distance to the site), and each joined group takes one
   point: a box corner, then a crossing of a box side, then the smallest bits;
3. the result is kept only when every ring it changed is still exactly convex, holds its
   site where it did, and every ring now shares every edge with its neighbours; else,
   without step 1, the same; else the rings are returned as they were.

Only rings that disagree (:func:`.kernels.ring_agree.rings_disagree`, one parallel pass)
and their neighbours are looked at.
"""

from __future__ import annotations

import numpy as np

from ..config import AGREE_JOIN_RTOL, AGREE_JOIN_ULPS, AGREE_SHORT
from ..kernels.predicates import orient2d
from ..kernels.ring_agree import rings_disagree, rings_disagree_at


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
    bad = rings_disagree(closed, lengths, owner, inv, ring_id, AGREE_SHORT, sites)
    if not bad.any():
        return closed, lengths, owner
    region = set(np.flatnonzero(bad).tolist())
    for r in list(region):
        for j in owner[lengths[r] : lengths[r + 1] - 1]:
            if j >= 0 and inv[j] >= 0:
                region.add(int(inv[j]))
    for insert in (True, False):
        got = _reconciled(closed, lengths, owner, ring_id, inv, sites, sorted(region), insert)
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
            mo = len(other[0])
            for w in range(mo):
                if other[2][w - 1] == b and other[2][w] == a:
                    # j's vertex between its edges with b and a becomes q, then p
                    other[0][w : w + 1] = [q[0], p[0]]
                    other[1][w : w + 1] = [q[1], p[1]]
                    other[2][w : w + 1] = [me, a]
                    break


def _close(p, q, site):
    d = abs(p[0] - q[0]) + abs(p[1] - q[1])
    if d == 0.0:
        return True
    mag = max(abs(p[0]), abs(p[1]), abs(q[0]), abs(q[1]))
    ulp = float(np.spacing(mag))
    scale = abs(p[0] - site[0]) + abs(p[1] - site[1])
    return d <= AGREE_JOIN_ULPS * ulp + AGREE_JOIN_RTOL * scale


def _reconciled(closed, lengths, owner, ring_id, inv, sites, region, insert):
    """Steps 1 (with ``insert``) to 3 of the module; None where the result is refused."""
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
            if s not in rings:
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
    # one point per class: a box corner, then a crossing of a side, then the smallest bits
    best = {}
    for r, ring in rings.items():
        m = len(ring[0])
        for v in range(m):
            k = root((r, v))
            kind = (ring[2][v - 1] < 0) + (ring[2][v] < 0)
            key = (-kind, ring[0][v], ring[1][v])
            if k not in best or key < best[k]:
                best[k] = key
    changed = set()
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
        if xs != closed[a:b, 0].tolist() or ys != closed[a:b, 1].tolist():
            changed.add(r)
            site = sites[int(ring_id[r])]
            held = _holds(closed[a:b, 0].tolist(), closed[a:b, 1].tolist(), site)
            if not _convex(xs, ys) or (held and not _holds(xs, ys, site)):
                return None
        ring[0], ring[1], ring[2] = xs, ys, [max(o, -1) for o in os_]
    if not changed:
        return None
    out = _rebuilt(closed, lengths, owner, rings)
    # the changed rings and every ring beside them share each edge now (rings keep their
    # places, so ``inv`` holds)
    near = set(changed)
    for r in changed:
        near.update(int(inv[j]) for j in rings[r][2] if j >= 0 and inv[j] >= 0)
    which = np.array(sorted(near), dtype=np.int64)
    if rings_disagree_at(*out, inv, ring_id, which).any():
        return None
    return out


def _convex(xs, ys):
    """Whether the open ring turns left or goes straight at every vertex, with positive area."""
    m = len(xs)
    if m < 3:
        return False
    area = 0
    for v in range(m):
        t = orient2d(xs[v - 1], ys[v - 1], xs[v], ys[v], xs[(v + 1) % m], ys[(v + 1) % m])
        if t < 0:
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
