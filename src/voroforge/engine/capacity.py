"""Capacity-constrained cells: :func:`power_fit`, power cells of prescribed areas.

The Newton iteration itself is :func:`.power.fit_weights`; this module validates the input,
chooses the frame it runs in and says why a fit that stalls could not do better.
"""

from __future__ import annotations

import numpy as np
import shapely
from scipy.spatial import cKDTree

from ..config import (
    POWER_FIT_BREAKOUT_GROW,
    POWER_FIT_BREAKOUT_ROUNDS,
    POWER_FIT_CONTINUATION_MIN_STEP,
    POWER_FIT_CONTINUATION_RTOL,
    POWER_FIT_CONTINUATION_STEP,
    POWER_FIT_DEFAULT_RTOL,
    POWER_FIT_FAR,
    POWER_FIT_GAP_EASY_STEPS,
    POWER_FIT_GAP_FACTOR,
    POWER_FIT_GAP_FIRST_EPS,
    POWER_FIT_GAP_FIRST_STEPS,
    POWER_FIT_GAP_MIN_FACTOR,
    POWER_FIT_GAP_STAGE_RTOL,
    POWER_FIT_GAP_STAGE_STEPS,
    POWER_FIT_HOLE_SEED_FRACTION,
    POWER_FIT_HOLE_SEED_STEPS,
    POWER_FIT_PARTS_HOPELESS,
    POWER_FIT_PARTS_REFUSE,
    POWER_FIT_SCALE_EXP,
    POWER_FIT_SUM_RTOL,
)
from .domain import Domain, make_domain, shifted
from .farparts import far_parts, parts_start, straddle_limit, weights_limit
from .inputs import as_points, as_weights, require_distinct, unit_exponent
from .power import PowerDiagram, fit_breakout, fit_weights, power_diagram, shrink_start
from .powerfit import fit_dual
from .threads import serial_below

__all__ = ["as_targets", "power_fit"]


def as_targets(target_areas, n: int, dom: Domain, name: str = "target_areas") -> np.ndarray:
    """Validated target areas, rescaled to sum exactly to the domain's area.

    Parameters
    ----------
    target_areas : (n,) array_like
        Positive areas summing to the domain's area (to ``POWER_FIT_SUM_RTOL``).
    n : int
        Number of sites.
    dom : Domain
        The domain.
    name : str
        The caller's name for them in errors (``vf.lloyd``'s is ``areas``).

    Returns
    -------
    (n,) float64
    """
    t = as_weights(target_areas, n, name=name)
    if not (t > 0.0).all():
        i = int(np.flatnonzero(~(t > 0.0))[0])
        raise ValueError(f"{name} must be positive; index {i} is {t[i]}")
    total = dom.area
    if abs(t.sum() - total) > POWER_FIT_SUM_RTOL * total:
        raise ValueError(
            f"{name} must sum to the domain's area {float(total)!r}; they sum to {float(t.sum())!r}"
        )
    return t * (total / t.sum())


