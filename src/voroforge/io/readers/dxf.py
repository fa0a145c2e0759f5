"""DXF in (ezdxf): closed outlines of the modelspace, bulges and circles as true arcs.

:func:`read_dxf` reads closed polylines (bulges flattened within ``tolerance``), circles,
ellipses and splines, optionally joining loose lines and arcs into faces, and combines
them by the even-odd rule. ezdxf is imported on first use.
"""

from __future__ import annotations

import math

import numpy as np
import shapely

from ...config import CURVE_TOLERANCE, ELLIPSE_FULL_TURN_ATOL
from .curves import arc_points
from .files import existing_file, positive_number
from .rings import even_odd

__all__ = ["bulge_polyline", "read_dxf"]


def bulge_polyline(points: np.ndarray, bulges: np.ndarray, closed: bool, tol: float):
    """Vertices of a polyline whose segments carry DXF bulges (tan of a quarter of the arc).

    Parameters
    ----------
    points : (n, 2) float64
        Polyline vertices.
    bulges : (n,) float64
        Bulge of the segment from each vertex to the next (0: straight).
    closed : bool
        Whether the last vertex connects back to the first.
    tol : float
        Largest chord error of the flattened arcs.

    Returns
    -------
    (k, 2) float64
        The flattened polyline (no closing repeat when ``closed``).
    """
    n = len(points)
    out = [points[:1]]
    last = n if closed else n - 1
    for i in range(last):
        a = points[i]
        b = points[(i + 1) % n]
        bulge = bulges[i]
        if bulge == 0.0 or (a == b).all():
            out.append(b[None])
            continue
        theta = 4.0 * math.atan(bulge)  # signed included angle, > 0 counter-clockwise
        chord = b - a
        length = math.hypot(*chord)
        radius = length / (2.0 * abs(math.sin(theta / 2.0)))
        mid = (a + b) / 2.0
        left = np.array([-chord[1], chord[0]]) / length
        # centre left of the chord for counter-clockwise arcs under a half turn; cos < 0
        # past a half turn moves it to the other side, as it must
        centre = mid + left * math.copysign(1.0, bulge) * radius * math.cos(theta / 2.0)
        t0 = math.atan2(a[1] - centre[1], a[0] - centre[0])
        pts = arc_points(centre[0], centre[1], radius, radius, 0.0, t0, theta, tol)
        pts[-1] = b
        out.append(pts)
    pts = np.vstack(out)
    if closed and len(pts) > 1 and (pts[-1] == pts[0]).all():
        pts = pts[:-1]
    return pts


def _ocs_to_wcs(entity, pts: np.ndarray) -> np.ndarray:
    """Map OCS points of a planar entity to WCS x, y (mirrored when extrusion is -z)."""
    ext = entity.dxf.get("extrusion", (0.0, 0.0, 1.0))
    if tuple(ext) == (0.0, 0.0, 1.0):
        return pts
    ocs = entity.ocs()
    wcs = np.array([tuple(v)[:2] for v in ocs.points_to_wcs([(x, y, 0.0) for x, y in pts])])
    return wcs


#: $INSUNITS codes -> millimetres per drawing unit
_DXF_MM = {1: 25.4, 2: 304.8, 4: 1.0, 5: 10.0, 6: 1000.0, 9: 0.0254, 10: 914.4, 13: 1e-3, 14: 100.0}


