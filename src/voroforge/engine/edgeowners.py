"""Shared edges handed to an empty cell, given to the cell across them.

A builder names the cell across each ring edge from the bisector it cut. Where two bisectors
are one line (a power diagram whose lighter site lies exactly on its heavier neighbours'
radical line: a 4 x 4 lattice with weights 1 and 0 in a checkerboard), the site between them
has an empty cell (a segment or a point) and may be named across the edge of its two
neighbours: the pair ``(0, 1)`` with cell 1 empty where cells 0 and 2 share the edge
(checker35 F1). Such a pair is wrong whatever the builder, so it is mended here, once, on the
diagram's rings: the edge goes to the cell whose ring holds it reversed (bit for bit), or
else holds a segment on its line overlapping it (exact ``orient2d``).

Where a diagram has lost sites, :func:`split_at_junctions` then cuts an edge at a T-junction
(another cell's vertex exactly on it) and adds a side two rings share that no edge covered.
"""

from __future__ import annotations

import math

import numpy as np

from ..kernels.predicates import orient2d


def reown(edges, buffers, n: int):
    """``(coords, pairs)`` of ``edges`` with no pair naming a cell that has no ring.

    ``buffers``: the diagram's GeoArrow ``(coords, ring, poly, geom)``. Returns ``edges``
    itself when every pair names two cells with rings (the usual case: one pass over ``n``).
    """
    seg, pairs = edges
    coords, ring, poly, geom = buffers
    has = np.zeros(n, bool)
    if len(ring) > 1:
        # a cell has a ring when one of its polygons' exterior rings has 4+ points
        ext = poly[:-1]
        full = (ring[ext + 1] - ring[ext]) >= 4
        cell_of_poly = np.searchsorted(geom, np.arange(len(poly) - 1), side="right") - 1
        has[cell_of_poly[full]] = True
    bad = np.flatnonzero(~(has[pairs[:, 0]] & has[pairs[:, 1]]))
    if not len(bad):
        return edges
    # every directed ring edge: its start, end and cell
    k, cell_of = _ring_starts(buffers)
    a_all, b_all = coords[k], coords[k + 1]
    seg = np.array(seg, copy=True)
    pairs = np.array(pairs, copy=True)
    keep = np.ones(len(pairs), bool)
    for e in bad.tolist():
        i, j = (int(c) for c in pairs[e])
        c = i if has[i] else j if has[j] else -1
        if c < 0:
            keep[e] = False  # two empty cells share nothing
            continue
        d = _across(seg[e], c, a_all, b_all, cell_of, has)
        if d < 0:
            continue  # no ring holds it: left as built
        pairs[e] = (min(c, d), max(c, d))
    # a pair mended onto an edge the other cell's ring had given too: once
    return _once(seg[keep], pairs[keep])


def _across(s, c: int, a_all, b_all, cell_of, has) -> int:
    """The cell other than ``c`` whose ring holds the segment ``s`` (2, 2), or -1."""
    p, q = s
    other = (cell_of != c) & has[cell_of]
    exact = other & (a_all == q).all(axis=1) & (b_all == p).all(axis=1)
    if exact.any():
        return int(cell_of[np.flatnonzero(exact)[0]])
    # else a ring edge on the segment's line that overlaps it by more than a point
    d = q - p
    t0 = (a_all - p) @ d
    t1 = (b_all - p) @ d
    L = float(d @ d)
    near = other & (np.maximum(t0, t1) > 0) & (np.minimum(t0, t1) < L)
    for r in np.flatnonzero(near).tolist():
        a, b = a_all[r], b_all[r]
        if orient2d(p[0], p[1], q[0], q[1], a[0], a[1]) == 0 and (
            orient2d(p[0], p[1], q[0], q[1], b[0], b[1]) == 0
        ):
            return int(cell_of[r])
    return -1


