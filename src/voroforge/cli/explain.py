"""``voroforge explain``: animations that show how an algorithm works."""

from __future__ import annotations

import argparse
from pathlib import Path

from .outputs import OneOutput
from .progress import Stage

__all__ = ["EXPLAIN_EPILOG", "add_parser", "run_explain"]

EXPLAIN_EPILOG = """\
examples:
  voroforge explain fortune points.csv -o sweep.gif
  voroforge explain fortune points.csv -o sweep.gif --frames 120 --size 720

The GIF shows the sweep line (red) moving down, the beach line (blue arcs: the lower
envelope of the parabolas of the swept sites), pending circle events (violet circles and
their event points), edges still growing at the breakpoints (orange) and finished Voronoi
edges (black). The last frame is the finished diagram. Meant for tens to a few hundred
points (at most 2000).
"""


def add_parser(commands, formatter_class) -> argparse.ArgumentParser:
    """Add ``explain fortune`` to ``commands`` (see :mod:`voroforge.cli`).

    Returns
    -------
    argparse.ArgumentParser
        The ``explain`` parser (its ``run`` default is :func:`run_explain`).
    """
    p = commands.add_parser(
        "explain",
        help="animations that show how an algorithm works (GIF)",
        description="Animations for people learning the algorithms.",
        epilog=EXPLAIN_EPILOG,
        formatter_class=formatter_class,
    )
    which = p.add_subparsers(dest="algorithm", metavar="ALGORITHM", required=True)
    f = which.add_parser(
        "fortune",
        help="Fortune's sweep line, frame by frame",
        description="Animate Fortune's sweep over POINTS as a GIF.",
        epilog=EXPLAIN_EPILOG,
        formatter_class=formatter_class,
    )
    f.add_argument(
        "points",
        metavar="POINTS",
        help="point file: .csv/.txt (x,y columns, header optional), .npy or .geojson/.json",
    )
    f.add_argument(
        "-o", "--output", metavar="OUT", action=OneOutput, required=True, help="output .gif file"
    )
    f.add_argument("--frames", type=int, default=60, help="number of frames (default 60)")
    f.add_argument(
        "--size", type=int, default=480, help="pixels along the longer side (default 480)"
    )
    f.add_argument("--duration", type=int, default=80, help="milliseconds per frame (default 80)")
    p.set_defaults(run=run_explain)
    return p


def run_explain(args: argparse.Namespace, stage: Stage | None = None) -> list[Path]:
    """Run ``voroforge explain fortune`` from parsed arguments; returns the written paths."""
    from ..explain.fortune import trace
    from ..explain.render import write_gif
    from ..io.readers import read_points

    stage = stage or (lambda name: None)
    out = Path(args.output)
    if out.suffix.lower() != ".gif":
        raise ValueError(f"{out}: explain writes an animated .gif file")
    if args.duration <= 0:
        raise ValueError(
            f"--duration must be a positive number of milliseconds; got {args.duration}"
        )
    stage("reading")
    pts = read_points(args.points)
    stage(f"tracing Fortune's sweep over {len(pts)} sites")
    tr = trace(pts)
    stage(f"drawing {args.frames} frames to {out}")
    return [write_gif(tr, out, frames=args.frames, size=args.size, duration_ms=args.duration)]
