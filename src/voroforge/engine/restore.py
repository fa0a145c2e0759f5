"""Rings for lost sites whose exact cells float64 can hold: the gaps they leave, filled.

Sites a few ulps apart far from the origin have cells an ulp or two wide (a wedge from the
cluster out to a box side). The kernels can merge such a cell's vertices and leave it
empty (:func:`voroforge.engine.planar.build` lists the site in ``Diagram.unresolved``);
where the neighbours' rings kept their own edges along it, the cells leave a gap that no
ring covers (``describe()``'s Euler count can fail, V - E + F = 2 where 1 on the
wedges of issue 15's clusters at 1e6). :func:`restore_lost` runs only when a site is lost,
and does work only when the rings leave a gap: directed edges whose reverse no ring
holds, or stretches of the box's sides no ring covers. Then each lost site whose ring is
empty gets its exact cell (integer arithmetic on the float sites, :mod:`.power_exact`),
its vertices rounded to float64 and each moved to the gap's vertex within ``RESTORE_SNAP_ULPS``
ulps of it (rounding puts a vertex the neighbours share, a class of merged centres, that
far from the exact point). The ring is kept when it is a valid polygon and every edge of it
runs along the gap: the reverse of an edge no ring shares, a stretch of a side no ring
covers, or the reverse of another kept ring's edge; no gap edge or stretch is taken twice.
The cells then meet edge to edge with the gap filled. A kept ring that holds its site (the
exact test of :func:`.cells.rings_astray`) takes the site out of the lost list; one that
passes beside it (a wedge whose rounded apex is an ulp off) is kept, closing the gap, and
the site stays listed. Everything depends on the rings and the sites alone, and every
algorithm reaches this step with the same rings (:func:`.planar._fewest_lost`), so they
all give the same answer. Where no exact cell fits (cells ~35 ulps wide at 4e12: a ring left
empty as folded, its neighbours' vertices up to 6 ulps from the exact ones), the gap's own
boundary closes it as the ring of a lost site its edges name (:func:`_fill_cycles`).
A lost site's ring that passes beside it (the gap's ring, or the dual's wedge) gets its
site back where the vertex the cells merged past it is two in floats (:func:`split_lost`).
"""

from __future__ import annotations

import math
from collections import Counter

import numpy as np
import shapely

from ..config import RESTORE_FIRST, RESTORE_SNAP_ULPS
from ..kernels.cells import rings_astray
from ..kernels.clip import rings_convex
from ..kernels.dual_some import splice_rings
from .agree import split_merged
from .power_exact import Exact, line, vertex

# the box's sides in counter-clockwise order: (axis varying, fixed coordinate's box index,
# direction along which a ring runs on it)
_SIDES = ((0, 1, 1.0), (1, 2, 1.0), (0, 3, -1.0), (1, 0, -1.0))
_BOX_OWNER = -1  # the owner of an edge along the box (the kernels' label)


def restore_lost(xs, ys, box, rings, lost, kmap):
    """The rings with gap-filling exact cells of lost sites, and the sites still lost.

    Parameters
    ----------
    xs, ys : (u,) float64
        Distinct sites (working frame).
    box : (4,) float64
        ``(xmin, ymin, xmax, ymax)``.
    rings : tuple
        ``(closed, lengths, owner)``: closed ring of distinct site ``k`` at
        ``closed[lengths[k]:lengths[k + 1]]``, owners mapped through ``kmap``.
    lost : (m,) intp
        Distinct sites without a cell that holds them.
    kmap : (u,) int64
        Input index of each distinct site.

    Returns
    -------
    rings : tuple
        ``(closed, lengths, owner)``, the input arrays where nothing was restored.
    lost : (m',) intp
        The sites still lost.
    """
    closed, lengths, owner = rings
    empty = lost[lengths[1:][lost] == lengths[:-1][lost]]
    if not len(empty):
        return rings, lost
    gaps = _Gaps(closed, lengths, box)
    if not gaps.any():
        return rings, lost
    # the sites the gap's edges name across them first (the neighbours were built with the
    # site there); the others only when those leave part of the gap open
    named = np.isin(kmap[empty], owner[list(gaps.free.values())])
    cand, kept = {}, {}
    for which in (empty[named], empty[~named]):
        if not len(which) or (kept and _filled(kept, gaps)):
            continue
        for i, ring in _exact_rings(xs, ys, box, which).items():
            snapped = gaps.snap(ring)
            if snapped is not None and _valid(snapped):
                cand[i] = snapped
        kept = _settle(cand, gaps)
    # a ring beside its site (rounding moved the wedge's apex an ulp past it) is kept too:
    # the gap closes, and the site stays flagged, as a hull strip's ring beside its site is
    if kept:
        held = _holding(xs, ys, box, kept)
        rings = _spliced(rings, kept, gaps, kmap)
        lost = lost[~np.isin(lost, list(held & set(kept)))]
    rest = empty[~np.isin(empty, list(kept))]
    if len(rest):
        rings, lost = _fill_cycles(xs, ys, box, rings, lost, rest, kmap)
    return rings, lost


