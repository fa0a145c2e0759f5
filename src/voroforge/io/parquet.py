"""GeoParquet out: Voronoi cells as GeoParquet 1.1 (WKB geometry, a bbox covering, CRS).

One row per cell: ``site_id`` (the input row), ``geometry`` (WKB Polygon, MultiPolygon for a
cell the domain split, an empty Polygon for a duplicate or a site whose cell misses the
domain), ``area``, ``neighbors`` (a list of site ids) and ``bbox`` (a struct of ``xmin, ymin,
xmax, ymax``: the GeoParquet 1.1 covering that lets readers skip row groups), then any
attribute columns. Every ring starts at its lowest ``(x, y)`` vertex and areas are summed in
that order, so a cell's bytes depend only on the cell, not on how it was computed. The WKB
is written straight from the diagram's GeoArrow buffers by one compiled pass, without
shapely objects. Files are written atomically (temp + rename).

pyarrow is imported on first use (the ``scale`` extra); :func:`write_cells` is what
``voroforge voronoi -o cells.parquet`` calls.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
from numba import njit

from ..config import NJIT
from ..engine.readonly import readonly
from .atomic import write_atomically

__all__ = [
    "GEOPARQUET_VERSION",
    "cell_wkb",
    "cells_table",
    "geo_metadata",
    "neighbor_lists",
    "write_cells",
    "write_table",
]

#: The GeoParquet specification version written in the ``geo`` metadata.
GEOPARQUET_VERSION = "1.1.0"

#: Rows per Parquet row group: small enough for the bbox statistics to prune reads.
ROW_GROUP_SIZE = 65536

#: The columns :func:`cells_table` makes, in order (attributes follow).
CELL_COLUMNS = ("site_id", "geometry", "area", "neighbors", "bbox")


@njit(**NJIT)
def _wkb_pass(
    xy, bits, ring, poly, geom, cells, out, offsets, bbox, area, fill
):  # pragma: no cover
    """Sizes (``fill`` False) or bytes (``fill`` True) of the WKB of ``cells``.

    ``bits`` is the ``uint64`` view of the coordinates ``xy``; one cell with one polygon is a WKB
    Polygon (type 3), with several a MultiPolygon (type 6), with none an empty Polygon.
    Little-endian throughout. Each closed ring is written from its lowest ``(x, y)``
    vertex, in its own direction; the polygons of a cell follow their outer rings' lowest
    vertices, the holes of a polygon theirs. ``bbox`` gets each cell's extent (NaN when empty) and
    ``area`` its area: shoelace sums in that ring order relative to the cell's lowest vertex,
    scaled by a power of two (exact) so no magnitude overflows; exterior rings add, holes
    subtract, whatever their orientation. So area bits, too, depend only on the cell.
    """
    pos = 0
    for c in range(len(cells)):
        i = cells[c]
        g0 = geom[i]
        g1 = geom[i + 1]
        multi = g1 - g0 > 1
        offsets[c] = pos
        if fill:
            bbox[c, 0] = np.inf
            bbox[c, 1] = np.inf
            bbox[c, 2] = -np.inf
            bbox[c, 3] = -np.inf
        header = 9
        if fill:
            out[pos] = 1
            _put_u32(out, pos + 1, 6 if multi else 3)
            _put_u32(out, pos + 5, (g1 - g0) if multi else (poly[g1] - poly[g0]))
        pos += header
        if g1 - g0 == 1 and poly[g0 + 1] - poly[g0] == 1:  # the usual cell: one ring
            pos = _put_ring(xy, bits, ring, poly[g0], out, pos, fill)
        else:
            for p in _canonical_order(xy, ring, poly, g0, g1):
                if multi:
                    if fill:
                        out[pos] = 1
                        _put_u32(out, pos + 1, np.int64(3))  # typed: a literal compiles twice
                        _put_u32(out, pos + 5, poly[p + 1] - poly[p])
                    pos += 9
                for r in _ring_order(xy, ring, poly, p):
                    pos = _put_ring(xy, bits, ring, r, out, pos, fill)
        if fill:
            if g1 == g0:
                area[c] = 0.0
                for j in range(4):
                    bbox[c, j] = np.nan
            else:
                area[c] = _cell_area(xy, ring, poly, g0, g1)
                for k in range(ring[poly[g0]], ring[poly[g1]]):
                    bbox[c, 0] = min(bbox[c, 0], xy[k, 0])
                    bbox[c, 1] = min(bbox[c, 1], xy[k, 1])
                    bbox[c, 2] = max(bbox[c, 2], xy[k, 0])
                    bbox[c, 3] = max(bbox[c, 3], xy[k, 1])
    offsets[len(cells)] = pos
    return pos


@njit(**NJIT)
def _put_ring(xy, bits, ring, r, out, pos, fill):  # pragma: no cover
    """Write ring ``r`` (count, then its closed vertices from the lowest); the new ``pos``."""
    k0 = ring[r]
    k1 = ring[r + 1]
    if fill:
        _put_u32(out, pos, k1 - k0)
    pos += 4
    if not fill:
        return pos + 16 * (k1 - k0)
    # canonical start: the lowest (x, y) vertex, so a ring's bytes do not depend on where
    # the cell builder happened to start it
    m = _lowest(xy, k0, k1 - 1)
    span = k1 - 1 - k0
    for j in range(span + 1):
        k = k0 + (m - k0 + j) % span if span > 0 else k0
        _put_u64(out, pos, bits[k, 0])
        _put_u64(out, pos + 8, bits[k, 1])
        pos += 16
    return pos


@njit(**NJIT)
def _lowest(xy, k0, k1):  # pragma: no cover
    """Index of the lowest ``(x, y)`` vertex among ``xy[k0:k1]``."""
    m = k0
    for k in range(k0 + 1, k1):
        if xy[k, 0] < xy[m, 0] or (xy[k, 0] == xy[m, 0] and xy[k, 1] < xy[m, 1]):
            m = k
    return m


@njit(**NJIT)
def _sorted_by_lowest(xy, ring, rings):  # pragma: no cover
    """``rings`` (ring indices) sorted by their lowest ``(x, y)`` vertex (insertion sort)."""
    keys = np.zeros((len(rings), 2))
    for i in range(len(rings)):
        r = rings[i]
        m = _lowest(xy, ring[r], ring[r + 1] - 1)
        keys[i, 0] = xy[m, 0]
        keys[i, 1] = xy[m, 1]
    out = rings.copy()
    for i in range(1, len(out)):
        j = i
        while j > 0 and (
            keys[j, 0] < keys[j - 1, 0]
            or (keys[j, 0] == keys[j - 1, 0] and keys[j, 1] < keys[j - 1, 1])
        ):
            keys[j, 0], keys[j - 1, 0] = keys[j - 1, 0], keys[j, 0]
            keys[j, 1], keys[j - 1, 1] = keys[j - 1, 1], keys[j, 1]
            out[j], out[j - 1] = out[j - 1], out[j]
            j -= 1
    return out


@njit(**NJIT)
def _canonical_order(xy, ring, poly, g0, g1):  # pragma: no cover
    """A cell's polygons ``g0..g1`` ordered by their outer ring's lowest vertex.

    The bytes and the area sum then depend only on the cell, not on the order in which an
    overlay happened to return its parts.
    """
    parts = np.arange(g0, g1)
    if g1 - g0 < 2:
        return parts
    outer = np.zeros(g1 - g0, dtype=np.int64)
    for i in range(g1 - g0):
        outer[i] = poly[parts[i]]
    order = _sorted_by_lowest(xy, ring, outer)
    for i in range(g1 - g0):  # outer ring index -> its polygon
        for q in range(g0, g1):
            if poly[q] == order[i]:
                parts[i] = q
    return parts


@njit(**NJIT)
def _ring_order(xy, ring, poly, p):  # pragma: no cover
    """Polygon ``p``'s rings: the outer one, then the holes by their lowest vertex."""
    rings = np.arange(poly[p], poly[p + 1])
    if len(rings) < 3:
        return rings
    rings[1:] = _sorted_by_lowest(xy, ring, rings[1:].copy())
    return rings