def power_fit(
    points,
    target_areas,
    boundary=None,
    *,
    tol: float = POWER_FIT_DEFAULT_RTOL,
    max_iter: int = 100,
    weights=None,
) -> PowerDiagram:
    """Weights that give every power cell a prescribed area (capacity-constrained cells).

    Maximises the concave dual of the semi-discrete transport problem (Aurenhammer,
    Hoffmann and Aronov 1998) with a damped Newton method: the Hessian is the sparse graph
    Laplacian with entries ``|edge_ij| / (2 |p_i - p_j|)``, solved with
    ``scipy.sparse.linalg.spsolve``; the step is halved until every cell keeps at least half
    of the smallest area seen at the start and the area error shrinks.

    Parameters
    ----------
    points : (n, 2) array_like
        Distinct sites, anywhere. Where sites in a hole or notch of the domain start with
        empty cells, the fit first follows a density relaxed into the domain's convex hull
        (1 on the domain, falling in stages on the rest) down to the domain alone. Else a
        site whose starting cell is empty (outside the domain) gets a weight that opens a
        small cell at the domain point nearest to it; if that fails, or Newton stalls,
        the fit starts again from the Voronoi cells
        of the sites shrunk towards a point inside the domain, and if that stalls too, it
        follows targets moved in steps from those cells' areas to the given ones (each
        step a warm start). Never modified.
    target_areas : (n,) array_like
        Positive areas that sum to the domain's area (to 1e-6 relative; they are rescaled to
        sum exactly).
    boundary : None, (xmin, ymin, xmax, ymax) or shapely Polygon/MultiPolygon, optional
        The domain, as for :func:`voroforge.voronoi`.
    tol : float
        Stop when every ``|area_i - target_i| / target_i <= tol``.
    max_iter : int
        Most Newton steps.
    weights : (n,) array_like, optional
        Starting weights (default zeros: the Voronoi diagram); warm starts converge faster.
        Starting weights that leave a cell empty are replaced by zeros.

    Returns
    -------
    PowerDiagram
        The fitted diagram; ``.weights`` are the weights found.

    Raises
    ------
    ValueError
        Malformed input, duplicate sites, targets not positive or not summing to the domain's
        area, or a site whose cell cannot be opened.
    RuntimeError
        When the areas do not reach ``tol`` within ``max_iter`` steps (per start, and per
        step of the targets); the message names the cells farthest from their targets.

    Examples
    --------
    >>> import numpy as np, voroforge as vf
    >>> pts = np.random.default_rng(2).random((40, 2))
    >>> target = np.full(40, 1 / 40)
    >>> d = vf.power_fit(pts, target, (0, 0, 1, 1))
    >>> bool(np.all(np.abs(d.areas - target) <= 1e-6 * target))
    True
    """
    pts = as_points(points)
    n = len(pts)
    dom = make_domain(boundary, pts)
    t = as_targets(target_areas, n, dom)
    w0 = np.zeros(n) if weights is None else as_weights(weights, n)
    if not (isinstance(tol, (int, float, np.number)) and tol > 0 and np.isfinite(tol)):
        raise ValueError(f"tol must be a positive number; got {tol!r}")
    if isinstance(max_iter, bool) or not isinstance(max_iter, (int, np.integer)):
        raise ValueError(f"max_iter must be an integer; got {max_iter!r}")
    if max_iter < 0:
        raise ValueError(f"max_iter must be >= 0; got {max_iter!r}")
    require_distinct(pts, "capacity fitting")
    # the fit runs where the domain is about unit size (the user's problem scaled by a power
    # of two, exactly): at 1e-150 its Newton stalled after one step and its polygon clip
    # raised GEOSException, and at 1e154 areas overflowed and the fit returned unfitted cells
    x0, y0, x1, y1 = dom.bounds
    e = unit_exponent(max(x1 - x0, y1 - y0), POWER_FIT_SCALE_EXP)
    ws = (pts, t, dom, w0) if not e else _scaled(pts, t, dom, w0, -e)
    with serial_below(n):
        d, w, err, it = _fit(*ws, tol, int(max_iter))
        if e:  # the weights back in the user's frame, and the cells and their error there
            d = power_diagram(pts, np.ldexp(w, 2 * e), dom)
            err = _area_error(d, t)
    if not err <= tol:  # NaN too: areas past float64's range are no fit
        # sites too close for float64 weights are the more specific cause: named first
        near = _near_pairs_note(pts, dom)
        held = "" if near else _weights_note(pts, d, tol)
        raise RuntimeError(
            f"power_fit did not reach tol={tol:g} in {it} Newton steps (largest relative "
            f"area error {err:.3g}){near}"
            f"{_far_note(t, dom, tol, d)}"
            f"{held}{_worst_note(d, t, n > 1 and not held)}"
        )
    return d


def _fit(pts, t, dom, w0, tol, max_iter):
    """``fit_weights`` near the origin, a second start where it stalls, a polish in place.

    Newton runs near the origin (weights do not change under a translation): far out the
    cells' areas carry the coordinates' rounding (a cell of area 2e-7 at 1e5 stalled at
    6e-6 relative); the given frame only checks and polishes the result.
    """
    x0, y0, x1, y1 = dom.bounds
    far = max(abs(x0), abs(y0), abs(x1), abs(y1)) > POWER_FIT_FAR * max(x1 - x0, y1 - y0)
    c = np.array([x0, y0]) if far else np.zeros(2)
    lpts, ldom = (pts - c, shifted(dom, c)) if far else (pts, dom)
    d, w, err, it = _local_fit(lpts, t, ldom, w0, tol, max_iter)
    if far:  # d is in the moved frame: the given frame's diagram, polished there
        d, w, err, it2 = fit_weights(pts, t, dom, w, tol, max_iter)
        it += it2
    return d, w, err, it


