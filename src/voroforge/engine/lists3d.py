"""Cells whose grid search ran past its budget, rebuilt from Delaunay candidate lists.

The grid search of a cell (:mod:`kernels.cellcut3d`) stops once no unscanned site can
reach the cell: twice its radius. Points on a sphere defeat it: every cell reaches from
the centre to the walls, so every site is within reach of every cell and the build was
quadratic (4,000 points without the centre: 12.5 s). So the unweighted build gives each
search a budget of sites (:data:`SITE_BUDGET`); a cell past it stops (``SLOW``) and is
built again from its list (:func:`.kernels.candidates3d.candidate_lists`: the sites of its
Delaunay polytopes, from one ``vf.delaunay3d`` of all sites, made when the first cell
needs it). The list holds every site whose plane bounds the cell or passes through one of
its vertices, so the cell and its vertex names are the ones the full search gives; only
the order of its vertices and faces (the cuts' history) and the rounding of its volume
and centroid may differ. A polytope of more than :data:`POLYTOPE_MOST` sites (integer
points of one sphere: one polytope of all n) is not listed whole: its sites list the sites
of its 2-faces at them, and its centre vertex is named once from all its sites (the
``big`` of :func:`.kernels.candidates3d.candidate_lists`). A site with no list (in two
such polytopes; a flat input) is searched again without a budget, as before. A cell whose
vertex has more owners than its owner table holds (the centre of a big polytope) stops
with ``SLOW`` too, so such inputs take the lists below the budget.
"""

from __future__ import annotations

import numpy as np

from ..config import LISTS3D_AFTER as LISTS_AFTER
from ..config import LISTS3D_POLYTOPE_MOST as POLYTOPE_MOST
from ..config import LISTS3D_SITE_BUDGET as SITE_BUDGET
from ..config import LISTS3D_STAR_LEAST as STAR_LEAST
from ..kernels.candidates3d import candidate_lists
from ..kernels.cellcut3d import SLOW

#: test only: every cell is built from its list (where it has one)
FORCE = False


class Lists:
    """The candidate lists of sites ``P`` (weights ``W``, all zero), made on first use.

    ``g`` is the search grid (9 values, :func:`.build3d.search3d`); :meth:`budget` is it
    with the budget, the lists' own grid ends in -1 (the kernel's list mode). A search is
    ``(start, SP, SW, sidx, g, big)``: ``big`` None for the grid's, for the lists' the big
    polytopes' sites and every site's Delaunay star (``big`` and ``star`` of
    :func:`.kernels.cells3d.build_cells`).
    """

    def __init__(self, P: np.ndarray, W: np.ndarray, g: np.ndarray, owners_only=False):
        self.P, self.W, self.g = P, W, g
        # owners_only (mesh containers): no budget of sites, lists only for the cells with a
        # vertex of more owners than their table holds
        self.most = float(2**62) if owners_only else SITE_BUDGET
        self.made = None
        self.slow = self.seen = 0  # cells past the budget, and cells built

    def budget(self) -> np.ndarray:
        """The search grid with the budget (``g[9]``, read by ``cellcut3d.one_cell``)."""
        if self.made is False:  # the sites span no volume: no lists, no budget
            return self.g
        return np.append(self.g, self.most)

    def worth(self, slow: int, k: int) -> bool:
        """Count ``slow`` cells past the budget in ``k`` more; whether to use (make) lists."""
        self.slow += slow
        self.seen += k
        most, share = LISTS_AFTER
        if self.most > SITE_BUDGET and slow:  # owners only: such a cell fails without its list
            return True
        force = FORCE and self.most == SITE_BUDGET
        return self.made is not None or force or self.slow >= max(most, share * self.seen)

    def get(self):
        """``(start, SP, SW, sidx, g, big, listed)`` or None when the sites span no volume."""
        if self.made is None:
            from .delaunay3d import delaunay3d  # (imports engine.voronoi3d, which imports us)

            tri = delaunay3d(self.P)
            self.made = False
            if len(tri.simplices):
                T = np.ascontiguousarray(tri.simplices, np.int64)
                N = np.ascontiguousarray(tri.neighbors, np.int64)
                start, sites, listed, big, (tpid, pstart, psite) = candidate_lists(
                    self.P, T, N, POLYTOPE_MOST
                )
                SP = np.ascontiguousarray(self.P[sites])
                SW = np.ascontiguousarray(self.W[sites])
                # the tetrahedra at each site (CSR)
                tlist = np.argsort(T.ravel(), kind="stable") // 4
                tstart = np.zeros(len(self.P) + 1, np.int64)
                np.cumsum(np.bincount(T.ravel(), minlength=len(self.P)), out=tstart[1:])
                star = (tstart, tlist, T, N, tpid, pstart, psite, np.array([STAR_LEAST]))
                g = np.append(self.g, -1.0)
                self.made = (start, SP, SW, sites, g, (big, star), listed)
        return self.made or None


