"""Some cells of the Delaunay dual beside the half-plane cells (issue 15, long lines).

The half-plane builder leaves a few cells hard (a site off a line of a million, with a
million neighbours); the dual builds those cells, and the cells beside them must share
their edges bit for bit. :func:`dual_cells_of` builds only the cells asked for, exactly as
:func:`.cells.cells_from_triangulation` builds them; :func:`seams_apart` finds the cells
whose edge with one of them is not that edge reversed; :func:`splice_rings` joins the two.
Rings are the closed layout of :func:`.cells.cells_from_triangulation`.
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

from ..config import NJIT_PARALLEL
from .cells import astray_of, rebuild_cells
from .folds import folded_rings


def dual_cells_of(state, want):
    """The dual's rings (``astray=True``) of the output cells in ``want``, others empty.

    Parameters
    ----------
    state : tuple
        :func:`.cells.dual_prepare` of the triangulation.
    want : (u,) bool
        Output cells to build.

    Returns
    -------
    ((coords, lengths, owner), codes) or None
        As :func:`.cells.cells_from_triangulation` returns them, bit for bit for the cells in
        ``want`` (and those that can fold, ``risk``); the other rings are empty. None where a
        ring that can fold does: the fold rounds move centres, so only the whole
        construction gives its answer.
    """
    xs, ys, tri, he, box, order, kmap, cx, cy, _, cls, risk, _, terr, reach = state
    n = xs.shape[0]
    build = want[order] | risk  # kernel numbering
    # every ring empty, and the cells in ``build`` built into it (each cell depends only on
    # the centres and classes of its own triangles)
    empty = (np.zeros((0, 2)), np.zeros(n + 1, np.int64), np.zeros(0, np.int64))
    _, cells = rebuild_cells(
        xs, ys, tri, he, cx, cy, terr, reach, cls, box, order, kmap, empty, build
    )
    codes = np.zeros(n, np.uint8)
    if risk.any():
        # the whole construction's first fold round: no folded ring, no round
        if folded_rings(cells[0], cells[1], order, risk).any():
            return None
        codes = astray_of(xs, ys, cells, box, order, risk)
    return cells, codes


@njit(**NJIT_PARALLEL)
def seams_apart(rings, dual, take, inv):
    """Cells not in ``take`` whose edge with a ``take`` cell is not that cell's edge reversed.

    Parameters
    ----------
    rings, dual : tuple
        Closed rings ``(coords, lengths, owner)``: cell ``k``'s from ``dual`` where
        ``take[k]``, else from ``rings``; owners are output ids (``inv`` maps them to cells).
    take : (u,) bool
    inv : (m,) int64
        Cell of each output id.

    Returns
    -------
    (u,) bool
        The cells outside ``take`` with an edge to a ``take`` cell that the latter lacks
        reversed, or the other way round. Edges are compared bit for bit (coordinates as
        int64 bits: 0.0 and -0.0 differ).
    """
    coords, lengths, owner = rings
    dcoords, dlengths, downer = dual
    hb = coords.view(np.int64)
    db = dcoords.view(np.int64)
    n = take.shape[0]
    bad = np.zeros(n, np.bool_)
    matched = np.zeros(owner.shape[0], np.bool_)
    # each take cell's edge to a cell outside: that cell's ring must hold it reversed
    # (serial: two take cells may share a neighbour, whose ``matched`` both write)
    for c in range(n):
        if not take[c]:
            continue
        for k in range(dlengths[c], dlengths[c + 1] - 1):
            w = downer[k]
            if w < 0:
                continue
            j = inv[w]
            if j < 0 or take[j]:
                continue
            found = False
            for m in range(lengths[j], lengths[j + 1] - 1):
                if owner[m] < 0 or inv[owner[m]] != c:
                    continue
                if hb[m, 0] == db[k + 1, 0] and hb[m, 1] == db[k + 1, 1]:
                    if hb[m + 1, 0] == db[k, 0] and hb[m + 1, 1] == db[k, 1]:
                        matched[m] = True
                        found = True
            if not found:
                bad[j] = True
    # each edge of a cell outside to a take cell: matched above, or it has no twin
    for j in prange(n):
        if take[j]:
            continue
        for m in range(lengths[j], lengths[j + 1] - 1):
            w = owner[m]
            if w < 0:
                continue
            c = inv[w]
            if c >= 0 and take[c] and not matched[m]:
                bad[j] = True
    return bad


@njit(**NJIT_PARALLEL)
def _copy_rings(cells, lengths, coords, owner, out, ncoords, nowner):
    """Copy the rings of ``cells`` (at ``lengths``) to their places at ``out``."""
    for i in prange(cells.shape[0]):
        k = cells[i]
        a = lengths[k]
        d = out[k] - a
        for t in range(a, lengths[k + 1]):
            ncoords[t + d, 0] = coords[t, 0]
            ncoords[t + d, 1] = coords[t, 1]
            nowner[t + d] = owner[t]


def splice_rings(rings, dual, take):
    """Closed rings with cell ``k`` from ``dual`` where ``take[k]``, else from ``rings``."""
    coords, lengths, owner = rings
    dcoords, dlengths, downer = dual
    size = np.where(take, np.diff(dlengths), np.diff(lengths))
    out = np.zeros_like(lengths)
    np.cumsum(size, out=out[1:])
    ncoords = np.zeros((int(out[-1]), 2))
    nowner = np.zeros(int(out[-1]), dtype=np.int64)
    _copy_rings(np.flatnonzero(~take), lengths, coords, owner, out, ncoords, nowner)
    _copy_rings(np.flatnonzero(take), dlengths, dcoords, downer, out, ncoords, nowner)
    return ncoords, out, nowner
