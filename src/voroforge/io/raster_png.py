"""PNG images of raster Voronoi results (pillow), and the ``voroforge raster`` command."""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

FIELDS = ("labels", "f1", "f2", "edge")


def palette(n: int, *, seed: int = 0) -> np.ndarray:
    """Deterministic pleasant colours, one per site.

    Parameters
    ----------
    n : int
        Number of colours.
    seed : int
        Seed of the random hues; the same seed always gives the same colours.

    Returns
    -------
    (n, 3) uint8
        RGB colours (random hue, moderate saturation, high value). Colour ``i`` depends
        only on ``i`` and ``seed``, not on ``n``.
    """
    u = np.random.default_rng(seed).random((n, 3))  # row i is the same for every n
    hue = u[:, 0]
    sat = 0.35 + 0.35 * u[:, 1]
    val = 0.75 + 0.25 * u[:, 2]
    # HSV -> RGB, vectorised.
    k = (np.array([5.0, 3.0, 1.0])[None, :] + hue[:, None] * 6.0) % 6.0
    ramp = np.clip(np.minimum(k, 4.0 - k), 0.0, 1.0)
    rgb = val[:, None] * (1.0 - sat[:, None] * ramp)
    return np.round(rgb * 255.0).astype(np.uint8)


def colorize(result, *, field: str = "labels", seed: int = 0) -> np.ndarray:
    """Image array of one field of a raster result.

    Parameters
    ----------
    result : RasterVoronoi
        From :func:`voroforge.rasterize`.
    field : {"labels", "f1", "f2", "edge"}
        ``labels``: one colour per cell. ``f1``/``f2``/``edge``: greyscale, black at 0 and
        white at the field's largest finite value (inf is white).
    seed : int
        Palette seed for ``labels``.

    Returns
    -------
    (h, w, 3) uint8 or (h, w) uint8
        RGB for labels, greyscale for distance fields.

    Raises
    ------
    ValueError
        For an unknown field, or ``f2``/``edge`` on a result computed without ``f2=True``.
    """
    if field not in FIELDS:
        raise ValueError(f"field must be one of {FIELDS}; got {field!r}")
    if field == "labels":
        labels = np.asarray(result.labels)
        n = int(labels.max()) + 1 if labels.size else 0
        return palette(n, seed=seed)[labels]
    if field in ("f2", "edge") and result.f2 is None:
        raise ValueError(f"field {field!r} needs a result computed with rasterize(..., f2=True)")
    values = {"f1": result.distance, "f2": result.f2, "edge": result.edge}[field]
    finite = np.isfinite(values)
    top = float(values[finite].max()) if finite.any() else 0.0
    scaled = np.ones(values.shape) if top <= 0.0 else np.where(finite, values / top, 1.0)
    return np.round(np.clip(scaled, 0.0, 1.0) * 255.0).astype(np.uint8)


def write_raster_png(result, path, *, field: str = "labels", seed: int = 0) -> Path:
    """Write one field of a raster result as a PNG.

    Parameters
    ----------
    result : RasterVoronoi
        From :func:`voroforge.rasterize`; row 0 is the top of the image.
    path : str or os.PathLike
        Output file.
    field : {"labels", "f1", "f2", "edge"}
        What to draw; see :func:`colorize`.
    seed : int
        Palette seed for ``labels``.

    Returns
    -------
    pathlib.Path
        The path written.

    Examples
    --------
    >>> import voroforge as vf, tempfile, os
    >>> from voroforge.io.raster_png import write_raster_png
    >>> r = vf.rasterize([[0, 0], [1, 1]], (8, 8))
    >>> p = write_raster_png(r, os.path.join(tempfile.mkdtemp(), "cells.png"))
    >>> p.suffix
    '.png'
    """
    from PIL import Image

    img = colorize(result, field=field, seed=seed)
    mode = "RGB" if img.ndim == 3 else "L"
    out = Path(path)
    Image.fromarray(np.ascontiguousarray(img), mode=mode).save(out, format="PNG")
    return out


# ---------------------------------------------------------------------------------------
# Command line: parsing helpers only; the CLI module wires them in.
# ---------------------------------------------------------------------------------------


