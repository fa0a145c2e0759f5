"""Point queries on a set of sites: nearest site (:func:`locate`) and Sibson interpolation.

:func:`locate` answers "which cell contains this point" for many points at once with a
KD-tree (scipy's ``cKDTree``), and breaks ties between equidistant sites towards the lowest
index, so the answer is deterministic. :func:`natural_neighbor` computes Sibson's
natural-neighbour interpolant from the Bowyer-Watson cavity of each query point in the
Delaunay triangulation (see :mod:`voroforge.kernels.natural`), never by rebuilding diagrams.
"""

from __future__ import annotations

import weakref

import numpy as np
from scipy.spatial import cKDTree

from ..config import (
    GRADIENT_FIT_FLOOR,
    GRADIENT_FIT_RTOL,
    LOCATE_FAR,
    LOCATE_FAR_ULPS,
    LOCATE_ROUND_RTOL,
    LOCATE_TIE_ATOL,
    LOCATE_TIE_RTOL,
    POWER_LOCATE_ULPS,
    POWER_TIE_RTOL,
)
from ..kernels.natural import INSIDE, sibson
from .delaunay import delaunay
from .inputs import as_points, as_query, as_values, duplicate_map, working_frame
from .locate3d import lifted_sites, nearest_exact, nearest_torus_exact

_EPS = float(np.finfo(float).eps)