@njit(**NJIT)
def _cell_area(xy, ring, poly, g0, g1):  # pragma: no cover
    """Area of one cell, from its canonical rings (see :func:`_wkb_pass`)."""
    o = _lowest(xy, ring[poly[g0]], ring[poly[g1]])
    ox = xy[o, 0]
    oy = xy[o, 1]
    big = 0.0
    for k in range(ring[poly[g0]], ring[poly[g1]]):
        big = max(big, abs(xy[k, 0] - ox), abs(xy[k, 1] - oy))
    if big == 0.0:
        return 0.0
    e = math.frexp(big)[1]
    if g1 - g0 == 1 and poly[g0 + 1] - poly[g0] == 1:  # one ring: no ordering to do
        k0 = ring[poly[g0]]
        span = ring[poly[g0] + 1] - 1 - k0
        total = abs(_ring_sum(xy, k0, span, ox, oy, e)) if span >= 3 else 0.0
        return math.ldexp(0.5 * total, 2 * e)
    total = 0.0
    for p in _canonical_order(xy, ring, poly, g0, g1):
        for r in _ring_order(xy, ring, poly, p):
            k0 = ring[r]
            span = ring[r + 1] - 1 - k0
            if span < 3:
                continue
            a = _ring_sum(xy, k0, span, ox, oy, e)
            total += abs(a) if r == poly[p] else -abs(a)
    return math.ldexp(0.5 * total, 2 * e)


