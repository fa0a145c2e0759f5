"""From convex cells (the kernels' output) to clipped cells in the GeoArrow multipolygon layout.

The kernels return, per site, one closed counter-clockwise ring clipped to the domain's
bounding box, with the neighbour that owns each edge. :func:`assemble` is the one routine that
turns them into a diagram's buffers and edges for every construction (Voronoi, power,
periodic): it expands the rings to all input sites (duplicates get empty cells), clips them
to non-rectangular domains, and extracts the unique shared edges when they are first read
(:class:`~voroforge.engine.diagram.LazyEdges`). :func:`from_shapely` and
:func:`first_cells` build and cut buffers for the periodic diagrams.
"""

from __future__ import annotations

from fractions import Fraction
from functools import partial

import numpy as np
import shapely

from ..config import (
    ASSEMBLE_ALIGN_MOVE_RATIO,
    ASSEMBLE_ALIGN_ULPS,
    ASSEMBLE_GROUP_MAX,
    ASSEMBLE_ROUNDING_ULPS,
    ASSEMBLE_THIN_ULPS,
    EDGE_LENGTH_RTOL,
    UNION_KEPT_RATIO,
)
from ..kernels.domain_grid import classify, mark_segments, scanline_inside
from ..kernels.rings import shared_edges
from .agree import agree
from .celledges import ends_on_cells, shared_pieces
from .diagram import Edges, LazyEdges
from .domain import Domain
from .pieces import Pieces
from .polyclip import clip_convex, clip_edges
from .slivers import sliver_owner
from .threads import serial_below


def assemble(dom: Domain, closed, lengths, owner, n: int, cell_ids=None):
    """Buffers and unique edges of ``n`` cells: :func:`assemble_checked` without the sites."""
    bufs, edges, _ = assemble_checked(dom, closed, lengths, owner, n, cell_ids)
    return bufs, edges


def assemble_checked(dom: Domain, closed, lengths, owner, n: int, cell_ids=None, sites=None):
    """Buffers and unique edges of ``n`` cells from closed convex rings clipped to the box.

    Parameters
    ----------
    dom : Domain
        The domain; rings are already clipped to its bounding box.
    closed : (k, 2) float64
        All rings, each closed (last vertex repeats the first).
    lengths : (u + 1,) int64
        Ring ``r`` is ``closed[lengths[r]:lengths[r + 1]]`` (empty for an empty cell).
    owner : (k,) int64
        The cell across the edge from each vertex to the next (negative where no cell is:
        the box, and -2 on the closing repeat).
    n : int
        Number of cells of the result.
    cell_ids : (u,) int64, optional
        The cell of each ring (default: ring ``r`` is cell ``r``).
    sites : (n, 2) float64, optional
        Each cell's site, in the rings' frame. Given, a cell that the polygon clip leaves
        without its site though the site is in the domain is clipped again in a frame at
        the site (:func:`_clip_at_site`), and listed in ``lost`` where that fails too.

    Returns
    -------
    buffers : tuple
        GeoArrow multipolygon buffers ``(coords, ring, poly, geom)`` of the ``n`` cells.
    edges : LazyEdges
        Each shared edge once, clipped to the domain: computed when first read (it keeps
        the rings and the domain's grid until then).
    lost : (m,) int64
        The cells whose clipped polygon does not hold their site though the domain does
        (empty without ``sites``, or on a rectangle).

    With ``sites`` (the Voronoi cells) the rings are first made to share every edge bit
    for bit where they do not (:func:`.agree.agree`: rings settled cell by cell at sites
    ulps apart; one parallel check where they do).
    """
    if sites is not None:
        ids = np.arange(len(lengths) - 1) if cell_ids is None else cell_ids
        closed, lengths, owner = agree(closed, lengths, owner, ids, n, sites)
    nonempty = lengths[1:] > lengths[:-1]
    ring_offsets = np.concatenate(([0], lengths[1:][nonempty]))
    ring_cell = np.flatnonzero(nonempty) if cell_ids is None else cell_ids[nonempty]
    grid = pieces = None
    if not dom.is_rect:
        grid = domain_grid(dom, len(ring_cell))
        pieces = Pieces(dom, closed, ring_offsets, ring_cell, n)
    lost = np.zeros(0, dtype=np.int64)
    cut = None
    if dom.is_rect:
        polys = np.arange(len(ring_cell) + 1, dtype=np.int64)
        bufs = (closed, ring_offsets, polys, geom_offsets_for(n, ring_cell))
    else:
        bufs, lost, cut = clip_to_polygon(
            dom, grid, pieces, closed, ring_offsets, ring_cell, n, sites=sites
        )
        cut = (bufs, cut)
    edges = LazyEdges(
        partial(_edges_later, n, dom, grid, pieces, closed, ring_offsets, ring_cell, owner, cut)
    )
    return bufs, edges, lost


