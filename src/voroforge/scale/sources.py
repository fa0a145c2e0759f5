"""Where the sites come from: row chunks that a worker can load by itself.

Every input becomes a list of :class:`Chunk` s, each a row range ``[start, stop)`` of the
input and a way to load it on any worker: a slice of a memory-mapped ``.npy`` file, Parquet
row groups, or a block of a dask array. In-memory arrays are written once to a ``.npy`` file
beside the output and CSV files are streamed into Parquet there, so a lost worker's chunks
can always be loaded again (dask recomputes lost results from their recipe).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

__all__ = ["Chunk", "Source", "open_source"]

_X_NAMES = ("x", "lon", "lng", "longitude", "easting")
_Y_NAMES = ("y", "lat", "latitude", "northing")


@dataclass(frozen=True)
class Chunk:
    """Rows ``start:stop`` of the input, loadable on a worker by :meth:`load`.

    Attributes
    ----------
    start, stop : int
        The chunk's input rows.
    kind : str
        ``"npy"`` (``path``), ``"parquet"`` (``path``, ``groups``, ``xy`` column names) or
        ``"dask"`` (the block is passed to :meth:`load` by the scheduler).
    """

    start: int
    stop: int
    kind: str
    path: str = ""
    groups: tuple = ()
    xy: tuple = ("x", "y")

    def load(self, block=None):
        """``(xy (m, 2) float64, attributes pyarrow.Table or None)`` of the chunk's rows."""
        if self.kind == "npy":
            arr = np.load(self.path, mmap_mode="r")
            return np.array(arr[self.start : self.stop], dtype=np.float64), None
        if self.kind == "parquet":
            import pyarrow.parquet as pq

            table = pq.ParquetFile(self.path).read_row_groups(list(self.groups))
            return _split_columns(table, self.xy)
        xy = np.asarray(block, dtype=np.float64)
        return np.ascontiguousarray(xy.reshape(-1, 2)), None


def _split_columns(table, xy):
    x = table.column(xy[0]).to_numpy(zero_copy_only=False).astype(np.float64, copy=False)
    y = table.column(xy[1]).to_numpy(zero_copy_only=False).astype(np.float64, copy=False)
    from ..io.parquet import CELL_COLUMNS
    from ..io.readers.points import attribute_names

    rest = [c for c in table.column_names if c not in xy]
    # an attribute named like a cell column (area, geometry, ...) is kept as input_<name>,
    # as by `voroforge voronoi`: two columns of one name made files pyarrow cannot read
    attrs = table.select(rest).rename_columns(attribute_names(rest, CELL_COLUMNS)) if rest else None
    return np.column_stack((x, y)), attrs


@dataclass
class Source:
    """The chunks of one input, and its dask blocks (``kind == "dask"``)."""

    n: int
    chunks: list
    blocks: list | None = None
    temporary: list | None = None
    description: str = ""
    attributes: bool = False


def _xy_names(names, where):
    seen = set()
    twice = [c for c in names if c in seen or seen.add(c)]
    if twice:
        raise ValueError(
            f"{where}: column {twice[0]!r} appears more than once; column names must be unique"
        )
    low = {c.lower(): c for c in names}
    xs = [low[c] for c in _X_NAMES if c in low]
    ys = [low[c] for c in _Y_NAMES if c in low]
    if not xs or not ys:
        raise ValueError(
            f"{where}: no x/y columns (looked for {'/'.join(_X_NAMES)} and "
            f"{'/'.join(_Y_NAMES)}; columns are {list(names)})"
        )
    return xs[0], ys[0]


def _row_chunks(n, rows):
    starts = list(range(0, n, rows)) or [0]
    return [(a, min(a + rows, n)) for a in starts]


def _npy_source(path: Path, rows: int, temporary=None) -> Source:
    try:
        arr = np.load(path, mmap_mode="r")
    except (ValueError, OSError) as exc:
        raise ValueError(f"{path}: not a readable .npy array ({exc})") from None
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise ValueError(f"{path}: points must have shape (n, 2); got {arr.shape}")
    if arr.dtype.kind not in "iuf":
        raise ValueError(f"{path}: points must be real numbers; got dtype {arr.dtype}")
    chunks = [Chunk(a, b, "npy", str(path)) for a, b in _row_chunks(len(arr), rows)]
    return Source(len(arr), chunks, temporary=temporary, description=f"{path} ({len(arr)} rows)")


