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
