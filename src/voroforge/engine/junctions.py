"""T-junctions of cells, for :func:`.describe.describe`'s count of edges.

Every ring side of an edge shared by two cells has a partner: the ring on the other side
passes the same two vertices the other way. Rounding can leave a Voronoi vertex on the side
of a cell whose ring does not have it (a T-junction): the cells still tile the domain, but
that edge is one ring side against two, and the count of edges came out one too many (in
the plane: Euler 0 for 1) or short (on a torus, where ``E`` is half the ring sides).

* On a torus (:func:`split`) rounding cells tens of ulps wide put a vertex exactly on the
  straight side of another cell (20,000 sites in a 3 x 2 box at 4e12: two vertices an ulp
  apart, one rounded onto the straight edge of the fourth cell around them).
* In the plane (:func:`split_plane`) a Voronoi vertex of two cells lies within an ulp or two
  of the third cell's side, or exactly on it (nested clusters at (3e3, -2e3): the three
  cells around a vertex, sites 1e-7 apart, leave a triangle 5e-7 long and 2e-13 wide,
  half an ulp there; three sites an ulp apart at a reflex corner of a saw-toothed domain).
  Only sides without a partner are searched (in an ordinary diagram: the domain's sides),
  and only for the ends of other such sides; a vertex farther than
  ``VERTEX_STRAIGHT_ULPS`` ulps of the coordinates from a side (a real gap, a missing cell)
  is left alone, so such a gap still fails Euler's count.

Both put such a vertex into the ring whose side it lies on, so both sides count alike.
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np

from ..config import VERTEX_STRAIGHT_ULPS


def split(coords, ring, idx, nxt, ids, lo, size):
    """The rings with the vertices that lie exactly inside another ring's side put in it.

    Parameters
    ----------
    coords : (m, 2) float64
        Closed rings' points; ``ring`` their offsets.
    idx, nxt : (k,) int64
        The open ring vertices (indices into ``coords``) and, for each, the position in
        ``idx`` of the next one along its ring.
    ids : (k,) int64
        Vertex ids modulo the box (copies of one vertex share an id).
    lo, size : (2,) float64
        The box.

    Returns
    -------
    (coords, ring) or None
        None where every side (between two points) has a partner, or no vertex lies on a
        side without one. Only sides without a partner are searched (few), in rationals.
    """
    a = ids
    b = ids[nxt]
    step = coords[idx[nxt]] - coords[idx] + 0.0  # -0.0 made 0.0
    live = (step != 0).any(axis=1)
    if not live.any():
        return None
    # a side and its partner: the same two vertices the other way, the step's signs
    # opposite (a side can join a vertex to its own image; two sides the same two vertices
    # apart by different steps, on a torus of few cells, are told apart by the signs)
    m = int(ids.max()) + 1
    sign = np.sign(step).astype(np.int64) + 1
    fwd = (a * m + b) * 9 + sign[:, 0] * 3 + sign[:, 1]
    back = (b * m + a) * 9 + (2 - sign[:, 0]) * 3 + (2 - sign[:, 1])
    keys, count = _counted(fwd[live])

    def times(k):
        at = np.minimum(np.searchsorted(keys, k), len(keys) - 1)
        return np.where(keys[at] == k, count[at], 0)

    odd = np.flatnonzero(live & (times(fwd) != times(back)))
    if not len(odd):
        return None
    cand = np.unique(np.concatenate((a[odd], b[odd])))
    first = np.full(int(ids.max()) + 1, -1, dtype=np.int64)
    seen, at_first = np.unique(ids, return_index=True)
    first[seen] = at_first
    w = [Fraction(float(s)) for s in size]
    inserts = {}
    for j in odd:
        p = [Fraction(float(t)) for t in coords[idx[j]]]
        q = [Fraction(float(t)) for t in coords[idx[nxt[j]]]]
        mid = [(p[k] + q[k]) / 2 for k in (0, 1)]
        for v in cand:
            if v == a[j] or v == b[j]:
                continue  # (a vertex whose own image lies on the side: not a junction)
            r = [Fraction(float(t)) for t in coords[idx[first[v]]]]
            # the copy of v nearest the side's middle
            r = [r[k] + w[k] * math.floor((mid[k] - r[k]) / w[k] + Fraction(1, 2)) for k in (0, 1)]
            dpq = (q[0] - p[0], q[1] - p[1])
            dpr = (r[0] - p[0], r[1] - p[1])
            if dpq[0] * dpr[1] != dpq[1] * dpr[0]:
                continue
            along = dpq[0] * dpr[0] + dpq[1] * dpr[1]
            if not 0 < along < dpq[0] ** 2 + dpq[1] ** 2:
                continue
            xy = (float(r[0]), float(r[1]))
            if Fraction(xy[0]) != r[0] or Fraction(xy[1]) != r[1]:
                continue  # the copy there is no float: not a point of these cells
            inserts.setdefault(int(idx[j]), []).append((along, xy))
    if not inserts:
        return None
    at = np.array(sorted(inserts), dtype=np.int64)
    pts = [np.array([xy for _, xy in sorted(inserts[i])]) for i in at]
    extra = np.array([len(t) for t in pts], dtype=np.int64)
    # each inserted run goes after its side's start point
    new = np.insert(coords, np.repeat(at + 1, extra), np.concatenate(pts), axis=0)
    added = np.searchsorted(at, ring, side="left")  # inserts before each ring's start
    shift = np.concatenate(([0], np.cumsum(extra)))
    return new, ring + shift[added]


def split_plane(coords, ring, idx, nxt, ids):
    """The rings with the vertices that lie on another ring's side, up to rounding, put in it.

    Parameters
    ----------
    coords : (m, 2) float64
        Closed rings' points; ``ring`` their offsets.
    idx, nxt : (k,) int64
        The open ring vertices (indices into ``coords``) and, for each, the position in
        ``idx`` of the next one along its ring.
    ids : (k,) int64
        Vertex ids (points merged as one vertex share an id).

    Returns
    -------
    (coords, ring) or None
        None where no side without a partner (the same two vertices the other way) has the
        end of another such side strictly between its ends, within ``VERTEX_STRAIGHT_ULPS``
        ulps of the three points' largest coordinate from it (exactly on it included).
    """
    from scipy.spatial import cKDTree

    a = ids
    b = ids[nxt]
    live = a != b  # (equal points have one id)
    if not live.any():
        return None
    # a side without a partner: its two vertices are the ends of no other live side (an
    # odd number of sides join them)
    m = int(ids.max()) + 1
    key = np.minimum(a, b) * m + np.maximum(a, b)
    keys, count = _counted(key[live])
    paired = keys[count % 2 == 1]
    if len(paired) < 2:
        return None
    at = np.minimum(np.searchsorted(paired, key), len(paired) - 1)
    odd = np.flatnonzero(live & (paired[at] == key))
    ends = np.concatenate((idx[odd], idx[nxt[odd]]))
    end_ids = np.concatenate((a[odd], b[odd]))
    pts, first = np.unique(coords[ends] + 0.0, axis=0, return_index=True)
    pid = end_ids[first]
    p = coords[idx[odd]]
    q = coords[idx[nxt[odd]]]
    big = np.maximum(np.abs(p).max(1), np.abs(q).max(1))
    reach = VERTEX_STRAIGHT_ULPS * np.spacing(big)
    half = 0.5 * np.hypot(*(q - p).T)
    near = cKDTree(pts).query_ball_point(0.5 * (p + q), half * (1 + 1e-9) + reach, p=np.inf)
    sizes = np.fromiter(map(len, near), dtype=np.int64, count=len(near))
    side = np.repeat(np.arange(len(odd)), sizes)
    cand = np.fromiter((j for row in near for j in row), dtype=np.int64, count=len(side))
    keep = (pid[cand] != a[odd][side]) & (pid[cand] != b[odd][side])
    side, cand = side[keep], cand[keep]
    if not len(side):
        return None
    e = q[side] - p[side]
    f = pts[cand] - p[side]
    top = np.maximum(big[side], np.abs(pts[cand]).max(1))
    with np.errstate(all="ignore"):
        cross = np.abs(e[:, 0] * f[:, 1] - e[:, 1] * f[:, 0])
        # within the rounding of the coordinates (a tenth more: the float products' error)
        close = cross <= 1.1 * VERTEX_STRAIGHT_ULPS * np.spacing(top) * np.hypot(*e.T)
    found = {}
    apart = {}  # (side, point): the point's exact distance from the side's line, scaled
    for s_, c_ in zip(side[close], cand[close], strict=True):
        pa = [Fraction(float(t)) for t in p[s_]]
        qa = [Fraction(float(t)) for t in q[s_]]
        va = [Fraction(float(t)) for t in pts[c_]]
        d = (qa[0] - pa[0], qa[1] - pa[1])
        along = d[0] * (va[0] - pa[0]) + d[1] * (va[1] - pa[1])
        if 0 < along < d[0] ** 2 + d[1] ** 2:  # strictly between the side's ends
            found.setdefault(int(s_), []).append((along, int(c_)))
            apart[int(s_), int(c_)] = abs(d[0] * (va[1] - pa[1]) - d[1] * (va[0] - pa[0]))
    # ... and not a vertex of the side's own ring (it would pass that vertex twice)
    for s_ in found:
        j = int(odd[s_])
        r = int(np.searchsorted(ring, idx[j], side="right")) - 1
        lo, hi = np.searchsorted(idx, (ring[r], ring[r + 1]))
        mine = set(ids[lo:hi].tolist())
        found[s_] = [(t, c_) for t, c_ in found[s_] if int(pid[c_]) not in mine]
    found = {s_: row for s_, row in found.items() if row}
    # a junction only where the other rings' sides without a partner cover the side, end to
    # end through such vertices (a T-junction), or pieces of other sides split here do (two
    # sides that cross an ulp from their ends): any other split would add edges, not pair
    # them (a sliver of another cell along the side, ulps thin, is no junction)
    chains = {}
    pieces = {}
    for s_, row in found.items():
        # at one place along the side, the point nearest it first: a vertex exactly on it
        # before one a few ulps off (cells 3 ulps wide at 1e14: a vertex 6 ulps below the
        # side, as far along it as the T-junction's, took its place in the chain)
        row.sort(key=lambda t, s_=s_: (t[0], apart[s_, t[1]], t[1]))
        chain = [int(a[odd[s_]])] + [int(pid[c_]) for _, c_ in row] + [int(b[odd[s_]])]
        chains[s_] = chain
        for u, w in zip(chain[:-1], chain[1:], strict=True):
            pieces.setdefault(min(u, w) * m + max(u, w), set()).add(s_)
    paired = set(paired.tolist())
    paths = {}
    for s_, chain in chains.items():
        path = _cover(chain, lambda k, s_=s_: k in paired or bool(pieces.get(k, set()) - {s_}), m)
        if path:
            paths[s_] = path
    # a vertex found on two sides of one ring (a corner of it an ulp off) goes in neither
    ring_of = np.searchsorted(ring, idx[odd], side="right") - 1
    twice = {}
    for s_, path in paths.items():
        for k in path:
            twice.setdefault((int(ring_of[s_]), chains[s_][k]), []).append(s_)
    for sides in twice.values():
        if len(sides) > 1:
            for s_ in sides:
                paths.pop(s_, None)
    # keep the splits whose pieces are sides without a partner, or pieces of another split
    # kept (until none is left without its support)
    changed = True
    while changed:
        made = {}
        for s_, path in paths.items():
            for k in _steps(chains[s_], path, m):
                made.setdefault(k, set()).add(s_)
        changed = False
        for s_ in list(paths):
            steps = _steps(chains[s_], paths[s_], m)
            if not all(k in paired or made.get(k, set()) - {s_} for k in steps):
                del paths[s_]
                changed = True
    inserts = {}
    for s_, path in paths.items():
        row = found[s_]
        inserts[int(idx[odd[s_]])] = [tuple(pts[row[k - 1][1]]) for k in path]
    if not inserts:
        return None
    at = np.array(sorted(inserts), dtype=np.int64)
    runs = [np.array(inserts[i]) for i in at]
    extra = np.array([len(t) for t in runs], dtype=np.int64)
    new = np.insert(coords, np.repeat(at + 1, extra), np.concatenate(runs), axis=0)
    added = np.searchsorted(at, ring, side="left")
    shift = np.concatenate(([0], np.cumsum(extra)))
    return new, ring + shift[added]


def _counted(keys):
    """``np.unique(keys, return_counts=True)`` by a sort (see :func:`.csr.unique`)."""
    flat = np.sort(keys)
    first = np.ones(len(flat), dtype=bool)
    np.not_equal(flat[1:], flat[:-1], out=first[1:])
    at = np.flatnonzero(first)
    return flat[at], np.diff(np.append(at, len(flat)))


def _cover(chain, paired, m):
    """Inner positions of a path through ``chain`` (in order) from its first to its last.

    Every step's key (``min * m + max`` of its two vertex ids) passes ``paired``; [] where
    no path does. The side itself (first to last) is no step.
    """
    n = len(chain)
    back = [-1] * n
    back[0] = 0
    for j in range(1, n):
        for i in range(j):
            if back[i] < 0 or (i == 0 and j == n - 1) or chain[i] == chain[j]:
                continue
            lo, hi = min(chain[i], chain[j]), max(chain[i], chain[j])
            if paired(lo * m + hi):
                back[j] = i
                break
    if back[n - 1] < 0:
        return []
    path = []
    k = back[n - 1]
    while k != 0:
        path.append(k)
        k = back[k]
    return path[::-1]


def _steps(chain, path, m):
    """The keys of the steps of ``chain`` through the inner positions ``path``."""
    at = [0, *path, len(chain) - 1]
    return [
        min(chain[i], chain[j]) * m + max(chain[i], chain[j])
        for i, j in zip(at[:-1], at[1:], strict=True)
    ]
