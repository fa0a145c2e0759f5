"""The chord test of the periodic margin's proof (:func:`.periodic._proved`).

A Voronoi vertex ``v`` of a kept cell, at distance ``r`` from its site, is proved when no copy
of a site left out of the diagram (past the grown box's margin on an axis ``k``) lies inside
its empty disk. Such a copy is at least ``room`` from ``v`` on axis ``k``, so it can only be
inside where its other coordinate is within the chord's half-length ``c = sqrt(r^2 -
room^2)`` of ``v``'s. Every copy's other coordinate is a site's plus whole periods:

- where no site's falls in that interval (grown by ``slack`` for the rounded sums), no copy
  past the margin is inside the disk (sites on one line: their cells reach half a period
  across it, and the line's own copies never enter the disks, so the margin along the line
  stays a few cells wide);
- where a few sites' do (a site off the line: its coordinate lies in the chords of the
  line's long disks), those sites' copies past the margin are measured one by one: the
  nearest of them on axis ``k`` and the nearest copy on the other axis bound the distance
  from below (:func:`_far_enough`). Before this a single site off a line of 1e5 failed the
  test for every vertex near the box's sides, and the margin along the line grew to 1.4
  periods: 5.9 n copies, not 3 n.
"""

from __future__ import annotations

import numpy as np

from ..config import PERIODIC_CHORD_SITES

# -> config: the most box shifts the exact disk test lists copies of (7 x 7: a margin and a
# radius of up to ~2.5 periods on each axis); past it the test is not tried
PERIODIC_DISK_SHIFTS = 49


def chord_clear(v, r2, room, sites, box, k, m, side, slack, which):
    """Where no copy past the margin ``m`` of axis ``k`` can lie in the vertex's empty disk.

    Parameters
    ----------
    v : (p, 2) float64
        The vertices.
    r2, room : (p,) float64
        Squared radius of each vertex's empty disk (rounding allowance included), and its
        room to the margin's nearer side on axis ``k``, both in units of ``side``.
    sites : (n, 2) float64
        The sites, in the box.
    box : (xmin, ymin, xmax, ymax)
    k : int
        The axis.
    m : float
        The margin on axis ``k``.
    side : float
        The box's longer side (the unit of ``r2`` and ``room``).
    slack : float
        The rounding of the copies' coordinates.
    which : (p,) bool
        The vertices to test.

    Returns
    -------
    (p,) bool
        True where proved.
    """
    out = np.zeros(len(v), dtype=bool)
    j = 1 - k
    lo, hi = box[j], box[j + 2]
    h = hi - lo
    idx = np.flatnonzero(which)
    c = side * np.sqrt(np.maximum(r2[idx] - room[idx] * room[idx], 0.0)) + 2.0 * slack
    short = 2.0 * c < h
    idx, c = idx[short], c[short]
    if not len(idx):
        return out
    order = np.argsort(sites[:, j], kind="stable")
    ys = sites[order, j]
    start = v[idx, j] - c
    base = start - np.floor((start - lo) / h) * h  # in [lo, hi), to rounding
    spans = []
    for t in (-1.0, 0.0, 1.0):  # the interval and its neighbours by a period: rounding
        a = base + t * h - slack
        z = base + t * h + 2.0 * c + slack
        spans.append((np.searchsorted(ys, a, side="left"), np.searchsorted(ys, z, side="right")))
    count = sum(np.maximum(b - a, 0) for a, b in spans)
    out[idx[count == 0]] = True
    few = (count > 0) & (count <= PERIODIC_CHORD_SITES)
    if few.any():
        pv, ps = [], []
        for a, b in spans:
            n = np.maximum(b - a, 0)[few]
            first = a[few]
            pv.append(np.repeat(np.flatnonzero(few), n))
            ps.append(np.repeat(first - np.cumsum(n) + n, n) + np.arange(int(n.sum())))
        pv = np.concatenate(pv)
        ps = order[np.concatenate(ps)]
        vi = idx[pv]
        clear = _far_enough(v[vi], r2[vi], sites[ps], box, k, m, side, slack)
        bad = np.bincount(pv, weights=~clear, minlength=len(idx)) > 0
        out[idx[few & ~bad]] = True
    return out


def _far_enough(v, r2, s, box, k, m, side, slack):
    """Whether every copy of site ``s`` past the margin ``m`` of axis ``k`` is outside the disk.

    Pairs of vertices ``v`` (squared radii ``r2``, in units of ``side``) and sites ``s`` in
    the box. On axis ``k`` the copies past the margin are ``s + t P`` outside ``[a - m, b +
    m]`` (``P`` the period); the margin is at most ~1.6 periods, so the nearest of them on
    each side has ``|t| <= 4``. On the other axis every copy ``s + u Q`` may be the one, so the
    nearest is taken. Distances are shortened by ``slack`` (rounded sums) and a copy within
    ``slack`` of the margin counts as past it: a lower bound of the true distance.
    """
    j = 1 - k
    a, b = box[k] - m, box[k + 2] + m
    period = box[k + 2] - box[k]
    if m > 2.5 * period:  # the nearest copies past the margin may have |t| > 4
        return np.zeros(len(v), dtype=bool)
    dk = np.full(len(v), np.inf)
    for t in range(-4, 5):
        if t == 0:
            continue
        q = s[:, k] + t * period
        past = (q < a + slack) | (q > b - slack)
        dk = np.where(past, np.minimum(dk, np.abs(v[:, k] - q)), dk)
    q_period = box[j + 2] - box[j]
    u = np.mod(v[:, j] - s[:, j], q_period)
    dj = np.minimum(u, q_period - u)
    dk = np.maximum(dk - 2.0 * slack, 0.0) / side
    dj = np.maximum(dj - 2.0 * slack, 0.0) / side
    return dk * dk + dj * dj >= r2


