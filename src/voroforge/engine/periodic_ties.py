"""Unwrapped periodic cells whose vertex copies by box shifts are exact shifts of each other.

A vertex of an original cell near one side of the box and its image in the cell of a site
near the opposite side are computed from different copies of the sites. They agree up to
the exact shift only where every copy is an exact shift of its site and the box lies on
one float grid; elsewhere (a box at the origin: ``0.12156171 + 1`` is a rounded sum) they
can be an ulp or two apart, and the cells leave a gap or an overlap of that much between a
vertex and its image. :func:`tie_images` makes each such class of copies one value shifted
by whole periods, exactly, wherever floats can hold it. A vertex and its images are found
by their names, the cells around them (:func:`_names`), and else by distance.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import shapely

from ..config import PERIODIC_AREA_NOISE_ULPS, PERIODIC_NAME_REACH_SLACK, PERIODIC_TIE_ULPS
from .periodic_frame import two_sum_error, whole_times


def tie_images(bufs, box, copies=None):
    """The original cells with every vertex an exact shift of its images, where floats allow.

    Points within ``PERIODIC_TIE_ULPS`` ulps of each other modulo the box (ulps of the
    copies' coordinates, the box grown by a period), one of them outside the box and not
    already an exact shift of the other, are one class. On each axis a class takes the
    value of one member shifted by whole periods: the member in the box (else the first),
    where every such shift is a float without rounding (always on one grid), else the member
    farthest from zero, whose floats are the coarsest: its value less whole periods is a
    float wherever the box's size is a multiple of its ulp (a unit box at the origin). A
    class where neither is exact keeps its points on that axis. A period that is no float
    (the box (0.3, 1.3): 1.3 - 0.3 rounds) is taken exactly, the shifts in rationals. A
    group with two points of one ring in one copy of the box is left alone (two vertices of
    a cell an ulp apart, not a vertex and its image). Rounding centres half-way between two
    floats goes opposite ways for an odd shift (a box 1 x 1e-5 at 1e6, one site: its cell 1
    ulp taller than the box): tied the same way.

    The result is kept only where it does not make the cells worse: their areas no farther
    from the box's, every changed ring valid and no ring's orientation flipped (at 1e15, a
    box 24 ulps wide, points that close are distinct vertices).

    ``copies = (full, sites, source, shift)``: the buffers of the whole diagram of the
    copies, its sites, and each copy's site and box shift. A vertex is then also tied to
    the vertices of other original cells that have the same cells around it shifted by
    whole periods (:func:`_names`), however far apart the two were computed: where a
    vertex's sites are close beside a long bisector, a rounded copy moves it by many ulps
    (18 ulps of 0.9 in a 3 x 2 box at the origin, 2000 sites: beyond any distance that tells
    an image from a neighbouring vertex).
    """
    coords, ring, poly, geom = bufs
    if not len(coords):
        return bufs
    x0, y0, x1, y1 = box
    lo = np.array([x0, y0])
    size = np.array([x1 - x0, y1 - y0])
    outside = ((coords < lo) | (coords >= lo + size)).any(axis=1)
    if not outside.any():
        return bufs
    # a point outside lies at most ``depth`` past a side, its partners in the box as near
    # the opposite side: only those points are looked at (a few per cent of them)
    past = np.maximum(lo - coords[outside], coords[outside] - (lo + size)).max(axis=0)
    grown = np.abs(np.concatenate((lo - size, lo + 2.0 * size))).max()
    tol = PERIODIC_TIE_ULPS * np.spacing(grown)
    reach = np.maximum(past, 0.0) + 4.0 * tol
    band = ((coords - lo <= reach) | (lo + size - coords <= reach)).any(axis=1)
    cand = np.flatnonzero(outside | band)
    rid = np.searchsorted(ring, cand, side="right") - 1
    named = None
    if copies is not None:
        pid = np.searchsorted(poly, rid, side="right") - 1
        cell = np.searchsorted(geom, pid, side="right") - 1
        named = _names(coords[cand], cell, copies, lo, size, reach)
    out = _tie_points(coords[cand], rid, lo, size, tol, (x0, y0, x1, y1), named)
    if out is None:
        return bufs
    moved = np.flatnonzero((out != coords[cand]).any(axis=1))
    new = coords.copy()
    new[cand[moved]] = out[moved]
    # kept only where it helps: at 1e15 (a box 24 ulps wide, cells of an ulp or two) points
    # that close are distinct vertices, and joining them broke cells
    changed = np.unique(rid[moved])
    sub = _rings_at(ring, changed)
    before = ring_area(coords[sub[0]], sub[1], lo, size)
    after = ring_area(new[sub[0]], sub[1], lo, size)
    rings = shapely.linearrings(
        new[sub[0]], indices=np.repeat(np.arange(len(changed)), np.diff(sub[1]))
    )
    flipped = np.sign(after) != np.sign(before)
    if not shapely.is_valid(shapely.polygons(rings)).all() or flipped.any():
        return bufs
    # the sums round by an ulp per term: a unit box's cells summed to 1 before and 1 + 2e-16
    # after, their vertices now exact shifts
    noise = PERIODIC_AREA_NOISE_ULPS * np.finfo(np.float64).eps * len(coords)
    delta = np.abs(after).sum() - np.abs(before).sum()
    if abs(delta) > noise:
        total = size[0] / size.max() * (size[1] / size.max())
        was = np.abs(ring_area(coords, ring, lo, size)).sum()
        if abs(was + delta - total) > abs(was - total) + noise:
            return bufs
    return new, ring, poly, geom


def _rings_at(ring, which):
    """``(points, offsets)``: the indices of the points of the rings ``which``, and theirs."""
    length = ring[which + 1] - ring[which]
    offsets = np.zeros(len(which) + 1, dtype=np.int64)
    np.cumsum(length, out=offsets[1:])
    take = np.repeat(ring[which] - offsets[:-1], length) + np.arange(int(offsets[-1]))
    return take, offsets


def _tie_points(coords, rid, lo, size, tol, box, named=None):
    """The points ``coords`` (of rings ``rid``) with their classes tied, or None if none.

    ``named``: per point, its name by the cells around it and that name's box shift
    (:func:`_names`): points of one name are joined too, or None.
    """
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components
    from scipy.spatial import cKDTree

    x0, y0, x1, y1 = box
    moved = ((coords < lo) | (coords >= lo + size)).any(axis=1)
    q = np.zeros_like(coords)
    c = coords[moved]
    qm = np.floor((c - lo) / size)
    qm = np.where(c - qm * size >= lo + size, qm + 1, qm)  # rounding of the division
    q[moved] = np.where(c - qm * size < lo, qm - 1, qm)
    if named is not None:
        # a named point's copy of the box is its name's: a vertex half-way between floats
        # near a side and its image near the other side can both round into the box (a box
        # 123 ulps tall at 2e12: a cell bordering its own image with vertices at 0 and 122)
        q = _named_copies(named, q)
        moved = (q != 0).any(axis=1)
    inner = coords - q * size  # exact on one grid; else rounded, used to find the pairs
    # the periods exactly: (0.3, 1.3) is not a float apart (its size rounds)
    period = (Fraction(x1) - Fraction(x0), Fraction(y1) - Fraction(y0))
    rel = np.minimum(inner - lo, size)  # in [0, size]
    rel = np.where(rel < 0, np.minimum(rel + size, size), rel)  # a named point past a side
    rel = np.where(rel >= size, 0.0, rel)
    pairs = cKDTree(rel, boxsize=size).query_pairs(tol, p=np.inf, output_type="ndarray")
    pairs = pairs[(moved[pairs[:, 0]] | moved[pairs[:, 1]])]
    pairs = pairs[~_exact_shifts(coords, q, size, period, pairs[:, 0], pairs[:, 1])]
    if named is not None:
        # two vertices named by different cells are different vertices, however near (at
        # 4e12 in a box 1229 ulps tall, two vertices 2 ulps apart joined a vertex's class to
        # its neighbour's, and the whole group was left alone)
        la, lb = named[0][pairs[:, 0]], named[0][pairs[:, 1]]
        pairs = pairs[(la < 0) | (lb < 0) | (la == lb)]
        # every member of a name with a member that is not its first's exact shift
        star, label = _named_pairs(named, q)
        off = ~_exact_shifts(coords, q, size, period, star[:, 0], star[:, 1])
        pairs = np.concatenate((pairs, star[np.isin(label, label[off])]))
    if not len(pairs):
        return None
    m = len(coords)
    graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(m, m))
    _, label = connected_components(graph, directed=False)
    touched = np.unique(pairs.ravel())
    # every member of the touched groups, by group
    group = np.unique(label[touched])
    members = np.flatnonzero(np.isin(label, group))
    members = members[np.argsort(label[members], kind="stable")]
    g = np.searchsorted(group, label[members])
    # two different points of one ring in one copy of the box: an ulp-short edge, not the
    # rounding of one vertex
    skip = np.zeros(len(group), dtype=bool)
    skip[_split_groups(g, rid[members], q[members], coords[members])] = True
    out = coords.copy()
    home = ~moved[members]
    # the first member in the box, else the first member
    first = _first_where(g, home, len(group), members)
    for k in range(2):
        done = skip.copy()
        far = _farthest(g, np.abs(coords[members, k]), len(group), members)
        for rep in (first, far):
            r = rep[g]
            val, ok = _shifted(coords[r, k], q[members, k] - q[r, k], size[k], period[k])
            good = np.bincount(g, weights=~ok, minlength=len(group)) == 0
            take = good[g] & ~done[g]
            out[members[take], k] = val[take]
            done |= good
    if not (out != coords).any():
        return None
    return out


def _split_groups(g, rid, q, coords) -> np.ndarray:
    """The groups ``g`` with two different ``coords`` of one ring ``rid`` in one box copy ``q``.

    Floats compared as values (``-0.0 == 0.0``). One lexsort of the rows, not two
    ``np.unique(axis=0)`` of them (their structured sorts were 0.09 s of 3e4 sites on a
    vertical line).
    """
    if not len(g):
        return np.zeros(0, dtype=np.int64)
    # + 0.0: -0.0 becomes 0.0, one value as in a float comparison
    cols = (q[:, 0] + 0.0, q[:, 1] + 0.0, coords[:, 0] + 0.0, coords[:, 1] + 0.0)
    order = np.lexsort((cols[3], cols[2], cols[1], cols[0], rid, g))
    head = np.zeros(len(g) - 1, dtype=bool)  # a new (g, rid, q) after each row
    for c in (g, rid, cols[0], cols[1]):
        s = c[order]
        head |= s[1:] != s[:-1]
    same = ~head
    for c in cols[2:]:
        s = c[order]
        same &= s[1:] == s[:-1]
    # within one (g, rid, q), a row that differs from the one before: two points
    split = ~head & ~same
    return np.unique(g[order][1:][split]).astype(np.int64)


def _exact_shifts(coords, q, size, period, a, b) -> np.ndarray:
    """Whether the points ``b`` are the points ``a`` shifted by their periods, exactly."""
    ok = np.ones(len(a), dtype=bool)
    for k in range(2):
        val, exact = _shifted(coords[a, k], q[b, k] - q[a, k], size[k], period[k])
        ok &= exact & (val == coords[b, k])
    return ok


def _shifted(x, t, w, period):
    """``x + t period`` on one axis, and where that is a float without rounding.

    ``w`` is the period rounded; where it is exact, in floats, else in rationals (few
    points: those near the box's sides).
    """
    if period == w:
        shift = t * w
        return x + shift, whole_times(t, w) & (two_sum_error(x, shift) == 0)
    val = np.zeros(len(x))
    ok = np.zeros(len(x), dtype=bool)
    for i, (xi, ti) in enumerate(zip(x.tolist(), t.tolist(), strict=True)):
        exact = Fraction(xi) + int(ti) * period
        val[i] = float(exact)
        ok[i] = Fraction(val[i]) == exact
    return val, ok


def _first_where(g, mask, n, members):
    """Per group of ``n``: the first of ``members`` where ``mask`` (the first if none)."""
    at = np.searchsorted(g, np.arange(n))
    idx = np.flatnonzero(mask)
    groups, first = np.unique(g[idx], return_index=True)
    at[groups] = idx[first]
    return members[at]


def _farthest(g, value, n, members):
    """Per group of ``n``: the member with the largest ``value`` (the first of equals)."""
    order = np.lexsort((np.arange(len(g)), -value, g))
    start = np.searchsorted(g[order], np.arange(n))
    return members[order[start]]


def ring_area(coords, ring, lo, size):
    """Signed areas of the rings, in units of the box's longer side squared."""
    side = size.max()
    v = (coords - lo) / side
    nxt = np.roll(v, -1, axis=0)
    cross = v[:, 0] * nxt[:, 1] - v[:, 1] * nxt[:, 0]
    last = ring[1:] - 1  # the closing point: no edge from it to the next ring
    cross[last] = 0.0
    return 0.5 * np.add.reduceat(cross, ring[:-1]) if len(ring) > 1 else np.zeros(0)


def _names(points, owner, copies, lo, size, reach):
    """Each of ``points`` named by the copies whose cells hold it, less a box shift.

    ``points`` are of the original cells ``owner``, within ``reach`` of a side;
    ``copies = ((coords, ring, poly, geom), sites, source, shift)``: the diagram of all the
    copies. A vertex's copies ``(source, shift)`` sorted, less the shift of the first, are the same
    for the vertex and its images by box shifts (the diagram of the copies is the same
    around each, up to rounding that changes no cell); the shift subtracted tells which
    image it is. Returns ``(label (m,), shift (m, 2))``: equal labels name images of one
    vertex; ``-1`` where a point is no vertex of three cells near the sides.
    """
    (coords, ring, poly, geom), sites, source, shift = copies
    label = np.full(len(points), -1, dtype=np.int64)
    ref = np.zeros((len(points), 2), dtype=np.int64)
    if not len(points):
        return label, ref
    # the cells holding a point are those whose sites are as far from it as its own: near
    # the sides (only their points are read, not the whole diagram's)
    orig = np.flatnonzero(~shift.any(axis=1))  # source-major: site i's original copy
    own = sites[orig[owner]]
    dx = points[:, 0] - own[:, 0]
    dy = points[:, 1] - own[:, 1]
    far = float(np.hypot(dx, dy).max())  # (squares overflowed past ~1e154: far read inf)
    grow = reach + far * (1.0 + PERIODIC_NAME_REACH_SLACK)
    hi = lo + size
    near = np.zeros(len(sites), dtype=bool)
    for k in range(2):  # column by column: (n, 2).any(axis=1) is slow
        x = sites[:, k]
        near |= (np.abs(x - lo[k]) <= grow[k]) | (np.abs(x - hi[k]) <= grow[k])
    near = np.flatnonzero(near)
    r0 = poly[geom[near]]
    nr = poly[geom[near + 1]] - r0
    rings = np.repeat(r0 - np.cumsum(nr) + nr, nr) + np.arange(int(nr.sum()))
    npts = np.maximum(ring[rings + 1] - ring[rings] - 1, 0)  # less the closing point
    at = np.repeat(ring[rings] - np.cumsum(npts) + npts, npts) + np.arange(int(npts.sum()))
    cell = np.repeat(np.repeat(near, nr), npts)
    if not len(at):
        return label, ref
    bits = np.ascontiguousarray(coords[at]).view(np.int64)
    src = source[cell]
    sh = shift[cell]
    # by vertex (its bits), then by copy: the copies are numbered by source, then shift
    order = np.lexsort((cell, bits[:, 1], bits[:, 0]))
    bits, src, sh = bits[order], src[order], sh[order]
    step = (bits[1:, 0] != bits[:-1, 0]) | (bits[1:, 1] != bits[:-1, 1])
    start = np.flatnonzero(np.r_[True, step])
    count = np.diff(np.r_[start, len(bits)])
    rows = np.column_stack((src, sh - np.repeat(sh[start], count, axis=0))).astype(np.int64)
    # each point's vertex (its bits among the vertices'), then names for those only
    k = _find_rows(bits[start], np.ascontiguousarray(points).view(np.int64))
    vlabel = np.full(len(start), -1, dtype=np.int64)
    used = np.unique(k[k >= 0])
    # a vertex of c cells: its name's 3 c numbers as one row, equal rows one name; by c
    # (three: most; four: every vertex of sites on one line, whose images make rectangles)
    base = 0
    for c in np.unique(count[used]).tolist():
        if c < 3:
            continue
        these = used[count[used] == c]
        key = rows[start[these][:, None] + np.arange(c)].reshape(len(these), 3 * c)
        order = np.lexsort(key.T[::-1])
        new = np.r_[True, (key[order][1:] != key[order][:-1]).any(axis=1)]
        vlabel[these[order]] = base + np.cumsum(new) - 1
        base = int(vlabel.max()) + 1
    found = k >= 0
    label[found] = vlabel[k[found]]
    ref[found] = sh[start][k[found]]
    return label, ref


def _find_rows(table, rows):
    """Index of each of ``rows`` in ``table`` (``(m, 2)`` int64, distinct rows), or -1."""
    both = np.concatenate((table, rows))
    is_row = np.r_[np.zeros(len(table), dtype=bool), np.ones(len(rows), dtype=bool)]
    order = np.lexsort((is_row, both[:, 1], both[:, 0]))  # a table row before equal rows
    pos = np.arange(len(order))
    last = np.maximum.accumulate(np.where(~is_row[order], pos, -1))
    at = np.zeros(len(order), dtype=np.int64)
    at[order] = pos
    mine = last[at[len(table) :]]
    k = np.where(mine >= 0, order[np.maximum(mine, 0)], -1)
    same = (k >= 0) & (both[np.maximum(k, 0)] == rows).all(axis=1)
    return np.where(same, k, -1)


def _named_copies(named, q):
    """``q`` with each named point's box copy set by its name's shift.

    A name's anchor is its first point in the box (else its first point); the others are
    in the copy of the anchor's box shifted by the difference of their names' shifts.
    """
    label, ref = named
    pts = np.flatnonzero(label >= 0)
    if not len(pts):
        return q
    home = ~(q[pts] != 0).any(axis=1)
    # per name: its points in the box first, each group in order
    pts = pts[np.lexsort((~home, label[pts]))]
    start = np.flatnonzero(np.r_[True, label[pts[1:]] != label[pts[:-1]]])
    anchor = np.repeat(pts[start], np.diff(np.r_[start, len(pts)]))
    out = q.copy()
    out[pts] = q[anchor] + (ref[pts] - ref[anchor])
    return out


def _named_pairs(named, q):
    """Each point of a name paired with the name's first point, and the pairs' names.

    Only where the box copies ``q`` of the two differ by their names' shifts: a point whose
    coordinates put it in another box copy than its name says (a vertex on a side, rounded
    across it) is left to the distance test.
    """
    label, ref = named
    pts = np.flatnonzero(label >= 0)
    if not len(pts):
        return np.zeros((0, 2), dtype=np.int64), pts
    pts = pts[np.argsort(label[pts], kind="stable")]
    start = np.flatnonzero(np.r_[True, label[pts[1:]] != label[pts[:-1]]])
    first = np.repeat(pts[start], np.diff(np.r_[start, len(pts)]))
    a, b = first[first != pts], pts[first != pts]
    agree = ((q[b] - q[a]).astype(np.int64) == ref[b] - ref[a]).all(axis=1)
    return np.column_stack((a[agree], b[agree])).astype(np.int64), label[b[agree]]
