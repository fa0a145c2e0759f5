"""Surface Morph: a 2D design laid into a surface's UV square and mapped onto the surface.

The Grasshopper way: the design's bounding box (or ``bounds``) becomes ``[0, 1]^2`` in UV,
every ring is densified in UV (so a straight UV edge follows the surface) and each vertex is
mapped through the surface's ``f(u, v)`` (analytic surfaces: on the surface to rounding) or its
UV triangles (meshes: on the mesh). UV mapping distorts cells where the map is not isometric
(large near a sphere's pole, sheared on a saddle); :func:`voroforge.surface.voronoi` is the
undistorted alternative.
"""

from __future__ import annotations

import numpy as np
import shapely

from ..config import SURFACE_MORPH_MERGE_RTOL
from .panels import Panels
from .shapes import Surface

__all__ = ["morph"]

WHAT = ("panels", "cells", "openings", "frame")


def _polygons(geom) -> list:
    if geom is None or geom.is_empty:
        return []
    if geom.geom_type == "Polygon":
        return [geom]
    if geom.geom_type in ("MultiPolygon", "GeometryCollection"):
        return [p for g in geom.geoms for p in _polygons(g)]
    return []


def _design_parts(result, what: str):
    """``(polygons, ids, bounds)`` of a design Result for ``what``."""
    bounds = result.boundary.bounds
    if what == "frame":
        polys = _polygons(result.frame)
        return polys, np.arange(len(polys)), bounds
    if what == "openings":
        polys = [p for g in result.openings for p in _polygons(g)]
        return polys, np.arange(len(polys)), bounds
    polys, ids = [], []
    for i, raw in enumerate(result.raw):
        cell = shapely.intersection(raw, result.domain)
        hole = result.cells[i] if (what == "panels" and result.mask[i]) else None
        for p in _polygons(cell):
            if hole is not None and not hole.is_empty:
                p = p.difference(hole)
            for q in _polygons(p):
                polys.append(q)
                ids.append(i)
    return polys, np.asarray(ids, dtype=np.int64), bounds


