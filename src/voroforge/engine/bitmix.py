"""64-bit mixing of bit patterns, for hashed tables of float rows (numpy, no numba)."""

from __future__ import annotations

import numpy as np


def splitmix64(x: np.ndarray) -> np.ndarray:
    """splitmix64's finaliser of ``uint64`` array ``x``, in place; returns ``x``.

    Every input bit moves every output bit.
    """
    with np.errstate(over="ignore"):
        x ^= x >> np.uint64(30)
        x *= np.uint64(0xBF58476D1CE4E5B9)
        x ^= x >> np.uint64(27)
        x *= np.uint64(0x94D049BB133111EB)
        x ^= x >> np.uint64(31)
    return x
