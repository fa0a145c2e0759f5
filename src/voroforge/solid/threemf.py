"""A solid's 3MF file, its text written by a numba kernel: the bytes of :func:`io.mesh.write`.

:func:`voroforge.io.mesh.write` writes each vertex coordinate as ``%r``, the shortest text
that reads back bit for bit (0.6 s of Python's float repr for a lattice's 830k
coordinates, plus 0.2 s of ``%d`` for its triangles). The implicit route rounds its
vertices to a decimal grid 1e5 times finer than the voxel (:func:`on_grid`, the places in
``metadata["decimals"]``), so each coordinate is an integer count of grid steps, and its
``repr`` is that integer's
digits with the decimal point set in (or, under 1e-4, with an exponent): the kernel writes
those, and the triangles' indices, straight into a byte buffer. :func:`write_3mf` gives
the same file byte for byte as ``io.mesh.write`` (tested), or leaves the file to
``io.mesh.write`` when a coordinate is not on the grid or is too large for it.

Examples
--------
>>> import numpy as np, tempfile, pathlib
>>> from voroforge.io.mesh import Arrays, read
>>> v = on_grid(np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]) * 10.1, 6)
>>> f = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
>>> out = pathlib.Path(tempfile.mkdtemp()) / "t.3mf"
>>> bool((read(write_3mf(Arrays(v, f), out, decimals=6)).vertices == v).all())
True
"""

from __future__ import annotations

import io
import zipfile
from pathlib import Path

import numpy as np
from numba import njit

from .. import config

__all__ = ["on_grid", "rows_text", "write_3mf"]

_VERTEX = '<vertex x="%r" y="%r" z="%r"/>'
_TRIANGLE = '<triangle v1="%d" v2="%d" v3="%d"/>'
_CHUNK = 1 << 16  # rows of text a piece: a 3MF's text is deflated as it is written


def on_grid(vertices, decimals: int) -> np.ndarray:
    """``vertices`` rounded to ``decimals`` places: each the float nearest ``q / 10**decimals``.

    numpy rounds as ``rint(x * 10**d) / 10**d``, one correctly rounded division of two exact
    numbers, which is the float ``float("<q's digits with the point set in>")`` reads.
    """
    return np.round(np.asarray(vertices, dtype=np.float64), decimals)


@njit(**config.NJIT)
def _rows(q, neg, decimals, pieces, starts, out):
    """Write ``pieces[0] v0 pieces[1] v1 ... pieces[k]`` per row of ``q`` into ``out``.

    ``q`` (n, k) int64 holds each value times ``10**decimals``; ``neg`` marks negative
    values (-0.0 included). A value is written as ``repr`` writes a float of that size: its
    digits, with ``decimals > 0`` a point and at least one fractional digit, trailing zeros
    dropped (``3.0``, ``0.25``, ``-12.5``), under 1e-4 with an exponent (``1.2e-05``); with
    ``decimals == 0`` as an integer (``17``).
    ``starts`` (k + 2,) are the offsets of the pieces in ``pieces``. Returns the bytes used.
    """
    n, k = q.shape
    digits = np.zeros(24, dtype=np.uint8)
    p = 0
    for i in range(n):
        for j in range(k + 1):
            for c in range(starts[j], starts[j + 1]):
                out[p] = pieces[c]
                p += 1
            if j == k:
                break
            x = q[i, j]
            if neg[i, j]:
                out[p] = 45  # '-'
                p += 1
            if x < 0:
                x = -x
            nd = 0
            while True:  # the digits of x, least significant first
                digits[nd] = 48 + x % 10
                x //= 10
                nd += 1
                if x == 0:
                    break
            if decimals > 0 and nd <= decimals - 4 and q[i, j] != 0:
                # under 1e-4: repr writes d.ddde-XX, trailing zeros dropped
                lo = 0
                while digits[lo] == 48:
                    lo += 1
                out[p] = digits[nd - 1]
                p += 1
                if lo < nd - 1:
                    out[p] = 46  # '.'
                    p += 1
                    for t in range(nd - 2, lo - 1, -1):
                        out[p] = digits[t]
                        p += 1
                e = decimals - nd + 1
                out[p] = 101  # 'e'
                out[p + 1] = 45  # '-'
                p += 2
                if e < 10:
                    out[p] = 48
                    p += 1
                ne = 0
                while e > 0:
                    digits[ne] = 48 + e % 10
                    e //= 10
                    ne += 1
                for t in range(ne - 1, -1, -1):
                    out[p] = digits[t]
                    p += 1
                continue
            while nd <= decimals:  # a leading zero: 0.25
                digits[nd] = 48
                nd += 1
            lo = 0
            if decimals > 0:
                while lo < decimals - 1 and digits[lo] == 48:  # keep one fractional digit
                    lo += 1
            for t in range(nd - 1, lo - 1, -1):
                out[p] = digits[t]
                p += 1
                if t == decimals and decimals > 0:
                    out[p] = 46  # '.'
                    p += 1
    return p


