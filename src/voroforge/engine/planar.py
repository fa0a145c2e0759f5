"""The planar build behind :func:`voroforge.voronoi`: validated sites and domain in, a Diagram out.

:func:`build` moves extreme magnitudes into the exact power-of-two working frame, maps exact
duplicates to their first occurrence, dispatches to one of the cell kernels (Delaunay dual,
Fortune's dual, half-planes), fills the gaps that sites every construction lost leave in
the cells with their exact cells where floats hold them (:mod:`.restore`), and assembles
the clipped cells and edges (:func:`voroforge.engine.assemble.assemble`).
:func:`voroforge.voronoi` and the periodic diagrams both call it, so neither needs the other.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import shapely

from ..config import FRAME2D_CAP_EXP, HALFPLANE_TILING_RTOL, VERTEX_STRAIGHT_ULPS
from ..kernels.cells import (
    cells_from_neighbors,
    cells_from_triangulation,
    dual_prepare,
    rings_astray,
    rings_miss,
    rings_nearly_convex,
)
from ..kernels.clip import open_ring_convex, rings_convex, rings_convex_area, tiny_folded
from ..kernels.delaunay import triangulate_sorted
from ..kernels.dual_some import dual_cells_of, seams_apart, splice_rings
from ..kernels.fortune import fortune_delaunay
from ..kernels.halfplane import halfplane_cells
from ..kernels.moments import farthest
from ..kernels.rings import boundary_cycle, close_rings
from .agree import agree, nudge_vertex, split_merged
from .assemble import assemble_checked
from .csr import csr_from_pairs
from .diagram import Diagram, Edges
from .domain import Domain
from .inputs import RES_BITS, duplicate_map, from_working, working_frame
from .readonly import readonly
from .threads import serial_below
from .uncross import uncrossed

ALGORITHMS = ("delaunay", "fortune", "halfplane")


def check_algorithm(algorithm: str) -> None:
    """Raise ``ValueError`` unless ``algorithm`` is one of :data:`ALGORITHMS`.

    Parameters
    ----------
    algorithm : str
        The construction method asked for.
    """
    if algorithm not in ALGORITHMS:
        raise ValueError(f"unknown algorithm {algorithm!r}; choose one of {', '.join(ALGORITHMS)}")


def _collinear_neighbors(xs, ys):
    order = np.lexsort((ys, xs))
    a = order[:-1]
    b = order[1:]
    return csr_from_pairs(len(xs), a, b)


def _dual(xs, ys, box, algorithm, kmap, memo=None):
    """Closed rings of the Delaunay dual: the default's triangulation or the sweep's.

    Sites all on one line have no triangles: their cells are the strips between bisectors.
    Which rings miss their site or are strips a few ulps wide at it (tested only where
    vertices merged or are close: :func:`.cells.rings_astray`'s codes) is noted in the dict
    ``memo`` under ``"astray"``, by the rings' ``lengths`` array (:func:`_lost`, :func:`build`).
    """
    ok = False
    if algorithm == "fortune":
        # the sweep's Delaunay dual, through the same cell builder as the default
        order, sx, sy, tri, he, ok = fortune_delaunay(xs, ys)
        # a triangulation that leaves part of the hull uncovered (sites a few ulps apart
        # along a line) would fold cells: the default's triangulation is used instead
        ok = ok and _fills_hull(sx, sy, tri, he)
    if not ok:
        order, sx, sy, tri, he, _, ok = triangulate_sorted(xs, ys)
    if ok:
        cells, astray = cells_from_triangulation(
            sx, sy, tri, he, box, order, kmap[order], astray=True
        )
        if memo is not None:
            memo.setdefault("astray", []).append((cells[1], astray))
        return cells
    indptr, indices = _collinear_neighbors(xs, ys)
    coords, offsets, owner = cells_from_neighbors(xs, ys, indptr, indices.astype(np.int64), box)
    return close_rings(coords, offsets, owner, np.arange(len(xs)), kmap)


def _memo(memo, key, fn, *args):
    """``fn(*args)``, computed once per ``key`` in the dict ``memo`` (None: no memo)."""
    if memo is None:
        return fn(*args)
    if key not in memo:
        memo[key] = fn(*args)
    return memo[key]


def _fills_hull(sx, sy, tri, he):
    """Whether triangles ``tri`` (halfedges ``he``, -1 on the boundary) fill the sites' hull.

    Every site is in a triangle, Euler's count holds for a disc (``t = 2 n - 2 - b`` with
    ``b`` boundary edges) and the boundary is one cycle, convex and winding once
    (:func:`.clip.open_ring_convex`, exact turns): a convex disc, so the hull. The sweep's
    certificate: on sites a few ulps apart along a line it once returned 37 triangles whose
    boundary wound twice where the hull needs 40.
    """
    n = len(sx)
    edges = int((he < 0).sum())
    if not np.bincount(tri, minlength=n).all() or len(tri) // 3 != 2 * n - 2 - edges:
        return False
    ring = boundary_cycle(tri, he, n)
    return len(ring) == edges > 0 and bool(open_ring_convex(sx[ring], sy[ring], len(ring)))


def _whole_halfplane(xs, ys, box, kmap, memo=None):
    """The half-plane rings when every cell was built and they tile the box, else None."""
    got = _memo(memo, "halfplane", halfplane_cells, xs, ys, box, kmap)
    if not got[3].any() and _certified(*got[:2], box, memo):
        return got[:3]
    return None


def _closed_cells(xs, ys, box, algorithm, kmap, memo=None):
    """Kernel dispatch: closed convex rings of distinct sites clipped to ``box``.

    Returns ``(coords, lengths, owner)`` with distinct site ``k``'s ring at
    ``coords[lengths[k]:lengths[k + 1]]`` and owners mapped through ``kmap``. ``memo`` (a
    dict) keeps each construction's output for :func:`_fewest_lost`.
    """
    if algorithm in ("delaunay", "fortune"):
        cells = _memo(memo, algorithm, _dual, xs, ys, box, algorithm, kmap, memo)
        if len(_lost(xs, ys, box, *cells[:2], memo)):
            # a distinct site whose cell merged away: its strip is narrower than the
            # centres' rounding bounds (sites a few ulps apart). The half-plane cells
            # decide each ring with exact predicates and keep it where floats can
            # represent it; they replace the dual's when they tile the box.
            got = _whole_halfplane(xs, ys, box, kmap, memo)
            if got is not None and len(_lost(xs, ys, box, *got[:2], memo)) < len(
                _lost(xs, ys, box, *cells[:2], memo)
            ):
                return got
        return cells
    # every cell on its own: the box cut by bisectors, finished with exact predicates
    closed, lengths, owner, hard = _memo(memo, "halfplane", halfplane_cells, xs, ys, box, kmap)
    if hard.any():
        # cells whose neighbours are not local (sites on one circle, a site with thousands
        # of neighbours): the Delaunay dual builds them in O(n log n)
        spliced = None
        if not hard.all():
            spliced = _with_dual(xs, ys, box, kmap, (closed, lengths, owner), hard, memo)
        if spliced is None:
            return _closed_cells(xs, ys, box, "delaunay", kmap, memo)
        closed, lengths, owner = spliced
    if _certified(closed, lengths, box, memo):
        return closed, lengths, owner
    # a cell the local finishing could not settle consistently (rounding-level vertices
    # that fold its ring, or cells that do not tile the box): the Delaunay dual decides
    # every vertex globally, and gives the answer every algorithm gives
    return _closed_cells(xs, ys, box, "delaunay", kmap, memo)


def _dual_state(xs, ys, box, kmap):
    """:func:`.cells.dual_prepare` of the default's triangulation (:func:`_dual`), or None."""
    order, sx, sy, tri, he, _, ok = triangulate_sorted(xs, ys)
    return dual_prepare(sx, sy, tri, he, box, order, kmap[order]) if ok else None


