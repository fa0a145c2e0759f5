"""The 3D build's per-cell slots: their sizes, growth for many-faced cells, cells built alone.

:func:`.build3d.build_cells3d` builds chunks of cells into fixed per-cell output slots
(``caps``: vertices, faces, ring entries, the kernel's scratch and its graph's degree). A cell
past its slots is ``OVERFLOW`` with the counts it needs and is built again alone with room to
spare (:func:`big_cell`): the first build's work is thrown away. Where most cells of a chunk
overflow (sites on a helix: 95-380 faces a cell; on three orthogonal lines) every cell was
built twice, so the next chunks get slots for the counts seen (:func:`grown_caps`). A cell's
result does not depend on its slots' size (they only decide whether it fits), so the
diagram is the same bit for bit.
"""

from __future__ import annotations

import numpy as np

from ..config3d import (
    GROW_BYTES,
    GROW_CHUNK_LEAST,
    GROW_LEAST,
    GROW_MOST,
    GROW_PAD,
    GROW_PROBE_PAD,
    GROW_SHARE,
    SMALL_PAGES_FROM,
)
from ..kernels.cells3d import OVERFLOW

#: Linux's ``MADV_NOHUGEPAGE`` and the base page size
_MADV_NOHUGEPAGE = 15
_PAGE = 4096
_MADVISE = None


