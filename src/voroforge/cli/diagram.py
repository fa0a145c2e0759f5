"""``voroforge voronoi`` and ``voroforge delaunay``: a point file in, cells or triangles out."""

from __future__ import annotations

import argparse
from pathlib import Path

from .outputs import check_outputs, unused_option
from .progress import Stage

__all__ = ["POINTS_HELP", "add_parsers", "run_delaunay", "run_voronoi"]

#: Help text of a POINTS argument.
POINTS_HELP = (
    "point file: .csv/.txt (x,y columns, header optional), .npy (n x 2 array) "
    "or .geojson/.json (Point/MultiPoint features)"
)

_VORONOI_EPILOG = """\
The output type follows each OUT's suffix: .svg, .png, .geojson, .json, .dxf or .parquet
(GeoParquet: site_id, geometry, area, neighbors, bbox). Give -o several times to write
several files from one computation.

examples:
  voroforge voronoi points.csv -o cells.svg
  voroforge voronoi points.csv -o cells.png --size 2048
  voroforge voronoi points.npy -o cells.geojson --boundary 0,0,100,50
  voroforge voronoi points.csv -o cells.svg --units mm -o cells.geojson \\
      --boundary outline.geojson
  voroforge voronoi points.csv -o cells.svg --boundary=-10,-10,10,10
  voroforge voronoi points.csv -o edges.dxf --edges   the edge network, each edge once

A DXF of cells draws every shared edge once (a laser cuts it once); --edges writes the
network as long strokes in pen-up order, for plotters.

A bounding box with a negative first number needs the '=' form shown last.
A GeoJSON boundary file's Polygon/MultiPolygon features are united, holes kept; an SVG
file gives its filled shapes, a DXF file its closed outlines (nested ones are holes).
"""

_DELAUNAY_EPILOG = """\
The output type follows each OUT's suffix: .svg, .png, .geojson, .json or .dxf.
GeoJSON features are the triangles, with their vertex indices in "vertices".

examples:
  voroforge delaunay points.csv -o triangles.svg
  voroforge delaunay points.npy -o triangles.geojson
"""


#: what ``voronoi -o`` writes besides :data:`voroforge.io.FORMATS` (``delaunay`` lacks it)
_VORONOI_SUFFIXES = ".svg, .png, .geojson, .json, .dxf, .parquet or .geoparquet"


def _add_outputs(sub: argparse.ArgumentParser, suffixes=".svg, .png, .geojson, .json or .dxf"):
    sub.add_argument(
        "-o",
        "--output",
        metavar="OUT",
        action="append",
        required=True,
        help=f"output file; {suffixes} (repeatable)",
    )
    sub.add_argument(
        "--size", type=int, default=None, help="PNG size in pixels, longer side (default 1024)"
    )
    sub.add_argument(
        "--units",
        choices=("mm", "cm", "in", "pt", "px"),
        help="SVG size units (with mm, 1 data unit = 1 mm) and DXF $INSUNITS (pt and px: unitless)",
    )


#: ``--size`` when not given.
_PNG_SIZE = 1024


def _option_uses(args: argparse.Namespace, kinds: list[str]) -> None:
    """Warn about ``--size``/``--units`` given where no output uses them; fill defaults."""
    if args.size is not None and "png" not in kinds:
        unused_option(f"--size {args.size}", ".png outputs")
    if args.units is not None and not {"svg", "dxf"} & set(kinds):
        unused_option(f"--units {args.units}", ".svg and .dxf outputs")
    if args.size is None:
        args.size = _PNG_SIZE


def _check_parquet(kinds: list[str]) -> None:
    """GeoParquet needs pyarrow (the ``scale`` extra): say so before writing anything."""
    import importlib.util

    if "parquet" in kinds and importlib.util.find_spec("pyarrow") is None:
        raise ValueError(
            "GeoParquet output needs pyarrow: pip install 'voroforge[scale]' (nothing written)"
        )


def add_parsers(commands, formatter_class) -> None:
    """Add ``voronoi`` and ``delaunay`` to ``commands`` (see :mod:`voroforge.cli`)."""
    vor = commands.add_parser(
        "voronoi",
        help="Voronoi cells of a point file, clipped to a boundary",
        description="Compute the Voronoi cells of POINTS, clipped to a boundary, and write them.",
        epilog=_VORONOI_EPILOG,
        formatter_class=formatter_class,
    )
    vor.add_argument("points", metavar="POINTS", help=POINTS_HELP)
    _add_outputs(vor, _VORONOI_SUFFIXES)
    vor.add_argument(
        "--boundary",
        metavar="FILE|xmin,ymin,xmax,ymax",
        help="domain: a GeoJSON, SVG or DXF file, or a box (default: the points' box padded 10%%)",
    )
    vor.add_argument(
        "--edges",
        action="store_true",
        help="write the unique edge network (each shared edge once, joined into long "
        "strokes, ordered for short pen-up travel) instead of closed cells: .svg/.dxf/.geojson",
    )
    vor.add_argument(
        "--algorithm",
        default="delaunay",
        help="engine algorithm: delaunay (default), fortune or halfplane where available",
    )
    vor.set_defaults(run=run_voronoi)

    tri = commands.add_parser(
        "delaunay",
        help="Delaunay triangles of a point file",
        description="Compute the Delaunay triangulation of POINTS and write its triangles.",
        epilog=_DELAUNAY_EPILOG,
        formatter_class=formatter_class,
    )
    tri.add_argument("points", metavar="POINTS", help=POINTS_HELP)
    _add_outputs(tri)
    tri.set_defaults(run=run_delaunay)