def _edges_later(n, dom, *args) -> Edges:
    """:func:`domain_edges` of :func:`assemble`'s rings, under the engine's thread policy."""
    with serial_below(n):
        return Edges(*domain_edges(dom, *args))


def from_shapely(cells: np.ndarray):
    """GeoArrow multipolygon buffers ``(coords, ring, poly, geom)`` of shapely cells.

    Parameters
    ----------
    cells : (n,) object
        Polygons, MultiPolygons or empty geometries.

    Returns
    -------
    tuple
        ``(coords (k, 2) float64, ring, poly, geom)`` with ``len(geom) == n + 1``.
    """
    n = len(cells)
    full = np.flatnonzero(~shapely.is_empty(cells))
    counts = np.zeros(n, dtype=np.int64)
    if not len(full):
        z = np.zeros(1, dtype=np.int64)
        return np.zeros((0, 2)), z, z.copy(), np.zeros(n + 1, dtype=np.int64)
    kind, coords, offsets = shapely.to_ragged_array(cells[full])
    if kind == shapely.GeometryType.POLYGON:
        ring, poly = offsets
        counts[full] = 1
    else:
        ring, poly, geom_full = offsets
        counts[full] = np.diff(geom_full)
    geom = np.zeros(n + 1, dtype=np.int64)
    np.cumsum(counts, out=geom[1:])
    return np.ascontiguousarray(coords), ring.astype(np.int64), poly.astype(np.int64), geom


def first_cells(bufs, n: int):
    """Copies of the buffers of the first ``n`` cells of GeoArrow buffers ``bufs``.

    Parameters
    ----------
    bufs : tuple
        ``(coords, ring, poly, geom)``.
    n : int
        How many leading cells to keep.

    Returns
    -------
    tuple
        ``(coords, ring, poly, geom)`` of cells ``0 .. n - 1``, fresh arrays.
    """
    coords, ring, poly, geom = bufs
    g = geom[: n + 1]
    p = poly[: g[-1] + 1]
    r = ring[: p[-1] + 1]
    return coords[: r[-1]].copy(), r.copy(), p.copy(), g.copy()


def geom_offsets_for(n, ring_cell):
    """Polygon offsets per cell when each polygon is one ring (ring r of ``ring_cell[r]``)."""
    geom = np.zeros(n + 1, dtype=np.int64)
    np.cumsum(np.bincount(ring_cell, minlength=n), out=geom[1:])
    return geom


def domain_grid(dom: Domain, n_hint: int):
    """Marked/inside grids over the domain's bounds, squares about half a cell wide."""
    x0, y0, x1, y1 = dom.bounds
    side = max(x1 - x0, y1 - y0)
    g = int(min(max(2.0 * np.sqrt(max(n_hint, 1)), 8), 4096))
    h = side / g
    gx = int(np.ceil((x1 - x0) / h)) + 1
    gy = int(np.ceil((y1 - y0) / h)) + 1
    rings = shapely.get_rings(shapely.get_parts(dom.geometry))
    pts = [shapely.get_coordinates(r) for r in rings]
    segs = np.concatenate([np.hstack((p[:-1], p[1:])) for p in pts])
    # segments on the bounding box cannot cut cells that are already clipped to the box
    on_box = (
        ((segs[:, 0] == x0) & (segs[:, 2] == x0))
        | ((segs[:, 0] == x1) & (segs[:, 2] == x1))
        | ((segs[:, 1] == y0) & (segs[:, 3] == y0))
        | ((segs[:, 1] == y1) & (segs[:, 3] == y1))
    )
    all_segs = np.ascontiguousarray(segs)
    segs = np.ascontiguousarray(segs[~on_box])
    marked = mark_segments(segs, x0, y0, h, gx, gy)
    # a free square's centre decides for the whole square; centres are pulled into the box
    # because squares beyond it are only separated from the domain by skipped box segments
    cx = _centres(x0, x1, h, gx)
    cy = _centres(y0, y1, h, gy)
    inside = scanline_inside(all_segs, cx, cy, y0, h)  # even-odd over all rings
    return marked, inside, x0, y0, h


def _centres(lo, hi, h, count):
    """Square centres along one axis, pulled inside ``[lo, hi]``.

    Where the domain is thinner than half a square they all go to its middle.
    """
    mid = 0.5 * (lo + hi)
    return np.clip(
        lo + (np.arange(count) + 0.5) * h, min(lo + 0.25 * h, mid), max(hi - 0.25 * h, mid)
    )


