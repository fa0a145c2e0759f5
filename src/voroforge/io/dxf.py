"""DXF output with ezdxf: closed LWPOLYLINEs on named layers, circular arcs as true bulges.

Laser cutters and CNC software read a DXF polyline with *bulges* as straight segments and
circular arcs. Shapely draws round buffers and fillets as many short chords; :func:`write_dxf`
finds the runs of chords that lie on one circle (:mod:`voroforge.io.arcs`) and writes each
run as one arc, so a filleted corner is a real arc in the cutter's software, not a fan of
tiny lines.

The file is deterministic: the same geometry gives the same bytes (fixed creation date, zero
GUIDs, handles in writing order).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import shapely

from ..config import ARC_TOLERANCE
from .arcs import bulges_of_rings
from .plotter import layer_paths
from .render import as_geometries

__all__ = ["LAYER_COLOURS", "UNITS", "write_dxf"]

#: ``$INSUNITS`` codes of the unit names :func:`write_dxf` accepts.
UNITS = {"unitless": 0, "in": 1, "ft": 2, "mm": 4, "cm": 5, "m": 6}

#: AutoCAD colour index of the conventional fabrication layers (others get white/black, 7).
LAYER_COLOURS = {
    "CUT": 1,  # red
    "SCORE": 5,  # blue
    "ENGRAVE": 3,  # green
    "SITES": 8,  # grey
    "BOUNDARY": 6,  # magenta
    "FRAME": 1,
    "OPENINGS": 1,
    "MARK": 2,  # yellow
}


def write_dxf(
    geoms=None,
    path=None,
    *,
    layers: dict | None = None,
    layer: str = "CUT",
    units: str = "mm",
    arcs: bool = True,
    arc_tolerance: float = ARC_TOLERANCE,
    max_arc_step: float = 30.0,
    colours: dict | None = None,
    version: str = "R2000",
    order: str = "file",
    dedupe: bool = True,
    merge: bool = True,
    point_marks: str = "circle",
    point_radius: float = 0.5,
) -> Path:
    """Write polygons as closed LWPOLYLINEs on named layers, with fillets as true arcs.

    Every polygon ring (exterior and each hole) becomes one closed LWPOLYLINE on its layer.
    Runs of at least three chords of equal length and equal turning that lie on one circle
    (what shapely's round buffers and :func:`voroforge.design.cellops.fillet` produce) are
    written as one arc each, through the vertex *bulge*. LineStrings become open
    LWPOLYLINEs and points POINT entities.

    Parameters
    ----------
    geoms : sequence of shapely geometries, optional
        Geometry for the ``layer`` layer (default ``"CUT"``).
    path : str or Path
        Output file.
    layers : dict of str to sequence of shapely geometries, optional
        More layers, by name (``{"CUT": frame, "SCORE": edges, "ENGRAVE": labels}``).
        Layer names are upper-cased; geometry for a name given twice is merged.
    layer : str
        Layer of ``geoms``.
    units : {"mm", "cm", "m", "in", "ft", "unitless"}
        Drawing units, written as ``$INSUNITS`` (1 data unit = 1 unit).
    arcs : bool
        Fold circular runs into arcs (``False`` writes every chord as a line).
    arc_tolerance : float
        Largest distance, in drawing units, of a vertex from the arc that replaces it.
    max_arc_step : float
        Largest turning per chord in degrees that still counts as part of an arc; coarser
        polygons (hexagons turn 60°) stay polygons.
    colours : dict of str to int, optional
        AutoCAD colour index per layer, over :data:`LAYER_COLOURS`.
    version : str
        DXF version, ``"R2000"`` or newer (``"R2004"``, ``"R2007"``, ``"R2010"``, ``"R2013"``,
        ``"R2018"``).
    order : {"file", "travel"}
        Path order within a layer: as given (rings, then lines), or ordered for short
        travel between paths (:func:`voroforge.io.plotter.layer_paths`).
    dedupe : bool
        Every segment of a layer once: a ring repeating another is dropped, segments shared
        with earlier geometry are cut out (neighbouring cells, frame and openings).
    merge : bool
        Join open line pieces into the fewest polylines, through junctions.
    point_marks : {"circle", "cross", "none"}
        What marks each point besides its POINT entity (laser software ignores POINTs):
        a CIRCLE of ``point_radius`` or a cross of two LINEs of that half-length.
    point_radius : float
        Size of the point marks, in drawing units.

    Returns
    -------
    Path
        The file written.

    Raises
    ------
    ValueError
        For unknown units, an old DXF version, a bad layer name or a non-geometry.

    Examples
    --------
    >>> import shapely, tempfile, pathlib
    >>> part = shapely.box(0, 0, 40, 20).buffer(3, quad_segs=8)
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "part.dxf"
    >>> write_dxf([part], out).name
    'part.dxf'
    """
    import ezdxf

    if path is None:
        raise ValueError("write_dxf needs an output path")
    if units not in UNITS:
        raise ValueError(f"units must be one of {', '.join(UNITS)}; got {units!r}")
    if version not in ("R2000", "R2004", "R2007", "R2010", "R2013", "R2018"):
        raise ValueError(f"version must be R2000 or newer; got {version!r}")
    if not arc_tolerance > 0:
        raise ValueError(f"arc_tolerance must be positive; got {arc_tolerance!r}")
    if point_marks not in ("circle", "cross", "none"):
        raise ValueError(f"point_marks must be 'circle', 'cross' or 'none'; got {point_marks!r}")
    if not (math.isfinite(point_radius) and point_radius > 0):
        raise ValueError(f"point_radius must be positive; got {point_radius!r}")
    content: dict[str, list] = {}
    if geoms is not None:
        content.setdefault(_layer_name(layer), []).extend(as_geometries(geoms))
    for name, value in (layers or {}).items():
        content.setdefault(_layer_name(name), []).extend(as_geometries(value))
    palette = {**LAYER_COLOURS, **{k.upper(): int(v) for k, v in (colours or {}).items()}}

    options = {"tolerance": arc_tolerance, "max_step": math.radians(max_arc_step), "arcs": arcs}
    saved = ezdxf.options.write_fixed_meta_data_for_testing
    ezdxf.options.write_fixed_meta_data_for_testing = True
    try:
        doc = ezdxf.new(version, setup=False, units=UNITS[units])
        doc.header["$MEASUREMENT"] = 0 if units in ("in", "ft") else 1
        msp = doc.modelspace()
        for name, items in content.items():
            doc.layers.add(name, color=palette.get(name, 7))
            attribs = {"layer": name}
            drawn = layer_paths(items, order=order, dedupe=dedupe, merge=merge)
            fitted = iter(bulges_of_rings(drawn.rings(), **options))
            for xy, closed in zip(drawn.paths, drawn.closed.tolist(), strict=True):
                if closed:
                    _add_closed(msp, next(fitted), attribs)
                else:
                    msp.add_lwpolyline(xy.tolist(), format="xy", close=False, dxfattribs=attribs)
            for geom in items:
                if "Point" not in geom.geom_type and geom.geom_type != "GeometryCollection":
                    continue
                for pt in shapely.get_parts(geom):
                    if pt.geom_type == "Point":
                        _add_point(msp, pt.x, pt.y, point_marks, point_radius, attribs)
        path = Path(path)
        tmp = path.with_name(f".{path.name}.tmp")
        try:
            doc.saveas(tmp)
            tmp.replace(path)  # atomic: a reader never sees half a file
        finally:
            tmp.unlink(missing_ok=True)
    finally:
        ezdxf.options.write_fixed_meta_data_for_testing = saved
    return path


def _add_point(msp, x: float, y: float, marks: str, r: float, attribs: dict) -> None:
    """A POINT (for CAD) and a mark a laser cuts or engraves: a circle or a cross."""
    msp.add_point((x, y), dxfattribs=attribs)
    if marks == "circle":
        msp.add_circle((x, y), r, dxfattribs=attribs)
    elif marks == "cross":
        msp.add_line((x - r, y), (x + r, y), dxfattribs=attribs)
        msp.add_line((x, y - r), (x, y + r), dxfattribs=attribs)


def _add_closed(msp, points: np.ndarray, attribs: dict) -> None:
    """Add a closed LWPOLYLINE of ``(k, 3)`` x, y, bulge rows.

    ezdxf keeps LWPOLYLINE vertices as an ``(k, 5)`` float array (x, y, start width, end
    width, bulge); filling it in one go is several times faster than appending point by
    point. Any other layout (a future ezdxf) takes the public, slower way.
    """
    e = msp.add_lwpolyline([], close=True, dxfattribs=attribs)
    store = getattr(e, "lwpoints", None)
    values = getattr(store, "values", None)
    if isinstance(values, np.ndarray) and values.ndim == 2 and values.shape[1] == 5:
        block = np.zeros((len(points), 5))
        block[:, :2] = points[:, :2]
        block[:, 4] = points[:, 2]
        store.values = block
    else:  # pragma: no cover - depends on ezdxf internals
        e.set_points(points.tolist(), format="xyb")


def _layer_name(name) -> str:
    text = str(name).strip().upper()
    bad = set('<>/\\":;?*|=`')
    if not text or any(c in bad for c in text):
        raise ValueError(f"invalid DXF layer name {name!r}")
    return text