def parse_size(text: str) -> tuple[int, int]:
    """``"WIDTHxHEIGHT"`` (or a single number for a square) -> ``(h, w)``."""
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
    """``"xmin,ymin,xmax,ymax"`` -> tuple, or None."""
    if text is None:
        return None
    try:
        vals = tuple(float(v) for v in text.split(","))
    except ValueError:
        raise ValueError(f"--bounds must be xmin,ymin,xmax,ymax numbers; got {text!r}") from None
    if len(vals) != 4:
        raise ValueError(f"--bounds needs 4 numbers xmin,ymin,xmax,ymax; got {text!r}")
    return vals


RASTER_EPILOG = """\
examples:
  voroforge raster points.csv -o cells.png --size 2048x2048
  voroforge raster points.npy -o cells.png --size 1920x1080 --method jfa
  voroforge raster points.csv -o noise.png --field edge --bounds 0,0,1,1
  voroforge raster points.csv -o f1.png --field f1 --metric manhattan --bounds=-1,-1,1,1

--size is WIDTHxHEIGHT (one number for a square). --field labels colours each cell;
f1, f2 and edge (f2 - f1, "cellular noise") are greyscale distance fields.
A bounding box with a negative first number needs the '=' form shown last.
"""


def add_raster_parser(commands, **kwargs) -> argparse.ArgumentParser:
    """Add the ``raster`` subcommand to argparse ``commands`` (from ``add_subparsers``).

    Extra keyword arguments (e.g. ``formatter_class``) go to ``add_parser``. The command's
    ``func`` default is :func:`raster_command`.
    """
    p = commands.add_parser(
        "raster",
        help="Voronoi diagram of a point file as a PNG image (labels or distance fields)",
        description="Nearest-site labels or distances at every pixel of POINTS' diagram, "
        "written as a PNG.",
        epilog=RASTER_EPILOG,
        **kwargs,
    )
    p.add_argument(
        "points",
        metavar="POINTS",
        help="point file: .csv/.txt (x,y columns, header optional), .npy or .geojson/.json",
    )
    p.add_argument("-o", "--output", metavar="OUT", required=True, help="output PNG file")
    p.add_argument(
        "--size", default="1024x1024", help="image size WIDTHxHEIGHT in pixels (default 1024x1024)"
    )
    p.add_argument(
        "--method",
        default="exact",
        choices=("exact", "jfa"),
        help="exact nearest site (default) or Jump Flooding (euclidean only)",
    )
    p.add_argument("--metric", default="euclidean", choices=("euclidean", "manhattan", "chebyshev"))
    p.add_argument(
        "--bounds",
        metavar="xmin,ymin,xmax,ymax",
        help="area covered by the image (default: the points' box padded 10%%)",
    )
    p.add_argument("--field", default="labels", choices=FIELDS, help="what to draw")
    p.add_argument("--seed", type=int, default=0, help="palette seed for --field labels")
    p.set_defaults(func=raster_command)
    return p


def raster_command(args, stage=None) -> list[Path]:
    """Run ``voroforge raster`` from parsed arguments; returns the written paths.

    ``args`` needs ``points, output, size, method, bounds, field`` (and optionally
    ``metric``, ``seed``), see :func:`add_raster_parser`. ``stage(name)`` is called with
    progress messages when given.
    """
    from ..engine.raster import rasterize
    from .readers import read_points

    stage = stage or (lambda name: None)
    out = Path(args.output)
    if out.suffix.lower() != ".png":
        raise ValueError(f"{out}: raster output must be a .png file")
    shape = parse_size(str(args.size))
    bounds = parse_bounds(args.bounds)
    stage("reading")
    pts = read_points(args.points)
    stage(f"rasterising {len(pts)} sites at {shape[1]}x{shape[0]} ({args.method})")
    result = rasterize(
        pts,
        shape,
        bounds,
        method=args.method,
        metric=getattr(args, "metric", "euclidean"),
        f2=args.field in ("f2", "edge"),
    )
    stage(f"writing {out}")
    return [write_raster_png(result, out, field=args.field, seed=getattr(args, "seed", 0))]