def clip_to_polygon(dom: Domain, grid, pieces, coords, ring_offsets, ring_cell, n, sites=None):
    """Clip convex closed rings (one per non-empty cell) to a polygonal domain.

    Rings that the grid proves wholly inside are kept as they are, wholly outside ones are
    dropped, and only the rest go through a shapely intersection. Returns the GeoArrow
    multipolygon buffers ``(coords, ring_offsets, polygon_offsets, geom_offsets)`` of all
    ``n`` cells, the cells that do not hold their site though the domain does (only
    tested where ``sites`` is given: see :func:`_held`), and the cells that were clipped.
    """
    lost = np.zeros(0, dtype=np.int64)
    status = classify(coords, ring_offsets, *grid)
    lengths = np.diff(ring_offsets)
    simple = np.flatnonzero(status == 1)
    hard = np.flatnonzero(status == 2)
    s_len = lengths[simple]
    if len(hard):
        h_mask = np.repeat(status == 2, lengths)
        h_off = np.zeros(len(hard) + 1, dtype=np.int64)
        np.cumsum(lengths[hard], out=h_off[1:])
        convex = shapely.from_ragged_array(
            shapely.GeometryType.POLYGON, coords[h_mask], (h_off, np.arange(len(hard) + 1))
        )
        cut = clip_convex(pieces, convex, coords[h_mask], h_off, ring_cell[hard])
        clipped = _polygonal(cut)
        rings = (coords[h_mask], h_off)
        clipped, lost = _held(pieces, convex, clipped, ring_cell[hard], sites, rings)
        clipped = shapely.orient_polygons(clipped)
        parts, idx = shapely.get_parts(clipped, return_index=True)
        keep = ~shapely.is_empty(parts)
        parts = parts[keep]
        idx = idx[keep]
        _, c_coords, (c_ring, c_poly) = shapely.to_ragged_array(parts)
        polys_per_hard = np.bincount(idx, minlength=len(hard))
    else:
        c_coords = np.zeros((0, 2))
        c_ring = np.zeros(1, dtype=np.int64)
        c_poly = np.zeros(1, dtype=np.int64)
        polys_per_hard = np.zeros(0, dtype=np.int64)
    rings_per_poly = np.diff(c_poly)
    len_per_ring = np.diff(c_ring)
    simple_cell = ring_cell[simple]
    hard_cell = ring_cell[hard]

    # merge, ordered by cell id (stable: within one source items are already in cell order)
    poly_cell = np.concatenate((simple_cell, np.repeat(hard_cell, polys_per_hard)))
    poly_rings = np.concatenate((np.ones(len(simple), dtype=np.int64), rings_per_poly))
    hard_ring_cell = np.repeat(poly_cell[len(simple) :], rings_per_poly)
    ring_cell_all = np.concatenate((simple_cell, hard_ring_cell))
    ring_len = np.concatenate((s_len, len_per_ring))
    # each ring's start in ``source``: simple rings stay where they are in ``coords``
    source = np.concatenate((coords, c_coords)) if len(c_coords) else coords
    src_start = np.concatenate((ring_offsets[simple], len(coords) + c_ring[:-1]))
    # two runs each already in cell order: the stable sorts are merges
    po = np.argsort(poly_cell, kind="stable")
    ro = np.argsort(ring_cell_all, kind="stable")
    out_ring = np.zeros(len(ring_len) + 1, dtype=np.int64)
    np.cumsum(ring_len[ro], out=out_ring[1:])
    # coordinates follow their rings: out position k of ring r reads src_start[r] + k - start
    lens = ring_len[ro]
    co = np.repeat(src_start[ro] - out_ring[:-1], lens) + np.arange(out_ring[-1])
    out_poly = np.zeros(len(poly_rings) + 1, dtype=np.int64)
    np.cumsum(poly_rings[po], out=out_poly[1:])
    bufs = (source[co], out_ring, out_poly, geom_offsets_for(n, poly_cell))
    return bufs, lost, hard_cell


