"""The studio's binary messages: a JSON header and flat typed arrays (GeoArrow-like rings).

A message is ``b"VFS1"``, the header's byte length (uint32, little-endian), the UTF-8 JSON
header padded with spaces to a multiple of 8, then each array padded to a multiple of 8
bytes. ``header["arrays"]`` lists ``[name, dtype, count]`` in order, so the page reads each
as a ``Float32Array``/``Int32Array``/... view on the message without copying.

Polygonal geometry travels as :func:`rings`: per geometry its first ring
(``geom_offsets``), per ring its first coordinate (``ring_offsets``) and float32
coordinates, the flat layout of GeoArrow without the polygon level (the page fills each
geometry's rings with the even-odd rule, so holes and multi-parts need no more).

Coordinates that are only drawn may travel as :func:`quantize` makes them: uint16 steps of
a fraction of the page's pixel from an origin, half the bytes of float32 (the header says
how to read them back).
"""

from __future__ import annotations

import json
import struct

import numpy as np
import shapely

__all__ = ["MAGIC", "dequantize", "pack", "quantize", "rings", "unpack"]

MAGIC = b"VFS1"
_DTYPES = {
    "f4": np.float32,
    "f8": np.float64,
    "i4": np.int32,
    "u1": np.uint8,
    "u2": np.uint16,
}


