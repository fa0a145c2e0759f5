"""Nearest site of 3D queries (``Diagram3D.locate``): float search, exact ties."""

from __future__ import annotations

from fractions import Fraction

import numpy as np

from ..kernels.nearest_exact import nearest_of
from .inputs import as_query

_NO_WEIGHTS = np.zeros(0)


def _exact_key(q, p, w):
    d = sum((Fraction(float(a)) - Fraction(float(b))) ** 2 for a, b in zip(q, p, strict=False))
    return d - Fraction(float(w))


def _frame(q, sites, w):
    """A power of two ``s`` for the float filter, or 1.0 where squares cannot over/underflow.

    Squared distances of coordinates past ~1e154 overflow (1e200: every distance ``inf``,
    every site a near tie, an overflow warning per chunk); past 2**480 or below 2**-480
    the filter runs on ``q * s``, ``sites * s``, ``w * s * s``, whose float arithmetic is
    the original's scaled exactly (no rounding changes, except digits lost to underflow
    far below the largest value, which only widen the near-tie set the exact pick decides).
    """
    big = 0.0
    for a in (q, sites):
        if a.size:
            big = max(big, float(np.abs(a).max()))
    if w.size:
        big = max(big, float(np.sqrt(np.abs(w).max())))
    if not np.isfinite(big) or big == 0.0 or 2.0**-480 <= big <= 2.0**480:
        return 1.0
    return float(np.ldexp(1.0, -int(np.frexp(big)[1])))


def lifted_sites(sites, q, w):
    """Sites and queries in a space where the Euclidean nearest is the power-nearest.

    Without weights, the points themselves (and ``None`` for the spread). With weights, one
    more coordinate ``sqrt(max(w) - w_p)`` for the sites and 0 for the queries (any
    dimension: the 2D power diagram's ``locate`` lifts its sites with it too): the lifted
    squared distance is the power distance ``|x - p|^2 - w_p`` plus ``max(w)``, so a KD-tree
    finds the power-nearest in ``log n`` (a block scan of every site per query was
    quadratic). ``spread`` (the largest ``|w|``) bounds the rounding the lift adds.
    """
    if w is None:
        return sites, q, None
    top = float(w.max())
    lifted = np.column_stack((sites, np.sqrt(top - w)))  # (top - w >= 0 also after rounding)
    return lifted, np.column_stack((q, np.zeros(len(q)))), float(np.abs(w).max())