@njit(**NJIT)
def _ring_sum(xy, k0, span, ox, oy, e):  # pragma: no cover
    """Twice the signed area of the ring ``xy[k0:k0 + span]`` (closed), from its lowest vertex.

    Relative to ``(ox, oy)`` and scaled by ``2**-e`` (exact).
    """
    m = _lowest(xy, k0, k0 + span)
    a = 0.0
    for j in range(span):
        u = k0 + (m - k0 + j) % span
        v = k0 + (m - k0 + j + 1) % span
        x0 = math.ldexp(xy[u, 0] - ox, -e)
        y0 = math.ldexp(xy[u, 1] - oy, -e)
        x1 = math.ldexp(xy[v, 0] - ox, -e)
        y1 = math.ldexp(xy[v, 1] - oy, -e)
        a += x0 * y1 - x1 * y0
    return a


@njit(**NJIT)
def _put_u32(out, pos, v):  # pragma: no cover
    for j in range(4):
        out[pos + j] = (v >> (8 * j)) & 0xFF


@njit(**NJIT)
def _put_u64(out, pos, v):  # pragma: no cover
    for j in range(4 * 2):
        out[pos + j] = (v >> np.uint64(8 * j)) & np.uint64(0xFF)


def cell_wkb(buffers, cells=None):
    """WKB of cells straight from GeoArrow multipolygon buffers.

    Parameters
    ----------
    buffers : tuple
        ``(coords (k, 2) float64, ring, poly, geom)`` as :func:`voroforge.engine.diagram.buffers`
        gives them.
    cells : (m,) int array_like, optional
        Which cells, in output order (default: all).

    Returns
    -------
    data : (b,) uint8
        The concatenated WKB.
    offsets : (m + 1,) int64
        Cell ``c``'s WKB is ``data[offsets[c]:offsets[c + 1]]``.
    bbox : (m, 4) float64
        ``xmin, ymin, xmax, ymax`` of each cell (NaN for an empty cell).
    area : (m,) float64
        Each cell's area from its canonical rings (equal to ``Diagram.areas`` up to rounding,
        and independent of how the cell was computed).
    """
    coords, ring, poly, geom = buffers
    n = len(geom) - 1
    cells = np.arange(n, dtype=np.int64) if cells is None else np.asarray(cells, np.int64)
    xy = np.ascontiguousarray(coords, dtype=np.float64).reshape(-1, 2)
    bits = xy.view(np.uint64)
    ring, poly, geom = (np.ascontiguousarray(a, dtype=np.int64) for a in (ring, poly, geom))
    offsets = np.zeros(len(cells) + 1, dtype=np.int64)
    bbox = np.zeros((len(cells), 4))
    area = np.zeros(len(cells))
    z = np.zeros(0, np.uint8)
    size = _wkb_pass(xy, bits, ring, poly, geom, cells, z, offsets, bbox, area, False)
    data = np.zeros(size, dtype=np.uint8)
    _wkb_pass(xy, bits, ring, poly, geom, cells, data, offsets, bbox, area, True)
    return data, offsets, bbox, area


