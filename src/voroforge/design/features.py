"""A built design's cells as a table of features: GeoJSON and GeoParquet outputs.

Both formats write the same rows (:func:`cell_features`): one per live cell, with its index
(``cell``), the attractor field there, whether it is an opening and its recursion level;
and, when the seeds came from a file (``seeds.method = "file"``), one per row of that file
instead, in file order, with every CSV column or GeoJSON property of the row, so that GIS
users can join the result back to their data by row number. A row outside the boundary
keeps its place with an empty (``null``) geometry.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import shapely

from ..io.readers.points import attribute_names

__all__ = ["COMPUTED", "cell_features", "write_parquet"]

#: Properties the writers fill themselves; a seed-file column of that name is kept as
#: ``input_<name>`` (as ``voroforge voronoi`` does).
COMPUTED = ("index", "site", "area", "cell", "field", "opening", "level", "geometry", "bbox")


def cell_features(result) -> tuple[np.ndarray, np.ndarray | None, dict]:
    """The rows of a design's ``cells`` output.

    Parameters
    ----------
    result : voroforge.design.compute.Result

    Returns
    -------
    geoms : (r,) object array
        One geometry per row (empty for a seed-file row without a cell).
    sites : (r, 2) float64 or None
        Each row's site (None when cells and sites are not one to one: recursion, tiles).
    properties : dict of name -> (r,) sequence
    """
    one_to_one = len(result.cells) == len(result.sites) and not result.design.voronoi.periodic
    one_to_one = one_to_one and result.design.recursion.depth == 0
    table = result.extra.get("seed_table")
    if one_to_one and table is not None:
        return _seed_rows(result, table)
    keep = ~shapely.is_empty(result.cells)
    props = {
        "cell": np.flatnonzero(keep),
        "field": result.values[keep],
        "opening": result.mask[keep],
        "level": result.level[keep],
    }
    return result.cells[keep], (result.sites[keep] if one_to_one else None), props


def _seed_rows(result, table) -> tuple[np.ndarray, np.ndarray, dict]:
    """One row per row of the seed file, in file order, with every column of the row."""
    n = len(table.points)
    geoms = np.full(n, shapely.Polygon(), dtype=object)
    geoms[table.rows] = result.cells
    sites = table.points.copy()
    sites[table.rows] = result.sites  # moved by [relax]; rows outside keep their own point
    cell = np.full(n, None, dtype=object)
    cell[table.rows] = np.arange(len(table.rows))
    props: dict = {"cell": cell}
    columns = (("field", result.values), ("opening", result.mask), ("level", result.level))
    for name, values in columns:
        column = np.full(n, None, dtype=object)
        column[table.rows] = values.tolist()
        props[name] = column
    # renamed again while a name clashes ("area" beside "input_area": both kept, checker25 F3)
    names = attribute_names(list(table.attributes), COMPUTED)
    for name, column in zip(names, table.attributes.values(), strict=True):
        props[name] = column
    return geoms, sites, props


def _column(values):
    """A pyarrow array of plain Python values (numpy scalars unwrapped, NaN kept)."""
    import pyarrow as pa

    out = [v.item() if isinstance(v, np.generic) else v for v in list(values)]
    return pa.array(out)


def write_parquet(geoms, path, *, sites=None, properties=None, crs=None) -> Path:
    """Write polygons and their properties as a GeoParquet 1.1 file (WKB, bbox covering).

    Row ``i`` is geometry ``i``: columns ``index``, ``geometry`` (WKB; null for an empty
    geometry), ``bbox``, ``area``, ``site_x``/``site_y`` (with ``sites``) and the
    ``properties``, the same as the GeoJSON features of :func:`cell_features`.

    Parameters
    ----------
    geoms : (r,) sequence of shapely geometries
    path : str or Path
    sites : (r, 2) array_like, optional
    properties : dict of name -> (r,) sequence, optional
    crs : str, dict or None
        As :func:`voroforge.io.parquet.geo_metadata` takes it (a GeoJSON ``crs`` member's
        name such as ``"urn:ogc:def:crs:EPSG::2056"`` works); None writes an unknown CRS.

    Returns
    -------
    Path
    """
    try:
        import pyarrow as pa
    except ImportError:  # pragma: no cover - pyarrow comes with the scale extra
        raise ValueError("parquet output needs pyarrow: pip install 'voroforge[scale]'") from None
    from ..io.parquet import geo_metadata, write_table

    geoms = np.asarray(list(geoms), dtype=object)
    n = len(geoms)
    empty = shapely.is_empty(geoms) if n else np.zeros(0, dtype=bool)
    wkb = shapely.to_wkb(np.where(empty, None, geoms)) if n else np.zeros(0, dtype=object)
    bounds = shapely.bounds(geoms) if n else np.zeros((0, 4))
    names = ("xmin", "ymin", "xmax", "ymax")
    bbox = pa.StructArray.from_arrays(
        [pa.array(np.where(empty, np.nan, bounds[:, k]), mask=empty) for k in range(4)],
        names=list(names),
    )
    columns = {
        "index": pa.array(np.arange(n, dtype=np.int64)),
        "geometry": pa.array(list(wkb), type=pa.binary()),
        "bbox": bbox,
        "area": pa.array(shapely.area(geoms) if n else np.zeros(0)),
    }
    if sites is not None:
        xy = np.asarray(sites, dtype=np.float64).reshape(n, 2)
        columns["site_x"] = pa.array(xy[:, 0])
        columns["site_y"] = pa.array(xy[:, 1])
    for name, values in (properties or {}).items():
        if len(values) != n:
            raise ValueError(f"property {name!r} has {len(values)} values for {n} geometries")
        columns[str(name)] = _column(values)
    live = geoms[~empty]
    types = sorted({g.geom_type for g in live})
    extent = shapely.total_bounds(live) if len(live) else np.full(4, np.nan)
    return write_table(pa.table(columns), path, geo_metadata(extent, types, crs))
