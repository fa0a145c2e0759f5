"""A cutting plane's values on the part of a 3D cell near it: a climb, then a flood (voro++'s idea).

:func:`.cellcut3d._cut_batch` evaluated every vertex of the cell for each candidate plane
(``_values``), and the graph cut listed the removed vertices by another full pass: a
many-faced cell (a helix's, 95-380 faces) paid its hundreds of vertices for each of its
~800 candidates, where voro++'s ``cell::plane`` pays for what the plane removes. Here
(:func:`plane_local`) the plane's values are found from a start vertex by steepest ascent
over the cell's edges, then:

* where the top reached (with its plateau: the vertices within ``CLIMB3D_PLATEAU_BAND`` bands below
  it, connected to it, none of whose neighbours lies higher) lies more than
  ``CLIMB3D_NOISE_BANDS`` bands below the plane, no vertex lies within the band or above: a convex
  cell's local top is its top, and rounding (a degenerate vertex rounded into a cluster of
  vertices a few ulps apart, each value good to far less than a band, as the band itself
  assumes) can hide a rising edge only within the plateau; the candidate is passed over,
  as the full pass would pass it over;
* else every vertex within ``CLIMB3D_FLOOD_BAND`` bands below the plane or above it is reached by
  a flood from there (the vertices above any level of a convex cell are connected, and
  each has a rising path to the top), and only those values are written; the removed
  vertices are listed from them (:func:`list_removed`) for :func:`.graph3d.cut_listed`.

Anything else (a plateau of more than ``CLIMB3D_PLATEAU_MOST`` vertices, values that rise for
ever) is reported ``FULL``: the caller evaluates every vertex as before. Each value is the
same expression as the full pass's, so every decision, and every output bit, is the full
pass's.

The climb starts from the best of the caller's hint (a vertex of the last cut's cap) and
the top last found for a normal of the same direction slot (``TOP_SLOTS``: the normal's
dominant axis and its three signs); where that slot has no top yet in this cell it starts
from ``CLIMB3D_SAMPLES`` vertices spread over the cell as well (a helix's cell: 29.7
vertices visited a passed-over plane, 9 of them these samples). Any start gives the same
top (a convex cell's), so the start changes no decision and no output bit, only how far
the climb goes.

Scratch: ``work[:, 0]`` marks the vertices evaluated for the current plane and
``work[:, 3]`` those of the plateau (both zero outside a call: the caller clears rows it
has not cleared since ``work`` was last used for something else), ``work[:, 1]`` lists
the vertices evaluated within the flood's margin or above it (the climb's vertices farther
below are evaluated, not marked: a passed-over plane marks none), ``work[:, 2]`` the
plateau's; the slots' tops are kept in
``work[-TOP_SLOTS:, 2]`` (:func:`clear_tops` empties them for a new cell; anything else
written there is only a worse start).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import (
    CLIMB3D_FLOOD_BAND,
    CLIMB3D_NOISE_BANDS,
    CLIMB3D_PLATEAU_BAND,
    CLIMB3D_PLATEAU_MOST,
    CLIMB3D_SAMPLES,
    NJIT,
)

NJIT_INLINE = {**NJIT, "inline": "always"}
#: called out of line (a cell's big loop stays small to compile); allocates nothing, so no
#: reference counting (see kernels.cellcut3d)
NJIT_NO_NRT = {**NJIT, "_nrt": False}

MISS = 0  # no vertex within the band of the plane or above it: pass the plane over
LOCAL = 1  # the values near and above the plane are written, listed in work[:nvis, 1]
FULL = 2  # not decided here: evaluate every vertex
#: the removed vertices are sorted by insertion up to this many, else marked and read off
SORT_MOST = 48


#: the tops last found, one per direction slot of a plane's normal (its dominant axis and
#: three signs), kept in ``work[-TOP_SLOTS:, 2]``: rows the plateau's list does not reach
TOP_SLOTS = 24
#: each slot split by the normal's two other components over the dominant one, each in
#: ``FINE_BINS`` bins of [0, 1]: a nearer top to start from (below the slots, in
#: ``work[-TOP_SLOTS - 1 - FINE_SLOTS:-TOP_SLOTS - 1, 2]``; the row between them says
#: whether they hold this cell's tops: -1 not yet, cleared at the cell's first climb)
FINE_BINS = 4
FINE_SLOTS = TOP_SLOTS * FINE_BINS * FINE_BINS
#: the rows at the end of ``work`` the slots take, with the fine ones
_FINE_ROWS = TOP_SLOTS + 1 + FINE_SLOTS


@njit(**NJIT_INLINE)
def _bin(b, a):
    """``|b| / |a|`` (at most 1) in one of ``FINE_BINS`` (4) equal bins, without a division."""
    return (4.0 * b >= a) + (2.0 * b >= a) + (4.0 * b >= 3.0 * a)


@njit(**NJIT_INLINE)
def _slot_row(work, nx, ny, nz):
    """The rows of ``work[:, 2]`` that keep the last tops for normals like ``n`` (-1: none).

    Returns ``(row, fine)``: the slot's row and its fine slot's.
    """
    nw = work.shape[0]
    if nw < CLIMB3D_PLATEAU_MOST + TOP_SLOTS:
        return -1, -1
    ax = abs(nx)
    ay = abs(ny)
    az = abs(nz)
    d = 0 if ax >= ay and ax >= az else (1 if ay >= az else 2)
    slot = 8 * d + 4 * (nx < 0.0) + 2 * (ny < 0.0) + (nz < 0.0)
    if nw < CLIMB3D_PLATEAU_MOST + _FINE_ROWS:
        return nw - 1 - slot, -1
    if d == 0:
        f = 4 * _bin(ay, ax) + _bin(az, ax)
    elif d == 1:
        f = 4 * _bin(az, ay) + _bin(ax, ay)
    else:
        f = 4 * _bin(ax, az) + _bin(ay, az)
    if work[nw - 1 - TOP_SLOTS, 2] < 0:  # the cell's first climb: its fine slots are stale
        for r in range(nw - _FINE_ROWS, nw - 1 - TOP_SLOTS):
            work[r, 2] = -1
        work[nw - 1 - TOP_SLOTS, 2] = 0
    return nw - 1 - slot, nw - 2 - TOP_SLOTS - (FINE_BINS * FINE_BINS * slot + f)


@njit(**NJIT_INLINE)
def clear_tops(work):
    """Forget the slots' tops (a new cell: its vertices are others); the fine ones lazily."""
    nw = work.shape[0]
    if nw >= CLIMB3D_PLATEAU_MOST + TOP_SLOTS:
        for r in range(nw - TOP_SLOTS, nw):
            work[r, 2] = -1
    if nw >= CLIMB3D_PLATEAU_MOST + _FINE_ROWS:
        work[nw - 1 - TOP_SLOTS, 2] = -1


