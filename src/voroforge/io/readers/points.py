"""Point files in: delimited text (CSV/TXT/XY) and NumPy ``.npy`` arrays.

GeoJSON points are read by :mod:`.geojson`; :func:`voroforge.io.readers.read_points` picks
the reader from the suffix.
"""

from __future__ import annotations

import csv
import math
import re

import numpy as np

from .files import existing_file, parse_number

__all__ = ["attribute_names", "read_npy_points", "read_text_point_table", "read_text_points"]

_X_NAMES = ("x", "lon", "lng", "longitude", "easting")
_Y_NAMES = ("y", "lat", "latitude", "northing")
_Z_NAMES = ("z", "elevation", "height", "alt", "altitude")
_AXES = ("x", "y", "z")


def split_fields(line: str, delimiter: str | None) -> list[str]:
    """The fields of one line, quoted as RFC 4180 has it.

    ``"Smith, John"`` is one field and ``""`` a quote inside one, as Python's csv module,
    pandas and spreadsheets write them; single quotes around a whole field are dropped too.
    """
    if not delimiter:
        return [_unquote(p.strip()) for p in line.split()]
    fields = next(csv.reader([line], delimiter=delimiter, skipinitialspace=True))
    return [_unquote(p.strip()) for p in fields]


def _unquote(field: str) -> str:
    if len(field) >= 2 and field[0] == field[-1] and field[0] in "\"'":
        return field[1:-1].strip()
    return field


def read_text_points(path) -> np.ndarray:
    """Points from delimited text: commas, semicolons, tabs or spaces; optional header.

    The points of :func:`read_text_point_table`.

    Parameters
    ----------
    path : str or Path
        A text file with two numeric columns, or columns named ``x`` and ``y`` (also
        ``lon``/``lat``, ``easting``/``northing``, ...) in a header row; ``#`` comments.

    Returns
    -------
    (n, 2) float64
        In file order.

    Raises
    ------
    ValueError
        Naming the file and the line: no points, missing columns, a non-numeric value.
    """
    return read_text_point_table(path)[0]


def _data_width(tokens: list[str]) -> int:
    """How many cells a row has, a trailing empty one (``0,0,``) not counted."""
    n = len(tokens)
    while n and tokens[n - 1] == "":
        n -= 1
    return n


def read_text_point_table(path, dims: int = 2) -> tuple[np.ndarray, dict]:
    """Points from delimited text, and the header row's other columns as attributes.

    Parameters
    ----------
    path : str or Path
        As for :func:`read_text_points`.
    dims : {2, 3}
        Coordinates per point: ``x, y`` or ``x, y, z`` (header names ``z``, ``elevation``,
        ``height``, ...).

    Returns
    -------
    points : (n, dims) float64
        In file order.
    attributes : dict of name -> list
        Every column besides x and y, by its header name (files without a header have
        none): ints where every cell is an integer (within int64), floats where every
        cell is a number a float64 holds as written, else the text as written (codes
        with leading zeros such as ``00501``, integers past 2**53 in a float column);
        empty cells None.

    Raises
    ------
    ValueError
        Naming the file and the line: no points, missing columns, a non-numeric value, a
        row with more cells than the header (or, without one, than the first row).
    """
    path = existing_file(path)
    try:
        text = path.read_text(encoding="utf-8-sig")
    except UnicodeDecodeError as exc:
        raise ValueError(f"{path}: not a text file ({exc.reason})") from None
    rows = [
        (number, line.strip())
        for number, line in enumerate(text.splitlines(), start=1)
        if line.strip() and not line.lstrip().startswith("#")
    ]
    if not rows:
        raise ValueError(f"{path}: no points (the file is empty)")
    first = rows[0][1]
    delimiter = next((d for d in (",", ";", "\t") if d in first), None)

    columns = tuple(range(dims))
    head, head_line = split_fields(first, delimiter), rows[0][0]
    header = any(parse_number(t) is None for t in head[: _data_width(head)])
    if header:
        names = [t.lower() for t in head]
        found = [
            next((names.index(n) for n in axis if n in names), None)
            for axis in (_X_NAMES, _Y_NAMES, _Z_NAMES)[:dims]
        ]
        for i in found:
            twice = [k + 1 for k, n in enumerate(names) if i is not None and n == names[i]]
            if len(twice) > 1:  # which one holds the coordinate is anyone's guess
                raise ValueError(
                    f"{path}: line {rows[0][0]}: header {head} names the coordinate column "
                    f"{head[i]!r} {len(twice)} times (columns {', '.join(map(str, twice))}); "
                    "rename all but one"
                )
        if None in found:
            if len(names) != dims:
                want = " and ".join((", ".join(_AXES[: dims - 1]), _AXES[dims - 1]))
                raise ValueError(
                    f"{path}: line {rows[0][0]}: header {head} has no columns named {want}"
                )
            found = list(range(dims))
        columns = tuple(found)
        rows = rows[1:]
        if not rows:
            raise ValueError(f"{path}: no points (only a header row)")
    # a row wider than the header (or the first row) is a broken file, not extra data
    width, where = (len(head), f"the header on line {head_line}") if header else (None, "")
    need = max(columns) + 1
    out = np.zeros((len(rows), dims), dtype=np.float64)
    for k, (number, line) in enumerate(rows):
        tokens = split_fields(line, delimiter)
        if width is None:
            width, where = _data_width(tokens), f"line {number}"
        if _data_width(tokens) > width:
            raise ValueError(
                f"{path}: line {number}: {_data_width(tokens)} columns, but {where} has {width}"
            )
        if len(tokens) < need:
            raise ValueError(
                f"{path}: line {number}: expected at least {need} columns, got {len(tokens)}"
            )
        for j, c in enumerate(columns):
            value = parse_number(tokens[c])
            if value is None:
                raise ValueError(f"{path}: line {number}: {tokens[c]!r} is not a number")
            if not math.isfinite(value):
                raise ValueError(f"{path}: line {number}: {tokens[c]!r} is not a finite number")
            out[k, j] = value
    return out, _attributes(rows, head if header else [], columns, delimiter)