def _parquet_source(path: Path, rows: int, temporary=None, label=None) -> Source:
    """Chunks of a Parquet file; errors name ``label`` (the user's file a CSV came from)."""
    import pyarrow.parquet as pq

    where = path if label is None else label
    try:
        pf = pq.ParquetFile(path)
    except Exception as exc:  # pyarrow raises its own error types for unreadable files
        raise ValueError(f"{where}: not a readable Parquet file ({exc})") from None
    xy = _xy_names(pf.schema_arrow.names, where)
    if pf.metadata.num_rows == 0:  # a CSV of a header alone read "column 'x' is not numeric"
        raise ValueError(f"no points: {where} has no rows")
    import pyarrow.types as pat

    for name in xy:
        kind = pf.schema_arrow.field(name).type
        if not (pat.is_integer(kind) or pat.is_floating(kind)):
            raise ValueError(f"{where}: column {name!r} is not numeric ({kind})")
    chunks, start, group, acc = [], 0, [], 0
    meta = pf.metadata
    for g in range(meta.num_row_groups):
        group.append(g)
        acc += meta.row_group(g).num_rows
        if acc >= rows or g == meta.num_row_groups - 1:
            chunks.append(Chunk(start, start + acc, "parquet", str(path), tuple(group), xy))
            start += acc
            group, acc = [], 0
    return Source(
        meta.num_rows,
        chunks,
        temporary=temporary,
        description=f"{path} ({start} rows)",
        attributes=len(pf.schema_arrow.names) > 2,
    )


def _csv_reader(path: Path, delimiter: str, names):
    """A streaming pyarrow CSV reader of every column as text, named ``names`` (the header's)."""
    import pyarrow as pa
    import pyarrow.csv as pacsv

    try:
        return pacsv.open_csv(
            path,
            read_options=pacsv.ReadOptions(block_size=1 << 24, column_names=names, skip_rows=1),
            parse_options=pacsv.ParseOptions(delimiter=delimiter),
            convert_options=pacsv.ConvertOptions(
                column_types=dict.fromkeys(names, pa.string()),
                null_values=[""],
                strings_can_be_null=True,
            ),
        )
    except Exception as exc:  # pyarrow.lib.ArrowInvalid and friends
        raise ValueError(f"{path}: not a readable CSV file ({exc})") from None


def _cells(col):
    """A text column's cells as the text reader sees them: trimmed, unquoted, "" missing."""
    import pyarrow.compute as pc

    col = pc.utf8_trim_whitespace(col)
    if pc.any(pc.starts_with(col, "'")).as_py():  # the regex only where it can match
        col = pc.utf8_trim_whitespace(pc.replace_substring_regex(col, r"^'(.*)'$", r"\1"))
    empty = pc.equal(col, "")
    return pc.if_else(empty, None, col) if pc.any(empty).as_py() else col


def _attribute_types(batches, rest) -> dict:
    """Arrow types of the attribute columns ``rest``, by the text reader's rules.

    As ``io.readers.points._typed_column`` has them, so `voroforge scale` and `voroforge
    voronoi` read one CSV alike: int64 where every cell is an integer literal within int64,
    float64 where every cell is a number a float64 holds as written, text otherwise (codes
    with leading zeros such as ``00501``, integers past 2**53 among floats). pyarrow's own
    inference looks at the first block only and reads ``00501`` as 501.
    """
    import pyarrow as pa
    import pyarrow.compute as pc

    lead, nonint, nonnum, unheld, outside = (dict.fromkeys(rest, False) for _ in range(5))
    for batch in batches:
        for name in rest:
            present = _cells(batch.column(name)).drop_null()
            if len(present) == 0:
                continue
            lead[name] |= pc.any(pc.match_substring_regex(present, r"^[+-]?0[0-9]")).as_py()
            is_int = pc.match_substring_regex(present, r"^[+-]?[0-9]+$")
            ints = present.filter(is_int)
            others = present.filter(pc.invert(is_int))
            nonint[name] |= len(others) > 0
            if len(ints):  # past 15 digits: is it an int64, and does a float64 hold it?
                long = ints.filter(pc.greater(pc.utf8_length(ints), 15)).to_pylist()
                values = [int(t) for t in long if len(t) <= 400]
                outside[name] |= len(values) < len(long)
                outside[name] |= any(not -(2**63) <= v <= 2**63 - 1 for v in values)
                unheld[name] |= len(values) < len(long) or any(float(v) != v for v in values)
            if len(others) and not nonnum[name]:
                try:
                    pc.cast(others, pa.float64())
                except (pa.ArrowInvalid, pa.ArrowNotImplementedError):
                    nonnum[name] = True
    types = {}
    for name in rest:
        if lead[name] or (not nonint[name] and outside[name]):
            types[name] = pa.string()
        elif not nonint[name]:
            types[name] = pa.int64()
        elif nonnum[name] or unheld[name]:
            types[name] = pa.string()
        else:
            types[name] = pa.float64()
    return types


def _typed(batch, types, xy, where):
    """``batch`` with its text columns cast to ``types`` (``xy``: float64, no empty cell)."""
    import pyarrow as pa
    import pyarrow.compute as pc

    columns = []
    for name, col in zip(batch.schema.names, batch.columns, strict=True):
        kind = types.get(name)
        if kind is not None:
            col = _cells(col)
            if kind == pa.int64() and pc.any(pc.starts_with(col, "+")).as_py():
                col = pc.replace_substring_regex(col, r"^\+", "")
            if name in xy and col.null_count:
                raise ValueError(f"{where}: column {name!r} has an empty cell")
            try:
                col = pc.cast(col, kind)
            except pa.ArrowInvalid as exc:
                raise ValueError(f"{where}: column {name!r} is not numeric ({exc})") from None
        columns.append(col)
    return pa.RecordBatch.from_arrays(columns, names=batch.schema.names)