def _with_dual(xs, ys, box, kmap, rings, hard, memo):
    """The half-plane ``rings`` with the ``hard`` cells from the Delaunay dual, or None.

    A cell beside a dual cell must share their edge bit for bit; where the two
    constructions named a degenerate vertex differently (float circles), the cell comes
    from the dual too, until every seam agrees (None: every cell came from the dual). Only
    the cells taken are built (:func:`.dual_some.dual_cells_of`: a site off a line of a
    million has a million neighbours, and the dual of the whole line cost as much as the
    half-plane cells), or, where a ring can fold or most cells are taken, every cell.
    """
    n = len(hard)
    inv = np.full(int(kmap.max()) + 1, -1, np.int64)
    inv[kmap] = np.arange(n)
    state = _memo(memo, "dual_state", _dual_state, xs, ys, box, kmap)
    take = hard.copy()
    dual, whole = None, False
    while not take.all():
        if dual is None or not whole:
            some = None
            if state is not None and 8 * int(take.sum()) <= n:
                some = dual_cells_of(state, take)
            whole = some is None
            if whole:
                dual = _closed_cells(xs, ys, box, "delaunay", kmap, memo)
            else:
                dual, codes = some
        bad = seams_apart(rings, dual, take, inv)
        if not bad.any():
            spliced = splice_rings(rings, dual, take)
            if not whole and memo is not None:
                memo.setdefault("astray", []).append((dual[1], codes))
            _note_spliced(memo, dual[1], take, spliced[1])
            return spliced
        take |= bad
    return None


