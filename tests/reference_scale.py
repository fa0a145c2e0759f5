"""The single-process reference of the tiled diagrams and the comparison the tests make.

"Identical" (docs/scale.md): for every input row, the tiled output holds the same WKB bytes
(every vertex bit for bit, rings from their lowest vertex), the same ``area`` bits, the same
sorted ``neighbors`` and the same ``bbox`` as :func:`voroforge.voronoi` on all sites written
by :func:`voroforge.io.parquet.write_cells`. Polygon domains: cells the polygon does not cut
are identical in this sense; a cut cell has the same neighbours and its vertices within a few
ulps (Hausdorff distance below 1e-14 of the domain's size), since the engine overlays cut
cells on local pieces of the domain whose edges depend on how many cells are cut.
"""

from __future__ import annotations

import numpy as np
import pyarrow.parquet as pq

import voroforge as vf
from voroforge.io.parquet import write_cells


def single_process(points, boundary, path):
    """Table of ``vf.voronoi(points, boundary)`` as ``write_cells`` writes it."""
    write_cells(vf.voronoi(points, boundary), path)
    return pq.read_table(path)


def tiled_table(out):
    """The tiled dataset as one table sorted by site id."""
    return pq.read_table(out).sort_by("site_id")


def differences(got, ref):
    """Per column, the rows where ``got`` and ``ref`` differ (NaN equal to NaN)."""
    out = {}
    for col in ("site_id", "geometry", "area", "neighbors"):
        a = got.column(col).to_pylist()
        b = ref.column(col).to_pylist()
        out[col] = [i for i, (x, y) in enumerate(zip(a, b, strict=True)) if x != y]
    for f in ("xmin", "ymin", "xmax", "ymax"):
        a = got.column("bbox").combine_chunks().field(f).to_numpy(zero_copy_only=False)
        b = ref.column("bbox").combine_chunks().field(f).to_numpy(zero_copy_only=False)
        bad = ~((a == b) | (np.isnan(a) & np.isnan(b)))
        out.setdefault("bbox", set()).update(np.flatnonzero(bad).tolist())
    out["bbox"] = sorted(out["bbox"])
    return out
