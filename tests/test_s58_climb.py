"""Issue 12: a many-faced cell's climbs start from the top of a finer direction slot (s58).

:func:`climb3d.plane_local` kept one top per direction slot of the normal (dominant axis
and signs, ``climb3d.TOP_SLOTS``); each slot is now split by the normal's other two
components (``climb3d.FINE_SLOTS``, below the slots in ``work``, cleared at a cell's first
climb), and a climb whose last step finds no neighbour within the plateau's band of the
top skips the plateau's search (it would find the top alone from the same values). Neither
may change a decision: whatever the fine slots hold, every plane gets the full pass's
answer; a plane whose top is a flat face (a plateau of equal values) still is decided.
"""

from __future__ import annotations

import numpy as np
import pytest

from test_s54_cut3d import CAP, _full, _planes, _sphere_cell
from test_s56_many3d import _answer
from voroforge.kernels import climb3d

FLAG = CAP - 1 - climb3d.TOP_SLOTS  # the row that says whether the fine slots are this cell's
FINE = slice(CAP - climb3d.TOP_SLOTS - 1 - climb3d.FINE_SLOTS, FLAG)


def _tol(q, r2):
    d2 = float(q @ q)
    h = 0.5 * d2
    return h, 1e-12 * (np.sqrt(d2 * r2) + abs(h))


@pytest.mark.parametrize("n, seed", [(150, 7), (400, 8)])
def test_fine_slots_change_no_decision(n, seed):
    P, W, WP, V, nv, G, FL = _sphere_cell(n, seed)
    rng = np.random.default_rng(seed + 30)
    warm = np.zeros((CAP, 4), np.int64)
    climb3d.clear_tops(warm)
    assert warm[FLAG, 2] == -1
    S = np.zeros(CAP)
    SF = np.zeros(CAP)
    r2 = float((V[:nv] ** 2).sum(axis=1).max())
    planes = _planes(rng, V, nv, 300)
    first = True
    for q in planes:
        h, tol = _tol(q, r2)
        full = _full(V, nv, q, h, SF)
        answers = set()
        for kind in range(3):
            if kind == 0:
                work = warm  # kept from climb to climb, as in a cell
            else:  # the fine slots hold anything: a vertex, out of range, garbage
                work = np.zeros((CAP, 4), np.int64)
                climb3d.clear_tops(work)
                work[FLAG, 2] = 0  # (marked as this cell's: read as they are)
                work[FINE, 2] = rng.integers(-5, 2 * nv, climb3d.FINE_SLOTS)
                if kind == 2:
                    work[CAP - climb3d.TOP_SLOTS :, 2] = rng.integers(0, nv, climb3d.TOP_SLOTS)
            S[:] = np.nan
            res = climb3d.plane_local(V, nv, G[0], G[1], S, work, *q, h, tol, 0)
            assert not work[:nv, 0].any() and not work[:nv, 3].any()  # marks cleared
            assert res[0] != climb3d.FULL
            answers.add(_answer(*res[:2], res[2], tol, S, work, res[3], full))
            if kind == 0 and first:  # the cell's first climb cleared its fine slots
                first = False
                assert warm[FLAG, 2] == 0
                assert (warm[FINE, 2] >= -1).all() and (warm[FINE, 2] >= 0).sum() == 1
        assert len(answers) == 1
    assert (warm[FINE, 2] >= 0).sum() > 10  # planes of many directions kept their tops


def test_flat_tops_are_decided():
    """Planes parallel to the box's faces: the top is what is left of a face (a plateau)."""
    P, W, WP, V, nv, G, FL = _sphere_cell(20, 9)
    r2 = float((V[:nv] ** 2).sum(axis=1).max())
    work = np.zeros((CAP, 4), np.int64)
    climb3d.clear_tops(work)
    S = np.zeros(CAP)
    SF = np.zeros(CAP)
    seen = set()
    flat = 0
    for axis in range(3):
        for sign in (1.0, -1.0):
            u = np.zeros(3)
            u[axis] = sign
            top = float((V[:nv] @ u).max())
            if ((V[:nv] @ u) == top).sum() < 3:
                continue  # (this face was cut away)
            flat += 1
            for d in (top * (1 + 1e-9), top, top * (1 - 1e-14), top * (1 - 1e-3), top * 0.5):
                q = 2.0 * d * u
                h, tol = _tol(q, r2)
                full = _full(V, nv, q, h, SF)
                for hint in (0, nv - 1):
                    S[:] = np.nan
                    res = climb3d.plane_local(V, nv, G[0], G[1], S, work, *q, h, tol, hint)
                    assert res[0] != climb3d.FULL
                    seen.add(_answer(*res[:2], res[2], tol, S, work, res[3], full)[0])
    assert flat >= 2
    assert seen == {"miss", "local"}