@njit(**NJIT_INLINE)
def _value(V, v, nx, ny, nz, h):
    """The plane's value at vertex ``v``: the full pass's expression, bit for bit."""
    return nx * V[v, 0] + ny * V[v, 1] + nz * V[v, 2] - h


@njit(**NJIT_INLINE)
def _visit(V, u, nx, ny, nz, h, S, work, nvis):
    """Evaluate vertex ``u`` once for this plane (marked, listed). Returns the list's length."""
    if work[u, 0] == 0:
        work[u, 0] = 1
        S[u] = _value(V, u, nx, ny, nz, h)
        work[nvis, 1] = u
        nvis += 1
    return nvis


@njit(**NJIT_INLINE)
def _keep(u, s, S, work, nvis):
    """List vertex ``u`` of value ``s`` once for this plane (marked, value written)."""
    if work[u, 0] == 0:
        work[u, 0] = 1
        S[u] = s
        work[nvis, 1] = u
        nvis += 1
    return nvis


@njit(**NJIT_NO_NRT)
def plane_local(V, nv, DEG, ED, S, work, nx, ny, nz, h, tol, hint):
    """The plane ``n . x = h``'s values near and above it on the graph cell (see the module).

    Returns ``(mode, smax, low, nvis)``: ``MISS``, ``LOCAL`` (``smax``/``low``: the largest
    value and the least ``|value|`` among the ``nvis`` vertices listed in ``work[:nvis, 1]``
    with their values in ``S``: every vertex within ``CLIMB3D_FLOOD_BAND`` bands below the
    plane or above it, and their neighbours), or ``FULL``. The climb's vertices farther
    below are evaluated but not marked nor listed (a passed-over plane lists none): the
    marks cost more than the values, and no caller reads those (their ``|value|`` is far
    beyond the band, so ``low <= tol`` and ``smax`` are the same). Marks are cleared again
    before it returns.
    """
    nvis = 0
    margin = CLIMB3D_FLOOD_BAND * tol
    best = hint if 0 <= hint < nv else 0
    sb = _value(V, best, nx, ny, nz, h)
    if sb > -margin:
        nvis = _keep(best, sb, S, work, nvis)
    # the top last found for a normal of this one's slot, else samples spread over the cell
    row, fine = _slot_row(work, nx, ny, nz)
    t = work[fine, 2] if fine >= 0 else -1
    if not 0 <= t < nv:
        t = work[row, 2] if row >= 0 else -1
    if 0 <= t < nv:
        s = _value(V, t, nx, ny, nz, h)
        if s > -margin:
            nvis = _keep(t, s, S, work, nvis)
        if s > sb:
            best = t
            sb = s
    step = nv // CLIMB3D_SAMPLES
    if step > 0 and not 0 <= t < nv:
        for k in range(CLIMB3D_SAMPLES):
            v = k * step
            s = _value(V, v, nx, ny, nz, h)
            if s > -margin:
                nvis = _keep(v, s, S, work, nvis)
            if s > sb:
                best = v
                sb = s
    tau = CLIMB3D_PLATEAU_BAND * tol
    mode = LOCAL
    steps = 0
    while mode == LOCAL:
        # steepest ascent over the edges to a vertex no neighbour of which lies higher
        flat = True
        while True:
            nb = -1
            # (the last pass, nb < 0, keeps sb: flat then tells whether a neighbour lies
            # within tau below the top, i.e. whether the plateau holds more than the top)
            flat = False
            for k in range(DEG[best]):
                u = ED[best, k]
                s = _value(V, u, nx, ny, nz, h)
                if s > -margin:
                    nvis = _keep(u, s, S, work, nvis)
                flat |= s >= sb - tau
                if s > sb:
                    sb = s
                    nb = u
            if nb < 0:
                break
            best = nb
            steps += 1
        if steps > nv:  # (values that rise for ever: not a convex cell's)
            mode = FULL
            break
        if not flat:
            # no neighbour of the top lies within tau below it nor above it: its plateau
            # is the top alone, which the loop below would find from the same values
            break
        # the top's plateau (vertices within tau below it, connected to it: rounding's
        # clusters) must have no neighbour above the top, else the climb goes on from there
        top = sb
        work[0, 2] = best
        work[best, 3] = 1
        npl = 1
        q = 0
        higher = -1
        sh = top
        while q < npl and higher < 0:
            v = work[q, 2]
            q += 1
            for k in range(DEG[v]):
                u = ED[v, k]
                s = _value(V, u, nx, ny, nz, h)
                if s > -margin:
                    nvis = _keep(u, s, S, work, nvis)
                if s > top:
                    higher = u
                    sh = s
                    break
                if s >= top - tau and work[u, 3] == 0:
                    if npl == CLIMB3D_PLATEAU_MOST:
                        mode = FULL
                        higher = u
                        break
                    work[u, 3] = 1
                    work[npl, 2] = u
                    npl += 1
        for q in range(npl):
            work[work[q, 2], 3] = 0
        if higher < 0:
            break
        best = higher
        sb = sh
        steps += 1
    smax = -np.inf
    low = np.inf
    if mode == LOCAL and sb < -CLIMB3D_NOISE_BANDS * tol:
        mode = MISS  # every vertex lies within rounding of the top or below it
    elif mode == LOCAL:
        # the flood: every vertex listed that lies within the margin below the plane, or
        # above it (the top is), has each of its neighbours listed
        q = 0
        while q < nvis:
            v = work[q, 1]
            q += 1
            if S[v] > -margin:
                for k in range(DEG[v]):
                    nvis = _visit(V, ED[v, k], nx, ny, nz, h, S, work, nvis)
        for q in range(nvis):
            s = S[work[q, 1]]
            a = abs(s)
            if a < low:
                low = a
            if s > smax:
                smax = s
    for q in range(nvis):
        work[work[q, 1], 0] = 0
    if row >= 0 and mode != FULL:
        work[row, 2] = best  # (a LOCAL's top is cut off: its row is then a cap's vertex)
        if fine >= 0:
            work[fine, 2] = best
    return mode, smax, low, nvis