def chunks(k: int, most: int, probe: bool, room=None):
    """Bounds ``(c0, c1)`` of the chunks of ``k`` cells, ``most`` a chunk.

    ``probe``: 64, 128, ... cells first: a cell past the budget has cost thousands of sites
    (a sphere's, each decided near the centre), so the lists are made after a few of them.
    ``room``: a one-element list, the most cells of the chunks from now on (read before
    each; the caller lowers it where its grown slots need: :func:`.slots3d.chunk_room`).
    """
    c0, size = 0, 64 if probe else most
    while c0 < k:
        if room is not None:
            size = min(size, room[0])
        yield c0, min(c0 + size, k)
        c0, size = c0 + size, min(2 * size, most)


def chunk_search(lists, search):
    """The search of the next chunk: the lists once they are made, else the grid's.

    ``search = (start, SP, SW, sidx, g, None)``: the grid's, given the budget here.
    """
    if lists.made and lists.most == SITE_BUDGET:  # (owners only: just the cells that need them)
        return lists.made[:6]
    return (*search[:4], lists.budget(), None)


def redo_slow(chunk, res, lists, run, search):
    """Build again the cells of ``chunk`` that ran past the budget; returns which from lists.

    ``res`` is :func:`.build3d._run`'s result for the chunk (changed in place), ``run(cells,
    start, SP, SW, sidx, g, big)`` runs the kernel on a few cells, ``search`` is ``(start, SP,
    SW, sidx, g, None)`` of the grid (no budget). Returns ``(k,) bool``, True where the cell was
    built from its list, or None when no cell ran past the budget.
    """
    if lists.made and lists.most == SITE_BUDGET:  # built from lists: those without, searched
        listed = lists.made[6][chunk]
        at = np.flatnonzero(~listed)
        if len(at):
            _splice(res, at, run(chunk[at], *search))
        return listed
    status = res[0]
    force = FORCE and lists.most == SITE_BUDGET  # (owners only: never forced)
    slow = np.flatnonzero(status == SLOW) if not force else np.arange(len(chunk))
    if len(slow) == 0:
        lists.worth(0, len(chunk))
        return None
    made = lists.get() if lists.worth(len(slow), len(chunk)) else None
    listed = np.zeros(len(chunk), np.bool_)
    if made is not None:
        listed[slow] = made[6][chunk[slow]]
    for use in (True, False):
        at = slow[listed[slow] == use]
        if len(at):
            _splice(res, at, run(chunk[at], *(made[:6] if use else search)))
    return listed


def _splice(res, at, new):
    """Put cells ``new`` (a :func:`.build3d._run` result) at positions ``at`` of ``res``."""
    for q in range(5):
        res[q][at] = new[q]
    cv, cf, cr = (int(x) for x in res[6][:3])  # slot rows a cell: osite, ovabs, ofaces, oring
    for a, b, per in zip(res[5], new[5], (cv, cv, cf, cr), strict=True):
        a.reshape((-1, per) + a.shape[1:])[at] = b.reshape((-1, per) + b.shape[1:])
