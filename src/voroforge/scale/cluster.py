"""The LocalCluster a tiled job starts when it is given no client.

One single-threaded worker process per core (a tile is one numba thread: processes, not
threads, keep the tiles from sharing a GIL), with dask's per-process housekeeping slowed
down and glibc's allocator left to reuse memory (see ``CLUSTER_CONFIG``): the workers'
statistical profiler (a thread that takes the GIL every 10 ms to sample
the stack) is off, and the event loops' health tick and the system monitor run less often.
On a small machine these run on the same cores as the tiles. :func:`voroforge.scale.voronoi`,
``voroforge scale`` and ``benchmarks/bench_scale.py`` use it; a cluster of your own keeps
its settings.
"""

from __future__ import annotations

import logging
import os

from .. import config

__all__ = ["CLUSTER_CONFIG", "check_local_workers", "local_cluster"]

#: dask settings under which :func:`local_cluster` starts its scheduler and workers.
CLUSTER_CONFIG = {
    # dask starts workers with MALLOC_TRIM_THRESHOLD_=65536, which also fixes glibc's mmap
    # threshold at 128 KiB: every array of a tile is then mapped and unmapped, and its pages
    # faulted in and zeroed again (30% more CPU per tile, measured). These two are the
    # values glibc's own adaptive thresholds reach (32 MiB, twice that to trim).
    "distributed.nanny.pre-spawn-environ.MALLOC_MMAP_THRESHOLD_": 32 * 2**20,
    "distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_": 64 * 2**20,
    "distributed.worker.profile.enabled": False,
    "distributed.admin.tick.interval": "500ms",
    "distributed.admin.system-monitor.interval": "2s",
}


def check_local_workers(workers, cores: int | None = None) -> None:
    """Refuse a worker count a local machine cannot start (before any process starts).

    Raises
    ------
    ValueError
        ``workers`` below 1 or above ``config.SCALE_LOCAL_WORKERS_PER_CORE`` per core.
    """
    if workers is None:
        return
    cores = max(1, os.cpu_count() or 1) if cores is None else cores
    most = config.SCALE_LOCAL_WORKERS_PER_CORE * cores
    if int(workers) < 1:
        raise ValueError(f"workers must be at least 1; got {workers}")
    if int(workers) > most:
        raise ValueError(
            f"workers: at most {most} local worker processes on {cores} cores "
            f"({config.SCALE_LOCAL_WORKERS_PER_CORE} a core); got {workers} (use --scheduler "
            "for a bigger cluster)"
        )


def local_cluster(workers: int | None = None, **kwargs):
    """A ``distributed.LocalCluster`` of ``workers`` single-threaded processes.

    Parameters
    ----------
    workers : int, optional
        Worker processes (default: one per core).
    **kwargs
        Passed to ``LocalCluster`` (e.g. ``dashboard_address``, ``memory_limit``).

    Returns
    -------
    distributed.LocalCluster
        Close it (or use it as a context manager) when done.
    """
    import dask
    from distributed import LocalCluster

    cores = max(1, os.cpu_count() or 1)
    check_local_workers(workers, cores)
    n = int(workers) if workers is not None else cores
    options = {"silence_logs": logging.ERROR, **kwargs}
    with dask.config.set(CLUSTER_CONFIG):
        return LocalCluster(n_workers=n, threads_per_worker=1, processes=True, **options)
