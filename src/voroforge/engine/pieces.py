"""The domain cut to a cell's box, and exact tests against the domain that stay local.

A cell that meets a polygonal domain's boundary is intersected with the domain cut to the
cell's box (:meth:`Pieces.around`, GEOS's rectangle clip). On a domain whose one outline
meets every cell (a comb of thousands of teeth) every call that reads the whole domain is
linear in its vertices and runs once per cell, which makes the diagram quadratic; here
each reads only the boundary near the cell:

- the boundary is indexed as chunks of ``PIECE_CHUNK`` consecutive segments of every ring
  (:meth:`Pieces._index`): a geometry that meets no chunk (an exact query) lies wholly
  inside or wholly outside the domain, which one of its points tells;
- a point that many boundary segments span is located in the domain cut to a box around
  it (:meth:`Pieces.holds`): within the box the cut domain's edges are the domain's own;
- the rectangle clip reads a copy of each ring that keeps the chunks meeting the rectangle
  and replaces the others by a detour far outside it (:func:`_detoured`), which GEOS clips
  to the same coordinates, bit for bit, as the whole ring.

Domains of at most ``PIECE_SMALL`` vertices keep the direct predicates on the whole domain.
"""

from __future__ import annotations

import numpy as np
import shapely

from ..config import PIECE_BIG_RING, PIECE_CHUNK, PIECE_RAY_SPAN, PIECE_SMALL, PIECE_TILE
from .domain import Domain