def _held(pieces, convex, clipped, cells, sites, rings):
    """The clipped cells, thin ones redone in a frame of their own, and the cells lost.

    A cell a few ulps wide at a reflex vertex of the domain (a site an ulp from the vertex,
    the vertex a site too) crosses the domain's boundary within ulps of the vertex: the
    overlay, which nodes in the coordinates' own floats, collapses its pieces to lines (the
    cell came back empty) or snaps a crossing onto the vertex in one cell and not in its
    neighbour (their rings then disagree by ulps). Such a cell (a thin ring near a vertex of
    the domain, or, where ``sites`` are given, a cell that misses its site), every ring
    that meets it and every ring meeting a thin one of those (:func:`_group`) is clipped
    again in one frame at that vertex, or at its site, where the crossings are far finer
    than the cell's width: with ``sites`` through one arrangement of all their boundaries
    (:func:`_clip_arranged`: each crossing is one point), else, or where that fails, each
    on its own (:func:`_clip_at_site`). With ``sites``, the cells that still do not hold
    their site where the domain does (exact tests) are returned as ``lost``.
    """
    lo = shapely.bounds(convex)
    size = np.hypot(lo[:, 2] - lo[:, 0], lo[:, 3] - lo[:, 1])
    ulp = np.spacing(np.abs(lo).max(axis=1))
    thin = shapely.area(convex) <= ASSEMBLE_THIN_ULPS * ulp * size
    missed = inside = np.zeros(len(cells), dtype=np.bool_)
    if sites is not None:
        xy = sites[cells]
        inside = np.zeros(len(cells), dtype=np.bool_)
        known = np.zeros(len(cells), dtype=np.bool_)
        _locate(pieces, clipped, xy, inside, known)
        missed = _missed(clipped, xy, inside, pieces.prepared)
    trouble = np.flatnonzero(missed | thin)
    done = np.zeros(len(cells), dtype=np.bool_)
    tree = shapely.STRtree(convex) if len(trouble) else None
    for k in trouble:
        if done[k]:
            continue
        origin = pieces.vertex_near(convex[k], ASSEMBLE_THIN_ULPS * ulp[k])
        if origin is None:
            if not missed[k]:
                continue  # a thin cell away from the domain's vertices: the overlay's is kept
            origin = xy[k]
        # the cells that meet this one are clipped in the same frame, so that the crossings
        # they share with it (the same two segments) are the same floats; so are those that
        # meet a thin one among them (a strip between two cells, which meet it only)
        near = _group(tree, convex, k, missed | thin)
        piece = pieces.around(*shapely.total_bounds(convex[near]))
        polys = _aligned(rings, k, near)
        got = None if sites is None else _clip_arranged(polys, piece, origin, xy[near])
        if got is None:
            got = _clip_at_site(polys, piece, origin)
        if got is not None:
            clipped[near] = got
            done[near] = True
    if sites is None or not len(trouble):
        return clipped, np.zeros(0, dtype=np.int64)
    _locate(pieces, clipped, xy, inside, known)
    return clipped, cells[_missed(clipped, xy, inside, pieces.prepared)].astype(np.int64)


def _locate(pieces, clipped, xy, inside, known):
    """Fill ``inside`` (the domain holds site ``xy[k]``) where clipped cell ``k`` misses it.

    Only those are read (:func:`_missed`), and locating a site is the costly part on a
    domain whose boundary spans it many times (:meth:`.pieces.Pieces.holds`).
    """
    need = np.flatnonzero(~known & ~shapely.intersects_xy(clipped, xy[:, 0], xy[:, 1]))
    inside[need] = pieces.holds(xy[need])
    known[need] = True


def _group(tree, convex, k, grow):
    """Rings meeting ring ``k``, and those meeting any ``grow`` ring among them (sorted).

    Stops growing at ``ASSEMBLE_GROUP_MAX`` rings (a thin ring's neighbours are always in).
    """
    near = np.sort(tree.query(convex[k], predicate="intersects"))
    seen = {k}
    while len(near) < ASSEMBLE_GROUP_MAX:
        todo = [j for j in near if grow[j] and j not in seen]
        if not todo:
            break
        seen.update(todo)
        more = np.union1d(near, tree.query(convex[todo], predicate="intersects")[1])
        if len(more) > ASSEMBLE_GROUP_MAX:
            break
        near = more
    return near


