"""Issue 12: a many-faced cell's climbs start from the top last found for a like normal.

:func:`climb3d.plane_local` climbed from the last cut's vertex and ``CLIMB3D_SAMPLES``
vertices spread over the cell for every candidate plane (a helix's cell: 29.7 vertices
visited a plane passed over). It now keeps the top it found per direction slot of the
normal (``climb3d.TOP_SLOTS``, in ``work``'s last rows) and starts from it, with the
samples only where the slot has none in this cell. The start must change no decision:
whatever the slots hold (cleared, left by earlier climbs, any vertex or garbage), every
plane gets the full pass's answer, and the same cell's top is reached again from it.
"""

from __future__ import annotations

import numpy as np
import pytest

from test_s54_cut3d import CAP, _full, _planes, _sphere_cell
from voroforge.kernels import climb3d


def _answer(mode, smax, low, tol, S, work, nvis, full):
    """What the caller reads: passed over, or the cut's sign, band test and the values above."""
    if mode == climb3d.MISS:
        assert full.max() < -tol
        return ("miss",)
    assert mode == climb3d.LOCAL
    seen = work[:nvis, 1]
    assert (S[seen] == full[seen]).all()
    up = sorted(int(v) for v in seen if S[v] > -tol)
    assert up == sorted(np.flatnonzero(full > -tol).tolist())
    return ("local", smax > 0, smax == 0, low <= tol, tuple(up))


@pytest.mark.parametrize("n, seed", [(150, 3), (400, 4)])
def test_start_changes_no_decision(n, seed):
    P, W, WP, V, nv, G, FL = _sphere_cell(n, seed)
    rng = np.random.default_rng(seed + 20)
    rows = slice(CAP - climb3d.TOP_SLOTS, CAP)
    warm = np.zeros((CAP, 4), np.int64)  # slots kept from climb to climb, as a cell does
    climb3d.clear_tops(warm)
    assert (warm[rows, 2] == -1).all()
    cold = np.zeros((CAP, 4), np.int64)
    S = np.zeros(CAP)
    SF = np.zeros(CAP)
    r2 = float((V[:nv] ** 2).sum(axis=1).max())
    visits = [0, 0]
    misses = 0
    for q in _planes(rng, V, nv, 300):
        d2 = float(q @ q)
        h = 0.5 * d2
        tol = 1e-12 * (np.sqrt(d2 * r2) + abs(h))
        full = _full(V, nv, q, h, SF)
        answers = set()
        for work, hint in ((warm, 0), (cold, -1), (cold, int(rng.integers(nv)))):
            if work is cold:  # the slots hold anything: a vertex, out of range, garbage
                work[rows, 2] = rng.integers(-5, 2 * nv, climb3d.TOP_SLOTS)
            S[:] = np.nan
            res = climb3d.plane_local(V, nv, G[0], G[1], S, work, *q, h, tol, hint)
            assert not work[:nv, 0].any() and not work[:nv, 3].any()  # marks cleared
            assert res[0] != climb3d.FULL
            answers.add(_answer(*res[:2], res[2], tol, S, work, res[3], full))
        assert len(answers) == 1
        misses += next(iter(answers))[0] == "miss"
        # from a cleared slot (samples) and from the slot the climbs above set (its top)
        fresh = np.zeros((CAP, 4), np.int64)
        climb3d.clear_tops(fresh)
        a = climb3d.plane_local(V, nv, G[0], G[1], S, fresh, *q, h, tol, -1)
        b = climb3d.plane_local(V, nv, G[0], G[1], S, warm, *q, h, tol, -1)
        assert a[:2] == b[:2] and (a[2] <= tol) == (b[2] <= tol)
        visits[0] += a[3]
        visits[1] += b[3]
    assert misses > 20
    # listed: the vertices near or above the plane and their neighbours, whatever the start
    # (the climb's vertices farther below are evaluated, not listed: helix5, s57)
    assert visits[1] == visits[0]