def split_at_junctions(edges, buffers, tol: float):
    """``(coords, pairs)`` of ``edges`` cut where another cell's vertex lies on them.

    Beside a lost site (issue 15: float circles of radius 1e-7 at (5e5, 4e6)) a vertex two
    cells share can lie exactly on the straight side of a third cell's ring, which does not
    have it (a T-junction): that side is two shared edges, with a different cell across each,
    but the builder names one cell across the whole side, so the edge ran past the other
    cell's end (an end that is not a vertex of that cell) and the second pair was missing.
    Each edge with an end that is not a vertex of both its cells' rings is cut at the
    vertices of its two cells lying exactly on it (``orient2d``), and each piece is given to
    the two cells whose rings hold it (a ring side containing it, on its line): every end is
    then a vertex of both cells, or lies on the straight side of a ring that passes through
    it. A piece that two rings do not hold (a gap) keeps the edge's pair. Pieces not longer
    than ``tol`` are left out. Returns ``edges`` itself where every end is a vertex of both
    its cells.
    """
    seg, pairs = edges
    coords, ring, poly, geom = buffers
    if not len(seg) or len(coords) < 2:
        return edges
    k, cell_of = _ring_starts(buffers)
    a_all, b_all = coords[k] + 0.0, coords[k + 1] + 0.0
    # each cell's vertices as one sorted key (cell, x bits, y bits)
    vkey = _keys(cell_of, a_all)
    vkey.sort()
    ends = seg + 0.0
    bad = np.zeros(len(seg), bool)
    for side in range(2):
        for e in range(2):
            q = _keys(pairs[:, side], ends[:, e])
            at = np.minimum(np.searchsorted(vkey, q), len(vkey) - 1)
            bad |= vkey[at] != q
    bad = np.flatnonzero(bad)
    # each cell's ring vertices as one slice of ``by_cell`` (not a pass over all per edge)
    by_cell = np.argsort(cell_of, kind="stable")
    first = np.searchsorted(cell_of[by_cell], np.arange(int(cell_of.max(initial=-1)) + 2))
    out_s, out_p, out_i = [], [], []
    keep = np.ones(len(seg), bool)
    for e in bad.tolist():
        i, j = (int(c) for c in pairs[e])
        p, q = ends[e]
        axis = 0 if p[0] != q[0] else 1
        lo, hi = min(p[axis], q[axis]), max(p[axis], q[axis])
        cand = a_all[
            np.concatenate(
                [by_cell[first[c] : first[c + 1]] for c in {i, j} if 0 <= c < len(first) - 1]
                + [by_cell[:0]]
            )
        ]
        inside = (cand[:, axis] > lo) & (cand[:, axis] < hi)
        cuts = {
            (float(v[0]), float(v[1]))
            for v in cand[inside]
            if orient2d(p[0], p[1], q[0], q[1], v[0], v[1]) == 0
        }
        sign = 1.0 if q[axis] > p[axis] else -1.0
        pts = [tuple(p.tolist()), *sorted(cuts, key=lambda v: sign * v[axis]), tuple(q.tolist())]
        pieces = []
        for u, v in zip(pts[:-1], pts[1:], strict=True):
            if math.hypot(v[0] - u[0], v[1] - u[1]) <= tol:
                continue
            held = _holders(u, v, a_all, b_all, cell_of)
            pair = (min(held), max(held)) if len(held) == 2 else (i, j)
            pieces.append(((u, v), pair))
        if len(pieces) == 1 and pieces[0][1] == (i, j) and len(pts) == 2:
            continue  # nothing to cut or re-own: left as built
        keep[e] = False
        out_s += [s for s, _ in pieces]
        out_p += [c for _, c in pieces]
        out_i += [e] * len(pieces)
    if not keep.all():
        # each edge's pieces where the edge was
        at = np.concatenate((np.flatnonzero(keep), np.array(out_i, dtype=np.int64)))
        order = np.argsort(at, kind="stable")
        seg = np.concatenate((seg[keep], np.array(out_s, dtype=np.float64).reshape(-1, 2, 2)))
        pairs = np.concatenate((pairs[keep], np.array(out_p, dtype=np.int64).reshape(-1, 2)))
        seg, pairs = _once(seg[order], pairs[order])
    # a side two rings share that no edge covers (both rings named a lost site's empty
    # cell across it, lower-numbered: neither gave the edge), at the end
    add_s, add_p = _unnamed(seg, pairs, a_all, b_all, cell_of, tol)
    if len(add_s):
        seg, pairs = np.concatenate((seg, add_s)), np.concatenate((pairs, add_p))
    elif keep.all():
        return edges
    return seg, pairs