def rows_text(values, template: str, decimals: int = 0) -> bytes | None:
    """``template % row`` for every row of ``values``, joined, as ``%r`` / ``%d`` write it.

    Parameters
    ----------
    values : (n, k) float64 or int
        Integers (``decimals == 0``, ``%d``) or floats on the ``decimals`` grid (``%r``).
    template : str
        ``k`` placeholders (``%r`` or ``%d``), ASCII, no other ``%``.
    decimals : int
        Places of the floats' grid; 0 for integers.

    Returns
    -------
    bytes or None
        The text, or None where a float is off the grid, from 1e16 (where ``repr`` writes
        an exponent) or so large that a shorter decimal than the grid's reads back as the
        same float (from ``2**51`` grid steps): the caller formats those itself.
    """
    a = np.asarray(values)
    a = a.reshape(len(a), -1)
    parts = template.replace("%d", "%r").split("%r")
    if len(parts) != a.shape[1] + 1:
        raise ValueError(f"template has {len(parts) - 1} fields for {a.shape[1]} columns")
    if a.dtype.kind == "f":
        decimals = max(int(decimals), 1)  # whole numbers are on the tenths' grid: 3.0
        scale = 10.0**decimals
        q = np.rint(a * scale)
        if not (np.array_equal(q / scale, a) and (np.abs(a) < min(1e16, 2.0**51 / scale)).all()):
            return None
        neg = np.signbit(a)
        q = q.astype(np.int64)
    else:
        q = a.astype(np.int64)
        neg = q < 0
        decimals = 0
    pieces = np.frombuffer("".join(parts).encode("ascii"), dtype=np.uint8)
    starts = np.cumsum([0] + [len(s) for s in parts]).astype(np.int64)
    # digits of |q| < 2**63, a sign, a point and a leading zero per value
    out = np.zeros(len(q) * (int(starts[-1]) + q.shape[1] * 23), dtype=np.uint8)
    used = _rows(np.ascontiguousarray(q), np.ascontiguousarray(neg), decimals, pieces, starts, out)
    return out[:used].tobytes()


def write_3mf(mesh, path, *, units: str = "mm", decimals: int | None = None) -> Path:
    """Write one mesh as 3MF, the bytes :func:`voroforge.io.mesh.write` writes.

    Parameters
    ----------
    mesh : trimesh.Trimesh or voroforge.io.mesh.Arrays
        Its vertices on the ``decimals`` grid (:func:`on_grid`) for the fast text; any other
        mesh is handed to ``io.mesh.write``.
    path : str or Path
        The ``.3mf`` file.
    units : str
        As ``io.mesh.write``.
    decimals : int, optional
        The vertices' grid; default the mesh's ``metadata["decimals"]`` (the implicit
        route's), without which the file is ``io.mesh.write``'s.

    Returns
    -------
    Path
        The file written.
    """
    from ..io import mesh as mio

    path = Path(path)
    if decimals is None:
        decimals = (getattr(mesh, "metadata", None) or {}).get("decimals")
    v = np.asarray(mesh.vertices, dtype=np.float64).reshape(-1, 3)
    f = np.asarray(mesh.faces, dtype=np.int64).reshape(-1, 3)
    vt = None
    if decimals is not None and len(f):  # the vertices' text first: None when off the grid
        vt = [rows_text(v[s : s + _CHUNK], _VERTEX, decimals) for s in range(0, len(v), _CHUNK)]
    if path.suffix.lower() != ".3mf" or vt is None or None in vt or not np.isfinite(v).all():
        return mio.write(mesh, path, units=units)
    units = mio.check_units(units)
    head = [
        b'<?xml version="1.0" encoding="UTF-8"?>\n',
        f'<model unit="{mio.UNITS[units]}" xml:lang="en-US" xmlns="{mio.NS3MF}">'.encode(),
        b'<resources><object id="1" type="model" name="body"><mesh><vertices>',
    ]
    buf = io.BytesIO()
    # as io.mesh._3mf_bytes: deflate level 1, a fixed date, writestr's file mode; the model
    # is deflated as its text is written, a run of rows at a time (the same stream as one
    # block: deflate's output does not depend on how its input is split), so no copy of the
    # whole text is made
    with zipfile.ZipFile(buf, "w", zipfile.ZIP_DEFLATED, compresslevel=1) as z:
        for name, data in (("[Content_Types].xml", mio.CONTENT_TYPES), ("_rels/.rels", mio.RELS)):
            z.writestr(_info(name), data, zipfile.ZIP_DEFLATED, compresslevel=1)
        with z.open(_info("3D/3dmodel.model", deflate=1), "w") as model:
            for piece in head + vt:
                model.write(piece)
            model.write(b"</vertices><triangles>")
            for s in range(0, len(f), _CHUNK):
                model.write(rows_text(f[s : s + _CHUNK], _TRIANGLE))
            model.write(b"</triangles></mesh></object></resources><build>")
            model.write(b'<item objectid="1"/></build></model>')
    return mio.save_bytes(path, buf.getvalue())


def _info(name: str, *, deflate: int | None = None) -> zipfile.ZipInfo:
    """A zip member with io.mesh's fixed date and writestr's file mode.

    With ``deflate``, deflated at that level: what ``writestr(..., compresslevel=...)``
    sets on the member it writes.
    """
    from ..io.mesh import ZIP_DATE

    info = zipfile.ZipInfo(name, ZIP_DATE)
    info.external_attr = 0o600 << 16
    if deflate is not None:
        info.compress_type = zipfile.ZIP_DEFLATED
        if hasattr(info, "compress_level"):  # Python 3.13 names it
            info.compress_level = deflate
        else:
            info._compresslevel = deflate
    return info
