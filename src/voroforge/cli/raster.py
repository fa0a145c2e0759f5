"""``voroforge raster``: nearest-site labels or distances at every pixel, as PNG or .npy."""

from __future__ import annotations

import argparse
from pathlib import Path

from .progress import Stage

__all__ = ["FIELDS", "add_parser", "parse_bounds", "parse_size", "run_raster"]

#: The drawable fields (:data:`voroforge.io.raster_png.FIELDS`, repeated here so that
#: ``--help`` does not import numpy; a test keeps the two equal).
FIELDS = ("labels", "distance", "f2", "edge")

RASTER_EPILOG = """\
examples:
  voroforge raster points.csv -o cells.png --size 2048x2048
  voroforge raster points.npy -o cells.png --size 1920x1080 --method jfa
  voroforge raster points.csv -o cells.png -o labels.npy --size 512
  voroforge raster points.csv -o noise.png --field edge --bounds 0,0,1,1
  voroforge raster points.csv -o f1.png --field distance --metric manhattan --bounds=-1,-1,1,1

--size is WIDTHxHEIGHT (one number for a square). --field labels colours each cell so
that touching cells differ; distance (F1), f2 and edge (F2 - F1, "cellular noise") are
greyscale, black at 0 and white at the largest value. A .npy output holds the field's
raw values: (height, width) int32 site indices for labels, float64 distances otherwise.
A bounding box with a negative first number needs the '=' form shown last.
"""


def parse_size(text: str) -> tuple[int, int]:
    """``"WIDTHxHEIGHT"`` (or a single number for a square) -> ``(h, w)``.

    Parameters
    ----------
    text : str
        The ``--size`` argument.

    Returns
    -------
    (int, int)
        Rows and columns of the image.

    Raises
    ------
    ValueError
        Not two positive integers.
    """
    parts = text.lower().replace("*", "x").split("x")
    try:
        vals = [int(v) for v in parts]
    except ValueError:
        raise ValueError(
            f"--size must look like 2048x1024 (width x height); got {text!r}"
        ) from None
    if len(vals) == 1:
        vals = vals * 2
    if len(vals) != 2 or min(vals) <= 0:
        raise ValueError(f"--size must be two positive ints WIDTHxHEIGHT; got {text!r}")
    return vals[1], vals[0]


def parse_bounds(text: str | None) -> tuple[float, float, float, float] | None:
    """``"xmin,ymin,xmax,ymax"`` -> tuple, or None.

    Parameters
    ----------
    text : str or None
        The ``--bounds`` argument.

    Returns
    -------
    tuple of 4 floats, or None when ``text`` is None

    Raises
    ------
    ValueError
        Not four numbers.
    """
    if text is None:
        return None
    try:
        vals = tuple(float(v) for v in text.split(","))
    except ValueError:
        raise ValueError(f"--bounds must be xmin,ymin,xmax,ymax numbers; got {text!r}") from None
    if len(vals) != 4:
        raise ValueError(f"--bounds needs 4 numbers xmin,ymin,xmax,ymax; got {text!r}")
    return vals


def add_parser(commands, formatter_class) -> argparse.ArgumentParser:
    """Add ``raster`` to ``commands`` (see :mod:`voroforge.cli`).

    Returns
    -------
    argparse.ArgumentParser
        The subcommand's parser (its ``run`` default is :func:`run_raster`).
    """
    p = commands.add_parser(
        "raster",
        help="Voronoi diagram of a point file as an image (labels or distance fields)",
        description="Nearest-site labels or distances at every pixel of POINTS' diagram, "
        "written as a PNG image or a .npy array.",
        epilog=RASTER_EPILOG,
        formatter_class=formatter_class,
    )
    p.add_argument(
        "points",
        metavar="POINTS",
        help="point file: .csv/.txt (x,y columns, header optional), .npy or .geojson/.json",
    )
    p.add_argument(
        "-o",
        "--output",
        metavar="OUT",
        action="append",
        required=True,
        help="output file: .png (image) or .npy (raw field); repeatable",
    )
    p.add_argument(
        "--size", default="1024x1024", help="image size WIDTHxHEIGHT in pixels (default 1024x1024)"
    )
    p.add_argument(
        "--method",
        default="exact",
        choices=("exact", "jfa"),
        help="exact nearest site (default) or Jump Flooding (euclidean only)",
    )
    p.add_argument(
        "--metric",
        default="euclidean",
        choices=("euclidean", "manhattan", "chebyshev"),
        help="distance (default euclidean; others need --method exact)",
    )
    p.add_argument(
        "--bounds",
        metavar="xmin,ymin,xmax,ymax",
        help="area covered by the image (default: the points' box padded 10%%)",
    )
    p.add_argument("--field", default="labels", choices=FIELDS, help="what to draw")
    p.add_argument(
        "--seed", type=int, default=None, help="colour seed for --field labels (default 0)"
    )
    p.set_defaults(run=run_raster)
    return p


def _any_png(outputs) -> bool:
    outputs = outputs if isinstance(outputs, list) else [outputs]
    return any(str(o).lower().endswith(".png") for o in outputs)


def run_raster(args: argparse.Namespace, stage: Stage | None = None) -> list[Path]:
    """Run ``voroforge raster`` from parsed arguments; returns the written paths.

    ``args`` needs ``points, output (list), size, method, bounds, field`` (and optionally
    ``metric``, ``seed``), see :func:`add_parser`. ``stage(name)`` is called with progress
    messages when given.
    """
    from ..engine.raster import check_raster_size, rasterize
    from ..io.raster_png import RASTER_SUFFIXES, write_raster
    from ..io.readers import read_points
    from .outputs import check_outputs, unused_option

    stage = stage or (lambda name: None)
    seed = getattr(args, "seed", None)
    if seed is not None and (args.field != "labels" or not _any_png(args.output)):
        unused_option(f"--seed {seed}", "--field labels in .png outputs")
    outputs = [Path(o) for o in (args.output if isinstance(args.output, list) else [args.output])]
    for out in outputs:
        if out.suffix.lower() not in RASTER_SUFFIXES:
            raise ValueError(f"{out}: raster output must be a .png or .npy file")
    shape = parse_size(str(args.size))
    f2 = args.field in ("f2", "edge")

    def check_size(sites: int) -> None:  # computing, then drawing the field (.npy: less)
        try:
            metric = getattr(args, "metric", "euclidean")
            check_raster_size(shape, f2=f2, field=args.field, sites=sites, metric=metric)
        except ValueError as exc:
            raise ValueError(f"--size {args.size}: {exc}") from None

    check_size(0)  # before any work
    check_outputs(outputs, inputs=[args.points])
    bounds = parse_bounds(args.bounds)
    stage("reading")
    pts = read_points(args.points)
    check_size(len(pts))
    stage(f"rasterising {len(pts)} sites at {shape[1]}x{shape[0]} ({args.method})")
    result = rasterize(
        pts,
        shape,
        bounds,
        method=args.method,
        metric=getattr(args, "metric", "euclidean"),
        f2=f2,
    )
    written = []
    for out in outputs:
        stage(f"writing {out}")
        written.append(write_raster(result, out, field=args.field, seed=seed or 0))
    return written
