"""The plotter's segment dedupe: its fast path (no two vertices snap) against the general one."""

from __future__ import annotations

import numpy as np
import pytest

from voroforge.io import plotter as P


def _general(rings, lines, tol):
    saved = P._all_apart
    P._all_apart = lambda coords, tol: False
    try:
        return P._dedupe(rings, lines, tol)
    finally:
        P._all_apart = saved


def _brute_apart(coords, tol):
    d = coords[:, None, :] - coords[None, :, :]
    d2 = (d * d).sum(axis=2)
    np.fill_diagonal(d2, np.inf)
    return not (d2 <= tol * tol).any()


def _items(rng, decimals):
    rings = [
        rng.random((rng.integers(3, 9), 2)).round(decimals) for _ in range(rng.integers(1, 25))
    ]
    lines = [rng.random((rng.integers(2, 6), 2)).round(decimals) for _ in range(rng.integers(0, 5))]
    return rings, lines


@pytest.mark.parametrize("tol", [0.0, 1e-9, 1e-4, 1e-2, 0.2])
def test_apart_is_never_wrong(tol):
    rng = np.random.default_rng(int(tol * 1e9) % 1000)
    for decimals in (2, 3, 17):
        for _ in range(40):
            rings, lines = _items(rng, decimals)
            coords = np.concatenate(rings + lines)
            if P._all_apart(coords, tol):
                assert _brute_apart(coords, tol)


def test_apart_with_many_vertices_on_one_line():
    # an inset frame: many vertices on x = 2 and on y = 2, all far apart
    t = np.arange(200, dtype=np.float64) * 3.0
    coords = np.concatenate(
        [np.column_stack((np.full_like(t, 2.0), t)), np.column_stack((t + 5, t * 0 + 2))]
    )
    assert P._all_apart(coords, 1e-6)
    close = np.vstack((coords, coords[17] + [0.0, 1e-7]))
    assert not P._all_apart(close, 1e-6)
    assert not P._all_apart(np.vstack((coords, coords[:1])), 0.0)


@pytest.mark.parametrize("decimals", [2, 3, 17])
def test_dedupe_fast_path_matches_general(decimals):
    rng = np.random.default_rng(decimals)
    taken = 0
    for trial in range(60):
        rings, lines = _items(rng, decimals)
        if trial % 3 == 0:
            rings.append(rings[0][::-1].copy())  # a repeated ring
        tol = (0.0, 1e-9, 1e-3)[trial % 3]
        taken += P._all_apart(np.concatenate(rings + lines), tol)
        fast = P._dedupe(rings, lines, tol)
        slow = _general(rings, lines, tol)
        assert [len(x) for x in fast] == [len(x) for x in slow]
        for a, b in zip(fast[0] + fast[1], slow[0] + slow[1], strict=True):
            assert np.array_equal(a, b)
    if decimals == 17:
        assert taken  # the fast path ran