def split_lost(xs, ys, box, rings, lost, kmap):
    """The rings with lost sites' rings that pass beside them split where floats hold two.

    Two sites 7 ulps apart on a float circle (issue 15: radius 1e-7 at 4e6, 1025 sites)
    have an edge whose ends lie 2.9 ulps apart; the rounding-bound rule merges them, the
    merged point puts the one site outside its ring, and that ring, a thin wedge, passes
    beside its site (or, left empty, its gap was closed by :func:`restore_lost`, beside
    it too). Where the merged point is one vertex of four sites with the fourth inside the
    circle, :func:`.agree.split_merged` splits it as the exact diagram has it (the two
    vertices named by their triples, every ring at the point changed alike); rings beside
    the changed ones that disagreed before (two cells an ulp apart at a box side) may
    still. A ring that then holds its site and is exactly convex takes it out of ``lost``;
    one convex to rounding only keeps its site flagged, now inside it. Returns
    ``(rings, lost)``.
    """
    closed, lengths, owner = rings
    has = lost[lengths[1:][lost] > lengths[:-1][lost]]
    if not len(has):
        return rings, lost
    which = np.zeros(len(xs), dtype=np.bool_)
    which[has] = True
    code = rings_astray(xs, ys, closed, lengths, box, which)
    miss = np.flatnonzero(code == 1)
    if not len(miss):
        return rings, lost
    sites = np.zeros((int(kmap.max()) + 1, 2))
    sites[kmap] = np.column_stack((xs, ys))
    got = split_merged(closed, lengths, owner, kmap, len(sites), sites, miss, tolerate=True)
    if got[0] is closed:
        return rings, lost
    closed, lengths, owner = got
    which[:] = False
    which[miss] = True
    now = rings_astray(xs, ys, closed, lengths, box, which)
    back = miss[now[miss] != 1]
    back = back[rings_convex(closed, lengths)[back]]
    return got, lost[~np.isin(lost, back)]


def _spliced(rings, kept, gaps, kmap):
    """The rings with ``kept`` (:func:`_settle`'s ``{site: (ring, labels)}``) spliced in.

    Each gap edge a kept ring runs along is a neighbour's edge reversed: the neighbour's
    edge now faces the kept ring's site.
    """
    closed, lengths, owner = rings
    own = owner.copy()
    new_lengths = np.zeros_like(lengths)
    size = np.zeros(len(lengths) - 1, dtype=np.int64)
    for i in sorted(kept):
        ring, labels = kept[i]
        for e in (e for kind, e in labels if kind == "gap"):
            own[e] = kmap[i]  # the neighbour's edge along the gap now faces site i
        size[i] = len(ring) + 1
    np.cumsum(size, out=new_lengths[1:])
    coords = np.zeros((int(new_lengths[-1]), 2))
    labels_out = np.full(len(coords), -2, dtype=np.int64)
    for i in sorted(kept):
        ring, labels = kept[i]
        a = new_lengths[i]
        coords[a : a + len(ring)] = ring
        coords[a + len(ring)] = ring[0]
        for k, (kind, e) in enumerate(labels):
            if kind == "gap":  # across: the ring that holds the edge's reverse
                labels_out[a + k] = kmap[gaps.ring_of[e]]
            else:
                labels_out[a + k] = kmap[e] if kind == "pair" else _BOX_OWNER
    take = np.zeros(len(lengths) - 1, dtype=np.bool_)
    take[sorted(kept)] = True
    return splice_rings((closed, lengths, own), (coords, new_lengths, labels_out), take)