def _lost(xs, ys, box, closed, lengths, memo=None):
    """Distinct sites in ``box`` (its sides included) whose ring is empty or misses them.

    Each owns a cell of positive area there: a disc around a distinct site is its own, and
    a site on a side keeps half of it (a quarter at a corner). A ring misses its site
    (exact test, :func:`.cells.rings_astray`) where rounding merged the two vertices at the
    end of a strip an ulp or two wide (three sites 1-4 ulps apart on a line): the ring, a
    triangle, passes beside the site. The Delaunay dual's rings are tested only where
    vertices merged or are close (noted in ``memo["astray"]`` by :func:`_dual`, and for
    the half-plane rings that took some of the dual's by :func:`_note_spliced`); other
    rings :func:`_certified` passed (the half-plane cells: each the box cut by the site's
    bisectors, none seen astray) are not tested; any other rings (a rarer path) are tested
    whole.
    """
    empty = lengths[1:] == lengths[:-1]
    astray = _astray(xs, ys, box, closed, lengths, memo)
    if not empty.any() and astray is None:
        return np.zeros(0, dtype=np.intp)  # (most diagrams: no site-by-site test)
    inside = (box[0] <= xs) & (xs <= box[2]) & (box[1] <= ys) & (ys <= box[3])
    if astray is not None:
        empty = empty | astray
    return np.flatnonzero(inside & empty)


def _astray(xs, ys, box, closed, lengths, memo):
    """Which sites' non-empty rings miss them, or None where none does (see :func:`_lost`)."""
    if memo is not None:
        for x, code in memo.get("astray", ()):
            if x is lengths:
                return code == 1 if (code == 1).any() else None
        if any(x is lengths for x in memo.get("convex", ())):
            return None
    code = rings_astray(xs, ys, closed, lengths, box, np.ones(len(xs), dtype=np.bool_))
    if memo is not None:
        memo.setdefault("astray", []).append((lengths, code))
    return code == 1 if (code == 1).any() else None


def _note_spliced(memo, dual, take, lengths):
    """Note the dual's ring codes for the spliced rings ``lengths``.

    They took the dual's cells (rings ``dual``, :func:`_dual`) where ``take``; the
    half-plane's own rings are not tested (see :func:`_lost`).
    """
    if memo is None:
        return
    for x, code in memo.get("astray", ()):
        if x is dual:
            memo["astray"].append((lengths, np.where(take, code, 0).astype(np.uint8)))
            return


def _thin_dual(lengths, memo):
    """Whether the Delaunay dual's rings ``lengths`` hold a site within ulps of an edge.

    Only the dual's rings at merged or close vertices are tested (:func:`_dual`).
    """
    for x, code in memo.get("astray", ()):
        if x is lengths:
            return bool((code == 2).any())
    return False


_FOLDED_ULPS = 64  # a folded ring this many ulps across is not representable: left empty
_ASTRAY_AREA = 2.0**-45  # a ring beside its site this small (of the box's area) is emptied


