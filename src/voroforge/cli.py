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
  voroforge demo -o out                      the flagship laser-cut panel: SVG, DXF, PNG
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
The output type follows each OUT's suffix: .svg, .png, .geojson, .json or .dxf.
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
The output type follows each OUT's suffix: .svg, .png, .geojson, .json or .dxf.
GeoJSON features are the triangles, with their vertex indices in "vertices".

examples:
  voroforge delaunay points.csv -o triangles.svg
  voroforge delaunay points.npy -o triangles.geojson
"""

_DEMO_EPILOG = """\
examples:
  voroforge demo               writes out/laser-panel.svg, .dxf and .png
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
        help="build the flagship design: a laser-cut panel (SVG, DXF, PNG)",
        description="Build the flagship design (examples/laser-panel.toml: a 600 x 400 mm "
        "laser-cut panel, 3 mm webs, 2 mm fillets): writes laser-panel.svg, .dxf and .png.",
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
    _add_design_parsers(commands, raw)
    return parser


_BUILD_EPILOG = """\
Writes every output the design file names (output.formats) into DIR and prints the paths.
Same file and seed -> byte-identical files.

examples:
  voroforge build examples/laser-panel.toml -o out
  voroforge build panel.toml --set seeds.radius=25 --set cells.web=4
  voroforge build panel.toml --preview          only the PNG preview, quickly
"""

_NEW_EPILOG = """\
examples:
  voroforge new                  writes design.toml
  voroforge new panel.toml       then: voroforge build panel.toml -o out
"""

_CHECK_EPILOG = """\
Checks the limits of the design's [fabrication] table: min_web, min_opening, tool_radius,
and loose islands. Prints one row per violation with its location.

examples:
  voroforge check panel.toml
  voroforge check panel.toml --strict --set fabrication.min_web=4
  voroforge check panel.toml --overlay check.png   the panel with violations circled
"""


def _add_design_parsers(commands, raw) -> None:
    """The design-file commands: build, new, check."""
    build = commands.add_parser(
        "build",
        help="build a TOML design file into SVG/DXF/PNG/GeoJSON/GIF",
        description="Build DESIGN (a TOML design file) and write the files it names.",
        epilog=_BUILD_EPILOG,
        formatter_class=raw,
    )
    build.add_argument("design", metavar="DESIGN", help="design file (.toml)")
    build.add_argument(
        "-o", "--output", metavar="DIR", default="out", help="output folder (default: out)"
    )
    _add_set(build)
    build.add_argument(
        "--preview", action="store_true", help="write only the PNG preview (at most 800 px)"
    )

    new = commands.add_parser(
        "new",
        help="write a commented starter design file",
        description="Write a commented starter design file to PATH (default design.toml).",
        epilog=_NEW_EPILOG,
        formatter_class=raw,
    )
    new.add_argument("path", metavar="PATH", nargs="?", default="design.toml")
    new.add_argument("--force", action="store_true", help="overwrite an existing file")

    check = commands.add_parser(
        "check",
        help="fabrication check of a design file (thin webs, small openings, corners)",
        description="Build DESIGN's geometry and check it against its [fabrication] limits.",
        epilog=_CHECK_EPILOG,
        formatter_class=raw,
    )
    check.add_argument("design", metavar="DESIGN", help="design file (.toml)")
    _add_set(check)
    check.add_argument(
        "--strict", action="store_true", help="exit with status 1 when there are violations"
    )
    check.add_argument(
        "--overlay",
        metavar="FILE",
        help="also draw the panel with every violation circled (.png or .svg)",
    )


def _add_set(sub: argparse.ArgumentParser) -> None:
    sub.add_argument(
        "--set",
        metavar="KEY=VALUE",
        action="append",
        default=[],
        help="override a key of the design file, e.g. seeds.count=500 (repeatable)",
    )


def _add_outputs(sub: argparse.ArgumentParser) -> None:
    sub.add_argument(
        "-o",
        "--output",
        metavar="OUT",
        action="append",
        required=True,
        help="output file; .svg, .png, .geojson, .json or .dxf (repeatable)",
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


def _overrides(pairs: list[str]) -> dict:
    out = {}
    for pair in pairs:
        key, sep, value = pair.partition("=")
        if not sep or not key.strip():
            raise ValueError(f"--set {pair!r}: expected KEY=VALUE, e.g. seeds.count=500")
        out[key.strip()] = value.strip()
    return out


def _build(args: argparse.Namespace, stage: Stage) -> list[Path]:
    import warnings

    from .design.pipeline import DesignWarning, build

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", DesignWarning)
        written = build(
            args.design,
            args.output,
            overrides=_overrides(args.set),
            preview=args.preview,
            progress=stage,
        )
    for w in caught:
        if issubclass(w.category, DesignWarning):
            print(f"{PROG}: warning: {args.design}: {w.message}", file=sys.stderr)
        else:
            warnings.showwarning(w.message, w.category, w.filename, w.lineno)
    return written


def _new(args: argparse.Namespace, stage: Stage) -> list[Path]:
    from .design.pipeline import write_starter

    return [write_starter(args.path, overwrite=args.force)]


def _check(args: argparse.Namespace, stage: Stage) -> int:
    from .design.pipeline import check_design

    if args.overlay and Path(args.overlay).suffix.lower() not in (".png", ".svg"):
        raise ValueError(f"{args.overlay}: the overlay must be a .png or .svg file")
    report = check_design(args.design, overrides=_overrides(args.set), progress=stage)
    print(report.table())
    if args.overlay:
        suffix = Path(args.overlay).suffix.lower()
        (report.write_png if suffix == ".png" else report.write_svg)(args.overlay)
    return 1 if (args.strict and not report.ok) else 0


_COMMANDS.update({"build": _build, "new": _new, "check": _check})


def _error(message: str) -> int:
    for line in str(message).splitlines() or [""]:  # a design file may have several issues
        print(f"{PROG}: error: {line}", file=sys.stderr)
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
        Exit status: 0 on success, 2 on bad arguments or input (message on stderr), 1 from
        ``check --strict`` when the design breaks a fabrication limit.
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
    if isinstance(written, int):  # commands that print their own report return a status
        return written
    for path in written:
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
