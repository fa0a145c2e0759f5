"""DXF output: closed LWPOLYLINEs on named layers, circular arcs as true bulges.

Laser cutters and CNC software read a DXF polyline with *bulges* as straight segments and
circular arcs. Shapely draws round buffers and fillets as many short chords; :func:`write_dxf`
finds the runs of chords that lie on one circle (:mod:`voroforge.io.arcs`) and writes each
run as one arc, so a filleted corner is a real arc in the cutter's software, not a fan of
tiny lines.

The file is deterministic: the same geometry gives the same bytes (fixed creation date, zero
GUIDs, handles in writing order).

The default DXF version, R2000, is written without importing ezdxf (0.2-0.3 s of a first
``voroforge build``): the document skeleton ezdxf writes for an empty drawing is kept as
package data, ``io/data/r2000.dxf`` (:func:`dxf_skeleton` makes it again from ezdxf), and the
layers and entities are filled in as ezdxf would write them, byte for byte
(``tests/test_firstrun.py`` compares the two writers). Other versions, and layer names the
skeleton already holds or that are not ASCII, go through ezdxf.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import shapely

from ..config import ARC_TOLERANCE
from .arcs import bulges_of_rings
from .atomic import write_atomically
from .plotter import layer_paths
from .render import as_geometries, data_bounds

__all__ = ["LAYER_COLOURS", "UNITS", "R2000", "dxf_skeleton", "write_dxf"]

#: The handle of the first layer added to the R2000 skeleton (ezdxf's next free handle).
FIRST_HANDLE = 0x2F


def stored_skeleton() -> str:
    """The R2000 skeleton stored as package data (``~FIELD~`` marks what a drawing fills in)."""
    from importlib.resources import files

    return files("voroforge.io").joinpath("data", "r2000.dxf").read_text(encoding="ascii")


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
    everything = [g for items in content.values() for g in items]
    if everything:
        data_bounds(np.array(everything, dtype=object))  # a width past float64 is refused

    options = {"tolerance": arc_tolerance, "max_step": math.radians(max_arc_step), "arcs": arcs}
    drawing = {
        "units": units,
        "options": options,
        "order": order,
        "dedupe": dedupe,
        "merge": merge,
        "point_marks": point_marks,
        "point_radius": point_radius,
    }
    if version == "R2000" and _skeleton_holds(content):
        text = _r2000_text(content, palette, **drawing)
        return write_atomically(path, lambda tmp: _write_text(tmp, text), suffix=".tmp")
    return _write_ezdxf(content, palette, Path(path), version, **drawing)


def _write_text(path: str, text: str) -> None:
    # as ezdxf saves R2000: text mode (the platform's line ends), the drawing's code page
    with open(path, "w", encoding="cp1252") as fp:
        fp.write(text)


def _skeleton_holds(content: dict) -> bool:
    """Whether the stored R2000 skeleton can take these layers (else ezdxf writes the file).

    The skeleton already has layers ``0`` and ``Defpoints``; ezdxf writes names outside ASCII
    in the code page with escapes, which the direct writer leaves to it.
    """
    return all(name.isascii() and name not in ("0", "DEFPOINTS") for name in content)


def _r2000_text(
    content: dict, palette: dict, *, units, options, order, dedupe, merge, point_marks, point_radius
) -> str:
    """The R2000 DXF text ezdxf would write for these layers, without ezdxf."""
    doc = R2000()
    for name, items in content.items():
        doc.layer(name, palette.get(name, 7))
        drawn = layer_paths(items, order=order, dedupe=dedupe, merge=merge)
        fitted = iter(bulges_of_rings(drawn.rings(), **options))
        for xy, closed in zip(drawn.paths, drawn.closed.tolist(), strict=True):
            rows = next(fitted).tolist() if closed else [(x, y, 0.0) for x, y in xy.tolist()]
            doc.lwpolyline(name, rows, closed)
        for geom in items:
            if "Point" not in geom.geom_type and geom.geom_type != "GeometryCollection":
                continue
            for pt in shapely.get_parts(geom):
                if pt.geom_type != "Point":
                    continue
                x, y, r = float(pt.x), float(pt.y), float(point_radius)
                doc.point(name, x, y)
                if point_marks == "circle":
                    doc.circle(name, x, y, r)
                elif point_marks == "cross":
                    doc.line(name, x - r, y, x + r, y)
                    doc.line(name, x, y - r, x, y + r)
    return doc.document(units)


class R2000:
    """An R2000 DXF document written as ezdxf writes it, without importing ezdxf.

    Layers and entities get handles in the order they are added, from 0x2F on (ezdxf's
    first free handle in a new drawing); after them come the three objects ezdxf adds when
    it saves (two APPIDs and its ``WRITTEN_BY_EZDXF`` variable), and ``$HANDSEED`` is the
    next one. Coordinates are written as ``repr`` gives them, as ezdxf does. Layer names
    must be ASCII and neither ``0`` nor ``DEFPOINTS`` (the skeleton's own layers).
    """

    def __init__(self) -> None:
        self._handle = FIRST_HANDLE
        self._layers: list[str] = []
        self._entities: list[str] = []

    def _next(self) -> str:
        h = self._handle
        self._handle += 1
        return f"{h:X}"

    def layer(self, name: str, colour: int = 7) -> None:
        """Add a layer table record (continuous line type, ``colour`` an AutoCAD index)."""
        self._layers.append(
            f"  0\nLAYER\n  5\n{self._next()}\n330\n1\n100\nAcDbSymbolTableRecord\n100\n"
            f"AcDbLayerTableRecord\n  2\n{name}\n 70\n0\n 62\n{int(colour)}\n"
            "  6\nContinuous\n370\n-3\n390\n13\n"
        )

    def _head(self, kind: str, layer: str) -> str:
        return f"  0\n{kind}\n  5\n{self._next()}\n330\n17\n100\nAcDbEntity\n  8\n{layer}\n"

    def lwpolyline(self, layer: str, rows, closed: bool) -> None:
        """An LWPOLYLINE of ``(x, y, bulge)`` rows (Python floats; zero bulges left out)."""
        out = [
            self._head("LWPOLYLINE", layer),
            f"100\nAcDbPolyline\n 90\n{len(rows)}\n 70\n{1 if closed else 0}\n",
        ]
        out.extend(
            f" 10\n{x!r}\n 20\n{y!r}\n 42\n{b!r}\n" if b else f" 10\n{x!r}\n 20\n{y!r}\n"
            for x, y, b in rows
        )
        self._entities.append("".join(out))

    def point(self, layer: str, x: float, y: float) -> None:
        """A POINT."""
        self._entities.append(
            f"{self._head('POINT', layer)}100\nAcDbPoint\n 10\n{x!r}\n 20\n{y!r}\n 30\n0.0\n"
        )

    def circle(self, layer: str, x: float, y: float, r: float) -> None:
        """A CIRCLE."""
        self._entities.append(
            f"{self._head('CIRCLE', layer)}100\nAcDbCircle\n"
            f" 10\n{x!r}\n 20\n{y!r}\n 30\n0.0\n 40\n{r!r}\n"
        )

    def line(self, layer: str, x0: float, y0: float, x1: float, y1: float) -> None:
        """A LINE."""
        self._entities.append(
            f"{self._head('LINE', layer)}100\nAcDbLine\n 10\n{x0!r}\n 20\n{y0!r}\n 30\n0.0\n"
            f" 11\n{x1!r}\n 21\n{y1!r}\n 31\n0.0\n"
        )

    def text(self, layer: str, text: str, x: float, y: float, height: float) -> None:
        """A one-line TEXT centred on ``(x, y)`` (ezdxf's ``MIDDLE_CENTER`` placement)."""
        self._entities.append(
            f"{self._head('TEXT', layer)}100\nAcDbText\n 10\n{x!r}\n 20\n{y!r}\n 30\n0.0\n"
            f" 40\n{height!r}\n  1\n{text}\n 72\n1\n 11\n{x!r}\n 21\n{y!r}\n 31\n0.0\n"
            "100\nAcDbText\n 73\n2\n"
        )

    def document(self, units: str, measurement: int | None = None) -> str:
        """The whole file: ``$INSUNITS`` from ``units``, ``$MEASUREMENT`` 0 for in/ft."""
        if measurement is None:
            measurement = 0 if units in ("in", "ft") else 1
        h = self._handle
        fields = {
            "INSUNITS": str(UNITS[units]),
            "MEASUREMENT": str(int(measurement)),
            "NLAYERS": str(2 + len(self._layers)),
            "LAYERS": "".join(self._layers),
            "ENTITIES": "".join(self._entities),
            "APPID1": f"{h:X}",
            "APPID2": f"{h + 1:X}",
            "WRITTEN": f"{h + 2:X}",
            "HANDSEED": f"{h + 3:X}",
        }
        # the skeleton alternates text and field names: "...~FIELD~..."
        parts = stored_skeleton().split("~")
        return "".join(fields[part] if k % 2 else part for k, part in enumerate(parts))


def dxf_skeleton() -> str:
    """The R2000 skeleton of ``io/data/r2000.dxf``, made again with ezdxf.

    ezdxf writes an empty drawing with one layer; the parts that vary (units, the layer
    table, the entities, the handles given after them) become ``~FIELD~`` marks.
    ``tests/test_firstrun.py`` checks that the stored copy is what the installed ezdxf
    writes.
    """
    import io

    import ezdxf

    saved = ezdxf.options.write_fixed_meta_data_for_testing
    ezdxf.options.write_fixed_meta_data_for_testing = True
    try:
        doc = ezdxf.new("R2000", setup=False, units=4)
        doc.header["$MEASUREMENT"] = 1
        doc.layers.add("VOROFORGE", color=7)
        stream = io.StringIO()
        doc.write(stream)
    finally:
        ezdxf.options.write_fixed_meta_data_for_testing = saved
    text = stream.getvalue()
    if "~" in text:
        raise ValueError("ezdxf's skeleton holds '~', which marks the fields")
    layer = (
        "  0\nLAYER\n  5\n2F\n330\n1\n100\nAcDbSymbolTableRecord\n100\nAcDbLayerTableRecord\n"
        "  2\nVOROFORGE\n 70\n0\n 62\n7\n  6\nContinuous\n370\n-3\n390\n13\n"
    )
    for old, new in (
        ("$INSUNITS\n 70\n4\n", "$INSUNITS\n 70\n~INSUNITS~\n"),
        ("$MEASUREMENT\n 70\n1\n", "$MEASUREMENT\n 70\n~MEASUREMENT~\n"),
        ("$HANDSEED\n  5\n33\n", "$HANDSEED\n  5\n~HANDSEED~\n"),
        (
            "  2\nLAYER\n  5\n1\n330\n0\n100\nAcDbSymbolTable\n 70\n3\n",
            "  2\nLAYER\n  5\n1\n330\n0\n100\nAcDbSymbolTable\n 70\n~NLAYERS~\n",
        ),
        (layer, "~LAYERS~"),
        ("  2\nENTITIES\n  0\nENDSEC\n", "  2\nENTITIES\n~ENTITIES~  0\nENDSEC\n"),
        ("APPID\n  5\n30\n", "APPID\n  5\n~APPID1~\n"),
        ("APPID\n  5\n31\n", "APPID\n  5\n~APPID2~\n"),
        ("WRITTEN_BY_EZDXF\n350\n32\n", "WRITTEN_BY_EZDXF\n350\n~WRITTEN~\n"),
        ("DICTIONARYVAR\n  5\n32\n", "DICTIONARYVAR\n  5\n~WRITTEN~\n"),
    ):
        if text.count(old) != 1:
            raise ValueError(f"ezdxf's skeleton changed: {old!r} is not there once")
        text = text.replace(old, new)
    return text


def _write_ezdxf(
    content: dict,
    palette: dict,
    path: Path,
    version: str,
    *,
    units,
    options,
    order,
    dedupe,
    merge,
    point_marks,
    point_radius,
) -> Path:
    """Write the layers with ezdxf (any version from R2000 on)."""
    import ezdxf

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
