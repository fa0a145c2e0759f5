"""``voroforge scale``: Voronoi cells of a big point file in tiles on dask.distributed."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from .progress import Stage

__all__ = ["add_parser", "run"]

_EPILOG = """\
POINTS is a .npy array (memory-mapped), or a .csv/.parquet table with x,y columns (other
columns are carried to the output). OUT is a folder: one GeoParquet file per tile, a
_metadata summary and the job manifest; read it with geopandas, GDAL, DuckDB or
voroforge.scale.read. The cells are those of 'voroforge voronoi' on all points at once.

Without --scheduler a LocalCluster of --workers single-threaded processes is started.
Rerunning an interrupted job resumes it (only missing tiles are computed).

examples:
  voroforge scale points.npy -o cells.parquet
  voroforge scale points.parquet -o cells.parquet --workers 2 --tile-size 250000
  voroforge scale points.csv -o cells.parquet --boundary county.geojson --crs EPSG:2056
  voroforge scale points.npy -o cells.parquet --scheduler tcp://10.0.0.5:8786
"""


def add_parser(commands, formatter_class) -> None:
    """Add ``scale`` to ``commands`` (see :mod:`voroforge.cli`)."""
    sub = commands.add_parser(
        "scale",
        help="Voronoi cells of millions of points in tiles on dask.distributed, GeoParquet out",
        description="Compute the Voronoi cells of POINTS in tiles on a dask cluster and write "
        "them as a GeoParquet dataset.",
        epilog=_EPILOG,
        formatter_class=formatter_class,
    )
    sub.add_argument("points", metavar="POINTS", help="point file: .npy, .csv or .parquet")
    sub.add_argument("-o", "--output", required=True, metavar="OUT", help="output folder")
    sub.add_argument(
        "--workers", type=int, metavar="N", help="LocalCluster workers (default: cores)"
    )
    sub.add_argument("--scheduler", metavar="ADDR", help="address of a running dask scheduler")
    sub.add_argument("--tile-size", type=int, metavar="K", help="sites per tile")
    sub.add_argument(
        "--boundary",
        metavar="FILE|xmin,ymin,xmax,ymax",
        help="domain: a GeoJSON, SVG or DXF file, or a box (default: the points' box padded 10%%)",
    )
    sub.add_argument("--crs", help="coordinate reference system of the points, e.g. EPSG:2056")
    sub.add_argument("--overwrite", action="store_true", help="replace an existing OUT")
    sub.set_defaults(run=run)


def _bar(done: int, total: int, width: int = 24) -> str:
    full = width * done // max(total, 1)
    return "[" + "#" * full + "-" * (width - full) + f"] {done}/{total} tiles"


def run(args: argparse.Namespace, stage: Stage) -> list[Path]:
    """Run ``voroforge scale``; returns the output folder."""
    from distributed import Client

    from .. import io, scale
    from ..scale.cluster import check_local_workers, local_cluster
    from ..scale.job import check_counts

    if args.workers is not None and args.workers < 1:
        raise ValueError(f"--workers must be at least 1; got {args.workers}")
    if args.scheduler and args.workers is not None:
        raise ValueError("--workers applies to the LocalCluster; not with --scheduler")
    # every count before the cluster starts (it prints its dashboard and takes seconds)
    check_local_workers(args.workers)
    check_counts(tile_size=args.tile_size)
    boundary = io.read_boundary(args.boundary) if args.boundary else None
    stage("starting the cluster")
    if args.scheduler:
        cluster = None
        client = Client(args.scheduler)
    else:
        cluster = local_cluster(args.workers)
        client = Client(cluster)
    try:
        print(f"dask dashboard: {client.dashboard_link}", file=sys.stderr)
        stage(_bar(0, 1))

        def show(done, total):
            stage(_bar(done, total))
            if not sys.stderr.isatty():
                print(_bar(done, total), file=sys.stderr)

        res = scale.voronoi(
            args.points,
            boundary,
            out=args.output,
            tile_size=args.tile_size,
            client=client,
            crs=args.crs,
            overwrite=args.overwrite,
            progress=show,
        )
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    print(
        f"{res.cells} cells in {res.tiles} tiles on {res.workers} workers, "
        f"{res.uncertified} uncertified ({res.retried} recomputed with a wider halo, "
        f"{res.resumed} tiles resumed), {res.seconds:.1f} s",
        file=sys.stderr,
    )
    return [res.path]