def _clip_arranged(rings, piece, site, xy):
    """``rings ∩ piece`` from one arrangement of their boundaries at ``site``; None: failed.

    Each ring clipped on its own (:func:`_clip_at_site`) computes its crossings with the
    domain's boundary itself, and GEOS's overlay snaps a segment an ulp from another one
    (a strip an ulp wide) differently in each: neighbours then round one crossing to two
    points, and a strip's pieces vanish from one cell and not from its neighbour. Here all
    the rings' and the piece's boundaries are noded together once (with the site at the
    origin, an exact shift), so every crossing is one point, and each face of the
    arrangement inside the piece goes to the ring holding it; a face that two rings hold
    (rings that overlap by an ulp) goes to the one whose site ``xy`` it holds, else to the
    nearer of their sites at its interior point, and a face no ring holds strictly is
    another cell's, or a gap the rings leave. A face a few ulps wide may hold no float point
    (a strip's piece of a tooth): its owner is decided exactly (:func:`.slivers.sliver_owner`).
    Each ring's faces are united (every vertex must be one of the faces': none is new) and
    shifted back: the crossings round once, the same in every cell.
    """
    o = np.asarray(site, dtype=np.float64)
    local = shapely.transform(rings, lambda p: p - o)
    lp = shapely.transform(piece, lambda p: p - o)
    lines = np.concatenate((shapely.boundary(local), [shapely.boundary(lp)]))
    try:
        noded = shapely.union_all(lines)
    except shapely.errors.GEOSException:
        return None  # (the clip one ring at a time is tried instead)
    faces = shapely.get_parts(shapely.polygonize(shapely.get_parts(noded)))
    if not len(faces):
        return None
    x, y = shapely.get_coordinates(shapely.point_on_surface(faces)).T
    # a face a few ulps wide may hold no float point: its owner is decided exactly
    ulp = np.spacing(np.abs(shapely.bounds(faces)).max(axis=1))
    thin = (shapely.area(faces) <= ASSEMBLE_THIN_ULPS * ulp * shapely.length(faces)) & (
        shapely.get_num_interior_rings(faces) == 0
    )
    sliver = np.full(len(faces), -2, dtype=np.int64)
    for f in np.flatnonzero(thin):
        got = sliver_owner(faces[f], local, lp, o, xy, ASSEMBLE_ROUNDING_ULPS * ulp[f])
        sliver[f] = -2 if got is None else got
    keep = np.where(sliver == -2, shapely.intersects_xy(lp, x, y), sliver >= 0)
    faces, x, y, sliver = faces[keep], x[keep], y[keep], sliver[keep]
    held = np.array([shapely.contains_xy(r, x, y) for r in local]).reshape(len(local), -1)
    cell = np.where(held.any(axis=0), np.argmax(held, axis=0), -1)
    cell = np.where(sliver >= 0, sliver, cell)
    held[:, sliver >= 0] = False
    rel = xy - o
    for f in np.flatnonzero(held.sum(axis=0) > 1):
        cand = np.flatnonzero(held[:, f])
        mine = cand[shapely.intersects_xy(faces[f], rel[cand, 0], rel[cand, 1])]
        if len(mine) == 1:
            cell[f] = mine[0]  # the face holds one of the sites: it is that site's
            continue
        d2 = (rel[cand, 0] - x[f]) ** 2 + (rel[cand, 1] - y[f]) ** 2
        cell[f] = cand[np.argmin(d2)]
    out = np.empty(len(rings), dtype=object)  # noqa: TID251 - every slot is filled below
    for j in range(len(rings)):
        mine = faces[cell == j]
        out[j] = _union_kept(mine) if len(mine) else shapely.Polygon()
        if len(mine):
            have = {tuple(p) for p in shapely.get_coordinates(mine).tolist()}
            if any(tuple(p) not in have for p in shapely.get_coordinates(out[j]).tolist()):
                return None
            # the faces are disjoint: a union that lost one (GEOS's cascaded union can drop
            # polygons a rounding from their neighbours) lost its area
            slack = ASSEMBLE_ROUNDING_ULPS * np.spacing(np.abs(shapely.bounds(out[j])).max())
            if shapely.area(mine).sum() - shapely.area(out[j]) > slack * shapely.length(mine).sum():
                return None
    return _shifted_back(_polygonal(out), o)


def _missed(clipped, xy, inside, prepared):
    """Which cells miss their site ``xy`` though the domain (``prepared``) holds it (``inside``).

    A site on the domain's boundary whose cell's crossing rounded past it by an ulp (a site
    on a hole's sloped edge) has its cell: only an empty cell, or one farther than
    ``ASSEMBLE_ROUNDING_ULPS`` ulps of the site's coordinates, misses it. A site inside the domain
    must be in its cell.
    """
    missed = inside & ~shapely.intersects_xy(clipped, xy[:, 0], xy[:, 1])
    for k in np.flatnonzero(missed):
        if not shapely.is_empty(clipped[k]) and not shapely.contains_xy(prepared, *xy[k]):
            reach = ASSEMBLE_ROUNDING_ULPS * np.spacing(np.abs(xy[k]).max())
            missed[k] = shapely.distance(clipped[k], shapely.points(xy[k])) > reach
    return missed


