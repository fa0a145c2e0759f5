"""2D designs as watertight slabs: ``solid.extrude`` (panels, coasters, CNC previews)."""

from __future__ import annotations

import numpy as np

__all__ = ["extrude"]


def _polygons(geom):
    for g in getattr(geom, "geoms", [geom]):
        if g.geom_type == "Polygon" and not g.is_empty:
            yield g
        elif g.geom_type in ("MultiPolygon", "GeometryCollection"):
            yield from _polygons(g)


def _rows(a):
    """Each (x, y) row of ``a`` as one hashable key (exact bit patterns)."""
    a = np.ascontiguousarray(a, dtype=np.float64)
    return a.view(np.dtype((np.void, 16))).ravel()


def _ring_arrays(poly):
    return [np.asarray(r.coords)[:-1] for r in (poly.exterior, *poly.interiors)]


def _cdt(poly):
    """The polygon's own vertices and a constrained Delaunay triangulation of them (GEOS)."""
    import shapely

    ring_xy = np.vstack(_ring_arrays(poly))
    _, first = np.unique(_rows(ring_xy), return_index=True)  # closing points repeat
    xy = ring_xy[np.sort(first)]
    keys = {k: i for i, k in enumerate(_rows(xy).tolist())}
    tris = shapely.get_parts(shapely.constrained_delaunay_triangles(poly))
    corners = shapely.get_coordinates(shapely.get_exterior_ring(tris)).reshape(-1, 4, 2)[:, :3]
    try:
        tri = np.array([keys[k] for k in _rows(corners.reshape(-1, 2)).tolist()], np.int64)
    except KeyError:  # GEOS added a point: cannot happen for a valid polygon
        raise ValueError("extrude: the outline could not be triangulated (is it valid?)") from None
    return xy, tri.reshape(-1, 3)


def _conforming(poly, max_area):
    """Points and triangles covering ``poly`` with every triangle's area about <= ``max_area``.

    A conforming Delaunay triangulation: the rings are split into segments no longer than
    the target edge ``h``, a hexagonal grid of spacing ``h`` fills the inside (kept at least
    ``h / 2`` from the rings, so it never hides a segment), and any ring segment still missing
    from the Delaunay triangulation is split at its midpoint until all are edges. Triangles
    are then inside or outside as a whole; the inside ones are kept.
    """
    import shapely

    from .. import delaunay

    h = float(np.sqrt(4.0 * max_area / np.sqrt(3.0)))
    rings = _node_rings(_ring_arrays(shapely.segmentize(poly, h)))
    x0, y0, x1, y1 = poly.bounds
    gy = np.arange(y0 + h / 2, y1, h * np.sqrt(3.0) / 2)
    gx = np.arange(x0 + h / 2, x1 + h, h)
    grid = np.column_stack(
        [
            (gx[None, :] + (np.arange(len(gy)) % 2)[:, None] * (h / 2)).ravel(),
            np.repeat(gy, len(gx)),
        ]
    )
    if len(grid):
        keep = shapely.contains_xy(poly, grid[:, 0], grid[:, 1])
        grid = grid[keep]
        grid = grid[shapely.distance(poly.boundary, shapely.points(grid)) >= h / 2]
    for _ in range(64):
        pts = np.vstack([*rings, grid])
        seg_end = [np.roll(np.arange(len(r)), -1) for r in rings]
        offs = np.cumsum([0] + [len(r) for r in rings])
        a = np.concatenate([np.arange(len(r)) + o for r, o in zip(rings, offs[:-1], strict=True)])
        b = np.concatenate([e + o for e, o in zip(seg_end, offs[:-1], strict=True)])
        _, first, inv = np.unique(_rows(pts), return_index=True, return_inverse=True)
        ids = np.argsort(first)  # unique points in input order
        rank = np.empty_like(ids)
        rank[ids] = np.arange(len(ids))
        inv = rank[inv.ravel()]
        xy = pts[np.sort(first)]
        tri = np.asarray(delaunay(xy).triangles, np.int64)
        n = len(xy)
        e = np.concatenate([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]])
        have = np.unique(e.min(axis=1) * n + e.max(axis=1))
        sa, sb = inv[a], inv[b]
        want = np.minimum(sa, sb) * n + np.maximum(sa, sb)
        missing = ~np.isin(want, have)
        if not missing.any():
            break
        miss_at = np.split(missing, offs[1:-1])
        rings = [_split_segments(r, m) for r, m in zip(rings, miss_at, strict=True)]
    else:
        raise ValueError(
            "extrude: could not fit the relief mesh to the outline (very sharp corners); "
            "try a larger max_area"
        )
    c = xy[tri].mean(axis=1)
    return xy, tri[shapely.contains_xy(poly, c[:, 0], c[:, 1])]


