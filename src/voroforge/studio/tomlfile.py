"""Write a design mapping back to TOML text (the studio's *save*), and save files safely.

:func:`dumps` writes the plain data of a design file (tables, arrays of tables, inline
tables for small mappings such as ``{ near = 6, far = 1 }``) so that ``tomllib.loads``
gives the same mapping back: floats are written with ``repr`` (shortest round trip), so
no coordinate moves by a bit. :func:`write_atomic` writes through a temporary file in the
same folder and renames it over the target.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

from ..io.atomic import write_bytes

__all__ = ["dumps", "write_atomic"]

_BARE = re.compile(r"[A-Za-z0-9_-]+")


def _key(k) -> str:
    k = str(k)
    return k if _BARE.fullmatch(k) else _string(k)  # fullmatch: "$" passes a final newline


def _string(s: str) -> str:
    out = ['"']
    for ch in s:
        if ch in '"\\':
            out.append("\\" + ch)
        elif ch == "\n":
            out.append("\\n")
        elif ch == "\t":
            out.append("\\t")
        elif ord(ch) < 0x20 or ord(ch) == 0x7F:
            out.append(f"\\u{ord(ch):04x}")
        else:
            out.append(ch)
    out.append('"')
    return "".join(out)


def _value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        if not -(2**63) <= v < 2**63:
            raise ValueError(f"cannot write {v} to a design file (TOML integers are 64-bit)")
        return str(v)
    if isinstance(v, float):
        if not math.isfinite(v):
            raise ValueError(f"cannot write {v!r} to a design file (finite numbers only)")
        text = repr(v)
        return text if any(c in text for c in ".en") else text + ".0"
    if isinstance(v, str):
        return _string(v)
    if isinstance(v, list | tuple):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    if isinstance(v, dict):
        if not v:
            return "{}"
        return "{ " + ", ".join(f"{_key(k)} = {_value(x)}" for k, x in v.items()) + " }"
    if hasattr(v, "item"):  # numpy scalars
        return _value(v.item())
    raise ValueError(f"cannot write a {type(v).__name__} to a design file")


def _is_table_array(v) -> bool:
    return isinstance(v, list) and bool(v) and all(isinstance(x, dict) for x in v)


def _inline(v: dict) -> bool:
    """Small flat mappings (``{near, far}``, layer maps) stay inline."""
    return all(not isinstance(x, dict) and not _is_table_array(x) for x in v.values())


def _table(path: list[str], data: dict, out: list[str], header: str | None) -> None:
    plain = [(k, v) for k, v in data.items() if not _subtable(v)]
    subs = [(k, v) for k, v in data.items() if _subtable(v)]
    # an item of an array of tables always gets its ``[[...]]`` line, even one holding only
    # sub-tables: without it TOML merges the item into the one before (or redefines a table)
    if header is not None and (plain or not subs or header.startswith("[[")):
        out.append(header)
    for k, v in plain:
        out.append(f"{_key(k)} = {_value(v)}")
    for k, v in subs:
        sub = [*path, _key(k)]
        if isinstance(v, dict):
            if out:
                out.append("")
            _table(sub, v, out, "[" + ".".join(sub) + "]")
        else:
            for item in v:
                if out:
                    out.append("")
                _table(sub, item, out, "[[" + ".".join(sub) + "]]")


def _subtable(v) -> bool:
    return (isinstance(v, dict) and not (_inline(v) and len(v) <= 4)) or _is_table_array(v)


def dumps(data: dict, *, comment: str | None = None) -> str:
    """The TOML text of a design mapping (what ``tomllib.loads`` reads back unchanged).

    Parameters
    ----------
    data : dict
        A design file's mapping: top-level tables, arrays of tables, values.
    comment : str, optional
        A ``#`` comment line at the top.

    Returns
    -------
    str

    Raises
    ------
    ValueError
        For values TOML cannot hold (NaN, infinities, ``None``, objects).

    Examples
    --------
    >>> print(dumps({"boundary": {"shape": "circle", "radius": 50.0}, "cells": {"web": 2}}))
    [boundary]
    shape = "circle"
    radius = 50.0
    <BLANKLINE>
    [cells]
    web = 2
    <BLANKLINE>
    """
    out: list[str] = []
    if comment:
        out.extend(f"# {line}".rstrip() for line in comment.splitlines())
        out.append("")
    top = [(k, v) for k, v in data.items() if not isinstance(v, dict) and not _is_table_array(v)]
    for k, v in top:
        out.append(f"{_key(k)} = {_value(v)}")
    for k, v in data.items():
        if isinstance(v, dict):
            if out and out[-1] != "":
                out.append("")
            _table([_key(k)], v, out, f"[{_key(k)}]")
        elif _is_table_array(v):
            for item in v:
                if out and out[-1] != "":
                    out.append("")
                _table([_key(k)], item, out, f"[[{_key(k)}]]")
    return "\n".join(out) + "\n"


def write_atomic(path, data: bytes | str) -> Path:
    """Write ``data`` to ``path`` through a temporary file in its folder, then rename.

    A reader never sees a half-written file, and a failed write leaves the old file as it
    was.

    Returns
    -------
    Path
    """
    raw = data.encode("utf-8") if isinstance(data, str) else bytes(data)
    # io.atomic's rename, so a saved file gets the mode of every other output (0666 less the
    # umask; its own mkstemp left 0600, also on a design saved over)
    return write_bytes(path, raw)