def morph(
    design_result_or_geoms,
    S: Surface,
    *,
    what: str = "panels",
    bounds=None,
    segment: float | None = None,
    simplify: float = 0.0,
) -> Panels:
    """Map a 2D design (a design ``Result`` or shapely polygons) onto a surface through UV.

    Parameters
    ----------
    design_result_or_geoms : voroforge.design.compute.Result or sequence of shapely geometries
    S : Surface
        Needs a UV map (every built-in shape; a mesh with UVs).
    what : {"panels", "cells", "openings", "frame"}
        For a design Result: ``"panels"`` every cell with its opening cut out (a panel per
        cell), ``"cells"`` the whole cells, ``"openings"`` only the openings, ``"frame"`` the
        panel minus its openings as one piece. Ignored for plain geometries (each polygon is
        a panel).
    bounds : (xmin, ymin, xmax, ymax), optional
        The design rectangle that becomes the UV square (default: the design's boundary, or
        the geometries' bounds).
    segment : float, optional
        Longest edge after densifying, as a fraction of the design's larger side (default
        1/256: a straight edge follows the surface).
    simplify : float
        Drop ring vertices within this distance (a fraction of the larger side) of the
        simplified outline first (0: keep all; previews use a little).

    Returns
    -------
    Panels
        One panel per polygon (holes kept), vertices on the surface, UVs attached;
        ``panels.ids`` the design cell of each panel.

    Examples
    --------
    >>> import shapely
    >>> from voroforge import surface
    >>> S = surface.cylinder(1.0, 2 * 3.141592653589793)
    >>> p = surface.morph([shapely.box(0.2, 0.2, 0.4, 0.5)], S, bounds=(0, 0, 1, 1))
    >>> round(float(p.areas()[0]), 9) == round(0.2 * 0.3 * 2 * 3.141592653589793 ** 2 * 2, 9)
    True
    """
    if not isinstance(S, Surface):
        raise ValueError(f"morph needs a Surface; got {type(S).__name__}")
    if S.fn is None and S.uv is None:
        raise ValueError(f"{S.name}: morph needs a surface with a UV map")
    if what not in WHAT:
        raise ValueError(f"what must be one of {WHAT}; got {what!r}")
    src = design_result_or_geoms
    if hasattr(src, "raw") and hasattr(src, "boundary"):
        polys, ids, box = _design_parts(src, what)
    else:
        geoms = list(src) if not isinstance(src, shapely.Geometry) else [src]
        for g in geoms:
            if not isinstance(g, shapely.Geometry):
                raise ValueError(f"morph takes shapely geometries; got {type(g).__name__}")
        polys, ids = [], []
        for k, g in enumerate(geoms):
            for p in _polygons(g):
                polys.append(p)
                ids.append(k)
        ids = np.asarray(ids, dtype=np.int64)
        box = shapely.total_bounds(geoms) if geoms else (0, 0, 1, 1)
    if bounds is not None:
        box = tuple(float(b) for b in bounds)
        if len(box) != 4 or not (box[2] > box[0] and box[3] > box[1]):
            raise ValueError(f"bounds must be (xmin, ymin, xmax, ymax); got {bounds!r}")
    x0, y0, x1, y1 = box
    if not (x1 > x0 and y1 > y0):
        raise ValueError("the design has an empty extent; give bounds")
    if not polys:
        raise ValueError("nothing to morph: no polygons")
    seg = 1.0 / 256 if segment is None else float(segment)
    if not seg > 0:
        raise ValueError(f"segment must be positive; got {segment!r}")
    to_uv = np.array([1 / (x1 - x0), 1 / (y1 - y0)])
    side = max(x1 - x0, y1 - y0)
    if simplify < 0:
        raise ValueError(f"simplify must be >= 0; got {simplify!r}")
    rings_uv = []
    for p in polys:
        if simplify > 0:
            p = shapely.simplify(p, simplify * side, preserve_topology=True)
        p = shapely.orient_polygons(shapely.segmentize(p, seg * side))
        uvp = shapely.transform(p, lambda xy: (xy - (x0, y0)) * to_uv)
        rings = [np.asarray(uvp.exterior.coords)[:-1]]
        rings += [np.asarray(r.coords)[:-1] for r in uvp.interiors]
        rings_uv.append(rings)
    flat = np.concatenate([r for rings in rings_uv for r in rings])
    if flat.min() < -1e-9 or flat.max() > 1 + 1e-9:
        raise ValueError("the design reaches outside its bounds (UV outside [0, 1]^2)")
    flat = np.clip(flat, 0.0, 1.0)
    xyz = S.evaluate(flat[:, 0], flat[:, 1])
    return _merged(rings_uv, flat, xyz, ids, S)


def _merged(rings_uv, flat, xyz, ids, S) -> Panels:
    """Panels with each ring's runs of coincident mapped vertices kept as one vertex.

    Where the map collapses a UV edge to a point (the pole of a sphere patch at polar 0),
    a ring that runs along it would repeat that point: zero-length edges, which the unroll
    fan and the solids cannot use. The first vertex of a run is kept (its UV too). A ring
    left with under 3 points is dropped (a hole), or the panel with it (an exterior).
    """
    ext = np.ptp(xyz, axis=0).max() if len(xyz) else 0.0
    tol = SURFACE_MORPH_MERGE_RTOL * max(float(ext), np.finfo(float).tiny)
    keep_uv, keep_xyz, keep_rings, keep_ids = [], [], [], []
    k = 0
    for p, rings in enumerate(rings_uv):
        out = []
        for r in rings:
            q = xyz[k : k + len(r)]
            sel = np.ones(len(r), bool)
            sel[1:] = np.linalg.norm(q[1:] - q[:-1], axis=1) > tol
            at_start = np.linalg.norm(q - q[0], axis=1) <= tol
            j = len(r)
            while j > 1 and at_start[j - 1]:  # the run wraps around the ring's start
                j -= 1
            sel[j:] = False
            out.append(k + np.flatnonzero(sel))
            k += len(r)
        if len(out[0]) < 3:  # the exterior collapsed to a point or a line: no panel
            continue
        out = [out[0]] + [h for h in out[1:] if len(h) >= 3]
        keep_rings.append([flat[s] for s in out])
        keep_uv += [flat[s] for s in out]
        keep_xyz += [xyz[s] for s in out]
        keep_ids.append(ids[p])
    if not keep_rings:
        raise ValueError("nothing to morph: every polygon maps to a point or a line")
    return Panels.from_rings(
        keep_rings,
        np.concatenate(keep_uv),
        np.concatenate(keep_xyz),
        ids=np.asarray(keep_ids, dtype=np.int64),
        surface=S,
    )