def _fill_cycles(xs, ys, box, rings, lost, rest, kmap):
    """The rings with each closed gap that names an empty lost site given to it.

    Where no exact cell of a lost site fits the gap its neighbours leave (their vertices,
    rounded circumcentres, lie more than ``RESTORE_SNAP_ULPS`` from the exact cell's: cells
    ~35 ulps wide at 4e12 whose rounded ring turned the wrong way by an ulp and was left
    empty as folded), the gap itself closes the cells: its boundary, traced along the
    edges no ring shares (reversed) and the bare stretches of the box's sides, is a ring
    whose every edge is a neighbour's reversed. A cycle that is a valid counter-clockwise
    polygon goes to an empty lost site its edges name (the neighbours were built with that
    site across), one that the cycle holds (exact test) first, then the one named most
    (ties: the lower index). The site leaves ``lost`` only where the ring holds it and is
    convex (exact turns); otherwise its ring is kept beside it, flagged, as a wedge's.
    Slivers between two cells (T-junctions) name no lost site and stay as they are; one
    that joins a lost site's gap is cut off its cycle (:func:`_despiked`).
    """
    closed, lengths, owner = rings
    gaps = _Gaps(closed, lengths, box)
    if not gaps.any():
        return rings, lost
    of_input = {int(kmap[i]): int(i) for i in rest}
    kept = {}
    for ring, labels in gaps.cycles():
        if not _valid(ring):
            ring, labels = _despiked(ring, labels, gaps)
        named = Counter(
            of_input[int(owner[e])]
            for kind, e in labels
            if kind == "gap" and int(owner[e]) in of_input
        )
        if not named or not _valid(ring):
            continue
        order = sorted((i for i in named if i not in kept), key=lambda i: (-named[i], i))
        if not order:
            continue
        held = _holding(xs, ys, box, {i: (ring, labels) for i in order})
        pick = next((i for i in order if i in held), order[0])
        kept[pick] = (ring, labels)
    if not kept:
        return rings, lost
    held = _holding(xs, ys, box, kept)
    convex = {i for i in kept if _convex(kept[i][0])}
    rings = _spliced(rings, kept, gaps, kmap)
    return rings, lost[~np.isin(lost, list(held & convex))]


def _despiked(ring, labels, gaps):
    """The gap cycle ``ring`` with each spike cut off (``labels`` as :meth:`_Gaps.cycles`'s).

    Two neighbours whose shared edge ends at points an ulp apart (each cell rounded its own
    end onto a box side: issue 15's float circles of radius 1e-7 at 4e6, 1025 sites) leave
    a sliver between their edges that no ring shares: an overlap of the two cells, not a
    gap. Where it meets a lost site's gap, the walk runs out along one edge and back along
    the other, to within ``RESTORE_SNAP_ULPS`` ulps of where it left, and the cycle is no
    polygon (the strip cell stayed empty and its gap open). The cycle goes straight from
    the spike's one end to the other instead: along the box side where both lie on it
    (labelled as the side), else along the first edge's cell (its site across).
    """
    ring, labels = list(ring), list(labels)
    k = 0
    while len(ring) > 3 and k < len(ring):
        p, r = ring[k - 1], ring[(k + 1) % len(ring)]
        u = RESTORE_SNAP_ULPS * math.ulp(max(abs(p[0]), abs(p[1]), abs(r[0]), abs(r[1])))
        spike = labels[k - 1][0] == labels[k][0] == "gap" and p != r
        if not (spike and abs(p[0] - r[0]) <= u and abs(p[1] - r[1]) <= u):
            k += 1
            continue
        cut = ("pair", int(gaps.ring_of[labels[k - 1][1]]))
        for s, (axis, fix, sign) in enumerate(_SIDES):
            other = 1 - axis
            if p[other] == r[other] == gaps.box[fix] and (r[axis] - p[axis]) * sign > 0:
                cut = ("side", s)
        labels[k - 1] = cut
        del ring[k], labels[k]
        k = 0
    return ring, labels


def _convex(ring) -> bool:
    """Whether an open counter-clockwise ring never turns right (exact turns)."""
    r = np.array(ring + ring[:1], dtype=np.float64)
    return bool(rings_convex(r, np.array([0, len(r)], dtype=np.int64))[0])


