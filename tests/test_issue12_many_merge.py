"""Issue 12: the linear-time merge of a cell's named vertices (kernels.merge3d).

Its remap, kept vertices and rings must be those of the plain scan (the first kept vertex
of the same name, or of the same coordinates and join key), bit for bit, on vertex sets
full of both kinds of repeats, ``-0.0`` beside ``0.0`` and NaN coordinates.
"""

import numpy as np
import pytest

from voroforge.config import MERGE3D_HASH_FROM as HASH_FROM
from voroforge.kernels.merge3d import merge_named


def _reference(nv, F, nf, R, vnames, vabs, vrel):
    """The plain scan, in Python (the rule of ``kernels.merge3d``)."""
    remap = np.zeros(nv, np.int64)
    kept = []
    for v in range(nv):
        same = -1
        for m, u in enumerate(kept):
            if all(vnames[u, q] == vnames[v, q] for q in range(4)) or (
                all(vabs[u, q] == vabs[v, q] for q in range(3))
                and vnames[u, 4] >> 8 == vnames[v, 4] >> 8
            ):
                same = m
                break
        if same >= 0:
            remap[v] = same
        else:
            remap[v] = len(kept)
            kept.append(v)
    rings = []
    for f in range(nf):
        ring = []
        for k in range(F[f, 2]):
            x = remap[R[F[f, 1] + k]]
            if ring and ring[-1] == x:
                continue
            ring.append(x)
        while len(ring) > 1 and ring[-1] == ring[0]:
            ring.pop()
        if len(ring) >= 3:
            rings.append((F[f, 0], ring))
    return remap, kept, rings


def _case(rng, nv):
    """``nv`` vertices, about a third repeating an earlier name or point, with rings."""
    vnames = rng.integers(0, 40, (nv, 5)).astype(np.int64)
    vnames[:, 4] = rng.integers(0, 1 << 12, nv)
    vabs = rng.integers(-3, 4, (nv, 3)).astype(np.float64) * 0.25
    for v in range(1, nv):
        u = int(rng.integers(0, v))
        r = rng.random()
        if r < 0.15:
            vnames[v, :4] = vnames[u, :4]
        elif r < 0.3:
            vabs[v] = vabs[u]
            vnames[v, 4] = (vnames[u, 4] & ~255) | int(rng.integers(0, 256))
        elif r < 0.35:
            vabs[v] = -vabs[u]  # -0.0 where vabs[u] is 0.0
            vnames[v, 4] = vnames[u, 4]
        elif r < 0.38:
            vabs[v, int(rng.integers(0, 3))] = np.nan
    vrel = rng.random((nv, 3))
    nf = max(1, nv // 3)
    lens = rng.integers(3, 9, nf)
    F = np.zeros((nf, 3), np.int64)
    F[:, 0] = rng.integers(-6, 50, nf)
    F[:, 1] = np.concatenate([[0], np.cumsum(lens)[:-1]])
    F[:, 2] = lens
    R = rng.integers(0, nv, int(lens.sum())).astype(np.int64)
    return F, nf, R, vnames, vabs, vrel


@pytest.mark.parametrize("nv", [5, HASH_FROM - 1, HASH_FROM, 97, 600])
@pytest.mark.parametrize("seed", [0, 1, 2])
@pytest.mark.parametrize("room", [True, False])
def test_merge_named_equals_scan(nv, seed, room):
    rng = np.random.default_rng(seed * 1000 + nv)
    F, nf, R, vnames, vabs, vrel = _case(rng, nv)
    remap0, kept, rings = _reference(nv, F, nf, R, vnames, vabs, vrel)
    names0 = vnames[kept].copy()
    abs0 = vabs[kept].copy()
    rel0 = vrel[kept].copy()
    work = np.full((3 * nv + 8 if room else 1, 4), -7, np.int64)  # (rows as rcap: 3 nv)
    remap = np.zeros(nv, np.int64)
    m, nf2, nr = merge_named(nv, F, nf, R, vnames, vabs, vrel, remap, work)
    assert m == len(kept)
    assert np.array_equal(remap, remap0)
    assert np.array_equal(vnames[:m], names0)
    assert np.array_equal(vabs[:m].view(np.int64), abs0.view(np.int64))
    assert np.array_equal(vrel[:m], rel0)
    assert nf2 == len(rings)
    assert nr == sum(len(r) for _, r in rings)
    for f, (lab, ring) in enumerate(rings):
        assert F[f, 0] == lab
        assert list(R[F[f, 1] : F[f, 1] + F[f, 2]]) == ring