def read_dxf(
    path,
    *,
    tolerance: float = CURVE_TOLERANCE,
    layers=None,
    loose: bool = True,
    to_mm: bool = False,
):
    """Read closed outlines from a DXF file as one boundary (even-odd nesting).

    Reads the modelspace: closed ``LWPOLYLINE`` and 2D ``POLYLINE`` (bulges flattened as true
    arcs), ``CIRCLE``, full ``ELLIPSE`` and closed ``SPLINE`` (flattened by ezdxf). With
    ``loose=True`` the ``LINE`` and ``ARC`` entities and open polylines are joined into
    closed faces as well (``shapely.polygonize``), as many drawings are made of loose
    segments. Blocks (``INSERT``) and hatches are ignored.

    Parameters
    ----------
    path : str or Path
        The DXF file.
    tolerance : float
        Largest distance between a curve and its polyline, in output units.
    layers : sequence of str, optional
        Read only these layers (default: all).
    loose : bool
        Also assemble loose lines/arcs/open polylines into faces.
    to_mm : bool
        Scale to millimetres by the header's ``$INSUNITS`` (inches, feet, cm, m, ...;
        unitless drawings stay as they are). Off by default: many programs (ezdxf's own
        ``new()`` among them) write "metres" for drawings made in millimetres.

    Returns
    -------
    shapely.Polygon or shapely.MultiPolygon

    Raises
    ------
    ValueError
        Missing or unreadable file, or no closed outline.
    """
    import ezdxf

    p = existing_file(path)
    tol = positive_number(tolerance, "tolerance")
    try:
        doc = ezdxf.readfile(p)
    except (OSError, ezdxf.DXFError) as exc:
        raise ValueError(f"{p}: not a readable DXF file ({exc})") from None
    factor = _DXF_MM.get(int(doc.header.get("$INSUNITS", 0)), 1.0) if to_mm else 1.0
    tol = tol / factor  # flatten in drawing units
    wanted = None if layers is None else {str(name) for name in layers}
    rings: list[np.ndarray] = []
    lines: list[np.ndarray] = []
    for e in doc.modelspace():
        if wanted is not None and e.dxf.get("layer", "0") not in wanted:
            continue
        kind = e.dxftype()
        if kind == "LWPOLYLINE":
            data = np.array(e.get_points("xyb"), dtype=np.float64).reshape(-1, 3)
            closed = bool(e.closed) or (len(data) > 2 and (data[0, :2] == data[-1, :2]).all())
            if len(data) < 2:
                continue
            pts = bulge_polyline(data[:, :2], data[:, 2], closed, tol)
            (rings if closed else lines).append(_ocs_to_wcs(e, pts))
        elif kind == "POLYLINE":
            if not (e.is_2d_polyline or e.is_3d_polyline):
                continue
            verts = list(e.vertices)
            if len(verts) < 2:
                continue
            xy = np.array([tuple(v.dxf.location)[:2] for v in verts], dtype=np.float64)
            bulge = np.array([v.dxf.get("bulge", 0.0) for v in verts], dtype=np.float64)
            closed = bool(e.is_closed) or (len(xy) > 2 and (xy[0] == xy[-1]).all())
            pts = bulge_polyline(xy, bulge, closed, tol)
            if e.is_2d_polyline:
                pts = _ocs_to_wcs(e, pts)
            (rings if closed else lines).append(pts)
        elif kind == "CIRCLE":
            c = tuple(e.dxf.center)
            pts = arc_points(c[0], c[1], e.dxf.radius, e.dxf.radius, 0.0, 0.0, 2 * np.pi, tol)
            rings.append(_ocs_to_wcs(e, pts))
        elif kind == "ELLIPSE":
            pts = np.array([tuple(v)[:2] for v in e.flattening(tol)], dtype=np.float64)
            span = (e.dxf.end_param - e.dxf.start_param) % (2 * np.pi)
            full = min(span, 2 * np.pi - span) < ELLIPSE_FULL_TURN_ATOL
            (rings if full else lines).append(pts)
        elif kind == "SPLINE":
            pts = np.array([tuple(v)[:2] for v in e.flattening(tol)], dtype=np.float64)
            closed = bool(e.closed) or (len(pts) > 2 and np.allclose(pts[0], pts[-1]))
            (rings if closed else lines).append(pts)
        elif loose and kind == "LINE":
            lines.append(np.array([tuple(e.dxf.start)[:2], tuple(e.dxf.end)[:2]]))
        elif loose and kind == "ARC":
            c = tuple(e.dxf.center)
            a0 = math.radians(e.dxf.start_angle)
            sweep = math.radians((e.dxf.end_angle - e.dxf.start_angle) % 360.0) or 2 * np.pi
            start = np.array(
                [[c[0] + e.dxf.radius * math.cos(a0), c[1] + e.dxf.radius * math.sin(a0)]]
            )
            arc = arc_points(c[0], c[1], e.dxf.radius, e.dxf.radius, 0.0, a0, sweep, tol)
            lines.append(_ocs_to_wcs(e, np.vstack((start, arc))))
    if loose and lines:
        noded = shapely.node(shapely.MultiLineString([ln for ln in lines if len(ln) >= 2]))
        faces = shapely.get_parts(shapely.polygonize(shapely.get_parts(noded)))
        rings.extend(np.asarray(f.exterior.coords) for f in faces)
    if not rings:
        raise ValueError(f"{p}: no closed outlines (closed LWPOLYLINE/POLYLINE, CIRCLE, ...)")
    out = even_odd([r * factor for r in rings] if factor != 1.0 else rings)
    if out.is_empty:
        raise ValueError(f"{p}: the outlines enclose no area")
    return out