class _Gaps:
    """Where the rings leave the box uncovered: edges no ring shares, bare stretches of sides.

    ``free`` maps each gap edge ``(px, py, qx, qy)`` (the reverse of an edge no ring
    shares) to that edge's index in ``closed``; ``bare[s]`` lists side ``s``'s uncovered
    stretches ``(lo, hi)``; ``verts`` holds the gap's vertices.
    """

    def __init__(self, closed, lengths, box):
        self.box = box
        size = np.diff(lengths)
        start = np.ones(len(closed), dtype=np.bool_)
        start[lengths[1:][size > 0] - 1] = False  # the closing vertex starts no edge
        e = np.flatnonzero(start)
        self.ring_of = np.repeat(np.arange(len(size)), size)
        p = closed[e] + 0.0  # (-0.0 as 0.0)
        q = closed[e + 1] + 0.0
        long = (p != q).any(axis=1)
        side = _side_of(p, q, box)
        inner = long & (side < 0)
        fwd = np.hstack((p, q))[inner]
        rev = np.hstack((q, p))[inner]
        alone = ~np.isin(_rows(rev), _rows(fwd))
        self.free = {
            tuple(r): int(k) for r, k in zip(rev[alone].tolist(), e[inner][alone], strict=True)
        }
        self.bare = []
        for s, (axis, _, _) in enumerate(_SIDES):
            on = long & (side == s)
            lo = np.minimum(p[on, axis], q[on, axis])
            hi = np.maximum(p[on, axis], q[on, axis])
            self.bare.append(_uncovered(lo, hi, box[axis], box[axis + 2]))
        verts = [k[:2] for k in self.free] + [k[2:] for k in self.free]
        for s, (axis, fix, _) in enumerate(_SIDES):
            for stretch in self.bare[s]:
                for t in stretch:
                    verts.append((t, box[fix]) if axis == 0 else (box[fix], t))
        self.verts = np.array(sorted(set(verts)), dtype=np.float64).reshape(-1, 2)
        self.known = set(map(tuple, self.verts.tolist()))

    def any(self) -> bool:
        """Whether the rings leave any gap."""
        return bool(len(self.verts))

    def snap(self, ring):
        """The rounded exact ring with each vertex moved to the gap's vertex near it, or None.

        A vertex that is one of the gap's, or lies on a bare stretch of a side, stays; any
        other goes to the nearest gap vertex within ``RESTORE_SNAP_ULPS`` ulps (None: there is
        none, or two are nearest). Repeated vertices are merged.
        """
        out = []
        for x, y in ring:
            if (x, y) not in self.known and not self._on_bare(x, y):
                u = RESTORE_SNAP_ULPS * math.ulp(max(abs(x), abs(y)))
                d = np.abs(self.verts - (x, y)).max(axis=1)
                near = np.flatnonzero(d <= u)
                if not len(near):
                    return None
                dist = np.hypot(self.verts[near, 0] - x, self.verts[near, 1] - y)
                best = near[dist == dist.min()]
                if len(best) > 1:
                    return None
                x, y = self.verts[best[0]]
            if not out or out[-1] != (x, y):
                out.append((float(x), float(y)))
        while len(out) > 1 and out[-1] == out[0]:
            out.pop()
        return out

    def cycles(self):
        """The gap's boundary as closed cycles: ``[(ring, labels), ...]``.

        Each cycle runs counter-clockwise around a gap (the gap on its left) through the gap
        edges (``("gap", e)``) and the bare stretches of the box's sides (``("side", s)``).
        At a vertex with several ways on, the one turning most to the right is taken (the
        smallest gap). A walk that does not come back to its start is dropped.
        """
        out = {}
        for key, e in self.free.items():
            out.setdefault(key[:2], []).append((key[2:], ("gap", e)))
        for s, (axis, fix, sign) in enumerate(_SIDES):
            for lo, hi in self.bare[s]:
                a, b = (lo, hi) if sign > 0 else (hi, lo)
                p, q = ((a, self.box[fix]), (b, self.box[fix]))
                if axis == 1:
                    p, q = p[::-1], q[::-1]
                out.setdefault(p, []).append((q, ("side", s)))
        used = set()
        found = []
        for start in sorted(out):
            for first in out[start]:
                if (start, first) in used:
                    continue
                ring, labels, here, step = [start], [], start, first
                while True:
                    used.add((here, step))
                    labels.append(step[1])
                    prev, here = here, step[0]
                    if here == start:
                        found.extend(_loops(ring, labels))
                        break
                    ways = [w for w in out.get(here, ()) if (here, w) not in used]
                    if not ways:
                        break
                    ring.append(here)
                    step = min(ways, key=lambda w: _turn(prev, here, w[0]))
        return found

    def _on_bare(self, x, y) -> bool:
        for s, (axis, fix, _) in enumerate(_SIDES):
            if (y, x)[axis] == self.box[fix]:
                t = (x, y)[axis]
                if any(lo < t < hi for lo, hi in self.bare[s]):
                    return True
        return False

    def label(self, p, q):
        """How edge ``p -> q`` runs along the gap: ``("gap", e)``, ``("side", s)`` or None."""
        key = (*p, *q)
        if key in self.free:
            return ("gap", self.free[key])
        for s, (axis, fix, sign) in enumerate(_SIDES):
            other = 1 - axis
            if p[other] == q[other] == self.box[fix] and (q[axis] - p[axis]) * sign > 0:
                lo, hi = sorted((p[axis], q[axis]))
                if any(a <= lo and hi <= b for a, b in self.bare[s]):
                    return ("side", s)
        return None