@njit(**NJIT)
def _pairs_csr(a, b, n):  # pragma: no cover
    """Symmetric CSR ``(indptr, values)`` of pairs: each row sorted, without repeats."""
    start = np.zeros(n + 1, dtype=np.int64)
    for k in range(len(a)):
        start[a[k] + 1] += 1
        start[b[k] + 1] += 1
    for i in range(n):
        start[i + 1] += start[i]
    pos = start[:-1].copy()
    raw = np.zeros(2 * len(a), dtype=np.int64)
    for k in range(len(a)):
        raw[pos[a[k]]] = b[k]
        pos[a[k]] += 1
        raw[pos[b[k]]] = a[k]
        pos[b[k]] += 1
    indptr = np.zeros(n + 1, dtype=np.int64)
    out = 0
    for i in range(n):
        k0 = start[i]
        k1 = start[i + 1]
        if k1 - k0 > 16:
            raw[k0:k1] = np.sort(raw[k0:k1])
        else:  # the usual few neighbours: insertion sort
            for j in range(k0 + 1, k1):
                v = raw[j]
                q = j
                while q > k0 and raw[q - 1] > v:
                    raw[q] = raw[q - 1]
                    q -= 1
                raw[q] = v
        for j in range(k0, k1):
            if j == k0 or raw[j] != raw[j - 1]:
                raw[out] = raw[j]
                out += 1
        indptr[i + 1] = out
    return indptr, raw[:out]


@njit(**NJIT)
def _csr_rows(indptr, values, rows):  # pragma: no cover
    """The CSR rows ``rows`` of ``(indptr, values)``, in that order."""
    offsets = np.zeros(len(rows) + 1, dtype=np.int64)
    for i in range(len(rows)):
        offsets[i + 1] = offsets[i] + indptr[rows[i] + 1] - indptr[rows[i]]
    out = np.zeros(offsets[-1], dtype=np.int64)
    for i in range(len(rows)):
        k0 = indptr[rows[i]]
        for j in range(offsets[i + 1] - offsets[i]):
            out[offsets[i] + j] = values[k0 + j]
    return offsets, out


def neighbor_lists(pairs, n: int, cells=None, ids=None):
    """Neighbour lists of ``cells`` from edge pairs, as CSR ``(offsets, values)``.

    Parameters
    ----------
    pairs : (m, 2) int
        Cell pairs sharing an edge (``Diagram.edges.pairs``; duplicates allowed).
    n : int
        Number of cells of the diagram.
    cells : (c,) int, optional
        Rows wanted, in order (default all).
    ids : (n,) int64, optional
        The name of each cell in the output (default: its index). Must be increasing, so
        the lists stay sorted (as ``Diagram.neighbors``).

    Returns
    -------
    offsets : (c + 1,) int64
    values : (·,) int64
        Sorted, distinct neighbours of each wanted cell.
    """
    # read-only views (engine.readonly): a diagram's pairs are read-only, and a column of
    # one or no pairs is no copy; numba types the flag, and _pairs_csr compiled twice
    a = readonly(pairs[:, 0], np.int64)
    b = readonly(pairs[:, 1], np.int64)
    indptr, dst = _pairs_csr(a, b, n)
    if cells is None:
        offsets, values = indptr, dst
    else:
        offsets, values = _csr_rows(indptr, dst, np.ascontiguousarray(cells, dtype=np.int64))
    if ids is not None:
        values = np.asarray(ids, dtype=np.int64)[values]
    return offsets, values