def _local_fit(pts, t, dom, w0, tol, max_iter):
    """The fit in Newton's frame: ``fit_weights``, and the restarts where it stalls."""
    parts = len(pts) > 1 and shapely.get_num_geometries(dom.geometry) > 1
    cap = min(max_iter, POWER_FIT_GAP_FIRST_STEPS) if parts else max_iter
    relaxed = None
    if parts and far_parts(dom.geometry):
        # parts far apart (two squares 1,000 apart, 400 sites in one: the gap continuation's
        # first stage stalled, no fit): each part fitted alone with the sites it serves
        spread, limit = straddle_limit(pts, t, dom)
        if limit > POWER_FIT_PARTS_REFUSE * tol:
            raise RuntimeError(
                f"power_fit cannot reach tol={tol:g} on this domain's far parts: the sites "
                f"serving one part need weights {spread:.3g} apart (a cell that must "
                "straddle a gap G from the far side needs about G**2, sites all on one side "
                "2 G times their extent), which float64 holds to "
                f"{float(np.spacing(spread)):.2g}: the cells' areas only to about {limit:.2g} "
                "relative (raise tol, move the parts closer, or give targets that the sites "
                "in each part fill without a cell across the gap)"
            )
        if w0.any():
            got = fit_weights(pts, t, dom, w0, tol, cap)
            if got[2] <= tol:
                return got
        got = _far_fit(pts, t, dom, tol, max_iter)
        # fitted, or float64 weights or coordinates cannot hold it (the error says so); an
        # infinite error is a start the dual could not use: the other starts follow
        if got is not None and (
            got[2] <= tol
            or np.isfinite(got[2])
            and (weights_limit(pts, got[1], got[0]) > tol or bool(_far_note(t, dom, tol, got[0])))
        ):
            return got
    start, few = (None, False) if parts or len(pts) < 2 else _hole_start(pts, dom, w0)
    if start is not None:
        got = _breakout(pts, t, dom, start, tol, max_iter)
        if got is not None and got[2] <= tol:
            return got
    if start is not None and few:
        # a few sites start with empty cells (a small hole): the slivers seeded for them
        # fit in a few Newton steps (r = 0.1: 500 sites 16 box builds against the relaxed
        # density's 23, 2,000 25 against 41); where they do not, the relaxed density follows
        got = fit_weights(pts, t, dom, w0, tol, min(max_iter, POWER_FIT_HOLE_SEED_STEPS))
        if got[2] <= tol:
            return got
    if start is not None:
        # sites in a hole or a notch that start with empty cells: the slivers seeded for
        # them give Newton a start where its steps empty other cells (checker22 F3: 28% of
        # 1000 sites in a hole, 100 steps stalled at 39x the targets, then the targets'
        # continuation, 47 s); the density relaxed into the hole gives them room instead
        relaxed = _gap_continuation(pts, t, dom, start, tol, max_iter)
        if relaxed is not None and relaxed[2] <= tol:
            return relaxed
    d, w, err, it = fit_weights(pts, t, dom, w0, tol, cap)
    if relaxed is not None and relaxed[2] < err:
        d, w, err, it = relaxed[0], relaxed[1], relaxed[2], it + relaxed[3]
    if err > tol and parts:
        # parts apart: the cells of one part see another's only through a cell on both
        start = w0 if (power_diagram(pts, w0, dom).areas > 0.0).all() else shrink_start(pts, dom)
        got = _gap_continuation(pts, t, dom, start, tol, max_iter)
        if got is not None and got[2] < err:
            d, w, err, it = got[0], got[1], got[2], it + got[3]
        if err > tol and cap < max_iter:
            d, w, err, it2 = fit_weights(pts, t, dom, w, tol, max_iter - cap)
            it += it2
    if err > tol and len(pts) > 1:
        # Newton stalled (e.g. cells that must straddle the gap of a MultiPolygon): start
        # again from the shrunk sites, where every cell is open and reaches the interior
        d2, w2, err2, it2 = fit_weights(pts, t, dom, shrink_start(pts, dom), tol, max_iter)
        if err2 < err:
            d, w, err, it = d2, w2, err2, it2
        if err > tol:
            # both stalled (checker12 F9: sites whose cells are slivers at a hole's edge, far
            # from the sites, where the areas bend too sharply for Newton's steps): follow
            # the targets from the shrunk sites' areas in steps, each a warm start
            got = _continuation(pts, t, dom, tol, max_iter)
            if got is not None and got[2] < err:
                d, w, err, it = got
    return d, w, err, it


