"""Inset and fillet of convex cells, computed directly and vectorised over all cells.

A Voronoi cell that the domain boundary does not cut is a convex polygon, and for a convex
polygon both operations have closed forms that GEOS's general buffer does not exploit:

- **inset** by ``d``: the intersection of the cell's half-planes, each moved inward by
  ``d``. Its vertices are the crossings of the moved lines of consecutive edges; an edge
  whose moved segment has negative length has vanished (it can never come back, because
  the other edges only shrink faster once a neighbour is gone), so it is dropped and its
  neighbours are crossed directly, until no edge vanishes. A cell vanishes when fewer than
  three edges remain or two consecutive ones turn by half a turn or more.
- **fillet** (opening) by ``r``: the inset by ``r`` grown back by ``r``, i.e. every edge
  back in place and every corner of the inset replaced by a circular arc of radius ``r``
  tangent to both edges. The arc is sampled the way GEOS samples a round join
  (``round(sweep / (pi / 2 / quad_segs))`` equal chords, at least one), so runs of chords
  are recognised as arcs by :mod:`voroforge.io.arcs` for the DXF and SVG writers.

Cells are passed around as flat rings: ``xy (N, 2)`` counter-clockwise vertices without the
closing point and ``start (m + 1,)`` offsets. Rings go back to shapely clockwise, as GEOS
returns the shells of a buffer. Cells that are not single convex polygons without holes
(the pieces the boundary cuts), and the rare ones whose moved lines cross at a near-parallel
angle, are left to GEOS by the callers in :mod:`voroforge.design.cellops`.
"""

from __future__ import annotations

import math

import numpy as np
import shapely
from numba import njit

from ..config import (
    CONVEX_ARC_SEPARATION,
    CONVEX_FULL_TURN_TOL,
    CONVEX_PARALLEL_TURN,
    CONVEX_SHORT_EDGE_RTOL,
    CONVEX_STRAIGHT_TURN,
    NJIT,
)

__all__ = ["convex_rings", "fillet_rings", "inset_rings", "polygons", "reconvex", "take"]


def _ring_index(start: np.ndarray):
    """Owner ring, next and previous vertex of every vertex of flat rings."""
    count = np.diff(start)
    owner = np.repeat(np.arange(len(count)), count)
    idx = np.arange(start[-1])
    nxt = idx + 1
    last = start[1:][count > 0] - 1
    nxt[last] = start[:-1][count > 0]
    prv = idx - 1
    prv[start[:-1][count > 0]] = last
    return owner, nxt, prv


def _kept_counts(keep: np.ndarray, start: np.ndarray) -> np.ndarray:
    c = np.concatenate(([0], np.cumsum(keep, dtype=np.int64)))
    return c[start[1:]] - c[start[:-1]]


def take(xy: np.ndarray, start: np.ndarray, keep: np.ndarray):
    """The flat rings ``keep`` (an ``(m,)`` mask) of ``xy, start``."""
    count = np.diff(start)
    owner = np.repeat(np.arange(len(count)), count)
    return xy[keep[owner]], np.concatenate(([0], np.cumsum(count[keep])))


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return a[:, 0] * b[:, 0] + a[:, 1] * b[:, 1]


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]


def convex_rings(cells: np.ndarray):
    """The cells that are single convex polygons, as flat counter-clockwise rings.

    Parameters
    ----------
    cells : (n,) object array of shapely geometries

    Returns
    -------
    mask : (n,) bool
        Cells taken (non-empty single Polygons without holes, every turn to the same side).
    xy : (N, 2) float64
        Their vertices, counter-clockwise, straight vertices and repeated points dropped.
    start : (mask.sum() + 1,) int64
        Ring offsets into ``xy``.
    """
    cells = np.asarray(cells, dtype=object)
    mask = (shapely.get_type_id(cells) == 3) & ~shapely.is_empty(cells)
    mask &= shapely.get_num_interior_rings(cells) == 0
    idx = np.flatnonzero(mask)
    xy, owner = shapely.get_coordinates(cells[idx], return_index=True)  # the shells only
    ok, xy, start = _convex(xy, np.bincount(owner, minlength=len(idx)))
    mask[idx[~ok]] = False
    return mask, xy, start


