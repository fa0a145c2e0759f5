"""Structure report of a Voronoi diagram: counts, Euler's formula, unbounded and convex cells.

The cells of a diagram, clipped to a domain ``D``, subdivide it. Count

* ``V``: distinct ring vertices of all cells (Voronoi vertices, points where Voronoi edges
  meet the boundary, and the boundary's own corners), leaving out a vertex that is a
  straight angle (within ``VERTEX_RTOL`` of the diagonal of the line through its two
  neighbours) in every ring that has it: the middle of an edge, or a rounding-level
  T-junction that only one side of an edge has,
* ``E``: distinct segments between consecutive corners of a ring (a shared Voronoi edge is
  in the rings of both of its cells and counts once; a boundary segment counts once),
* ``F``: the faces, each polygon part of each cell counting ``1 - h`` for its ``h`` holes
  (an open disk counts 1; a part with holes is not a disk).

Vertices closer than ``VERTEX_RTOL`` of the domain's diagonal count as one (the report
says how many coordinates differed from their vertex by rounding). Then
``V - E + F = chi(D)``, the Euler characteristic of the domain: the number of its parts
minus the number of its holes (1 for a box). A vertex that one cell has and its neighbour
lacks at a corner, a gap or an overlap breaks the equality, so it checks that the cells fit
together. On a torus (``periodic=True``, unwrapped cells) ``chi = 0``, faces are the cells,
edges the torus edges, and vertices are the cell vertices identified modulo the box.
Cut into the box (``wrap=True``) the pieces subdivide the box and ``chi = 1``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely

from ..config import CONVEX_DOMAIN_RTOL, VERTEX_RTOL
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
        they differ from it only by rounding (``VERTEX_RTOL``); 0 when neighbouring cells
        share their vertices bit for bit.
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
        else those farther than ``100 * VERTEX_RTOL`` of the diagonal from its boundary
        (with ``wrap=True`` every piece of every cell that does not border its own image).
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


def _ring_vertices(coords: np.ndarray, ring: np.ndarray, tol: float):
    """Open ring vertices: ``(idx, rid, nxt, corner, cross)``.

    ``idx`` indexes ``coords`` (the closing repeat of each ring left out), ``rid`` is the
    ring, ``nxt`` the next vertex of the ring, ``corner`` False where the vertex lies within
    ``tol`` of the chord between its two neighbours (a straight angle, or a near-duplicate),
    ``cross`` the cross product of the edges into and out of the vertex.
    """
    lengths = np.diff(ring) - 1  # rings are closed: the last vertex repeats the first
    rid = np.repeat(np.arange(len(lengths)), lengths)
    start = np.repeat(ring[:-1], lengths)
    pos = np.arange(len(rid)) - np.repeat(np.cumsum(lengths) - lengths, lengths)
    idx = start + pos
    size = lengths[rid]
    prev = start + (pos - 1) % size
    nxt = start + (pos + 1) % size
    e = coords[idx] - coords[prev]
    f = coords[nxt] - coords[idx]
    cross = e[:, 0] * f[:, 1] - e[:, 1] * f[:, 0]
    chord = np.hypot(*(e + f).T)
    return idx, rid, nxt, np.abs(cross) > tol * chord, cross


def _vertex_ids(pts: np.ndarray, tol: float, boxsize=None) -> tuple[np.ndarray, int]:
    """Cluster points closer than ``tol`` (single linkage); ``(ids, exact_mismatches)``."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components
    from scipy.spatial import cKDTree

    uniq, inv = np.unique(pts, axis=0, return_inverse=True)
    inv = inv.ravel()
    m = len(uniq)
    pairs = cKDTree(uniq, boxsize=boxsize).query_pairs(tol, output_type="ndarray")
    graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(m, m))
    count, label = connected_components(graph, directed=False)
    return label[inv].astype(np.int64), int(m - count)