def rings(geoms, tol: float | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Flat ring buffers of polygonal geometries (empty ones have no rings).

    Parameters
    ----------
    geoms : (n,) object array of shapely Polygon/MultiPolygon
    tol : float, optional
        For drawing only: a vertex in the same ``tol``-square of a grid as the vertex before
        it is left out (each kept vertex stands for a run of vertices less than
        ``tol * sqrt(2)`` away from it; rings keep their first and last vertex and at least
        four). A page passes half its pixel size: a fillet's arcs have far more vertices
        than pixels.

    Returns
    -------
    geom_offsets : (n + 1,) int32
        Geometry ``i`` owns rings ``geom_offsets[i]:geom_offsets[i + 1]``.
    ring_offsets : (r + 1,) int32
        Ring ``j`` owns coordinates ``ring_offsets[j]:ring_offsets[j + 1]`` (closed rings,
        the last coordinate repeats the first).
    coords : (c, 2) float32
    """
    geoms = np.asarray(geoms, dtype=object).reshape(-1)
    n = len(geoms)
    if not n:
        return np.zeros(1, np.int32), np.zeros(1, np.int32), np.zeros((0, 2), np.float32)
    # A polygon without holes is one ring holding all its coordinates: no need to take it
    # apart (cloning parts and rings costs far more than reading the coordinates).
    counts = shapely.get_num_coordinates(geoms)
    simple = (shapely.get_type_id(geoms) == 3) & (shapely.get_num_interior_rings(geoms) == 0)
    hard = np.flatnonzero(~simple & (counts > 0))
    per_geom = (counts > 0).astype(np.int64)
    lengths = {}
    if len(hard):
        parts, part_of = shapely.get_parts(geoms[hard], return_index=True)
        ring_geoms, ring_of_part = shapely.get_rings(parts, return_index=True)
        ring_len = shapely.get_num_coordinates(ring_geoms)
        owner = part_of[ring_of_part]
        per_geom[hard] = np.bincount(owner, minlength=len(hard))
        lengths = dict(
            zip(hard.tolist(), np.split(ring_len, np.cumsum(per_geom[hard])[:-1]), strict=True)
        )
    geom_offsets = np.zeros(n + 1, dtype=np.int64)
    np.cumsum(per_geom, out=geom_offsets[1:])
    ring_len = np.zeros(int(geom_offsets[-1]), dtype=np.int64)
    one = np.flatnonzero(simple & (counts > 0))
    ring_len[geom_offsets[one]] = counts[one]
    for k, ls in lengths.items():
        ring_len[geom_offsets[k] : geom_offsets[k] + len(ls)] = ls
    ring_offsets = np.zeros(len(ring_len) + 1, dtype=np.int64)
    np.cumsum(ring_len, out=ring_offsets[1:])
    coords = shapely.get_coordinates(geoms)
    if tol is not None and tol > 0 and len(coords):
        ring_offsets, coords = _thin(ring_offsets, coords, float(tol))
    return geom_offsets.astype(np.int32), ring_offsets.astype(np.int32), coords.astype(np.float32)


def _thin(ring_offsets: np.ndarray, coords: np.ndarray, tol: float):
    """Drop each vertex whose ``tol``-grid square is that of the vertex before it (see rings)."""
    inv = 1.0 / tol
    kx = np.floor(coords[:, 0] * inv)
    ky = np.floor(coords[:, 1] * inv)
    keep = np.ones(len(coords), dtype=bool)
    np.not_equal(kx[1:], kx[:-1], out=keep[1:])
    keep[1:] |= ky[1:] != ky[:-1]
    starts, ends = ring_offsets[:-1], ring_offsets[1:]
    full = ends > starts
    keep[starts[full]] = True
    keep[ends[full] - 1] = True
    kept = np.add.reduceat(keep.astype(np.int64), starts[full]) if full.any() else keep[:0]
    counts = np.zeros(len(starts), dtype=np.int64)
    counts[full] = kept
    few = np.flatnonzero(full & (counts < 4))  # a ring smaller than the grid: keep it whole
    for j in few:
        keep[starts[j] : ends[j]] = True
        counts[j] = ends[j] - starts[j]
    out = np.zeros(len(ring_offsets), dtype=np.int64)
    np.cumsum(counts, out=out[1:])
    # as one complex per row: boolean indexing of (n, 2) rows is far slower
    pairs = np.ascontiguousarray(coords, dtype=np.float64).view(np.complex128)[:, 0]
    return out, pairs[keep].view(np.float64).reshape(-1, 2)


#: The steps :func:`quantize` tries, as fractions of a pixel (finest first)
STEPS_PER_PIXEL = (64, 32, 16, 8)


def quantize(coords: np.ndarray, px: float) -> tuple[list[float], np.ndarray] | None:
    """Coordinates as uint16 multiples of a step from an origin, or None where they do not fit.

    The step is the finest of ``px / STEPS_PER_PIXEL`` (``px``: the page's pixel size in
    design units) at which the coordinates' extent takes at most 65,535 steps; each
    coordinate moves by at most half a step (1/128 to 1/16 of a pixel).

    Parameters
    ----------
    coords : (c, 2) float array
    px : float

    Returns
    -------
    (list of float, (2c,) uint16) or None
        ``[x0, y0, step]`` and the codes: ``x = x0 + code * step`` (:func:`dequantize`).
    """
    xy = np.asarray(coords, dtype=np.float64).reshape(-1, 2)
    if not len(xy) or not (px > 0 and np.isfinite(px)):
        return None
    x, y = xy[:, 0], xy[:, 1]  # per column: a reduction over axis 0 of (c, 2) is far slower
    origin = np.array([x.min(), y.min()])
    extent = max(float(x.max() - origin[0]), float(y.max() - origin[1]))
    for k in STEPS_PER_PIXEL:
        step = px / k
        if extent / step <= 65535.0 - 1.0:
            codes = np.rint((xy - origin) / step).astype(np.uint16).reshape(-1)
            return [float(origin[0]), float(origin[1]), float(step)], codes
    return None


def dequantize(q, codes: np.ndarray) -> np.ndarray:
    """``(c, 2)`` float64 coordinates of :func:`quantize`'s ``q`` and codes."""
    c = np.asarray(codes, dtype=np.float64).reshape(-1, 2)
    return np.asarray(q[:2], dtype=np.float64) + c * float(q[2])


def pack(header: dict, arrays: dict[str, np.ndarray]) -> bytes:
    """One binary message: ``header`` (JSON) and the named arrays after it.

    Returns
    -------
    bytes
    """
    listed, blobs = [], []
    for name, arr in arrays.items():
        a = np.ascontiguousarray(arr)
        code = {np.dtype(v): k for k, v in _DTYPES.items()}.get(a.dtype)
        if code is None:
            raise ValueError(f"array {name!r}: dtype {a.dtype} cannot travel")
        raw = a.astype(a.dtype.newbyteorder("<"), copy=False).tobytes()
        listed.append([name, code, int(a.size)])
        blobs.append(raw + b"\0" * (-len(raw) % 8))
    text = json.dumps({**header, "arrays": listed}, separators=(",", ":"), allow_nan=False)
    head = text.encode("utf-8")
    head += b" " * (-(len(head) + 8) % 8)
    return MAGIC + struct.pack("<I", len(head)) + head + b"".join(blobs)


def unpack(message: bytes) -> tuple[dict, dict[str, np.ndarray]]:
    """The header and arrays of a :func:`pack` message (for tests and the Python widget).

    Raises
    ------
    ValueError
        For a message that is not one.
    """
    if len(message) < 8 or message[:4] != MAGIC:
        raise ValueError("not a studio message")
    (length,) = struct.unpack("<I", message[4:8])
    header = json.loads(message[8 : 8 + length].decode("utf-8"))
    offset = 8 + length
    out = {}
    for name, code, count in header.pop("arrays"):
        dtype = np.dtype(_DTYPES[code]).newbyteorder("<")
        size = dtype.itemsize * count
        out[name] = np.frombuffer(message, dtype=dtype, count=count, offset=offset)
        offset += size + (-size % 8)
    return header, out
