"""When the engine's parallel kernels are worth their threads."""

from __future__ import annotations

from contextlib import contextmanager

import numba

from ..config import PARALLEL_MIN_SITES


@contextmanager
def serial_below(n: int):
    """Run numba's parallel kernels on one thread while ``n < PARALLEL_MIN_SITES``.

    Small inputs take less time than waking the thread pool, and on a loaded machine a
    parallel region can wait for a busy core far longer than the work takes (35 sites:
    0.27 s with two threads against 0.1 ms with one, measured while other jobs ran).
    Parametric loops and iterative solvers call the engine many times on small inputs.
    ``numba.set_num_threads`` is per calling thread, so this is safe under threads.
    """
    if n >= PARALLEL_MIN_SITES:
        yield
        return
    before = numba.get_num_threads()
    numba.set_num_threads(1)
    try:
        yield
    finally:
        numba.set_num_threads(before)
