"""Tiled Voronoi diagrams on dask.distributed, GeoParquet out (the ``scale`` extra).

:func:`voronoi` computes the cells of :func:`voroforge.voronoi` on inputs too big for one
process, as tiles with certified halos on a dask.distributed cluster (the current client, or
a LocalCluster started for the call), and writes one GeoParquet 1.1 partition per tile;
:func:`read` reads them back with their spatial partitions; :func:`lloyd` relaxes sites
(Lloyd's algorithm, :func:`voroforge.lloyd` in tiles). Imported only when used:
``import voroforge`` never imports dask.

Examples
--------
>>> import numpy as np
>>> from voroforge import scale
>>> pts = np.random.default_rng(0).random((100_000, 2))
>>> res = scale.voronoi(pts, (0, 0, 1, 1), out="cells.parquet", tiles=8)  # doctest: +SKIP
>>> cells = scale.read("cells.parquet", bbox=(0.4, 0.4, 0.6, 0.6))  # doctest: +SKIP
"""

from __future__ import annotations

from .cluster import local_cluster
from .dataset import partitions, read
from .job import ScaleResult, voronoi
from .lloyd import ScaleRelaxation, lloyd

__all__ = [
    "ScaleRelaxation",
    "ScaleResult",
    "local_cluster",
    "lloyd",
    "partitions",
    "read",
    "voronoi",
]