def _unnamed(seg, pairs, a_all, b_all, cell_of, tol):
    """Ring sides ``(r, 2, 2)`` two cells share that no edge of theirs covers, and pairs.

    A side is shared where one cell's ring holds it and another's holds it reversed, bit for
    bit; an edge of the two covers it where the side lies on it (exact ``orient2d``).
    """
    none = np.zeros((0, 2, 2)), np.zeros((0, 2), dtype=np.int64)
    fwd = _keys(np.zeros(len(a_all), np.int64), np.hstack((a_all, b_all)))
    back = _keys(np.zeros(len(a_all), np.int64), np.hstack((b_all, a_all)))
    order = np.argsort(fwd, kind="stable")
    at = order[np.minimum(np.searchsorted(fwd[order], back), len(fwd) - 1)]
    mate = np.where(fwd[at] == back, cell_of[at], -1)
    shared = np.flatnonzero(mate > cell_of)  # once, from the lower cell's ring
    if not len(shared):
        return none
    d = b_all[shared] - a_all[shared]
    shared = shared[np.hypot(d[:, 0], d[:, 1]) > tol]
    want = _pair_keys(
        np.column_stack((cell_of[shared], mate[shared])), a_all[shared], b_all[shared]
    )
    have = _pair_keys(pairs, seg[:, 0] + 0.0, seg[:, 1] + 0.0)
    have.sort()
    pos = np.minimum(np.searchsorted(have, want), max(len(have) - 1, 0))
    miss = shared[~((have[pos] == want) if len(have) else np.zeros(len(want), bool))]
    out_s, out_p = [], []
    for r in miss.tolist():
        c, m = int(cell_of[r]), int(mate[r])
        u, v = a_all[r], b_all[r]
        same = np.flatnonzero((pairs[:, 0] == c) & (pairs[:, 1] == m))
        if any(_contains(seg[e, 0], seg[e, 1], u, v) for e in same.tolist()):
            continue  # a longer edge of the two along it
        out_s.append((u, v))
        out_p.append((c, m))
    if not out_s:
        return none
    return np.array(out_s, dtype=np.float64), np.array(out_p, dtype=np.int64)


def _pair_keys(pairs, a, b):
    """One sortable key per (pair, undirected segment)."""
    swap = (b[:, 0] < a[:, 0]) | ((b[:, 0] == a[:, 0]) & (b[:, 1] < a[:, 1]))
    lo = np.where(swap[:, None], b, a)
    hi = np.where(swap[:, None], a, b)
    rows = np.column_stack((np.asarray(pairs, np.int64), lo.view(np.int64), hi.view(np.int64)))
    return np.ascontiguousarray(rows).view(np.dtype((np.void, 48))).ravel()


def _contains(p, q, u, v) -> bool:
    """Whether segment ``p q`` contains segment ``u v`` (exact: on its line, within it)."""
    lo, hi = np.minimum(p, q), np.maximum(p, q)
    if not ((lo <= np.minimum(u, v)).all() and (hi >= np.maximum(u, v)).all()):
        return False
    return (
        orient2d(p[0], p[1], q[0], q[1], u[0], u[1]) == 0
        and orient2d(p[0], p[1], q[0], q[1], v[0], v[1]) == 0
    )


def _ring_starts(buffers):
    """Every directed ring edge's start (index into coords) and cell."""
    coords, ring, poly, geom = buffers
    starts = np.ones(len(coords), bool)
    starts[ring[1:] - 1] = False  # a ring's closing point starts no edge
    starts[len(coords) - 1 :] = False
    k = np.flatnonzero(starts)
    ring_of = np.searchsorted(ring, k, side="right") - 1
    poly_of = np.searchsorted(poly, ring_of, side="right") - 1
    cell_of = np.searchsorted(geom, poly_of, side="right") - 1
    return k, cell_of


def _keys(cell, xy):
    """One sortable key per (cell, point or points): the cell and the coordinates' bits."""
    rows = np.column_stack(
        (np.asarray(cell, np.int64), np.ascontiguousarray(xy + 0.0).view(np.int64))
    )
    return np.ascontiguousarray(rows).view(np.dtype((np.void, 8 * rows.shape[1]))).ravel()


def _holders(u, v, a_all, b_all, cell_of):
    """The cells with a ring side on the line of ``u -> v`` that contains the segment."""
    lo = np.minimum(u, v)
    hi = np.maximum(u, v)
    box = (np.minimum(a_all, b_all) <= lo).all(axis=1) & (np.maximum(a_all, b_all) >= hi).all(
        axis=1
    )
    got = set()
    for r in np.flatnonzero(box).tolist():
        a, b = a_all[r], b_all[r]
        if orient2d(a[0], a[1], b[0], b[1], u[0], u[1]) == 0 and (
            orient2d(a[0], a[1], b[0], b[1], v[0], v[1]) == 0
        ):
            got.add(int(cell_of[r]))
    return got


def _once(seg, pairs):
    """Edges with each (pair, undirected segment) once, the first kept, in order."""
    a, b = seg[:, 0], seg[:, 1]
    swap = (b[:, 0] < a[:, 0]) | ((b[:, 0] == a[:, 0]) & (b[:, 1] < a[:, 1]))
    lo = np.where(swap[:, None], b, a)
    hi = np.where(swap[:, None], a, b)
    key = np.column_stack([pairs, lo, hi])
    _, first = np.unique(key, axis=0, return_index=True)
    first.sort()
    return seg[first], pairs[first]
