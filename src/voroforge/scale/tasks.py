"""What the workers run: chunk statistics and the tiles (the buckets: :mod:`.buckets`).

A tile loads the sites of its halo-grown rectangle from the bucket files (sorted by input
row, so the engine sees them in the global order), runs :func:`voroforge.voronoi` with
the global domain, and keeps the cells of its own sites whose certificate holds: every site
closer to the cell's site than ``2 R`` (``R`` its farthest vertex distance) is loaded. Then no
missing site can reach the cell (a site at distance ``> 2 R`` has its bisector beyond the
cell), so the cell, its neighbours and, by the vertex rule (a vertex is computed from its
owner triple alone), its vertex bits are those of the single-process diagram. Cells that
fail are recomputed with the sites of the disc of radius ``2 R``: a recomputed cell can only
shrink, so that disc certifies it.
"""

from __future__ import annotations

import time
from contextlib import contextmanager
from dataclasses import dataclass

import numpy as np

from ..config import SCALE_CERT_RTOL
from ..engine.readonly import readonly
from ..kernels.moments import farthest

__all__ = [
    "Piece",
    "chunk_stats",
    "compute_cells",
    "radii",
    "run_tile",
    "split_by_tile",
    "take",
]


@dataclass
class Piece:
    """Sites with their input rows (increasing) and, for owned pieces, their attributes."""

    ids: np.ndarray
    xy: np.ndarray
    attrs: object = None


def _load(chunk, block):
    xy, attrs = chunk.load(block)
    return xy, attrs


def chunk_stats(chunk, block, sample_size: int, seed: int):
    """Counts, extent, non-finite rows, a checksum and a sample of one chunk."""
    xy, _ = _load(chunk, block)
    bad = np.flatnonzero(~np.isfinite(xy).all(axis=1))
    good = xy if not len(bad) else np.delete(xy, bad, axis=0)
    rng = np.random.default_rng(seed)
    k = min(len(good), sample_size)
    sample = good[rng.choice(len(good), size=k, replace=False)] if k else np.zeros((0, 2))
    return {
        "n": len(xy),
        "bad": (chunk.start + bad[:20]).tolist(),
        "bad_count": len(bad),
        "lo": good.min(axis=0).tolist() if len(good) else None,
        "hi": good.max(axis=0).tolist() if len(good) else None,
        "checksum": [float(v).hex() for v in _sum(good)] if len(good) else None,
        "sample": sample,
    }


def _sum(xy):
    """Column sums (a fingerprint: past ~1.8e308 they are infinite, which still fingerprints)."""
    with np.errstate(over="ignore", invalid="ignore"):
        return xy.sum(axis=0)


def split_by_tile(ids, xy, attrs, tiling):
    """``(counts (t,), pieces)``: sites split by owning tile, keeping their order in each."""
    tile = tiling.assign(xy) if len(xy) else np.zeros(0, np.int64)
    order = np.argsort(tile, kind="stable")  # stable: rows stay increasing within a tile
    counts = np.bincount(tile, minlength=len(tiling))
    ends = np.cumsum(counts)
    pieces = []
    for t in range(len(tiling)):
        if not counts[t]:
            pieces.append(None)
            continue
        rows = order[ends[t] - counts[t] : ends[t]]
        sub = None if attrs is None else attrs.take(rows)
        pieces.append(Piece(ids[rows], np.ascontiguousarray(xy[rows]), sub))
    return counts, pieces


def take(split, t):
    """Tile ``t``'s piece of a :func:`chunk_split` result."""
    return split[1][t]


def gather_sites(pieces, rect):
    """Sites of ``pieces`` inside the closed ``rect``, sorted by input row."""
    ids, xy = [], []
    x0, y0, x1, y1 = rect
    for p in pieces:
        m = (p.xy[:, 0] >= x0) & (p.xy[:, 0] <= x1) & (p.xy[:, 1] >= y0) & (p.xy[:, 1] <= y1)
        ids.append(p.ids[m])
        xy.append(p.xy[m])
    ids = np.concatenate(ids) if ids else np.zeros(0, np.int64)
    xy = np.concatenate(xy) if xy else np.zeros((0, 2))
    order = np.argsort(ids, kind="stable")
    return ids[order], np.ascontiguousarray(xy[order])


