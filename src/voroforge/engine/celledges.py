"""The shared edges of polygon-clipped cells, read off the clipped cells themselves.

A Voronoi edge that meets a polygon domain's boundary was cut on its own (GEOS's line
overlay, or the exact kernel of :mod:`.polyclip`), and the cells it separates were cut
apart (GEOS's polygon overlay, a redo in a frame at a site or a domain vertex): each
rounds the crossing itself. Far out (a domain 80 ulps wide at 7e14, issue 15) a crossing
0.39 ulp from a domain vertex rounded onto it in one and not the other, and edge ends lay
off their cells' vertices. Here the edge between cells ``i`` and ``j`` is what their
clipped rings share: the segments of ``i``'s rings whose reverse is a segment of ``j``'s,
bit for bit, joined into runs along ``i``'s ring, so every end is a vertex of both cells.
"""

from __future__ import annotations

import numpy as np


def shared_pieces(bufs, pairs):
    """Pieces of boundary that clipped cells ``pairs[k] = (i, j)`` share.

    Parameters
    ----------
    bufs : tuple
        GeoArrow multipolygon buffers ``(coords, ring, poly, geom)`` of the clipped cells
        (shells counter-clockwise, holes clockwise).
    pairs : (m, 2) int64
        Cell pairs, ``i < j``.

    Returns
    -------
    piece : (r, 2, 2) float64
        Each shared run of segments as one piece, in the direction of cell ``i``'s ring,
        its ends vertices of both cells; grouped by pair, in ``pairs``' order.
    idx : (r,) int64
        The pair of each piece.
    found : (m,) bool
        Whether the two cells share any segment.
    """
    coords, ring_off, poly_off, geom_off = bufs
    m = len(pairs)
    empty = (np.zeros((0, 2, 2)), np.zeros(0, dtype=np.int64), np.zeros(m, dtype=np.bool_))
    if not m:
        return empty
    n = len(geom_off) - 1
    want = np.zeros(n, dtype=np.bool_)
    want[pairs.ravel()] = True
    poly_cell = np.repeat(np.arange(n, dtype=np.int64), np.diff(geom_off))
    ring_cell = np.repeat(poly_cell, np.diff(poly_off))
    rings = np.flatnonzero(want[ring_cell] & (np.diff(ring_off) > 1))
    lens = ring_off[rings + 1] - ring_off[rings] - 1  # segments of each closed ring
    total = int(lens.sum())
    if not total:
        return empty
    first = np.zeros(len(rings), dtype=np.int64)
    np.cumsum(lens[:-1], out=first[1:])
    pos = np.repeat(ring_off[rings] - first, lens) + np.arange(total)
    ring = np.repeat(np.arange(len(rings)), lens)
    cell = ring_cell[rings][ring]
    xy = coords + 0.0  # (-0.0 and 0.0 are one point)
    a = xy[pos].view(np.int64)
    b = xy[pos + 1].view(np.int64)
    keys = np.concatenate((np.hstack((a, b)), np.hstack((b, a))))
    _, inv = np.unique(keys, axis=0, return_inverse=True)
    inv = inv.ravel()
    by_fwd = np.full(int(inv.max()) + 1, -1, dtype=np.int64)
    by_fwd[inv[:total]] = np.arange(total)
    other = by_fwd[inv[total:]]  # the segment that runs back along each one, or -1
    has = other >= 0
    mate = np.where(has, cell[np.maximum(other, 0)], -1)
    lower = has & (mate > cell)
    code = pairs[:, 0].astype(np.int64) * n + pairs[:, 1]
    order = np.argsort(code, kind="stable")
    sorted_code = code[order]
    seg_code = cell * n + mate
    at = np.minimum(np.searchsorted(sorted_code, seg_code), m - 1)
    hit = lower & (sorted_code[at] == seg_code)
    segs = np.flatnonzero(hit)
    if not len(segs):
        return empty
    pair = order[at[segs]]
    srt = np.lexsort((pos[segs], pair))
    segs, pair = segs[srt], pair[srt]
    # runs: consecutive segments of one ring shared with one cell
    new = np.ones(len(segs), dtype=np.bool_)
    new[1:] = (pair[1:] != pair[:-1]) | (pos[segs][1:] != pos[segs][:-1] + 1)
    starts = np.flatnonzero(new)
    ends = np.r_[starts[1:], len(segs)] - 1
    head = segs[starts]
    tail = segs[ends]
    keep = np.ones(len(starts), dtype=np.bool_)
    # a run through a ring's closing vertex: its two parts (the ring's last segment, then
    # its first) are one piece
    r_first = ring_off[rings][ring]
    r_last = r_first + lens[ring] - 1
    opens = {
        (int(ring[head[q]]), int(pair[starts[q]])): q
        for q in np.flatnonzero(pos[head] == r_first[head])
    }
    for k in np.flatnonzero(pos[tail] == r_last[tail]):
        q = opens.get((int(ring[tail[k]]), int(pair[starts[k]])), -1)
        if q >= 0 and q != k and keep[q]:
            tail[k] = tail[q]  # the piece runs on past the closing vertex to q's end
            keep[q] = False
    piece = np.stack((xy[pos[head]], xy[pos[tail] + 1]), axis=1)[keep]
    idx = pair[starts][keep]
    found = np.zeros(m, dtype=np.bool_)
    found[idx] = True
    return piece, idx, found


def ends_on_cells(bufs, piece, pairs):
    """Which pieces ``(r, 2, 2)`` end at vertices of both their cells ``pairs (r, 2)``.

    For the few edges whose clipped cells share no segment (rings that did not meet edge
    to edge before the clip: sites a few ulps apart far out, left unresolved): a piece cut
    on its own that does not end at both cells' vertices separates nothing they share (an
    edge of an empty cell included, which :func:`.edgeowners.reown` would give to the cell
    holding it).
    """
    coords, ring_off, poly_off, geom_off = bufs
    keep = np.zeros(len(piece), dtype=np.bool_)
    seen = {}

    def points(c):
        if c not in seen:
            lo = ring_off[poly_off[geom_off[c]]]
            hi = ring_off[poly_off[geom_off[c + 1]]]
            seen[c] = set(map(tuple, (coords[lo:hi] + 0.0).tolist()))
        return seen[c]

    for k in range(len(piece)):
        ends = [tuple(q) for q in (piece[k] + 0.0).tolist()]
        i, j = int(pairs[k, 0]), int(pairs[k, 1])
        keep[k] = all(q in points(i) and q in points(j) for q in ends)
    return keep
