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

Sites whose copies are all in the diagram up to the margins' caps (``extra``: a site off a
line, whose copies cut the line's cells from past a narrow margin) are measured past the
cap instead; :func:`shortfall` names the sites a failing vertex's chord measured, so the
next try takes their copies rather than growing a margin of the whole line.
"""

from __future__ import annotations

import numpy as np

from ..config import (
    PERIODIC_CHORD_SITES,
    PERIODIC_CUT_CELLS,
    PERIODIC_CUT_CELLS_ASK,
    PERIODIC_PROOF_RTOL,
    PERIODIC_SHORTFALL_SLACK,
)


def chord_clear(v, r2, room, sites, box, k, m, side, slack, which, extra=None, culprits=None):
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
    extra : ((n,) bool, float) or None
        Sites whose copies are in the diagram up to the margin ``cap`` on axis ``k``, and
        ``cap``: their copies are measured past it.
    culprits : list or None
        Receives an array of the sites whose measured copies failed a vertex (a vertex of
        many sites in its chord names none).

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
        mp = np.full(len(ps), m) if extra is None else np.where(extra[0][ps], extra[1], m)
        clear = _far_enough(v[vi], r2[vi], sites[ps], box, k, mp, side, slack)
        bad = np.bincount(pv, weights=~clear, minlength=len(idx)) > 0
        out[idx[few & ~bad]] = True
        if culprits is not None:
            culprits.append(ps[~clear])
    return out


def _far_enough(v, r2, s, box, k, m, side, slack):
    """Whether every copy of site ``s`` past the margin ``m`` of axis ``k`` is outside the disk.

    Pairs of vertices ``v`` (squared radii ``r2``, in units of ``side``) and sites ``s`` in
    the box. On axis ``k`` the copies past the margin (per pair) are ``s + t P`` outside ``[a
    - m, b + m]`` (``P`` the period); the margin is at most ~1.6 periods, so the nearest of them on
    each side has ``|t| <= 4``. On the other axis every copy ``s + u Q`` may be the one, so the
    nearest is taken. Distances are shortened by ``slack`` (rounded sums) and a copy within
    ``slack`` of the margin counts as past it: a lower bound of the true distance.
    """
    j = 1 - k
    a, b = box[k] - m, box[k + 2] + m
    period = box[k + 2] - box[k]
    if np.max(m) > 2.5 * period:  # the nearest copies past the margin may have |t| > 4
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


def shortfall(v, own, box, margin, sites, slack, extra, most, cell, cut=None):
    """Per axis, the margin the proof's disk test asked for (0.0 where it passed), and sites.

    ``v`` are the kept cells' vertices, ``own`` their sites' copies, ``slack`` the copies'
    rounding, ``extra = (mask, caps)`` the sites whose copies are in to the caps (per
    axis), ``most`` how many sites may be asked for, ``cell`` each vertex's cell (what the
    cut-off cells ask: see the comments below). A vertex that fails on an axis asks
    for its radius past its room there, added to the axis's margin: an estimate (more
    copies move the vertices), not a proof. A vertex the chord test clears on an axis asks
    nothing there (sites on a line and one off it: the first margins hold only the line,
    the off site's cell reaches across the box and asked for 1.4 periods along the line,
    5.9 n copies where 3 n are proved). A vertex whose chord holds a few sites, some of
    whose copies past the margin fail it, asks for those sites instead (returned, an int
    array): their copies to the caps are a few dozen. ``cut`` ((p, 2) bool or None): the
    vertices whose cells the grown box cuts off on each axis elsewhere (wrapped pieces).
    """
    x0, y0, x1, y1 = box
    side = max(x1 - x0, y1 - y0)
    diff = (v - own) / side
    r = np.sqrt(diff[:, 0] * diff[:, 0] + diff[:, 1] * diff[:, 1]) * (1.0 + PERIODIC_PROOF_RTOL)
    # a vertex on the grown box's side is where a cell was cut off, not a vertex: it asks
    # for that axis only (sites on one line: their cells end there until the copies of the
    # line beside it are in, and asked for half a period along the line too)
    axes = ((x0, x1, margin[0]), (y0, y1, margin[1]))
    edge = np.column_stack(
        [
            (v[:, k] <= a - m + slack) | (v[:, k] >= b + m - slack)
            for k, (a, b, m) in enumerate(axes)
        ]
    )
    if cut is not None:
        # ``cut`` (per vertex and axis): its cell is cut off by the grown box there, though
        # the vertex is not on its side (a wrapped piece's corner on the box's side: sites on
        # a vertical line, whose cut-off cells asked for a whole period along the line too)
        edge = edge | cut
    bads, rooms, named = [], [], []
    for k, (a, b, m) in enumerate(axes):
        room = np.minimum(v[:, k] - (a - m), (b + m) - v[:, k])
        bad = (room < (b - a) + slack) & (room / side < r) & ~edge[:, 1 - k]
        if bad.any():
            rs = np.maximum(room, 0.0) / side
            got = []
            ek = (extra[0], extra[1][k])
            bad &= ~chord_clear(v, r * r, rs, sites, box, k, m, side, slack, bad, ek, got)
            got = np.unique(np.concatenate(got)) if got else got
            if 0 < len(got) <= most:
                # those sites' copies to the caps: the vertices they alone failed wait
                more = extra[0].copy()
                more[got] = True
                ek = (more, extra[1][k])
                bad &= ~chord_clear(v, r * r, rs, sites, box, k, m, side, slack, bad, ek)
                named.append(got)
        bads.append(bad)
        rooms.append(room)
    if edge.any():
        # cells cut off by the grown box: the copies past that side are missing, and a vertex
        # failing on both axes may be one they move (a site off a line: the first margins
        # hold only the line, and the line's cells beside the off site's asked for 1.4
        # periods along the line, 5.9 n copies where the next try proves 3 n): it waits
        both = bads[0] & bads[1]
        # so does every vertex of a cell cut off on both axes while others are cut off on
        # one (a site off a vertical line: before the line's copies beside it are in, its
        # cell reaches the grown box's top and bottom and asked for 1.6 periods along the
        # line, 7.7 n copies where 3.6 n are proved)
        cut = [np.unique(cell[edge[:, k]]) for k in range(2)]
        twice = np.intersect1d(cut[0], cut[1])
        if len(twice) and len(twice) < max(len(cut[0]), len(cut[1])):
            both |= np.isin(cell, twice)
        bads = [bad & ~both for bad in bads]
    out = []
    for k, (room, bad, m) in enumerate(zip(rooms, bads, margin, strict=True)):
        bad = bad | (room < 0)
        need = (r[bad] - np.maximum(room[bad], 0.0) / side).max() if bad.any() else 0.0
        out.append(float(m + PERIODIC_SHORTFALL_SLACK * need * side) if bad.any() else 0.0)
        few = np.unique(cell[bad])
        cut_off = 0 < len(few) <= PERIODIC_CUT_CELLS and np.isin(few, cell[edge[:, k]]).all()
        if cut_off and out[k] > PERIODIC_CUT_CELLS_ASK * m:
            # only a few cells, each cut off by the grown box on this axis, not all the
            # line's (the cell of a site off a vertical line, past the box's top by 0.12
            # of its height): the margin doubles, where their radii asked for 1.6 periods
            # (where they ask for more than a few times the margin)
            out[k] = float(2.0 * m)
    sites_asked = np.unique(np.concatenate(named)) if named else np.zeros(0, dtype=np.int64)
    return out, sites_asked