def _empty_astray(closed, lengths, owner, lost, box):
    """Rings beside their site (every construction's) left empty where tiny; sites flagged.

    Returns the rings and the ``lost`` sites that stay flagged.

    A strip an ulp or two wide (sites a few ulps apart) whose ring passes beside its site
    is flagged and emptied, as a site whose ring merged away is (its area, under
    ``_ASTRAY_AREA`` of the box's, is below the tiling's rounding). A bigger ring that
    misses its site (the hull strip of a cluster a few ulps wide, reaching far out) is most
    of the site's cell: it is kept so the cells tile the domain, and the site is flagged
    too (``Diagram.unresolved``: no cell, or a cell beside its site).
    """
    size = lengths[1:][lost] - lengths[:-1][lost]
    ring = lost[size > 0]
    if not len(ring):
        return closed, lengths, owner, lost
    area = np.zeros(len(ring))
    for k, j in enumerate(ring):
        r = closed[lengths[j] : lengths[j + 1]] - closed[lengths[j]]
        area[k] = 0.5 * abs(math.fsum(r[:-1, 0] * r[1:, 1] - r[1:, 0] * r[:-1, 1]))
    tiny = area <= _ASTRAY_AREA * (box[2] - box[0]) * (box[3] - box[1])
    drop = np.zeros(len(lengths) - 1, dtype=np.bool_)
    drop[ring[tiny]] = True
    if drop.any():
        empty = (closed[:0], np.zeros_like(lengths), owner[:0])
        closed, lengths, owner = _splice(closed, lengths, owner, empty, drop)
    return closed, lengths, owner, lost


def _drop_folded(closed, lengths, owner, memo=None, kmap=None):
    """The rings with every tiny or thin one that folds left empty.

    Each builder certifies its rings; one that still folds and is only a few dozen ulps
    across lies where floats cannot represent the cell (sites a few ulps apart far from the
    origin: its vertices are a few ulps apart too), unless it is valid, convex to rounding
    and edge to edge with its neighbours (:func:`_kept_tiny`; ``kmap`` maps ring indices to
    the owners' numbering, None: the same). So does a long strip a few dozen ulps
    wide whose ring is not a valid polygon (the cell of a hull site of such a cluster,
    reaching far out: its vertices rounded onto one line). Either is reported in
    ``Diagram.unresolved`` (:func:`_lost`) instead of as a self-intersecting polygon.

    Rings that :func:`_certified` passed (listed in ``memo``) are all convex, and only a
    ring that is not convex can be flagged: they are returned as they are, untested.
    """
    if memo is not None and any(x is lengths for x in memo.get("convex", ())):
        return closed, lengths, owner
    code = tiny_folded(closed, lengths, _FOLDED_ULPS)
    if not code.any():
        return closed, lengths, owner
    bad = code == 1
    inv = np.arange(len(lengths) - 1)  # owner's numbering -> ring
    if kmap is not None:
        inv = np.full(int(kmap.max()) + 1, -1, np.int64)
        inv[kmap] = np.arange(len(kmap))
    for i in np.flatnonzero(code == 2):
        # a strip a few ulps wide that rounding left concave but simple stays; one whose
        # vertices rounded onto one line (or across each other) is not a polygon, unless
        # it crosses itself once and the crossing can cut it (:mod:`.uncross`)
        bad[i] = not _valid_ring(closed[lengths[i] : lengths[i + 1]])
        if bad[i]:
            got = uncrossed(closed, lengths, owner, i, inv)
            if got is not None:
                closed, lengths, owner = got
                bad[i] = False
    for i in np.flatnonzero(code == 1):
        bad[i] = not _kept_tiny(closed, lengths, owner, i, inv)
    empty = (closed[:0], np.zeros_like(lengths), owner[:0])  # every ring of no vertex
    return _splice(closed, lengths, owner, empty, bad)


def _kept_tiny(closed, lengths, owner, i, inv):
    """Whether ring ``i``, a few ulps across and not exactly convex, is kept as it is.

    It is where it is a valid polygon, convex to the rounding of its vertices (as
    ``describe()`` counts convexity: ``VERTEX_STRAIGHT_ULPS``) and each of its bisector
    edges is an edge of its owner's ring reversed, bit for bit: then it fills exactly the
    hole that emptying it would leave (float circles of radius 1e-7 far out, cells within
    rounding of the exact ones). A ring a neighbour does not match edge for edge (a
    neighbour's cut lost a vertex between nearly parallel bisectors) is left empty, so its
    gap is traced from the neighbours' edges (``restore``) and the cells meet edge to edge.
    ``inv`` maps an owner to its ring (-1: none).
    """
    a, b = lengths[i], lengths[i + 1]
    ring = closed[a:b]
    one = np.array([0, len(ring)], dtype=lengths.dtype)
    if not (_valid_ring(ring) and rings_nearly_convex(ring, one, VERTEX_STRAIGHT_ULPS)):
        return False
    for k in range(len(ring) - 1):
        o = int(owner[a + k])
        if o < 0:
            continue  # a box side
        j = int(inv[o]) if o < len(inv) else -1
        other = closed[lengths[j] : lengths[j + 1]] if j >= 0 else closed[:0]
        at = (other[:-1] == ring[k + 1]).all(axis=1) & (other[1:] == ring[k]).all(axis=1)
        if not at.any():
            return False
    return True