def radii(d, xy):
    """Each cell's farthest vertex distance from its site (0 for an empty cell)."""
    from ..engine.diagram import buffers

    coords, ring, poly, geom = buffers(d)
    start = np.ascontiguousarray(ring[poly[geom]], dtype=np.int64)
    # read-only views, as engine.planar passes them (one compiled farthest)
    return farthest(readonly(coords, np.float64), start, readonly(xy, np.float64))


def certified_sites(xy, r, loaded):
    """True where the disc of radius ``2 r`` (with slack) around ``xy`` lies in ``loaded``."""
    reach = 2.0 * r * (1.0 + SCALE_CERT_RTOL)
    x0, y0, x1, y1 = loaded
    return (
        (xy[:, 0] - reach > x0)
        & (xy[:, 0] + reach < x1)
        & (xy[:, 1] - reach > y0)
        & (xy[:, 1] + reach < y1)
    )


def open_sides(rect, lo, hi):
    """``rect`` with the sides beyond the sites' extent ``lo..hi`` opened to infinity."""
    x0, y0, x1, y1 = (float(v) for v in rect)
    inf = float("inf")
    return (
        -inf if x0 < lo[0] else x0,
        -inf if y0 < lo[1] else y0,
        inf if x1 > hi[0] else x1,
        inf if y1 > hi[1] else y1,
    )


@contextmanager
def limit_threads():
    """Limit numba to the worker's threads (one thread per worker: one numba thread)."""
    import numba

    try:
        from distributed import get_worker

        want = int(get_worker().state.nthreads)
    except (ImportError, ValueError, AttributeError):
        want = numba.get_num_threads()
    before = numba.get_num_threads()
    numba.set_num_threads(max(1, min(want, numba.config.NUMBA_NUM_THREADS)))
    try:
        yield
    finally:
        numba.set_num_threads(before)


def compute_cells(ids, xy, boundary, loaded, wanted, last=False):
    """Cells of ``wanted`` (local rows) among sites ``xy``: certified table part + the rest.

    With ``last`` the uncertified cells go into the table too (they are reported).
    """
    import voroforge as vf

    from ..engine.diagram import buffers, convex_reach
    from ..io.parquet import cells_table, neighbor_lists

    d = vf.voronoi(xy, boundary)
    polygon = hasattr(boundary, "geom_type")  # a shapely Polygon/MultiPolygon, not a box
    # on a polygon domain a cell is its convex ring (the cell of the domain's box) clipped by
    # GEOS, which computes a crossing inside the box (a hole's edge, a gap between parts)
    # from the ring edge's two vertices: the outer one may lie beyond twice the clipped
    # cell's radius, where a site still moves the crossing's last bit (checker7 R1); the
    # ring's radius, which the build keeps, certifies every bit
    r = convex_reach(d) if polygon else radii(d, xy)
    ok = certified_sites(xy[wanted], r[wanted], loaded)
    keep = wanted if last else wanted[ok]
    nb = neighbor_lists(d.edges.pairs, len(xy), cells=keep, ids=ids)
    table, _, _ = cells_table(buffers(d), keep, ids[keep], nb)
    bad = wanted[~ok]
    return table, (ids[bad], xy[bad], r[bad])


