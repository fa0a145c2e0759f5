"""Raster Voronoi: nearest-site labels and distance fields per pixel (:func:`rasterize`)."""

from __future__ import annotations

import math
import numbers
from functools import cached_property

import numpy as np

from .. import config
from ..config import (
    RASTER_BYTES,
    RASTER_MAX_BYTES,
    RASTER_RESULT_BYTES,
    RASTER_SITE_BYTES,
    RASTER_WRITE_BYTES,
    RASTER_WRITE_SITE_BYTES,
)
from ..kernels.raster import exact_nearest, fix_pixels, jfa_nearest, nearest_tiles, walk_tiles
from .csr import csr_from_pairs
from .delaunay import delaunay
from .domain import padded_bounds
from .inputs import as_points, duplicate_map, unit_exponent

METHODS = ("exact", "jfa")
METRICS = ("euclidean", "manhattan", "chebyshev")

#: Initial tile of the exact method, in site spacings (tuned on uniform sites).
_TILE_SPACINGS = 1.0
#: Tiles of the exact method with more candidate sites than this are split.
_MAX_CANDIDATES = 48
#: Largest initial tile side of the exact method, in pixels.
_MAX_TILE = 64


class RasterVoronoi:
    """Nearest-site labels and distances sampled at pixel centres.

    Pixel ``(row r, column c)`` is sampled at ``x = xmin + (c + 0.5) (xmax - xmin) / w``,
    ``y = ymax - (r + 0.5) (ymax - ymin) / h``: row 0 is at the top, as in an image. The
    sampled points are :attr:`x` and :attr:`y` (see :func:`pixel_centers`), and the labels
    are ``locate``'s answers there.

    Attributes
    ----------
    labels : (h, w) int32
        Input index of the nearest site of each pixel (ties and duplicates: lowest index).
    distance : (h, w) float64
        F1: distance from the pixel centre to that site, in data units.
    f2 : (h, w) float64 or None
        F2: distance to the second nearest distinct site (inf with a single distinct site);
        None unless requested.
    bounds : tuple of 4 float
        ``(xmin, ymin, xmax, ymax)`` of the image.
    shape : tuple of 2 int
        ``(h, w)``.
    method, metric : str
        How the labels were computed and with which distance.
    """

    def __init__(self, labels, distance, f2, bounds, method, metric, centers=None):
        self._centers = centers
        self.labels = labels
        self.distance = distance
        self.f2 = f2
        self.bounds = bounds
        self.shape = labels.shape
        self.method = method
        self.metric = metric
        for arr in (labels, distance, f2):
            if arr is not None:
                arr.setflags(write=False)

    def __repr__(self) -> str:
        h, w = self.shape
        return (
            f"RasterVoronoi(shape=({h}, {w}), bounds={self.bounds}, method={self.method!r}, "
            f"metric={self.metric!r}, f2={self.f2 is not None})"
        )

    @cached_property
    def edge(self) -> np.ndarray:
        """(h, w) float64 ``f2 - f1``: distance-like value that is 0 on cell edges."""
        if self.f2 is None:
            raise ValueError(
                "edge needs the second-nearest distances: call rasterize(..., f2=True)"
            )
        out = self.f2 - self.distance
        out.setflags(write=False)
        return out

    @cached_property
    def x(self) -> np.ndarray:
        """(w,) float64 x of the pixel centres of each column: the points sampled."""
        return (self._centers or pixel_centers(self.bounds, self.shape))[0]

    @cached_property
    def y(self) -> np.ndarray:
        """(h,) float64 y of the pixel centres of each row (decreasing): the points sampled."""
        return (self._centers or pixel_centers(self.bounds, self.shape))[1]