@njit(**NJIT_INLINE)
def list_removed(nv, DEG, S, work, nvis, CP):
    """The vertices above the plane among the ``nvis`` listed, ascending, as ``cut_open`` lists.

    In ``CP``'s column 2 from its last row up (:func:`.graph3d.cut_open`'s layout).

    Returns ``(nup, down)``: their count, and whether a vertex lies below (one not
    evaluated does: it lies below the margin); ``nup`` is -1 where the list and the cut's
    trace (at most one row more than the removed vertices' edges) might not fit in ``CP``.
    """
    ncap = CP.shape[0]
    nup = 0
    down = nvis < nv
    room = 0
    for q in range(nvis):
        v = work[q, 1]
        s = S[v]
        down |= s < 0.0
        if s > 0.0:
            room += DEG[v]
            if nup < SORT_MOST:  # insertion into the ascending list
                r = nup
                while r > 0 and CP[ncap - r, 2] > v:
                    CP[ncap - 1 - r, 2] = CP[ncap - r, 2]
                    r -= 1
                CP[ncap - 1 - r, 2] = v
            nup += 1
    if nup + room + 1 >= ncap:
        return -1, down
    if nup > SORT_MOST:  # many: marked, then read off in order
        for q in range(nvis):
            v = work[q, 1]
            if S[v] > 0.0:
                work[v, 0] = 1
        r = 0
        for v in range(nv):
            if work[v, 0]:
                work[v, 0] = 0
                CP[ncap - 1 - r, 2] = v
                r += 1
    return nup, down