def _separate_pinches(xy, tri):
    """One vertex copy per side where the material touches itself at a point.

    A valid polygon may have a hole meeting its outline (or another hole) at one point;
    sharing that vertex would make the slab's vertical edge there carry four side faces.
    The triangles around such a vertex fall into fans that meet only across outline edges;
    each fan after the first takes its own copy of the vertex, so the slab stays manifold.
    """
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    e = np.sort(np.concatenate([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]]), axis=1)
    n = len(xy)
    key = e[:, 0] * n + e[:, 1]
    _, inv, cnt = np.unique(key, return_inverse=True, return_counts=True)
    outline = e[cnt[inv] == 1]
    degree = np.bincount(outline.ravel(), minlength=n)
    interior = set(key[cnt[inv] == 2].tolist())
    tri = tri.copy()
    extra = []
    for u in np.flatnonzero(degree > 2):
        t, k = np.nonzero(tri == u)
        others = [set(tri[ti].tolist()) - {int(u)} for ti in t]
        pairs = [
            (i, j)
            for i in range(len(t))
            for j in range(i + 1, len(t))
            if any(min(u, w) * n + max(u, w) in interior for w in others[i] & others[j])
        ]
        ij = np.array(pairs, dtype=np.int64).reshape(-1, 2)
        graph = coo_matrix((np.ones(len(ij)), (ij[:, 0], ij[:, 1])), shape=(len(t), len(t)))
        _, fan = connected_components(graph, directed=False)
        for f in range(1, fan.max() + 1):
            mine = fan == f
            tri[t[mine], k[mine]] = n + len(extra)
            extra.append(xy[u])
    return np.vstack([xy, *extra]) if extra else xy, tri


def _node_rings(rings):
    """Each ring with the other rings' vertices that lie on its segments added as vertices."""
    import shapely

    out = []
    for i, r in enumerate(rings):
        pts = [q for j, q in enumerate(rings) if j != i]
        if not pts:
            out.append(r)
            continue
        cand = np.vstack(pts)
        on = shapely.intersects_xy(shapely.LinearRing(r), cand[:, 0], cand[:, 1])
        cand = cand[on & ~np.isin(_rows(cand), _rows(r))]
        segs = shapely.linestrings(np.stack([r, np.roll(r, -1, axis=0)], axis=1))
        r = list(map(tuple, r))
        for q in cand:
            at = int(np.flatnonzero(shapely.intersects_xy(segs, q[0], q[1]))[0])
            a = np.asarray(r[at])
            # insert after the segment's start, ordered along the segment
            pos = at + 1
            while pos < len(r) and _between(a, np.asarray(r[pos]), q):
                pos += 1
            r.insert(pos, tuple(q))
            segs = shapely.linestrings(np.stack([np.asarray(r), np.roll(r, -1, axis=0)], axis=1))
        out.append(np.asarray(r, dtype=np.float64))
    return out


def _between(a, p, q):
    """Whether ``p`` lies strictly between ``a`` and ``q`` on their segment."""
    return float(np.dot(p - a, q - a)) < float(np.dot(q - a, q - a))


def _split_segments(ring, which):
    """``ring`` with the midpoint of each segment ``i -> i + 1`` flagged in ``which`` added."""
    nxt = np.roll(ring, -1, axis=0)
    mid = (ring + nxt) / 2
    out = np.zeros((len(ring) + int(which.sum()), 2))
    pos = np.arange(len(ring)) + np.concatenate([[0], np.cumsum(which)[:-1]])
    out[pos] = ring
    out[pos[which] + 1] = mid[which]
    return out


def _heights(relief, xy) -> np.ndarray:
    """``relief(xy)`` checked: one finite height per point (a NaN passed ``top_z <= 0``)."""
    r = np.asarray(relief(xy), dtype=np.float64)
    if r.shape != (len(xy),):
        raise ValueError(
            f"relief must return one height per point, shape ({len(xy)},) for the "
            f"({len(xy)}, 2) points it is given; got shape {r.shape}"
        )
    bad = np.flatnonzero(~np.isfinite(r))
    if len(bad):
        at = ", ".join(f"({xy[i, 0]:.6g}, {xy[i, 1]:.6g})" for i in bad[:3])
        more = f" and {len(bad) - 3} more points" if len(bad) > 3 else ""
        raise ValueError(f"relief returned non-finite heights at (x, y) = {at}{more}")
    return r


def _material(geom):
    """The polygonal material of ``geom``: an invalid geometry's parts made valid and unioned.

    ``shapely.make_valid`` of a MultiPolygon whose parts overlap (polygons collected in a
    list) keeps their symmetric difference: the overlap was lost. The material is what any
    part covers, so each part is made valid on its own and the parts are unioned. A
    GeometryCollection's parts may overlap and still be valid: it is always unioned (its
    parts were extruded twice where they overlapped, a mesh through itself).
    """
    import shapely

    if geom.is_valid and geom.geom_type != "GeometryCollection":
        return geom
    parts = []
    todo = [geom]
    while todo:
        g = todo.pop()
        if g.geom_type in ("MultiPolygon", "GeometryCollection"):
            todo.extend(shapely.get_parts(g).tolist())
        elif not g.is_empty:
            parts.append(shapely.make_valid(g))
    return shapely.union_all(parts)


