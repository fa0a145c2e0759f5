"""The studio server's memory settings, so that an edit's step neither walks nor faults.

Objects alive at start-up are left out of GC (:func:`freeze_heap`), and freed memory is kept
for reuse (:func:`keep_heap`).
"""

from __future__ import annotations

import gc


def freeze_heap() -> None:
    """Leave the objects alive now (modules, compiled kernels, the first result) out of GC.

    A full collection walks every tracked object: ~150,000 after the imports, ~80 ms (170 ms
    on a loaded machine), and one came every ~15 slider steps that make all cells anew, in
    the middle of an edit (the p95 of the latency table). Frozen, a full collection walks
    only what was made since: under a millisecond.
    """
    gc.collect()
    gc.freeze()


#: glibc's mallopt parameters: M_TRIM_THRESHOLD, M_MMAP_THRESHOLD
_M_TRIM_THRESHOLD, _M_MMAP_THRESHOLD = -1, -3


def keep_heap(mmap_above: int = 64 << 20, trim_above: int = 256 << 20) -> bool:
    """Let freed memory be reused instead of handed back to the system (glibc only).

    An edit that makes every cell anew allocates numpy arrays of 0.1-2 MB by the dozen
    (140,000 fillet vertices). By default glibc maps such blocks from the system and unmaps
    them when freed (its threshold adapts, but not always), so new arrays are page-faulted
    in again: 700-3,100 faults per ``design.seed`` step of the holed 2,000-cell panel, none
    with blocks below ``mmap_above`` taken from the heap and up to ``trim_above`` bytes of
    free heap kept (four A/B runs, 24 steps each: 37-61 -> 34-49 ms CPU per step, the wire
    rings 4.6-9.7 -> 3.6-5.0 ms). Elsewhere (no glibc) nothing changes. Returns whether it
    applied.
    """
    import ctypes
    import ctypes.util
    import sys

    if not sys.platform.startswith("linux"):
        return False
    try:
        libc = ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6")
        mallopt = libc.mallopt
    except (OSError, AttributeError):  # musl has no mallopt
        return False
    mallopt.argtypes, mallopt.restype = [ctypes.c_int, ctypes.c_int], ctypes.c_int
    return bool(mallopt(_M_MMAP_THRESHOLD, mmap_above)) and bool(
        mallopt(_M_TRIM_THRESHOLD, trim_above)
    )