def _fewest_lost(xs, ys, box, kmap, memo):
    """Of the constructions' rings, those that leave the fewest distinct sites without a cell.

    Only for diagrams where an algorithm's rings lost a site: sites a few ulps apart far
    from the origin, whose cells are a few ulps wide. There the constructions can differ
    (the sweep and the default choose different diagonals of exactly cocircular sites, so
    their centres merge differently by rounding); every algorithm then compares the same
    three constructions (:func:`_closed_cells` of each algorithm, fallbacks included) and
    keeps the first in the order default, sweep, half-plane among those with the fewest
    invalid rings that give the most sites a cell, so that every algorithm gives one answer.
    """
    best = None
    for alg in ("delaunay", "fortune", "halfplane", "tiling"):
        # (each construction's kernels run once per build: ``memo``)
        if alg == "tiling":
            rings = _tiling_halfplane(xs, ys, box, kmap, memo)
            if rings is None:
                continue
        else:
            rings = _drop_folded(*_closed_cells(xs, ys, box, alg, kmap, memo), memo, kmap)
        key = (_invalid(*rings[:2]), len(_lost(xs, ys, box, *rings[:2], memo)))
        if best is None or key < best[0]:
            best = (key, rings)
    return best[1]


def _tiling_halfplane(xs, ys, box, kmap, memo):
    """The half-plane rings when they tile the box though rounding left one reflex, else None.

    A site whose cell is a strip an ulp or two wide (sites 1 ulp apart on a line) has exact
    vertices closer than floats can place on the neighbours' straight edges: the half-plane
    cells share them bit for bit but round a turn there the wrong way by less than an ulp.
    The certificate (:func:`_certified`) refuses that ring and the Delaunay dual, which
    merges the strip's vertices, loses the site; these rings keep it. Only compared with
    the others in :func:`_fewest_lost` (fewest invalid rings first).
    """
    closed, lengths, owner, hard = _memo(memo, "halfplane", halfplane_cells, xs, ys, box, kmap)
    if hard.any() or len(closed) == 0:
        return None
    # signed areas relative to each ring's first vertex, added with math.fsum (a rare path)
    size = np.diff(lengths)
    rel = closed - np.repeat(closed[lengths[:-1][size > 0]], size[size > 0], axis=0)
    last = np.zeros(len(closed), np.bool_)
    last[lengths[1:][size > 0] - 1] = True  # the closing vertex starts no edge
    k = np.flatnonzero(~last)
    area = 0.5 * math.fsum(rel[k, 0] * rel[k + 1, 1] - rel[k + 1, 0] * rel[k, 1])
    want = (box[2] - box[0]) * (box[3] - box[1])
    if not abs(area - want) <= HALFPLANE_TILING_RTOL * want:
        return None
    # a turn the wrong way by more than rounding (44 ulps, sites_ulps_apart seed 3) is a
    # cell the half-plane settling got wrong, not one floats cannot do better
    if not rings_nearly_convex(closed, lengths, VERTEX_STRAIGHT_ULPS):
        return None
    return closed, lengths, owner


def _invalid(closed, lengths):
    """How many rings are not valid polygons (convex ones are: only the others are tested)."""
    uncertain = np.flatnonzero(~rings_convex(closed, lengths) & (lengths[1:] > lengths[:-1]))
    return sum(not _valid_ring(closed[lengths[i] : lengths[i + 1]]) for i in uncertain)


def _valid_ring(ring):
    """Whether a closed ring (last vertex repeating the first) is a valid polygon."""
    return len(ring) >= 4 and bool(shapely.is_valid(shapely.polygons(ring)))