def _far_fit(pts, t, dom, tol, max_iter):
    """``fit_weights`` from :func:`.farparts.parts_start`'s weights, or None where it fails."""
    w, steps = parts_start(pts, t, dom, tol, max_iter, _local_fit)
    if w is None:
        return None
    d = power_diagram(pts, w, dom)
    if (d.areas > 0.0).all():
        err = _area_error(d, t)
        if err > tol and weights_limit(pts, w, d) > POWER_FIT_PARTS_HOPELESS * tol:
            # the joined weights' own rounding moves the areas past tol: a polish's steps
            # round back to them, each halved 40 times (2,000 sites split between squares
            # 1,000 apart, random targets: 3.7e-6 before and after ~100 diagrams); the
            # caller raises with the weights' note
            return d, w, err, steps
        d, w, err, it = fit_weights(pts, t, dom, w, tol, max_iter)
        return d, w, err, it + steps
    # a site serving one part reached into another and emptied a cell there (the parts'
    # transport sorts sites by the gap's direction only): the dual's steps from here (where
    # fit_weights would start again from zeros)
    hull = make_domain(shapely.convex_hull(dom.geometry), pts)
    d, w, err, it = fit_dual(pts, t, dom, hull, w, tol, max_iter)
    return d, w, err, it + steps


def _hole_start(pts, dom, w0):
    """Start weights for the relaxed fit when sites outside the domain start with empty cells.

    ``(None, False)`` when every site lies in the domain, when the domain is convex (no hole
    or notch to relax into), or when the start :func:`.power.fit_weights` takes (``w0``,
    else zeros) opens every cell. Else zeros where their cells all meet the convex hull
    (every cell has mass under the relaxed density), or the shrunk sites' weights; and
    whether at most ``POWER_FIT_HOLE_SEED_FRACTION`` of the cells start empty.
    """
    geom = dom.geometry
    if shapely.contains_xy(geom, pts[:, 0], pts[:, 1]).all():
        return None, False
    hull = shapely.convex_hull(geom)
    if not hull.area > dom.area:
        return None, False
    areas = power_diagram(pts, w0, dom).areas
    if (areas > 0.0).all():
        return None, False
    zeros = np.zeros(len(pts))
    if w0.any():
        areas = power_diagram(pts, zeros, dom).areas
        if (areas > 0.0).all():
            return None, False
    few = bool((areas <= 0.0).sum() <= POWER_FIT_HOLE_SEED_FRACTION * len(pts))
    if (power_diagram(pts, zeros, make_domain(hull, pts)).areas > 0.0).all():
        return zeros, few
    return shrink_start(pts, dom), few


def _breakout(pts, t, dom, w0, tol, max_iter):
    """``fit_weights`` from :func:`.power.fit_breakout`'s weights, or None where it fails.

    The relaxed density's continuation moved the cells wholly in a hole out of it about
    half at a time as its ``eps`` halved, each stage a few damped Newton steps on both
    diagrams, down to ``eps ~ 1/n`` (a 4,000-site ring: 13 stages, 223 diagram pairs).
    """
    hull = make_domain(shapely.convex_hull(dom.geometry), pts)
    got = fit_breakout(pts, t, dom, hull, w0, POWER_FIT_BREAKOUT_ROUNDS, POWER_FIT_BREAKOUT_GROW)
    if got is None:
        return None
    # where a round pushed cells back out, Kitagawa-Merigot-Thibert's steps from here empty
    # cells and are taken at 1/16-1/4 (a U notch, 4,000 sites: 28 steps, 43 diagrams); the
    # dual's steps may empty a cell on the way (17 steps, 29 diagrams). Else (a ring, a
    # small hole: the breakout's count falls every round) the plain steps are the cheaper
    fit = fit_dual if got[2] else fit_weights
    args = (pts, t, dom, hull, got[0]) if got[2] else (pts, t, dom, got[0])
    d, w, err, it = fit(*args, tol, max_iter)
    return d, w, err, it + got[1]