class Pieces:
    """The domain cut to each cell's box: what a cell, or an edge of it, is intersected with.

    Overlay cost grows with the size of both operands, so a cell meeting the domain's
    boundary is intersected with the domain cut to the cell's bounding box (GEOS's
    rectangle clip, tens of times cheaper than an overlay; when its result is not valid,
    the overlay makes it), and an edge with the piece of its lower-numbered cell, whose box
    holds it. A piece depends on the domain and the cell's convex ring alone, never on the
    other cells: a cell gets the same crossing points bit for bit whichever other cells are
    computed with it (the tiled ``scale.voronoi`` relies on it). Above ``PIECE_SMALL``
    vertices every test reads only the domain's boundary near the cell (see the module's
    docstring), so a domain of ``N`` vertices costs about ``N`` in all, not ``N`` per cell.
    """

    def __init__(self, dom: Domain, closed, ring_offsets, ring_cell, n: int):
        self.geometry = dom.geometry
        self.whole = int(shapely.get_num_coordinates(dom.geometry)) <= PIECE_SMALL
        # the boundary's chunks (see the module's docstring) where a ring is that long
        self.local = not self.whole and _longest_ring(dom.geometry) > PIECE_BIG_RING
        self._prepared = None
        self.box = np.asarray(shapely.bounds(dom.geometry), dtype=np.float64)
        self.bounds = np.zeros((n, 4))
        if len(ring_cell):
            starts = ring_offsets[:-1]
            self.bounds[ring_cell, 0] = np.minimum.reduceat(closed[:, 0], starts)
            self.bounds[ring_cell, 1] = np.minimum.reduceat(closed[:, 1], starts)
            self.bounds[ring_cell, 2] = np.maximum.reduceat(closed[:, 0], starts)
            self.bounds[ring_cell, 3] = np.maximum.reduceat(closed[:, 1], starts)
        self.cache: dict[int, object] = {}
        self.coords = None
        self.sides = None  # the domain's distinct x and y coordinates, sorted (when needed)
        self.rings = None  # an index of the domain's rings (:meth:`_near`), when needed
        self.chunks = None  # the boundary's chunk index (:meth:`_index`), when needed
        self.spans = None  # every segment's lowest and highest ordinate, sorted

    @property
    def prepared(self):
        """A prepared copy of the domain (the caller's geometry is left as it is)."""
        if self._prepared is None:
            self._prepared = shapely.from_wkb(shapely.to_wkb(self.geometry))
            shapely.prepare(self._prepared)
        return self._prepared

    def piece(self, cell: int):
        """The domain cut to cell ``cell``'s box (:meth:`around`), computed once."""
        got = self.cache.get(cell)
        if got is None:
            got = self.cache[cell] = self.around(*self.bounds[cell])
        return got

    def around(self, x0, y0, x1, y1):
        """The domain cut to a rectangle that holds ``[x0, x1] x [y0, y1]``.

        GEOS's rectangle clip returns the complement of the answer (valid, so unnoticed) when
        the domain's boundary passes through two corners of the rectangle (a box-wide cell
        in a domain with vertices on its box: ``clip_by_rect`` of the polygon
        ``(0 0, 3 0, 3 10, 1.5 0.5, 0 10)`` to its own bounds is the notch between its
        teeth): the rectangle is grown a little, to sides on which no vertex of the domain
        lies. A domain of at most ``PIECE_SMALL`` vertices is returned whole: a cut adds
        rounded vertices on the rectangle's sides, and a crossing with such a shortened
        segment can round to the other neighbouring float than the crossing with the domain's
        own segment, which the exact clip and the shared edges use (a 20-point star at 3e12:
        a cell redone in its site's frame ended one ulp off its edge's end).
        """
        if self.whole:
            return self.geometry
        rect = self._grown(x0, y0, x1, y1)
        got = shapely.clip_by_rect(self._near(rect), *rect)
        if not shapely.is_valid(got):
            got = shapely.intersection(self.geometry, shapely.box(*rect))
        return got

    def _grown(self, x0, y0, x1, y1):
        """``[x0, x1] x [y0, y1]`` grown by a sixteenth, to sides off the domain's vertices."""
        if self.sides is None:
            xy = self._coords()
            self.sides = (np.unique(xy[:, 0]), np.unique(xy[:, 1]))
        rect = []
        for v, step, axis in ((x0, -1, 0), (y0, -1, 1), (x1, 1, 0), (y1, 1, 1)):
            width = (x1 - x0) if axis == 0 else (y1 - y0)
            used = self.sides[axis]
            v = v + step * max(width, abs(v) * 2.0**-40) / 16
            while used[min(np.searchsorted(used, v), len(used) - 1)] == v:
                v = v + step * max(width, abs(v) * 2.0**-40) / 16
            rect.append(v)
        return rect

    def _ring_index(self):
        """An STRtree of the domain's rings (shells, then holes) and each ring's part."""
        if self.rings is None:
            polys = shapely.get_parts(self.geometry)
            holes = [
                shapely.get_interior_ring(p, range(shapely.get_num_interior_rings(p)))
                for p in polys
            ]
            shells = shapely.get_exterior_ring(polys)
            every = np.concatenate([shells, *holes])
            part = np.concatenate(
                [np.arange(len(polys)), *[np.full(len(h), k) for k, h in enumerate(holes)]]
            )
            self.rings = (shapely.STRtree(every), every, part)
        return self.rings

    def _index(self):
        """The boundary in chunks: an STRtree of LineStrings and where each chunk lies.

        Chunk ``c`` is vertices ``start[c] .. end[c]`` of ring ``ring[c]`` (ring numbers as
        in :meth:`_ring_index`); ``coords[r]`` is ring ``r``'s closed coordinates, ``ccw[r]``
        GEOS's orientation test of it.
        """
        if self.chunks is None:
            every = self._ring_index()[1]
            coords = [shapely.get_coordinates(r) for r in every]
            segs = np.array([len(c) - 1 for c in coords])
            per = -(-segs // PIECE_CHUNK)
            ring = np.repeat(np.arange(len(every)), per)
            first = np.repeat(np.cumsum(per) - per, per)
            start = (np.arange(len(ring)) - first) * PIECE_CHUNK
            end = np.minimum(start + PIECE_CHUNK, segs[ring])
            size = end - start + 1
            at = np.repeat(np.cumsum(size) - size, size)
            base = np.repeat((np.cumsum(segs + 1) - segs - 1)[ring] + start, size)
            flat = np.concatenate(coords)[base + np.arange(size.sum()) - at]
            lines = shapely.linestrings(flat, indices=np.repeat(np.arange(len(ring)), size))
            ccw = np.array([bool(shapely.is_ccw(r)) for r in every])
            self.chunks = (shapely.STRtree(lines), ring, start, end, coords, ccw)
            # every chunk's segments' boxes, chunk after chunk (chunk c's from seg_at[c])
            nseg = size - 1
            self.seg_at = np.cumsum(nseg) - nseg
            pos = np.repeat(np.cumsum(size) - size - self.seg_at, nseg) + np.arange(nseg.sum())
            self.seg_box = np.hstack(
                (np.minimum(flat[pos], flat[pos + 1]), np.maximum(flat[pos], flat[pos + 1]))
            )
        return self.chunks

    def meets_boundary(self, geoms):
        """Whether each geometry meets the domain's boundary (exact, chunk by chunk)."""
        tree = self._index()[0]
        out = np.zeros(len(geoms), dtype=np.bool_)
        if len(geoms):
            out[tree.query(geoms, predicate="intersects")[0]] = True
        return out

    def holds(self, xy):
        """Whether the domain holds (or its boundary meets) each point of ``xy`` (exact).

        GEOS's point location casts a ray that crosses every boundary segment spanning the
        point's ordinate (on a comb, every tooth). Points that more than ``PIECE_RAY_SPAN``
        segments span are located instead, a tile of about ``PIECE_TILE`` of them at a
        time, in the domain cut to a rectangle around the tile (:meth:`_local_domain`),
        whose edges near them are the domain's own: the same answers.
        """
        out = np.zeros(len(xy), dtype=np.bool_)
        if not len(xy):
            return out
        far = np.zeros(len(xy), dtype=np.bool_)
        if self.local:
            if self.spans is None:
                every = self._index()[4]
                lo = np.concatenate([np.minimum(c[:-1, 1], c[1:, 1]) for c in every])
                hi = np.concatenate([np.maximum(c[:-1, 1], c[1:, 1]) for c in every])
                self.spans = (np.sort(lo), np.sort(hi))
            lo, hi = self.spans
            span = np.searchsorted(lo, xy[:, 1], "right") - np.searchsorted(hi, xy[:, 1], "left")
            far = span > PIECE_RAY_SPAN
        near = np.flatnonzero(~far)
        if len(near):
            out[near] = shapely.intersects_xy(self.prepared, xy[near, 0], xy[near, 1])
        far = np.flatnonzero(far)
        if not len(far):
            return out
        p = xy[far]
        lo, hi = p.min(axis=0), p.max(axis=0)
        w = hi - lo
        side = np.sqrt(w[0] * w[1] * PIECE_TILE / len(far))
        if not side > 0:
            side = max(w.max() * PIECE_TILE / len(far), 1e-300)
        tile = np.floor((p - lo) / side).astype(np.int64)
        key = tile[:, 0] * (int(tile[:, 1].max()) + 1) + tile[:, 1]
        order = np.argsort(key, kind="stable")
        cuts = np.flatnonzero(np.diff(key[order])) + 1
        for group in np.split(order, cuts):
            q = p[group]
            a, b = q.min(axis=0), q.max(axis=0)
            local = self._local_domain(a[0], a[1], b[0], b[1])
            where = self.prepared if local is None else local
            out[far[group]] = shapely.intersects_xy(where, q[:, 0], q[:, 1])
        return out

    def _local_domain(self, x0, y0, x1, y1):
        """The domain cut to a rectangle ``N`` around ``B = [x0, x1] x [y0, y1]``, or None.

        ``B`` is grown by an eighth (and by ``2**-30`` of the domain's magnitude) on each
        side, then by the boxes of the segments that meet it (of the chunks that meet it);
        ``N`` holds that strictly. An edge of the domain that meets ``B`` then has both ends
        inside ``N``, so the clip keeps it as it is; an edge that the clip cuts misses ``B``
        by at least the growth, far more than the rounding of the cut. A point of ``B`` is
        thus in the cut domain exactly when it is in the domain. None where the domain's
        boundary passes through a corner of ``N``, where GEOS's clip can return the
        complement (the caller asks the whole domain).
        """
        tree, _, start, end, _, _ = self._index()
        mag = max(np.abs(self.box).max(), abs(x0), abs(x1), abs(y0), abs(y1))
        pad = max(x1 - x0, y1 - y0, mag * 2.0**-30) / 8
        box = np.array([x0 - pad, y0 - pad, x1 + pad, y1 + pad])
        hit = tree.query(shapely.box(*box), predicate="intersects")
        if len(hit):
            count = end[hit] - start[hit]
            first = np.repeat(self.seg_at[hit] - (np.cumsum(count) - count), count)
            seg = self.seg_box[first + np.arange(count.sum())]
            meet = (seg[:, 0] <= box[2]) & (seg[:, 2] >= box[0])
            meet &= (seg[:, 1] <= box[3]) & (seg[:, 3] >= box[1])
            if meet.any():
                box[:2] = np.minimum(box[:2], seg[meet, :2].min(axis=0))
                box[2:] = np.maximum(box[2:], seg[meet, 2:].max(axis=0))
        x0, y0, x1, y1 = rect = self._grown(*box)
        # GEOS's clip is wrong only where the boundary passes through corners of the rectangle
        corners = shapely.points([(x0, y0), (x1, y0), (x1, y1), (x0, y1)])
        if len(tree.query(corners, predicate="intersects")[0]):
            return None
        return shapely.clip_by_rect(self._near(rect), *rect)

    def _disjoint(self, geoms, todo):
        """``disjoint(domain, geoms[k])`` where ``todo[k]`` (False elsewhere), exactly.

        The prepared predicate tests a point of every ring of the domain against each
        geometry (thousands of holes: quadratic); here a geometry that meets no ring (an
        indexed exact query) lies wholly inside or wholly outside, which its first vertex
        tells.
        """
        out = np.zeros(len(geoms), dtype=np.bool_)
        idx = np.flatnonzero(todo)
        if self.whole or not len(idx):
            out[idx] = shapely.disjoint(self.prepared, geoms[idx])
            return out
        tree = self._ring_index()[0]
        meets = np.zeros(len(idx), dtype=np.bool_)
        meets[tree.query(geoms[idx], predicate="intersects")[0]] = True
        xy, at = shapely.get_coordinates(geoms[idx], return_index=True)
        first = xy[np.unique(at, return_index=True)[1]]
        out[idx] = ~meets & ~shapely.intersects_xy(self.prepared, first[:, 0], first[:, 1])
        return out

    def _near(self, rect):
        """What GEOS's rectangle clip of the domain to ``rect`` reads: the same clip.

        GEOS's rectangle clip drops a ring that misses the rectangle (a hole whose box
        misses it cannot hold it) and keeps the others in their order, so the clip of what
        is left is the clip of the domain, point for point, in time linear in the rings
        near the rectangle rather than in all the domain's vertices (a domain with
        thousands of holes spread over it). Above ``PIECE_SMALL`` vertices a ring that
        meets the rectangle also keeps only its chunks near it (:func:`_detoured`).
        """
        tree, every, part = self._ring_index()
        if len(every) <= 2 and not self.local:
            return self.geometry
        hit = np.sort(tree.query(shapely.box(*rect)))
        if len(hit) == len(every) and not self.local:
            return self.geometry
        rings = every[hit]
        if self.local:
            rings = self._cut_rings(hit, rect)
            if rings is None:
                return self.geometry
        polys = []
        for k in np.unique(part[hit]):
            mine = np.flatnonzero(part[hit] == k)
            if hit[mine[0]] == k:  # (a part whose shell misses the rectangle misses it whole)
                polys.append(shapely.polygons(rings[mine[0]], holes=rings[mine[1:]]))
        if not polys:
            return self.geometry  # (the rectangle misses the domain: the clip is empty)
        if shapely.get_type_id(self.geometry) == 3:
            return polys[0]
        return shapely.multipolygons(polys)

    def _cut_rings(self, hit, rect):
        """Rings ``hit``, each cut to its chunks near ``rect`` (:func:`_detoured`), or None.

        None where a cut ring might leave GEOS nothing inside the rectangle (it then locates
        the rectangle's centre in the ring, which the detours do not keep).
        """
        tree, ring, start, end, coords, ccw = self._index()
        every = self._ring_index()[1]
        near = tree.query(shapely.box(*rect))
        keep = np.zeros(len(ring), dtype=np.bool_)
        keep[near] = True
        first = np.searchsorted(ring, hit)
        last = np.searchsorted(ring, hit, "right")
        frame = _frame(self.box, rect)
        out = np.empty(len(hit), dtype=object)  # noqa: TID251 - every slot is filled below
        for j, r in enumerate(hit):
            kept = keep[first[j] : last[j]]
            if kept.all() or not kept.any():
                out[j] = every[r]
                continue
            c = coords[r]
            s, e = start[first[j] : last[j]], end[first[j] : last[j]]
            if not _clipped_inside(c, s[kept], e[kept], rect):
                return None
            out[j] = shapely.linearrings(_detoured(c, s, e, kept, rect, frame, ccw[r]))
        return out

    def vertex_near(self, ring, reach):
        """The vertex of the domain nearest to ``ring`` if within ``reach`` of it, else None."""
        coords = self._coords()
        x0, y0, x1, y1 = shapely.bounds(ring)
        box = (
            (coords[:, 0] >= x0 - reach)
            & (coords[:, 0] <= x1 + reach)
            & (coords[:, 1] >= y0 - reach)
            & (coords[:, 1] <= y1 + reach)
        )
        cand = coords[box]
        if not len(cand):
            return None
        dist = shapely.distance(ring, shapely.points(cand))
        best = int(np.argmin(dist))
        return cand[best] if dist[best] <= reach else None

    def in_interior(self, lines, cells):
        """Whether each of ``lines`` meets the domain's interior (exact predicates).

        Line ``k`` lies in the domain and in the box of cell ``cells[k]``; a piece along
        the domain's boundary does not meet its interior.
        """
        out = np.zeros(len(lines), dtype=np.bool_)
        if self.whole:
            return shapely.relate_pattern(self.geometry, lines, "T********")
        order = np.argsort(cells, kind="stable")
        cuts = np.flatnonzero(np.diff(cells[order])) + 1
        for group in np.split(order, cuts) if len(order) else []:
            out[group] = shapely.relate_pattern(
                self.piece(int(cells[group[0]])), lines[group], "T********"
            )
        return out

    def _coords(self):
        if self.coords is None:
            self.coords = shapely.get_coordinates(self.geometry)
        return self.coords

    def intersect(self, geoms, cells, empty):
        """``geoms[k] ∩ domain`` for geometries inside the boxes of cells ``cells[k]``.

        A geometry in the domain's interior is its own intersection and one disjoint from it
        has ``empty`` (exact predicates, several times cheaper than an overlay); only the
        rest, which meet the domain's boundary, are overlaid. Above ``PIECE_SMALL``
        vertices a (connected) geometry that meets no chunk of the boundary lies wholly
        inside or wholly outside, which its first vertex tells (:meth:`holds`).
        """
        out = np.empty(len(geoms), dtype=object)  # noqa: TID251 - every slot is filled below
        if not self.local:
            inside = shapely.contains_properly(self.prepared, geoms)
            outside = self._disjoint(geoms, ~inside)
        else:
            free = np.flatnonzero(~self.meets_boundary(geoms))
            xy, at = shapely.get_coordinates(geoms[free], return_index=True)
            held = self.holds(xy[np.unique(at, return_index=True)[1]])
            inside = np.zeros(len(geoms), dtype=np.bool_)
            outside = np.zeros(len(geoms), dtype=np.bool_)
            inside[free[held]] = True
            outside[free[~held]] = True
        out[inside] = geoms[inside]
        out[outside] = empty
        rest = np.flatnonzero(~(inside | outside))
        if self.whole:
            out[rest] = shapely.intersection(geoms[rest], self.geometry)
            return out
        order = rest[np.argsort(cells[rest], kind="stable")]
        cuts = np.flatnonzero(np.diff(cells[order])) + 1
        for group in np.split(order, cuts) if len(order) else []:
            out[group] = shapely.intersection(geoms[group], self.piece(int(cells[group[0]])))
        return out


def _longest_ring(geom):
    """The most vertices of one ring of a Polygon or MultiPolygon."""
    polys = shapely.get_parts(geom)
    rings = [shapely.get_exterior_ring(polys)]
    rings += [shapely.get_interior_ring(p, range(shapely.get_num_interior_rings(p))) for p in polys]
    return int(max(shapely.get_num_coordinates(r).max(initial=0) for r in rings))


def _frame(bounds, rect):
    """A box around the domain and ``rect``, as far again beyond them: the detours' road."""
    x0, y0 = min(bounds[0], rect[0]), min(bounds[1], rect[1])
    x1, y1 = max(bounds[2], rect[2]), max(bounds[3], rect[3])
    w, h = x1 - x0, y1 - y0
    return x0 - w, y0 - h, x1 + w, y1 + h


def _detoured(c, start, end, kept, rect, frame, ccw):
    """Ring ``c`` (closed) with its chunks that miss ``rect`` replaced by detours around it.

    Where GEOS's rectangle clip reads a ring, a segment that misses the rectangle gives
    nothing; only the segments that meet it, in their order from the ring's first vertex,
    make the clipped lines, and the ring's orientation (GEOS's ``isCCW``: the turn at its
    highest vertex) says which way they are closed along the rectangle. So each run of
    chunks whose boxes miss the rectangle (each of its segments lies beyond one side)
    becomes a path from its first vertex straight out to the frame, along the frame, and
    back to its last vertex, never meeting the rectangle; the first such path climbs to a
    peak above everything whose turn has the ring's orientation. The first vertex stays
    first. GEOS then clips this ring to what it clips the whole ring to, point for point,
    as long as it clips some segment (:func:`_clipped_inside`).
    """
    x0, y0, x1, y1 = rect
    fx0, fy0, fx1, fy1 = frame
    w, h = fx1 - fx0, fy1 - fy0
    corner = {0: [], 1: [], 2: [(fx1, fy1)], 3: [(fx0, fy0)]}
    peak = [True]

    def side(p):
        return 0 if p[0] < x0 else 2 if p[0] > x1 else 3 if p[1] < y0 else 1

    def detour(a, b):
        sa, sb = side(a), side(b)
        out = [[(fx0, a[1]), (a[0], fy1), (fx1, a[1]), (a[0], fy0)][sa], *corner[sa]]
        out.append((fx0, fy1))
        if peak[0]:
            peak[0] = False
            s = 1.0 if ccw else -1.0
            out += [(fx0 + s * w, fy1 + h), (fx0, fy1 + 2 * h), (fx0 - s * w, fy1 + h)]
            out.append((fx0, fy1))
        out += corner[sb][::-1]
        out.append([(fx0, b[1]), (b[0], fy1), (fx1, b[1]), (b[0], fy0)][sb])
        return np.array(out, dtype=np.float64)

    cuts = np.flatnonzero(np.diff(kept.astype(np.int8))) + 1
    bounds = np.concatenate(([0], cuts, [len(kept)]))
    parts = [] if kept[0] else [c[:1]]
    for lo, hi in zip(bounds[:-1], bounds[1:], strict=True):
        if kept[lo]:
            parts.append(c[start[lo] : end[hi - 1] + 1])
        else:
            parts.append(detour(c[start[lo]], c[end[hi - 1]]))
    if not kept[-1]:
        parts.append(c[-1:])
    return np.concatenate(parts)


def _clipped_inside(c, start, end, rect):
    """Whether GEOS's rectangle clip surely finds part of the ring inside ``rect``.

    True where a vertex of the kept chunks (``c[start[k] .. end[k]]``) lies strictly inside
    the rectangle, or a segment crossing it is clipped to two points on two of its sides,
    well away from its corners (the float steps of GEOS's ``clip_to_edges``). Else GEOS
    might find nothing and locate the rectangle's centre in the ring, which a detoured
    ring does not keep: the caller clips the whole domain.
    """
    x0, y0, x1, y1 = rect
    idx = np.concatenate([np.arange(s, e + 1) for s, e in zip(start, end, strict=True)])
    p = c[idx]
    if ((p[:, 0] > x0) & (p[:, 0] < x1) & (p[:, 1] > y0) & (p[:, 1] < y1)).any():
        return True
    seg = np.concatenate(
        [np.hstack((c[s:e], c[s + 1 : e + 1])) for s, e in zip(start, end, strict=True)]
    )
    lo = np.minimum(seg[:, :2], seg[:, 2:])
    hi = np.maximum(seg[:, :2], seg[:, 2:])
    cross = (lo[:, 0] <= x1) & (hi[:, 0] >= x0) & (lo[:, 1] <= y1) & (hi[:, 1] >= y0)
    tol = 2.0**-40 * max(abs(x0), abs(x1), abs(y0), abs(y1), x1 - x0, y1 - y0)
    return any(_crosses(*seg[k], rect, tol) for k in np.flatnonzero(cross))


def _crosses(ax, ay, bx, by, rect, tol):
    """GEOS's clip of segment ``a b`` (both ends outside) gives a line, ``tol`` off corners."""
    x0, y0, x1, y1 = rect
    px, py = _clip_to_edges(ax, ay, bx, by, rect)
    qx, qy = _clip_to_edges(bx, by, px, py, rect)
    ends = []
    for x, y in ((px, py), (qx, qy)):
        if x0 + tol < x < x1 - tol and y in (y0, y1):
            ends.append(1 if y == y0 else 3)
        elif y0 + tol < y < y1 - tol and x in (x0, x1):
            ends.append(0 if x == x0 else 2)
        else:
            return False
    return ends[0] != ends[1]


def _clip_to_edges(x, y, tx, ty, rect):
    """GEOS's ``clip_to_edges``: point ``(x, y)`` moved along the line to ``(tx, ty)``."""
    x0, y0, x1, y1 = rect
    if x < x0:
        x, y = _clip_one(x, y, tx, ty, x0)
    elif x > x1:
        x, y = _clip_one(x, y, tx, ty, x1)
    if y < y0:
        y, x = _clip_one(y, x, ty, tx, y0)
    elif y > y1:
        y, x = _clip_one(y, x, ty, tx, y1)
    return x, y


def _clip_one(x, y, tx, ty, limit):
    """GEOS's ``clip_one_edge`` (the same float steps)."""
    if tx == limit:
        x, y = tx, ty
    if x != tx:
        y += (ty - y) * (limit - x) / (tx - x)
        x = limit
    return x, y
