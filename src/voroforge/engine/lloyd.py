"""Centroidal Voronoi tessellations: Lloyd relaxation, a quasi-Newton solver, capacity constraints.

The CVT energy of sites ``z`` in a domain ``Ω`` with density ``ρ`` is
``F(z) = Σ_i ∫_{V_i(z)} ρ(x) |x - z_i|^2 dx`` over the Voronoi cells ``V_i`` clipped to ``Ω``.
Its gradient is ``∂F/∂z_i = 2 m_i (z_i - c_i)`` with ``m_i`` the mass and ``c_i`` the
density-weighted centroid of cell ``i``; a CVT (``z_i = c_i``) is a critical point.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize

from ._inputs import as_points
from ._integrate import Integrator
from .domain import make_domain
from .power import _fit, _targets
from .voronoi import Diagram, voronoi

METHODS = ("lloyd", "lbfgs")


@dataclass(frozen=True)
class Relaxation:
    """Result of :func:`lloyd`.

    Attributes
    ----------
    points : (n, 2) float64
        The final sites.
    diagram : Diagram
        The final diagram of ``points`` (a :class:`PowerDiagram` with ``areas=``).
    energy : (k + 1,) float64
        CVT energy ``Σ_i ∫_{V_i} ρ |x - z_i|^2`` of the start (``energy[0]``) and after each
        of the ``k`` iterations.
    shift : (k,) float64
        Largest distance a site moved in each iteration.
    elapsed : (k + 1,) float64
        Seconds since the call started when each ``energy`` value was known.
    iterations : int
        ``k``, the iterations performed.
    method : str
        ``"lloyd"`` or ``"lbfgs"``.
    weights : (n,) float64 or None
        Power weights of the final diagram when ``areas=`` was given.
    """

    points: np.ndarray
    diagram: Diagram
    energy: np.ndarray
    shift: np.ndarray
    elapsed: np.ndarray
    iterations: int
    method: str
    weights: np.ndarray | None = None


def _check(iterations, tol, method, areas):
    if method not in METHODS:
        raise ValueError(f"unknown method {method!r}; choose one of {', '.join(METHODS)}")
    if isinstance(iterations, bool) or not isinstance(iterations, (int, np.integer)):
        raise ValueError(f"iterations must be an integer; got {iterations!r}")
    if iterations < 0:
        raise ValueError(f"iterations must be >= 0; got {iterations}")
    if tol is not None and not (np.isfinite(tol) and tol >= 0):
        raise ValueError(f"tol must be None or a non-negative number; got {tol!r}")
    if areas is not None and method != "lloyd":
        raise ValueError("areas= (capacity-constrained CVT) works with method='lloyd' only")


def lloyd(
    points,
    boundary=None,
    *,
    iterations: int = 100,
    tol: float | None = None,
    density=None,
    method: str = "lloyd",
    areas=None,
) -> Relaxation:
    """Relax sites towards a centroidal Voronoi tessellation (CVT) of a domain.

    Parameters
    ----------
    points : (n, 2) array_like
        Starting sites; never modified.
    boundary : None, (xmin, ymin, xmax, ymax) or shapely Polygon/MultiPolygon, optional
        The domain, fixed for the whole run (None: the starting sites' bounding box padded by
        10%). Concave domains, holes and several parts are fine.
    iterations : int
        Most iterations (Lloyd steps, or L-BFGS iterations).
    tol : float, optional
        Stop early once an iteration moves no site farther than ``tol`` times the domain's
        larger side.
    density : None, callable, or raster, optional
        ``ρ >= 0``. None: uniform (exact closed-form moments). A vectorised callable
        ``rho(x, y)`` taking and returning arrays: integrated over each clipped cell with a
        degree-5 triangle rule on a fan of each ring. A raster ``(values (h, w), (xmin, ymin,
        xmax, ymax))`` (or an object with ``values``/``array`` and ``bounds``): row 0 is the top
        (``y = ymax``), the density is 0 outside the box, and it is integrated exactly over
        each cell (cell ∩ pixel pieces), not by counting pixels.
    method : {"lloyd", "lbfgs"}
        ``"lloyd"``: move every site to its cell's centroid. ``"lbfgs"``: minimise the CVT
        energy with L-BFGS (Liu et al. 2009, "On centroidal Voronoi tessellation — energy
        smoothness and fast computation"), energy and gradient from one diagram per
        evaluation, sites kept in the domain's bounding box; much faster near convergence.
    areas : (n,) array_like, optional
        Capacity-constrained CVT (after Balzer et al. 2009): target cell areas summing to the
        domain's area. Every iteration refits power weights with :func:`power_fit` (warm
        started, to 1e-9 relative) and moves the sites to the centroids of those power
        cells, so the final cells have the target areas and are as compact as the targets
        allow. The energy need not decrease monotonically in this mode. Needs distinct sites
        and centroids that stay in the domain (true for convex domains).

    Returns
    -------
    Relaxation
        ``points``, ``diagram``, per-iteration ``energy`` and ``shift``, ``iterations``.

    Raises
    ------
    ValueError
        Malformed points, boundary, density, options or areas.

    Notes
    -----
    Lloyd's energy never increases (exactly so for uniform and raster densities; with a
    callable density up to the quadrature error). Sites outside the domain get the part of
    the domain nearest to them and move to its centroid; a site whose cell is empty has no
    centroid and stays where it is for that iteration. Exact duplicates: the later copies
    get empty cells, so they wait one iteration while the first copy moves to its centroid,
    then they have cells of their own and the sites separate. The centroid of a cell cut by
    a concave boundary can lie outside the domain (that site then gets the domain part
    nearest to it, as any outside site).

    Examples
    --------
    >>> import numpy as np, voroforge as vf
    >>> pts = np.random.default_rng(3).random((100, 2))
    >>> r = vf.lloyd(pts, (0, 0, 1, 1), iterations=20)
    >>> bool(np.all(np.diff(r.energy) <= 1e-15))
    True
    """
    _check(iterations, tol, method, areas)
    z = as_points(points)
    dom = make_domain(boundary, z)
    bnd = dom.bounds if dom.is_rect else dom.geometry
    x0, y0, x1, y1 = dom.bounds
    stop = None if tol is None else float(tol) * max(x1 - x0, y1 - y0)
    integ = Integrator(density, len(z))
    if method == "lbfgs":
        return _lbfgs(z, dom, bnd, integ, int(iterations), stop)
    if areas is not None:
        targets = _targets(areas, len(z), dom)
        return _capacity(z, dom, integ, targets, int(iterations), stop)
    t0 = time.perf_counter()
    energy, elapsed, shifts = [], [], []
    z_new = np.zeros_like(z)
    for it in range(int(iterations) + 1):
        d = voronoi(z, bnd)
        mass, first, second = integ(d._buffers, z)
        energy.append(float(second.sum()))
        elapsed.append(time.perf_counter() - t0)
        if it == iterations:
            break
        shift = _step(z, mass, first, z_new)
        shifts.append(shift)
        z, z_new = z_new, z
        if stop is not None and shift <= stop:
            d = voronoi(z, bnd)
            mass, first, second = integ(d._buffers, z)
            energy.append(float(second.sum()))
            elapsed.append(time.perf_counter() - t0)
            break
    return Relaxation(
        z.copy(), d, np.array(energy), np.array(shifts), np.array(elapsed), len(shifts), "lloyd"
    )


def _step(z, mass, first, out):
    """Centroids into ``out`` (sites with empty cells stay); returns the largest move."""
    ok = mass > 0.0
    move = np.zeros_like(z)
    move[ok] = first[ok] / mass[ok, None]
    np.add(z, move, out=out)
    return float(np.sqrt((move * move).sum(axis=1).max())) if len(z) else 0.0


def _capacity(z, dom, integ, targets, iterations, stop):
    """Lloyd steps on power diagrams whose weights are refitted to the target areas."""
    t0 = time.perf_counter()
    w = np.zeros(len(z))
    energy, elapsed, shifts = [], [], []
    z_new = np.zeros_like(z)
    for it in range(iterations + 1):
        d, w, _, _ = _fit(z.copy(), targets, dom, w, 1e-9, 100)
        mass, first, second = integ(d._buffers, z)
        energy.append(float(second.sum()))
        elapsed.append(time.perf_counter() - t0)
        if it == iterations:
            break
        shift = _step(z, mass, first, z_new)
        shifts.append(shift)
        z, z_new = z_new, z
        if stop is not None and shift <= stop:
            d, w, _, _ = _fit(z.copy(), targets, dom, w, 1e-9, 100)
            mass, first, second = integ(d._buffers, z)
            energy.append(float(second.sum()))
            elapsed.append(time.perf_counter() - t0)
            break
    return Relaxation(
        z.copy(),
        d,
        np.array(energy),
        np.array(shifts),
        np.array(elapsed),
        len(shifts),
        "lloyd",
        w.copy(),
    )


def _lbfgs(z, dom, bnd, integ, iterations, stop):
    """Quasi-Newton CVT: scipy's L-BFGS-B on F(z) with ∂F/∂z_i = -2 ∫ρ (x - z_i)."""
    t0 = time.perf_counter()
    n = len(z)
    cache = {}

    def fun(x):
        zz = x.reshape(n, 2)
        d = voronoi(zz, bnd)
        _, first, second = integ(d._buffers, zz)
        f = float(second.sum())
        cache["last"] = (x.copy(), d, f)
        return f, (-2.0 * first).ravel()

    x0 = z.ravel().copy()
    f0, _ = fun(x0)
    energy, elapsed, shifts = [f0], [time.perf_counter() - t0], []
    prev = [x0]

    def callback(intermediate_result):
        x = intermediate_result.x
        energy.append(float(intermediate_result.fun))
        elapsed.append(time.perf_counter() - t0)
        step = (x - prev[0]).reshape(n, 2)
        shift = float(np.sqrt((step * step).sum(axis=1).max())) if n else 0.0
        shifts.append(shift)
        prev[0] = x.copy()
        if stop is not None and shift <= stop:
            raise StopIteration

    if iterations > 0 and n > 0:
        x_lo, y_lo, x_hi, y_hi = dom.bounds
        bounds = [(x_lo, x_hi), (y_lo, y_hi)] * n
        minimize(
            fun,
            x0,
            jac=True,
            method="L-BFGS-B",
            bounds=bounds,
            callback=callback,
            options={
                "maxiter": iterations,
                "maxfun": 20 * iterations + 20,
                "ftol": 0.0,
                "gtol": 0.0,
                "maxcor": 10,
            },
        )
    x_last = prev[0]
    cx, d, _ = cache["last"]
    if not np.array_equal(cx, x_last):
        fun(x_last)
        _, d, _ = cache["last"]
    return Relaxation(
        x_last.reshape(n, 2).copy(),
        d,
        np.array(energy),
        np.array(shifts),
        np.array(elapsed),
        len(shifts),
        "lbfgs",
    )