def small_pages(*arrays):
    """Ask for 4 KB pages under large, fresh, not yet touched arrays (Linux; else nothing).

    numpy asks for transparent huge pages under every array of 4 MB or more; on this VM
    (``defrag=madvise``: a huge page's fault may compact memory first, and pages freed a
    while ago are back with the host) first touching 300 MB in huge pages cost 0.61-0.93 s
    of system time, in 4 KB pages 0.14-0.16 s. Used for the join's outputs and vertex
    table (:class:`.build3d._Out`: ~0.5 GB at 1e6 cells, read and written near the cells
    being joined, so few TLB misses); the sites and the kernel's scratch keep huge pages.
    A pages' hint only: an array in the heap among others (glibc) just splits its map.
    """
    global _MADVISE
    if _MADVISE is None:
        _MADVISE = False
        import sys

        if sys.platform.startswith("linux"):
            import ctypes
            import ctypes.util

            try:
                f = ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6").madvise
                f.argtypes = [ctypes.c_void_p, ctypes.c_size_t, ctypes.c_int]
                _MADVISE = f
            except (OSError, AttributeError):
                pass
    if not _MADVISE:
        return
    for a in arrays:
        if a.nbytes < SMALL_PAGES_FROM:
            continue
        p = a.ctypes.data
        lo = -(-p // _PAGE) * _PAGE
        hi = (p + a.nbytes) // _PAGE * _PAGE
        _MADVISE(lo, hi - lo, _MADV_NOHUGEPAGE)


def slot_arrays(k, caps):
    """Fixed per-cell output slots for ``k`` cells (reused from chunk to chunk)."""
    cv, cf, cr = caps[:3]
    return (
        np.zeros(k * cv, np.int32),  # name key << 8 | owner sites (cells3d.build_cells)
        np.zeros((k * cv, 3)),
        np.zeros((k * cf, 2), np.int32),
        np.zeros(k * cr, np.int32),
    )


def slot_bytes(k, caps):
    """The bytes of :func:`slot_arrays` for ``k`` cells."""
    return k * (caps[0] * (4 + 24) + caps[1] * 8 + caps[2] * 4)


def probe_caps(base):
    """Caps whose output slots are as large as ``base``'s scratch (the first chunk's)."""
    return tuple(base[3:6]) + tuple(base[3:])


def chunk_room(caps, nsl, most):
    """The most cells a chunk may hold: ``nsl`` sets of its slots within :data:`GROW_BYTES`.

    ``most`` at most, :data:`GROW_CHUNK_LEAST` at least (three lines of 1,500 needed slots of
    ~72 KB a cell: 1,024 cells' slots passed the bytes, so the slots did not grow and ~30%
    of the cells were built twice; the chunks are made smaller instead).
    """
    return int(max(GROW_CHUNK_LEAST, min(most, GROW_BYTES // (nsl * slot_bytes(1, caps)))))


def probe_grown(status, counts, base, nsl):
    """Caps after the first chunk, built with :func:`probe_caps`: :func:`grown_caps` of it.

    A cell there overflowed ``base``'s output slots where its counts pass them; the growth
    is padded by :data:`GROW_PROBE_PAD` more. None: ``base`` fits (or cannot grow).
    """
    over = (counts[:, :3] > np.asarray(base[:3])).any(axis=1) & (status != OVERFLOW)
    status = np.where(over, OVERFLOW, status)
    k = nsl * GROW_CHUNK_LEAST
    return grown_caps(status, counts, base, base, k, GROW_PAD * GROW_PROBE_PAD)


def grown_caps(status, counts, caps, base, k, pad=GROW_PAD):
    """Caps for the next chunks of ``k`` cells after one whose cells had ``status, counts``.

    None (keep ``caps``) unless :data:`GROW_SHARE` of the chunk, and :data:`GROW_LEAST`
    cells, overflowed their output slots with known counts; else the output slots cover
    the most they needed (padded by ``pad``, at most :data:`GROW_MOST` times ``base``'s) and the
    scratch grows in proportion (as :func:`big_cell`'s). None when that is no bigger or
    its slots would pass :data:`GROW_BYTES`.
    """
    over = (status == OVERFLOW) & (counts[:, 0] > 0)
    m = int(np.count_nonzero(over))
    if m < GROW_LEAST or m < GROW_SHARE * len(status):
        return None
    need = counts[over].max(axis=0)
    out = [min(max(caps[q], int(np.ceil(need[q] * pad))), base[q] * GROW_MOST) for q in range(3)]
    if all(out[q] <= caps[q] for q in range(3)):
        return None
    grown = tuple(out) + tuple(
        max(caps[3 + q], -(-base[3 + q] * out[q] // base[q])) for q in range(3)
    )
    grown += tuple(caps[6:])
    if slot_bytes(k, grown) > GROW_BYTES:
        return None
    return grown


def big_cell(i, P, W, search, order, tree, t, out, wmax, need, gone, bv, keep, base, factor, run):
    """Build cell ``i`` alone with big slots, growing until it fits, and join it.

    ``search = (start, SP, SW, sidx, g, big)`` (:mod:`.lists3d`); scratch holds twice
    ``need`` (its ``(nv, nf, nr)``), at least ``factor`` times the caps ``base``, and the
    output slots as much as the scratch: a cell whose cut fits its scratch fits them, so it
    is searched again only when its scratch overflowed (a heavy site's cell of 3,914
    vertices was searched twice here, the first time for its counts alone). ``gone``:
    :func:`.build3d._run`'s, which is ``run``; ``bv``: :mod:`.bigvertex3d`'s. ``keep``:
    scratch kept between calls, by slot size and grid (a helix's cells all came here).
    """
    *s, big = search
    big = bv.search(i) if bv is not None and big is None else big
    need = [0, 0, 0] if need is None else [int(x) for x in need]
    while True:  # (growing by 4 alone built a sphere's centre cell, 8,000 vertices, 5 times)
        scratch = tuple(max(base[3 + q] * factor, need[q] * 2) for q in range(3))
        caps = scratch + scratch + tuple(base[6:])
        scr = keep.setdefault((caps, s[4].tobytes()), {})
        st, counts, v, c, r2, sl, capa = run(
            np.array([i]), P, W, *s, order, tree, t, caps, None, None, scr, wmax, big, gone
        )
        if st[0] == OVERFLOW and factor == 16 and big is None and bv and bv.find(i, scr):
            big = bv.search(i)  # its owners overflowed the widest table: a big vertex
            continue
        # (a sphere's centre cell of 40,000 faces needs the slots of its counts at 1024)
        if st[0] != OVERFLOW or factor >= 1024:
            break
        need = [max(need[q], int(counts[0, q])) for q in range(3)]
        factor *= 4
    if st[0] == OVERFLOW:
        raise RuntimeError(f"3D cell {int(i)} has more than {caps[0]} vertices")
    out.add(st, counts, sl, capa)
    return st[0], counts[0], v[0], c[0], r2[0]


def minus_ones(size, dtype):
    """``np.full(size, -1, dtype)`` in 4 KB pages (:func:`small_pages`): the join's table."""
    a = np.empty(size, dtype)  # noqa: TID251 - filled at once
    small_pages(a)
    a.fill(-1)
    return a