def _aligned(rings, k, near):
    """Polygons of rings ``near``, each edge they share with ring ``k`` taken from ring ``k``.

    Builders may return the two sides of a strip an ulp wide as segments an ulp apart (the
    neighbour's ring then even names the cell beyond the strip as its owner). Clipped
    apart, their crossings with the domain's boundary round apart too, and the cells
    disagree there. Ring ``k``'s edge replaces a neighbour's whose two end points are within
    ``ASSEMBLE_ALIGN_ULPS`` ulps of its own (reversed), where the neighbour stays convex and valid,
    so the overlay sees one segment. Only edges not shared yet bit for bit on either side are
    matched, and only where each end moves by at most ``1 / ASSEMBLE_ALIGN_MOVE_RATIO`` of the
    edge's length and no edge of the neighbour collapses: in a domain a few hundred ulps wide (a
    polygon at 3e14) cells are a few ulps across, and 4 ulps matched an edge with the next
    one along the neighbour's ring, dropping a vertex (a gap, Euler's count failed).
    """
    coords, off = rings
    mine = coords[off[k] : off[k + 1]]
    out = []
    for j in near:
        ring = coords[off[j] : off[j + 1]]
        if j != k:
            tol = ASSEMBLE_ALIGN_ULPS * np.spacing(max(np.abs(ring).max(), np.abs(mine).max()))
            # ring k's edges that ring j has reversed bit for bit are shared already
            have = {
                (tuple(a), tuple(b))
                for a, b in zip(ring[1:].tolist(), ring[:-1].tolist(), strict=True)
            }
            free = np.array(
                [
                    (tuple(a), tuple(b)) not in have
                    for a, b in zip(mine[:-1].tolist(), mine[1:].tolist(), strict=True)
                ]
            )
            theirs = {
                (tuple(a), tuple(b))
                for a, b in zip(mine[1:].tolist(), mine[:-1].tolist(), strict=True)
            }
            for t in range(len(ring) - 1):
                if (tuple(ring[t].tolist()), tuple(ring[t + 1].tolist())) in theirs:
                    continue  # ring j's edge t is ring k's already
                # edge t of ring j against every edge of ring k, reversed
                close = (
                    (np.abs(mine[1:] - ring[t]).max(axis=1) <= tol)
                    & (np.abs(mine[:-1] - ring[t + 1]).max(axis=1) <= tol)
                    & free
                )
                hit = np.flatnonzero(close)
                if len(hit) != 1:
                    continue
                a, b = mine[hit[0] + 1], mine[hit[0]]
                # one segment rounded apart: each end moves far less than the edge is long
                move = max(np.abs(a - ring[t]).max(), np.abs(b - ring[t + 1]).max())
                if ASSEMBLE_ALIGN_MOVE_RATIO * move > np.abs(a - b).max():
                    continue
                moved = ring.copy()
                moved[t], moved[t + 1] = a, b
                if t + 1 == len(moved) - 1:
                    moved[0] = moved[t + 1]  # (the closing repeat moved: its first vertex too)
                moved[-1] = moved[0]
                if (np.diff(moved, axis=0) == 0).all(axis=1).any():
                    continue  # an edge of ring j collapsed to a point
                if _valid_convex(moved):
                    ring = moved
        out.append(shapely.polygons(ring))
    return np.array(out, dtype=object)


def _valid_convex(ring):
    """Whether a closed ring is a valid polygon that turns left (or straight) at every vertex."""
    e = np.diff(ring, axis=0)
    nxt = np.roll(e, -1, axis=0)
    turns = e[:, 0] * nxt[:, 1] - e[:, 1] * nxt[:, 0]
    return bool((turns >= 0).all()) and bool(shapely.is_valid(shapely.polygons(ring)))


def _clip_at_site(rings, piece, site):
    """``rings ∩ piece`` computed with the site at the origin, or None where one fails.

    The shift is exact for every coordinate near the site (its difference is a float), so the
    overlay's crossings near the site are placed to the ulps of their small local
    coordinates; shifted back they round once. Parts that rounding made overlap are united,
    parts it collapsed (too few distinct vertices) are dropped, a ring it made touch itself
    is split (GEOS's make_valid); each result must then be valid and keep its area to
    within its rounding (``ASSEMBLE_ROUNDING_ULPS`` ulps times its perimeter), else None.
    """
    o = np.asarray(site, dtype=np.float64)
    local = _polygonal(
        shapely.intersection(
            shapely.transform(rings, lambda xy: xy - o),
            shapely.transform(piece, lambda xy: xy - o),
        )
    )
    return _shifted_back(local, o)


def _shifted_back(local, o):
    """Polygons ``local`` (in the frame at ``o``) moved back, rounding made valid, or None.

    See :func:`_clip_at_site`: each must be valid after the fix and keep its area to within
    ``ASSEMBLE_ROUNDING_ULPS`` ulps times its perimeter.
    """
    back = shapely.transform(local, lambda xy: xy + o)
    try:
        got = _polygonal(shapely.remove_repeated_points(back))
    except shapely.errors.GEOSException:
        return None  # a ring collapsed to fewer than 3 points (1e15 out: the overlay's ulps)
    for k in np.flatnonzero(~shapely.is_valid(got)):
        parts = shapely.get_parts(got[k])
        parts = parts[shapely.is_valid(parts) | (shapely.get_num_coordinates(parts) >= 4)]
        fixed = _union_kept(parts) if len(parts) else shapely.Polygon()
        if not shapely.is_valid(fixed):
            fixed = _polygonal(np.array([shapely.make_valid(fixed)], dtype=object))[0]
        slack = ASSEMBLE_ROUNDING_ULPS * np.spacing(np.abs(shapely.bounds(got[k])).max())
        slack *= shapely.length(local[k])
        if (
            shapely.get_type_id(fixed) not in (3, 6)
            or not shapely.is_valid(fixed)
            or abs(shapely.area(fixed) - shapely.area(local[k])) > slack
        ):
            return None
        got[k] = fixed
    return got


