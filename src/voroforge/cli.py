"""The ``voroforge`` command line: parse arguments, call the library, print what was written."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable, Sequence
from contextlib import contextmanager
from pathlib import Path

PROG = "voroforge"

_MAIN_EPILOG = """\
examples:
  voroforge demo -o out                      write out/demo.svg, demo.png, demo.geojson
  voroforge voronoi points.csv -o cells.svg  Voronoi cells of points.csv as SVG
  voroforge voronoi points.csv -o cells.geojson --boundary domain.geojson
  voroforge delaunay points.csv -o triangles.svg
  voroforge raster points.csv -o cells.png --size 2048x2048 --method jfa
  voroforge explain fortune points.csv -o sweep.gif   animation of Fortune's sweep

Run 'voroforge COMMAND --help' for the options of one command.
"""

_POINTS_HELP = (
    "point file: .csv/.txt (x,y columns, header optional), .npy (n x 2 array) "
    "or .geojson/.json (Point/MultiPoint features)"
)

_VORONOI_EPILOG = """\
The output type follows each OUT's suffix: .svg, .png, .geojson or .json.
Give -o several times to write several files from one computation.

examples:
  voroforge voronoi points.csv -o cells.svg
  voroforge voronoi points.csv -o cells.png --size 2048
  voroforge voronoi points.npy -o cells.geojson --boundary 0,0,100,50
  voroforge voronoi points.csv -o cells.svg --units mm -o cells.geojson \\
      --boundary outline.geojson
  voroforge voronoi points.csv -o cells.svg --boundary=-10,-10,10,10

A bounding box with a negative first number needs the '=' form shown last.
A boundary file is GeoJSON; all its Polygon/MultiPolygon features are united, holes kept.
"""

_DELAUNAY_EPILOG = """\
The output type follows each OUT's suffix: .svg, .png, .geojson or .json.
GeoJSON features are the triangles, with their vertex indices in "vertices".

examples:
  voroforge delaunay points.csv -o triangles.svg
  voroforge delaunay points.npy -o triangles.geojson
"""

_DEMO_EPILOG = """\
examples:
  voroforge demo               writes out/demo.svg, out/demo.png, out/demo.geojson
  voroforge demo -o /tmp/vf    the same files in /tmp/vf
