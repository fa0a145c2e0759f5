"""The shuffle on disk: every chunk's sites bucketed by tile, halos included, read by span.

One task per input chunk loads its rows, sorts them by owning tile (stably, so rows stay
increasing within a tile) and writes one file, ``_shuffle/chunk-NNNNN.bin``. For each tile
the file holds a block of the sites it owns, then a block of the sites it only loads: the
chunk's sites of other tiles that lie in this tile's loaded region (its rectangle grown by
its halo), copied there by the same task. So a tile reads exactly its loaded sites with one
read per chunk file, and the halo copies cost a few percent of the data (the halo's share),
not a second pass over the neighbours' sites.

File layout (little-endian): a header of ``3 t + 2`` int64 (``t`` tiles): ``S`` (``2 t + 1``
record offsets: tile ``u`` owns records ``S[2u]:S[2u+1]`` and loads ``S[2u+1]:S[2u+2]`` as
halo) and ``A`` (``t + 1``: tile ``u``'s owned rows are rows ``A[u]:A[u+1]`` of the chunk's
attribute file), then one 24-byte record ``(row, x, y)`` per entry. A chunk with attribute
columns also writes its owned rows in tile order as an Arrow IPC file
(``chunk-NNNNN.arrow``). Both are written to a temporary name and renamed, so a file exists
only complete and a rerun task (a lost worker) replaces it by the same bytes.

The data never passes through the scheduler or the driver: the driver sees each chunk's
counts per tile. The folder must be one that every worker can read (the output folder,
which the workers write anyway).
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np

__all__ = ["RECORD", "Store", "bucket_chunk", "halo_sources"]

#: One site in a bucket file: its input row and coordinates.
RECORD = np.dtype([("id", "<i8"), ("x", "<f8"), ("y", "<f8")])


def halo_sources(tiling, loaded) -> list:
    """For each tile ``t``, the other tiles whose loaded rectangle meets ``t``'s rectangle.

    Only their loaded regions can take halo copies of ``t``'s sites. ``loaded`` is ``(t, 4)``.
    """
    out = [[] for _ in range(len(tiling))]
    for u, rect in enumerate(loaded):
        for t in tiling.touching(rect):
            if t != u:
                out[int(t)].append(u)
    return [np.array(v, dtype=np.int64) for v in out]


def _atomic_write(path: Path, parts) -> None:
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    try:
        with open(tmp, "wb") as fh:
            for part in parts:
                fh.write(memoryview(np.ascontiguousarray(part)).cast("B"))
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()


def bucket_chunk(chunk, block, tiling, loaded, sources, folder: str, index: int) -> np.ndarray:
    """Write chunk ``index``'s sites bucketed by tile with the halo copies.

    ``loaded`` is each tile's loaded rectangle ``(t, 4)``, ``sources`` :func:`halo_sources`.
    Returns ``(2, t)`` int64: the sites each tile owns and loads as halo in this chunk.
    """
    import pyarrow as pa

    xy, attrs = chunk.load(block)
    ntiles = len(tiling)
    tile = tiling.assign(xy) if len(xy) else np.zeros(0, np.int64)
    order = np.argsort(tile, kind="stable")  # stable: rows stay increasing within a tile
    counts = np.bincount(tile, minlength=ntiles).astype(np.int64)
    starts = np.zeros(ntiles + 1, dtype=np.int64)
    np.cumsum(counts, out=starts[1:])
    xs = xy[order, 0]
    ys = xy[order, 1]
    # halo copies: each tile's sites that lie in another tile's loaded rectangle
    dest, picks = [], []
    for t in np.flatnonzero(counts):
        a, b = starts[t], starts[t + 1]
        px, py = xs[a:b], ys[a:b]
        for u in sources[t]:
            x0, y0, x1, y1 = loaded[u]
            hit = np.flatnonzero((px >= x0) & (px <= x1) & (py >= y0) & (py <= y1))
            if len(hit):
                dest.append(np.full(len(hit), u, dtype=np.int64))
                picks.append(a + hit)
    dest = np.concatenate(dest) if dest else np.zeros(0, np.int64)
    picks = np.concatenate(picks) if picks else np.zeros(0, np.int64)
    by = np.argsort(dest, kind="stable")
    dest, picks = dest[by], picks[by]
    hcounts = np.bincount(dest, minlength=ntiles).astype(np.int64)
    hstarts = np.zeros(ntiles + 1, dtype=np.int64)
    np.cumsum(hcounts, out=hstarts[1:])
    # tile u: owned block at starts[u] + hstarts[u], its halo block right after it
    rec = np.zeros(len(xy) + len(dest), dtype=RECORD)
    at = np.arange(len(xy)) + hstarts[tile[order]]
    rec["id"][at] = chunk.start + order
    rec["x"][at] = xs
    rec["y"][at] = ys
    at = starts[dest + 1] + np.arange(len(dest))
    rec["id"][at] = chunk.start + order[picks]
    rec["x"][at] = xs[picks]
    rec["y"][at] = ys[picks]
    spans = np.zeros(2 * ntiles + 1, dtype=np.int64)
    spans[0:-1:2] = starts[:-1] + hstarts[:-1]
    spans[1::2] = starts[1:] + hstarts[:-1]
    spans[-1] = len(rec)
    base = Path(folder)
    _atomic_write(base / f"chunk-{index:05d}.bin", [spans, starts, rec])
    if attrs is not None:
        path = base / f"chunk-{index:05d}.arrow"
        tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
        table = attrs.take(order)
        with pa.OSFile(str(tmp), "wb") as sink, pa.ipc.new_file(sink, table.schema) as w:
            w.write_table(table)
        os.replace(tmp, path)
    return np.stack((counts, hcounts))


def _header(fh, at: int, k: int):
    fh.seek(8 * at)
    return [int(v) for v in np.fromfile(fh, dtype="<i8", count=k)]


def _records(fh, head: int, a: int, b: int, path: str) -> np.ndarray:
    fh.seek(8 * head + 24 * a)
    rec = np.fromfile(fh, dtype=RECORD, count=b - a)
    if len(rec) != b - a:
        raise OSError(f"{path}: truncated bucket file")
    return rec


def _split(recs) -> tuple:
    rec = np.concatenate(recs) if recs else np.zeros(0, dtype=RECORD)
    xy = np.zeros((len(rec), 2))
    xy[:, 0] = rec["x"]
    xy[:, 1] = rec["y"]
    return rec["id"].copy(), xy


@dataclass(frozen=True)
class Store:
    """The bucket files of a job: where they are, how many chunks and tiles, attributes."""

    folder: str
    chunks: int
    tiles: int
    attrs: bool = False

    def _path(self, c: int, ext: str = "bin") -> str:
        return os.path.join(self.folder, f"chunk-{c:05d}.{ext}")

    @property
    def _head(self) -> int:
        return 3 * self.tiles + 2

    def loaded(self, t: int):
        """Tile ``t``'s sites: ``(ids, xy)`` of those it owns (rows increasing), of its halo."""
        own, halo = [], []
        for c in range(self.chunks):
            path = self._path(c)
            with open(path, "rb", buffering=0) as fh:
                a, m, b = _header(fh, 2 * t, 3)
                if b > a:
                    rec = _records(fh, self._head, a, b, path)
                    own.append(rec[: m - a])
                    halo.append(rec[m - a :])
        return _split(own), _split(halo)

    def owned(self, tiles) -> dict:
        """``{tile: (ids, xy)}``: the sites each of ``tiles`` owns, rows increasing."""
        got = {int(t): [] for t in tiles}
        for c in range(self.chunks):
            path = self._path(c)
            with open(path, "rb", buffering=0) as fh:
                for t in sorted(got):
                    a, m = _header(fh, 2 * t, 2)
                    if m > a:
                        got[t].append(_records(fh, self._head, a, m, path))
        return {t: _split(recs) for t, recs in got.items()}

    def attributes(self, t: int):
        """The attribute rows of the sites tile ``t`` owns (in their order), or None."""
        if not self.attrs:
            return None
        import pyarrow as pa

        parts = []
        for c in range(self.chunks):
            with open(self._path(c), "rb", buffering=0) as fh:
                a, b = _header(fh, 2 * self.tiles + 1 + t, 2)
            if b > a or (c == self.chunks - 1 and not parts):
                # memory-mapped: the slice is read when the tile writes it (the map lives
                # as long as the buffers that use it)
                table = pa.ipc.open_file(pa.memory_map(self._path(c, "arrow"))).read_all()
                parts.append(table.slice(a, b - a))
        return pa.concat_tables(parts)