class _Locator:
    """A KD-tree over the distinct sites (first occurrences), optionally on a torus."""

    def __init__(self, sites: np.ndarray, duplicate_of: np.ndarray, box=None):
        self.owners = np.flatnonzero(duplicate_of < 0)
        self.box = box
        pts = sites[self.owners]
        # squared distances must stay normal doubles: at extreme scales (1e-300, 1e300) work
        # on everything scaled by a power of two, which is exact and changes no comparison
        self.k = working_frame(pts if box is None else np.vstack((pts, np.reshape(box, (2, 2)))))[1]
        if self.k:
            pts = np.ldexp(pts, self.k)
            box = None if box is None else np.ldexp(np.asarray(box, dtype=np.float64), self.k)
        if box is None:
            self.origin = np.zeros(2)
            self.size = None
            self.tree = cKDTree(pts)
        else:
            self.origin = np.array(box[:2], dtype=np.float64)
            self.size = np.array([box[2] - box[0], box[3] - box[1]], dtype=np.float64)
            rel = self._wrap(pts)
            self.tree = cKDTree(rel, boxsize=self.size)
        self.pts = pts
        self.user_pts = sites[self.owners]  # unscaled: exact comparisons in the user frame

    def _wrap(self, xy: np.ndarray) -> np.ndarray:
        rel = np.mod(xy - self.origin, self.size)
        rel[rel >= self.size] = 0.0  # np.mod can round up to the period itself
        return rel

    def _d2(self, q: np.ndarray, cand: np.ndarray) -> np.ndarray:
        """Squared distances ``dx*dx + dy*dy`` from ``q (m, 2)`` to sites ``cand (m, k)``."""
        diff = q[:, None, :] - self.pts[cand]
        if self.size is not None:
            diff = np.abs(diff) % self.size
            diff = np.minimum(diff, self.size - diff)
        return diff[..., 0] * diff[..., 0] + diff[..., 1] * diff[..., 1]

    def _torus_err(self, q: np.ndarray, cand: np.ndarray, d2: np.ndarray) -> np.ndarray:
        """A bound on the rounding of :meth:`_d2` on the torus, per candidate ``(m, k)``.

        ``|q - s|`` rounds by half an ulp of itself, ``np.mod`` is exact and ``size - d`` rounds
        by half an ulp of the period: each minimum-image component is off by at most
        ``t = eps (|q - s| + size)``, so its square by ``2 d t + t^2``; the squares and their
        sum round by ``eps d2`` more. Twice that is the bound.
        """
        raw = np.abs(q[:, None, :] - self.pts[cand])
        t = _EPS * (raw + self.size)
        comp = np.sqrt(d2)[..., None]  # each component is at most the distance
        return 2.0 * (((2.0 * comp + t) * t).sum(axis=2) + 2.0 * _EPS * d2)

    def _torus_pick(self, q: np.ndarray, cand: np.ndarray, d2: np.ndarray) -> int:
        """Lowest index among the exactly nearest of ``cand`` (``d2``: their float ``_d2``)."""
        err = self._torus_err(q[None, :], cand[None, :], d2[None, :])[0]
        at = int(np.argmin(d2))
        close = cand[d2 - err <= d2[at] + err[at]]
        if len(close) == 1:
            return int(close[0])
        return nearest_torus_exact(q, close, self.pts, None, self.size)

    def _settle(self, q, tq, rows, out, k):
        """Lowest index among the exactly nearest sites for ``rows``, looking at ``k``."""
        npts = len(self.pts)
        k = min(k, npts)
        _, cand = self.tree.query(tq[rows], k=k)
        cand = cand.reshape(len(rows), k)
        d2 = self._d2(q[rows], cand)
        best = d2.min(axis=1)
        tied = d2 == best[:, None]
        rank = np.where(tied, self.owners[cand], np.iinfo(np.int64).max)
        out[rows] = rank.min(axis=1)
        slack = 0.0
        if self.size is None:
            # float distances within their rounding of the best: decided exactly
            close = d2 <= best[:, None] * (1.0 + LOCATE_ROUND_RTOL)
            for r in np.flatnonzero(close.sum(axis=1) > 1):
                out[rows[r]] = self.owners[nearest_exact(q[rows[r]], cand[r][close[r]], self.pts)]
        else:
            # on the torus a component near the period rounds by an ulp of the period, not
            # of itself: candidates within the proven bound of the best are decided exactly
            err = self._torus_err(q[rows], cand, d2)
            at = np.argmin(d2, axis=1)
            reach = (best + err[np.arange(len(rows)), at])[:, None]
            close = d2 - err <= reach
            for r in np.flatnonzero(close.sum(axis=1) > 1):
                pick = nearest_torus_exact(q[rows[r]], cand[r][close[r]], self.pts, None, self.size)
                out[rows[r]] = self.owners[pick]
            slack = 2.0 * err.max(axis=1)
        if k == npts:
            return rows[:0], best[:0]
        # a candidate this close to the best one may hide further ties beyond the k-th
        again = d2[:, -1] <= best * (1.0 + LOCATE_TIE_RTOL) + LOCATE_TIE_ATOL + slack
        return rows[again], best[again]

    def _far(self, q: np.ndarray) -> np.ndarray:
        """Nearest sites of queries (user frame) whose squared distances would overflow.

        ``|q - s|^2 = |q|^2 - 2 q.s + |s|^2``: the site minimising ``|s|^2 - 2 q.s`` wins.
        With the sites in the locator's frame (``P = s 2**k``) and ``q = u 2**e``, ``|u|``
        about 1 (exact), that is ``g = |P|^2 2**-(k + e) - 2 u.P``: nothing overflows, even
        where ``q 2**k`` would (sites 1e-100 apart, a query at 1e300). Values of ``g`` within
        their rounding of the least are compared exactly; ties go to the lowest index.
        """
        out = np.zeros(len(q), dtype=np.int64)
        pp = np.einsum("ij,ij->i", self.pts, self.pts)
        norm = np.sqrt(pp)
        step = max(1, 4_000_000 // max(len(self.pts), 1))
        for a in range(0, len(q), step):
            rows = q[a : a + step]
            e = np.frexp(np.abs(rows).max(axis=1))[1]
            u = np.ldexp(rows, -e[:, None])
            with np.errstate(under="ignore"):
                g = np.ldexp(pp[None, :], -(self.k + e)[:, None]) - 2.0 * (u @ self.pts.T)
                bound = (
                    LOCATE_FAR_ULPS
                    * _EPS
                    * (
                        np.abs(g)
                        + np.ldexp(pp[None, :], -(self.k + e)[:, None])
                        + 2.0 * norm[None, :]
                    )
                )
            best = np.argmin(g, axis=1)
            for r in range(len(rows)):
                close = np.flatnonzero(g[r] <= g[r, best[r]] + bound[r, best[r]] + bound[r])
                if len(close) > 1:
                    best[r] = nearest_exact(rows[r], close, self.user_pts)
            out[a : a + step] = self.owners[best]
        return out

    def query(self, q: np.ndarray) -> np.ndarray:
        if self.size is None and len(self.pts):
            # queries beyond ~1e150 of the sites, or beyond the double range once scaled
            # into the sites' frame: their squared distances overflow
            with np.errstate(over="ignore"):
                qs = np.ldexp(q, self.k) if self.k else q
                centre = 0.5 * (self.pts.min(axis=0) + self.pts.max(axis=0))
                far = ~np.isfinite(qs).all(axis=1) | (np.abs(qs - centre) > LOCATE_FAR).any(axis=1)
            if far.any():
                out = np.zeros(len(q), dtype=np.int64)
                out[far] = self._far(q[far])
                near = np.flatnonzero(~far)
                out[near] = self.query_near(qs[near]) if len(near) else out[near]
                return out
            return self.query_near(qs)
        return self.query_near(np.ldexp(q, self.k) if self.k else q)

    def query_near(self, q: np.ndarray) -> np.ndarray:
        """:meth:`query` for queries whose squared distances to the sites stay finite."""
        tq = q if self.size is None else self._wrap(q)
        out = np.zeros(len(q), dtype=np.int64)
        rows = np.arange(len(q))
        for k in (2, 16):
            rows, best = self._settle(q, tq, rows, out, k)
            if not len(rows):
                return out
        # more than 16 nearly equidistant sites: settle exhaustively
        radius = np.sqrt(best) * (1.0 + LOCATE_TIE_RTOL) + LOCATE_TIE_ATOL
        if self.size is not None:  # on the torus rounding is absolute (ulps of the period)
            reach = np.abs(q[rows] - self.origin).max(axis=1) + float(self.size.max())
            radius = radius + 8.0 * _EPS * reach
        lists = self.tree.query_ball_point(tq[rows], radius)
        for row, members in zip(rows, lists, strict=True):
            members = np.asarray(members, dtype=np.int64)
            dd = self._d2(q[row : row + 1], members[None, :])[0]
            if self.size is None:
                near = members[dd <= dd.min() * (1.0 + LOCATE_ROUND_RTOL)]
                out[row] = self.owners[nearest_exact(q[row], near, self.pts)]
            else:
                out[row] = self.owners[self._torus_pick(q[row], members, dd)]
        return out


_CACHE: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def _nearest(locator: _Locator, xy):
    q, single = as_query(xy)
    if len(locator.pts) == 0:
        raise ValueError("cannot locate points without sites")
    out = locator.query(q) if len(q) else np.zeros(0, dtype=np.int64)
    return int(out[0]) if single else out.astype(np.int64)


def locate(points, xy) -> np.ndarray | int:
    """Index of the nearest site to each query point (the Voronoi cell containing it).

    Parameters
    ----------
    points : (n, 2) array_like
        Sites. Duplicates are allowed: the first occurrence answers for all copies.
    xy : (2,) or (m, 2) array_like
        Query points, anywhere in the plane.

    Returns
    -------
    int or (m,) int64
        Index into ``points`` of the nearest site by exact distance: sites whose float64
        squared distances are within rounding of the nearest are compared in rationals, and
        exact ties go to the lowest index; on a periodic diagram the same with
        minimum-image distances (rationals modulo the period).

    Raises
    ------
    ValueError
        Malformed ``points`` or ``xy``, or no sites.

    Examples
    --------
    >>> import voroforge as vf
    >>> vf.locate([[0, 0], [2, 0]], [[0.4, 1.0], [1.0, 0.0], [5.0, 5.0]])
    array([0, 0, 1])
    """
    pts = as_points(points)
    dup = np.full(len(pts), -1, dtype=np.int64)
    if len(pts):
        dup = duplicate_map(pts)[0]
    return _nearest(_Locator(pts, dup), xy)


def locate_in_diagram(diagram, xy) -> np.ndarray | int:
    """Nearest site of ``diagram`` for each query point; see :meth:`Diagram.locate`."""
    loc = _CACHE.get(diagram)
    if loc is None:
        box = diagram.bounds if getattr(diagram, "periodic", False) else None
        loc = _Locator(np.asarray(diagram.sites), np.asarray(diagram.duplicate_of), box)
        _CACHE[diagram] = loc
    return _nearest(loc, xy)


def locate_power(diagram, xy) -> np.ndarray | int:
    """Power diagram locate (see :meth:`voroforge.engine.power.PowerDiagram.locate`)."""
    q, single = as_query(xy)
    owners = np.flatnonzero(diagram.duplicate_of < 0)
    if not len(owners):
        raise ValueError("the diagram has no sites to locate")
    w = diagram.weights[owners]
    if (w == w[0]).all():
        # equal weights: the Voronoi diagram's exact locate (far queries included)
        out = np.atleast_1d(locate_in_diagram(diagram, q))
        return int(out[0]) if single else out
    user_sites = diagram.sites[owners]
    user_w = diagram.weights[owners]
    # one power-of-two frame (exact) where squares of queries, sites and weights are
    # finite: a query at 1e300 overflowed and cKDTree answered with its sentinel
    big = max(float(np.abs(q).max(initial=0.0)), float(np.abs(user_sites).max()))
    big = max(big, float(np.sqrt(np.abs(w).max())))
    e = -int(np.frexp(big)[1]) if big > 0.0 else 0
    qs, sites, w = np.ldexp(q, e), np.ldexp(user_sites, e), np.ldexp(w, 2 * e)
    top = float(w.max())
    pts, lifted, _ = lifted_sites(sites, qs, w)
    tree = cKDTree(pts)
    m = len(owners)
    out = np.zeros(len(q), dtype=np.int64)
    rows = np.arange(len(q))
    for k in (min(4, m), min(32, m), m):
        # chunks keep the (rows, k) candidate arrays small when every site is needed
        step = max(1, (1 << 22) // k)
        again = []
        for lo in range(0, len(rows), step):
            r = rows[lo : lo + step]
            dist, idx = tree.query(lifted[r], k=k)
            dist = dist.reshape(len(r), k)
            idx = idx.reshape(len(r), k)
            diff = qs[r, None, :] - sites[idx]
            d2 = diff[..., 0] * diff[..., 0] + diff[..., 1] * diff[..., 1]
            pd = d2 - w[idx]
            best = pd.min(axis=1)
            rank = np.where(pd == best[:, None], owners[idx], np.iinfo(np.int64).max)
            out[r] = rank.min(axis=1)
            # power distances within their rounding of the best: decided exactly
            err = POWER_LOCATE_ULPS * _EPS * (d2 + np.abs(w[idx]))
            at = np.argmin(pd, axis=1)
            close = pd <= (best + err[np.arange(len(r)), at])[:, None] + err
            for j in np.flatnonzero(close.sum(axis=1) > 1):
                cand = idx[j][close[j]]
                pick = nearest_exact(q[r[j]], cand, user_sites, user_w)
                out[r[j]] = owners[pick]
            if k < m:
                # a site past the k-th could tie after rounding: look further for those
                slack = POWER_TIE_RTOL * (np.abs(best) + abs(top))
                near = dist[:, -1] ** 2 <= (best + top) + slack
                again.append(r[near])
        rows = np.concatenate(again) if again else rows[:0]
        if not len(rows):
            break
    return int(out[0]) if single else out


def _two_ring(tri) -> tuple[np.ndarray, np.ndarray]:
    """CSR of each point's Delaunay neighbours and their neighbours (itself excluded)."""
    from scipy.sparse import csr_matrix

    n = len(tri.points)
    indptr, indices = tri.neighbors
    adj = csr_matrix((np.ones(len(indices)), indices, indptr), shape=(n, n))
    ring = (adj + adj @ adj).tocsr()
    ring.setdiag(0)
    ring.eliminate_zeros()
    ring.sort_indices()
    return ring.indptr.astype(np.int64), ring.indices.astype(np.int64)


def _fit(rows, w, rhs, owner, n):
    """Per-site weighted least squares ``rows @ x ~ rhs``; returns ``(x, ok)``."""
    wr = rows * w[:, None]
    normal = np.zeros((n, rows.shape[1], rows.shape[1]))
    np.add.at(normal, owner, wr[:, :, None] * rows[:, None, :])
    right = np.zeros((n, rows.shape[1], rhs.shape[1]))
    np.add.at(right, owner, wr[:, :, None] * rhs[:, None, :])
    eig = np.linalg.eigvalsh(normal)
    ok = eig[:, 0] > GRADIENT_FIT_RTOL * np.maximum(eig[:, -1], GRADIENT_FIT_FLOOR)
    x = np.zeros_like(right)
    if ok.any():
        x[ok] = np.linalg.solve(normal[ok], right[ok])
    return x, ok


def estimate_gradients(tri, values: np.ndarray, pts: np.ndarray | None = None) -> np.ndarray:
    """Gradients of the data at the sites from local quadratic least squares.

    For each site a quadratic through its value is fitted to the values at its Delaunay
    neighbours and their neighbours (weights ``1 / distance**2``); where that is
    ill-posed (a site with too few neighbours) a plane through the first ring is fitted
    instead. Exact for quadratic data wherever the quadratic fit is used.

    Parameters
    ----------
    tri : Triangulation
    values : (n, k) float64
    pts : (n, 2) float64, optional
        The sites in the frame the gradients are wanted in (``tri.points`` scaled by a power
        of two, or moved: :func:`natural_neighbor`'s working frame); default ``tri.points``.

    Returns
    -------
    (n, k, 2) float64
        Zero for duplicates and where neither fit is possible.
    """
    pts = np.asarray(tri.points if pts is None else pts)
    n, k = values.shape
    grads = np.zeros((n, k, 2))
    # each field fitted scaled down by a power of two to a largest |value| in [0.5, 1)
    # (exact): differences of values near +-8e307 and the normal equations overflowed
    # (checker12 F7); small values are left as they are
    vexp = np.maximum(np.frexp(np.abs(values).max(axis=0, initial=0.0))[1], 0)
    values = np.ldexp(values, -vexp)
    indptr, nbr = _two_ring(tri)
    owner = np.repeat(np.arange(n), np.diff(indptr))
    if not len(nbr):
        return grads
    # each site's offsets scaled by a power of two to unit size (exact): their squares and
    # fourth powers overflowed past ~1e155 and vanished below ~1e-155 (checker9 F2), and a
    # quadratic in 2**-e d is a quadratic in d, so the fit stays exact
    pre = 1 if np.abs(pts).max(initial=0.0) >= 2.0**1023 else 0  # differences stay finite
    d = np.ldexp(pts[nbr], -pre) - np.ldexp(pts[owner], -pre)
    reach = np.zeros(n)
    np.maximum.at(reach, owner, np.abs(d).max(axis=1))
    e = np.frexp(reach)[1]  # 0 where all offsets are 0
    d = np.ldexp(d, -e[owner][:, None])
    white = _whitening(d, owner, n)
    u = np.einsum("mij,mj->mi", white[owner], d)
    uu = (u * u).sum(1)
    rows = np.column_stack((u, 0.5 * u[:, 0] ** 2, u[:, 0] * u[:, 1], 0.5 * u[:, 1] ** 2))
    rhs = values[nbr] - values[owner]
    x, ok = _fit(rows, 1.0 / uu, rhs, owner, n)
    # f(p + d) ~ f(p) + x . (W d): the gradient in the user's frame is W^T x
    grads[ok] = np.einsum("nji,nkj->nki", white[ok], np.transpose(x[ok, :2], (0, 2, 1)))
    if not ok.all():
        ip1, nb1 = tri.neighbors
        own1 = np.repeat(np.arange(n), np.diff(ip1))
        nb1 = nb1.astype(np.int64)
        d1 = np.ldexp(pts[nb1], -pre) - np.ldexp(pts[own1], -pre)
        u1 = np.einsum("mij,mj->mi", white[own1], np.ldexp(d1, -e[own1][:, None]))
        x1, ok1 = _fit(u1, 1.0 / (u1 * u1).sum(1), values[nb1] - values[own1], own1, n)
        use = ~ok & ok1
        grads[use] = np.einsum("nji,nkj->nki", white[use], np.transpose(x1[use], (0, 2, 1)))
    # back to the user's units: d was scaled by 2**-(pre + e), the values by 2**-vexp
    with np.errstate(over="ignore"):  # inf only where the gradient is beyond the range
        return np.ldexp(grads, vexp[None, :, None] - (pre + e)[:, None, None])


def _whitening(d, owner, n):
    """Per site, ``W`` (2 x 2) making its neighbours' offsets ``W d`` unit-spread on each axis.

    An isotropic scale left sites on a 1 x 1e-6 strip with columns 1e6 apart in size (1e24
    in the quadratic terms) and the fit lost the gradient (3.8e-2 error on linear data);
    a quadratic in ``W d`` is a quadratic in ``d``, so exactness is kept. A direction the
    offsets do not span keeps its column 0 (the fit then reports itself singular).
    """
    count = np.maximum(np.bincount(owner, minlength=n), 1)
    cov = np.zeros((n, 2, 2))
    np.add.at(cov, owner, d[:, :, None] * d[:, None, :])
    cov /= count[:, None, None]
    _, vec = np.linalg.eigh(cov)  # the directions: right to ~eps / (gap of eigenvalues)
    # the spreads along them from the offsets' projections: a thin strip's small eigenvalue
    # of cov itself is lost below eps * the large one (1e-18 of it on a 1 x 1e-9 strip)
    along = np.einsum("mj,mjk->mk", d, vec[owner])
    lam = np.zeros((n, 2))
    np.add.at(lam, owner, along * along)
    lam /= count[:, None]
    top = lam.max(axis=1, keepdims=True)
    inv = np.where(lam > 0, 1.0 / np.sqrt(np.where(lam > 0, lam, 1.0)), 0.0)
    inv = np.where(top > 0, inv, 1.0)  # all offsets 0 (duplicates): the fit fails alone
    return inv[:, :, None] * np.transpose(vec, (0, 2, 1))


def _exact_origin(pts: np.ndarray) -> np.ndarray:
    """An origin near the sites that every site's difference from is exact, else zero.

    Far from the origin (UTM-like coordinates) the Sibson areas lose digits to the
    coordinates' magnitude; in a frame at the sites' lower corner they keep the spacing's.
    The translation must leave the triangulation's exact decisions unchanged, so it is used
    only when every ``site - origin`` is exact (Knuth's two-sum error is zero).
    """
    origin = pts.min(axis=0)
    d = pts - origin
    back = d - pts
    err = (pts - (d - back)) + (-origin - back)
    return origin if not err.any() else np.zeros(2)


def natural_neighbor(
    points,
    values,
    query,
    *,
    extrapolate: str | None = None,
    smooth: bool = False,
    gradients=None,
):
    """Sibson natural-neighbour interpolation of values given at scattered sites.

    The weight of site ``i`` at a query point ``q`` is the area that inserting ``q`` into the
    Voronoi diagram steals from the cell of ``i``, divided by the area of ``q``'s new cell.
    The interpolant is continuous, equals the data at the sites and reproduces linear
    functions exactly (to rounding) inside the convex hull of the sites. On a hull edge it
    is the linear interpolation between the edge's two end points (Sibson's limit there).

    Parameters
    ----------
    points : (n, 2) array_like
        Sites. Duplicates are allowed: the first occurrence's value is used.
    values : (n,) or (n, k) array_like
        Data at the sites (``k`` fields are interpolated with the same weights).
    query : (2,) or (m, 2) array_like
        Points to interpolate at.
    extrapolate : {None, "nearest"}, optional
        Outside the convex hull of the sites: None gives NaN, "nearest" the value of the
        nearest site (ties to the lowest index). With fewer than three sites, or all sites
        on a line, every query that is not exactly at a site counts as outside.
    smooth : bool, optional
        False (default): Sibson's interpolant ``Z0``, the weighted mean above (continuous,
        with kinks at the sites). True: Sibson's ``Z1`` (Sibson 1980), which blends ``Z0``
        with the same weights applied to tangent planes at the sites so that the result
        is smooth away from the sites and exact for ``a + b.x + c |x|**2`` (given exact
        gradients). Still exact for linear data and equal to the data at the sites; much
        more accurate on smooth data.
    gradients : (n, 2) or (n, k, 2) array_like, optional
        Gradients of the data at the sites for ``smooth=True``. Default: estimated by local
        quadratic least squares over each site's Delaunay neighbours and theirs.

    Returns
    -------
    float64 array
        Shape ``(m,)`` or ``(m, k)`` (following ``values``); a single query point gives a
        float (``values`` of shape ``(n,)``) or a ``(k,)`` array.

    Raises
    ------
    ValueError
        Malformed inputs (non-finite ``values`` included), no sites, or an unknown
        ``extrapolate``.

    Examples
    --------
    >>> import numpy as np, voroforge as vf
    >>> pts = np.random.default_rng(0).random((200, 2))
    >>> f = 3 * pts[:, 0] - 2 * pts[:, 1] + 1
    >>> round(float(vf.natural_neighbor(pts, f, [0.5, 0.5])), 9)
    1.5
    """
    if extrapolate not in (None, "nearest"):
        raise ValueError(f"extrapolate must be None or 'nearest'; got {extrapolate!r}")
    tri = delaunay(points)
    pts = np.asarray(tri.points)
    n = len(pts)
    if n == 0:
        raise ValueError("natural_neighbor needs at least one site")
    vals, flat = as_values(values, n)
    q, single = as_query(query, name="query")
    if gradients is not None and not smooth:
        raise ValueError("gradients= is used only with smooth=True")
    if len(tri.triangles):
        # the kernel's incircle and areas need degree-4 terms in the double range: at extreme
        # scales it works on points, queries and gradients scaled by a power of two (exact)
        origin = _exact_origin(pts)
        work, k = working_frame(pts - origin)
    # each field scaled down by a power of two to a largest |value| in [0.5, 1) (exact; the
    # interpolants are linear in the values): differences, normal equations and the
    # kernel's area-weighted sums of values near +-1e308 overflowed to NaN (checker12 F7).
    # Small values are left as they are (given gradients scaled up could overflow)
    vexp = np.maximum(np.frexp(np.abs(vals).max(axis=0, initial=0.0))[1], 0)
    svals = np.ldexp(vals, -vexp)
    if smooth and len(tri.triangles):
        if gradients is None:  # in the working frame (d f / d work = 2**-k d f / d pts)
            grads = estimate_gradients(tri, svals, work)
        else:
            grads = np.array(gradients, dtype=np.float64, copy=True)
            if grads.shape in ((n, 2), (n, 1, 2)) and vals.shape[1] == 1:
                grads = grads.reshape(n, 1, 2)
            if grads.shape != (n, vals.shape[1], 2) or not np.isfinite(grads).all():
                raise ValueError(
                    f"gradients must be finite with shape ({n}, 2) or ({n}, k, 2) matching "
                    f"values; got {grads.shape}"
                )
            grads = np.ldexp(grads, (-k - vexp)[:, None])
    else:
        grads = np.zeros((n, vals.shape[1], 2))
    loc = _Locator(pts, np.asarray(tri.duplicate_of))
    nearest = loc.query(q) if len(q) else np.zeros(0, dtype=np.int64)
    out = np.full((len(q), vals.shape[1]), np.nan)
    if len(tri.triangles):
        with np.errstate(over="ignore"):
            qk = np.ldexp(q - origin, k) if k else q - origin
        # a query beyond the double range once scaled is far outside the sites' hull
        fits = np.isfinite(qk).all(axis=1)
        status = np.full(len(q), INSIDE + 1, dtype=np.int8)
        inner = out[fits]
        status[fits] = sibson(
            np.ascontiguousarray(work[:, 0]),
            np.ascontiguousarray(work[:, 1]),
            np.ascontiguousarray(tri.triangles.ravel()),
            np.asarray(tri.halfedges),
            svals,
            grads,
            bool(smooth),
            np.ascontiguousarray(nearest[fits]),
            np.ascontiguousarray(qk[fits, 0]),
            np.ascontiguousarray(qk[fits, 1]),
            inner,
        )
        with np.errstate(over="ignore"):  # inf only where the true value is beyond 1.8e308
            out[fits] = np.ldexp(inner, vexp)
    else:
        at_site = (pts[nearest] == q).all(axis=1)
        out[at_site] = vals[nearest[at_site]]
        status = np.where(at_site, INSIDE, INSIDE + 1)
    if extrapolate == "nearest":
        miss = status != INSIDE
        out[miss] = vals[nearest[miss]]
    if flat:
        out = out[:, 0]
    return out[0] if single else out
