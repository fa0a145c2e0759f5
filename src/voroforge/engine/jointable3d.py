"""The join's vertex table (engine.build3d): slots local to a vertex's join bucket, probing.

A vertex's probe sequence starts in its join bucket's run of slots (:func:`slot`, so a chunk
of cells joined in bucket order stays in a few cached runs), steps linearly
``JOIN_LOCAL_PROBES`` times, then jumps once to a slot hashed over the whole table
(:func:`probe_next`): a function of the vertex and the step alone, so a lookup walks the
insert's sequence (nothing is ever removed).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import JOIN_LOCAL_PROBES, NJIT


@njit(**{**NJIT, "inline": "always"})
def slot(bits, vx, r, jg, bslot, mask, key):
    """Table slot of the vertex at ``vx[r]`` (coordinates' bits ``bits[r]``): spatially local.

    The vertex's bucket in the join grid ``jg = (x0, y0, z0, 1/hx, 1/hy, 1/hz, nx, ny,
    nz)`` picks a run of slots ``bslot[b]:bslot[b + 1]`` (as long as the bucket's share of
    the table: one unit per bucket and one per cell built in it), the hash of the bits a
    slot in the run. Cells are joined in bucket order, so the vertices a chunk looks up
    lie in a few runs of the table that stay in cache, where a plain hash put every insert
    at a random place in a table of ~100 MB (a cache miss each). A function of the bits
    and the name ``key`` (the join's identity, :func:`kernels.vertex3d.name_key`): equal
    vertices meet in one probe sequence, and the thousands of distinct vertices of a float
    sphere that round to one point do not all share one (3,000 sites on a sphere: over
    150 s with the bits alone).
    """
    nx = int(jg[6])
    ny = int(jg[7])
    nz = int(jg[8])
    ix = min(max(int(np.floor((vx[r, 0] - jg[0]) * jg[3])), 0), nx - 1)
    iy = min(max(int(np.floor((vx[r, 1] - jg[1]) * jg[4])), 0), ny - 1)
    iz = min(max(int(np.floor((vx[r, 2] - jg[2]) * jg[5])), 0), nz - 1)
    b = (iz * ny + iy) * nx + ix
    base = bslot[b]
    width = max(bslot[b + 1] - base, 1)
    h = np.uint64(0x9E3779B97F4A7C15)
    for q in range(3):
        h ^= np.uint64(bits[r, q])
        h *= np.uint64(0xBF58476D1CE4E5B9)
        h ^= h >> np.uint64(31)
    h ^= np.uint64(key)
    h *= np.uint64(0xBF58476D1CE4E5B9)
    h ^= h >> np.uint64(31)
    off = (np.int64(h >> np.uint64(33)) * width) >> 31  # in [0, width)
    return (base + off) & mask


@njit(**{**NJIT, "inline": "always"})
def probe_next(h, mask, bits, r, key, steps):
    """The slot after ``h`` in the probe sequence of the vertex ``bits[r]`` (name ``key``).

    ``JOIN_LOCAL_PROBES`` linear steps from its :func:`slot`, then one jump to a slot hashed
    from its bits and key over the whole table, then linear again: a function of the vertex
    and the step alone, so a lookup walks the insert's sequence (nothing is ever removed).
    """
    if steps != JOIN_LOCAL_PROBES - 1:
        return (h + 1) & mask
    x = np.uint64(0x632BE59BD9B4E019)
    for q in range(3):
        x ^= np.uint64(bits[r, q])
        x *= np.uint64(0x94D049BB133111EB)
        x ^= x >> np.uint64(29)
    x ^= np.uint64(key)
    x *= np.uint64(0x94D049BB133111EB)
    x ^= x >> np.uint64(32)
    return np.int64(x >> np.uint64(1)) & mask


@njit(**NJIT)
def rehash(verts, want, nvert, table, jg, bslot):
    """Fill an empty (all -1) ``table`` with vertices ``0:nvert`` (slots of :func:`slot`)."""
    mask = table.shape[0] - 1
    bits = verts.view(np.int64)
    for g in range(nvert):
        h = slot(bits, verts, g, jg, bslot, mask, want[g] >> 8)
        steps = 0
        while table[h] >= 0:
            h = probe_next(h, mask, bits, g, want[g] >> 8, steps)
            steps += 1
        table[h] = g


@njit(**NJIT)
def rows_box(P):
    """``(lo, hi)``: the least and largest coordinate of the rows of ``P (n >= 1, 3)``.

    One pass over the rows (numpy's ``P.min(axis=0)`` on a C-ordered ``(n, 3)`` array takes
    ~30 ms at 1e6 rows: a reduction along its short axis); the same values (a minimum does
    not round; only the sign of a zero may differ, which no bucket of :func:`slot` sees).
    """
    lo = P[0].copy()
    hi = P[0].copy()
    for i in range(1, P.shape[0]):
        for q in range(3):
            x = P[i, q]
            if x < lo[q]:
                lo[q] = x
            elif x > hi[q]:
                hi[q] = x
    return lo, hi