def locate3d(d, xyz):
    """Index of the site whose cell holds each query (power distance with weights).

    Near ties (float distances within 1e-9 relative) are decided with exact rational
    arithmetic, so an exact tie goes to the lowest index. The float search runs in a
    power-of-two frame where squares of the coordinates would overflow or underflow.
    """
    q, single = as_query(xyz, dim=3, name="xyz")
    sites0 = np.ascontiguousarray(d.sites, dtype=np.float64)
    n = len(sites0)
    if n == 0:
        raise ValueError("locate on an empty diagram")
    w0 = np.zeros(n) if d.weights is None else np.ascontiguousarray(d.weights, dtype=np.float64)
    if d.periodic:
        out = _locate_torus(q, sites0, w0, np.asarray(d.duplicate_of), d.box)
        return int(out[0]) if single else out
    q0 = q
    s = _frame(q, sites0, w0)
    sites, w = sites0, w0
    if s != 1.0:
        q, sites, w = q * s, sites0 * s, w0 * (s * s)
    live = np.flatnonzero(np.asarray(d.duplicate_of) < 0)
    out = np.zeros(len(q), np.int64)
    step = max(1, 2_000_000 // max(len(live), 1))
    if len(live) > 64:
        from scipy.spatial import cKDTree

        pts, qq, spread = lifted_sites(sites[live], q, None if d.weights is None else w[live])
        kk = min(8, len(live))
        dist, idx = cKDTree(pts).query(qq, k=kk)
        dist = dist.reshape(len(q), kk)
        idx = idx.reshape(len(q), kk)
        for r in range(len(q)):
            if spread is None:
                near = dist[r] <= dist[r, 0] * (1 + 1e-9) + 1e-300
            else:  # (lifted squared distances: the power distance plus max(w))
                dd = dist[r] ** 2
                near = dd <= dd[0] + 1e-9 * (dd[0] + spread) + 1e-300
            cand = live[idx[r][near]]
            if near.all():  # many ties: fall back to a full scan of this query
                dd = ((sites[live] - q[r]) ** 2).sum(axis=1) - w[live]
                best = dd.min()
                cand = live[dd <= best + 1e-9 * (abs(best) + np.abs(q[r]).max() ** 2 + 1e-300)]
            out[r] = nearest_exact(q0[r], cand, sites0, w0)
    else:
        for s0 in range(0, len(q), step):
            qq = q[s0 : s0 + step]
            dd = ((qq[:, None, :] - sites[live][None, :, :]) ** 2).sum(axis=2) - w[live][None, :]
            best = dd.min(axis=1, keepdims=True)
            for r in range(len(qq)):
                near = dd[r] <= best[r, 0] + 1e-9 * (
                    abs(best[r, 0]) + np.abs(qq[r]).max() ** 2 + 1e-300
                )
                out[s0 + r] = nearest_exact(q0[s0 + r], live[near], sites0, w0)
    return int(out[0]) if single else out


def nearest_exact(q, cand, sites, w=None) -> int:
    """Lowest index among the exactly nearest of sites ``cand`` to ``q`` (any dimension).

    Squared distances less the weights ``w`` (none: zero), decided exactly, so float ties
    and near ties go to the lowest index; ``locate`` in 2D uses it for its near ties too.
    A compiled float filter and expansion comparison (:func:`kernels.nearest_exact.nearest_of`)
    decides them; rationals only where the offsets span more binades than one scaled frame
    holds exactly.
    """
    if len(cand) == 1:
        return int(cand[0])
    cand = np.asarray(cand, dtype=np.int64)
    q = np.ascontiguousarray(q, dtype=np.float64)
    sites = np.ascontiguousarray(sites, dtype=np.float64)
    ww = _NO_WEIGHTS if w is None else np.ascontiguousarray(w, dtype=np.float64)
    # read-only views (one numba type: a frozen diagram's sites and weights are read-only,
    # a caller's may not be; numba types the flag)
    sites, ww = sites.view(), ww.view()
    sites.setflags(write=False)
    ww.setflags(write=False)
    pick = int(nearest_of(q, cand, sites, ww))
    if pick >= 0:
        return pick
    keys = [(_exact_key(q, sites[c], 0.0 if w is None else w[c]), int(c)) for c in cand]
    return min(keys)[1]


def _torus_d2(q, sites, size):
    """Squared minimum-image distances ``(m, k)`` from queries ``q (m, 3)`` to ``sites (k, 3)``."""
    diff = np.abs(q[:, None, :] - sites[None, :, :]) % size
    diff = np.minimum(diff, size - diff)
    return (diff * diff).sum(axis=2)


def _locate_torus(q, sites0, w0, duplicate_of, box):
    """:func:`locate3d` on the 3-torus ``box``: minimum-image power distances, exact ties.

    A site's nearest image is its nearest in each axis (weights do not depend on the image),
    so the float filter takes the per-axis minimum image (in a power-of-two frame where the
    squares would over/underflow) and near ties (1e-9 of the box's squared diagonal) are
    decided in rationals modulo the box, on the queries as given.
    """
    lo = np.asarray(box[0], np.float64)
    size = np.asarray(box[1], np.float64) - lo
    live = np.flatnonzero(duplicate_of < 0)
    s = _frame(size, sites0, w0)
    sites, w, size_s = sites0 * s, w0 * (s * s), size * s
    # queries into the box first (fmod is exact; only the shift by a period may round)
    rel = np.mod(q * s - lo * s, size_s)
    S = np.mod(sites[live] - lo * s, size_s)
    slack = 1e-9 * float((size_s * size_s).sum() + np.abs(w).max())
    out = np.zeros(len(q), np.int64)
    rows = np.arange(len(q))
    if len(live) > 64:
        # the 8 nearest images from a periodic KD-tree (with weights, of the lifted sites: a
        # fourth, non-periodic coordinate; see lifted_sites); a query whose 8th is within the
        # slack of its nearest (many near ties) is scanned in full below
        from scipy.spatial import cKDTree

        S[S >= size_s] = 0.0  # (np.mod can round up to the period itself)
        rel[rel >= size_s] = 0.0
        kk = min(8, len(live))
        pts, qq, spread = lifted_sites(S, rel, w[live] if np.any(w) else None)
        period = size_s if spread is None else np.append(size_s, 0.0)  # (0: not periodic)
        dist, idx = cKDTree(pts, boxsize=period).query(qq, k=kk)
        dd = dist.reshape(len(q), kk) ** 2
        idx = live[idx.reshape(len(q), kk)]
        near = dd <= dd[:, :1] + slack
        for r in range(len(q)):
            k = idx[r][near[r]]
            out[r] = k[0] if len(k) == 1 else nearest_torus_exact(q[r], k, sites0, w0, size)
        rows = np.flatnonzero(near[:, -1]) if kk < len(live) else rows[:0]
    step = max(1, 2_000_000 // max(len(live), 1))
    for a in range(0, len(rows), step):
        batch = rows[a : a + step]
        dd = _torus_d2(rel[batch], S, size_s) - w[live][None, :]
        best = dd.min(axis=1, keepdims=True)
        for r, qi in enumerate(batch):
            near = live[dd[r] <= best[r, 0] + slack]
            if len(near) == 1:
                out[qi] = near[0]
            else:
                out[qi] = nearest_torus_exact(q[qi], near, sites0, w0, size)
    return out


def nearest_torus_exact(q, cand, sites, w, size) -> int:
    """Lowest index among the exactly nearest of ``cand`` to ``q`` on the torus ``size``.

    Minimum-image squared distances less the weights ``w`` (``None``: zero) in rationals,
    in any dimension (``len(size)``); 2D ``locate`` on a periodic diagram uses it too.
    """
    per = [Fraction(float(x)) for x in size]
    keys = []
    for c in cand:
        t = Fraction(0)
        for a in range(len(per)):
            dl = (Fraction(float(q[a])) - Fraction(float(sites[c, a]))) % per[a]
            dl = min(dl, per[a] - dl)
            t += dl * dl
        keys.append((t if w is None else t - Fraction(float(w[c])), int(c)))
    return min(keys)[1]
