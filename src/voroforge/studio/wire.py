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
from numba import njit

from ..config import NJIT

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
        For drawing only: each ring thinned (Douglas-Peucker, :func:`_thin`) so that every
        vertex left out lies within ``tol / 2`` of the kept ring, and the kept ring within
        ``tol / 2`` of the whole one; rings keep their first and last vertex, both ends of
        every edge longer than ``tol`` and at least four vertices. A page passes half its
        pixel size (a quarter of a pixel off at most): a fillet's arcs have far more
        vertices than pixels.

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
    """Rings thinned to within ``tol / 2`` (see :func:`rings`); (offsets, coordinates)."""
    return _simplify(
        np.ascontiguousarray(coords, dtype=np.float64),
        np.ascontiguousarray(ring_offsets, dtype=np.int64),
        0.5 * tol,
        tol,
    )


@njit(**NJIT)
def _simplify(xy, offsets, eps, edge):
    """Douglas-Peucker of each closed ring of ``xy`` (ring ``j``: ``offsets[j]:offsets[j+1]``).

    A ring keeps its first and last vertex and both ends of every edge longer than
    ``edge`` (a corner the page can show); each run of shorter edges between two kept
    vertices keeps its vertex farthest from their segment while that is more than ``eps``
    away (then both halves again). Every vertex left out is within ``eps`` of the segment
    that replaces it, so the thinned ring and the whole one are within ``eps`` of each
    other. A ring left with fewer than four vertices is kept whole (smaller than ``eps``:
    nothing to gain).

    Returns
    -------
    offsets : (m + 1,) int64
    xy : (k, 2) float64
    """
    m = len(offsets) - 1
    n = len(xy)
    keep = np.zeros(n, dtype=np.bool_)
    counts = np.zeros(m, dtype=np.int64)
    widest = np.int64(0)
    for j in range(m):
        widest = max(widest, offsets[j + 1] - offsets[j])
    stack = np.zeros(2 * widest + 2, dtype=np.int64)  # the runs of one ring
    e2 = eps * eps
    edge2 = edge * edge
    for j in range(m):
        s0 = offsets[j]
        s1 = offsets[j + 1]
        if s1 - s0 <= 4:
            for t in range(s0, s1):
                keep[t] = True
            counts[j] = s1 - s0
            continue
        keep[s0] = True
        keep[s1 - 1] = True
        for t in range(s0, s1 - 1):
            ex = xy[t + 1, 0] - xy[t, 0]
            ey = xy[t + 1, 1] - xy[t, 1]
            if ex * ex + ey * ey > edge2:
                keep[t] = True
                keep[t + 1] = True
        # the runs between kept vertices
        kept = np.int64(1)
        top = np.int64(0)
        last = s0
        for t in range(s0 + 1, s1):
            if keep[t]:
                kept += 1
                stack[top] = last
                stack[top + 1] = t
                top += 2
                last = t
        while top > 0:
            b = stack[top - 1]
            a = stack[top - 2]
            top -= 2
            if b - a < 2:
                continue
            ax = xy[a, 0]
            ay = xy[a, 1]
            dx = xy[b, 0] - ax
            dy = xy[b, 1] - ay
            ll = dx * dx + dy * dy
            inv = 1.0 / ll if ll > 0.0 else 0.0
            far = -1.0
            at = np.int64(-1)
            for t in range(a + 1, b):
                px = xy[t, 0] - ax
                py = xy[t, 1] - ay
                dot = px * dx + py * dy
                if dot <= 0.0:  # nearest to a (or a and b are one point)
                    d2 = px * px + py * py
                elif dot >= ll:  # nearest to b
                    qx = px - dx
                    qy = py - dy
                    d2 = qx * qx + qy * qy
                else:
                    cr = px * dy - py * dx
                    d2 = cr * cr * inv
                if d2 > far:
                    far = d2
                    at = t
            if far > e2:
                keep[at] = True
                kept += 1
                stack[top] = a
                stack[top + 1] = at
                stack[top + 2] = at
                stack[top + 3] = b
                top += 4
        if kept < 4:
            for t in range(s0, s1):
                keep[t] = True
            kept = s1 - s0
        counts[j] = kept
    out_offsets = np.zeros(m + 1, dtype=np.int64)
    for j in range(m):
        out_offsets[j + 1] = out_offsets[j] + counts[j]
    out = np.zeros((out_offsets[m], 2))
    w = np.int64(0)
    for t in range(n):
        if keep[t]:
            out[w, 0] = xy[t, 0]
            out[w, 1] = xy[t, 1]
            w += 1
    return out_offsets, out


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
        if not step > 0.0:  # px / k underflowed: send the coordinates as they are
            return None
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
