"""Power (Laguerre) diagrams, :func:`power`, and the Newton fit of their weights.

Cell ``i`` of the power diagram of sites ``p`` with weights ``w`` is
``{x : |x - p_i|^2 - w_i <= |x - p_j|^2 - w_j for all j}``. Its neighbours come from the
regular triangulation, the lower convex hull of the lifted points ``(x, y, x^2 + y^2 - w)``
(Qhull through ``scipy.spatial.ConvexHull``); each cell is the domain's bounding box cut by the
power bisectors of those neighbours (``kernels/power.py``), then clipped to polygonal domains
by the same code as :func:`voroforge.voronoi`.
"""

from __future__ import annotations

import warnings
from functools import partial

import numpy as np
import scipy.sparse as sp
import shapely
from scipy.sparse.csgraph import connected_components
from scipy.sparse.linalg import MatrixRankWarning, spsolve
from scipy.spatial import ConvexHull, QhullError

from ..config import (
    POWER_BRIDGE_GAIN_RTOL,
    POWER_FIT_ALPHA_GROWTH,
    POWER_FLAT_RTOL,
    POWER_FRAME_EXP,
    POWER_HIDDEN_RTOL,
    POWER_LABEL_RTOL,
    POWER_LIFT_RESOLVE_ULPS,
    POWER_NEWTON_SHIFT,
)
from ..kernels.power import power_cells
from .assemble import assemble
from .diagram import Diagram, Edges, buffers, frame_exponent
from .domain import Domain, make_domain
from .inputs import as_points, as_weights, duplicate_map, unit_exponent
from .planar import build
from .power_check import checked_cells, lost_candidates, pairs_csr, settle
from .power_exact import lost_sites, on_one_line

#: Up to this many sites every pair is a candidate neighbour (no triangulation needed).
_ALL_PAIRS_MAX = 16
_EPS = float(np.finfo(float).eps)


class PowerDiagram(Diagram):
    """A power (Laguerre) diagram: a :class:`~voroforge.Diagram` with the sites' weights.

    Cells may be empty (a light site can be hidden by heavy neighbours) and a site need not
    lie in its own cell.

    Attributes
    ----------
    weights : (n,) float64
        The weights the cells were built with (read-only), in squared coordinate units.
    duplicate_of : (n,) int64
        -1, or for sites at the same coordinates the index of the one that owns the cell (the
        heaviest; the first among equal weights). Note that the owner may come later.
    """

    def __init__(self, sites, duplicate_of, domain, buffers, edges, weights, k=0, unresolved=None):
        super().__init__(sites, duplicate_of, domain, buffers, edges, "power", k, unresolved)
        self.weights = weights
        weights.setflags(write=False)

    def locate(self, xy):
        """Index of the site with the smallest power distance ``|x - p_i|^2 - w_i``.

        That is the site whose (unclipped) power cell contains ``x``. With ``c = max(w)``,
        ``|x - p_i|^2 - w_i + c`` is the squared 3D distance from ``(x, 0)`` to
        ``(p_i, sqrt(c - w_i))``, so one KD-tree query answers it.

        Parameters
        ----------
        xy : (2,) or (m, 2) array_like
            Query points, anywhere.

        Returns
        -------
        int or (m,) int64
            Site index (the owner for duplicated sites; exact ties go to the lowest index).
        """
        from .interpolate import locate_power

        return locate_power(self, xy)


def _owners(pts: np.ndarray, w: np.ndarray) -> np.ndarray:
    """``duplicate_of`` for power cells: the heaviest copy of a site owns it (ties: first)."""
    dup, _ = duplicate_map(pts)
    if (dup < 0).all():
        return dup
    key = np.where(dup < 0, np.arange(len(pts)), dup)
    order = np.lexsort((np.arange(len(pts)), -w, key))
    first = np.ones(len(pts), dtype=bool)
    first[1:] = key[order][1:] != key[order][:-1]
    winner = np.zeros(len(pts), dtype=np.int64)
    winner[key[order[first]]] = order[first]
    own = winner[key]
    return np.where(own == np.arange(len(pts)), -1, own)