def cells_table(buffers, cells, site_ids, neighbors, attributes=None):
    """A pyarrow Table of cells in the GeoParquet column layout of this module.

    Parameters
    ----------
    buffers : tuple
        The diagram's GeoArrow buffers ``(coords, ring, poly, geom)``.
    cells : (m,) int
        Which cells of ``buffers``, in row order.
    site_ids : (m,) int64
        The ``site_id`` of each row.
    neighbors : tuple
        ``(offsets (m + 1,), values)``: each row's neighbour site ids.
    attributes : pyarrow.Table, optional
        ``m`` rows of extra columns appended after ``bbox``.

    Returns
    -------
    table : pyarrow.Table
    extent : (4,) float64
        Bounding box of all non-empty cells (NaN if none).
    types : list of str
        The geometry types present (``Polygon``, ``MultiPolygon``).
    """
    import pyarrow as pa

    data, offsets, bbox, areas = cell_wkb(buffers, cells)
    geom = buffers[3]
    parts = np.diff(geom)[np.asarray(cells, dtype=np.int64)]
    types = [
        t
        for t, has in (("Polygon", (parts <= 1).any()), ("MultiPolygon", (parts > 1).any()))
        if has
    ]
    wkb = pa.LargeBinaryArray.from_buffers(
        pa.large_binary(), len(offsets) - 1, [None, pa.py_buffer(offsets), pa.py_buffer(data)]
    )
    noff, nval = neighbors
    columns = {
        "site_id": pa.array(np.asarray(site_ids, dtype=np.int64)),
        "geometry": wkb.cast(pa.binary()) if len(data) < 2**31 - 1 else wkb,
        "area": pa.array(areas),
        "neighbors": pa.LargeListArray.from_arrays(
            pa.array(np.asarray(noff, dtype=np.int64)), pa.array(np.asarray(nval, np.int64))
        ).cast(pa.list_(pa.int64())),
        "bbox": pa.StructArray.from_arrays(
            [pa.array(np.ascontiguousarray(bbox[:, j])) for j in range(4)],
            names=["xmin", "ymin", "xmax", "ymax"],
        ),
    }
    table = pa.table(columns)
    if attributes is not None:
        for name in attributes.column_names:
            if name in columns:
                raise ValueError(f"attribute column {name!r} clashes with a cell column")
            table = table.append_column(name, attributes.column(name))
    full = ~np.isnan(bbox[:, 0])
    if full.any():
        extent = np.array(
            [bbox[full, 0].min(), bbox[full, 1].min(), bbox[full, 2].max(), bbox[full, 3].max()]
        )
    else:
        extent = np.full(4, np.nan)
    return table, extent, types


def projjson(crs):
    """The PROJJSON of ``crs`` (None: unknown, written as an explicit null).

    A dict is checked to be PROJJSON that pyproj reads (as GDAL and geopandas will) and
    written as pyproj writes it back; without pyproj it is written as given.
    """
    if crs is None:
        return None
    try:
        import pyproj
    except ImportError:  # pragma: no cover - pyproj comes with geopandas
        if isinstance(crs, dict):
            return crs
        raise ValueError("crs needs pyproj (install voroforge[scale])") from None
    try:
        return pyproj.CRS.from_user_input(crs).to_json_dict()
    except pyproj.exceptions.CRSError as exc:
        raise ValueError(f"crs {crs!r} is not a coordinate reference system: {exc}") from None


def geo_metadata(extent, types, crs=None) -> dict:
    """The GeoParquet 1.1 ``geo`` metadata of a cells table.

    Parameters
    ----------
    extent : (4,) float
        ``xmin, ymin, xmax, ymax`` of the geometries (NaN: none, then no bbox is written).
    types : list of str
        Geometry types present.
    crs : str, dict or None
        Anything ``pyproj.CRS.from_user_input`` takes, PROJJSON, or None for an unknown
        (planar, unreferenced) system: an explicit ``null``, since a missing key would mean
        longitude/latitude (OGC:CRS84).

    Returns
    -------
    dict
    """
    column = {
        "encoding": "WKB",
        "geometry_types": list(types),
        "crs": projjson(crs),
        "edges": "planar",
        "covering": {
            "bbox": {
                "xmin": ["bbox", "xmin"],
                "ymin": ["bbox", "ymin"],
                "xmax": ["bbox", "xmax"],
                "ymax": ["bbox", "ymax"],
            }
        },
    }
    if not np.isnan(np.asarray(extent, dtype=np.float64)).any():
        column["bbox"] = [float(v) for v in extent]
    return {
        "version": GEOPARQUET_VERSION,
        "primary_column": "geometry",
        "columns": {"geometry": column},
    }