def _gap_continuation(pts, t, dom, w0, tol, max_iter):
    """``fit_weights`` on a domain with gaps, through densities that fill them.

    Between a MultiPolygon's parts the Hessian has entries only where a cell lies in
    both, so Newton's step is singular, or nearly so (checker22 F1: two squares 1000
    apart, 40 sites in one: 49 steps, no fit); sites in a hole start with empty cells, and
    the slivers seeded for them make Newton's steps empty other cells (checker22 F3). The
    density 1 on the domain and ``eps`` on the rest of its convex hull has a connected
    support, where damped Newton converges from any weights that give every cell mass
    (Kitagawa, Merigot and Thibert 2019). ``eps`` starts at ``POWER_FIT_GAP_FIRST_EPS`` (at most
    the gap holding as much mass as the domain) and falls by ``POWER_FIT_GAP_FACTOR`` per stage
    (squared after an easy stage, its square root after a stage that does not fit), each
    a warm start fitted to ``POWER_FIT_GAP_STAGE_RTOL``, until the gap's mass is within that
    tolerance of the smallest target; then ``eps = 0`` to ``tol``. ``w0`` must give
    every cell mass under the first density. Returns ``(d, w, err, steps)``, or None when
    the first stage does not fit or the factor falls below ``POWER_FIT_GAP_MIN_FACTOR``.
    """
    hull = make_domain(shapely.convex_hull(dom.geometry), pts)
    area = dom.area
    gap = hull.area - area
    if not gap > 0.0:
        return None
    eps = min(POWER_FIT_GAP_FIRST_EPS, area / gap)
    want = max(tol, POWER_FIT_GAP_STAGE_RTOL)
    end = want * float(t.min())
    w, steps = w0.copy(), 0
    factor, last = POWER_FIT_GAP_FACTOR, None
    while eps * gap > end:
        te = t * ((area + eps * gap) / area)
        cap = max_iter if last is None else min(max_iter, POWER_FIT_GAP_STAGE_STEPS)
        if eps >= 1.0:  # the density 1 on the whole hull: the plain fit there
            _, w_try, err, it = fit_weights(pts, te, hull, w, want, cap)
        else:
            _, w_try, err, it = fit_weights(pts, te, dom, w, want, cap, relax=(hull, eps))
        steps += it
        if err <= want:
            w, last = w_try, eps
            if it <= POWER_FIT_GAP_EASY_STEPS:  # an easy stage: the next one a longer step
                factor *= factor
            eps /= factor
            continue
        if last is None:
            return None
        factor = np.sqrt(factor)
        if factor < POWER_FIT_GAP_MIN_FACTOR:
            return None
        eps = last / factor
    d, w, err, it = fit_weights(pts, t, dom, w, tol, max_iter)
    return d, w, err, steps + it


def _continuation(pts, t, dom, tol, max_iter):
    """``fit_weights`` along targets moving from the shrunk sites' areas to ``t``.

    The targets ``a0**(1 - s) t**s`` (normalised to the domain's area) for growing ``s``,
    each fitted to ``config.POWER_FIT_CONTINUATION_RTOL`` from the last one's weights (the
    last to ``tol``);
    a step that does not fit is halved. Returns ``(d, w, err, steps)`` of the furthest
    target reached (its error against ``t``), or None when no step fits.
    """
    w = shrink_start(pts, dom)
    a0 = power_diagram(pts, w, dom).areas
    if not (a0 > 0.0).all():
        return None
    log0, log1 = np.log(a0), np.log(t)
    best, s, ds, steps = None, 0.0, POWER_FIT_CONTINUATION_STEP, 0
    while s < 1.0 and ds >= POWER_FIT_CONTINUATION_MIN_STEP:
        nxt = min(1.0, s + ds)
        ts = np.exp((1.0 - nxt) * log0 + nxt * log1)
        ts *= t.sum() / ts.sum()
        want = tol if nxt == 1.0 else max(tol, POWER_FIT_CONTINUATION_RTOL)
        d, w_try, err, it = fit_weights(pts, ts, dom, w, want, max_iter)
        steps += it
        if err <= want:
            s, w = nxt, w_try
            best = (d, w, _area_error(d, t), steps)
        else:
            ds *= 0.5
    return best


def _scaled(pts, t, dom, w0, k):
    """The fit's input scaled by ``2**k`` (areas and weights by ``4**k``): exact."""
    return np.ldexp(pts, k), np.ldexp(t, 2 * k), dom.scaled(k), np.ldexp(w0, 2 * k)