def _union_kept(parts):
    """The union of polygons ``parts`` whose interiors are disjoint, none of them lost.

    GEOS's overlay can collapse polygons an ulp or two wide: the two pieces of a strip an
    ulp wide either side of a domain's reflex vertex (issue 15, sites an ulp apart at the
    vertex of a notch) came back as an empty union, the faces of their arrangement as
    well as the rounded-back pieces, which touch along a segment. Where the union lost
    half the parts' area (counted exactly; tested only where the float areas say so) the
    parts are joined by a buffer of 0 instead, whose noding keeps them.
    """
    got = shapely.union_all(parts)
    total = shapely.area(parts).sum()
    if not (shapely.is_empty(got) or shapely.area(got) < UNION_KEPT_RATIO * total):
        return got
    if 2 * _area_exact(got) >= _area_exact(parts):
        return got
    return shapely.buffer(shapely.multipolygons(shapely.get_parts(parts)), 0)


def _ring_area_exact(ring):
    """The exact area (a Fraction) a closed ring encloses (its shoelace sum, unsigned)."""
    xy = shapely.get_coordinates(ring).tolist()
    twice = Fraction(0)
    for (x0, y0), (x1, y1) in zip(xy[:-1], xy[1:], strict=True):
        twice += Fraction(x0) * Fraction(y1) - Fraction(x1) * Fraction(y0)
    return abs(twice) / 2


def _area_exact(geoms):
    """The exact area (a Fraction) of polygonal geometries, holes taken out."""
    total = Fraction(0)
    for poly in shapely.get_parts(geoms):
        if shapely.get_type_id(poly) != 3 or shapely.is_empty(poly):
            continue
        total += _ring_area_exact(shapely.get_exterior_ring(poly))
        for k in range(shapely.get_num_interior_rings(poly)):
            total -= _ring_area_exact(shapely.get_interior_ring(poly, k))
    return total


def _polygonal(geoms):
    """Keep only the polygonal parts of overlay results (drop stray lines and points)."""
    out = np.empty(len(geoms), dtype=object)  # noqa: TID251 - every slot is filled below
    for k, g in enumerate(geoms):
        if shapely.get_type_id(g) in (3, 6):
            out[k] = g
        else:
            parts = [p for p in shapely.get_parts(g) if shapely.get_type_id(p) in (3, 6)]
            out[k] = shapely.union_all(parts) if parts else shapely.Polygon()
    return out


def domain_edges(dom: Domain, grid, pieces, coords, ring_offsets, ring_cell, owner, cells=None):
    """Unique shared edges ``(m, 2, 2)`` and their cell pairs ``(m, 2)``, clipped to the domain.

    Each pair ``(i, j)`` with ``i < j`` is taken from cell ``i``'s ring. Edges not longer than
    ``EDGE_LENGTH_RTOL`` times the domain's size are point contacts and are left out, and so
    are the pieces on the domain's boundary (an edge along a hole's side or the box's).
    Given ``cells``, the clipped cells' buffers and which cells were clipped, an edge that
    meets a polygon domain's boundary or a clipped cell is what the two clipped cells share
    (:func:`.celledges.shared_pieces`).
    """
    x0, y0, x1, y1 = dom.bounds
    tol = EDGE_LENGTH_RTOL * max(x1 - x0, y1 - y0)
    # read-only views whichever way the rings came (a diagram's buffers are read-only, a
    # fresh assembly's not): one compiled signature of the kernel instead of two
    coords, ring_offsets = coords.view(), ring_offsets.view()
    coords.setflags(write=False)
    ring_offsets.setflags(write=False)
    seg, pairs = shared_edges(coords, ring_offsets, ring_cell, owner, tol)
    # an edge on a side of the box (two sites mirrored across it) has its second cell
    # outside the box, clipped to nothing: no two cells share it
    xs, ys = seg[:, :, 0], seg[:, :, 1]
    on_box = (xs == x0).all(axis=1) | (xs == x1).all(axis=1)
    on_box |= (ys == y0).all(axis=1) | (ys == y1).all(axis=1)
    if on_box.any():
        seg, pairs = seg[~on_box], pairs[~on_box]
    if dom.is_rect or len(seg) == 0:
        return seg, pairs
    return _clip_segments(grid, pieces, seg, pairs, tol, cells)