def _csv_to_parquet(path: Path, dest: Path, rows: int) -> Path:
    """Stream a CSV file into Parquet row groups of ``rows`` (bounded memory).

    Cells are read as text and typed as the text reader types them: two passes, the first
    types the attribute columns (:func:`_attribute_types`).
    """
    import pyarrow as pa
    import pyarrow.parquet as pq

    delimiter, names = _header(path)
    xy = _xy_names(names, path)
    rest = [c for c in names if c not in xy]
    tmp = dest.with_name(dest.name + ".part")
    try:
        try:
            types = _attribute_types(_csv_reader(path, delimiter, names), rest)
            types.update(dict.fromkeys(xy, pa.float64()))
            reader = _csv_reader(path, delimiter, names)
            first = _typed(reader.read_next_batch(), types, xy, path)
            with pq.ParquetWriter(tmp, first.schema) as out:
                out.write_batch(first, row_group_size=rows)
                for batch in reader:
                    out.write_batch(_typed(batch, types, xy, path), row_group_size=rows)
        except StopIteration:
            raise ValueError(f"no points: {path} has no rows") from None
        except pa.ArrowException as exc:  # a ValueError too: caught before the plain ones
            raise ValueError(f"{path}: CSV parse error ({exc})") from None
    except BaseException:
        tmp.unlink(missing_ok=True)  # a failed conversion leaves nothing behind
        raise
    tmp.replace(dest)
    return dest


def _header(path: Path) -> tuple[str, list]:
    """The delimiter (``,``, ``;`` or a tab) and the header row's names.

    Split as the text reader splits them (``io.readers.points.split_fields``: RFC 4180
    quoting, quotes and padding dropped).
    """
    from ..io.readers.files import parse_number
    from ..io.readers.points import split_fields

    with open(path, encoding="utf-8-sig") as fh:
        first = fh.readline().rstrip("\r\n")
    delimiter = next((d for d in (",", ";", "\t") if d in first), None)
    # the streamed reader needs what the text reader (voroforge voronoi) can do without
    how = "a header row naming the x and y columns, cells separated by commas, semicolons or tabs"
    if delimiter is None and len(first.split()) > 1:
        raise ValueError(f"{path}: space-separated; scale reads CSV files with {how}")
    names = split_fields(first, delimiter or ",")
    if names and all(parse_number(t) is not None for t in names):
        raise ValueError(
            f"{path}: no header row ({first[:40]!r}); scale reads CSV files with {how}"
        )
    return delimiter or ",", names


def open_source(points, work: Path, rows: int) -> Source:
    """The chunks of ``points``.

    Parameters
    ----------
    points : (n, 2) array_like, dask array, or str/Path of a .npy, .csv or .parquet file
        The sites (files: ``x``/``y`` columns, the other columns are attributes).
    work : Path
        A folder for converted input (an in-memory array as ``.npy``, CSV as Parquet).
    rows : int
        Rows per chunk.

    Returns
    -------
    Source
    """
    if isinstance(points, (str, Path)):
        path = Path(points)
        if not path.is_file():
            raise ValueError(f"{path}: no such points file")
        suffix = path.suffix.lower()
        if suffix == ".npy":
            return _npy_source(path, rows)
        if suffix in (".parquet", ".pq", ".geoparquet"):
            return _parquet_source(path, rows)
        if suffix in (".csv", ".txt", ".tsv"):
            dest = _csv_to_parquet(path, work / "_points.tmp.parquet", rows)
            try:
                return _parquet_source(dest, rows, temporary=[dest], label=path)
            except BaseException:
                dest.unlink(missing_ok=True)
                raise
        raise ValueError(f"{path}: unknown points format {suffix!r} (use .npy, .csv or .parquet)")
    if type(points).__module__.startswith("dask."):
        arr = points
        if arr.ndim != 2 or arr.shape[1] != 2:
            raise ValueError(f"points must have shape (n, 2); got {arr.shape}")
        arr = arr.rechunk({0: arr.chunks[0], 1: 2})
        bounds = np.concatenate(([0], np.cumsum(arr.chunks[0])))
        chunks = [
            Chunk(int(a), int(b), "dask") for a, b in zip(bounds[:-1], bounds[1:], strict=True)
        ]
        blocks = list(arr.to_delayed()[:, 0])
        return Source(int(bounds[-1]), chunks, blocks=blocks, description="dask array")
    try:
        raw = np.asarray(points)
        if raw.dtype.kind not in "iuf":
            raise TypeError(f"dtype {raw.dtype}")
    except (TypeError, ValueError) as exc:
        raise ValueError(f"points must be an (n, 2) array of real numbers ({exc})") from None
    if raw.ndim != 2 or raw.shape[1] != 2:
        raise ValueError(f"points must have shape (n, 2); got shape {raw.shape}")
    dest = work / "_points.tmp.npy"
    tmp = work / "_points.tmp.npy.part"
    with open(tmp, "wb") as fh:
        np.save(fh, np.ascontiguousarray(raw, dtype=np.float64))
    tmp.replace(dest)
    return _npy_source(dest, rows, temporary=[dest])
