"""Structure report of a Voronoi diagram: counts, Euler's formula, unbounded and convex cells.

The cells of a diagram, clipped to a domain ``D``, subdivide it. Count

* ``V``: distinct ring vertices of all cells (Voronoi vertices, points where Voronoi edges
  meet the boundary, and the boundary's own corners), leaving out a vertex that is a
  straight angle in every ring that has it: the middle of an edge, or a T-junction that
  only one side of an edge has,
* ``E``: distinct segments between consecutive corners of a ring (a shared Voronoi edge is
  in the rings of both of its cells and counts once; a boundary segment counts once),
* ``F``: the faces, each polygon part of each cell counting ``1 - h`` for its ``h`` holes
  (an open disk counts 1; a part with holes is not a disk).

Nothing is measured against the domain's size, so the report is the same at every scale and
mix of scales (a 1e-12 cluster beside 1e6 cells, strips a few ulps wide). The engine
computes each vertex once, from its name, so vertices are identified by their bits. Rounding
is merged only where the engine rounds twice: a boundary crossing that one cell rounded onto
another point (an *orphan*: one ring has it; it joins the points at most two rings have
within ``VERTEX_MERGE_ULPS`` ulps of its coordinates), and on a torus a vertex and its image
(within ``VERTEX_RTOL`` of the box's diagonal: images come from sites shifted by the box's
size; points are taken modulo the box by their exact offsets where those are floats). The
report counts the points so merged. A vertex is straight when the exact ``orient2d`` of it
and its ring neighbours is 0; one that only one or two rings have is also straight within
``VERTEX_STRAIGHT_ULPS`` ulps of the coordinates involved (a rounded T-junction), unless
three or more edges meet there in the plane (the end of a sliver where two rings part), and
no turn that small counts against convexity. A vertex of other cells that lies on a cell's side
(exactly on a torus; within ``VERTEX_STRAIGHT_ULPS`` ulps in the plane) where those cells'
sides cover that side end to end is put into its ring first (:mod:`.junctions`), so the side
counts as the edges along it.

Then ``V - E + F = chi(D)``, the Euler characteristic of the domain: the number of its parts
minus the number of its holes (1 for a box). A vertex that one cell has and its neighbour
lacks at a corner, a gap or an overlap breaks the equality, so it checks that the cells fit
together. On a torus (``periodic=True``, unwrapped cells) ``chi = 0``, faces are the cells,
vertices are the cell vertices identified modulo the box, and every edge borders two ring
sides (``E`` is half the ring segments). Cut into the box (``wrap=True``) the pieces
subdivide the box and ``chi = 1``.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

import numpy as np
import shapely

from ..config import (
    CONVEX_DOMAIN_RTOL,
    VERTEX_MERGE_ULPS,
    VERTEX_RTOL,
    VERTEX_STRAIGHT_ULPS,
)
from .csr import unique
from .diagram import domain_of


@dataclass(frozen=True)
class Description:
    """What :meth:`Diagram.describe` reports.

    Attributes
    ----------
    sites : int
        Number of sites (duplicates included).
    cells : int
        Non-empty cells.
    parts : int
        Polygon parts of all cells (a clipped cell can split).
    holes : int
        Holes in the cells (a cell can surround a hole of the domain).
    vertices, edges : int
        ``V`` and ``E`` of the subdivision (see the module description).
    mismatched_vertices : int
        Distinct float64 vertex coordinates that were merged into another vertex because
        they differ from it only by rounding (a boundary crossing rounded differently by
        the two cells beside it, a vertex and its image on a torus; see the module
        description); 0 when neighbouring cells share their vertices bit for bit.
    faces : int
        ``F``: parts minus holes.
    voronoi_edges : int
        Shared edges between two cells (``len(d.edges.pairs)``).
    voronoi_vertices : int
        Vertices that at least three cells share: the Voronoi vertices inside the domain
        (on a torus, all of them).
    euler : int
        ``V - E + F``.
    euler_expected : int
        The domain's Euler characteristic (parts minus holes; 0 on a torus).
    euler_ok : bool
        ``euler == euler_expected``.
    unbounded : int
        Cells that were unbounded before clipping: the distinct sites on the boundary of the
        sites' convex hull, from their Delaunay triangulation (all distinct sites when they
        are collinear; 0 on a torus). For a power diagram this counts the same sites,
        although weights can hide a site that lies inside a hull edge.
    convex_checked : int
        Cells that must be convex: all non-empty cells when the domain is convex (a box),
        else those farther from its boundary than ``100 * VERTEX_RTOL`` of their own
        largest coordinate (with ``wrap=True`` every piece of every cell that does not
        border its own image); never the cell of a site in ``Diagram.unresolved`` (a ring
        that closes the gap its neighbours leave, not the site's Voronoi cell).
    nonconvex : int
        How many of them are not convex (should be 0).
    convex_ok : bool
        ``nonconvex == 0``.
    """

    sites: int
    cells: int
    parts: int
    holes: int
    vertices: int
    edges: int
    mismatched_vertices: int
    faces: int
    voronoi_edges: int
    voronoi_vertices: int
    euler: int
    euler_expected: int
    euler_ok: bool
    unbounded: int
    convex_checked: int
    nonconvex: int
    convex_ok: bool

    def __str__(self) -> str:
        ok = {True: "OK", False: "FAILED"}
        return "\n".join(
            [
                f"sites {self.sites}, non-empty cells {self.cells} "
                f"({self.parts} polygon parts, {self.holes} holes)",
                f"vertices V = {self.vertices}, edges E = {self.edges} "
                f"({self.voronoi_edges} shared between two cells), faces F = {self.faces}",
                f"Voronoi vertices (shared by three or more cells): {self.voronoi_vertices}",
                f"vertex coordinates equal only to rounding: {self.mismatched_vertices}",
                f"Euler: V - E + F = {self.euler}, domain characteristic "
                f"{self.euler_expected}: {ok[self.euler_ok]}",
                f"cells unbounded before clipping (hull sites): {self.unbounded}",
                f"convexity: {self.convex_checked} cells checked, {self.nonconvex} not convex: "
                f"{ok[self.convex_ok]}",
            ]
        )


_EPS = 2.0**-53
#: Shewchuk's orient2d filter: the float determinant's sign is right when its magnitude
#: exceeds this fraction of the sum of its two products' magnitudes
_CCW_BOUND = (3.0 + 16.0 * _EPS) * _EPS
#: products below this may have underflowed (the filter's bound then fails): decided exactly
_TINY = 2.0**-900
#: ring triples whose largest coordinate lies outside (_FAR_LO, _FAR_HI) are scaled first
_FAR_LO = 2.0**-400
_FAR_HI = 2.0**400


def _orient(a: np.ndarray, b: np.ndarray, c: np.ndarray) -> np.ndarray:
    """Exact signs (int8) of ``orient2d(a[k], b[k], c[k])``: positive for a left turn.

    A float filter answers where its error bound proves the sign (every vertex of a
    general-position diagram); the rest, collinear or nearly so, are decided in rationals.
    """
    with np.errstate(all="ignore"):
        acx = a[:, 0] - c[:, 0]
        acy = a[:, 1] - c[:, 1]
        bcx = b[:, 0] - c[:, 0]
        bcy = b[:, 1] - c[:, 1]
        left = acx * bcy
        right = acy * bcx
        det = left - right
        size = np.abs(left) + np.abs(right)
        sure = (np.abs(det) > _CCW_BOUND * size) & (size > _TINY) & (size < np.inf)
    sign = np.zeros(len(det), dtype=np.int8)
    sign[sure] = np.sign(det[sure])
    for k in np.flatnonzero(~sure):
        ax, ay, bx, by, cx, cy = map(Fraction, (*a[k], *b[k], *c[k]))
        v = (ax - cx) * (by - cy) - (ay - cy) * (bx - cx)
        sign[k] = (v > 0) - (v < 0)
    return sign


def _ring_vertices(coords: np.ndarray, ring: np.ndarray):
    """Open ring vertices: ``(idx, rid, turn, flat)``.

    ``idx`` indexes ``coords`` (the closing repeat of each ring left out), ``rid`` is the
    ring, ``turn`` the side the ring turns to at the vertex (+1 left, -1 right, 0 straight:
    the exact ``orient2d`` of the previous vertex, it and the next), ``flat`` True where the
    vertex lies within ``VERTEX_STRAIGHT_ULPS`` ulps of the three points' largest coordinate
    from the chord between its neighbours: straight up to the rounding of those coordinates.
    """
    lengths = np.diff(ring) - 1  # rings are closed: the last vertex repeats the first
    rid = np.repeat(np.arange(len(lengths)), lengths)
    start = np.repeat(ring[:-1], lengths)
    pos = np.arange(len(rid)) - np.repeat(np.cumsum(lengths) - lengths, lengths)
    idx = start + pos
    size = lengths[rid]
    a = coords[start + (pos - 1) % size]
    b = coords[idx]
    c = coords[start + (pos + 1) % size]
    big = np.maximum(np.abs(a).max(1), np.maximum(np.abs(b).max(1), np.abs(c).max(1)))
    # a triple far from 1 is scaled by a power of two to a largest coordinate in [0.5, 1),
    # so its products neither overflow nor underflow (1e300, 1e-300); the scaling is exact
    # unless a coordinate falls below 2**-1074 of the largest (such a triple's turn is then
    # taken on its own coordinates)
    far = np.flatnonzero(~((big > _FAR_LO) & (big < _FAR_HI)))
    sa, sb, sc = a, b, c
    oa, ob, oc = a, b, c
    if len(far):
        ex = np.clip(np.frexp(big[far])[1], -1020, 1024)
        big = big.copy()
        big[far] = np.ldexp(big[far], -ex)
        sa, sb, sc = a.copy(), b.copy(), c.copy()
        oa, ob, oc = a.copy(), b.copy(), c.copy()
        exact = np.ones(len(far), dtype=bool)
        for raw, scaled in ((a, sa), (b, sb), (c, sc)):
            scaled[far] = np.ldexp(raw[far], -ex[:, None])
            exact &= (np.ldexp(scaled[far], ex[:, None]) == raw[far]).all(1)
        for scaled, used in ((sa, oa), (sb, ob), (sc, oc)):
            used[far[exact]] = scaled[far[exact]]
    turn = _orient(oa, ob, oc)
    with np.errstate(all="ignore"):
        e = sb - sa
        f = sc - sb
        cross = e[:, 0] * f[:, 1] - e[:, 1] * f[:, 0]
        reach = VERTEX_STRAIGHT_ULPS * np.spacing(big) * np.hypot(*(sc - sa).T)
        flat = (turn == 0) | (np.abs(cross) <= reach)
    return idx, rid, turn, flat


def _row_keys(xy: np.ndarray) -> np.ndarray:
    """One complex key per row of a ``(m, 2)`` float array (-0.0 made 0.0).

    Complex numbers sort by their real part, then their imaginary part, as rows sort.
    """
    return np.ascontiguousarray(xy + 0.0).view(np.complex128).ravel()


def _unique_rows(xy: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``np.unique(xy, axis=0, return_inverse=True)`` by a sort of complex keys (~8x faster)."""
    keys = _row_keys(xy)
    order = np.argsort(keys)
    ordered = keys[order]
    first = np.ones(len(keys), dtype=bool)
    np.not_equal(ordered[1:], ordered[:-1], out=first[1:])
    inv = np.zeros(len(keys), dtype=np.int64)
    inv[order] = np.cumsum(first) - 1
    return ordered[first].view(np.float64).reshape(-1, 2), inv


def _rings_per_vertex(ids: np.ndarray, rid: np.ndarray) -> np.ndarray:
    """How many distinct rings have each vertex id."""
    k = int(rid.max(initial=0)) + 1
    return np.bincount(unique(ids * k + rid) // k, minlength=int(ids.max(initial=-1)) + 1)


def _vertex_ids(
    pts: np.ndarray, rid: np.ndarray, flat, corners, wrap=None
) -> tuple[np.ndarray, int]:
    """Vertex ids of the ring vertices ``pts`` (ring ``rid``); ``(ids, merged)``.

    Equal bits are one vertex: the engine computes each vertex once, from its name. Rounding
    is merged (single linkage) in two places only. In the plane, an *orphan* (a point that
    only one ring has and turns at, not a corner of the domain: a boundary crossing rounded
    differently by the two cells beside it, such as onto a corner) joins the points that at
    most two rings have within ``VERTEX_MERGE_ULPS`` ulps of its largest coordinate (max
    norm). On a torus (``wrap = (outside, lo, size, tol)``, ``pts`` taken into the box
    ``[lo, lo + size)``, ``outside`` where they were outside the open box) two points closer
    than ``tol`` modulo the box are one when one of them was outside: a vertex and its
    image, computed from sites shifted by the box's size. ``merged`` counts the distinct
    points merged into another.
    """
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components
    from scipy.spatial import cKDTree

    uniq, inv = _unique_rows(pts)
    m = len(uniq)
    if wrap is None:
        rings = _rings_per_vertex(inv, rid)
        few = np.flatnonzero(rings <= 2)
        # an orphan: a point only one ring has, turning there, that is no corner of the
        # domain (a crossing of the boundary is in both cells beside it, a Voronoi vertex in
        # three; a straight one is a T-junction, left out of the graph anyway)
        turning = np.bincount(inv, weights=~flat, minlength=m) > 0
        orphan = few[(rings[few] == 1) & turning[few]]
        if len(corners):
            corner = np.sort(_row_keys(corners))
            key = _row_keys(uniq[orphan])
            at = np.minimum(np.searchsorted(corner, key), len(corner) - 1)
            orphan = orphan[corner[at] != key]
        if not len(orphan):
            return inv, 0
        reach = VERTEX_MERGE_ULPS * np.spacing(np.abs(uniq[orphan]).max(1))
        tree = cKDTree(uniq[few])
        lists = tree.query_ball_point(uniq[orphan], reach, p=np.inf, return_sorted=False)
        sizes = np.fromiter(map(len, lists), dtype=np.int64, count=len(lists))
        src = np.repeat(orphan, sizes)
        dst = np.fromiter((j for row in lists for j in row), dtype=np.int64, count=len(src))
        pairs = np.column_stack((src, few[dst]))
    else:
        outside, lo, boxsize, tol = wrap
        out_u = np.bincount(inv, weights=outside, minlength=m) > 0
        shifted = np.mod(uniq - lo, boxsize)
        shifted[shifted >= boxsize] = 0.0
        tree = cKDTree(shifted, boxsize=boxsize)
        pairs = tree.query_pairs(tol, p=np.inf, output_type="ndarray")
        pairs = pairs[out_u[pairs[:, 0]] | out_u[pairs[:, 1]]]
    graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(m, m))
    count, label = connected_components(graph, directed=False)
    return label[inv].astype(np.int64), int(m - count)


def _box_offsets(raw: np.ndarray, lo: np.ndarray, hi: np.ndarray):
    """The points' exact offsets ``(m, 2)`` in their copies of the box, or None.

    Moving a point into the box by ``lo + mod(raw - lo, size)`` rounds where the box crosses
    a power of two: a vertex below it whose image above is no float landed on another
    vertex (a box 256 x 77 ulps across 2**44: V 57 where the bits give 58). The offsets are
    ``raw - lo - a size`` for whole ``a``, used where every step is exact; None elsewhere.
    """
    from .periodic_frame import periods, two_sum_error

    size = hi - lo
    if any(Fraction(float(hi[k])) - Fraction(float(lo[k])) != size[k] for k in range(2)):
        return None
    out = np.zeros_like(raw)
    for k in range(2):
        r = raw[:, k] - lo[k]
        if two_sum_error(raw[:, k], -lo[k]).any():
            return None
        _, c, exact = periods(r, size[k])
        if not exact.all():
            return None
        out[:, k] = c
    return out


def _counts(coords, ring, cell_of_ring, corners, wrap=None, junctions=2):
    """``(V, E, merged, V3)`` of the ring graph (``wrap``: see :func:`_vertex_ids`).

    A vertex that is a straight angle in every ring that has it (the middle of an edge, or a
    T-junction that only one side of an edge has) is not a vertex of the graph. ``V3``
    counts the vertices that at least three cells share. On a torus (``wrap``) every edge
    borders two ring sides, so ``E`` is half the segments between the kept vertices (an edge
    can join a vertex to itself there). A vertex lying on a ring side without it (a
    T-junction: exactly, on a torus; within ``VERTEX_STRAIGHT_ULPS`` ulps, in the plane) is
    first put in that ring (``junctions``: :mod:`.junctions`).
    """
    if len(coords) == 0:
        return 0, 0, 0, 0
    idx, rid, turn, flat = _ring_vertices(coords, ring)
    pts = coords[idx]
    torus = wrap
    if wrap is not None:
        lo, hi, tol = wrap
        boxsize = hi - lo
        raw = pts
        outside = ~((raw > lo) & (raw < hi)).all(1)
        offsets = _box_offsets(raw, lo, hi)
        if offsets is not None:
            # each point as its exact offset in its copy of the box: two points are one
            # vertex modulo the box exactly when their offsets are equal
            pts, wrap = offsets, (outside, np.zeros(2), boxsize, tol)
        else:
            # inside the open box a point is its own bits; outside it is taken modulo the
            # box (rounded)
            pts = raw.copy()
            moved = lo + np.mod(raw[outside] - lo, boxsize)
            moved = np.where(moved >= hi, lo, moved)
            pts[outside] = moved
            wrap = (outside, lo, boxsize, tol)
    ids, merged = _vertex_ids(pts, rid, flat, corners, wrap)
    if junctions and len(idx):
        from .junctions import split, split_plane

        lengths = np.diff(ring) - 1
        nxt = np.arange(1, len(idx) + 1)
        ends = np.cumsum(lengths)
        nxt[ends[lengths > 0] - 1] = (ends - lengths)[lengths > 0]
        if torus is not None:
            got = split(coords, ring, idx, nxt, ids, torus[0], torus[1] - torus[0])
        else:
            got = split_plane(coords, ring, idx, nxt, ids)
        if got is not None:
            # on a torus one pass; in the plane a split can leave a side that the next
            # covers (nested clusters at (3e3, -2e3): Euler -3, 0 after one pass, 1 after two)
            again = junctions - 1 if torus is None else 0
            return _counts(got[0], got[1], cell_of_ring, corners, torus, junctions=again)
    rings = _rings_per_vertex(ids, rid)
    if wrap is not None:
        # on a torus a cell that borders its own image has a vertex twice in its ring (as
        # two copies): a vertex three ring sides pass through is the engine's, not a
        # T-junction (a cell 320 x 96 ulps at -2**47: V 57 where the bits give 58)
        rings = np.maximum(rings, np.bincount(ids, minlength=len(rings)))
    # a vertex three cells share is the engine's, computed once: straight only exactly;
    # one that one or two rings have is straight also up to rounding (a T-junction), but in
    # the plane not where the ring graph branches there: a vertex with three or more
    # neighbours (the end of a sliver an ulp wide, where two rings that share a path part)
    # is a vertex of every ring that has it, however straight each ring is there (dropped
    # from both rings, they joined it to different points: Euler 2 for 1 at a saw's valley)
    rounded = flat & (rings[ids] <= 2)
    if wrap is None:
        rounded &= _degree(ids, rid)[ids] <= 2
    corner = (turn != 0) & ~rounded
    keep = np.bincount(ids, weights=corner)[ids] > 0
    few = np.bincount(rid, weights=keep, minlength=len(ring) - 1) < 3
    keep |= few[rid]  # a flat ring (all its vertices on one line) keeps them all
    # ... and they are vertices in every ring that has them: a triangle an ulp wide keeps its
    # corners, which its neighbour's ring passes straight through (a wrapped piece 1 ulp
    # wide at 4e12: V 57, E 84 where the bits give 59 and 87)
    keep = np.bincount(ids, weights=keep)[ids] > 0
    kept = np.flatnonzero(keep)
    krid = rid[kept]
    following = np.append(kept[1:], 0)
    first = np.ones(len(kept), dtype=bool)
    first[1:] = krid[1:] != krid[:-1]
    starts = kept[first]
    last = np.append(np.flatnonzero(first)[1:], len(kept)) - 1
    following[last] = starts
    va = ids[kept]
    vb = ids[following]
    if wrap is None:
        sep = va != vb
        lo_ = np.minimum(va, vb)[sep]
        hi_ = np.maximum(va, vb)[sep]
        n_edges = len(unique(lo_ * (len(coords) + 1) + hi_))
    else:
        # segments of positive length (a ring's repeated point is none), each edge twice;
        # not one whose two ends are one vertex within tol of each other: the ulp-long edges
        # of a cluster of vertices whose image across the box rounded to one point (eight
        # float sites on a circle about the box's corner: E 15 for 14)
        a, b = coords[idx[kept]], coords[idx[following]]
        loop = (va == vb) & (np.abs(a - b).max(1) <= wrap[3])
        n_edges = int(((a != b).any(1) & ~loop).sum()) // 2
    cells = cell_of_ring[krid].astype(np.int64)
    pairs = unique(va * (int(cells.max(initial=0)) + 1) + cells)
    per_vertex = np.bincount(pairs // (int(cells.max(initial=0)) + 1))
    return len(unique(va)), n_edges, merged, int((per_vertex >= 3).sum())


def _degree(ids: np.ndarray, rid: np.ndarray) -> np.ndarray:
    """Per vertex id, how many distinct other ids precede or follow it in some ring.

    ``ids`` are the ring vertices' ids in ring order (``rid`` the ring of each, rings
    contiguous, no closing repeat).
    """
    nxt = np.arange(1, len(ids) + 1)
    last = np.flatnonzero(np.append(rid[1:] != rid[:-1], True))
    nxt[last] = np.append(0, last[:-1] + 1)
    a = np.concatenate((ids, ids[nxt]))
    b = np.concatenate((ids[nxt], ids))
    sep = a != b
    k = int(ids.max(initial=0)) + 1
    return np.bincount(unique(a[sep] * k + b[sep]) // k, minlength=k)


def _open_holes(cells, parts_per_cell, poly) -> int:
    """How many holes of the cells' parts do not make a part's interior less than a disk.

    A face counts ``1 - h`` for its ``h`` holes only where they are apart from its outer
    ring: a hole that touches the outer ring at a point (a domain whose hole touches its
    shell) leaves the interior an open disk, and holes that touch one another count once.
    So each part counts one minus the groups of touching holes that do not reach its shell.
    """
    holed = np.flatnonzero(np.diff(poly) > 1)
    if not len(holed):
        return 0
    owner = np.repeat(np.arange(len(cells)), parts_per_cell)
    first = np.concatenate(([0], np.cumsum(parts_per_cell)[:-1]))
    opened = 0
    for j in holed:
        c = owner[j]
        geom = cells[c]
        part = (
            shapely.get_parts(geom)[j - first[c]] if shapely.get_num_geometries(geom) > 1 else geom
        )
        rings = [part.exterior, *part.interiors]
        group = list(range(len(rings)))  # union-find over touching rings

        def root(a, group=group):
            while group[a] != a:
                group[a] = group[group[a]]
                a = group[a]
            return a

        for a in range(len(rings)):
            for b in range(a + 1, len(rings)):
                if rings[a].intersects(rings[b]):
                    group[root(a)] = root(b)
        roots = {root(a) for a in range(1, len(rings))}
        closed_groups = len(roots - {root(0)})
        opened += (len(rings) - 1) - closed_groups
    return opened


def _domain_chi(geom) -> int:
    """Euler characteristic of a polygonal domain: parts minus holes, less the pinches.

    The parts of a valid MultiPolygon meet at most at single points; ``k`` parts meeting at
    one point join there (inclusion-exclusion: ``chi`` drops by ``k - 1``), so two squares
    touching at a corner have ``chi = 1``, not 2.
    """
    parts = shapely.get_parts(geom)
    chi = int(len(parts) - shapely.get_num_interior_rings(parts).sum())
    if len(parts) < 2:
        return chi
    tree = shapely.STRtree(parts)
    i, j = tree.query(parts, predicate="intersects")
    keep = i < j
    meets: dict = {}
    for a, b in zip(i[keep], j[keep], strict=True):
        for xy in shapely.get_coordinates(shapely.intersection(parts[a], parts[b])):
            meets.setdefault((float(xy[0]), float(xy[1])), set()).update((int(a), int(b)))
    return chi - sum(len(k) - 1 for k in meets.values())


def _nonconvex(coords, ring, poly, geom, cells) -> int:
    """Number of ``cells`` that are not one convex polygon without holes.

    A ring is convex when it never turns both left and right (a vertex within rounding of
    the chord between its neighbours turns neither way; see :func:`_ring_vertices`).
    """
    if not len(cells):
        return 0
    parts = geom[cells + 1] - geom[cells]
    rings = poly[geom[cells + 1]] - poly[geom[cells]]
    simple = (parts == 1) & (rings == 1)
    bad = int((~simple).sum())
    r = poly[geom[cells[simple]]]
    if not len(r):
        return bad
    lo = ring[r]
    length = ring[r + 1] - lo
    sub_ring = np.zeros(len(r) + 1, dtype=np.int64)
    np.cumsum(length, out=sub_ring[1:])
    take = np.repeat(lo - sub_ring[:-1], length) + np.arange(int(sub_ring[-1]))
    _, rid, turn, flat = _ring_vertices(coords[take], sub_ring)
    turn = np.where(flat, 0, turn)  # a turn within rounding of straight is no turn
    left = np.bincount(rid, weights=turn > 0, minlength=len(r))
    right = np.bincount(rid, weights=turn < 0, minlength=len(r))
    return bad + int(((left > 0) & (right > 0)).sum())


def _unbounded(d) -> int:
    from .delaunay import delaunay

    if d.periodic or len(d.sites) == 0:
        return 0
    tri = delaunay(d.sites)
    if tri.collinear:
        return len(tri.hull)
    he = np.asarray(tri.halfedges)
    flat = np.asarray(tri.triangles).ravel()
    e = np.flatnonzero(he < 0)
    nxt = 3 * (e // 3) + (e % 3 + 1) % 3
    return len(unique(np.concatenate((flat[e], flat[nxt]))))


def describe(d) -> Description:
    """Structure report of a diagram; see :class:`Description` and the module description.

    Parameters
    ----------
    d : Diagram

    Returns
    -------
    Description
        A frozen dataclass; ``str()`` gives a readable multi-line report.

    Examples
    --------
    >>> import numpy as np, voroforge as vf
    >>> d = vf.voronoi(np.random.default_rng(0).random((100, 2)), (0, 0, 1, 1))
    >>> r = d.describe()
    >>> r.euler, r.euler_ok, r.convex_ok, r.cells
    (1, True, True, 100)
    """
    coords, (ring, poly, geom) = d.to_geoarrow()
    # past 2**1000 the counts run on coordinates scaled by 2**-64 (exact: a power of two;
    # every decision below is relative to the coordinates' ulps): distances between
    # vertices near +-1.8e308 overflowed (scipy's "'x' must be finite")
    scale = 1.0
    if len(coords) and float(np.abs(coords).max()) > 2.0**1000:
        scale = 2.0**-64
        coords = coords * scale
    n = len(d.sites)
    parts_per_cell = np.diff(geom)
    cells = int((parts_per_cell > 0).sum())
    parts = int(len(poly) - 1)
    holes = int(len(ring) - 1 - parts)
    faces = parts - holes + _open_holes(d.cells, parts_per_cell, poly) if holes else parts
    x0, y0, x1, y1 = d.bounds
    size = np.array([x1 * scale - x0 * scale, y1 * scale - y0 * scale])
    cell_of_poly = np.repeat(np.arange(n), parts_per_cell)
    cell_of_ring = cell_of_poly[np.repeat(np.arange(len(poly) - 1), np.diff(poly))]
    if d.periodic and not d.wrapped:
        tol = VERTEX_RTOL * float(np.hypot(*size))
        wrap = (np.array([x0, y0]) * scale, np.array([x1, y1]) * scale, tol)
        vertices, edges, mismatched, vor_vertices = _counts(coords, ring, cell_of_ring, None, wrap)
        faces = cells
        expected = 0
    else:
        corners = shapely.get_coordinates(d.boundary) * scale
        vertices, edges, mismatched, vor_vertices = _counts(coords, ring, cell_of_ring, corners)
        expected = 1 if d.periodic else _domain_chi(d.boundary)
    if cells == 0:
        expected = 0  # nothing is subdivided
    euler = vertices - edges + faces
    nonempty = np.flatnonzero(parts_per_cell > 0)
    # a flagged site's ring (kept beside it, or the gap its neighbours leave, engine.restore)
    # stands in for a cell floats cannot give: not held to convexity
    nonempty = nonempty[~np.isin(nonempty, d.unresolved)]
    geom_b = d.boundary
    convex_domain = d.periodic or domain_of(d).is_rect
    if not convex_domain:
        hull = shapely.convex_hull(geom_b)
        convex_domain = abs(hull.area - geom_b.area) <= CONVEX_DOMAIN_RTOL * hull.area
    if convex_domain or not len(nonempty):
        checked = nonempty
    else:
        # cells that keep a distance from the boundary were not cut by it: farther than
        # 100 VERTEX_RTOL of their own coordinates' magnitude (what a cut rounds by is ulps)
        edge = shapely.boundary(geom_b)
        shapely.prepare(edge)
        own = d.cells[nonempty]
        reach = 100.0 * VERTEX_RTOL * np.abs(shapely.bounds(own)).max(1)
        inner = ~shapely.dwithin(edge, own, reach)
        checked = nonempty[inner]
    if d.periodic and d.wrapped:
        # the pieces of a wrapped cell are convex each: check them one by one, except for
        # cells that border their own image (their touching pieces were united)
        pairs = d.edges.pairs
        selfish = np.zeros(n, dtype=bool)
        selfish[pairs[pairs[:, 0] == pairs[:, 1], 0]] = True
        checked = nonempty[~selfish[nonempty]]
        polys = np.concatenate([np.arange(geom[i], geom[i + 1]) for i in checked] or [[]])
        pieces = np.arange(len(poly), dtype=np.int64)
        bad = _nonconvex(coords, ring, poly, pieces, polys.astype(np.int64))
    else:
        bad = _nonconvex(coords, ring, poly, geom, checked)
    return Description(
        sites=n,
        cells=cells,
        parts=parts,
        holes=holes,
        vertices=int(vertices),
        voronoi_vertices=int(vor_vertices),
        edges=int(edges),
        mismatched_vertices=int(mismatched),
        faces=int(faces),
        voronoi_edges=int(len(d.edges.pairs)),
        euler=int(euler),
        euler_expected=int(expected),
        euler_ok=bool(euler == expected),
        unbounded=int(_unbounded(d)),
        convex_checked=int(len(checked)),
        nonconvex=int(bad),
        convex_ok=bool(bad == 0),
    )