def pixel_centers(bounds, shape) -> tuple[np.ndarray, np.ndarray]:
    """Pixel-centre coordinates of an image over ``bounds``: the points a raster samples.

    Where the bounds are past ``2**±RASTER_FRAME_EXP`` (config) the formulas below are
    evaluated on the bounds scaled by a power of two, where they neither overflow
    (``xmax - xmin`` at bounds of ``±1e308``) nor lose digits to underflow (a subnormal
    pixel size), and scaled back: a centre then rounds only where it is subnormal, and the
    raster samples the rounded point (so its labels are ``locate``'s answers at exactly
    these coordinates).

    Parameters
    ----------
    bounds : tuple of 4 float
        ``(xmin, ymin, xmax, ymax)``.
    shape : tuple of 2 int
        ``(h, w)``.

    Returns
    -------
    x : (w,) float64
        ``xmin + (c + 0.5) * ((xmax - xmin) / w)`` for each column ``c``.
    y : (h,) float64
        ``ymax - (r + 0.5) * ((ymax - ymin) / h)`` for each row ``r`` (row 0 at the top).
    """
    e = unit_exponent(max(abs(float(v)) for v in bounds), config.RASTER_FRAME_EXP)
    if e:
        xs, ys = pixel_centers(tuple(np.ldexp(np.asarray(bounds, np.float64), -e)), shape)
        with np.errstate(under="ignore"):
            x, y = np.ldexp(xs, e), np.ldexp(ys, e)
    else:
        xmin, ymin, xmax, ymax = bounds
        h, w = shape
        x = xmin + (np.arange(w, dtype=np.float64) + 0.5) * ((xmax - xmin) / w)
        y = ymax - (np.arange(h, dtype=np.float64) + 0.5) * ((ymax - ymin) / h)
    for arr in (x, y):
        arr.setflags(write=False)
    return x, y


def raster_bytes(
    shape, *, f2: bool = False, field: str | None = None, sites: int = 0, metric="euclidean"
) -> int:
    """Estimated peak memory of a raster, in bytes: computing it, then drawing one field.

    Parameters
    ----------
    shape : tuple of 2 int
        ``(h, w)``.
    f2 : bool
        Whether the second-nearest distances are computed.
    field : {"labels", "distance", "f2", "edge"} or None
        The field then drawn as a PNG (None: the computation alone).
    sites : int
        Number of sites (0: a lower bound, before they are read).
    metric : str
        The distance (only the Euclidean one may walk the sites' Delaunay graph).

    Returns
    -------
    int
        Bytes: the larger of the computation's peak and the result plus the drawing's, from
        the measured :data:`config.RASTER_BYTES`, :data:`RASTER_SITE_BYTES`,
        :data:`RASTER_RESULT_BYTES`, :data:`RASTER_WRITE_BYTES` and
        :data:`RASTER_WRITE_SITE_BYTES`.
    """
    h, w = shape
    px, n, f2 = int(h) * int(w), int(sites), bool(f2)
    # the walk needs at most a site a pixel: up to px sites at its cost (monotone in px)
    walked = min(n, px) if metric == "euclidean" and not f2 else 0
    sites_bytes = walked * RASTER_SITE_BYTES[0] + (n - walked) * RASTER_SITE_BYTES[1]
    compute = px * RASTER_BYTES[f2] + sites_bytes
    if field is None:
        return compute
    draw = px * (RASTER_RESULT_BYTES[f2] + RASTER_WRITE_BYTES[field])
    if field == "labels":
        draw += min(n, px) * RASTER_WRITE_SITE_BYTES
    return max(compute, draw)


def check_raster_size(
    shape, *, f2: bool = False, field: str | None = None, sites: int = 0, metric="euclidean"
) -> None:
    """``ValueError`` when a raster would need more than :data:`RASTER_MAX_BYTES`.

    Parameters
    ----------
    shape : tuple of 2 int
        ``(h, w)``, positive.
    f2, field, sites, metric
        As for :func:`raster_bytes`.

    Raises
    ------
    ValueError
        Naming the size, the memory it needs, and the most pixels allowed.
    """
    h, w = shape
    kw = {"f2": f2, "field": field, "sites": sites, "metric": metric}
    need = raster_bytes((h, w), **kw)
    if need <= RASTER_MAX_BYTES:
        return
    # the most pixels that fit with these sites (the estimate grows with the pixels)
    lo, hi = 0, h * w
    while lo < hi:
        mid = (lo + hi + 1) // 2
        if raster_bytes((1, mid), **kw) <= RASTER_MAX_BYTES:
            lo = mid
        else:
            hi = mid - 1
    what = "to compute" + (" with f2" if f2 else "") + (f" and draw {field}" if field else "")
    who = f" for {sites:,} sites" if sites else ""
    most = (
        f"at most {lo:,} pixels (e.g. {math.isqrt(lo)} x {math.isqrt(lo)})"
        if lo
        else "no image fits: use fewer sites"
    )
    raise ValueError(
        f"shape {h} x {w} is too large: {h * w:,} pixels need about {need / 2**30:.1f} GiB "
        f"{what}{who}; the limit is {RASTER_MAX_BYTES / 2**30:g} GiB, that is {most}"
    )