def run_tile(t, spec, store, tiling):
    """Tile ``t``: read its sites and halo, compute, certify, recompute, write its file.

    The tile reads the sites of its loaded region ``spec["loaded"]`` (its own and the halo
    copies the bucket tasks made) from the bucket files (``store``, a
    :class:`~voroforge.scale.buckets.Store`), computes its own sites' cells, and recomputes
    the cells whose certificate fails, grouped where their discs overlap, with all the sites
    of their discs (read from the tiles the discs reach), for up to ``spec["max_rounds"]``
    rounds. Writes the tile's file; returns its info (a small dict).
    """
    t0 = time.perf_counter()
    lo, hi, boundary = spec["lo"], spec["hi"], spec["boundary"]
    with limit_threads():
        (own_ids, own_xy), (halo_ids, halo_xy) = store.loaded(t)
        own = Piece(own_ids, own_xy)
        ids = np.concatenate((own_ids, halo_ids))
        order = np.argsort(ids, kind="stable")
        ids = ids[order]
        xy = np.concatenate((own_xy, halo_xy))[order]
        wanted = np.flatnonzero(order < len(own_ids))
        loaded_sites = len(ids)
        del halo_ids, halo_xy, order
        if len(own.ids) == 0:
            table, pending = _compute_empty()
        else:
            loaded = open_sides(spec["loaded"], lo, hi)
            table, pending = compute_cells(ids, xy, boundary, loaded, wanted)
        del ids, xy
        tables = [table]
        first = len(pending[0])
        rounds = 0
        pieces = {t: own}
        while len(pending[0]) and rounds < spec["max_rounds"]:
            rounds += 1
            last = rounds >= spec["max_rounds"]
            ids_u, xy_u, r_u = pending
            boxes, member = group_discs(xy_u, r_u)
            reach = [tiling.touching(box) for box in boxes]
            missing = {int(u) for r in reach for u in r} - pieces.keys()
            if missing:
                pieces.update({u: Piece(*p) for u, p in store.owned(missing).items()})
            left = ([], [], [])
            for g, box in enumerate(boxes):
                ids_b, xy_b = gather_sites([pieces[int(u)] for u in reach[g]], box)
                wanted = np.flatnonzero(np.isin(ids_b, ids_u[member == g], assume_unique=True))
                part, more = compute_cells(
                    ids_b, xy_b, boundary, open_sides(box, lo, hi), wanted, last
                )
                tables.append(part)
                for acc, new in zip(left, more, strict=True):
                    acc.append(new)
            pending = tuple(np.concatenate(a) for a in left)
    info = {
        "tile": t,
        "loaded_sites": loaded_sites,
        "owned": len(own.ids),
        "first_uncertified": first,
        "rounds": rounds,
        "uncertified_ids": pending[0].tolist() if len(pending[0]) else [],
    }
    info["seconds"] = time.perf_counter() - t0  # stored in the file: compute only
    info = _finish(t, spec, tables, Piece(own.ids, own.xy, store.attributes(t)), info)
    info["seconds"] = time.perf_counter() - t0  # returned: with the write
    return info


def _compute_empty():
    import pyarrow as pa  # noqa: F401 - the schema comes from cells_table on no cells

    from ..io.parquet import cells_table

    z = np.zeros(1, dtype=np.int64)
    bufs = (np.zeros((0, 2)), z, z.copy(), z.copy())
    table, _, _ = cells_table(bufs, np.zeros(0, np.int64), [], (z, np.zeros(0, np.int64)))
    empty = np.zeros(0, np.int64)
    return table, (empty, np.zeros((0, 2)), np.zeros(0))


def group_discs(xy, r):
    """Boxes of the discs ``(xy, 2 r)``, merged while they overlap: one recomputation each.

    Returns ``(boxes (g, 4), member (k,) int64)``: disc ``i`` is recomputed in box
    ``member[i]``, which contains it with a little more slack than the certificate asks.
    """
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    reach = 2.0 * r * (1.0 + 4 * SCALE_CERT_RTOL) + 4 * np.spacing(np.abs(xy).max(axis=1) + r)
    boxes = np.column_stack((xy - reach[:, None], xy + reach[:, None]))
    member = np.arange(len(xy))
    while len(boxes) > 1:
        b = boxes
        over = (
            (b[:, None, 0] <= b[None, :, 2])
            & (b[:, None, 2] >= b[None, :, 0])
            & (b[:, None, 1] <= b[None, :, 3])
            & (b[:, None, 3] >= b[None, :, 1])
        )
        i, j = np.nonzero(over)
        k, label = connected_components(coo_matrix((np.ones(len(i)), (i, j)), shape=over.shape))
        if k == len(b):
            break
        merged = np.zeros((k, 4))
        merged[:, :2] = np.inf
        merged[:, 2:] = -np.inf
        np.minimum.at(merged[:, 0], label, b[:, 0])
        np.minimum.at(merged[:, 1], label, b[:, 1])
        np.maximum.at(merged[:, 2], label, b[:, 2])
        np.maximum.at(merged[:, 3], label, b[:, 3])
        boxes = merged
        member = label[member]
    return boxes, member


