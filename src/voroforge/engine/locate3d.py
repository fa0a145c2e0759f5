"""Nearest site of 3D queries (``Diagram3D.locate``): float search, exact ties."""

from __future__ import annotations

from fractions import Fraction

import numpy as np

from .inputs import as_query


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


def locate3d(d, xyz):
    """Index of the site whose cell holds each query (power distance with weights).

    Near ties (float distances within 1e-9 relative) are decided with exact rational
    arithmetic, so an exact tie goes to the lowest index. The float search runs in a
    power-of-two frame where squares of the coordinates would overflow or underflow.
    """
    q, single = as_query(xyz, dim=3)
    sites0 = np.asarray(d.sites)
    n = len(sites0)
    if n == 0:
        raise ValueError("locate on an empty diagram")
    w0 = np.zeros(n) if d.weights is None else np.asarray(d.weights)
    q0 = q
    s = _frame(q, sites0, w0)
    sites, w = sites0, w0
    if s != 1.0:
        q, sites, w = q * s, sites0 * s, w0 * (s * s)
    live = np.flatnonzero(np.asarray(d.duplicate_of) < 0)
    out = np.zeros(len(q), np.int64)
    step = max(1, 2_000_000 // max(len(live), 1))
    if d.weights is None and len(live) > 64:
        from scipy.spatial import cKDTree

        tree = cKDTree(sites[live])
        kk = min(8, len(live))
        dist, idx = tree.query(q, k=kk)
        dist = dist.reshape(len(q), kk)
        idx = idx.reshape(len(q), kk)
        for r in range(len(q)):
            near = dist[r] <= dist[r, 0] * (1 + 1e-9) + 1e-300
            cand = live[idx[r][near]]
            if near.all():  # many ties: fall back to a full scan of this query
                d2 = ((sites[live] - q[r]) ** 2).sum(axis=1)
                cand = live[d2 <= d2.min() * (1 + 1e-9) + 1e-300]
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

    Squared distances less the weights ``w`` (none: zero) in rationals, so float ties and
    near ties are decided exactly; ``locate`` in 2D uses it for its near ties too.
    """
    if len(cand) == 1:
        return int(cand[0])
    keys = [(_exact_key(q, sites[c], 0.0 if w is None else w[c]), int(c)) for c in cand]
    return min(keys)[1]