def _counts(coords, ring, cell_of_ring, tol, boxsize=None, origin=None):
    """``(V, E, mismatched, V3)`` of the ring graph, vertices identified within ``tol``.

    A vertex that is a straight angle in every ring that has it (the middle of an edge, or a
    T-junction that rounding left on one side only) is not a vertex of the graph. ``V3``
    counts the vertices that at least three cells share.
    """
    if len(coords) == 0:
        return 0, 0, 0, 0
    idx, rid, nxt, corner, _ = _ring_vertices(coords, ring, tol)
    pts = coords[idx]
    if boxsize is not None:
        pts = np.mod(pts - origin, boxsize)
        pts[pts >= boxsize] = 0.0
    ids, mismatched = _vertex_ids(pts, tol, boxsize)
    keep = np.bincount(ids, weights=corner)[ids] > 0
    few = np.bincount(rid, weights=keep, minlength=len(ring) - 1) < 3
    keep |= few[rid]  # a ring thinner than the tolerance keeps all its vertices
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
    sep = va != vb
    lo = np.minimum(va, vb)[sep]
    hi = np.maximum(va, vb)[sep]
    edges = unique(lo * (len(coords) + 1) + hi)
    cells = cell_of_ring[krid].astype(np.int64)
    pairs = unique(va * (int(cells.max(initial=0)) + 1) + cells)
    per_vertex = np.bincount(pairs // (int(cells.max(initial=0)) + 1))
    return len(unique(va)), len(edges), mismatched, int((per_vertex >= 3).sum())


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


def _nonconvex(coords, ring, poly, geom, cells, tol) -> int:
    """Number of ``cells`` that are not one convex polygon without holes.

    A vertex turns the wrong way when it lies more than ``tol`` off the line through its two
    neighbours on the inner side (rounding moves vertices by far less).
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
    _, rid, _, turns, cross = _ring_vertices(coords[take], sub_ring, tol)
    left = np.bincount(rid, weights=turns & (cross > 0), minlength=len(r))
    right = np.bincount(rid, weights=turns & (cross < 0), minlength=len(r))
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
    n = len(d.sites)
    parts_per_cell = np.diff(geom)
    cells = int((parts_per_cell > 0).sum())
    parts = int(len(poly) - 1)
    holes = int(len(ring) - 1 - parts)
    faces = parts - holes
    x0, y0, x1, y1 = d.bounds
    size = np.array([x1 - x0, y1 - y0])
    cell_of_poly = np.repeat(np.arange(n), parts_per_cell)
    cell_of_ring = cell_of_poly[np.repeat(np.arange(len(poly) - 1), np.diff(poly))]
    tol = VERTEX_RTOL * float(np.hypot(*size))
    if d.periodic and not d.wrapped:
        vertices, _, mismatched, vor_vertices = _counts(
            coords, ring, cell_of_ring, tol, size, np.array([x0, y0])
        )
        edges = len(d.edges.pairs)
        faces = cells
        expected = 0
    else:
        vertices, edges, mismatched, vor_vertices = _counts(coords, ring, cell_of_ring, tol)
        expected = 1 if d.periodic else _domain_chi(d.boundary)
    if cells == 0:
        expected = 0  # nothing is subdivided
    euler = vertices - edges + faces
    nonempty = np.flatnonzero(parts_per_cell > 0)
    geom_b = d.boundary
    convex_domain = d.periodic or domain_of(d).is_rect
    if not convex_domain:
        hull = shapely.convex_hull(geom_b)
        convex_domain = abs(hull.area - geom_b.area) <= CONVEX_DOMAIN_RTOL * hull.area
    if convex_domain or not len(nonempty):
        checked = nonempty
    else:
        # cells that keep a distance from the boundary were not cut by it
        edge = shapely.boundary(geom_b)
        shapely.prepare(edge)
        inner = ~shapely.dwithin(edge, d.cells[nonempty], 100.0 * tol)
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
        bad = _nonconvex(coords, ring, poly, pieces, polys.astype(np.int64), tol)
    else:
        bad = _nonconvex(coords, ring, poly, geom, checked, tol)
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
