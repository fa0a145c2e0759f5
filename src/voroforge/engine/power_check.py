"""Power cells where Qhull's lift could not resolve the sites: candidates completed by checks.

Over a cluster far narrower than the box (1e-6 wide 1e3 away, 1e-9 at 1e6) the lifted
paraboloid's curvature is below the lift's rounding: Qhull loses sites and edges there.
:func:`lost_candidates` gives the sites near such places (the *suspects*) their nearest
sites in the lifted space as candidates; :func:`checked_cells` cuts the cells and completes
the candidates of the cells near the suspects until every vertex checks. A cell that no
suspect can reach (a bound on the suspects' power distances over the cell) keeps the
lift's neighbours unchecked: the cost follows the cells near the unresolved places.
"""

from __future__ import annotations

import numpy as np
import shapely
from scipy.spatial import cKDTree

from ..config import (
    POWER_CHECK_ROUNDS,
    POWER_CHECK_ULPS,
    POWER_LOST_NEAR,
    POWER_REACH_RTOL,
    POWER_SETTLE_ROUNDS,
    POWER_SETTLE_ULPS,
)
from ..kernels.clip import rings_convex, tiny_folded
from ..kernels.power import cut_rings, finish_rings
from ..kernels.predicates import orient2d

_EPS = float(np.finfo(float).eps)


