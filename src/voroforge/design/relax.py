"""Lloyd relaxation of seeds inside a boundary (evens out cell sizes and shapes)."""

from __future__ import annotations

import math

import numpy as np

import voroforge

__all__ = ["relax"]

_MAX_WITH_TOL = 500  # iteration cap when only a tolerance is given


def relax(points, boundary, *, iterations: int = 0, tol=None, density=None) -> np.ndarray:
    """Move seeds towards the centroids of their Voronoi cells (Lloyd's algorithm).

    Uses ``voroforge.lloyd`` (exact cell moments, optional density) when the engine has
    it, otherwise a plain loop of ``vf.voronoi`` and cell centroids.

    Parameters
    ----------
    points : (n, 2) array_like
        Seeds; never modified.
    boundary : shapely Polygon/MultiPolygon or (xmin, ymin, xmax, ymax)
        The domain the cells are clipped to.
    iterations : int
        Most Lloyd steps. 0 with ``tol=None`` returns a copy of the points; 0 with a ``tol``
        iterates until converged (at most 500 steps).
    tol : float, optional
        Stop once no seed moves farther than ``tol`` (in boundary units, e.g. mm).
    density : callable, optional
        ``density(xy (m, 2)) -> (m,)`` >= 0 (for example an attractor field): cells become
        smaller where it is large. Needs the engine's ``voroforge.lloyd``.

    Returns
    -------
    (n, 2) float64
        The relaxed seeds, in input order. A seed whose cell is empty stays put.

    Examples
    --------
    >>> import numpy as np
    >>> pts = np.random.default_rng(0).random((50, 2)) * 100
    >>> relax(pts, (0, 0, 100, 100), iterations=10).shape
    (50, 2)
    """
    if isinstance(iterations, bool) or int(iterations) != iterations or iterations < 0:
        raise ValueError(f"iterations must be an integer >= 0, got {iterations!r}")
    iterations = int(iterations)
    stop = None
    if tol is not None:
        stop = float(tol)
        if not (math.isfinite(stop) and stop >= 0):
            raise ValueError(f"tol must be a finite number >= 0, got {tol!r}")
        if iterations == 0:
            iterations = _MAX_WITH_TOL
    if density is not None and not callable(density):
        raise ValueError("density must be a callable density(xy) -> values >= 0")
    pts = np.array(points, dtype=np.float64, copy=True)
    if pts.ndim != 2 or pts.shape[1] != 2:
        raise ValueError(f"points must have shape (n, 2), got {pts.shape}")
    if not np.isfinite(pts).all():
        raise ValueError("points contain NaN or infinite coordinates")
    if iterations == 0 or len(pts) == 0:
        return pts
    lloyd = getattr(voroforge, "lloyd", None)
    if lloyd is not None:
        return _engine(lloyd, pts, boundary, iterations, stop, density)
    if density is not None:
        raise ValueError("density needs voroforge.lloyd, which this engine does not provide")
    return _plain(pts, boundary, iterations, stop)


def _engine(lloyd, pts, boundary, iterations, stop, density):
    rel_tol = None
    if stop is not None:
        from ..engine.domain import make_domain

        x0, y0, x1, y1 = make_domain(boundary, pts).bounds  # the domain as lloyd sees it
        rel_tol = stop / max(x1 - x0, y1 - y0)
    rho = None
    if density is not None:

        def rho(x, y):
            xy = np.column_stack((np.ravel(x), np.ravel(y)))
            return np.asarray(density(xy), dtype=np.float64).reshape(np.shape(x))

    result = lloyd(pts, boundary, iterations=iterations, tol=rel_tol, density=rho)
    return np.array(result.points, dtype=np.float64)


def _plain(pts, boundary, iterations, stop):
    for _ in range(iterations):
        c = voroforge.voronoi(pts, boundary).centroids
        new = np.where(np.isfinite(c), c, pts)
        shift = float(np.sqrt(((new - pts) ** 2).sum(axis=1)).max())
        pts = new
        if stop is not None and shift <= stop:
            break
    return pts