def _check_shape(shape) -> tuple[int, int]:
    try:
        items = tuple(shape)
    except TypeError:
        raise ValueError(f"shape must be a pair (h, w) of positive ints; got {shape!r}") from None
    ok = len(items) == 2 and all(
        isinstance(v, numbers.Integral) and not isinstance(v, bool) and v > 0 for v in items
    )
    if not ok:
        raise ValueError(f"shape must be a pair (h, w) of positive ints; got {shape!r}")
    return int(items[0]), int(items[1])


def _check_bounds(bounds, pts: np.ndarray) -> tuple[float, float, float, float]:
    if bounds is None:
        return tuple(float(v) for v in padded_bounds(pts))
    if isinstance(bounds, (str, bytes)):
        raise ValueError(f"bounds must be (xmin, ymin, xmax, ymax) numbers or None; got {bounds!r}")
    try:
        vals = tuple(float(v) for v in bounds)
    except (TypeError, ValueError):
        raise ValueError(
            f"bounds must be (xmin, ymin, xmax, ymax) numbers or None; got {bounds!r}"
        ) from None
    if len(vals) != 4:
        raise ValueError(f"bounds must have 4 numbers (xmin, ymin, xmax, ymax); got {len(vals)}")
    if not all(math.isfinite(v) for v in vals):
        raise ValueError(f"bounds must be finite; got {vals}")
    xmin, ymin, xmax, ymax = vals
    if not (xmin < xmax and ymin < ymax):
        raise ValueError(f"bounds must satisfy xmin < xmax and ymin < ymax; got {vals}")
    return vals


def _frame(pts: np.ndarray, box) -> int:
    """0, or ``e`` bringing the sites and the box near unit size, past ``2**±RASTER_FRAME_EXP``."""
    big = max(float(np.abs(pts).max(initial=0.0)), *(abs(v) for v in box))
    return unit_exponent(big, config.RASTER_FRAME_EXP)