def reconvex(xy: np.ndarray, start: np.ndarray):
    """:func:`convex_rings` of ``polygons(xy, start)``, without making the polygons.

    The flat rings of :func:`inset_rings` or :func:`fillet_rings` go on to the next operation
    as the shapely round trip would give them (the same bytes): each ring as GEOS would hold
    it (clockwise, closed), then the same clean-up and convexity test.

    Returns
    -------
    ok : (m,) bool
        Rings taken (a ring :func:`polygons` leaves empty is not).
    xy, start
        The taken rings, as :func:`convex_rings` returns them.
    """
    count = np.diff(start)
    live = count >= 3
    if not live.all():
        xy, start = take(xy, start, live)
        count = np.diff(start)
    # each ring clockwise, as polygons() hands it to GEOS
    owner = np.repeat(np.arange(len(count)), count)
    rev = start[owner + 1] - 1 - (np.arange(len(xy)) - start[owner])
    cw = _rows(xy, rev)
    # and closed, as GEOS closes it: its first point again, unless the last one is that
    first, last = cw[start[:-1]], cw[start[1:] - 1]
    open_ = (first[:, 0] != last[:, 0]) | (first[:, 1] != last[:, 1])
    shift = np.concatenate(([0], np.cumsum(open_)))
    closed = np.zeros((len(xy) + int(shift[-1]), 2))
    closed[np.arange(len(xy)) + shift[owner]] = cw
    closed[start[1:][open_] + shift[1:][open_] - 1] = first[open_]
    ok_live, xy, start = _convex(closed, count + open_)
    ok = np.zeros(len(live), dtype=bool)
    ok[live] = ok_live
    return ok, xy, start


def _rows(xy: np.ndarray, index: np.ndarray) -> np.ndarray:
    """``xy[index]`` (integer or boolean) of (N, 2) float64 rows, as complex numbers.

    The same values; indexing rows of two floats is several times slower.
    """
    pairs = np.ascontiguousarray(xy, dtype=np.float64).view(np.complex128)[:, 0]
    return pairs[index].view(np.float64).reshape(-1, 2)


def _convex(xy: np.ndarray, count: np.ndarray):
    """The convexity test and clean-up of :func:`convex_rings` on closed rings as GEOS holds them.

    Returns
    -------
    ok : (len(count),) bool
    xy, start
        The rings taken.
    """
    m = len(count)
    xy = np.ascontiguousarray(xy, dtype=np.float64)
    xy, start, twice, cross, dot = _clean(xy, np.asarray(count, dtype=np.int64))
    ok = twice != 0
    owner = np.repeat(np.arange(m), np.diff(start))
    turn = np.arctan2(cross, dot)  # (numpy's atan2: see _arcs)
    count = np.diff(start)
    ok &= count >= 3
    ok &= np.bincount(owner, turn <= 0, minlength=m) == 0
    total = np.bincount(owner, turn, minlength=m)
    ok &= np.abs(total - 2.0 * math.pi) <= CONVEX_FULL_TURN_TOL  # once round: a simple convex ring
    return ok, _rows(xy, ok[owner]), np.concatenate(([0], np.cumsum(count[ok])))


