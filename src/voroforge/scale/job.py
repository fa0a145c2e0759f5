"""The driver of a tiled Voronoi job on dask.distributed: :func:`voronoi`.

Steps, all as dask tasks on the client's workers: (1) every chunk reports its extent, its
non-finite rows, a checksum and a sample; (2) the sample places a k-d tiling balanced by
count, and each tile's halo of a few site spacings; (3) every chunk writes its sites
bucketed by tile, with the halo copies, to one file (the shuffle, on disk:
:mod:`~voroforge.scale.buckets`); (4) each tile reads its loaded sites, certifies its cells,
recomputes the uncertified ones with the sites their discs reach and writes its partition
file; (5) the driver writes the dataset's ``_metadata``/``_common_metadata`` and the job
manifest. Between tasks the driver only collects small results.

A partition file appears only complete (temp + rename); a rerun on the same input finds the
manifest, checks the fingerprint (row count, per-chunk checksums, boundary, tiling) and
computes only the tiles whose files are missing.
"""

from __future__ import annotations

import json
import math
import numbers
import re
import shutil
import time
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .. import config
from ..io.atomic import write_atomically
from .buckets import Store, bucket_chunk, halo_sources
from .sources import open_source
from .tasks import chunk_stats, run_tile
from .tiling import kd_tiling

__all__ = ["MANIFEST", "ScaleResult", "voronoi"]

#: The job manifest's file name inside the output folder.
MANIFEST = "_voroforge_scale.json"
#: The folder of the bucket files (the shuffle) inside the output folder, removed at the end.
SHUFFLE = "_shuffle"
_FORMAT = "voroforge-scale/1"


@dataclass
class ScaleResult:
    """Summary of a tiled job.

    Attributes
    ----------
    path : Path
        The output folder (a Parquet dataset: one ``part-NNNNN.parquet`` per tile).
    cells : int
        Rows written (one per input site).
    tiles : int
        Number of tiles.
    workers : int
        Workers of the client.
    uncertified : int
        Cells that no round could certify (0 unless something is wrong; their ids are in
        the tiles' info).
    retried : int
        Cells the first halo did not certify (recomputed with a wider one).
    resumed : int
        Tiles found finished on disk and not recomputed.
    seconds : float
        Wall time of the call.
    dashboard : str or None
        The dask dashboard's address.
    halo_copies : int
        Sites copied into other tiles' halos by the shuffle (the bucket files hold
        ``cells + halo_copies`` records of 24 bytes).
    phases : dict
        Seconds spent in each step: ``stats`` (extent, checks, sample), ``shuffle`` (split
        and merge of the chunks by tile), ``tiles`` (compute, certify, write) and
        ``metadata`` (``_metadata`` and the manifest).
    tile_info : list of dict
        Per tile: sites owned and loaded, first-round uncertified cells, rounds, seconds,
        extent, file.
    """

    path: Path
    cells: int
    tiles: int
    workers: int
    uncertified: int
    retried: int
    resumed: int
    seconds: float
    dashboard: str | None = None
    halo_copies: int = 0
    phases: dict = field(default_factory=dict)
    tile_info: list = field(default_factory=list, repr=False)


@contextmanager
def client_for(client, workers):
    """The given client, the current one, or a LocalCluster started for the call."""
    if client is not None:
        yield client
        return
    from distributed import Client, default_client

    from .cluster import local_cluster

    try:
        yield default_client()
        return
    except ValueError:
        pass
    with local_cluster(workers) as cluster, Client(cluster) as fresh:
        yield fresh


def _ours(path: Path) -> bool:
    """True when every entry of folder ``path`` is something a job writes."""
    for p in path.iterdir():
        name = p.name
        if not (
            name in (MANIFEST, "_metadata", "_common_metadata")
            or re.fullmatch(r"part-\d{5,}\.parquet", name)
            or name.startswith("_points.tmp")
            or (name == SHUFFLE and p.is_dir())
            or (name.startswith(".") and name.endswith(".tmp"))
        ):
            return False
    return True