def _clip_segments(grid, pieces, seg, pairs, tol, cells=None):
    """Edges ``seg`` (m, 2, 2) cut to the domain: the grid keeps or drops most of them whole.

    Given ``cells`` (the clipped cells' buffers, and which cells were clipped), an edge the
    grid cannot decide, or one of a clipped cell (whose clip may have moved its vertices
    far out), is the run of boundary its two clipped cells share: each crossing rounded
    once, by the cells' clip. Where they share none, it is cut by the exact kernel, or
    GEOS's overlay, and kept only where it ends at both cells' vertices.
    """
    two = seg.reshape(-1, 2)
    offs = np.arange(0, 2 * len(seg) + 1, 2, dtype=np.int64)
    status = classify(two, offs, *grid)
    hard = np.flatnonzero(status == 2)
    keep = status == 1
    ask = np.zeros(0, dtype=np.int64)
    if cells is not None:
        touched = np.zeros(int(pairs.max(initial=-1)) + 1, dtype=np.bool_)
        touched[cells[1][cells[1] < len(touched)]] = True
        ask = np.flatnonzero(keep & touched[pairs].any(axis=1))
    if not len(hard) and not len(ask):
        return seg[keep], pairs[keep]
    # every edge's pieces, tagged with the edge, then put back in the edges' order
    alone = np.flatnonzero(keep)
    alone = alone[~np.isin(alone, ask)]
    out_p, out_i = [seg[alone]], [alone]
    if cells is not None:
        both = np.concatenate((ask, hard))
        c_piece, c_idx, found = shared_pieces(cells[0], pairs[both])
        out_p.append(c_piece)
        out_i.append(both[c_idx])
        # a kept edge of a clipped cell that the cells do not share: itself, if it ends at
        # both cells' vertices
        lone = ask[~found[: len(ask)]]
        on = ends_on_cells(cells[0], seg[lone], pairs[lone])
        out_p.append(seg[lone[on]])
        out_i.append(lone[on])
        left = hard[~found[len(ask) :]]
    else:
        left = hard
    # the exact kernel next: its pieces end at the kernel-clipped cells' vertices bit for bit
    k_piece, k_idx = np.zeros((0, 2, 2)), np.zeros(0, dtype=np.int64)
    rest = np.arange(len(left))
    if not pieces.whole and len(left):
        k_piece, k_idx, rest = clip_edges(pieces, seg[left])
    piece, idx = _overlay_segments(pieces, seg[left[rest]], pairs[left[rest]])
    idx = np.concatenate((left[k_idx], left[rest[idx]]))
    piece = np.concatenate((k_piece, piece))
    if cells is not None and len(piece):
        on = ends_on_cells(cells[0], piece, pairs[idx])
        piece, idx = piece[on], idx[on]
    out_p.append(piece)
    out_i.append(idx)
    piece = np.concatenate(out_p)
    idx = np.concatenate(out_i)
    # the kept edges first, in order, then the pieces of the others by edge (as before)
    late = ~keep[idx]
    order = np.lexsort((idx, late))
    piece, idx = piece[order], idx[order]
    long = ~late[order] | (np.hypot(*(piece[:, 1] - piece[:, 0]).T) > tol)
    return piece[long], pairs[idx[long]]


def _overlay_segments(pieces, seg, pairs):
    """Segments ``seg`` cut to the domain by GEOS's overlay: pieces ``(r, 2, 2)``, their segment.

    Pieces along the domain's boundary are left out.
    """
    if not len(seg):
        return np.zeros((0, 2, 2)), np.zeros(0, dtype=np.int64)
    lines = shapely.linestrings(seg)
    cut = pieces.intersect(lines, pairs.min(axis=1), shapely.LineString())
    parts, idx = shapely.get_parts(cut, return_index=True)
    is_line = (shapely.get_type_id(parts) == 1) & ~shapely.is_empty(parts)
    parts = parts[is_line]
    idx = idx[is_line]
    # a piece along the domain's boundary (a cell's side on a hole's edge, the other cell
    # empty or beyond it) separates no two clipped cells: only pieces in the interior stay
    inner = pieces.in_interior(parts, pairs[idx].min(axis=1))
    parts = parts[inner]
    idx = idx[inner]
    # a straight segment intersected with a region gives straight pieces: keep end points
    piece = np.stack(
        (
            shapely.get_coordinates(shapely.get_point(parts, 0)),
            shapely.get_coordinates(shapely.get_point(parts, -1)),
        ),
        axis=1,
    )
    return piece.reshape(-1, 2, 2), idx
