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


def _slab(poly, thickness, relief, max_area):
    """One polygon (with holes) as a closed slab; the top displaced by ``relief(xy)``."""
    import triangle
    import trimesh

    rings = [np.asarray(poly.exterior.coords)[:-1]] + [
        np.asarray(r.coords)[:-1] for r in poly.interiors
    ]
    verts, segs, n = [], [], 0
    for r in rings:
        k = len(r)
        verts.append(r)
        segs.append(np.column_stack([np.arange(k), np.roll(np.arange(k), -1)]) + n)
        n += k
    holes = [
        np.asarray(h.representative_point().coords[0]) for h in map(_hole_poly, poly.interiors)
    ]
    data = {"vertices": np.vstack(verts), "segments": np.vstack(segs)}
    if holes:
        data["holes"] = np.array(holes)
    opts = "pQ" + (f"a{max_area:.12g}q30" if relief is not None else "")
    t = triangle.triangulate(data, opts)
    xy = np.asarray(t["vertices"], dtype=np.float64)
    tri = np.asarray(t["triangles"], dtype=np.int64)
    nv = len(xy)
    top_z = np.full(nv, float(thickness))
    if relief is not None:
        top_z = top_z + np.asarray(relief(xy), dtype=np.float64)
        if (top_z <= 0).any():
            raise ValueError(
                "relief: the top surface goes below the bottom (thickness + relief <= 0)"
            )
    v = np.vstack([np.column_stack([xy, np.zeros(nv)]), np.column_stack([xy, top_z])])
    # orient: triangle's output is counter-clockwise seen from +z
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
    return trimesh.Trimesh(v, np.vstack(faces), process=False)


def _hole_poly(ring):
    import shapely

    return shapely.Polygon(ring)


def extrude(design_result, thickness, *, relief=None, max_area=None):
    """A 2D design's material (frame and webs, openings cut through) as a watertight slab.

    Parameters
    ----------
    design_result : design Result, shapely Polygon/MultiPolygon
        ``voroforge.design.compute(...)`` (its ``frame``), or any polygonal material.
    thickness : float
        Slab thickness (> 0), in the design's units; the bottom is at z = 0.
    relief : callable, optional
        A height field ``xy (m, 2) -> (m,)`` added to the top (for example an attractor
        field remapped to millimetres): the top is triangulated finely enough to follow it.
    max_area : float, optional
        Largest top triangle with ``relief`` (default: the material's area / 20000).

    Returns
    -------
    trimesh.Trimesh
        Watertight; one body per separate piece of material.

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
    polys = list(_polygons(shapely.make_valid(geom) if not geom.is_valid else geom))
    if not polys:
        raise ValueError("extrude: no polygonal material to extrude")
    if max_area is None:
        max_area = sum(p.area for p in polys) / 20000.0
    parts = [_slab(p, t, relief, max_area) for p in polys]
    m = trimesh.util.concatenate(parts) if len(parts) > 1 else parts[0]
    m.metadata.update({"kind": "extrude"})
    return m