def _merged(tables):
    """The tables of a tile's rounds as one, sorted by ``site_id``.

    The first round's table is sorted and holds nearly every cell; the few recomputed rows
    are slotted in between slices of it (zero-copy) rather than sorting the whole table.
    """
    import pyarrow as pa

    first = tables[0]
    rest = pa.concat_tables(tables[1:]) if len(tables) > 1 else first.slice(0, 0)
    if len(rest) > 1:
        rest = rest.take(np.argsort(rest.column("site_id").to_numpy(), kind="stable"))
    a = first.column("site_id").to_numpy()
    b = rest.column("site_id").to_numpy()
    if not len(b):
        return first
    if len(b) > 1000:  # many recomputations (tiny tiles): one sort
        both = pa.concat_tables([first, rest])
        return both.take(np.argsort(np.concatenate((a, b)), kind="stable"))
    at = np.searchsorted(a, b)
    parts, prev = [], 0
    for j, k in enumerate(at):
        parts.append(first.slice(prev, int(k) - prev))
        parts.append(rest.slice(j, 1))
        prev = int(k)
    parts.append(first.slice(prev))
    return pa.concat_tables([p for p in parts if len(p)])


def _finish(t, spec, tables, own, info):
    """Sort the tile's cells by site, add the attributes and write its partition file."""
    from ..io.parquet import geo_metadata, write_table

    table = _merged(tables)
    if len(table) != len(own.ids) or not np.array_equal(
        table.column("site_id").to_numpy(), own.ids
    ):
        raise RuntimeError(f"tile {t}: cells do not match the tile's sites")  # a bug, not input
    if own.attrs is not None:
        for name in own.attrs.column_names:
            table = table.append_column(name, own.attrs.column(name))
    bbox = table.column("bbox").combine_chunks()
    xs = [bbox.field(k).to_numpy(zero_copy_only=False) for k in ("xmin", "ymin", "xmax", "ymax")]
    full = ~np.isnan(xs[0])
    extent = (
        [
            float(xs[0][full].min()),
            float(xs[1][full].min()),
            float(xs[2][full].max()),
            float(xs[3][full].max()),
        ]
        if full.any()
        else [float("nan")] * 4
    )
    geoms = table.column("geometry")
    types = _types(geoms)
    bad = info.pop("uncertified_ids", [])
    info = {**info, "rows": len(table), "extent": extent, "file": spec["file"]}
    info["uncertified"] = len(bad)
    info["uncertified_ids"] = bad[:100]
    write_table(
        table,
        spec["path"],
        geo_metadata(extent, types, spec["crs"]),
        extra={"voroforge_tile": info},
    )
    return info


def _types(geoms):
    """Geometry types present in a WKB column (the type word after the byte-order byte)."""
    import pyarrow as pa
    import pyarrow.compute as pc

    if len(geoms) == 0:
        return []
    head = pc.binary_slice(geoms, 1, 2) if hasattr(pc, "binary_slice") else None
    if head is None:  # pragma: no cover - older pyarrow
        kinds = {bytes(v.as_py())[1] for v in geoms}
    else:
        kinds = {v[0] for v in pc.unique(pa.chunked_array(head.chunks)).to_pylist()}
    return [name for code, name in ((3, "Polygon"), (6, "MultiPolygon")) if code in kinds]