def _loops(ring, labels):
    """A closed walk split at the vertices it passes twice into simple loops (with labels).

    The gap of two lost sites side by side can pinch at a vertex: its walk is no valid ring,
    the loops on either side of the pinch are.
    """
    out = []
    stack = []  # (vertex, label of the step leaving it)
    at = {}
    for v, lab in zip(ring, labels, strict=True):
        if v in at:
            k = at[v]
            loop = stack[k:]
            del stack[k:]
            for u, _ in loop:
                at.pop(u, None)
            out.append(([u for u, _ in loop], [b for _, b in loop]))
        at[v] = len(stack)
        stack.append((v, lab))
    if stack:
        out.append(([u for u, _ in stack], [b for _, b in stack]))
    return out


def _turn(p, q, r) -> float:
    """The signed angle of the turn ``p -> q -> r`` (left positive), in local differences."""
    ax, ay = q[0] - p[0], q[1] - p[1]
    bx, by = r[0] - q[0], r[1] - q[1]
    return math.atan2(ax * by - ay * bx, ax * bx + ay * by)


def _rows(a):
    """Rows of a float array as single opaque items (for set tests)."""
    a = np.ascontiguousarray(a)
    return a.view(np.dtype((np.void, a.dtype.itemsize * a.shape[1]))).ravel()


def _side_of(p, q, box):
    """Per edge ``p -> q``: the box side it runs along (index into ``_SIDES``), else -1."""
    side = np.full(len(p), -1, dtype=np.int64)
    for s, (axis, fix, _) in enumerate(_SIDES):
        other = 1 - axis
        side[(p[:, other] == box[fix]) & (q[:, other] == box[fix])] = s
    return side


def _uncovered(lo, hi, start, stop):
    """The stretches of ``[start, stop]`` no interval ``[lo, hi]`` covers."""
    out = []
    cur = start
    for a, b in sorted(zip(lo.tolist(), hi.tolist(), strict=True)):
        if a > cur:
            out.append((cur, a))
        cur = max(cur, b)
    if cur < stop:
        out.append((cur, stop))
    return out


def _valid(ring) -> bool:
    """Whether an open ring is a valid counter-clockwise polygon."""
    if len(ring) < 3:
        return False
    r = np.array(ring + ring[:1])
    if not shapely.is_valid(shapely.polygons(r)):
        return False
    r = r - r[0]
    return math.fsum(r[:-1, 0] * r[1:, 1] - r[1:, 0] * r[:-1, 1]) > 0.0


def _settle(cand, gaps):
    """The candidate rings that fill the gap together: ``{site: (ring, labels)}``.

    A ring is dropped when an edge of it runs along no gap (and is not the reverse of another
    remaining ring's edge), or when it takes a gap edge or stretch another ring takes too;
    repeated until none is dropped, so the result does not depend on the rings' order.
    """
    alive = dict(cand)
    while alive:
        edges = {}
        for i, ring in alive.items():
            for k in range(len(ring)):
                edges.setdefault((*ring[k], *ring[(k + 1) % len(ring)]), []).append(i)
        bad = set()
        used = {}
        out = {}
        for i, ring in alive.items():
            labels = []
            for k in range(len(ring)):
                p, q = ring[k], ring[(k + 1) % len(ring)]
                got = gaps.label(p, q)
                if got is None:
                    other = [j for j in edges.get((*q, *p), ()) if j != i]
                    got = ("pair", other[0]) if len(other) == 1 else None
                if got is None or len(edges[(*p, *q)]) > 1:
                    bad.add(i)
                    break
                if got[0] == "side":
                    axis = _SIDES[got[1]][0]
                    lo, hi = sorted((p[axis], q[axis]))
                    used.setdefault(("side", got[1]), []).append((lo, hi, i))
                elif got[0] == "gap":
                    used.setdefault(got, []).append((0, 0, i))
                labels.append(got)
            else:
                out[i] = (ring, labels)
        for key, uses in used.items():
            uses.sort()
            if key[0] == "gap":
                if len(uses) > 1:
                    bad.update(u[2] for u in uses)
                continue
            for a, b in zip(uses[:-1], uses[1:], strict=True):
                if b[0] < a[1]:  # two rings on one stretch of a side
                    bad.update((a[2], b[2]))
        if not bad:
            return {i: out[i] for i in out}
        for i in bad:
            del alive[i]
    return {}


