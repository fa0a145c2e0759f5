"""The shuffle on disk: every chunk's sites bucketed by owning tile, read back by span.

One task per input chunk loads its rows, sorts them by owning tile (stably, so rows stay
increasing within a tile) and writes one file, ``_shuffle/chunk-NNNNN.bin``: a header of
``tiles + 1`` int64 span starts, then one 24-byte record ``(row, x, y)`` per site; a chunk with
attribute columns also writes its rows in the same order as an Arrow IPC file
(``chunk-NNNNN.arrow``). Both are written to a temporary name and renamed, so a file exists
only complete and a rerun task (a lost worker) replaces it by the same bytes.

A tile then reads its own span of every chunk file (two small reads each) and its
neighbours' spans for its halo: the data never passes through the scheduler or the driver,
and the driver only sees each chunk's counts per tile. The folder needs to be one that every
worker can read (the output folder, which the workers write anyway).
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np

__all__ = ["RECORD", "Store", "bucket_chunk"]

#: One site in a bucket file: its input row and coordinates.
RECORD = np.dtype([("id", "<i8"), ("x", "<f8"), ("y", "<f8")])


def _atomic_write(path: Path, parts) -> None:
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    try:
        with open(tmp, "wb") as fh:
            for part in parts:
                fh.write(memoryview(part).cast("B"))
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()


def bucket_chunk(chunk, block, tiling, folder: str, index: int) -> np.ndarray:
    """Write chunk ``index``'s sites bucketed by owning tile; return its counts ``(t,)``."""
    import pyarrow as pa

    xy, attrs = chunk.load(block)
    tile = tiling.assign(xy) if len(xy) else np.zeros(0, np.int64)
    order = np.argsort(tile, kind="stable")  # stable: rows stay increasing within a tile
    counts = np.bincount(tile, minlength=len(tiling)).astype(np.int64)
    starts = np.zeros(len(tiling) + 1, dtype=np.int64)
    np.cumsum(counts, out=starts[1:])
    rec = np.zeros(len(xy), dtype=RECORD)
    rec["id"] = chunk.start + order
    rec["x"] = xy[order, 0]
    rec["y"] = xy[order, 1]
    base = Path(folder)
    _atomic_write(base / f"chunk-{index:05d}.bin", [starts, rec])
    if attrs is not None:
        path = base / f"chunk-{index:05d}.arrow"
        tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
        table = attrs.take(order)
        with pa.OSFile(str(tmp), "wb") as sink, pa.ipc.new_file(sink, table.schema) as w:
            w.write_table(table)
        os.replace(tmp, path)
    return counts


def _span(fh, t: int):
    """Records ``a:b`` of tile ``t`` in an open bucket file (its header's entries t, t + 1)."""
    fh.seek(8 * t)
    a, b = np.fromfile(fh, dtype="<i8", count=2)
    return int(a), int(b)


@dataclass(frozen=True)
class Store:
    """The bucket files of a job: where they are, how many chunks and tiles, attributes."""

    folder: str
    chunks: int
    tiles: int
    attrs: bool = False

    def _path(self, c: int, ext: str = "bin") -> str:
        return os.path.join(self.folder, f"chunk-{c:05d}.{ext}")

    def read(self, tiles) -> dict:
        """``{tile: (ids, xy)}``: the sites each of ``tiles`` owns, rows increasing."""
        tiles = sorted({int(t) for t in tiles})
        head = 8 * (self.tiles + 1)
        got = {t: [] for t in tiles}
        for c in range(self.chunks):
            with open(self._path(c), "rb", buffering=0) as fh:
                for t in tiles:
                    a, b = _span(fh, t)
                    if b > a:
                        fh.seek(head + 24 * a)
                        rec = np.fromfile(fh, dtype=RECORD, count=b - a)
                        if len(rec) != b - a:
                            raise OSError(f"{self._path(c)}: truncated bucket file")
                        got[t].append(rec)
        out = {}
        for t, recs in got.items():
            rec = np.concatenate(recs) if recs else np.zeros(0, dtype=RECORD)
            xy = np.zeros((len(rec), 2))
            xy[:, 0] = rec["x"]
            xy[:, 1] = rec["y"]
            out[t] = (rec["id"].copy(), xy)
        return out

    def attributes(self, t: int):
        """The attribute rows of tile ``t``'s sites (in :meth:`read` order), or None."""
        if not self.attrs:
            return None
        import pyarrow as pa

        parts = []
        for c in range(self.chunks):
            with open(self._path(c), "rb", buffering=0) as fh:
                a, b = _span(fh, int(t))
            if b > a or (c == self.chunks - 1 and not parts):
                # memory-mapped: the slice is read when the tile writes it (the map lives
                # as long as the buffers that use it)
                table = pa.ipc.open_file(pa.memory_map(self._path(c, "arrow"))).read_all()
                parts.append(table.slice(int(a), int(b - a)))
        return pa.concat_tables(parts)