def _splice(closed, lengths, owner, dual, take):
    """Closed rings with cell ``k`` from ``dual`` where ``take[k]``, else from ``closed``."""
    return splice_rings((closed, lengths, owner), dual, take)


def _certified(closed, lengths, box, memo=None) -> bool:
    """Whether closed rings are convex (exact test) and tile the box (areas to 1e-9).

    Areas are summed per ring relative to its first vertex, so coordinates far from the
    origin keep their precision. Certified rings are noted in the dict ``memo`` (under
    ``"convex"``, by their ``lengths`` array), so :func:`_drop_folded` need not test them.
    """
    if len(closed) == 0:
        return False
    convex, area = rings_convex_area(closed, lengths)  # one pass for both
    if not convex:
        return False
    want = (box[2] - box[0]) * (box[3] - box[1])
    ok = abs(area - want) <= HALFPLANE_TILING_RTOL * want
    if ok and memo is not None:
        memo.setdefault("convex", []).append(lengths)
    return ok


def _warn_merged(given: np.ndarray, dup: np.ndarray, k: int) -> None:
    """Warn that the working frame's rounding made distinct sites one (``duplicate_of``)."""
    same = np.flatnonzero(dup >= 0)
    diff = same[(given[same] != given[dup[same]]).any(axis=1)]
    if len(diff):
        i = int(diff[0])
        warnings.warn(
            f"{len(diff)} distinct sites are used as one: the working frame of the sites' and "
            "the domain's largest magnitude rounds small coordinates to multiples of "
            f"{math.ldexp(1.0, -RES_BITS - k):.3g} (e.g. site {i} {given[i].tolist()} is site "
            f"{int(dup[i])}; see duplicate_of; a domain nearer the sites' size keeps them apart)",
            RuntimeWarning,
            stacklevel=4,
        )


def build(pts: np.ndarray, dom: Domain, algorithm: str, *, split: bool = True) -> Diagram:
    """Voronoi diagram of validated sites clipped to a validated domain.

    Parameters
    ----------
    pts : (n, 2) float64
        Sites, C-contiguous; the diagram keeps this array (read-only) unless the working
        frame had to round it. Not modified.
    dom : Domain
        The domain.
    algorithm : {"delaunay", "fortune", "halfplane"}
        Construction method (already checked).
    split : bool
        Whether a lost site's ring is split where floats hold two merged vertices
        (:func:`.restore.split_lost`); the periodic build of rounded copies asks not to (on
        a sloped line at 4e12 the split rings turned right by ~25 ulps).

    Returns
    -------
    Diagram
    """
    n = len(pts)
    given = pts
    # the domain's box stays below 2**FRAME2D_CAP_EXP: the half-plane cut squares it (at
    # 2**900, sites 1e-154 apart in a box 10 wide, it did not return)
    work, k = working_frame(pts, np.array(dom.bounds, dtype=np.float64), cap=FRAME2D_CAP_EXP)
    if work is not pts:
        pts = from_working(work, k)  # equal to the input unless it spans > 1e57 in magnitude
    wdom = dom.scaled(k)  # everything below runs in the working frame
    dup, unique = duplicate_map(work)
    if work is not given and (dup >= 0).sum() > (duplicate_map(given)[0] >= 0).sum():
        _warn_merged(given, dup, k)
    sub = work if len(unique) == n else work[unique]
    xs = np.ascontiguousarray(sub[:, 0])
    ys = np.ascontiguousarray(sub[:, 1])
    box = np.array(wdom.bounds, dtype=np.float64)
    with serial_below(n):
        memo = {}
        rings = _closed_cells(xs, ys, box, algorithm, unique, memo)
        closed, lengths, own = _drop_folded(*rings, memo, unique)
        lost = _lost(xs, ys, box, closed, lengths, memo)
        if len(lost):
            closed, lengths, own = _fewest_lost(xs, ys, box, unique, memo)
            lost = _lost(xs, ys, box, closed, lengths, memo)
        elif _thin_dual(lengths, memo):
            # a strip a few ulps wide whose two vertices at one end merged by rounding: the
            # dual's ring, a triangle, holds its site but not the points an ulp beside it
            # that are nearer to it than to any other site; the half-plane rings keep both
            # vertices, and replace the dual's where they tile the box, are all valid and
            # give every site its cell (the same rings from every algorithm)
            got = _tiling_halfplane(xs, ys, box, unique, memo)
            if got is not None and not _invalid(*got[:2]):
                if not len(_lost(xs, ys, box, *got[:2], memo)):
                    closed, lengths, own = got
        certified = any(x is lengths for x in memo.get("convex", ()))
        del memo
        if len(lost):
            closed, lengths, own, lost = _empty_astray(closed, lengths, own, lost, box)
            # a lost site's exact cell where floats hold it and the rings leave a gap for it
            # (imported here: its exact cells need scipy's KD-tree, which a first build of
            # ordinary input never loads)
            from .restore import restore_lost, split_lost

            (closed, lengths, own), lost = restore_lost(
                xs, ys, box, (closed, lengths, own), lost, unique
            )
            # a ring beside its site where the cells merged two vertices floats hold apart
            if split:
                (closed, lengths, own), lost = split_lost(
                    xs, ys, box, (closed, lengths, own), lost, unique
                )
        if certified:
            (closed, lengths, own), lost = _held_after_agree(
                xs, ys, box, (closed, lengths, own), lost, unique, work
            )
        reach = None if dom.is_rect else _reach(closed, lengths, sub, unique, n)
        bufs, edges, clip_lost = assemble_checked(wdom, closed, lengths, own, n, unique, sites=work)
    # sites every construction leaves without a cell holding them (empty, or a ring beside
    # the site): floats cannot represent it; and sites whose cell the polygon clip could
    # not keep around them (a cell an ulp wide at a reflex vertex of the domain)
    unresolved = unique[lost].astype(np.int64)
    if len(clip_lost):
        unresolved = np.union1d(unresolved, clip_lost)
    if k:
        bufs = (np.ldexp(bufs[0], -k), *bufs[1:])
        edges = Edges(np.ldexp(edges.coords, -k), edges.pairs)
        if reach is not None:
            reach = np.ldexp(reach, -k)
    return Diagram(pts, dup, dom, bufs, edges, algorithm, k, unresolved, reach)