def _jfa_steps(h: int, w: int, reach: int | None = None) -> np.ndarray:
    """JFA steps: K, K/2, ..., 2, 1.

    ``K`` is N/2 with N the power of two >= max(h, w) (standard JFA), or, when ``reach`` is
    given, the smallest power of two with ``2 K - 1 >= reach`` if that is smaller: the steps
    K, ..., 1 can carry a seed ``2 K - 1`` pixels along each axis, so every pixel still
    hears of its nearest site when all nearest sites lie within ``reach`` pixels. No
    refinement passes (JFA+1, JFA+2) follow: the exact check after the flood corrects every
    pixel, and the flood only has to give it tight bounds (2048^2, 10k uniform sites: the
    passes "2, 1" cost 20% of the flood and left the check's time unchanged).
    """
    n = 1
    while n < max(h, w):
        n *= 2
    k = max(n // 2, 1)
    if reach is not None:
        small = 1
        while 2 * small - 1 < reach:
            small *= 2
        k = min(k, small)
    steps = []
    while k >= 1:
        steps.append(k)
        k //= 2
    return np.array(steps, dtype=np.int64)


def _jfa_reach(xs: np.ndarray, ys: np.ndarray, geom: np.ndarray, shape) -> int:
    """Upper bound, in pixels along an axis, on the offset from any pixel to its nearest seed.

    Seeds of the sites inside the image are bucketed in a grid of ``b x b`` pixel buckets;
    ``d`` dilations (Chebyshev) cover the grid from the occupied buckets. A pixel is then
    within ``D = (d + 1) b`` pixels per axis of some site, so its nearest site is within the
    distance ``E = D hypot(pw, ph)`` (pixel sizes ``pw, ph``), that is within
    ``E / min(pw, ph)`` pixels per axis; 2 more absorb the rounding of seeds to pixels.
    """
    h, w = shape
    b = max(1, -(-max(h, w) // 128))
    gh, gw = -(-h // b), -(-w // b)
    # Only sites inside the image count: a site outside is seeded on the border, possibly
    # far from where it is. (The nearest site of a pixel may still be outside; its border
    # seed is then no farther, per axis, than the site itself.)
    fc = (xs - geom[0]) / geom[2]
    fr = (geom[1] - ys) / geom[3]
    inside = (fc >= 0) & (fc < w) & (fr >= 0) & (fr < h)
    if not inside.any():
        return max(h, w)
    c = np.minimum(fc[inside].astype(np.int64), w - 1)
    r = np.minimum(fr[inside].astype(np.int64), h - 1)
    covered = np.zeros((gh, gw), dtype=bool)
    covered[r // b, c // b] = True
    d = 0
    while not covered.all():
        grown = np.pad(covered, 1)
        covered = np.zeros_like(covered)
        for dr in range(3):
            for dc in range(3):
                covered |= grown[dr : dr + gh, dc : dc + gw]
        d += 1
    pw, ph = geom[2], geom[3]
    return math.ceil((d + 1) * b * math.hypot(pw, ph) / min(pw, ph)) + 2


def _exact_tile(sites: np.ndarray, bounds, shape) -> np.ndarray:
    """Initial tile (rows, cols): about one site spacing of the sites inside the image."""
    xmin, ymin, xmax, ymax = bounds
    h, w = shape
    inside = (
        (sites[:, 0] >= xmin)
        & (sites[:, 0] <= xmax)
        & (sites[:, 1] >= ymin)
        & (sites[:, 1] <= ymax)
    )
    n_in = max(int(inside.sum()), 1)
    spacing = _TILE_SPACINGS * math.sqrt((xmax - xmin) * (ymax - ymin) / n_in)
    th = int(min(max(spacing / ((ymax - ymin) / h), 1), _MAX_TILE))
    tw = int(min(max(spacing / ((xmax - xmin) / w), 1), _MAX_TILE))
    return np.array([th, tw], dtype=np.int64)


#: Largest coordinate magnitude the Delaunay walk is used at: its squared distances must
#: not overflow (past it, the tile search decides every pixel).
_WALK_MAX_SCALE = 1e150


def _walks(sites: np.ndarray, bounds, shape, metric: str, want_f2: bool) -> bool:
    """Whether the Delaunay walk decides the labels instead of the tile search.

    Euclidean F1 only, at least a pixel a site, and only where the sites crowd (most
    buckets of a uniform grid over the image and the sites empty: along a curve or a line,
    in clusters, or in a small part of the image). There the tile
    search scans every empty bucket within the nearest distance for each small tile (inside
    a circle of sites, the whole grid: 10,000 sites at 1024^2 took 9.7 s against 0.17 s);
    on uniform sites it is about 1.2x faster than the walk plus its triangulation.
    """
    h, w = shape
    scale = max(float(np.abs(sites).max()), *(abs(v) for v in bounds))
    if metric != "euclidean" or want_f2 or h * w < len(sites) or scale >= _WALK_MAX_SCALE:
        return False
    # buckets of about two sites each over the image and the sites together
    lo = np.minimum(sites.min(axis=0), (bounds[0], bounds[1]))
    hi = np.maximum(sites.max(axis=0), (bounds[2], bounds[3]))
    size = hi - lo
    nb = max(len(sites) / 2.0, 1.0)
    with np.errstate(over="ignore"):  # (a strip 1e308 long: the ratio is inf, nx is nb)
        nx = int(min(max(math.sqrt(nb * size[0] / size[1]), 1.0), nb))
    ny = int(min(max(nb / nx, 1.0), nb))
    ix = np.minimum(((sites[:, 0] - lo[0]) / size[0] * nx).astype(np.int64), nx - 1)
    iy = np.minimum(((sites[:, 1] - lo[1]) / size[1] * ny).astype(np.int64), ny - 1)
    filled = len(np.unique(iy * nx + ix))
    return filled < (1.0 - config.RASTER_CROWDED_EMPTY) * nx * ny


def _delaunay_neighbors(sites: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """CSR Delaunay neighbours of distinct sites (collinear: the previous and next on the line)."""
    tri = delaunay(sites)
    if len(tri.triangles):
        t = tri.triangles.astype(np.int64)
        a = np.concatenate((t[:, 0], t[:, 1], t[:, 2]))
        b = np.concatenate((t[:, 1], t[:, 2], t[:, 0]))
    else:
        a = tri.hull[:-1].astype(np.int64)
        b = tri.hull[1:].astype(np.int64)
    return csr_from_pairs(len(sites), a, b)


def _walk_nearest(xs, ys, pxs, pys, tile, hint):
    """Labels and distances by the Delaunay walk; pixels within rounding of a tie brute-forced."""
    nptr, nidx = _delaunay_neighbors(np.column_stack((xs, ys)))
    lab, d1, hard = walk_tiles(xs, ys, pxs, pys, nptr, nidx, tile, hint)
    rows, cols = np.nonzero(hard)
    if len(rows):
        fix_pixels(xs, ys, pxs, pys, rows.astype(np.int64), cols.astype(np.int64), lab, d1)
    return lab, d1, np.zeros((0, 0))


def rasterize(
    points,
    shape,
    bounds=None,
    *,
    method: str = "exact",
    metric: str = "euclidean",
    f2: bool = False,
) -> RasterVoronoi:
    """Voronoi diagram as an image: nearest site and distance at each pixel centre.

    Parameters
    ----------
    points : (n, 2) array_like
        Sites (n >= 1, finite). Duplicates are allowed: the lowest index owns the cell.
        Sites outside ``bounds`` still own the pixels nearest to them.
    shape : tuple of 2 int
        ``(h, w)`` of the image, positive.
    bounds : tuple of 4 float, optional
        ``(xmin, ymin, xmax, ymax)`` covered by the image. Default: the sites' bounding box
        padded by 10% on each side, exactly as :func:`voroforge.voronoi` pads its default
        domain (so the image and the diagram cover the same area).
    method : {"exact", "jfa"}
        ``"exact"``: the exactly nearest site of every pixel centre (ties to the lowest
        index), any metric: a brute-force argmin's answer wherever its float distances
        differ by more than their rounding, and decided in exact arithmetic where they do
        not, so the labels agree with :meth:`Diagram.locate` at the pixel centres.
        ``"jfa"``: Jump Flooding (Euclidean only; the first step cut to what the sites'
        spacing needs, sites outside ``bounds`` seeded on the border pixel), then an exact
        check: each pixel is compared with every site within the distance the flood found
        for it, so the labels and distances equal the exact method's on every arrangement.
        (The flood alone misses sites where they crowd: several per pixel, or cells thinner
        than a pixel, e.g. many sites along a circle or a slanted line.) On a CPU
        ``"exact"`` is faster; ``"jfa"`` is the method GPU pipelines use, kept for
        comparison. Where the sites crowd (most of a uniform bucket grid empty: sites along
        curves or lines, in clusters) both decide the Euclidean nearest site by walking the
        sites' Delaunay graph from pixel to pixel, which costs about the same per pixel on
        any arrangement.
    metric : {"euclidean", "manhattan", "chebyshev"}
        Distance used for the labels and distances.
    f2 : bool
        Also compute distances to the second-nearest distinct site (``r.f2``, ``r.edge``).

    Returns
    -------
    RasterVoronoi
        ``labels``, ``distance``, ``f2`` (or None), ``edge``, ``bounds``, ``shape``.

    Raises
    ------
    ValueError
        On non-finite or wrongly shaped points, no points, a bad shape or bounds, a shape
        needing more than :data:`RASTER_MAX_BYTES` (:func:`check_raster_size`), or an
        unknown or unsupported method/metric.

    Examples
    --------
    >>> import voroforge as vf
    >>> r = vf.rasterize([[0.25, 0.5], [0.75, 0.5]], (1, 4), (0, 0, 1, 1))
    >>> r.labels.tolist()
    [[0, 0, 1, 1]]
    >>> r.distance.tolist()  # pixel centres at x = 0.125, 0.375, 0.625, 0.875 and y = 0.5
    [[0.125, 0.125, 0.125, 0.125]]
    """
    if method not in METHODS:
        raise ValueError(f"method must be one of {METHODS}; got {method!r}")
    if metric not in METRICS:
        raise ValueError(f"metric must be one of {METRICS}; got {metric!r}")
    if method == "jfa" and metric != "euclidean":
        raise ValueError(
            f"method='jfa' supports metric='euclidean' only (got {metric!r}); "
            "use method='exact' for other metrics"
        )
    pts = as_points(points)
    if len(pts) == 0:
        raise ValueError("points is empty: rasterize needs at least one site")
    h, w = _check_shape(shape)
    check_raster_size((h, w), f2=bool(f2), sites=len(pts), metric=metric)
    box = _check_bounds(bounds, pts)
    pxs, pys = pixel_centers(box, (h, w))
    e = _frame(pts, box)
    if not e:
        lab, d1, d2 = _nearest(pts, box, pxs, pys, method, metric, bool(f2))
        return RasterVoronoi(lab, d1, d2, box, method, metric)
    # squared distances (and the box's width at +-1e308) leave float64's range: the same
    # raster at unit size, scaled by a power of two (exact), distances scaled back. The
    # samples are the pixel centres scaled (exact unless one underflows there: the centres
    # reported are then the points sampled, scaled back)
    with np.errstate(under="ignore"):
        sx, sy = np.ldexp(pxs, -e), np.ldexp(pys, -e)
    sbox = tuple(np.ldexp(box, -e).tolist())
    lab, d1, d2 = _nearest(np.ldexp(pts, -e), sbox, sx, sy, method, metric, bool(f2))
    with np.errstate(over="ignore"):  # (distances past the largest double are inf)
        d2 = None if d2 is None else np.ldexp(d2, e)
        d1 = np.ldexp(d1, e)
    centers = []
    for full, scaled in ((pxs, sx), (pys, sy)):
        back = np.ldexp(scaled, e)
        back.setflags(write=False)
        centers.append(full if np.array_equal(back, full) else back)
    return RasterVoronoi(lab, d1, d2, box, method, metric, tuple(centers))


def _nearest(pts, box, pxs, pys, method, metric, want_f2):
    """``(labels, distance, f2 or None)`` of :func:`rasterize` at the samples ``pxs, pys``."""
    h, w = len(pys), len(pxs)
    # read-only views, as pixel_centers gives them: numba types the writeable flag, and the
    # scaled samples (np.ldexp) compiled every raster kernel a second time
    pxs, pys = pxs.view(), pys.view()
    pxs.setflags(write=False)
    pys.setflags(write=False)
    dup, unique = duplicate_map(pts)
    sub = pts[unique]
    xs = np.ascontiguousarray(sub[:, 0])
    ys = np.ascontiguousarray(sub[:, 1])
    tile = _exact_tile(sub, box, (h, w))
    walk = _walks(sub, box, (h, w), metric, want_f2)
    if method == "exact" and walk:
        lab, d1, d2 = _walk_nearest(xs, ys, pxs, pys, tile, np.zeros((0, 0), dtype=np.int32))
    elif method == "exact":
        lab, d1, d2 = exact_nearest(
            xs, ys, pxs, pys, METRICS.index(metric), want_f2, tile, _MAX_CANDIDATES
        )
    else:
        geom = np.array([box[0], box[3], (box[2] - box[0]) / w, (box[3] - box[1]) / h])
        steps = _jfa_steps(h, w, _jfa_reach(xs, ys, geom, (h, w)))
        flood = jfa_nearest(xs, ys, pxs, pys, geom, steps, want_f2)
    if method == "jfa" and walk:
        # The flood's labels start each pixel's walk on the Delaunay graph (a step or two
        # where the flood was right), which then decides every pixel exactly.
        lab, d1, d2 = _walk_nearest(xs, ys, pxs, pys, tile, flood[0])
    elif method == "jfa":
        # The flood's distances are to real sites: each bounds the pixel's nearest (second
        # nearest) distance, so the tiles below check every pixel against the few sites
        # within that bound. The flood misses sites (crowded arrangements: many sites per
        # pixel, cells thinner than a pixel); the check puts them back.
        lab, d1, d2 = nearest_tiles(
            xs, ys, pxs, pys, 0, want_f2, tile, _MAX_CANDIDATES, flood[2 if want_f2 else 1]
        )
    if len(unique) < len(pts):
        lab = unique.astype(np.int32)[lab]
    return lab, d1, d2 if want_f2 else None
