"""Weighted Voronoi stippling (Secord 2002): dots whose density follows an image's darkness.

:func:`stipple` places ``n`` dots by sampling the image's darkness (``1 - grey``), then runs
density-weighted Lloyd relaxation (:func:`voroforge.lloyd` with the image as an exact raster
density), so each dot sits at the centroid of its Voronoi cell under the darkness: dark areas
get many small, evenly spaced cells, light areas few. :func:`stipple_svg` writes the dots as
small circles in pen-up order (nearest neighbour + 2-opt, :mod:`voroforge.io.plotter`), ready
for a plotter. :func:`demo_image` draws a test image (a lit sphere on a gradient) so no
image file is needed.

Examples
--------
>>> pts = stipple(demo_image(48), 200, iterations=2)
>>> pts.shape
(200, 2)
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..config import STIPPLE_MAX_PAGE, STIPPLE_MAX_POINTS, STIPPLE_MAX_WORK

__all__ = ["demo_image", "grey_image", "image_seeds", "stipple", "stipple_svg"]


def demo_image(size: int = 256) -> np.ndarray:
    """A greyscale test image: a sphere lit from the top left, its shadow, a soft gradient.

    Parameters
    ----------
    size : int
        Width and height in pixels (>= 8).

    Returns
    -------
    (size, size) float64
        Grey levels in [0, 1] (1 white), row 0 at the top.
    """
    n = int(size)
    if n < 8:
        raise ValueError(f"size must be at least 8; got {size!r}")
    y, x = (np.mgrid[0:n, 0:n] + 0.5) / n
    grey = 0.92 - 0.25 * y  # background: lighter at the top
    sx, sy = x - 0.72, (y - 0.80) * 3.0  # shadow on the floor, an ellipse
    grey = np.where(sx**2 + sy**2 < 0.09, grey - 0.35 * (1 - (sx**2 + sy**2) / 0.09), grey)
    dx, dy = x - 0.48, y - 0.45
    r2 = (dx**2 + dy**2) / 0.33**2
    inside = r2 < 1.0
    nz = np.sqrt(np.clip(1.0 - r2, 0.0, 1.0))
    light = np.array([-0.5, -0.6, 0.62])
    light /= np.linalg.norm(light)
    lam = (dx / 0.33) * light[0] + (dy / 0.33) * light[1] + nz * light[2]
    sphere = 0.08 + 0.9 * np.clip(lam, 0.0, 1.0) ** 1.4
    grey = np.where(inside, sphere, grey)
    return np.clip(grey, 0.0, 1.0)


#: Pillow's single-channel modes deeper than 8 bits (16-bit PNG/TIFF open as "I" or "I;16",
#: float TIFF as "F"): converting them to "L" clipped every value above 255 to white
_DEEP_MODES = ("I", "I;16", "I;16B", "I;16L", "I;16N", "F")


def _deep_grey(arr: np.ndarray, mode: str, path: Path) -> np.ndarray:
    """Grey values in [0, 1] of a 16-bit, 32-bit integer or float image (1 white)."""
    if not np.isfinite(arr).all():
        raise ValueError(f"{path}: the image has NaN or infinite pixels")
    lo, hi = float(arr.min()), float(arr.max())
    if mode == "F":
        if lo < 0 or hi > 1:
            raise ValueError(
                f"{path}: a float image's grey values must lie in [0, 1]; got [{lo:g}, {hi:g}]"
            )
        return arr
    if lo < 0 or hi > 65535:
        raise ValueError(
            f"{path}: integer grey values past 16 bits ([{lo:g}, {hi:g}]); save it as an 8- or "
            "16-bit image"
        )
    return arr / 65535.0


def grey_image(source) -> np.ndarray:
    """A greyscale image in [0, 1] (1 white), row 0 at the top, from a file or an array.

    Parameters
    ----------
    source : str, Path or (h, w) array_like
        An image file pillow reads (PNG, JPEG, ...; colour is converted to luminance, alpha
        over white; 16-bit grey is read at 16 bits, a float image must hold [0, 1]), or grey
        values in [0, 1].

    Returns
    -------
    (h, w) float64
    """
    if isinstance(source, str | Path):
        from PIL import Image, UnidentifiedImageError

        from ..io.readers.files import open_image

        path = Path(source)
        if not path.is_file():
            raise ValueError(f"{path}: no such image file")
        try:
            with open_image(path) as im:
                if im.mode in _DEEP_MODES:  # one channel past 8 bits: read at its own depth
                    return _deep_grey(np.asarray(im, dtype=np.float64), im.mode, path)
                im = im.convert("RGBA")
                white = Image.new("RGBA", im.size, (255, 255, 255, 255))
                arr = np.asarray(Image.alpha_composite(white, im).convert("L"), dtype=np.float64)
        except UnidentifiedImageError:
            raise ValueError(f"{path}: not an image pillow can read") from None
        return arr / 255.0
    arr = np.array(source, dtype=np.float64)
    if arr.ndim != 2 or arr.size == 0:
        raise ValueError(
            f"the image must be a 2-D array of grey values, at least 1 x 1; got shape {arr.shape}"
        )
    if not np.isfinite(arr).all() or arr.min() < 0 or arr.max() > 1:
        raise ValueError("grey values must be finite and in [0, 1]")
    return arr


def stipple(
    image,
    n: int,
    *,
    width: float = 200.0,
    iterations: int = 30,
    gamma: float = 1.0,
    seed: int = 0,
    progress=None,
) -> np.ndarray:
    """Dots for weighted Voronoi stippling of an image.

    Parameters
    ----------
    image : str, Path or (h, w) array_like
        See :func:`grey_image`.
    n : int
        Number of dots (>= 1).
    width : float
        Width of the drawing in output units; the height follows the image's aspect ratio.
    iterations : int
        Density-weighted Lloyd steps (0: the random start only).
    gamma : float
        The density is ``(1 - grey) ** gamma``: above 1 lightens the midtones.
    seed : int
        Seed of the starting sample.
    progress : callable, optional
        Called with a short text before each stage.

    Returns
    -------
    (n, 2) float64
        Dot centres, y up, in ``[0, width] x [0, height]``.

    Raises
    ------
    ValueError
        For an empty (all white) image or bad options.
    """
    import voroforge as vf

    grey = grey_image(image)
    n = int(n)
    if n < 1:
        raise ValueError(f"need at least 1 point; got {n}")
    if not (math.isfinite(width) and width > 0 and math.isfinite(gamma) and gamma > 0):
        raise ValueError("width and gamma must be positive")
    if int(iterations) < 0:
        raise ValueError(f"iterations must be >= 0; got {iterations!r}")
    if n > STIPPLE_MAX_POINTS:
        raise ValueError(f"at most {STIPPLE_MAX_POINTS:,} points; got {n:,}")
    if n * max(int(iterations), 1) > STIPPLE_MAX_WORK:
        raise ValueError(
            f"{n:,} points x {int(iterations):,} iterations is too much work: at most "
            f"{STIPPLE_MAX_WORK:,} dot-steps (a few minutes); use fewer of either"
        )
    density = (1.0 - grey) ** float(gamma)
    total = density.sum()
    if not total > 0:
        raise ValueError("the image is white everywhere: nothing to stipple")
    h, w = density.shape
    k = float(width) / w
    box = (0.0, 0.0, w * k, h * k)
    if not math.isfinite(h * k):
        raise ValueError(
            f"width {width!r} is too large: the drawing's height ({h} / {w} of it) is past "
            "the largest float"
        )
    stage = progress or (lambda text: None)
    stage(f"sampling {n} dots")
    rng = np.random.default_rng(seed)
    pick = rng.choice(h * w, size=n, p=(density / total).ravel())
    col, row = pick % w, pick // w
    pts = np.column_stack(((col + rng.random(n)) * k, (h - row - rng.random(n)) * k))
    if int(iterations) == 0:
        return pts
    stage(f"relaxing {n} dots ({iterations} weighted Lloyd steps)")
    return vf.lloyd(pts, box, iterations=int(iterations), density=(density, box)).points


def stipple_svg(points, path, *, width: float, height: float, dot: float = 0.4, units="mm"):
    """Write dots as small circles in pen-up order (for a plotter); returns the path.

    Parameters
    ----------
    points : (n, 2) array_like
        Dot centres (y up).
    path : str or Path
        The SVG file.
    width, height : float
        Page size in ``units``.
    dot : float
        Dot radius (> 0).
    units : {"mm", "cm", "in", "px"}
        Page units.
    """
    import shapely

    from ..io.plotter import order_paths
    from ..io.svg import write_layers

    if not (math.isfinite(dot) and dot > 0):
        raise ValueError(
            f"dot must be a positive radius; got {dot!r} (a radius of 0 draws nothing)"
        )
    if not all(0 < v <= STIPPLE_MAX_PAGE for v in (width, height)):
        raise ValueError(
            f"width and height must be positive, at most {STIPPLE_MAX_PAGE:g}; "
            f"got {width!r}, {height!r}"
        )
    pts = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    order, _ = order_paths([p[None] for p in pts], start=(0.0, float(height)), reverse=False)
    dots = shapely.MultiPoint(pts[order]) if len(pts) else shapely.MultiPoint()
    return write_layers(
        path,
        {"DOTS": [dots]},
        units=units,
        stroke_width=max(dot * 0.5, 1e-3),
        colours={"DOTS": "#000000"},
        fills={"DOTS": "#000000"},
        bounds=(0.0, 0.0, float(width), float(height)),
        point_radius=dot,
    )


def image_seeds(image, domain, count: int, *, seed: int = 0, gamma: float = 1.0) -> np.ndarray:
    """``count`` seeds inside ``domain`` with a density that follows an image's darkness.

    The image is stretched over the domain's bounding box (row 0 at the top); candidates are
    drawn from the darkness ``(1 - grey) ** gamma`` and those outside the domain rejected,
    until there are ``count``. This is ``seeds.method = "image"`` of a design file.

    Parameters
    ----------
    image : str, Path or (h, w) array_like
        See :func:`grey_image`.
    domain : shapely Polygon or MultiPolygon
        Where the seeds go.
    count : int
        Number of seeds.
    seed : int
        Random seed.
    gamma : float
        Exponent of the darkness.

    Returns
    -------
    (count, 2) float64

    Raises
    ------
    ValueError
        For a white image, or when the dark parts miss the domain.
    """
    import shapely

    grey = grey_image(image)
    density = (1.0 - grey) ** float(gamma)
    total = density.sum()
    if not total > 0:
        raise ValueError("the image is white everywhere: no density to place seeds by")
    h, w = density.shape
    xmin, ymin, xmax, ymax = domain.bounds
    kx, ky = (xmax - xmin) / w, (ymax - ymin) / h
    rng = np.random.default_rng(seed)
    prob = (density / total).ravel()
    from .populate import next_batch

    out = np.zeros((0, 2))
    drawn = 0
    while True:  # until count, or next_batch gives up
        short = int(count) - len(out)
        m = next_batch(max(2 * short, 16), short, drawn, len(out), "the image's darkness")
        drawn += m
        pick = rng.choice(h * w, size=m, p=prob)
        col, row = pick % w, pick // w
        xy = np.column_stack((xmin + (col + rng.random(m)) * kx, ymax - (row + rng.random(m)) * ky))
        out = np.vstack((out, xy[shapely.contains_xy(domain, xy[:, 0], xy[:, 1])]))
        if len(out) >= count:
            return out[: int(count)]
