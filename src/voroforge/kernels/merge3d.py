"""A cell's named vertices merged (``cells3d.build_cells``), in linear time for big cells.

:func:`merge_named` merges a vertex into the first kept one with the same name (its four
owners) or the same coordinates and join key (:func:`kernels.vertex3d.name_key`,
``vnames[:, 4] >> 8``), else keeps it. With the key, exactly distinct vertices of four
owners that round to the same doubles (points rounded onto a sphere, an FCC lattice at 1e8)
stay two vertices here and in the join, as the exact diagram has them (merging them pinched
the cell's faces at the merged vertex, or repeated it in a ring, and moved one vertex's
relative coordinates to the other's); vertices of more owners with equal coordinates are
one vertex. Repeats in rings and thin faces go after.

A cell under :data:`~voroforge.config.MERGE3D_HASH_FROM` vertices (a uniform cell has
~26) is merged by a scan of the vertices kept so far; a bigger one by hash tables. Kept
vertices never match each other (each was kept because it matched none before it, and both
relations are equivalences where they hold), so at most one kept vertex has the vertex's
name and at most one its coordinates and key: the first kept match is the smaller of the
two tables' answers, and the remap, the kept vertices and the rings are the scan's, bit for
bit. A helix's cells of 95-380 faces spent ~10% of the build in the scan (540 vertices:
~146,000 comparisons). The tables live in a scratch the caller has free at that point
(``work`` of ``cellcut3d.cut_scratch``: ``(max(vcap, rcap), 4)`` int64, free after the
naming), so nothing is allocated; where they do not fit it the scan runs.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import MERGE3D_HASH_FROM, NJIT
from .graph3d import remap_rings

_NO_NRT = {**NJIT, "_nrt": False}
_INLINE = {**_NO_NRT, "inline": "always"}
_MIX = np.uint64(0xBF58476D1CE4E5B9)
_NEG_ZERO = np.int64(-(2**63))


@njit(**_INLINE)
def _mix(h, x):
    """One SplitMix-style step of a 64-bit hash over the word ``x``."""
    h ^= np.uint64(x)
    h *= _MIX
    return h ^ (h >> np.uint64(31))


@njit(**_INLINE)
def _name_hash(vnames, v):
    h = np.uint64(0x9E3779B97F4A7C15)
    for q in range(4):
        h = _mix(h, vnames[v, q])
    return h


@njit(**_INLINE)
def _key_hash(vnames, vbits, v):
    """The hash of vertex ``v``'s coordinates' bits and its join key.

    ``vbits`` is ``vabs`` as int64; ``-0.0`` hashes as ``0.0`` (they compare equal).
    """
    h = np.uint64(0x9E3779B97F4A7C15)
    for q in range(3):
        b = vbits[v, q]
        h = _mix(h, 0 if b == _NEG_ZERO else b)
    return _mix(h, vnames[v, 4] >> 8)


@njit(**_INLINE)
def _same_name(vnames, u, v):
    return (
        vnames[u, 0] == vnames[v, 0]
        and vnames[u, 1] == vnames[v, 1]
        and vnames[u, 2] == vnames[v, 2]
        and vnames[u, 3] == vnames[v, 3]
    )


@njit(**_INLINE)
def _same_key(vnames, vabs, u, v):
    return (
        vabs[u, 0] == vabs[v, 0]
        and vabs[u, 1] == vabs[v, 1]
        and vabs[u, 2] == vabs[v, 2]
        and vnames[u, 4] >> 8 == vnames[v, 4] >> 8
    )


@njit(**_INLINE)
def keep_vertex(m, v, vnames, vabs, vrel):
    """Vertex ``v`` kept as the ``m``-th: its name, coordinates and relative point moved."""
    if m != v:
        for q in range(5):
            vnames[m, q] = vnames[v, q]
        for q in range(3):
            vabs[m, q] = vabs[v, q]
            vrel[m, q] = vrel[v, q]


@njit(**_NO_NRT)
def merge_named(nv, F, nf, R, vnames, vabs, vrel, remap, work):
    """Merge local vertices with equal names or equal join keys; drop repeats and thin faces.

    The rule of the module's docstring, in time linear in ``nv`` from
    ``MERGE3D_HASH_FROM`` vertices on. ``work``: free int64 scratch of at least
    ``4 nv`` entries in rows of 4 (else the plain scan). Returns ``(nv, nf, nr)``; rings
    are repacked from 0.
    """
    size = 1
    while size < 2 * nv:
        size *= 2
    m = 0
    if nv < MERGE3D_HASH_FROM or 2 * size > work.shape[0] * work.shape[1] or work.shape[1] != 4:
        for v in range(nv):
            same = -1
            for u in range(m):
                if _same_name(vnames, u, v) or _same_key(vnames, vabs, u, v):
                    same = u
                    break
            if same >= 0:
                remap[v] = same
                continue
            remap[v] = m
            keep_vertex(m, v, vnames, vabs, vrel)
            m += 1
    else:
        # two open-addressed tables of ``size`` slots (names, then keys) in work's first
        # 2 * size entries (row e >> 2, column e & 3), each slot the kept index + 1
        mask = np.uint64(size - 1)
        vbits = vabs.view(np.int64)
        for e in range(2 * size):
            work[e >> 2, e & 3] = 0
        for v in range(nv):
            en = np.int64(_name_hash(vnames, v) & mask)
            un = -1
            while True:
                u = work[en >> 2, en & 3] - 1
                if u < 0:
                    break
                if _same_name(vnames, u, v):
                    un = u
                    break
                en = (en + 1) & (size - 1)
            ek = np.int64(_key_hash(vnames, vbits, v) & mask)
            uk = -1
            while True:
                u = work[(size + ek) >> 2, (size + ek) & 3] - 1
                if u < 0:
                    break
                if _same_key(vnames, vabs, u, v):
                    uk = u
                    break
                ek = (ek + 1) & (size - 1)
            if un >= 0 or uk >= 0:  # the first kept match: the smaller
                remap[v] = un if uk < 0 else (uk if un < 0 else min(un, uk))
                continue
            remap[v] = m
            keep_vertex(m, v, vnames, vabs, vrel)
            work[en >> 2, en & 3] = m + 1  # (en, ek: the empty slots the probes ended at)
            work[(size + ek) >> 2, (size + ek) & 3] = m + 1
            m += 1
    nf2, nr = remap_rings(nf, F, R, remap)
    return m, nf2, nr