def _slab(poly, thickness, relief, max_area):
    """One polygon (with holes) as a closed slab; the top displaced by ``relief(xy)``."""
    import trimesh

    xy, tri = _cdt(poly) if relief is None else _conforming(poly, max_area)
    xy, tri = _separate_pinches(xy, tri)
    nv = len(xy)
    top_z = np.full(nv, float(thickness))
    if relief is not None:
        top_z = top_z + _heights(relief, xy)
        if (top_z <= 0).any():
            raise ValueError(
                "relief: the top surface goes below the bottom (thickness + relief <= 0)"
            )
    v = np.vstack([np.column_stack([xy, np.zeros(nv)]), np.column_stack([xy, top_z])])
    # orient every triangle counter-clockwise seen from +z
    a = xy[tri]
    ccw = (a[:, 1, 0] - a[:, 0, 0]) * (a[:, 2, 1] - a[:, 0, 1]) - (a[:, 2, 0] - a[:, 0, 0]) * (
        a[:, 1, 1] - a[:, 0, 1]
    ) > 0
    tri = np.where(ccw[:, None], tri, tri[:, ::-1])
    faces = [tri[:, ::-1], tri + nv]
    # boundary edges: used by exactly one triangle; each becomes a side quad
    e = np.concatenate([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]])
    key = np.sort(e, axis=1)
    _, inv, cnt = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    b = e[cnt[inv.reshape(-1)] == 1]  # directed as the (ccw) triangle walks it
    i, j = b[:, 0], b[:, 1]
    faces.append(np.column_stack([i, j, j + nv]))
    faces.append(np.column_stack([i, j + nv, i + nv]))
    k = int(np.argmin(top_z))  # the slab's thinnest point (``check(min_wall=)``)
    thin = (np.array([xy[k, 0], xy[k, 1], 0.5 * top_z[k]]), float(top_z[k]))
    return trimesh.Trimesh(v, np.vstack(faces), process=False), thin


def extrude(design_result, thickness, *, relief=None, max_area=None):
    """A 2D design's material (frame and webs, openings cut through) as a watertight slab.

    Parameters
    ----------
    design_result : design Result, shapely Polygon/MultiPolygon
        ``voroforge.design.compute(...)`` (its ``frame``), or any polygonal material
        (overlapping parts of an invalid MultiPolygon are unioned: the material is what
        any part covers).
    thickness : float
        Slab thickness (> 0), in the design's units; the bottom is at z = 0.
    relief : callable, optional
        A height field ``xy (m, 2) -> (m,)`` added to the top (for example an attractor
        field remapped to millimetres): the top is triangulated finely enough to follow it.
        Heights must be finite (a ValueError names the points where they are not).
    max_area : float, optional
        Largest top triangle with ``relief`` (default: the material's area / 20000).

    Returns
    -------
    trimesh.Trimesh
        Watertight; one body per separate piece of material. ``metadata["walls"]`` holds
        each piece's thinnest point (``at`` (k, 3), mid-slab) and its thickness (``thickness``
        (k,): the slab, or the lowest top with ``relief``), what ``check(min_wall=)`` compares.

    Examples
    --------
    >>> import shapely
    >>> from voroforge import solid
    >>> m = solid.extrude(shapely.box(0, 0, 10, 10).difference(shapely.box(2, 2, 8, 8)), 3.0)
    >>> bool(m.is_volume), round(float(m.volume), 9)
    (True, 192.0)
    """
    import shapely
    import trimesh

    geom = getattr(design_result, "frame", design_result)
    if not isinstance(geom, shapely.Geometry):
        raise ValueError(
            f"extrude: expected a design result or polygons, got {type(geom).__name__}"
        )
    t = float(thickness)
    if not (np.isfinite(t) and t > 0):
        raise ValueError(f"thickness must be a finite number > 0, got {thickness!r}")
    polys = list(_polygons(_material(geom)))
    if not polys:
        raise ValueError("extrude: no polygonal material to extrude")
    if max_area is None:
        max_area = sum(p.area for p in polys) / 20000.0
    slabs = [_slab(p, t, relief, max_area) for p in polys]
    parts = [s for s, _ in slabs]
    m = trimesh.util.concatenate(parts) if len(parts) > 1 else parts[0]
    walls = {
        "at": np.array([at for _, (at, _) in slabs]).reshape(-1, 3),
        "thickness": np.array([z for _, (_, z) in slabs]),
    }
    m.metadata.update({"kind": "extrude", "walls": walls})
    return m