# The exact disk test (perlines2). The chord test above fails where many sites' other
# coordinates fall in a disk's chord though none of their copies is in the disk (sites on a
# sloped line: every chord holds thousands), and the shortfall then asked for the disk's
# whole radius past the margin on that axis (a vertical line plus one site off it: 1.34
# periods of y, 7 n copies where 3 n are proved). Here the copies left out of the diagram
# (past the grown box) near it are listed and each failing vertex's disk is searched for
# them: a vertex is proved when its disk holds none, and a failing vertex asks for the
# margins that take in the ones it holds, no more.
#
# The bound: a cell of the diagram of the copies ``S`` kept, not cut by the grown box, is
# the convex hull of its vertices. A copy ``q`` left out cuts the torus cell of ``p`` only
# where its half-plane ``|x - q| < |x - p|`` meets that hull, that is at a vertex ``v``:
# ``|v - q| < |v - p| = r``. So no copy outside every vertex's disk can matter, and a copy
# in a disk lies within ``r`` of the grown box: only the copies within the largest failing
# radius of the box are listed.


def _left_out(sites, box, margin, reach):
    """The copies of ``sites`` left out of the diagram, within ``reach`` of the grown box.

    Left out as by ``periodic._images`` with ``margin``: outside the grown box, by the same
    float sums.
    """
    x0, y0, x1, y1 = box
    mx, my = margin
    w = x1 - x0
    h = y1 - y0
    ax = int(np.ceil((mx + reach) / w)) + 1
    ay = int(np.ceil((my + reach) / h)) + 1
    if (2 * ax + 1) * (2 * ay + 1) > PERIODIC_DISK_SHIFTS:
        return None  # a thin box's short side: its bracket test proves it, not this
    out = [np.zeros((0, 2))]
    for a in range(-ax, ax + 1):
        for b in range(-ay, ay + 1):
            if not (a or b):
                continue
            t = np.array([a * w, b * h])
            # the copies past the far side of the grown box by reach are out of every disk
            if x0 + t[0] > x1 + mx + reach or x1 + t[0] < x0 - mx - reach:
                continue
            if y0 + t[1] > y1 + my + reach or y1 + t[1] < y0 - my - reach:
                continue
            img = sites + t  # the sum _images keeps or leaves out
            x, y = img[:, 0], img[:, 1]
            kept = (x >= x0 - mx) & (x <= x1 + mx) & (y >= y0 - my) & (y <= y1 + my)
            near = (
                (x >= x0 - mx - reach)
                & (x <= x1 + mx + reach)
                & (y >= y0 - my - reach)
                & (y <= y1 + my + reach)
            )
            out.append(img[near & ~kept])
    return np.concatenate(out)


def _in_disks(v, r, sites, box, margin, slack, few):
    """The copies left out that lie in the disks ``(v, r)``, at most ``few + 1`` a disk.

    Returns ``(count (p,), copies (p, few + 1) int64 into q, q)``: the nearest of them first,
    ``count`` capped at ``few + 1`` (a k-nearest search: a disk over a copied line of sites
    holds thousands, and counting them all cost more than the builds).
    """
    from scipy.spatial import cKDTree

    rad = r + 4.0 * slack  # the copies and the vertices are rounded sums
    q = _left_out(sites, box, margin, float(rad.max()))
    k = few + 1
    if q is None:  # not searched: every disk counts as holding more than ``few``
        return np.full(len(v), k, dtype=np.int64), np.full((len(v), k), -1, dtype=np.int64), q
    if not len(q):
        return np.zeros(len(v), dtype=np.int64), np.zeros((len(v), k), dtype=np.int64), q
    bound = float(rad.max()) * (1.0 + 2.0**-40)  # the search's bound is strict
    dist, at = cKDTree(q).query(v, k=k, distance_upper_bound=bound)
    dist, at = dist.reshape(len(v), k), at.reshape(len(v), k)
    inside = dist <= rad[:, None]
    return inside.sum(axis=1), np.where(inside, at, -1), q


def disks_clear(v, r, sites, box, margin, slack, which):
    """Where no copy left out of the diagram lies in the vertex's empty disk.

    ``r``: each vertex's distance to its site, rounding allowance included (in the box's
    units). Only for the vertices ``which``, each strictly inside the grown box on both axes
    (a vertex on its side is where the box cut a cell off: the cell may go on past it).
    """
    out = np.zeros(len(v), dtype=bool)
    idx = np.flatnonzero(which)
    if not len(idx):
        return out
    count, _, _ = _in_disks(v[idx], r[idx], sites, box, margin, slack, 0)
    out[idx[count == 0]] = True
    return out


def disk_asks(v, r, sites, box, margin, slack, which, few):
    """How many copies left out each disk ``which`` holds (capped at ``few + 1``), and asks.

    The asks: per axis, how far past the box's side the copies in the disks holding at most
    ``few`` lie (0.0 where none).
    """
    idx = np.asarray(which)
    count, at, q = _in_disks(v[idx], r[idx], sites, box, margin, slack, few)
    at = at[(count > 0) & (count <= few)]
    at = at[at >= 0]
    if not len(at):
        return count, [0.0, 0.0]
    q = q[at]
    x0, y0, x1, y1 = box
    past_x = np.maximum(x0 - q[:, 0], q[:, 0] - x1).max()
    past_y = np.maximum(y0 - q[:, 1], q[:, 1] - y1).max()
    return count, [max(float(past_x), 0.0), max(float(past_y), 0.0)]