def _prepare_out(out: Path, overwrite: bool, points=None):
    """Create ``out``; returns the manifest of an unfinished job there (to resume) or None.

    Only a folder of a job's own files is ever removed: a file at ``out`` (the points file
    itself, a report) or a dataset without the job's manifest is refused, overwrite or not.
    """
    if isinstance(points, (str, Path)):
        src = Path(points).resolve()
        if src == out.resolve() or out.resolve() in src.parents:
            raise ValueError(f"{out} is the points file or holds it; write the cells elsewhere")
    if out.exists() and not out.is_dir():
        raise ValueError(f"{out} is a file, not a dataset folder; refusing to overwrite it")
    if out.exists():
        manifest = out / MANIFEST
        if out.is_dir() and manifest.is_file():
            old = json.loads(manifest.read_text())
            if not old.get("complete") and not overwrite:
                return old
        if not overwrite:
            raise ValueError(f"{out} exists; pass overwrite=True (--overwrite) to replace it")
        if not _ours(out) or (any(out.glob("part-*")) and not manifest.is_file()):
            raise ValueError(
                f"{out} is a folder with other files (or a dataset no job of ours wrote);"
                " refusing to overwrite it"
            )
        shutil.rmtree(out)
    out.mkdir(parents=True)
    return None


def _boundary_spec(boundary):
    """``(engine boundary, manifest text)``, validated here (errors before any work)."""
    import shapely

    from ..engine.domain import make_domain

    if boundary is None:
        return None, None
    dom = make_domain(boundary, np.zeros((1, 2)))
    if isinstance(boundary, shapely.Geometry):
        return boundary, shapely.to_wkb(boundary, hex=True)
    return tuple(float(v) for v in dom.bounds), list(dom.bounds)


def _whole(name, value):
    """``value`` as an int >= 1, or ``None``; a clear error for 0, 1.5, True, "4"."""
    if value is None:
        return None
    ok = isinstance(value, numbers.Integral) and not isinstance(value, bool)
    if isinstance(value, float) and value.is_integer():
        ok = True
    if not ok or value < 1:
        raise ValueError(f"{name} must be a whole number >= 1; got {value!r}")
    return int(value)


def check_counts(tiles=None, tile_size=None, workers=None, chunk_rows=None):
    """Validate the size-like arguments of a tiled job before any work starts."""
    tiles, tile_size = _whole("tiles", tiles), _whole("tile_size", tile_size)
    if tiles is not None and tile_size is not None:
        raise ValueError(f"give tiles or tile_size, not both; got {tiles} and {tile_size}")
    return tiles, tile_size, _whole("workers", workers), _whole("chunk_rows", chunk_rows)