def _attributes(rows, head, columns, delimiter) -> dict:
    """The non-coordinate columns named in ``head``, typed by :func:`_typed_column`."""
    out = {}
    for c, name in enumerate(head):
        if c in columns:
            continue
        key = name or f"column_{c + 1}"
        while key in out:
            key += "_"
        cells = []
        for _, line in rows:
            tokens = split_fields(line, delimiter)
            cells.append(tokens[c] if c < len(tokens) and tokens[c] != "" else None)
        out[key] = _typed_column(cells)
    return out


#: An integer literal as a CSV writes one: optional sign, digits, nothing else.
_INT = re.compile(r"[+-]?[0-9]+")
#: A number written with a leading zero that a number would drop (``00501``, ``-007``,
#: ``012.5``): a code (zip, FIPS, id), not a quantity.
_LEADING_ZERO = re.compile(r"[+-]?0[0-9]")
_INT64 = (-(2**63), 2**63 - 1)


def _typed_column(cells: list) -> list:
    """One attribute column (``None`` for empty cells) as ints, floats or the text.

    ints: every cell an integer literal within int64 (Parquet's int64; ids past 2**53
    keep every digit). floats: every cell a number whose value a float64 holds as
    written: no leading zeros (``00501`` stays text) and no integer literal past 2**53
    (9007199254740993 would become ...992). Otherwise the text as written.
    """
    present = [t for t in cells if t is not None]
    if any(_LEADING_ZERO.match(t) for t in present):
        return cells
    if all(_INT.fullmatch(t) for t in present):
        if any(len(t.lstrip("+-")) > 19 for t in present):  # past int64 (and int()'s limit)
            return cells
        ints = [None if t is None else int(t) for t in cells]
        if all(_INT64[0] <= v <= _INT64[1] for v in ints if v is not None):
            return ints
        return cells
    numbers = [None if t is None else parse_number(t) for t in cells]
    if any(v is None for v, t in zip(numbers, cells, strict=True) if t is not None):
        return cells
    if any(_INT.fullmatch(t) and not _float_holds(t) for t in present):
        return cells
    return numbers


def _float_holds(literal: str) -> bool:
    """Whether float64 holds the integer ``literal`` exactly."""
    digits = len(literal.lstrip("+-"))
    if digits <= 15:
        return True
    return digits <= 309 and float(int(literal)) == int(literal)


def attribute_names(names, reserved) -> list[str]:
    """Input attribute names kept apart from the columns a writer fills itself.

    A name among ``reserved`` becomes ``input_<name>`` (``area`` -> ``input_area``), again
    while it still clashes with a reserved name or an earlier attribute.

    Parameters
    ----------
    names : sequence of str
        The attribute columns, in order.
    reserved : collection of str
        The computed columns (``area``, ``site_id``, ``geometry``, ...).

    Returns
    -------
    list of str
        Unique names, none in ``reserved``; a name that clashes with nothing is unchanged.

    Examples
    --------
    >>> attribute_names(["area", "species", "input_area"], {"area"})
    ['input_input_area', 'species', 'input_area']
    """
    taken = set(reserved)
    out = []
    for name in names:
        key = str(name)
        if key in taken:
            key = f"input_{key}"
            while key in taken or key in names:
                key = f"input_{key}"
        taken.add(key)
        out.append(key)
    return out


def read_npy_points(path, dims: int = 2) -> np.ndarray:
    """Points from a ``.npy`` file holding an ``(n, dims)`` array of real numbers.

    Parameters
    ----------
    path : str or Path
        The file (no pickles).
    dims : {2, 3}
        Coordinates per point.

    Returns
    -------
    (n, dims) float64

    Raises
    ------
    ValueError
        Unreadable file, wrong shape, non-numeric dtype or a non-finite row.
    """
    path = existing_file(path)
    try:
        # mapped first: a header claiming more rows than the file holds is refused here,
        # not allocated (1.46 TiB for a 64-byte file)
        arr = np.array(np.load(path, mmap_mode="r", allow_pickle=False))
    except (ValueError, OSError) as exc:
        raise ValueError(f"{path}: not a readable .npy array ({exc})") from None
    if arr.ndim != 2 or arr.shape[1] != dims:
        raise ValueError(f"{path}: expected an (n, {dims}) array, got shape {arr.shape}")
    if arr.dtype.kind not in "iuf":  # complex would lose its imaginary part, bool is no number
        raise ValueError(f"{path}: array of dtype {arr.dtype} is not real numbers")
    if len(arr) == 0:
        raise ValueError(f"{path}: no points (the array is empty)")
    arr = arr.astype(np.float64)
    if not np.isfinite(arr).all():
        row = int(np.flatnonzero(~np.isfinite(arr).all(axis=1))[0])
        raise ValueError(f"{path}: row {row} is not finite: {arr[row].tolist()}")
    return arr