@njit(**NJIT)
def _clean(xy, count):
    """The clean-up of :func:`_convex`, ring by ring.

    The closing point dropped, the ring counter-clockwise (reversed where the shoelace sum
    ``twice`` of its signed area is negative), then repeated points and straight vertices
    dropped (of two neighbouring straight vertices only the first, then look again) until
    none is.

    The operations of the vectorised numpy this replaces, in its order (sums in vertex order,
    ``math.hypot`` the C library's, as numpy's is), so the same bytes.

    Returns
    -------
    xy, start
        The cleaned rings.
    twice : (m,) float64
        Twice each ring's signed area, before the clean-up.
    cross, dot : (len(xy),) float64
        Of each vertex's incoming and outgoing edges, in the cleaned rings.
    """
    m = len(count)
    size = 0
    widest = 0
    for r in range(m):
        size += max(count[r] - 1, 0)
        widest = max(widest, count[r])
    out = np.zeros((size, 2))
    start = np.zeros(m + 1, dtype=np.int64)
    twice = np.zeros(m)
    cross = np.zeros(size)
    dot = np.zeros(size)
    drop = np.zeros(widest, dtype=np.bool_)
    keep = np.zeros(widest, dtype=np.bool_)
    src = 0
    at = 0
    for r in range(m):
        n = max(count[r] - 1, 0)
        b = at
        for k in range(n):
            out[b + k, 0] = xy[src + k, 0]
            out[b + k, 1] = xy[src + k, 1]
        src += count[r]
        t = 0.0
        for k in range(n):
            j = k + 1 if k + 1 < n else 0
            t += out[b + k, 0] * out[b + j, 1] - out[b + k, 1] * out[b + j, 0]
        twice[r] = t
        if t < 0:
            for k in range(n // 2):
                for c in range(2):
                    out[b + k, c], out[b + n - 1 - k, c] = out[b + n - 1 - k, c], out[b + k, c]
        while n > 0:
            for k in range(n):
                p = k - 1 if k > 0 else n - 1
                q = k + 1 if k + 1 < n else 0
                i0 = out[b + k, 0] - out[b + p, 0]
                i1 = out[b + k, 1] - out[b + p, 1]
                o0 = out[b + q, 0] - out[b + k, 0]
                o1 = out[b + q, 1] - out[b + k, 1]
                l_in = math.hypot(i0, i1)
                l_out = math.hypot(o0, o1)
                cr = i0 * o1 - i1 * o0
                dt = i0 * o0 + i1 * o1
                cross[b + k] = cr
                dot[b + k] = dt
                drop[k] = (l_in == 0.0) or (
                    abs(cr) <= CONVEX_STRAIGHT_TURN * l_in * l_out and dt > 0
                )
            dropped = False
            for k in range(n):
                p = k - 1 if k > 0 else n - 1
                keep[k] = not (drop[k] and not (drop[p] and k != p))
                dropped |= not keep[k]
            if not dropped:
                break
            w = 0
            for k in range(n):
                if keep[k]:
                    out[b + w, 0] = out[b + k, 0]
                    out[b + w, 1] = out[b + k, 1]
                    w += 1
            n = w
        at = b + n
        start[r + 1] = at
    return out[:at], start, twice, cross[:at], dot[:at]


def inset_rings(xy: np.ndarray, start: np.ndarray, distance):
    """Move every edge of convex rings inward by ``distance`` (per ring or scalar, >= 0).

    Parameters
    ----------
    xy, start
        Counter-clockwise convex rings (from :func:`convex_rings`).
    distance : float or (m,) array_like
        Inset of each ring.

    Returns
    -------
    xy : (K, 2) float64
        The inset rings (counter-clockwise; an emptied ring has no vertices).
    start : (m + 1,) int64
        Their offsets.
    normal : (K, 2) float64
        Inward unit normal of the edge that starts at each vertex (for :func:`fillet_rings`).
    hard : (m,) bool
        Rings whose moved lines met too close to parallel to cross accurately (left to GEOS).
    """
    m = len(start) - 1
    d = np.broadcast_to(np.asarray(distance, dtype=np.float64), (m,))
    owner, nxt, prv = _ring_index(start)
    e = _rows(xy, nxt) - xy
    length = np.hypot(e[:, 0], e[:, 1])
    tangent = e / length[:, None]
    normal = np.stack((-tangent[:, 1], tangent[:, 0]), axis=1)
    size = np.zeros(m)
    live = np.diff(start) > 0
    if live.any():
        lo = np.minimum.reduceat(xy, start[:-1][live])
        hi = np.maximum.reduceat(xy, start[:-1][live])
        size[live] = np.max(hi - lo, axis=1)
    # an inset past the ring's extent empties it (its inradius is at most half that): so
    # capped, a huge distance (the studio's slider at 1e308) cannot overflow the products
    d = np.minimum(d, 2.0 * size)
    # the moved line of edge k: points q = base + s * tangent, base = xy + d * normal
    dk = d[0] if m and (d == d[0]).all() else d[owner, None]  # one distance: the same products
    base = xy + dk * normal
    # first round: neighbours share the vertex, the crossing is xy + d (n_p + n_k) / (1 + c),
    # c = n_p . n_k; at a corner sharper than a right angle 1 + c ~ theta^2 / 2 cancels
    # (a 2e-9 corner gave NaN, one of 2e-7 a vertex 1.9e-4 off), so there the same point is
    # xy + d (t_k - t_p) / (t_p x t_k), which has no cancellation: t_k - t_p ~ 2 t_k
    n_p = _rows(normal, prv)
    t_p = _rows(tangent, prv)
    c = _dot(n_p, normal)
    sharp = c < 0.0
    num = np.where(sharp[:, None], tangent - t_p, n_p + normal)
    vert = xy + dk * num / np.where(sharp, _cross(t_p, tangent), 1.0 + c)[:, None]
    # the moved segment of edge k runs from vert[k] to vert[k + 1]
    gone = _dot(_rows(vert, nxt) - vert, tangent) <= CONVEX_SHORT_EDGE_RTOL * size[owner]
    keep = np.ones(len(xy), dtype=bool)
    hard = np.zeros(m, dtype=bool)
    if gone.any():  # drop edges until none vanishes, in the rings that lost one only
        rings = np.unique(owner[gone])
        lost_edge = np.zeros(m, dtype=bool)
        lost_edge[rings] = True
        idx = np.flatnonzero(lost_edge[owner])
        sub = np.concatenate(([0], np.cumsum(np.diff(start)[rings])))
        alive, vert[idx], lost, hard[rings] = _drop(
            sub, normal[idx], tangent[idx], base[idx], vert[idx], gone[idx], size[rings]
        )
        keep[idx] = alive & ~(lost | hard[rings])[np.repeat(np.arange(len(rings)), np.diff(sub))]
    counts = np.bincount(owner[keep], minlength=m)
    out_start = np.concatenate(([0], np.cumsum(counts)))
    return _rows(vert, keep), out_start, _rows(normal, keep), hard


def _drop(start, normal, tangent, base, vert, gone, size):
    """Drop vanished edges of rings and cross their live neighbours, until none vanishes.

    Returns the live edges, the crossings (``vert``, updated), and per ring whether it
    emptied and whether two moved lines met too close to parallel (``hard``).
    """
    m = len(start) - 1
    owner, nxt, first_prv = _ring_index(start)
    empty = np.zeros(m, dtype=bool)
    hard = np.zeros(m, dtype=bool)
    alive = np.ones(len(vert), dtype=bool)
    for _ in range(len(vert) + 1):
        if not gone.any():
            break
        alive &= ~gone
        empty |= np.bincount(owner, alive, minlength=m) < 3
        alive &= ~empty[owner]
        # relink the live edges of each ring and cross each with its live predecessor
        live_idx = np.flatnonzero(alive)
        sub_start = np.concatenate(([0], np.cumsum(np.bincount(owner[live_idx], minlength=m))))
        _, s_nxt, s_prv = _ring_index(sub_start)
        nxt = np.arange(len(vert))
        nxt[live_idx] = live_idx[s_nxt]
        p, k = live_idx[s_prv], live_idx
        moved = p != first_prv[k]  # only edges with a new predecessor cross anew
        p, k = p[moved], k[moved]
        turn = np.arctan2(_cross(normal[p], normal[k]), _dot(normal[p], normal[k]))
        # half a turn or more between consecutive live edges: nothing is left
        bad = (turn <= 0.0) | (turn >= math.pi)
        empty[owner[k[bad]]] = True
        near = ~bad & (turn < CONVEX_PARALLEL_TURN)
        hard[owner[k[near]]] = True
        fresh = ~bad & ~near
        kk, pp = k[fresh], p[fresh]
        # cross the moved line of k (base[k] + s tangent[k]) with that of p
        den = _cross(normal[pp], normal[kk])  # normal_p . tangent_k
        s = _dot(base[pp] - base[kk], normal[pp]) / den
        vert[kk] = base[kk] + s[:, None] * tangent[kk]
        alive &= ~(empty | hard)[owner]
        gone = alive & (_dot(vert[nxt] - vert, tangent) <= CONVEX_SHORT_EDGE_RTOL * size[owner])
    return alive, vert, empty, hard


def fillet_rings(xy: np.ndarray, start: np.ndarray, radius, quad_segs: int):
    """Open convex rings by ``radius``: inset by it, then every corner an arc of it.

    Parameters
    ----------
    xy, start
        Counter-clockwise convex rings (from :func:`convex_rings`).
    radius : float or (m,) array_like
        Fillet radius of each ring (> 0).
    quad_segs : int
        Chords per quarter circle.

    Returns
    -------
    xy : (K, 2) float64
        The filleted rings, counter-clockwise (an emptied ring has no vertices).
    start : (m + 1,) int64
        Their offsets.
    hard : (m,) bool
        As for :func:`inset_rings`.
    """
    m = len(start) - 1
    r = np.broadcast_to(np.asarray(radius, dtype=np.float64), (m,))
    core, cstart, normal, hard = inset_rings(xy, start, r)
    owner, nxt, prv = _ring_index(cstart)
    n_in = _rows(normal, prv)  # inward normals of the edges before and after each corner
    turn = np.arctan2(_cross(n_in, normal), _dot(n_in, normal))
    a0 = np.arctan2(-n_in[:, 1], -n_in[:, 0])  # (atan2 by numpy: its SIMD one, not libm's)
    if not np.ndim(radius) or (m and (r == r[0]).all()):  # one radius: the same products
        rr = np.full(len(core), float(r[0]) if m else 0.0)
    else:
        rr = r[owner]
    npts = _chord_counts(turn, int(quad_segs))
    pts = _arcs(core, turn, a0, rr, npts)
    counts = np.bincount(owner, npts, minlength=m).astype(np.int64)
    return pts, np.concatenate(([0], np.cumsum(counts))), hard


@njit(**NJIT)
def _chord_counts(turn, quad_segs):
    """Points of each corner's arc: ``round(turn / (pi / 2 / quad_segs))`` chords and one more.

    At least one chord; one point where the two ends nearly meet.
    """
    quantum = math.pi / 2.0 / quad_segs
    npts = np.ones(len(turn), dtype=np.int64)
    for k in range(len(turn)):
        if not turn[k] < CONVEX_ARC_SEPARATION:
            npts[k] = max(int(turn[k] / quantum + 0.5), 1) + 1
    return npts


@njit(**NJIT)
def _arcs(core, turn, a0, rr, npts):
    """The arcs of :func:`fillet_rings`, ``(sum(npts), 2)`` points.

    Corner ``k`` of the inset rings ``core`` gets ``npts[k]`` points at angles
    ``a0[k] + j * turn[k] / (npts[k] - 1)`` and radius ``rr[k]`` around it: the same
    operations in the same order as the vectorised numpy this replaces (``j * step + a0``,
    then ``core + rr * cos``), so the same bytes; ``math.cos`` and ``math.sin`` are the C
    library's, as numpy's are for float64 (``atan2`` is not: the callers keep numpy's).
    """
    total = 0
    for k in range(len(npts)):
        total += npts[k]
    pts = np.zeros((total, 2))
    at = 0
    for k in range(len(npts)):
        step = turn[k] / max(npts[k] - 1, 1)
        x, y, r = core[k, 0], core[k, 1], rr[k]
        for j in range(npts[k]):
            ang = j * step + a0[k]
            pts[at, 0] = x + r * math.cos(ang)
            pts[at, 1] = y + r * math.sin(ang)
            at += 1
    return pts


def _backwards(xy: np.ndarray) -> np.ndarray:
    """The rows of ``xy`` in reverse order (as complex numbers: a reversed 2D copy is slow)."""
    pairs = np.ascontiguousarray(xy, dtype=np.float64).view(np.complex128)[::-1, 0]
    return pairs.copy().view(np.float64).reshape(-1, 2)


def polygons(xy: np.ndarray, start: np.ndarray) -> np.ndarray:
    """Flat counter-clockwise rings as shapely Polygons with clockwise shells (as GEOS buffers).

    Returns
    -------
    (m,) object array
        Empty Polygons for rings without vertices.
    """
    m = len(start) - 1
    out = np.full(m, shapely.Polygon(), dtype=object)
    count = np.diff(start)
    live = count >= 3
    if not live.any():
        return out
    if not (live | (count == 0)).all():
        xy, start = take(xy, start, live | (count == 0))
        count = np.diff(start)
    # the whole flat array backwards: every ring clockwise, the rings in reverse order; an
    # emptied cell has no ring
    back = count[::-1]
    ring = np.concatenate(([0], np.cumsum(back[back > 0])))
    polys = shapely.from_ragged_array(
        shapely.GeometryType.POLYGON,
        _backwards(xy),
        (ring, np.concatenate(([0], np.cumsum(back > 0)))),
    )
    return polys[::-1]  # GEOS closes each ring