def _may_win(x, y, w, box, active):
    """``active`` without the sites that lose to one other site everywhere in the box.

    Site ``i`` has no point of the box when its smallest power distance there exceeds the
    largest power distance there of some site ``k``. Dropping such sites changes no cell,
    and keeps Qhull's lift well scaled when the weights span many orders of magnitude.
    """
    if active.sum() < 2:
        return active
    near_x = np.maximum(np.maximum(box[0] - x, x - box[2]), 0.0)
    near_y = np.maximum(np.maximum(box[1] - y, y - box[3]), 0.0)
    far_x = np.maximum(x - box[0], box[2] - x)
    far_y = np.maximum(y - box[1], box[3] - y)
    near = near_x * near_x + near_y * near_y - w
    far = far_x * far_x + far_y * far_y - w
    best = float(far[active].min())
    # generous slack for rounding: only clearly hidden sites are dropped
    slack = POWER_HIDDEN_RTOL * (float((far_x * far_x + far_y * far_y)[active].max()) + abs(best))
    return active & (near <= best + slack)


def _neighbors(x, y, w, box, active):
    """Candidate neighbours (CSR), sites that may have a cell, and the suspects.

    Suspects (a mask) are sites near what the lift could not resolve, for
    :func:`~voroforge.engine.power_check.checked_cells`; None when it resolved all.
    """
    n = len(x)
    active = _may_win(x, y, w, box, active)
    idx = np.flatnonzero(active)
    m = len(idx)
    if m <= _ALL_PAIRS_MAX:
        a, b = np.triu_indices(m, 1)
        return (*pairs_csr(n, idx[a], idx[b]), active, None)
    # lift in a frame centred on the box with unit size: well-conditioned for Qhull
    cx = 0.5 * (box[0] + box[2])
    cy = 0.5 * (box[1] + box[3])
    s = max(box[2] - box[0], box[3] - box[1])
    u = (x[idx] - cx) / s
    v = (y[idx] - cy) / s
    lift = np.column_stack((u, v, u * u + v * v - (w[idx] - w[idx].max()) / (s * s)))
    try:
        hull = ConvexHull(lift, qhull_options="Qc")  # Qc: the coplanar points too
    except QhullError:
        span = np.column_stack((u - u[0], v - v[0]))
        far = int(np.argmax(np.einsum("ij,ij->i", span, span)))
        cross = span[:, 0] * span[far, 1] - span[:, 1] * span[far, 0]
        if np.abs(cross).max() <= POWER_FLAT_RTOL * float(span[far] @ span[far]):
            indptr, indices, on_line = _collinear(n, idx, span, span[far], lift[:, 2], active)
            if not np.abs(cross).max() > 0.0 and on_one_line(x[idx], y[idx], far):
                return indptr, indices, on_line, None
            # flat only to rounding (two clusters 1e-9 wide 1e6 apart; or 1e-12 wide at
            # the origin, all one point in the frame): the chain is a first guess, checked
            # like a lift that lost sites
            rows = np.repeat(np.arange(n), np.diff(indptr))
            a, b = lost_candidates(x, y, w, idx, (cx, cy), rows, indices, idx)
            key = np.unique(np.minimum(a, b) * n + np.maximum(a, b))
            return (*pairs_csr(n, key // n, key % n), active, active.copy())
        hull = ConvexHull(lift, qhull_options="QJ")  # coplanar lift: one shared vertex
    lower = hull.simplices[hull.equations[:, 2] < 0.0]
    on_hull = np.zeros(n, dtype=bool)
    on_hull[idx[lower.ravel()]] = True
    a = idx[lower[:, [0, 1, 2]].ravel()]
    b = idx[lower[:, [1, 2, 0]].ravel()]
    # a facet shorter than Qhull's rounding (relative to the largest lifted coordinate) has
    # lost z's curvature and sites with it (1e-6 clusters 1e3 apart: 17 of 120 on the hull,
    # or one at the box's centre); every site may then have a cell
    turn = lower[:, [1, 2, 0]]
    side = (u[lower] - u[turn]) ** 2 + (v[lower] - v[turn]) ** 2
    short = side < POWER_LIFT_RESOLVE_ULPS * _EPS * 2.0 * np.abs(lift).max()
    # sites Qhull set aside within its rounding of a lower facet: lost the same way, also
    # where no facet is short (four clusters 1e-10 wide at 3e5: one vertex each, 116 lost)
    cop = hull.coplanar
    cop = cop[hull.equations[cop[:, 1], 2] < 0.0]
    suspect = None
    if short.any() or len(cop):
        # suspects: the short facets' sites and the lost sites' nearest vertices, their
        # lift neighbours, and the sites off the hull (hidden, or lost); each gets its
        # nearest lifted sites as candidates
        suspect = np.zeros(n, dtype=bool)
        suspect[idx[lower[short.any(axis=1)].ravel()]] = True
        suspect[idx[cop[:, 2]]] = True
        touch = suspect[idx[lower]].any(axis=1)
        suspect[idx[lower[touch].ravel()]] = True
        suspect |= active & ~on_hull
        a, b = lost_candidates(x, y, w, idx, (cx, cy), a, b, np.flatnonzero(suspect))
        on_hull = active
    key = np.minimum(a, b) * n + np.maximum(a, b)
    key.sort()
    keep = np.ones(len(key), dtype=bool)
    keep[1:] = key[1:] != key[:-1]
    key = key[keep]
    return (*pairs_csr(n, key // n, key % n), active & on_hull, suspect)


def _collinear(n, idx, span, direction, z, active):
    """Collinear sites: neighbours along the lower hull of ``(t, t^2 - w)`` (1D lift)."""
    t = span @ (direction / np.sqrt(direction @ direction))
    # on the line z = u^2 + v^2 - w is t^2 - w plus an affine function of t: same lower hull
    order = np.argsort(t, kind="stable")
    chain: list[int] = []
    for k in order.tolist():
        while len(chain) >= 2:
            a, b = chain[-2], chain[-1]
            cr = (t[b] - t[a]) * (z[k] - z[a]) - (z[b] - z[a]) * (t[k] - t[a])
            if cr <= 0.0:
                chain.pop()
            else:
                break
        chain.append(k)
    ch = idx[np.array(chain, dtype=np.int64)]
    keep = np.zeros(n, dtype=bool)
    keep[ch] = True
    return (*pairs_csr(n, ch[:-1], ch[1:]), active & keep)


def power_diagram(pts: np.ndarray, w: np.ndarray, dom: Domain) -> PowerDiagram:
    """Power diagram of validated input (no copies of ``pts``/``w`` are taken).

    Parameters
    ----------
    pts : (n, 2) float64
        Sites, as :func:`voroforge.engine.inputs.as_points` gives them.
    w : (n,) float64
        Weights, as :func:`voroforge.engine.inputs.as_weights` gives them.
    dom : Domain
        The domain.

    Returns
    -------
    PowerDiagram
    """
    return power_diagrams(pts, w, (dom,))[0]


def power_diagrams(pts: np.ndarray, w: np.ndarray, doms) -> tuple[PowerDiagram, ...]:
    """:func:`power_diagram` on each of ``doms``, the box cells built once where they can be.

    The cells are the bounding box cut by power bisectors, then clipped to the domain: on
    domains with one bounding box (a domain and its convex hull, as the relaxed fit asks)
    only the clip differs, so the box cells are built once (the same bits as one
    :func:`power_diagram` per domain).
    """
    dom = doms[0]
    if any(tuple(d.bounds) != tuple(dom.bounds) for d in doms[1:]):
        return tuple(power_diagrams(pts, w, (d,))[0] for d in doms)
    n = len(pts)
    if n and (w == w[0]).all():
        # equal weights: the ordinary Voronoi diagram, from the exact engine
        out = []
        for one in doms:
            d = build(pts, one, "delaunay")
            k = frame_exponent(d)
            bufs = buffers(d)
            out.append(
                PowerDiagram(d.sites, d.duplicate_of, one, bufs, d.edges, w, k, d.unresolved)
            )
        return tuple(out)
    e = _frame(pts, dom)
    if e:
        # squared distances and weights past float64's range (a cell at 2**490: its bits
        # moved; areas inf): build the diagram scaled by 2**-e, weights by 4**-e (exact)
        scaled = tuple(one.scaled(-e) for one in doms)
        out = []
        for one, d in zip(
            doms, power_diagrams(np.ldexp(pts, -e), np.ldexp(w, -2 * e), scaled), strict=True
        ):
            coords, ring, poly, geom = buffers(d)
            edges = Edges(np.ldexp(d.edges.coords, e), d.edges.pairs)
            bufs = (np.ldexp(coords, e), ring, poly, geom)
            out.append(PowerDiagram(pts, d.duplicate_of, one, bufs, edges, w, -e, d.unresolved))
        return tuple(out)
    dup = _owners(pts, w)
    active = dup < 0
    x = np.ascontiguousarray(pts[:, 0])
    y = np.ascontiguousarray(pts[:, 1])
    # the kernels get writeable weights, whatever the caller's flag: numba types the flag,
    # and the Voronoi cells hand the cut they share with these kernels (power.box_cell and
    # 7 callees: 7.7 of the 37.5 s vf.power compiled after vf.voronoi) writeable zero
    # weights. PowerDiagram freezes the weights it keeps, so a diagram's weights passed
    # again (the fits) are copied here (n floats, once per diagram)
    ww = w if w.flags.writeable else w.copy()
    box = np.array(dom.bounds, dtype=np.float64)
    indptr, indices, active, suspect = _neighbors(x, y, ww, box, active)
    lost = None
    if suspect is None:
        closed, lengths, own = power_cells(x, y, ww, indptr, indices, box, active)
    else:
        rings = checked_cells(x, y, ww, box, active, indptr, indices, suspect)
        closed, lengths, own = settle(box, *rings)
        # the sites left without a ring that have a cell (exactly): float64 cannot hold it
        lost = lost_sites(x, y, ww, box, active, np.flatnonzero(active & ~(np.diff(lengths) > 0)))
    out = []
    for one in doms:
        bufs, edges = assemble(one, closed, lengths, own, n)
        out.append(PowerDiagram(pts, dup, one, bufs, edges, w, unresolved=lost))
    return tuple(out)


def _frame(pts: np.ndarray, dom: Domain) -> int:
    """0, or ``e`` such that the sites and the domain scaled by ``2**-e`` are about unit size.

    Only past ``2**±POWER_FRAME_EXP``: nearer 1 the bits do not depend on it.
    """
    big = max(float(np.abs(pts).max(initial=0.0)), *(abs(float(v)) for v in dom.bounds))
    return unit_exponent(big, POWER_FRAME_EXP)


def power(points, weights, boundary=None) -> PowerDiagram:
    """Power (Laguerre) diagram of weighted sites, every cell clipped to a domain.

    Cell ``i`` holds the points ``x`` of the domain where ``|x - p_i|^2 - w_i`` is smallest.
    Equal weights give exactly :func:`voroforge.voronoi`'s cells.

    Parameters
    ----------
    points : (n, 2) array_like
        Sites; never modified. Sites at the same coordinates: the heaviest owns the cell (the
        first among equal weights), the others get empty cells and ``duplicate_of``.
    weights : (n,) array_like
        Weights in squared coordinate units (a weight ``r**2`` acts like a circle of radius
        ``r``). Adding one constant to all weights changes nothing.
    boundary : None, (xmin, ymin, xmax, ymax) or shapely Polygon/MultiPolygon, optional
        The domain, as for :func:`voroforge.voronoi`.

    Returns
    -------
    PowerDiagram
        A :class:`~voroforge.Diagram` (cells in input order, possibly empty, with areas,
        centroids, neighbours and unique edges) with ``.weights``.

    Raises
    ------
    ValueError
        Malformed points or weights (shape, NaN/inf), an invalid or empty boundary.

    Notes
    -----
    Neighbours come from Qhull's lower hull of the lifted sites (where it cannot resolve
    them, e.g. clusters far narrower than the box, each cell's vertices are checked against
    the sites nearest in power); the cells are cut in floating point relative to each site
    (unequal weights do not use the exact predicates of :func:`voroforge.voronoi`).
    Collinear sites are handled by a 1D lower hull. In a cluster only a few ulps of its
    coordinates wide a cell can be narrower than float64 holds there: such a site gets an
    empty cell and is listed in ``unresolved`` (the rest still tile the domain).

    Examples
    --------
    >>> import numpy as np, voroforge as vf
    >>> pts = np.random.default_rng(1).random((50, 2))
    >>> d = vf.power(pts, np.linspace(0, 0.01, 50), (0, 0, 1, 1))
    >>> round(float(d.areas.sum()), 12)
    1.0
    """
    pts = as_points(points)
    w = as_weights(weights, len(pts))
    dom = make_domain(boundary, pts)
    return power_diagram(pts, w, dom)


def hessian(d: PowerDiagram, pts: np.ndarray) -> tuple[sp.csc_matrix, np.ndarray]:
    """``dA_i/dw_j`` and its diagonal.

    The graph Laplacian with ``-|edge_ij| / (2 |p_i - p_j|)`` off the diagonal (edges clipped
    to the domain) and the row sums on it.
    """
    coords, pairs = d.edges
    n = len(pts)
    length = np.hypot(*(coords[:, 1] - coords[:, 0]).T)
    a = pairs[:, 0]
    b = pairs[:, 1]
    c = length / (2.0 * np.hypot(*(pts[a] - pts[b]).T))
    off = sp.coo_matrix((c, (a, b)), shape=(n, n)).tocsr()
    off = off + off.T
    deg = np.asarray(off.sum(axis=1)).ravel()
    return (sp.diags(deg) - off).tocsc(), deg


def _seed_empty(pts, w, targets, dom, empty):
    """Weights that let each site in ``empty`` win a little region at its nearest domain point.

    At that point ``q`` site ``i`` beats the best other site ``j`` by a margin that moves
    their power bisector about ``0.1 sqrt(target_i)`` past ``q``: a small cell opens there.
    """
    w = w.copy()
    geom = dom.geometry
    near = shapely.points(pts[empty])
    out = ~shapely.covers(geom, near)
    if out.any():
        edge = shapely.boundary(geom)
        near[out] = shapely.line_interpolate_point(edge, shapely.line_locate_point(edge, near[out]))
    q = shapely.get_coordinates(near)
    for k, i in enumerate(empty.tolist()):
        pw = ((pts - q[k]) ** 2).sum(axis=1) - w
        pw[i] = np.inf
        j = int(np.argmin(pw))
        # beat site j at q by a margin that moves their bisector ~0.1 sqrt(target) past q
        margin = 0.2 * np.sqrt(float(targets[i])) * float(np.hypot(*(pts[i] - pts[j])))
        w[i] = float(((pts[i] - q[k]) ** 2).sum()) - float(pw[j]) + margin
    return w


def shrink_start(pts, dom):
    """Weights whose power cells are the Voronoi cells of the sites shrunk towards the domain.

    With ``c`` inside the domain and ``0 < s <= 1``, ``|x - p_i|^2 - (1 - s) |p_i - c|^2``
    equals ``(1 - 1/s) |x - c|^2 + |x - c - s (p_i - c)|^2 / s``: the power diagram is the
    Voronoi diagram of the points ``c + s (p_i - c)``. Halving ``s`` until all of them lie in
    the domain gives every (distinct) site a cell of positive area, wherever the sites are.
    """
    from shapely.ops import polylabel

    geom = dom.geometry
    parts = shapely.get_parts(geom)
    part = parts[int(np.argmax(shapely.area(parts)))]
    c = np.array(polylabel(part, tolerance=POWER_LABEL_RTOL * np.sqrt(part.area)).coords[0])
    q = pts - c
    s = 1.0
    for _ in range(80):
        z = c + s * q
        if shapely.contains_xy(geom, z[:, 0], z[:, 1]).all():
            break
        s *= 0.5
    return (1.0 - s) * np.einsum("ij,ij->i", q, q)


def fit_weights(pts, targets, dom, w0, tol, max_iter, relax=None):
    """Damped Newton on the concave dual: weights whose power cells have ``targets`` areas.

    Parameters
    ----------
    pts : (n, 2) float64
        Distinct validated sites.
    targets : (n,) float64
        Target areas from :func:`as_targets`.
    dom : Domain
        The domain.
    w0 : (n,) float64
        Starting weights (not modified).
    tol : float
        Largest relative area error to stop at.
    max_iter : int
        Most Newton steps.
    relax : (Domain, float), optional
        ``(hull, eps)``: fit the masses of the density 1 on ``dom`` and ``eps`` on the rest
        of the convex ``hull`` (``targets`` then sum to that density's mass). Its support is
        connected, so the Hessian is never singular (``capacity._gap_continuation``).

    Returns
    -------
    diagram : PowerDiagram
    weights : (n,) float64
    error : float
        Largest relative area error reached.
    iterations : int
        Newton steps taken.
    """
    if relax is not None:
        return _fit_relaxed(pts, targets, dom, w0, tol, max_iter, *relax)
    w = w0.copy()
    d = power_diagram(pts, w, dom)
    areas = d.areas
    if (areas <= 0.0).any() and w.any():
        # the warm start empties a cell: start from the Voronoi diagram instead
        w = np.zeros_like(w)
        d = power_diagram(pts, w, dom)
        areas = d.areas
    for _ in range(10):
        empty = np.flatnonzero(areas <= 0.0)
        if not len(empty):
            break
        w = _seed_empty(pts, w, targets, dom, empty)
        d = power_diagram(pts, w, dom)
        areas = d.areas
    if (areas <= 0.0).any():
        # seeding one cell can empty another (sites sharing their nearest domain point)
        w = shrink_start(pts, dom)
        d = power_diagram(pts, w, dom)
        areas = d.areas
    if (areas <= 0.0).any():
        i = int(np.flatnonzero(areas <= 0.0)[0])
        raise ValueError(
            f"the cell of site {i} stays empty: capacity fitting could not find starting "
            "weights that give every site a cell (move the site closer to the domain)"
        )
    floor = 0.5 * min(float(targets.min()), float(areas.min()))
    err = float(np.max(np.abs(areas - targets) / targets))
    it, alpha = 0, 1.0
    while err > tol and it < max_iter:
        it += 1
        r = targets - areas
        lap, deg = hessian(d, pts)
        ncomp, labels = connected_components(lap, directed=False)
        if ncomp > 1:
            # cells in separate groups (no edge between them inside the domain: their
            # bisectors lie in the gap of a MultiPolygon): the areas do not depend on how
            # the groups' weights differ until a bisector reaches the other side, so the
            # Hessian is singular there; move the neediest group across first
            got = _bridge(pts, w, targets, areas, dom, labels, ncomp, floor)
            if got is None:
                break
            w, d, areas = got
            err = float(np.max(np.abs(areas - targets) / targets))
            continue
        got = _damped_step(partial(_areas, pts, dom), w, lap, deg, r, targets, floor, alpha)
        if got is None:
            break  # no progress possible at float precision
        w, d, areas, taken = got
        alpha = _first_alpha(taken, alpha)
        err = float(np.max(np.abs(areas - targets) / targets))
    return d, w, err, it


def newton_steps(lap, deg, r):
    """Newton's step, then the diagonal (Jacobi) step when Newton's gives no progress.

    The Hessian is shifted by ``POWER_NEWTON_SHIFT`` of each row's own degree (a site a few
    ulps from another has a row ``1e16`` times its neighbours'; one shift for all rows
    would swamp theirs). When rows differ that much, elimination keeps the large entries
    and loses the small ones to rounding: the diagonal step, exact per row, moves each
    near pair's bisector and Newton takes over again.
    """
    shift = POWER_NEWTON_SHIFT * np.maximum(deg, deg.max() * 1e-300)
    step = _solve(lap + sp.diags(shift, format="csc"), r)
    if step is not None:
        yield step
    step = _two_level(lap, r, shift)
    if step is not None:
        yield step
    yield r / np.maximum(deg, np.finfo(float).tiny)


def _solve(a, r):
    """``a^-1 r`` by sparse LU, or None when ``a`` is singular to working precision."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", MatrixRankWarning)
        x = spsolve(a, r)
    return x if np.all(np.isfinite(x)) else None


def _two_level(lap, r, shift):
    """Newton's step solved in two levels when some edges are far stiffer than the rest.

    Sites a few ulps apart give Hessian entries ``1e16`` times the others'. Their groups
    (joined by stiff edges) first move as one site, on the Hessian summed over each group
    (stiff entries cancel there exactly); then each group's stiff Laplacian spreads what is
    left of the residual inside it. Each level is well conditioned, unlike the whole.
    """
    off = sp.triu(-lap, k=1).tocoo()
    if not len(off.data):
        return None
    stiff = off.data > 1e8 * float(np.median(off.data))
    if not stiff.any():
        return None
    n = lap.shape[0]
    a, b, c = off.row[stiff], off.col[stiff], off.data[stiff]
    ls = sp.coo_matrix((c, (a, b)), shape=(n, n)).tocsr()
    ls = ls + ls.T
    m, group = connected_components(ls, directed=False)
    p = sp.csr_matrix((np.ones(n), (np.arange(n), group)), shape=(n, m))
    coarse = (p.T @ lap @ p).tocsc()
    sc = _solve(coarse + sp.diags(p.T @ shift, format="csc"), p.T @ r)
    if sc is None:
        return None
    step = sc[group]
    # what the coarse step leaves, from edge differences (stiff ones are zero exactly)
    d = off.data * (step[off.row] - step[off.col])
    rest = (
        r
        - np.bincount(off.row, weights=d, minlength=n)
        + np.bincount(off.col, weights=d, minlength=n)
    )
    stiff_lap = sp.diags(np.asarray(ls.sum(axis=1)).ravel()) - ls
    fine = _solve(
        (stiff_lap + sp.diags(shift)).tocsc(), np.where(np.bincount(group)[group] > 1, rest, 0.0)
    )
    return None if fine is None else step + fine


def _damped_step(masses, w, lap, deg, r, goal, floor, alpha):
    """The first of :func:`newton_steps`' directions that :func:`_line_search` accepts, or None."""
    norm = float(np.linalg.norm(r))
    for step in newton_steps(lap, deg, r):
        got = _line_search(masses, w, step, goal, floor, norm, alpha)
        if got is not None:
            return got
    return None


def _line_search(masses, w, step, targets, floor, norm, alpha=1.0):
    """Halve ``step`` until the cells keep ``floor`` and the mass error shrinks; or None.

    ``masses(w)`` gives ``(state, masses)`` of weights ``w`` (the diagram and its areas, or
    :func:`_relaxed`'s diagrams and masses); the first try is ``alpha`` of the step. Returns
    ``(w, state, masses, alpha)`` of the step taken.
    """
    for _ in range(40):
        w_try = w + alpha * step
        state, m_try = masses(w_try)
        if m_try.min() >= floor and np.linalg.norm(targets - m_try) <= (1 - alpha / 2) * norm:
            return w_try, state, m_try, alpha
        alpha *= 0.5
    return None


def _first_alpha(taken, tried):
    """The first fraction of the next step to try, from the last one ``tried`` and ``taken``.

    ``POWER_FIT_ALPHA_GROWTH`` x the last taken where it was taken at its first try, else
    the fraction taken. Far from the fit (the relaxed density's stages) Newton's full step
    empties hundreds of cells and steps of 1/8-1/16 are taken step after step: trying the
    full step first cost 3-4 diagrams a step; near the fit full steps are taken, and the
    full step is tried. A step halved before it was taken is tried at that fraction next
    (growing it again cost one diagram a step where each was halved once: a U notch's
    breakout took every round at 1/2 after a full step that emptied cells; 4,000 sites 77
    -> 67 diagrams, ring 36 -> 29).
    """
    return min(1.0, POWER_FIT_ALPHA_GROWTH * taken) if taken == tried else taken


def _areas(pts, dom, w):
    """``masses`` of :func:`_line_search` for the plain fit: the diagram and its areas."""
    d = power_diagram(pts, w, dom)
    return d, d.areas


def _bridge(pts, w, targets, areas, dom, labels, ncomp, floor):
    """Raise the weights of the group of cells short of most area until it gains some.

    ``labels`` are the groups of the cells' edge graph. The group's bisectors with the
    others move by ``dw / (2 |p_i - p_j|)``: the raise doubles from a tiny fraction of the
    domain's squared size until the group's area grows by more than rounding
    (``POWER_BRIDGE_GAIN_RTOL`` of the domain's area), then is halved back while it still
    does, so the front just crosses the gap. When a doubling both crosses and empties a cell
    of another group, the raise is bisected between the two doublings for one that gains
    and keeps every cell. Returns ``(w, diagram, areas)`` or None.
    """
    need = np.bincount(labels, weights=targets - areas, minlength=ncomp)
    g = int(np.argmax(need))
    if not need[g] > 0.0:
        return None
    mask = labels == g
    have = float(areas[mask].sum())
    noise = POWER_BRIDGE_GAIN_RTOL * float(targets.sum())
    x0, y0, x1, y1 = dom.bounds
    dw = 1e-12 * ((x1 - x0) ** 2 + (y1 - y0) ** 2)

    def attempt(dw):
        w_try = w + dw * mask
        d_try = power_diagram(pts, w_try, dom)
        a_try = d_try.areas
        keeps = bool(a_try.min() >= floor)
        return (w_try, d_try, a_try), keeps, keeps and a_try[mask].sum() - have > noise

    best = None
    lo = 0.0
    for _ in range(200):
        got, keeps, gains = attempt(dw)
        if gains:
            best = got
            break
        if not keeps:
            best, dw = _bridge_between(attempt, lo, dw)
            if best is None:
                return None  # a cell of another group empties before this one gains
            break
        lo = dw
        dw *= 2.0
    if best is None:
        return None
    for _ in range(60):  # back to the smallest raise that still gains (within 1%)
        dw *= 0.5
        got, _, gains = attempt(dw)
        if not gains:
            break
        best = got
        if got[2][mask].sum() - have <= 0.01 * need[g]:
            break
    return best


def _bridge_between(attempt, lo, hi):
    """A raise in ``(lo, hi)`` that gains and keeps every cell, by bisection, and itself.

    At ``lo`` no cell empties and the group does not gain; at ``hi`` a cell empties. Returns
    ``(None, hi)`` when none is found within 60 halvings.
    """
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if not lo < mid < hi:
            break
        got, keeps, gains = attempt(mid)
        if gains:
            return got, mid
        if keeps:
            lo = mid
        else:
            hi = mid
    return None, hi


def fit_breakout(pts, targets, dom, hull, w0, rounds, grow):
    """Weights that give every site a cell in ``dom``, by steps on its convex ``hull``.

    A site whose cell lies wholly in a hole of ``dom`` has no area there, and Newton on
    ``dom`` has nothing to move it by. On the hull every cell has area: each round takes one
    damped Newton step on the hull towards the areas ``targets + hole share`` (the part of
    each cell outside ``dom``, so that a cell meeting its target on the hull meets it in
    ``dom``), where a cell still wholly outside ``dom`` asks ``grow`` times its hole share
    (its hull area) instead, so that it reaches ``dom`` in a few rounds, all such cells at
    once. ``w0`` must give every cell area on the hull. Returns ``(w, steps, back)`` once every
    cell has area in ``dom`` (``back``: a round left more cells outside than the one
    before), or None after ``rounds`` rounds or when a step fails.
    """
    masses = partial(_relaxed, pts, dom, hull, 1.0)  # 1.0: the masses are the hull areas
    w = w0.copy()
    (d, dh), mass = masses(w)
    if not (mass > 0.0).all():
        return None
    alpha, last, back = 1.0, len(pts), False
    for it in range(rounds):
        a = d.areas
        out = ~(a > 0.0)
        back = back or bool(out.sum() > last)
        last = int(out.sum())
        if not last:
            return w, it, back
        share = mass - a
        goal = targets + np.where(out, grow * share, share)
        goal *= mass.sum() / goal.sum()
        lap, deg = hessian(dh, pts)
        r = goal - mass
        floor = 0.5 * min(float(goal.min()), float(mass.min()))
        got = _damped_step(masses, w, lap, deg, r, goal, floor, alpha)
        if got is None:
            return None
        w, (d, dh), mass, taken = got
        alpha = _first_alpha(taken, alpha)
    return None


def _relaxed(pts, dom, hull, eps, w):
    """``((diagram on dom, diagram on hull), masses)`` of the relaxed density.

    Density 1 on ``dom`` and ``eps`` on ``hull`` outside it: the masses are
    ``(1 - eps) A_dom + eps A_hull``, the Hessian the same mix of the two Laplacians.
    """
    d, dh = power_diagrams(pts, w, (dom, hull))
    return (d, dh), (1.0 - eps) * d.areas + eps * dh.areas


def _fit_relaxed(pts, targets, dom, w0, tol, max_iter, hull, eps):
    """:func:`fit_weights` for the relaxed density (see its ``relax``); same returns.

    Kitagawa, Merigot and Thibert (2019): on a connected support the damped Newton step,
    halved until every mass keeps ``floor`` and the error shrinks, converges from any
    weights that give every cell mass.
    """
    masses = partial(_relaxed, pts, dom, hull, eps)
    w = w0.copy()
    (d, dh), mass = masses(w)
    if not (mass > 0.0).all():
        return d, w, np.inf, 0
    floor = 0.5 * min(float(targets.min()), float(mass.min()))
    err = float(np.max(np.abs(mass - targets) / targets))
    it, alpha = 0, 1.0
    while err > tol and it < max_iter:
        it += 1
        r = targets - mass
        lap, deg = hessian(d, pts)
        laph, degh = hessian(dh, pts)
        lap = (1.0 - eps) * lap + eps * laph
        deg = (1.0 - eps) * deg + eps * degh
        got = _damped_step(masses, w, lap, deg, r, targets, floor, alpha)
        if got is None:
            break
        w, (d, dh), mass, taken = got
        alpha = _first_alpha(taken, alpha)
        err = float(np.max(np.abs(mass - targets) / targets))
    return d, w, err, it
