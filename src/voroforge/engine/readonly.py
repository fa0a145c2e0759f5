"""Read-only views of the arrays handed to compiled kernels: one numba type per argument.

numba types an array's writeable flag: a kernel handed a read-only array on one path (a
frozen diagram's sites, weights, vertices, buffers) and a writeable one on another (a fresh
array) compiles a second specialisation, and with it every kernel it calls (the power cells'
tree: ~24 s of compile per variant). The engine hands a kernel an input it does not write
through :func:`readonly`, whoever made the array, so every path reaches the same compiled
code. The view shares the array's memory (no copy) and leaves the caller's flag alone.
"""

from __future__ import annotations

import numpy as np


def readonly(a, dtype=None) -> np.ndarray:
    """A read-only view of ``a`` as a C-contiguous array of ``dtype`` (default: its own).

    ``a`` is copied only where ``np.ascontiguousarray`` copies it (another dtype, or not
    contiguous); the caller's array keeps its flags.

    Examples
    --------
    >>> a = np.arange(3.0)
    >>> r = readonly(a)
    >>> r.flags.writeable, a.flags.writeable, np.shares_memory(a, r)
    (False, True, True)
    """
    v = np.ascontiguousarray(a, dtype=dtype).view()
    v.flags.writeable = False
    return v
