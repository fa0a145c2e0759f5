"""Starting weights for a MultiPolygon whose parts lie far apart: :func:`parts_start`.

Across a gap ``G`` the power cells of one part see another's only through a cell in both,
and Newton's Hessian is all but singular there (two squares 1,000 apart with 400 sites in
one: no fit). Seen from far, a part is a point: which sites serve which part is the discrete
transport of the sites' targets to the parts' areas at cost ``|p_i - c_k|^2`` (``c_k`` the
part's centroid; its basic solution splits at most ``K - 1`` sites between parts). Each
part is then fitted alone with the sites it serves, moved onto them: on a part moved by
``-s`` the power diagram of weights ``v`` is the one of weights ``v - 2 s . p`` on the
part itself (``|x - p|^2 - w = |x - s - p|^2 - (w + 2 s . p) + (2 s . (x - s) + |s|^2)``,
the last term the same for every site), exactly. One constant per part is left free: a
site split between two parts ties theirs; a part tied to none gets the constant halfway
between where its sites would reach into the other parts and where theirs would reach
into it (sampled at the part's points). The weights are then polished on the whole domain.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
import shapely
from scipy.optimize import linprog
from scipy.spatial import cKDTree

from ..config import (
    POWER_FIT_PARTS_CANCELS,
    POWER_FIT_PARTS_FAR,
    POWER_FIT_PARTS_SAMPLES,
    POWER_FIT_PARTS_SHARE,
)
from .domain import make_domain, shifted

__all__ = ["far_parts", "parts_start", "straddle_limit", "transport", "weights_limit"]


def far_parts(geom) -> bool:
    """Whether ``geom`` has several parts, each two farther apart than their sizes."""
    parts = shapely.get_parts(geom)
    if len(parts) < 2:
        return False
    b = shapely.bounds(parts)
    size = np.hypot(b[:, 2] - b[:, 0], b[:, 3] - b[:, 1])
    for k in range(len(parts)):
        gap = shapely.distance(parts[k], parts[k + 1 :])
        if len(gap) and not (gap > POWER_FIT_PARTS_FAR * np.maximum(size[k], size[k + 1 :])).all():
            return False
    return True


def parts_start(pts, t, dom, tol, max_iter, fit):
    """Weights that fit each far part of ``dom`` alone, joined into one set.

    Parameters
    ----------
    pts : (n, 2) float64
        Distinct sites.
    t : (n,) float64
        Targets summing to ``dom``'s area.
    dom : Domain
        A MultiPolygon domain.
    tol : float
        Each part's fit's tolerance.
    max_iter : int
        Most Newton steps per part.
    fit : callable
        ``fit(pts, targets, dom, w0, tol, max_iter) -> (d, w, err, steps)`` for a one-part
        domain (``capacity``'s own fit).

    Returns
    -------
    weights : (n,) float64, or None when a part's fit does not reach ``tol``
    steps : int
        Newton steps taken by the parts' fits.
    """
    parts = shapely.get_parts(dom.geometry)
    k = len(parts)
    areas = np.array([make_domain(p, pts).area for p in parts])
    cent = shapely.get_coordinates(shapely.centroid(parts))
    share = transport(pts, t, cent, areas)
    if share is None:
        return None, 0
    serves = share > POWER_FIT_PARTS_SHARE * t[:, None]
    w = np.zeros(len(pts))
    own = [None] * k  # each part's weights for the sites it serves, its constant not yet set
    steps = 0
    for j in range(k):
        idx = np.flatnonzero(serves[:, j])
        tj = share[idx, j] * (areas[j] / share[idx, j].sum())
        sub = make_domain(parts[j], pts)
        # the part moved onto the median of its sites (a mean is pulled a gap away by a
        # site split in from another part)
        s = _exact_shift(parts[j], cent[j] - _median(pts[idx], tj))
        v, err, it = np.zeros(1), 0.0, 0
        if len(idx) > 1:
            try:
                _, v, err, it = fit(
                    pts[idx], tj, shifted(sub, s), np.zeros(len(idx)), tol, max_iter
                )
            except ValueError:  # a cell that cannot be opened: the caller's other starts
                return None, steps
        steps += it
        if not err <= tol:
            return None, steps
        own[j] = (idx, v - 2.0 * (pts[idx] @ s))
    lam = _constants(pts, parts, serves, own)
    for j in range(k):
        idx, v = own[j]
        w[idx] = v + lam[j]
    return w, steps


def straddle_limit(pts, t, dom) -> tuple[float, float]:
    """``(spread, limit)``: the weights' spread a fit across ``dom``'s far parts needs.

    The sites serving part ``k`` (see :func:`parts_start`) need weights about their spread
    of ``|p_i - c_k|^2`` apart: ``2 G`` times their extent where all lie on one side of the
    gap ``G``, ``G^2`` where one must straddle it from the other side. Rounded to ``u`` (the
    spread's ulp), a bisector of sites ``delta`` apart moves by ``u / (2 delta)``, a cell of
    area ``a`` (perimeter ``4 sqrt(a)``) by ``2 u / (delta sqrt(a))`` relative; ``limit`` is
    that at the median cell.
    """
    parts = shapely.get_parts(dom.geometry)
    areas = np.array([make_domain(p, pts).area for p in parts])
    cent = shapely.get_coordinates(shapely.centroid(parts))
    share = transport(pts, t, cent, areas)
    if share is None or len(pts) < 2:
        return 0.0, 0.0
    serves = share > POWER_FIT_PARTS_SHARE * t[:, None]
    spread = 0.0
    for j in range(len(parts)):
        r2 = ((pts[serves[:, j]] - cent[j]) ** 2).sum(axis=1)
        spread = max(spread, float(r2.max() - r2.min()))
    dist = cKDTree(pts).query(pts, k=2)[0][:, 1]
    return spread, float(2.0 * np.spacing(spread) / np.median(dist * np.sqrt(t)))


def transport(pts, t, cent, areas):
    """``(n, k)`` masses of the sites' targets sent to the parts, or None.

    The costs ``|p_i - c_k|^2`` less each row's and column's own terms (the constraints fix
    the row and column sums, so those do not change the optimum): ``-2 c_k . p_i``. Two
    parts: the sites sorted along ``c_1 - c_0``, part 1 filled from the top, exactly (one
    site split). More: dual simplex (a basic solution, at most ``k - 1`` sites split) on the
    costs scaled to at most 1, whose tolerance (1e-7) can hide differences between sites of
    one cluster across a large gap: its answer is then checked exactly and mended
    (:func:`_exact_optimum`).
    """
    n, k = len(pts), len(cent)
    want = areas * (t.sum() / areas.sum())
    dc = cent - cent[0]
    if k == 2:
        order = np.argsort(-(pts @ dc[1]), kind="stable")
        before = np.cumsum(t[order]) - t[order]
        got = np.clip(want[1] - before, 0.0, t[order])
        share = np.zeros((n, 2))
        share[order, 1] = got
        share[:, 0] = t - share[:, 1]
        return share
    cost = -2.0 * (pts - pts.mean(axis=0)) @ dc.T
    top = float(np.abs(cost).max())
    cost = cost / top if top > 0.0 else cost
    v = np.arange(n * k)
    last = v % k < k - 1
    rows = np.r_[v // k, n + (v % k)[last]]
    cols = np.r_[v, v[last]]
    a_eq = sp.csr_matrix((np.ones(len(rows)), (rows, cols)), shape=(n + k - 1, n * k))
    scale = float(t.sum())
    res = linprog(
        cost.ravel(),
        A_eq=a_eq,
        b_eq=np.r_[t, want[:-1]] / scale,
        bounds=(0.0, None),
        method="highs-ds",
    )
    if res.status != 0:
        return None
    return _exact_optimum(pts, t, cent, np.maximum(res.x.reshape(n, k), 0.0) * scale)


def _exact_optimum(pts, t, cent, share):
    """``share`` moved along negative cycles until it is exactly optimal.

    A transport is optimal when some part constants ``psi`` make every site's parts
    cheapest for it: ``psi_b - psi_a <= D_ab``, ``D_ab`` the least exact cost change
    ``-2 p_i . (c_b - c_a)`` over the sites ``i`` that send to ``a``. Such ``psi`` exist
    unless the graph of the ``D_ab`` has a negative cycle; along one, each arc's site sends
    the cycle's least share on to the next part (the column and row sums kept) and the cost
    falls. At most ``POWER_FIT_PARTS_CANCELS`` cycles (then the best transport so far).
    """
    share = share.copy()
    for _ in range(POWER_FIT_PARTS_CANCELS):
        cycle = _negative_cycle(pts, t, cent, share)
        if cycle is None:
            break
        amount = min(float(share[i, a]) for a, _, i in cycle)
        for a, b, i in cycle:
            share[i, b] += amount
            share[i, a] = max(0.0, float(share[i, a]) - amount)
    return share


def _negative_cycle(pts, t, cent, share):
    """``[(a, b, i), ...]``: a cycle of parts whose exact ``D_ab`` (site ``i``) sum below 0.

    ``D_ab`` is found in floats and confirmed among the sites within its rounding bound in
    integers (every double a multiple of ``2**-1074``); Bellman and Ford's relaxation on
    the ``k`` parts finds the cycle.
    """
    k = len(cent)
    serves = share > POWER_FIT_PARTS_SHARE * t[:, None]
    big = np.full((k, k), None, dtype=object)  # exact D_ab, scaled to integers
    site = np.full((k, k), -1)
    for a in range(k):
        ia = np.flatnonzero(serves[:, a])
        if not len(ia):
            continue
        for b in range(k):
            if b == a:
                continue
            d = cent[b] - cent[a]  # only its sign pattern and size feed the filter
            f = -2.0 * (pts[ia] @ d)
            bound = 1e-12 * (2.0 * (np.abs(pts[ia]) @ (np.abs(cent[a]) + np.abs(cent[b]))))
            near = ia[f - bound <= float((f + bound).min())]
            vals = [_exact_change(pts[i], cent[a], cent[b]) for i in near]
            m = min(range(len(vals)), key=vals.__getitem__)
            big[a, b], site[a, b] = vals[m], int(near[m])
    dist = [0] * k
    parent = [-1] * k
    changed = -1
    for _ in range(k):
        changed = -1
        for a in range(k):
            for b in range(k):
                if big[a, b] is not None and dist[a] + big[a, b] < dist[b]:
                    dist[b] = dist[a] + big[a, b]
                    parent[b] = a
                    changed = b
        if changed < 0:
            return None
    v = changed
    for _ in range(k):  # into the cycle
        v = parent[v]
    cycle, u = [], v
    while True:
        a = parent[u]
        cycle.append((a, u, int(site[a, u])))
        u = a
        if u == v:
            break
    return cycle[::-1]


def _exact_change(p, ca, cb) -> int:
    """``-2 p . (cb - ca)`` exactly, in units of ``2**-2148`` (a product of two doubles)."""
    total = 0
    for x, y, z in zip(p, ca, cb, strict=True):
        fx, fy, fz = (_units(q) for q in (x, y, z))
        total -= 2 * fx * (fz - fy)
    return total


def _units(q) -> int:
    """The double ``q`` in units of ``2**-1074`` (exact: every double is a multiple)."""
    num, den = float(q).as_integer_ratio()
    return num * (2**1074 // den)


def _median(p, wt):
    """The ``wt``-weighted median of ``p``'s coordinates, each axis apart."""
    out = np.zeros(2)
    for a in range(2):
        order = np.argsort(p[:, a], kind="stable")
        c = np.cumsum(wt[order])
        out[a] = p[order[min(int(np.searchsorted(c, 0.5 * c[-1])), len(c) - 1)], a]
    return out


def _exact_shift(part, s):
    """``s`` rounded to a multiple of the ulp of ``part``'s largest coordinate.

    ``x - s`` is then exact for every coordinate ``x`` of the part (both multiples of that
    ulp, the difference no larger than they are), so the moved part is the part moved.
    """
    big = float(np.abs(shapely.get_coordinates(part)).max())
    u = float(np.spacing(big)) if big > 0.0 else 0.0
    if u == 0.0:
        return np.asarray(s, dtype=np.float64)
    return np.round(np.asarray(s, dtype=np.float64) / u) * u


def _constants(pts, parts, serves, own):
    """Each part's weight constant: split sites tie parts; others sit between their bounds."""
    k = len(parts)
    lam = np.full(k, np.nan)
    for root in range(k):
        if not np.isnan(lam[root]):
            continue
        lam[root] = 0.0 if root == 0 else _between(pts, parts, serves, own, lam, root)
        queue = [root]
        while queue:  # the parts tied to this one through sites that serve both
            a = queue.pop()
            ia, va = own[a]
            for b in range(k):
                if not np.isnan(lam[b]):
                    continue
                ib, vb = own[b]
                both = np.intersect1d(ia, ib)
                if len(both):
                    i = both[0]
                    lam[b] = va[np.searchsorted(ia, i)] + lam[a] - vb[np.searchsorted(ib, i)]
                    queue.append(b)
    return lam


def _between(pts, parts, serves, own, lam, j):
    """Part ``j``'s constant, halfway between where its cells and the set parts' cross.

    ``g_i(x) = w_i - |x - p_i|^2`` is largest for the site that owns ``x``. Part ``j``'s
    sites must lose on the set parts and win on their own: its constant lies in
    ``(lo, hi)``, each end sampled at the parts' points.
    """
    ij, vj = own[j]
    lo, hi = -np.inf, np.inf
    for m in range(len(parts)):
        if m == j or np.isnan(lam[m]):
            continue
        im, vm = own[m]
        xm, xj = _samples(parts[m]), _samples(parts[j])
        # j's sites lose on part m, m's sites lose on part j
        hi = min(hi, float((_top(xm, pts[im], vm + lam[m]) - _top(xm, pts[ij], vj)).min()))
        lo = max(lo, float((_top(xj, pts[im], vm + lam[m]) - _top(xj, pts[ij], vj)).max()))
    if not (np.isfinite(lo) and np.isfinite(hi)):
        return lo if np.isfinite(lo) else (hi if np.isfinite(hi) else 0.0)
    # 0 where it lies in the middle half: the ends are each about the gap squared, and
    # their midpoint keeps only their rounding (weights 1e2 off at a gap of 1e9)
    q = 0.25 * (hi - lo)
    return float(np.clip(0.0, lo + q, hi - q))


def _samples(part):
    """A grid of points of ``part`` and its vertices."""
    x0, y0, x1, y1 = part.bounds
    g = np.linspace(0.0, 1.0, POWER_FIT_PARTS_SAMPLES)
    gx, gy = np.meshgrid(x0 + g * (x1 - x0), y0 + g * (y1 - y0))
    q = np.column_stack([gx.ravel(), gy.ravel()])
    q = q[shapely.intersects_xy(part, q[:, 0], q[:, 1])]
    return np.vstack([q, shapely.get_coordinates(part)])


def _top(x, p, w):
    """``max_i (w_i - |x - p_i|^2)`` at each point of ``x`` (in chunks of about 1e6 pairs)."""
    out = np.zeros(len(x))
    step = max(1, 1_000_000 // max(1, len(p)))
    for a in range(0, len(x), step):
        q = x[a : a + step]
        out[a : a + step] = (w[None, :] - ((q[:, None, :] - p[None, :, :]) ** 2).sum(axis=2)).max(
            axis=1
        )
    return out


def weights_limit(pts, w, d) -> float:
    """The relative area error that rounding the weights ``w`` alone can cause.

    A weight is held to ``u``, the ulp of the largest ``|w|``; the bisector of sites
    ``delta`` apart then moves by ``u / (2 delta)``, and a cell's area by its perimeter
    times that. A cell that must straddle the gap ``G`` between far parts needs weights
    about ``G^2`` apart from its neighbours' on the other part (two squares 1e6 apart with
    sites in both: ``u`` 1.2e-4, cells of 40 sites off by 1%). Returns the largest such
    error over the cells of ``d`` (0 for a single site).
    """
    if len(pts) < 2:
        return 0.0
    u = float(np.spacing(np.abs(w).max()))
    dist = cKDTree(pts).query(pts, k=2)[0][:, 1]
    cells = np.asarray(d.cells, dtype=object)
    areas = np.asarray(d.areas)
    keep = areas > 0.0
    per = shapely.length(cells[keep])
    return float(np.max(per * u / (2.0 * dist[keep] * areas[keep]), initial=0.0))