def _holding(xs, ys, box, kept):
    """The sites of the rings ``kept`` (:func:`_settle`) that their ring holds (exact)."""
    sites = sorted(kept)
    if not sites:
        return set()
    size = np.array([len(kept[i][0]) + 1 for i in sites], dtype=np.int64)
    lengths = np.concatenate(([0], np.cumsum(size)))
    coords = np.concatenate([np.array(kept[i][0] + kept[i][0][:1]) for i in sites])
    code = rings_astray(
        xs[sites], ys[sites], coords, lengths, box, np.ones(len(sites), dtype=np.bool_)
    )
    return {i for i, c in zip(sites, code.tolist(), strict=True) if c != 1}


def _filled(kept, gaps) -> bool:
    """Whether the rings ``kept`` (:func:`_settle`) take every gap edge."""
    return sum(kind == "gap" for _, labels in kept.values() for kind, _ in labels) == len(gaps.free)


def _exact_rings(xs, ys, box, which):
    """Each site of ``which``'s exact Voronoi cell in ``box``, vertices rounded to float64.

    ``{site: [(x, y), ...]}`` counter-clockwise (a site with no area left out). The cut
    starts with the site's ``RESTORE_FIRST`` nearest sites; any site strictly nearer than the site
    to a vertex of the cut (exact test, on the sites a KD-tree finds within the vertex's
    distance to the site, widened by its rounding) joins it, until none is: the cut is then
    the cell (convex, so its vertices decide).
    """
    n = len(xs)
    exact = Exact(xs, ys, np.zeros(n), np.asarray(box, dtype=np.float64), np.arange(n))
    from scipy.spatial import cKDTree

    tree = cKDTree(np.column_stack((xs, ys)))
    s = exact.s
    out = {}
    for i in (int(i) for i in which):
        near = np.atleast_1d(tree.query((xs[i], ys[i]), k=min(n, RESTORE_FIRST + 1))[1])
        cand = list(dict.fromkeys(int(j) for j in near))
        while True:
            lines = exact.cell(i, cand)
            if not lines:
                break
            verts = [vertex(lines[k - 1], lines[k]) for k in range(len(lines))]
            near = [(x / (d << s), y / (d << s)) for x, y, d in verts]
            more = _beaten(exact, tree, xs, ys, i, verts, near, set(cand))
            if not more:
                out[i] = near
                break
            cand += more
    return out


def _beaten(exact, tree, xs, ys, i, verts, rounded, skip):
    """Sites not in ``skip`` strictly nearer than site ``i`` to a vertex of ``verts``.

    ``rounded`` are the vertices in floats: a site nearer to the exact vertex lies within
    the rounded vertex's distance to site ``i`` plus twice the rounding (an ulp of each
    coordinate). The vertex's ``RESTORE_FIRST`` nearest sites are tested first (a violator among
    them is the nearest, the cut that shrinks the cell most); only where none is and the
    farthest of them is still that close, every site in the ball.
    """
    more = {}
    own = exact.site(i)
    k = min(len(xs), RESTORE_FIRST)
    for (x, y, d), (fx, fy) in zip(verts, rounded, strict=True):
        reach = math.hypot(fx - xs[i], fy - ys[i]) * (1.0 + 2.0**-40)
        reach += 4.0 * math.ulp(max(abs(fx), abs(fy), abs(xs[i]), abs(ys[i])))
        dist, near = tree.query((fx, fy), k=k)
        dist, near = np.atleast_1d(dist), np.atleast_1d(near)
        found = False
        for group in (near[dist <= reach].tolist(), None):
            if group is None:
                if found or dist[-1] > reach:
                    break
                group = tree.query_ball_point((fx, fy), reach)
            for j in group:
                if j in more:
                    found = True  # (a vertex before this one found it)
                if j in skip or j in more or j == i:
                    continue
                a, b, c = line(*own, *exact.site(j))
                if a * x + b * y - c * d > 0:
                    more[j] = None
                    found = True
    return list(more)
