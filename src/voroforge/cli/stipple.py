"""``voroforge stipple``: weighted Voronoi stippling of an image, as a plotter-ready SVG."""

from __future__ import annotations

import argparse
import math
from pathlib import Path

from .outputs import OneOutput
from .progress import Stage

__all__ = ["add_parser", "run_stipple"]

_EPILOG = """\
Dots follow the image's darkness (Secord 2002: density-weighted Lloyd relaxation from a
random sample), written as small circles in pen-up order. IMAGE is any file pillow reads,
or @sphere for a built-in test image.

examples:
  voroforge stipple @sphere -o sphere.svg --points 4000
  voroforge stipple photo.png -o photo.svg --points 10000 --width 200 --dot 0.35
"""


def add_parser(commands, formatter_class) -> None:
    """Add ``stipple`` to ``commands`` (see :mod:`voroforge.cli`)."""
    sub = commands.add_parser(
        "stipple",
        help="weighted Voronoi stippling of an image (plotter-ready SVG of dots)",
        description="Stipple IMAGE: dots whose density follows its darkness.",
        epilog=_EPILOG,
        formatter_class=formatter_class,
    )
    sub.add_argument("image", metavar="IMAGE", help="image file (PNG, JPEG, ...) or @sphere")
    sub.add_argument(
        "-o", "--output", metavar="OUT.svg", action=OneOutput, required=True, help="SVG to write"
    )
    sub.add_argument("--points", type=int, default=4000, help="number of dots (default 4000)")
    sub.add_argument("--iterations", type=int, default=30, help="weighted Lloyd steps (default 30)")
    sub.add_argument("--width", type=float, default=200.0, help="page width in mm (default 200)")
    sub.add_argument("--dot", type=float, default=0.4, help="dot radius in mm (default 0.4)")
    sub.add_argument("--gamma", type=float, default=1.0, help="density = darkness ** gamma")
    sub.add_argument("--seed", type=int, default=0, help="seed of the starting sample")
    sub.set_defaults(run=run_stipple)


def run_stipple(args: argparse.Namespace, stage: Stage) -> list[Path]:
    """Run ``voroforge stipple``; returns the file written."""
    from ..design.stipple import STIPPLE_MAX_PAGE, demo_image, grey_image, stipple, stipple_svg

    if Path(args.output).suffix.lower() != ".svg":
        raise ValueError(f"{args.output}: stipple writes an .svg file")
    if not (math.isfinite(args.dot) and args.dot > 0):
        raise ValueError(f"--dot must be a positive radius in mm; got {args.dot!r}")
    if not (math.isfinite(args.width) and args.width > 0):
        raise ValueError(f"--width must be a positive page width in mm; got {args.width!r}")
    if args.image.startswith("@"):
        if args.image != "@sphere":
            raise ValueError(f"{args.image}: the built-in image is @sphere")
        grey = demo_image(256)
    else:
        grey = grey_image(args.image)
    h, w = grey.shape
    if max(args.width, args.width * (h / w)) > STIPPLE_MAX_PAGE:
        raise ValueError(
            f"--width {args.width!r} is too large: the {w} x {h} image's page sides must be "
            f"at most {STIPPLE_MAX_PAGE:g} mm"
        )
    pts = stipple(
        grey,
        args.points,
        width=args.width,
        iterations=args.iterations,
        gamma=args.gamma,
        seed=args.seed,
        progress=stage,
    )
    height = args.width * h / w
    stage(f"writing {args.output}")
    return [stipple_svg(pts, args.output, width=args.width, height=height, dot=args.dot)]