def _held_after_agree(xs, ys, box, rings, lost, unique, work):
    """Certified rings (the half-plane cells) made to agree, with the sites they miss flagged.

    Each half-plane vertex is named, but a vertex rounded (or a group of vertices ulps
    apart merged) across its site's bisector can leave the site outside its ring by less
    than an ulp (issue 15's ulp clusters c202, c354); :func:`_lost` does not test these
    rings. The rings that miss their site (:func:`.cells.rings_miss`, an exact turn or two
    per ring) are first made to agree with their neighbours (:func:`.agree.agree`, which
    assembly would apply next and which can give a site back: c328), then a vertex merged
    from two that floats hold apart is split (:func:`.agree.split_merged`: c354), or a
    vertex rounded the other way (:func:`.agree.nudge_vertex`: c202), and the sites still
    outside are added to ``lost``. Returns ``(rings, lost)``.
    """
    miss = rings_miss(xs, ys, rings[0], rings[1], box)
    if not miss.any():
        return rings, lost
    rings = agree(*rings, unique, len(work), work)
    miss = rings_miss(xs, ys, rings[0], rings[1], box)
    if miss.any():
        rings = split_merged(*rings, unique, len(work), work, np.flatnonzero(miss))
        miss = rings_miss(xs, ys, rings[0], rings[1], box)
    if miss.any():
        rings = nudge_vertex(*rings, unique, len(work), work, np.flatnonzero(miss))
        miss = rings_miss(xs, ys, rings[0], rings[1], box)
    return rings, np.union1d(lost, np.flatnonzero(miss)).astype(lost.dtype)


def _reach(closed, lengths, sub, unique, n):
    """``diagram.convex_reach`` in the working frame: each unique site's ring radius."""
    reach = np.zeros(n)
    # the rings and sites as read-only views (the sites are a frozen diagram's on some
    # paths; scale.tasks.radii hands a diagram's frozen coordinates): one compiled farthest
    lengths = np.ascontiguousarray(lengths, dtype=np.int64)
    reach[unique] = farthest(readonly(closed), lengths, readonly(sub))
    reach.setflags(write=False)
    return reach