def write_table(table, path, geo: dict, *, extra: dict | None = None) -> Path:
    """Write ``table`` with its ``geo`` metadata to ``path`` atomically (temp file + rename).

    Parameters
    ----------
    table : pyarrow.Table
    path : str or Path
    geo : dict
        From :func:`geo_metadata`.
    extra : dict, optional
        More key-value metadata (values JSON-encoded).

    Returns
    -------
    Path
    """
    import pyarrow.parquet as pq

    path = Path(path)
    meta = dict(table.schema.metadata or {})
    meta[b"geo"] = json.dumps(geo).encode()
    for key, value in (extra or {}).items():
        meta[key.encode()] = json.dumps(value).encode()
    table = table.replace_schema_metadata(meta)
    # no dictionaries for the cell columns (all distinct values: pyarrow tries one for each
    # column and gives up, which costs half the write); statistics where readers prune by
    # them (site_id, area, the bbox covering) and on the attributes
    names = table.column_names
    attrs = [c for c in names if c not in CELL_COLUMNS]
    stats = [c for c in names if c not in ("geometry", "neighbors", "bbox")]
    if "bbox" in names:
        stats += [f"bbox.{k}" for k in ("xmin", "ymin", "xmax", "ymax")]
    # the temporary file ends in .tmp: a scale job's folder check knows such leftovers
    return write_atomically(
        path,
        lambda tmp: pq.write_table(
            table,
            tmp,
            row_group_size=ROW_GROUP_SIZE,
            compression="zstd",
            use_dictionary=attrs or False,
            write_statistics=stats,
        ),
        suffix=".tmp",
    )


def write_cells(diagram, path, *, crs=None, attributes=None, site_ids=None) -> Path:
    """Write a diagram's cells as a GeoParquet 1.1 file.

    Parameters
    ----------
    diagram : voroforge.Diagram
        A planar diagram (periodic ones too: their cells as stored).
    path : str or Path
        The ``.parquet`` file (written atomically).
    crs : str, dict or None
        The coordinates' reference system (e.g. ``"EPSG:2056"``); None writes an explicit
        unknown CRS.
    attributes : pyarrow.Table, pandas.DataFrame or dict of arrays, optional
        One row per site, appended as columns (a join key is ``site_id`` anyway).
    site_ids : (n,) int64, optional
        The ``site_id`` column (default ``0 .. n - 1``, the input rows).

    Returns
    -------
    Path

    Examples
    --------
    >>> import numpy as np, voroforge as vf
    >>> from voroforge.io.parquet import write_cells
    >>> d = vf.voronoi(np.random.default_rng(0).random((100, 2)), (0, 0, 1, 1))
    >>> write_cells(d, "cells.parquet", crs="EPSG:3857")  # doctest: +SKIP
    """
    import pyarrow as pa

    from ..engine.diagram import buffers

    n = len(diagram)
    ids = np.arange(n, dtype=np.int64) if site_ids is None else np.asarray(site_ids, np.int64)
    if ids.shape != (n,):
        raise ValueError(f"site_ids must have shape ({n},); got {ids.shape}")
    if attributes is not None and not isinstance(attributes, pa.Table):
        attributes = (
            pa.table(attributes)
            if isinstance(attributes, dict)
            else pa.Table.from_pandas(attributes, preserve_index=False)
        )
    if attributes is not None and attributes.num_rows != n:
        raise ValueError(f"attributes have {attributes.num_rows} rows for {n} cells")
    cells = np.arange(n, dtype=np.int64)
    nb = neighbor_lists(diagram.edges.pairs, n, ids=ids if site_ids is not None else None)
    table, extent, types = cells_table(buffers(diagram), cells, ids, nb, attributes)
    return write_table(table, path, geo_metadata(extent, types, crs))
