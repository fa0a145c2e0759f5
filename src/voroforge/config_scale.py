"""Settings of :mod:`voroforge.scale` (tiled Voronoi on dask.distributed).

Re-exported by :mod:`voroforge.config`, so modules import them from ``config``.
"""

__all__ = [
    "SCALE_CERT_RTOL",
    "SCALE_CHUNK_ROWS",
    "SCALE_HALO_SPACINGS",
    "SCALE_LOCAL_WORKERS_PER_CORE",
    "SCALE_MAX_ROUNDS",
    "SCALE_SAMPLE_SITES",
    "SCALE_TILE_SITES",
]

#: First halo of a tile, in mean site spacings of the tile (sqrt(area / sites)): most cells of a
#: Poisson tile are certified by it; the rest are recomputed with the halo their own bound asks.
SCALE_HALO_SPACINGS = 3.0
#: Relative slack on the certificate: a cell is final only when every site nearer than
#: (2 + this) times its farthest vertex distance is loaded (the inequality is then strict).
SCALE_CERT_RTOL = 1e-9
#: Rounds of recomputation before a cell is reported uncertified (one is enough in exact
#: arithmetic: a recomputed cell can only shrink, so its own bound covers it).
SCALE_MAX_ROUNDS = 4
#: Sites per tile when neither ``tiles`` nor ``tile_size`` is given.
SCALE_TILE_SITES = 250_000
#: Input rows per chunk read by one task (a .npy slice, Parquet row groups of a CSV).
SCALE_CHUNK_ROWS = 1_000_000
#: Sites sampled (over all chunks) to place the k-d tile splits.
SCALE_SAMPLE_SITES = 200_000
#: A LocalCluster starts one Python process a worker: at most this many a core (``--workers
#: 100000`` started processes for minutes with no output; a remote ``--scheduler`` has no cap).
SCALE_LOCAL_WORKERS_PER_CORE = 4
