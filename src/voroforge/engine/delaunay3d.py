"""``vf.delaunay3d``: the 3D Delaunay tetrahedralisation with exact predicates."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..kernels.delaunay3d import FACE, INF, triangulate
from .inputs import as_points, working_frame
from .voronoi3d import duplicate_owner3d


@dataclass(frozen=True)
class Tetrahedralization:
    """Delaunay tetrahedra of 3D points (input indices), in scipy's ``Delaunay`` layout.

    Attributes
    ----------
    points : (n, 3) float64
        A copy of the input points.
    simplices : (m, 4) int64
        Tetrahedra ``a, b, c, d``, each right-handed: ``det[b - a, c - a, d - a] > 0``.
    neighbors : (m, 4) int64
        The tetrahedron across the face opposite each vertex, -1 on the convex hull.
    convex_hull : (h, 3) int64
        Hull triangles, counter-clockwise seen from outside.
    duplicate_of : (n,) int64
        -1 for a point's first occurrence, else the index of its first occurrence (left out
        of the tetrahedra). Points that the working frame made equal count as equal: where
        the points span more than ~2**188 (a unit grid beside a point at 1e300), coordinates
        below ``2**-188`` of the largest magnitude are rounded to multiples of ``2**-240`` of
        it (the exact predicates' resolution, ``engine.inputs.working_frame``), and every
        decision is made on those rounded points.
    """

    points: np.ndarray
    simplices: np.ndarray
    neighbors: np.ndarray
    convex_hull: np.ndarray
    duplicate_of: np.ndarray

    @property
    def volumes(self) -> np.ndarray:
        """Each tetrahedron's volume (positive; inf past float64's range).

        In floating point relative to the first vertex; a sliver whose float determinant
        is within its rounding bound (a float volume of -1.5e-16 where the exact one is
        +1.4e-33) is computed exactly (rationals) and rounded once.
        """
        q = self.points[self.simplices]
        u, v, w = q[:, 1] - q[:, 0], q[:, 2] - q[:, 0], q[:, 3] - q[:, 0]
        det, perm = _dets(u, v, w, q)
        # past ~1e100 the products overflow (inf - inf: NaN): those tetrahedra's edges are
        # taken with the coordinates scaled by a power of two to below 1 (exact), scaled
        # again to edges below 1 and the determinant scaled back, so a volume past
        # float64's range is inf and any other is as at scale 1
        big = np.flatnonzero(~np.isfinite(perm))
        if big.size:
            qb = q[big]
            e = np.frexp(np.abs(qb).max(axis=(1, 2)))[1][:, None]
            qs = np.ldexp(qb, -e[:, :, None])
            ub, vb, wb = qs[:, 1] - qs[:, 0], qs[:, 2] - qs[:, 0], qs[:, 3] - qs[:, 0]
            f = np.frexp(np.abs(np.hstack([ub, vb, wb])).max(axis=1))[1][:, None]
            small, _ = _dets(np.ldexp(ub, -f), np.ldexp(vb, -f), np.ldexp(wb, -f), None)
            with np.errstate(over="ignore"):
                scaled = np.ldexp(small, 3 * (e + f)[:, 0])
            for t in np.flatnonzero(np.isnan(small)).tolist():  # unsure: exact, unscaled
                scaled[t] = _exact_det(qb[t])
            det[big] = scaled
        return det / 6.0


def _dets(u, v, w, q):
    """``det[u, v, w]`` of each row and its rounding scale (the terms' magnitudes' sum).

    A determinant within its rounding bound is computed exactly from the rows of ``q``
    (rationals) where the bound is finite, or left NaN where ``q`` is None.
    """
    with np.errstate(over="ignore", invalid="ignore"):
        det = np.einsum("ij,ij->i", np.cross(u, v), w)
        # the sum of the determinant's terms' magnitudes: its rounding is below a few
        # eps of this (and so is the rounding of the differences u, v, w)
        au, av = np.abs(u), np.abs(v)
        pairs = au[:, [1, 2, 0]] * av[:, [2, 0, 1]] + au[:, [2, 0, 1]] * av[:, [1, 2, 0]]
        perm = np.einsum("ij,ij->i", pairs, np.abs(w))
    unsure = np.flatnonzero(~(np.abs(det) > VOLUME_UNSURE * perm) & np.isfinite(perm))
    for t in unsure.tolist():
        det[t] = np.nan if q is None else _exact_det(q[t])
    return det, perm


#: a float determinant relative to its permanent-like bound below this is recomputed exactly
#: (Shewchuk's orient3d bound is ~8 eps for the difference form; this leaves room for the
#: differences' own rounding)
VOLUME_UNSURE = 64.0 * np.finfo(float).eps


def _exact_det(q: np.ndarray) -> float:
    """``det[b - a, c - a, d - a]`` of the rows of ``q`` in rationals, rounded once."""
    from fractions import Fraction

    a, b, c, d = ([Fraction(float(x)) for x in row] for row in q)
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    w = [d[i] - a[i] for i in range(3)]
    det = (
        u[0] * (v[1] * w[2] - v[2] * w[1])
        - u[1] * (v[0] * w[2] - v[2] * w[0])
        + u[2] * (v[0] * w[1] - v[1] * w[0])
    )
    try:
        return float(det)
    except OverflowError:  # past float64's range
        return float(np.copysign(np.inf, det))


def delaunay3d(points) -> Tetrahedralization:
    """Delaunay tetrahedralisation of 3D points, decided by exact predicates.

    Each point is inserted in turn (Bowyer-Watson); whether a point lies inside a
    tetrahedron's circumsphere, or beyond a hull facet, is an exact sign (Shewchuk-style
    filtered ``orient3d``/``insphere``, exact expansions where the filter cannot tell). Five
    points on one sphere (a cubic grid's cubes) or four on a hull plane's circle are
    decided by a symbolic perturbation of the lifting (a point of larger index lies
    infinitesimally higher), so the result is one triangulation, independent of the
    insertion order, with no flat tetrahedron, and Delaunay for the given points: no point
    strictly inside any tetrahedron's circumsphere.

    Parameters
    ----------
    points : (n, 3) array_like
        Finite coordinates; exact duplicates are allowed (only the first occurrence is a
        vertex). The input is never modified.

    Returns
    -------
    Tetrahedralization
        Empty ``simplices`` (shape (0, 4)) when the points span no volume (fewer than four
        distinct points, or all on one plane).

    Raises
    ------
    ValueError
        If ``points`` is not an ``(n, 3)`` array of finite numbers.

    Examples
    --------
    >>> import numpy as np, voroforge as vf
    >>> t = vf.delaunay3d(np.random.default_rng(0).random((50, 3)))
    >>> t.simplices.shape[1], bool((t.volumes > 0).all())
    (4, True)
    """
    pts = as_points(points, dim=3)
    work, _ = working_frame(pts)
    dup = duplicate_owner3d(work, None)  # the first of equal points (+0.0 == -0.0)
    unique = np.flatnonzero(dup < 0)
    order = _insertion_order(work[unique], unique)
    T, nb, ok = triangulate(np.ascontiguousarray(work), order)
    empty = np.zeros((0, 4), np.int64)
    if not ok:
        return Tetrahedralization(pts, empty, empty.copy(), np.zeros((0, 3), np.int64), dup)
    finite = (T != INF).all(axis=1)
    idx = np.full(len(T), -1, np.int64)
    idx[finite] = np.arange(int(finite.sum()))
    # orient3d > 0 is left-handed (d below a, b, c seen counter-clockwise from above): swap
    # the last two vertices (and their neighbours) for right-handed, positive volumes
    simplices = T[finite][:, [0, 1, 3, 2]]
    neighbors = idx[nb[finite]][:, [0, 1, 3, 2]]
    # hull triangles: the face of each infinite tetrahedron opposite its infinite vertex.
    # FACE orders it so that (face, a point beyond it) is positive, i.e. counter-clockwise
    # seen from inside (orient3d's convention): reversed, it looks outward
    inf_t = T[~finite]
    k = np.argmax(inf_t == INF, axis=1)
    faces = np.take_along_axis(inf_t, FACE[k], axis=1)
    convex_hull = faces[:, ::-1].copy()
    return Tetrahedralization(pts, simplices, neighbors, convex_hull, dup)


def _insertion_order(pts: np.ndarray, ids: np.ndarray) -> np.ndarray:
    """Ids in a biased randomised insertion order.

    Rounds of doubling size, each sorted along a Morton curve: walks stay short, and the
    result does not depend on the order.
    """
    n = len(ids)
    if n <= 64:
        return ids.astype(np.int64)
    rng = np.random.default_rng(0x5EED)
    perm = rng.permutation(n)
    lo = pts.min(axis=0)
    span = np.maximum(pts.max(axis=0) - lo, np.finfo(float).tiny)
    q = np.clip(((pts - lo) / span * 1023.0).astype(np.int64), 0, 1023)
    code = np.zeros(n, np.int64)
    for bit in range(10):
        for ax in range(3):
            code |= ((q[:, ax] >> bit) & 1) << (3 * bit + ax)
    out = []
    start = 0
    size = 64
    while start < n:
        block = perm[start : start + size]
        out.append(block[np.argsort(code[block], kind="stable")])
        start += size
        size *= 2
    return ids[np.concatenate(out)].astype(np.int64)