def _area_error(d, t) -> float:
    """Largest ``|area - target| / target`` (NaN where the areas left float64's range)."""
    with np.errstate(invalid="ignore", over="ignore"):
        return float(np.max(np.abs(np.asarray(d.areas) - t) / t))


def _worst_note(d, t, tried) -> str:
    """The cells farthest from their targets, and (``tried``) the starts tried."""
    with np.errstate(invalid="ignore", over="ignore"):
        rel = np.abs(np.asarray(d.areas) - t) / t
    worst = np.argsort(-np.nan_to_num(rel, nan=np.inf), kind="stable")[:3]
    cells = ", ".join(f"{int(i)} (area {d.areas[i]:.3g}, target {t[i]:.3g})" for i in worst)
    tried = (
        "; tried Newton from the given weights, from the sites shrunk into the domain and "
        "along targets moved in steps from the shrunk sites' areas"
        if tried
        else ""
    )
    return f"; farthest from their targets: sites {cells}{tried}"


def _weights_note(pts, d, tol) -> str:
    """A note when rounding the fitted weights alone moves the areas past ``tol``."""
    w = np.asarray(d.weights)
    if not np.isfinite(w).all():
        return ""
    limit = weights_limit(pts, w, d)
    if not limit > tol:
        return ""
    return (
        f"; the weights span {float(w.max() - w.min()):.3g} (a cell that must straddle far "
        "parts of the domain needs its weight about the gap squared from its neighbours' on "
        f"the other part): float64 holds them to {float(np.spacing(np.abs(w).max())):.2g}, "
        f"which moves the cells' areas by up to about {limit:.2g} relative (raise tol, or "
        "give targets that each part's sites fill without a cell across the gap)"
    )


def _far_note(targets, dom, tol, d=None) -> str:
    """A note when the smallest cell is too few ulps of its coordinates wide for ``tol``.

    Vertices rounded to ``u`` (the ulp of the coordinates) move a cell's area by about
    ``perimeter * u``: ``4 u / s`` relative for a square of side ``s``, ``2 u / w`` for a
    strip ``w`` wide. The smallest target's cell in ``d`` gives its own perimeter, area and
    width (the short side of its minimum rotated rectangle; checker15 F2: a strip 5e-11
    wide was called 7e-9 wide, from the square root of its area); without that cell, a
    square of the target's area.
    """
    far = float(np.abs(np.asarray(dom.bounds)).max())
    ulp = float(np.spacing(far))
    i = int(np.argmin(targets))
    side = float(np.sqrt(targets[i]))
    limit = 4.0 * ulp / side
    cell = None if d is None else d.cells[i]
    if cell is not None and not cell.is_empty and cell.area > 0.0:
        rect = np.asarray(shapely.get_coordinates(shapely.minimum_rotated_rectangle(cell)))
        sides = np.hypot(*np.diff(rect[:3], axis=0).T) if len(rect) >= 3 else np.zeros(1)
        side = float(sides.min()) if sides.min() > 0.0 else 2.0 * cell.area / cell.length
        limit = cell.length * ulp / cell.area
    if limit < 0.1 * tol:
        return ""
    x0, y0, x1, y1 = dom.bounds
    moved = far > 2.0 * max(x1 - x0, y1 - y0)  # else the input is already at the origin
    return (
        f"; the smallest cell (about {side:.3g} wide) at coordinates near {far:.3g} is "
        f"{side / ulp:.3g} ulps wide, so rounding alone limits its area to "
        f"about {limit:.2g} relative ("
        f"{'move the input near the origin, or raise tol' if moved else 'raise tol'})"
    )


def _near_pairs_note(pts, dom) -> str:
    """A note naming sites too close for float64 weights to place their bisector, if any.

    The bisector of sites ``d`` apart moves by ``dw / (2 d)``: with weights of size ``w``
    its position is only known to ``ulp(w) / (2 d)``. Sites a few ulps apart with other
    cells needing weights of any size cannot reach a small tolerance.
    """
    if len(pts) < 2:
        return ""
    dist, idx = cKDTree(pts).query(pts, k=2)
    x0, y0, x1, y1 = dom.bounds
    size = max(x1 - x0, y1 - y0)
    close = np.flatnonzero(dist[:, 1] < 1e-9 * size)
    if not len(close):
        return ""
    i = int(close[0])
    return (
        f"; sites {i} and {int(idx[i, 1])} are {dist[i, 1]:.3g} apart, too close for "
        "float64 weights to place their bisector (merge them or move them apart)"
    )
