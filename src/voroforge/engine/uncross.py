"""A thin ring that crosses itself once, cut at the crossing, its neighbours made to match.

Issue 15's float circle (1025 sites of radius 1e-7 at (5e5, 4e6), phase 0.90): the
Delaunay dual merges every Voronoi vertex within ~150 ulps of the circle's centre into
one class, so the wedge of a site runs its last edges to the centre point. Moving that
end turns the wedge's edge with one neighbour (``o2``) by more than the wedge is wide
there (an ulp), and the edge crosses the wedge's other side (the edge with ``o1``): the
ring is a bow-tie, a big counter-clockwise loop holding the site and a thin clockwise
loop towards the centre, which both neighbours' rings cover too. Left empty
(:func:`.planar._drop_folded`), the wedge's gap was that bow-tie and stayed open, and
``describe()``'s Euler count failed.

:func:`uncrossed` keeps the big loop as the site's ring, cut at the crossing ``X`` (the
exact crossing of the two edges, rounded to the nearest floats), and gives the thin loop
to the cells across the other side: ``o2``'s ring runs from the crossing along the
wedge's old edges (``X -> b -> ... -> c``) instead of straight to ``c``, ``o1``'s edge
gets the vertex ``X``, and the cells across the loop's edges face ``o2`` there. Every
edge is then shared by two rings, reversed, bit for bit. Kept only where each changed
ring is a valid polygon and the site's ring is counter-clockwise; a rare path (exact
rationals).
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import shapely

from ..kernels.dual_some import splice_rings


def uncrossed(closed, lengths, owner, i, inv):
    """Rings with ring ``i``'s single self-crossing resolved, or None where it does not apply.

    Parameters
    ----------
    closed, lengths, owner : ndarray
        Closed rings (last vertex repeating the first), ring ``k`` at
        ``closed[lengths[k]:lengths[k + 1]]``; ``owner[s]`` the site across the edge from
        slot ``s`` (-1: a box side).
    i : int
        The ring to resolve.
    inv : (m,) int64
        Ring of each owner (-1: none).

    Returns
    -------
    (closed, lengths, owner) or None
    """
    ring = _open(closed, lengths, owner, i)
    m = len(ring)
    if m < 4 or any(o < 0 or o >= len(inv) or inv[o] < 0 for _, _, o in ring):
        return None
    got = _crossing(ring)
    if got is None:
        return None
    e, f, x = got  # edges e = (a -> b) and f = (c -> d); the loop X -> b .. c is clockwise
    o1, o2 = ring[e][2], ring[f][2]
    me = _site_of(i, inv)
    path = [(e + 1 + k) % m for k in range((f - e) % m)]  # slots b .. c
    across = [ring[s][2] for s in path[:-1]]  # the owners of edges b -> .. -> c
    if o1 == o2 or o2 in across or o1 in across or me is None:
        return None
    new = {}
    # ring i: a -> X -> d, the loop's run dropped
    keep = [(e + 1 + (f - e) % m + k) % m for k in range(m - (f - e) % m)]  # d .. a
    mine = [ring[s] for s in keep]
    mine[-1] = (mine[-1][0], mine[-1][1], o1)
    mine.append((x[0], x[1], o2))
    new[i] = mine
    # o2: its edge d -> c (facing i) becomes d -> X -> b -> .. -> c
    b, c, d = ring[path[0]], ring[path[-1]], ring[(f + 1) % m]
    r2 = _open(closed, lengths, owner, int(inv[o2]))
    at = _edge_at(r2, d, c, me)
    if at is None:
        return None
    run = [(d[0], d[1], me), (x[0], x[1], o1)]
    run += [(ring[s][0], ring[s][1], ring[s][2]) for s in path[:-1]]
    new[int(inv[o2])] = r2[:at] + run + r2[at + 1 :]
    # o1: its edge b -> a (facing i) becomes b -> X -> a
    a = ring[e]
    r1 = _open(closed, lengths, owner, int(inv[o1]))
    at = _edge_at(r1, b, a, me)
    if at is None:
        return None
    new[int(inv[o1])] = r1[:at] + [(b[0], b[1], o2), (x[0], x[1], me)] + r1[at + 1 :]
    # the cells across the loop's edges face o2 now
    for s, k in zip(path[:-1], across, strict=True):
        r = int(inv[k])
        rk = new.get(r) or _open(closed, lengths, owner, r)
        u, w = ring[s], ring[(s + 1) % m]
        at = _edge_at(rk, w, u, me)
        if at is None:
            return None
        rk = list(rk)
        rk[at] = (rk[at][0], rk[at][1], o2)
        new[r] = rk
    if not all(_valid(rk) for rk in new.values()):
        return None
    if _area2(new[i]) <= 0:
        return None
    return _spliced(closed, lengths, owner, new)


def _open(closed, lengths, owner, r):
    """Ring ``r`` as ``[(x, y, owner of the edge from it), ...]``, without the closing vertex."""
    a, b = int(lengths[r]), int(lengths[r + 1])
    return [(float(closed[k, 0]), float(closed[k, 1]), int(owner[k])) for k in range(a, b - 1)]


def _site_of(i, inv):
    """The owner number of ring ``i`` (``inv`` inverted), or None."""
    hit = np.flatnonzero(inv == i)
    return int(hit[0]) if len(hit) == 1 else None


def _edge_at(ring, p, q, me):
    """The slot of edge ``p -> q`` facing ``me`` in an open ring, or None."""
    m = len(ring)
    for k in range(m):
        u, w = ring[k], ring[(k + 1) % m]
        if u[:2] == p[:2] and w[:2] == q[:2] and u[2] == me:
            return k
    return None


def _crossing(ring):
    """The one pair of non-adjacent edges that cross, as ``(e, f, X)``; None unless one.

    ``e`` and ``f`` are slots with the loop ``X -> ring[e + 1] .. ring[f] -> X`` clockwise;
    ``X`` is their exact crossing rounded to the nearest floats.
    """
    m = len(ring)
    q = [(Fraction(x), Fraction(y)) for x, y, _ in ring]
    hits = []
    for s in range(m):
        for t in range(s + 2, m):
            if (t + 1) % m == s:
                continue
            x = _cross(q[s], q[(s + 1) % m], q[t], q[(t + 1) % m])
            if x is not None:
                hits.append((s, t, x))
                if len(hits) > 1:
                    return None
    if len(hits) != 1:
        return None
    s, t, x = hits[0]
    loop = [x] + [q[(s + 1 + k) % m] for k in range(t - s)]
    if _area2_exact(loop) < 0:
        e, f = s, t
    else:
        e, f = t, s
    xf = (float(x[0]), float(x[1]))
    if any(xf == (r[0], r[1]) for r in ring):
        return None
    return e, f, xf


def _cross(p, q, r, s):
    """The exact crossing point of segments ``p q`` and ``r s`` in their interiors, or None."""
    d = (q[0] - p[0]) * (s[1] - r[1]) - (q[1] - p[1]) * (s[0] - r[0])
    if d == 0:
        return None
    t = ((r[0] - p[0]) * (s[1] - r[1]) - (r[1] - p[1]) * (s[0] - r[0])) / d
    u = ((r[0] - p[0]) * (q[1] - p[1]) - (r[1] - p[1]) * (q[0] - p[0])) / d
    if not (0 < t < 1 and 0 < u < 1):
        return None
    return (p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]))


def _area2_exact(pts):
    m = len(pts)
    return sum(pts[k][0] * pts[(k + 1) % m][1] - pts[(k + 1) % m][0] * pts[k][1] for k in range(m))


def _area2(ring):
    return _area2_exact([(Fraction(x), Fraction(y)) for x, y, _ in ring])


def _valid(ring):
    """Whether an open ring is a valid polygon with no repeated consecutive vertex."""
    m = len(ring)
    if m < 3 or any(ring[k][:2] == ring[(k + 1) % m][:2] for k in range(m)):
        return False
    xy = [r[:2] for r in ring]
    return bool(shapely.is_valid(shapely.polygons(xy + xy[:1])))


def _spliced(closed, lengths, owner, new):
    """The rings with the open rings ``new`` (``{ring: [(x, y, owner), ...]}``) put in."""
    take = np.zeros(len(lengths) - 1, dtype=np.bool_)
    size = np.zeros(len(lengths) - 1, dtype=np.int64)
    for r, rk in new.items():
        take[r] = True
        size[r] = len(rk) + 1
    lens = np.zeros_like(lengths)
    np.cumsum(size, out=lens[1:])
    coords = np.zeros((int(lens[-1]), 2))
    own = np.full(len(coords), -2, dtype=owner.dtype)
    for r, rk in new.items():
        a = int(lens[r])
        for k, (x, y, o) in enumerate(rk):
            coords[a + k] = (x, y)
            own[a + k] = o
        coords[a + len(rk)] = rk[0][:2]
    return splice_rings((closed, lengths, owner), (coords, lens, own), take)