def pairs_csr(n, a, b):
    """Symmetric CSR ``(indptr, indices int64)`` of distinct undirected pairs ``a < b``."""
    a = np.asarray(a, dtype=np.int64)
    b = np.asarray(b, dtype=np.int64)
    key = np.concatenate((a * n + b, b * n + a))
    key.sort()  # a plain sort: faster here than np.unique's hashing
    indptr = np.zeros(n + 1, dtype=np.int64)
    np.cumsum(np.bincount(key // n, minlength=n), out=indptr[1:])
    return indptr, key % n


def lost_candidates(x, y, w, idx, centre, a, b, rows):
    """Pairs ``a, b`` and, for the sites ``rows``, their nearest sites in the lifted space.

    ``idx`` are the sites that may have a cell; the lifted space is ``(x, y, sqrt(max w -
    w))`` about ``centre`` (power distances are squared distances there, as in
    ``PowerDiagram.locate``).
    """
    m = len(idx)
    k = min(m, POWER_LOST_NEAR + 1)
    near = np.column_stack((x[idx] - centre[0], y[idx] - centre[1], np.sqrt(w[idx].max() - w[idx])))
    tree = cKDTree(near)
    pos = np.searchsorted(idx, rows)
    nb = tree.query(near[pos], k=k)[1].reshape(len(rows), k)
    a = np.concatenate((a, np.repeat(rows, k)))
    b = np.concatenate((b, idx[nb.ravel()]))
    keep = a != b
    return a[keep], b[keep]


def _slots(cap, cnt):
    """Slab slots of every ring vertex, and the cell of each."""
    cell = np.repeat(np.arange(len(cnt)), cnt)
    start = np.cumsum(cnt) - cnt
    return cap[:-1][cell] + (np.arange(len(cell)) - start[cell]), cell


def _unreached(x, y, w, rings, suspect, active):
    """Cells that no suspect site can beat anywhere (proven), as a mask.

    Cell ``i`` lies within ``r_i`` (its farthest vertex) of its site, where its own power
    distance is at most ``P_i`` (the largest at a vertex: the power distance is convex). A
    suspect ``j`` at distance ``D`` has power distance at least ``(D - r_i)^2 - w_j`` there.
    When that exceeds ``P_i`` for the nearest suspect and the heaviest weight, no missing
    candidate can cut the cell: the lift's neighbours were complete for it.
    """
    sx, sy, _, cap, cnt = rings
    slot, cell = _slots(cap, cnt)
    dx = sx[slot] - x[cell]
    dy = sy[slot] - y[cell]
    d2 = dx * dx + dy * dy
    n = len(x)
    some = cnt > 0
    start = (np.cumsum(cnt) - cnt)[some]
    r2, mag, top = np.zeros(n), np.zeros(n), np.full(n, -np.inf)
    if len(start):
        r2[some] = np.maximum.reduceat(d2, start)
        mag[some] = np.maximum.reduceat(np.maximum(np.abs(sx[slot]), np.abs(sy[slot])), start)
        top[some] = np.maximum.reduceat(d2 - w[cell], start)
    ids = np.flatnonzero(suspect)
    pts = np.column_stack((x, y))
    dist = cKDTree(pts[ids]).query(pts, k=1)[0]
    heavy = float(w[ids].max())
    # each vertex is rounded at its coordinates: widen the cell's radius by that
    r = np.sqrt(r2) + POWER_CHECK_ULPS * _EPS * mag
    gap = np.maximum(dist - r, 0.0)
    low = gap * gap - heavy
    slack = POWER_REACH_RTOL * (dist * dist + r * r + abs(heavy) + np.abs(w))
    proven = (cnt > 0) & (low > top + slack) & ~suspect
    return proven | ((cnt == 0) & ~suspect) | ~active


def _beaten(x, y, w, ids, tree, q, cell, n):
    """Pairs ``(cell, j)`` keys of sites ``j`` that beat or tie ``cell`` at vertices ``q``.

    The sites nearest in power at each vertex (a KD-tree of the lifted sites, as in
    ``locate``; power distances in differences) that lead or tie the cell's own site there,
    within the vertex's rounding. A missed tie is a missed tiny edge (a T-junction); an
    extra candidate costs one cut.
    """
    pts = np.column_stack((x, y))
    rows, k, key = np.arange(len(q)), min(len(ids), POWER_LOST_NEAR), [np.zeros(0, np.int64)]
    while len(rows):  # more sites where all k found lead or tie
        i = cell[rows, None]
        j = ids[tree.query(np.column_stack((q[rows], np.zeros(len(rows)))), k=k)[1]]
        j = j.reshape(len(rows), k)
        di = q[rows] - pts[i[:, 0]]
        dj = q[rows, None, :] - pts[j]
        pi = np.einsum("ij,ij->i", di, di)[:, None] - w[i]
        pj = np.einsum("ijk,ijk->ij", dj, dj) - w[j]
        # a vertex moved by delta changes the difference by 2 delta |p_i - p_j|
        delta = POWER_CHECK_ULPS * _EPS * np.abs(q[rows]).max(axis=1)[:, None]
        gap = np.linalg.norm(pts[j] - pts[i], axis=2)
        band = pj <= pi + 2.0 * delta * gap + POWER_CHECK_ULPS * _EPS * (np.abs(pi) + np.abs(pj))
        bad = band & (j != i)
        i, j = np.broadcast_arrays(i, j)
        key.append(np.minimum(i, j)[bad] * n + np.maximum(i, j)[bad])
        rows, k = (rows[band[:, -1]], min(len(ids), 4 * k)) if k < len(ids) else (rows[:0], k)
    return np.unique(np.concatenate(key))


def checked_cells(x, y, w, box, active, indptr, indices, suspect):
    """Power cells from candidates that may lack neighbours, completed until every vertex checks.

    A cell cut by too few bisectors is larger than the true cell, so one of its vertices
    lies in another site's cell: the sites that beat or tie it there (:func:`_beaten`)
    become candidates both ways, and the cells whose candidates grew are cut again, until
    none is new. Only cells a suspect may reach are checked (:func:`_unreached`), and they
    are cut with every vertex named (``kernels.power._careful_cell``). An empty cell is
    certain: fewer bisectors leave more of the box.

    Returns
    -------
    coords, lengths, owner
        As ``kernels.power.power_cells``.
    """
    n = len(x)
    rows = np.repeat(np.arange(n), np.diff(indptr))
    careful = suspect.copy()
    careful[rows[suspect[indices]]] = True
    zf, zi = np.zeros(0), np.zeros(0, dtype=np.int64)
    rings = cut_rings(x, y, w, indptr, indices, box, active, careful, zf, zf, zi, zi, zi)
    todo = ~_unreached(x, y, w, rings, suspect, active)
    redo = todo & ~careful
    if redo.any():  # cells a suspect may reach, cut with named vertices
        careful |= redo
        rings = cut_rings(x, y, w, indptr, indices, box, redo, careful, *rings)
    ids = np.flatnonzero(active)
    top = float(w[ids].max())
    tree = cKDTree(np.column_stack((x[ids], y[ids], np.sqrt(top - w[ids]))))
    known = np.sort(rows * n + indices)
    for _ in range(POWER_CHECK_ROUNDS):
        sx, sy, _, cap, cnt = rings
        slot, cell = _slots(cap, cnt * todo)
        q = np.column_stack((sx[slot], sy[slot]))
        key = _beaten(x, y, w, ids, tree, q, cell, n)
        both = np.unique(np.concatenate((key, (key % n) * n + key // n)))
        at = np.minimum(np.searchsorted(known, both), len(known) - 1)
        new = both[known[at] != both] if len(known) else both
        if not len(new):
            break
        known = np.sort(np.concatenate((known, new)))
        todo = np.zeros(n, dtype=bool)
        todo[new // n] = True
        todo &= active
        careful |= todo
        keep = known // n < known % n
        indptr, indices = pairs_csr(n, known[keep] // n, known[keep] % n)
        rings = cut_rings(x, y, w, indptr, indices, box, todo, careful, *rings)
    return finish_rings(x, y, *rings)


def settle(box, closed, lengths, owner):
    """The checked path's rings with what float64 cannot hold merged to points.

    In a cluster one to a few ulps of its coordinates wide (1e-10 at 3e5..1e6) the power
    cells are a few ulps across: each cell's named vertices are rounded alone, so a tiny
    ring folds (a self-intersecting polygon), or one cell keeps an edge an ulp long that
    no other ring has (the neighbour's ring went straight past, or compacted away): Euler
    fails. Such places are merged, each to one point shared bit for bit by every ring that
    has one of them: every vertex of a ring at most ``POWER_SETTLE_ULPS`` across that is
    not a valid polygon (``kernels.clip.tiny_folded``), the two ends of an edge that short
    at a right turn of a larger ring that is not valid (a wedge's apex rounded across its
    next vertex), and the two ends of an edge that short that no ring has reversed. Rings
    are compacted (a ring left with no area is empty), and rounds repeat while anything is
    merged. Which sites so emptied have a cell is decided exactly afterwards
    (``engine.power_exact.lost_sites``: ``Diagram.unresolved``). Nothing changes where
    every ring is valid and every short edge shared.
    """
    for _ in range(POWER_SETTLE_ROUNDS):
        groups = _unheld(closed, lengths, owner)
        if not groups:
            break
        closed, lengths, owner = _merge(box, closed, lengths, owner, groups)
    return closed, lengths, owner


def _unheld(closed, lengths, owner):
    """Slot groups to merge (see :func:`settle`): folded rings' rounding, unshared tiny edges."""
    cx, cy = closed[:, 0], closed[:, 1]
    big = np.maximum(np.abs(cx), np.abs(cy))  # (columns: faster than reductions of rows)
    step = np.maximum(np.abs(np.diff(cx)), np.abs(np.diff(cy)))
    short = step <= POWER_SETTLE_ULPS * 2.0 * _EPS * np.maximum(big[:-1], big[1:])
    short &= owner[:-1] != -2
    groups = []
    tiny = tiny_folded(closed, lengths, POWER_SETTLE_ULPS) == 1
    # rings that are not valid polygons (convex ones are: only the others are tested)
    for i in np.flatnonzero(~rings_convex(closed, lengths) & (lengths[1:] > lengths[:-1])):
        lo, hi = lengths[i], lengths[i + 1]
        if shapely.is_valid(shapely.polygons(closed[lo:hi])):
            continue
        if tiny[i]:  # a few ulps across: nothing of it is held
            groups.append(np.arange(lo, hi - 1))
            continue
        # a short edge at a right turn (exact): its ends rounded across each other (a
        # wedge's apex at a cluster an ulp wide)
        m = hi - lo - 1
        for v in range(m):
            p, c, q = lo + (v - 1) % m, lo + v, lo + (v + 1) % m
            if orient2d(*closed[p], *closed[c], *closed[q]) >= 0.0:
                continue
            if short[p] or short[c]:
                e = p if short[p] and not (short[c] and _len(closed, c) < _len(closed, p)) else c
                groups.append(np.array([e, e + 1]))
    # a short bisector edge that no ring has reversed in the same bits (whatever the
    # owners say: a ring emptied by an earlier round still names the edges it bordered)
    _, pid = np.unique(closed, axis=0, return_inverse=True)
    pid = pid.ravel().astype(np.int64)
    edge = owner[:-1] != -2
    key = pid[:-1] * len(closed) + pid[1:]
    back = np.isin(pid[1:] * len(closed) + pid[:-1], key[edge])
    for s in np.flatnonzero((owner[:-1] >= 0) & short & ~back).tolist():
        groups.append(np.array([s, s + 1]))
    return groups


def _len(closed, s):
    """L-infinity length of edge ``s -> s + 1``."""
    return float(np.abs(closed[s + 1] - closed[s]).max())


def _merge(box, closed, lengths, owner, groups):
    """Rings with each group's points (and every copy of them) at one point, compacted.

    The point kept is a box corner, else one on a box side, else the member leaving the
    rings that have one the fewest right turns (:func:`_least_turned`), then the smallest
    bits, so the choice does not depend on the cells' order.
    """
    pts, inv = np.unique(closed, axis=0, return_inverse=True)
    inv = inv.ravel()
    parent = np.arange(len(pts))

    def root(p):
        while parent[p] != p:
            parent[p] = parent[parent[p]]
            p = parent[p]
        return p

    side = (np.isin(pts[:, 0], box[[0, 2]])).astype(np.int64) + np.isin(pts[:, 1], box[[1, 3]])
    for g in groups:
        ids = np.unique(inv[g])
        r = [root(p) for p in ids.tolist()]
        # np.unique sorted the points: the lowest index has the smallest bits
        best = max(r, key=lambda p: (side[p], -p))
        for p in r:
            parent[p] = best
    to = np.array([root(p) for p in range(len(pts))])
    to = _least_turned(pts, inv, lengths, to, side)
    moved = to[inv] != inv
    closed = pts[to[inv]]
    touched = np.zeros(len(lengths) - 1, dtype=bool)
    touched[np.searchsorted(lengths, np.flatnonzero(moved), side="right") - 1] = True
    rings = []
    for i in range(len(lengths) - 1):
        lo, hi = lengths[i], lengths[i + 1]
        if hi == lo or not touched[i]:
            rings.append((closed[lo:hi], owner[lo:hi]))
            continue
        rings.append(_compacted(closed[lo : hi - 1], owner[lo : hi - 1]))
    size = np.array([len(r[0]) for r in rings], dtype=np.int64)
    lengths = np.zeros(len(rings) + 1, dtype=np.int64)
    np.cumsum(size, out=lengths[1:])
    if not lengths[-1]:
        return closed[:0], lengths, owner[:0]
    return np.concatenate([r[0] for r in rings]), lengths, np.concatenate([r[1] for r in rings])


def _least_turned(pts, inv, lengths, to, side):
    """``to`` (each point's class representative) with each class's point chosen again.

    A class merged across several rounds can span tens of ulps: its first-ranked member
    (``to``'s choice: the smallest bits) may sit beyond a larger ring's chord there, which
    then turns right (a wedge's apex moved past its neighbours: non-convex). Each class
    takes, among its members on as many box sides as ``to``'s choice (a box corner or
    side stays), the one leaving the fewest exact right turns in the rings that have one
    of its members (compacted; the other classes at their current choice; a ring that
    passes a point twice counts worst, :func:`_bad_turns`); ties keep ``to``'s choice,
    then the smallest bits.
    """
    size = np.bincount(to, minlength=len(pts))
    slot_ring = np.searchsorted(lengths, np.arange(len(inv)), side="right") - 1
    for r in np.flatnonzero(size > 1).tolist():
        mem = np.flatnonzero(to == r)
        at = np.isin(inv, mem)
        rings = np.unique(slot_ring[at]).tolist()
        best, least = r, None
        for c in [r, *(p for p in mem.tolist() if p != r and side[p] == side[r])]:
            turns = 0
            for i in rings:
                lo, hi = lengths[i], lengths[i + 1] - 1
                idx = to[inv[lo:hi]]
                idx[at[lo:hi]] = c
                turns += _bad_turns(pts[idx])
            if least is None or turns < least:
                best, least = c, turns
        to[mem] = best
    return to


def _bad_turns(xy):
    """Exact right turns of an open ring after dropping repeated points (0: no ring left).

    A point the ring passes twice, or a spike (a straight turn back), counts as many
    turns as the ring has vertices: worse than any choice that leaves the ring simple.
    """
    keep = np.ones(len(xy), dtype=bool)
    keep[1:] = (xy[1:] != xy[:-1]).any(axis=1)
    xy = xy[keep]
    while len(xy) > 1 and (xy[-1] == xy[0]).all():
        xy = xy[:-1]
    m = len(xy)
    if m < 3:
        return 0
    if len(np.unique(xy, axis=0)) < m:
        return m
    bad = 0
    for v in range(m):
        a, b, c = xy[v - 1], xy[v], xy[(v + 1) % m]
        turn = orient2d(*a, *b, *c)
        if turn == 0.0 and ((b - a) * (c - b)).sum() < 0.0:
            return m
        bad += turn < 0.0
    return bad


def _compacted(xy, own):
    """Open ring without repeated points, closed again (empty when no area is left).

    The edge that leaves a dropped point is the kept one's, as in ``kernels.power``.
    """
    keep_xy, keep_o = [], []
    for v in range(len(xy)):
        if keep_xy and (xy[v] == keep_xy[-1]).all():
            keep_o[-1] = own[v]
            continue
        keep_xy.append(xy[v])
        keep_o.append(own[v])
    while len(keep_xy) > 1 and (keep_xy[-1] == keep_xy[0]).all():
        keep_xy.pop()
        keep_o.pop()
    if len(keep_xy) < 3:
        return xy[:0], own[:0]
    r = np.array(keep_xy)
    d = r - r[0]
    if not (d[:-1, 0] * d[1:, 1] - d[1:, 0] * d[:-1, 1]).sum() > 0.0:
        return xy[:0], own[:0]
    return np.vstack((r, r[:1])), np.array([*keep_o, -2], dtype=own.dtype)