def tile_count(n, tiles, tile_size, workers):
    """How many tiles ``n`` sites get: ``tiles``, else from ``tile_size`` or ``workers``.

    The counts are validated first (:func:`check_counts`).
    """
    if tiles is not None:
        return int(min(tiles, max(n, 1)))
    if tile_size is not None:
        return max(1, math.ceil(n / int(tile_size)))
    return max(1, min(max(n // 1000, 1), max(math.ceil(n / config.SCALE_TILE_SITES), 2 * workers)))


def first_halo(rect, count, lo, hi):
    """The first halo of a tile: a few mean site spacings of its finite part."""
    x0, y0 = max(rect[0], lo[0]), max(rect[1], lo[1])
    x1, y1 = min(rect[2], hi[0]), min(rect[3], hi[1])
    w, h = max(x1 - x0, 0.0), max(y1 - y0, 0.0)
    if count == 0:
        return 0.0
    # sqrt(w) sqrt(h), not sqrt(w h): the area under/overflows past ~1e+-154
    spacing = math.sqrt(w) * math.sqrt(h) / math.sqrt(count)
    if spacing == 0.0:  # sites on a line: the spacing along it
        spacing = max(w, h) / count
    if spacing == 0.0:  # one point: a halo of its own magnitude's ulps
        spacing = math.ulp(max(abs(x0), abs(y0), 1e-300)) * 64
    return config.SCALE_HALO_SPACINGS * spacing


def extent_check(lo, hi, boundary, padded):
    """Refuse, before any tile runs, sites or a domain whose extent overflows float64.

    The tiling, the halos and the certificate work with widths (``hi - lo``) and the
    default domain pads the sites' box by 10% of them: past ~1.8e308 these are infinite
    and a tile would fail on a box the user never gave.
    """
    box = np.array(boundary.bounds if hasattr(boundary, "bounds") else boundary, dtype=float)
    with np.errstate(over="ignore", invalid="ignore"):
        sites = np.all(np.isfinite(hi - lo))
        domain = np.all(np.isfinite(box)) and np.all(np.isfinite(box[2:] - box[:2]))
    if sites and domain:
        return
    if not sites:
        what = "their extent"
    elif padded:
        what = "their box padded by 10% (the default domain)"
    else:
        what = "the boundary's extent"
    raise ValueError(
        f"points span x {lo[0]:g} .. {hi[0]:g}, y {lo[1]:g} .. {hi[1]:g}: {what} overflows "
        "float64 (widths past ~1.8e308); scale the coordinates down"
    )


def _grown(rect, h):
    return (rect[0] - h, rect[1] - h, rect[2] + h, rect[3] + h)


def _tile_done(path: Path):
    """The info stored in a finished partition file, or None."""
    if not path.is_file():
        return None
    import pyarrow.parquet as pq

    try:
        meta = pq.read_metadata(path).metadata or {}
    except Exception:  # a damaged file is recomputed
        return None
    raw = meta.get(b"voroforge_tile")
    return json.loads(raw) if raw else None


def _bad_rows_error(stats):
    rows = [r for s in stats for r in s["bad"]]
    total = sum(s["bad_count"] for s in stats)
    shown = ", ".join(str(r) for r in rows[:20])
    more = f" (and {total - 20} more)" if total > 20 else ""
    return ValueError(f"points contain NaN or infinite coordinates in {total} rows: {shown}{more}")


def voronoi(
    points,
    boundary=None,
    *,
    out="cells.parquet",
    tiles: int | None = None,
    tile_size: int | None = None,
    client=None,
    workers: int | None = None,
    crs=None,
    overwrite: bool = False,
    progress=None,
    chunk_rows: int | None = None,
) -> ScaleResult:
    """Voronoi cells of many sites in tiles on dask.distributed, written as GeoParquet.

    The cells are those of :func:`voroforge.voronoi` on all sites at once (see
    ``docs/scale.md`` for exactly what "identical" means): each tile computes its own sites'
    cells with a halo of neighbouring sites, and a cell is kept only when its certificate
    holds (every site within twice its farthest vertex distance was loaded); the others are
    recomputed with the sites their own bound asks for, until none is left.

    Parameters
    ----------
    points : (n, 2) array_like, dask array, or path of a .npy (memory-mapped), .csv or .parquet
        The sites. Files need ``x``/``y`` columns (or lon/lat, easting/northing); their other
        columns are carried to the output as attributes. Rows are the ``site_id`` s.
    boundary : None, (xmin, ymin, xmax, ymax) or shapely Polygon/MultiPolygon
        The domain, as for :func:`voroforge.voronoi` (None: the sites' box padded by 10%).
    out : str or Path
        The output folder: a Parquet dataset with one GeoParquet 1.1 file per tile, a
        ``_metadata`` summary and the job manifest.
    tiles : int, optional
        Number of tiles (default: about ``SCALE_TILE_SITES`` sites each, at least two per
        worker).
    tile_size : int, optional
        Sites per tile instead of ``tiles`` (the CLI's ``--tile-size``).
    client : distributed.Client, optional
        Default: the current client, else a LocalCluster started for the call (one
        single-threaded process per core, or ``workers``).
    workers : int, optional
        Workers of the LocalCluster started when there is no client.
    crs : str, dict or None
        Coordinate reference system written into the GeoParquet metadata (None: unknown).
    overwrite : bool
        Replace an existing ``out``. Without it an existing output is refused, except an
        unfinished job on the same input, which is resumed.
    progress : callable, optional
        ``progress(done, total)`` after every finished tile.
    chunk_rows : int, optional
        Input rows read per task (default ``SCALE_CHUNK_ROWS``).

    Returns
    -------
    ScaleResult

    Raises
    ------
    ValueError
        Bad points (shape, non-finite rows, with their row numbers), an invalid boundary, an
        existing output without ``overwrite``, ``tiles``/``tile_size``/``workers``/
        ``chunk_rows`` that are not whole numbers >= 1, or both ``tiles`` and ``tile_size``.

    Examples
    --------
    >>> import numpy as np
    >>> from voroforge import scale
    >>> pts = np.random.default_rng(0).random((100_000, 2))
    >>> res = scale.voronoi(pts, (0, 0, 1, 1), out="cells.parquet")  # doctest: +SKIP
    >>> res.uncertified  # doctest: +SKIP
    0
    """
    t_start = time.perf_counter()
    tiles, tile_size, workers, chunk_rows = check_counts(tiles, tile_size, workers, chunk_rows)
    out = Path(out)
    eng_boundary, boundary_text = _boundary_spec(boundary)
    crs_json = None
    if crs is not None:
        from ..io.parquet import projjson

        crs_json = projjson(crs)
    resume = _prepare_out(out, overwrite, points)
    rows = chunk_rows or config.SCALE_CHUNK_ROWS
    source = None
    try:
        source = open_source(points, out, rows)
        with client_for(client, workers) as cl:
            job = {
                "boundary": eng_boundary,
                "boundary_text": boundary_text,
                "crs": crs_json,
                "out": out,
                "tiles": tiles,
                "tile_size": tile_size,
                "resume": resume,
                "progress": progress,
            }
            result = _run(cl, source, job)
    except BaseException:
        # failed before any work was recorded (a refusal, or an error reading the input):
        # leave no folder that a rerun would refuse
        if resume is None and not (out / MANIFEST).exists() and out.is_dir() and _ours(out):
            shutil.rmtree(out, ignore_errors=True)
        raise
    finally:
        for tmp in source.temporary if source is not None and source.temporary else []:
            Path(tmp).unlink(missing_ok=True)
        if (out / SHUFFLE).is_dir():  # a rerun buckets the input again
            shutil.rmtree(out / SHUFFLE, ignore_errors=True)
        for stale in out.glob(".*.tmp") if out.is_dir() else []:
            stale.unlink(missing_ok=True)
    result.seconds = time.perf_counter() - t_start
    return result


def _run(cl, source, job):
    """The job's steps on client ``cl`` (``job``: the validated arguments of :func:`voronoi`)."""
    from distributed import as_completed

    from ..engine.domain import padded_bounds

    eng_boundary, boundary_text, crs_json = job["boundary"], job["boundary_text"], job["crs"]
    out, resume, progress = job["out"], job["resume"], job["progress"]

    clock = [time.perf_counter()]
    phases = {}

    def lap(name):
        now = time.perf_counter()
        phases[name] = now - clock[0]
        clock[0] = now

    nworkers = max(1, len(cl.scheduler_info(n_workers=-1)["workers"]))
    blocks = cl.compute(source.blocks) if source.blocks else [None] * len(source.chunks)
    share = max(1, math.ceil(config.SCALE_SAMPLE_SITES / max(len(source.chunks), 1)))
    stats = cl.gather(
        [
            cl.submit(chunk_stats, c, b, share, i, pure=False)
            for i, (c, b) in enumerate(zip(source.chunks, blocks, strict=True))
        ]
    )
    if any(s["bad_count"] for s in stats):
        raise _bad_rows_error(stats)
    n = sum(s["n"] for s in stats)
    if n == 0:
        raise ValueError("no points: the input has no rows")
    lo = np.min([s["lo"] for s in stats if s["lo"] is not None], axis=0)
    hi = np.max([s["hi"] for s in stats if s["hi"] is not None], axis=0)
    if eng_boundary is None:
        with np.errstate(over="ignore", invalid="ignore"):  # refused just below
            eng_boundary = tuple(float(v) for v in padded_bounds(np.array([lo, hi])))
    extent_check(lo, hi, eng_boundary, job["boundary"] is None)
    ntiles = tile_count(n, job["tiles"], job["tile_size"], nworkers)
    sample = np.concatenate([s["sample"] for s in stats])
    tiling = kd_tiling(sample, ntiles)
    ntiles = len(tiling)
    # each tile's halo, from its share of the sample (it only sets how many cells need a
    # second round; the certificate decides what is final)
    share = np.bincount(tiling.assign(sample), minlength=ntiles) * (n / max(len(sample), 1))
    loaded = np.array(
        [
            _grown(r, first_halo(r, max(c, 1.0), lo, hi))
            for r, c in zip(tiling.rects, share, strict=True)
        ]
    ).reshape(-1, 4)
    fingerprint = {
        "n": n,
        "checksums": [s["checksum"] for s in stats],
        "chunk_rows": [[c.start, c.stop] for c in source.chunks],
        "boundary": boundary_text if boundary_text is not None else list(eng_boundary),
        "tiling": tiling.to_json(),
        "crs": crs_json,
    }
    if resume is not None and resume.get("fingerprint") != fingerprint:
        raise ValueError(
            f"{out} holds an unfinished job on other input or settings; pass overwrite=True"
        )
    manifest = {"format": _FORMAT, "complete": False, "fingerprint": fingerprint}
    _write_json(out / MANIFEST, manifest)
    lap("stats")

    # the shuffle, on disk: every chunk's sites bucketed by tile, with the halo copies
    shuffle = out / SHUFFLE
    shuffle.mkdir(exist_ok=True)
    sources = halo_sources(tiling, loaded)
    bucketed = cl.gather(
        [
            cl.submit(bucket_chunk, c, b, tiling, loaded, sources, str(shuffle), i, pure=False)
            for i, (c, b) in enumerate(zip(source.chunks, blocks, strict=True))
        ]
    )
    del blocks
    per_tile, halo_sites = np.sum(bucketed, axis=0)
    store = Store(str(shuffle), len(source.chunks), ntiles, attrs=source.attributes)
    lap("shuffle")

    def spec(t):
        name = f"part-{t:05d}.parquet"
        return {
            "loaded": tuple(float(v) for v in loaded[t]),
            "lo": lo.tolist(),
            "hi": hi.tolist(),
            "boundary": eng_boundary,
            "crs": crs_json,
            "file": name,
            "path": str(out / name),
            "max_rounds": config.SCALE_MAX_ROUNDS,
        }

    infos = {}
    resumed = 0
    futures = []
    for t in range(ntiles):
        s = spec(t)
        done = _tile_done(out / s["file"]) if resume is not None else None
        if done is not None and done.get("rows") == int(per_tile[t]):
            infos[t] = done
            resumed += 1
            continue
        futures.append(cl.submit(run_tile, t, s, store, tiling, pure=False))
    try:
        if progress is not None:
            progress(len(infos), ntiles)
        for f in as_completed(futures):
            info = f.result()
            infos[info["tile"]] = info
            f.release()
            if progress is not None:
                progress(len(infos), ntiles)
    except BaseException:
        cl.cancel(futures)  # an interrupted job leaves no queued tiles behind on the cluster
        raise
    del futures
    shutil.rmtree(shuffle, ignore_errors=True)
    lap("tiles")

    tile_info = [infos[t] for t in range(ntiles)]
    _write_dataset_metadata(out, tile_info)
    manifest["complete"] = True
    manifest["tiles"] = tile_info
    _write_json(out / MANIFEST, manifest)
    lap("metadata")
    return ScaleResult(
        path=out,
        cells=int(sum(i["rows"] for i in tile_info)),
        tiles=ntiles,
        workers=nworkers,
        uncertified=int(sum(i["uncertified"] for i in tile_info)),
        retried=int(sum(i["first_uncertified"] for i in tile_info)),
        resumed=resumed,
        seconds=0.0,
        dashboard=getattr(cl, "dashboard_link", None),
        halo_copies=int(halo_sites.sum()),
        phases=phases,
        tile_info=tile_info,
    )


def _write_json(path: Path, obj) -> None:
    text = json.dumps(obj, indent=1, allow_nan=True)
    write_atomically(path, lambda tmp: Path(tmp).write_text(text), suffix=".tmp")


def _write_dataset_metadata(out: Path, tile_info) -> None:
    """``_common_metadata`` (schema, geo of the whole dataset) and ``_metadata`` (row groups)."""
    import pyarrow.parquet as pq

    collected, types, extents = [], set(), []
    schema = None
    for info in tile_info:
        md = pq.read_metadata(out / info["file"])
        geo = json.loads(md.metadata[b"geo"])
        types.update(geo["columns"]["geometry"]["geometry_types"])
        if not any(np.isnan(info["extent"])):
            extents.append(info["extent"])
        if schema is None:
            schema = pq.read_schema(out / info["file"])
        md.set_file_path(info["file"])
        collected.append(md)
    meta = dict(schema.metadata or {})
    geo = json.loads(meta[b"geo"])
    col = geo["columns"]["geometry"]
    col.pop("bbox", None)
    if extents:
        e = np.array(extents)
        col["bbox"] = [
            float(e[:, 0].min()),
            float(e[:, 1].min()),
            float(e[:, 2].max()),
            float(e[:, 3].max()),
        ]
    col["geometry_types"] = sorted(types)
    meta[b"geo"] = json.dumps(geo).encode()
    meta.pop(b"voroforge_tile", None)
    schema = schema.with_metadata(meta)
    for name, mds in (("_common_metadata", None), ("_metadata", collected)):
        write_atomically(
            out / name,
            lambda tmp, mds=mds: pq.write_metadata(schema, tmp, metadata_collector=mds),
            suffix=".tmp",
        )
