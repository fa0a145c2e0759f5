"""Reading a tiled job's output back: :func:`read`, with its spatial partitions.

The partition files are plain GeoParquet 1.1 (geopandas, GDAL, DuckDB read them; the folder
is a Parquet dataset with ``_metadata``). :func:`read` adds what generic readers lose
(dask-geopandas#260): the extent of every partition, from the job manifest, so a query
window reads only the files it meets and, inside them, only the rows whose ``bbox`` meets it.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from .job import MANIFEST

__all__ = ["partitions", "read"]


def partitions(path):
    """The partitions of a finished job: ``[(file, extent (xmin, ymin, xmax, ymax), rows)]``.

    Parameters
    ----------
    path : str or Path
        The output folder of :func:`voroforge.scale.voronoi`.

    Returns
    -------
    list of tuple
    """
    path = Path(path)
    man = path / MANIFEST
    if not man.is_file():
        raise ValueError(f"{path}: not the output of voroforge.scale.voronoi (no {MANIFEST})")
    manifest = json.loads(man.read_text())
    if not manifest.get("complete"):
        raise ValueError(f"{path}: the job has not finished (rerun it to resume)")
    return [(t["file"], tuple(t["extent"]), t["rows"]) for t in manifest["tiles"]]


def _meets(extent, box):
    return not (
        np.isnan(extent[0])
        or extent[0] > box[2]
        or extent[2] < box[0]
        or extent[1] > box[3]
        or extent[3] < box[1]
    )


def read(path, *, bbox=None, columns=None, arrow: bool = False):
    """Cells written by :func:`voroforge.scale.voronoi`, optionally only those meeting ``bbox``.

    Parameters
    ----------
    path : str or Path
        The output folder.
    bbox : (xmin, ymin, xmax, ymax), optional
        Keep the cells whose bounding box meets this window: partitions are skipped by their
        extent, rows by the ``bbox`` column (pushed down to the row groups' statistics).
    columns : list of str, optional
        Columns to read (``geometry`` and ``bbox`` are added).
    arrow : bool
        Return a pyarrow Table instead of a GeoDataFrame.

    Returns
    -------
    geopandas.GeoDataFrame or pyarrow.Table
        Rows ordered by partition, then ``site_id``; the ``bbox`` column kept (a struct).
        ``.attrs["spatial_partitions"]`` (GeoDataFrame) or the schema metadata key
        ``voroforge_partitions`` (Table) holds the extents of the partitions read, in order,
        with ``.attrs["partition_rows"]`` their row counts.
    """
    import pyarrow as pa
    import pyarrow.compute as pc
    import pyarrow.dataset as ds

    path = Path(path)
    parts = partitions(path)
    if bbox is not None:
        box = tuple(float(v) for v in bbox)
        if len(box) != 4 or not box[0] <= box[2] or not box[1] <= box[3]:
            raise ValueError(f"bbox must be (xmin, ymin, xmax, ymax); got {bbox}")
        parts = [p for p in parts if _meets(p[1], box)]
    files = [str(path / p[0]) for p in parts]
    cols = None
    if columns is not None:
        cols = list(dict.fromkeys(["site_id", *columns, "geometry", "bbox"]))
    tables = []
    rows = []
    for f in files:
        dset = ds.dataset(f, format="parquet")
        flt = None
        if bbox is not None:
            b = pc.field("bbox")
            flt = (
                (pc.struct_field(b, "xmin") <= box[2])
                & (pc.struct_field(b, "xmax") >= box[0])
                & (pc.struct_field(b, "ymin") <= box[3])
                & (pc.struct_field(b, "ymax") >= box[1])
            )
        tab = dset.to_table(columns=cols, filter=flt)
        tables.append(tab)
        rows.append(tab.num_rows)
    if tables:
        table = pa.concat_tables(tables)
    else:
        import pyarrow.parquet as pq

        table = pq.read_schema(path / "_common_metadata").empty_table()
        if cols:
            table = table.select(cols)
    extents = [list(p[1]) for p in parts]
    geo = json.loads((table.schema.metadata or {}).get(b"geo", b"{}") or b"{}")
    meta = dict(table.schema.metadata or {})
    meta[b"voroforge_partitions"] = json.dumps({"extents": extents, "rows": rows}).encode()
    table = table.replace_schema_metadata(meta)
    if arrow:
        return table
    return _to_geopandas(table, geo, extents, rows)


def _to_geopandas(table, geo, extents, rows):
    import geopandas as gpd
    import pandas as pd
    import shapely

    crs = geo.get("columns", {}).get("geometry", {}).get("crs")
    struct = table.schema.field("bbox").type
    frame = table.drop_columns(["geometry"]).to_pandas(
        types_mapper={struct: pd.ArrowDtype(struct)}.get
    )
    geoms = shapely.from_wkb(table.column("geometry").to_numpy(zero_copy_only=False))
    gdf = gpd.GeoDataFrame(frame, geometry=geoms, crs=crs)
    boxes = [shapely.box(*e) if not np.isnan(e[0]) else shapely.Polygon() for e in extents]
    gdf.attrs["spatial_partitions"] = gpd.GeoSeries(boxes, crs=crs)
    gdf.attrs["partition_rows"] = list(rows)
    return gdf