def run_voronoi(args: argparse.Namespace, stage: Stage) -> list[Path]:
    """Run ``voroforge voronoi``; returns the files written."""
    import voroforge as vf

    from .. import io

    kinds = []
    for out in args.output:
        try:
            kind = "parquet" if _is_parquet(out) else io.output_format(out)
        except ValueError:
            raise ValueError(
                f"{out}: unsupported output type {Path(out).suffix or '(none)'!r}; "
                f"use {_VORONOI_SUFFIXES}"
            ) from None
        if args.edges and kind in ("png", "parquet"):
            raise ValueError(f"{out}: --edges writes .svg, .dxf or .geojson, not .{kind}")
        kinds.append(kind)
    # every output's options checked before any is written: a failing run writes nothing
    _option_uses(args, kinds)
    _check_parquet(kinds)
    check_outputs(args.output, png=lambda: _check_png(args.size), inputs=_inputs(args))
    stage("reading")
    from ..io.readers import boundary_crs, read_point_table
    from ..io.readers.points import attribute_names

    # every input row keeps its place (row i is cell i; a site outside the domain gets an
    # empty cell), its attributes and the boundary's CRS go to the GeoJSON/GeoParquet cells
    points, attributes = read_point_table(args.points)
    attributes = dict(
        zip(attribute_names(list(attributes), _RESERVED), attributes.values(), strict=True)
    )
    boundary = io.read_boundary(args.boundary) if args.boundary else None
    crs = boundary_crs(args.boundary) if args.boundary else None
    stage(f"computing {len(points)} Voronoi cells")
    d = vf.voronoi(points, boundary, algorithm=args.algorithm)
    if args.edges:
        return _write_edges(d, args, stage)
    written = []
    for out in args.output:
        stage(f"writing {out}")
        if _is_parquet(out):  # GeoParquet cells (voroforge.io.parquet, the scale extra)
            from ..io.parquet import write_cells

            written.append(
                write_cells(d, out, crs=_parquet_crs(crs), attributes=attributes or None)
            )
            continue
        if io.output_format(out) == "geojson":
            written.append(
                io.write_geojson(d.cells, out, sites=d.sites, properties=attributes, crs=crs)
            )
            continue
        written.append(
            io.write(
                d.cells, out, sites=d.sites, boundary=d.boundary, size=args.size, units=args.units
            )
        )
    return written


#: Columns the writers fill themselves: an input attribute of that name is kept as input_<name>.
_RESERVED = {"index", "site", "area", "site_id", "geometry", "neighbors", "bbox"}


def _parquet_crs(crs):
    """A GeoJSON ``crs`` member's name (``urn:ogc:def:crs:EPSG::2056``) for GeoParquet."""
    if not crs:
        return None
    name = (crs.get("properties") or {}).get("name")
    return name if isinstance(name, str) else None


def _inputs(args) -> list:
    """The files a command reads: POINTS and a ``--boundary`` file (not written over)."""
    boundary = getattr(args, "boundary", None)
    return [args.points, *([boundary] if boundary else [])]


def _check_png(size) -> None:
    from ..io.png import check_png_size

    check_png_size(size)


def _is_parquet(out) -> bool:
    return str(out).lower().endswith((".parquet", ".geoparquet"))


def _write_edges(d, args: argparse.Namespace, stage: Stage) -> list[Path]:
    """The unique edge network of ``d`` and its outline, as merged, ordered strokes."""
    from .. import io
    from ..io.plotter import network_lines

    lines = network_lines(d.edges.coords, d.boundary)
    written = []
    for out in args.output:
        stage(f"writing {out}")
        kind = io.output_format(out)
        if kind == "svg":
            written.append(
                io.write_layers(out, {"EDGES": lines}, units=args.units or "px", merge=False)
            )
        elif kind == "dxf":
            written.append(
                io.write_dxf(None, out, layers={"EDGES": lines}, units=io.dxf_units(args.units))
            )
        else:
            written.append(io.write_geojson(lines, out))
    return written


def run_delaunay(args: argparse.Namespace, stage: Stage) -> list[Path]:
    """Run ``voroforge delaunay``; returns the files written."""
    import voroforge as vf

    from .. import io

    _option_uses(args, [io.output_format(out) for out in args.output])
    check_outputs(args.output, png=lambda: _check_png(args.size), inputs=_inputs(args))
    stage("reading")
    points = io.read_points(args.points)
    stage(f"triangulating {len(points)} points")
    tri = vf.delaunay(points)
    polygons = io.triangle_polygons(tri.points, tri.triangles)
    written = []
    for out in args.output:
        stage(f"writing {out}")
        drawn = None if io.output_format(out) == "geojson" else tri.points
        written.append(
            io.write(
                polygons,
                out,
                sites=drawn,
                properties={"vertices": tri.triangles},
                size=args.size,
                units=args.units,
            )
        )
    return written