"""


def _parser() -> argparse.ArgumentParser:
    from . import __version__

    raw = argparse.RawDescriptionHelpFormatter
    parser = argparse.ArgumentParser(
        prog=PROG,
        description="Voronoi diagrams clipped to any domain, and Delaunay triangulations.",
        epilog=_MAIN_EPILOG,
        formatter_class=raw,
    )
    parser.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    commands = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)

    vor = commands.add_parser(
        "voronoi",
        help="Voronoi cells of a point file, clipped to a boundary",
        description="Compute the Voronoi cells of POINTS, clipped to a boundary, and write them.",
        epilog=_VORONOI_EPILOG,
        formatter_class=raw,
    )
    vor.add_argument("points", metavar="POINTS", help=_POINTS_HELP)
    _add_outputs(vor)
    vor.add_argument(
        "--boundary",
        metavar="FILE|xmin,ymin,xmax,ymax",
        help="domain: a GeoJSON polygon file or a box (default: the points' box padded 10%%)",
    )
    vor.add_argument(
        "--algorithm",
        default="delaunay",
        help="engine algorithm: delaunay (default), fortune or halfplane where available",
    )

    tri = commands.add_parser(
        "delaunay",
        help="Delaunay triangles of a point file",
        description="Compute the Delaunay triangulation of POINTS and write its triangles.",
        epilog=_DELAUNAY_EPILOG,
        formatter_class=raw,
    )
    tri.add_argument("points", metavar="POINTS", help=_POINTS_HELP)
    _add_outputs(tri)

    demo = commands.add_parser(
        "demo",
        help="write a demo diagram (SVG, PNG, GeoJSON)",
        description="300 random sites in an outline with a hole: writes demo.svg, demo.png "
        "and demo.geojson.",
        epilog=_DEMO_EPILOG,
        formatter_class=raw,
    )
    demo.add_argument(
        "-o", "--output", metavar="DIR", default="out", help="output folder (default: out)"
    )

    from .io.raster_png import add_raster_parser

    add_raster_parser(commands, formatter_class=raw)

    from .explain.command import add_explain_parser

    add_explain_parser(commands, formatter_class=raw)
    return parser


def _add_outputs(sub: argparse.ArgumentParser) -> None:
    sub.add_argument(
        "-o",
        "--output",
        metavar="OUT",
        action="append",
        required=True,
        help="output file; .svg, .png, .geojson or .json (repeatable)",
    )
    sub.add_argument(
        "--size", type=int, default=1024, help="PNG size in pixels, longer side (default 1024)"
    )
    sub.add_argument(
        "--units",
        choices=("mm", "cm", "in", "pt", "px"),
        help="SVG size units; with mm, 1 data unit = 1 mm",
    )


Stage = Callable[[str], None]


@contextmanager
def _progress(enabled: bool):
    """Yield ``stage(name)``; shows a transient spinner on a terminal, nothing otherwise."""
    if not enabled:
        yield lambda name: None
        return
    from rich.console import Console
    from rich.progress import Progress, SpinnerColumn, TextColumn, TimeElapsedColumn

    progress = Progress(
        SpinnerColumn(),
        TextColumn("{task.description}"),
        TimeElapsedColumn(),
        console=Console(stderr=True),
        transient=True,
    )
    with progress:
        task = progress.add_task("starting", total=None)
        yield lambda name: progress.update(task, description=name)


def _voronoi(args: argparse.Namespace, stage: Stage) -> list[Path]:
    import voroforge as vf

    from . import io

    for out in args.output:
        io.output_format(out)
    stage("reading")
    points = io.read_points(args.points)
    boundary = io.read_boundary(args.boundary) if args.boundary else None
    stage(f"computing {len(points)} Voronoi cells")
    d = vf.voronoi(points, boundary, algorithm=args.algorithm)
    written = []
    for out in args.output:
        stage(f"writing {out}")
        written.append(
            io.write(
                d.cells, out, sites=d.sites, boundary=d.boundary, size=args.size, units=args.units
            )
        )
    return written


def _delaunay(args: argparse.Namespace, stage: Stage) -> list[Path]:
    import voroforge as vf

    from . import io

    for out in args.output:
        io.output_format(out)
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


def _demo(args: argparse.Namespace, stage: Stage) -> list[Path]:
    from .demo import build_demo

    return build_demo(args.output, progress=stage)


_COMMANDS = {"voronoi": _voronoi, "delaunay": _delaunay, "demo": _demo}


def _raster(args: argparse.Namespace, stage: Stage) -> list[Path]:
    from .io.raster_png import raster_command

    return raster_command(args, stage)


_COMMANDS["raster"] = _raster


def _explain(args: argparse.Namespace, stage: Stage) -> list[Path]:
    from .explain.command import explain_command

    return explain_command(args, stage)


_COMMANDS["explain"] = _explain


def _error(message: str) -> int:
    print(f"{PROG}: error: {message}", file=sys.stderr)
    return 2


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line.

    Parameters
    ----------
    argv : sequence of str, optional
        Arguments without the program name (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        Exit status: 0 on success, 2 on bad arguments or input (message on stderr).
    """
    try:
        args = _parser().parse_args(argv)
    except SystemExit as exc:  # --help, --version and argparse's own usage errors
        return exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 2)
    try:
        with _progress(sys.stderr.isatty()) as stage:
            written = _COMMANDS[args.command](args, stage)
    except ValueError as exc:
        return _error(str(exc))
    except OSError as exc:
        where = f": {exc.filename}" if exc.filename else ""
        return _error(f"{exc.strerror or exc}{where}")
    except KeyboardInterrupt:
        print(f"{PROG}: interrupted", file=sys.stderr)
        return 130
    for path in written:
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
