"""Paths for machines that draw or cut: no line twice, long strokes, short pen-up travel.

A pen plotter or a laser follows the paths of a file one after another. Three things decide
how well it does:

- **No line twice.** When two products of one layer share an edge (the frame's holes and
  the openings, neighbouring cells), the machine would pass over it twice: a laser burns
  it twice, a plotter bleeds ink. :func:`layer_paths` keeps every segment once: a ring that
  is another ring again (either direction, any start) is dropped; a ring that shares only
  some segments with what came before keeps the rest as open runs.
- **Long strokes.** Line work (the edge network) arrives as thousands of two-point
  segments. :func:`merge_lines` joins them into trails *through junctions* (like vpype's
  ``linemerge``, not only where exactly two segments meet): the fewest trails that cover
  the network, one per pair of odd-degree vertices (Euler's theorem).
- **Short pen-up travel.** :func:`order_paths` orders the paths by a greedy nearest-neighbour
  tour from the pen's home, each path entered from its nearer end, then improves the tour
  with 2-opt moves (reverse a run of paths and each path in it) on a nearest-neighbour
  candidate list until no move shortens it.

Examples
--------
>>> import numpy as np
>>> segs = [np.array([[0, 0], [1, 0]]), np.array([[1, 0], [1, 1]]), np.array([[1, 0], [2, 0]])]
>>> len(merge_lines(segs))  # a T-junction: two strokes, not three
2
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np
import shapely

from .. import config
from ..kernels.plotter import nearest_tour, two_opt
from .snap import close_pairs, cluster_labels, nearest

__all__ = [
    "Paths",
    "coincident_segments",
    "layer_paths",
    "merge_lines",
    "network_lines",
    "order_paths",
    "segment_keys",
    "travel",
]

ORDERS = ("travel", "file")


@dataclass(frozen=True)
class Paths:
    """The paths of one layer, in drawing order.

    Attributes
    ----------
    paths : list of (k, 2) float64
        Vertices of each path. A closed ring does not repeat its first vertex.
    closed : (n,) bool
        Which paths are closed rings (drawn back to their first vertex).
    """

    paths: list
    closed: np.ndarray

    def __len__(self) -> int:
        return len(self.paths)

    def rings(self) -> list:
        """The closed rings, in drawing order."""
        return [p for p, c in zip(self.paths, self.closed.tolist(), strict=True) if c]

    def lines(self) -> list:
        """The open paths, in drawing order."""
        return [p for p, c in zip(self.paths, self.closed.tolist(), strict=True) if not c]

    def travel(self, start=None) -> tuple[float, float]:
        """Pen-up and pen-down length of drawing the paths in order (see :func:`travel`)."""
        return travel(_as_drawn(self), start=start)


def _as_drawn(p: Paths) -> list:
    return [np.vstack((x, x[:1])) if c else x for x, c in zip(p.paths, p.closed, strict=True)]


# --- geometry in: rings and lines ----------------------------------------------------------


def _collect(geoms) -> tuple[list, list]:
    """Closed rings (without the closing vertex) and open lines of shapely geometries."""
    rings, lines = [], []
    if isinstance(geoms, shapely.Geometry):
        geoms = [geoms]
    for geom in geoms:
        if geom is None or geom.is_empty:
            continue
        for part in shapely.get_parts(geom):
            kind = part.geom_type
            if kind == "Polygon":
                if hasattr(shapely, "orient_polygons"):  # exteriors CCW, holes CW
                    part = shapely.orient_polygons(part)
                for ring in (part.exterior, *part.interiors):
                    xy = np.asarray(ring.coords, dtype=np.float64)[:-1, :2]
                    if len(xy) >= 3:
                        rings.append(xy)
            elif kind == "LinearRing":
                xy = np.asarray(part.coords, dtype=np.float64)[:-1, :2]
                if len(xy) >= 3:
                    rings.append(xy)
            elif kind == "LineString":
                xy = np.asarray(part.coords, dtype=np.float64)[:, :2]
                if len(xy) >= 2:
                    lines.append(xy)
            elif kind in ("MultiPolygon", "MultiLineString", "GeometryCollection"):
                r, ln = _collect([part])
                rings += r
                lines += ln
    return rings, lines


def _tolerance(coords: np.ndarray, tolerance, pieces=()) -> float:
    """The vertex merge distance: ``tolerance`` if given, else from the drawing.

    ``pieces`` are the drawn point runs (rings, lines, segments: consecutive points joined).
    """
    if tolerance is not None:
        t = float(tolerance)
        if not math.isfinite(t) or t < 0:
            raise ValueError(f"tolerance must be a non-negative number; got {tolerance!r}")
        return t
    if not len(coords):
        return 0.0
    # the drawing's size, not its distance from the origin (a 0.5 mm fillet's chords were
    # merged away at an offset of 5e8); far out, the rounding of the coordinates, but never
    # a quarter of a drawn segment or more: exact cells one unit wide at 1e14 (64 ulps) were
    # merged to points and left out of the DXF (checker23 F4)
    size = float(np.ptp(coords, axis=0).max()) * config.PLOTTER_MERGE_RTOL
    ulps = float(np.abs(coords).max()) * np.finfo(np.float64).eps * config.PLOTTER_MERGE_ULPS
    if ulps > size:
        ulps = min(ulps, 0.25 * _shortest_step(pieces))
    return max(size, ulps)


def _shortest_step(pieces) -> float:
    """The shortest nonzero distance between consecutive points of any piece (inf if none)."""
    if isinstance(pieces, np.ndarray):  # (s, 2, 2) segments
        steps = [pieces[:, 1] - pieces[:, 0]]
    else:
        steps = [np.diff(np.asarray(p, dtype=np.float64), axis=0) for p in pieces if len(p) >= 2]
    if not steps:
        return float("inf")
    d = np.hypot(*np.concatenate(steps).reshape(-1, 2).T)
    d = d[d > 0]
    return float(d.min()) if len(d) else float("inf")


def _vertex_ids(coords: np.ndarray, tol: float) -> tuple[np.ndarray, np.ndarray]:
    """One id per coordinate row: rows closer than ``tol`` share an id; and the id's point."""
    # unique rows by a lexicographic sort (np.unique(axis=0) is several times slower)
    order = np.lexsort((coords[:, 1], coords[:, 0]))
    sc = coords[order]
    head = np.ones(len(sc), dtype=bool)
    head[1:] = (sc[1:] != sc[:-1]).any(axis=1)
    verts = sc[head]
    inverse = np.zeros(len(coords), dtype=np.int64)
    inverse[order] = np.cumsum(head) - 1
    if tol > 0 and len(verts) > 1:
        pairs = close_pairs(verts, tol)
        if len(pairs):
            label = cluster_labels(len(verts), pairs)
            # each cluster is represented by its lowest vertex (labels follow those)
            first = np.unique(label, return_index=True)[1]
            verts = verts[first]
            inverse = label[inverse]
    return inverse.astype(np.int64), verts


def segment_keys(geoms, *, tolerance=None, points=None) -> np.ndarray:
    """Every segment of the geometries as an unordered pair of snapped vertex ids.

    Parameters
    ----------
    geoms : sequence of shapely geometries
        Polygons (every ring), lines and rings.
    tolerance : float, optional
        Vertices closer than this are one (default ``config.PLOTTER_MERGE_RTOL`` of the size).
    points : (m, 2) float64, optional
        Snap against these vertices too (to compare two layers in one frame).

    Returns
    -------
    (s, 2) int64
        ``(low, high)`` vertex ids, one row per non-degenerate segment (duplicates kept).
    """
    rings, lines = _collect(geoms)
    segs = [np.stack((r, np.roll(r, -1, axis=0)), axis=1) for r in rings]
    segs += [np.stack((ln[:-1], ln[1:]), axis=1) for ln in lines]
    if not segs:
        return np.zeros((0, 2), dtype=np.int64)
    arr = np.concatenate(segs)
    coords = arr.reshape(-1, 2)
    extra = np.zeros((0, 2)) if points is None else np.asarray(points, dtype=np.float64)
    both = np.vstack((coords, extra))
    ids, _ = _vertex_ids(both, _tolerance(both, tolerance, arr))
    ids = ids[: len(coords)].reshape(-1, 2)
    ids = ids[ids[:, 0] != ids[:, 1]]
    return np.sort(ids, axis=1)


def coincident_segments(a, b, *, tolerance=None) -> int:
    """How many segments of geometry ``a`` are also segments of geometry ``b``.

    Parameters
    ----------
    a, b : sequence of shapely geometries
        Two layers.
    tolerance : float, optional
        Vertex snap distance (default relative to the size).

    Returns
    -------
    int
        Segments of ``a`` (counted once each) that ``b`` draws too.
    """
    rings_a, lines_a = _collect(a)
    rings_b, lines_b = _collect(b)
    if not (rings_a or lines_a) or not (rings_b or lines_b):
        return 0
    both = list(a) + list(b) if not isinstance(a, shapely.Geometry) else [a, *b]
    keys = segment_keys(both, tolerance=tolerance)
    n_a = len(segment_keys(a, tolerance=tolerance))
    ka = {tuple(k) for k in keys[:n_a].tolist()}
    kb = {tuple(k) for k in keys[n_a:].tolist()}
    return len(ka & kb)


# --- no segment twice -----------------------------------------------------------------------


def _all_apart(coords: np.ndarray, tol: float) -> bool:
    """Whether every two rows of ``coords`` are more than ``tol`` apart (and none repeats).

    A sweep along a skew direction ``x + a y`` (not along an axis: outlines have many
    vertices on one vertical or horizontal line): two rows within ``tol`` have keys within
    ``(1 + a) tol`` plus the keys' rounding, so when the vertices are sparse at the scale
    of ``tol`` such rows are at most a few places apart in key order, and their distance
    (a hair above ``tol``, so no pair :func:`.snap.close_pairs` finds escapes) decides.
    A set dense at that scale is not proved apart (False).
    """
    n = len(coords)
    if n < 2:
        return True
    a = 0.6180339887498949
    key = coords[:, 0] + a * coords[:, 1]
    reach = tol * (1.0 + 1e-6)
    size = float(np.abs(coords).max())
    if not np.isfinite(size):
        return False
    reach_key = (1.0 + a) * reach + 8.0 * np.finfo(np.float64).eps * size
    order = np.argsort(key)
    k = key[order]
    x = coords[order, 0]
    y = coords[order, 1]
    for w in range(1, 9):
        if w >= n:
            return True
        near = np.flatnonzero(k[w:] - k[:-w] <= reach_key)
        if not len(near):
            return True
        dx = x[near + w] - x[near]
        dy = y[near + w] - y[near]
        if (dx * dx + dy * dy <= reach * reach).any():
            return False
    return False


def _dedupe(rings: list, lines: list, tol: float) -> tuple[list, list]:
    """Drop repeated rings; cut segments already drawn out of later rings and lines.

    A segment (an unordered pair of snapped vertices) is drawn by its first occurrence, in
    item order and then along each item; a ring all of whose segments are new is kept whole
    (a ring that repeats an earlier one has none, so it goes), the other items keep their
    runs of new segments as open lines.
    """
    items = rings + lines
    if not items:
        return [], []
    sizes = np.array([len(x) for x in items], dtype=np.int64)
    coords = np.concatenate(items)
    if _all_apart(coords, tol):
        # no two vertices snap together, so no segment repeats and no vertex goes: every
        # live item is kept whole (what the general path below gives, several times faster)
        return [r for r in rings if len(r) >= 3], [ln for ln in lines if len(ln) >= 2]
    ids, _ = _vertex_ids(coords, tol)
    nitem = len(items)
    item = np.repeat(np.arange(nitem), sizes)
    is_ring = np.arange(nitem) < len(rings)
    starts = np.concatenate(([0], np.cumsum(sizes)))
    # consecutive vertices that snap together are one vertex; a ring's closing repeat goes
    keep = np.ones(len(ids), dtype=bool)
    keep[1:] = (ids[1:] != ids[:-1]) | (item[1:] != item[:-1])
    last = starts[1:] - 1
    closing = is_ring & (sizes > 1) & (ids[last] == ids[starts[:-1]])
    keep[last[closing]] = False
    count = np.bincount(item[keep], minlength=nitem)
    live = np.where(is_ring, count >= 3, count >= 2)
    keep &= live[item]
    vid = ids[keep]
    owner = item[keep]
    xy_all = coords[keep]
    k_start = np.concatenate(([0], np.cumsum(count * live)))
    # segment j of an item joins its vertex j to j + 1 (rings wrap round)
    nxt = np.arange(1, len(vid) + 1)
    ends = k_start[1:] - 1
    wrap = live & is_ring
    nxt[ends[wrap]] = k_start[:-1][wrap]
    seg = np.ones(len(vid), dtype=bool)
    seg[ends[live & ~is_ring]] = False  # a line has one segment less than vertices
    a, b = vid[seg], vid[nxt[seg]]
    seg_owner = owner[seg]
    n = int(ids.max()) + 1 if len(ids) else 1
    key = np.minimum(a, b) * n + np.maximum(a, b)
    order = np.argsort(key, kind="stable")  # stable: the first occurrence leads its group
    first = np.ones(len(key), dtype=bool)
    first[1:] = key[order[1:]] != key[order[:-1]]
    new = np.zeros(len(key), dtype=bool)
    new[order[first]] = True
    per_item_new = np.bincount(seg_owner, weights=new, minlength=nitem).astype(np.int64)
    per_item_seg = np.bincount(seg_owner, minlength=nitem)
    seg_start = np.concatenate(([0], np.cumsum(per_item_seg)))
    out_rings, out_lines = [], []
    for k in np.flatnonzero(live & (per_item_new > 0)).tolist():
        xy = xy_all[k_start[k] : k_start[k + 1]]
        ring = bool(is_ring[k])
        if ring and per_item_new[k] == per_item_seg[k]:
            out_rings.append(xy)
            continue
        fresh = new[seg_start[k] : seg_start[k + 1]]
        m = len(fresh)
        pts = np.vstack((xy, xy[:1])) if ring else xy
        if ring:  # start the runs right after a segment that is dropped
            s0 = int(np.flatnonzero(~fresh)[0]) + 1
            walk = (np.arange(m) + s0) % m
        else:
            walk = np.arange(m)
        run: list[int] = []
        for j in walk.tolist():
            if fresh[j]:
                run.append(j)
                continue
            if run:
                out_lines.append(_run_points(pts, run, ring, m))
                run = []
        if run:
            out_lines.append(_run_points(pts, run, ring, m))
    return out_rings, out_lines


def _run_points(pts: np.ndarray, run: list, ring: bool, m: int) -> np.ndarray:
    idx = [*run, (run[-1] + 1) % (m if ring else m + 1)]
    if ring:
        idx = [i % m for i in idx]
        base = pts[:-1]
        return base[idx]
    return pts[idx]


# --- long strokes ---------------------------------------------------------------------------


def merge_lines(lines, *, tolerance=None) -> list:
    """Join line pieces into the fewest trails that draw every segment once.

    Segments are deduplicated (end points closer than ``tolerance`` are one vertex), then
    each connected network is split into trails at its odd-degree vertices: odd vertices are
    paired (nearest first) by virtual pen-up moves, an Euler circuit of the network plus
    those moves is walked (Hierholzer), and the circuit is cut at the virtual moves. A network
    with ``2k`` odd vertices gives ``k`` trails (one closed trail when ``k = 0``), the least
    any pen can do.

    Parameters
    ----------
    lines : sequence of (k, 2) array_like or shapely lines
        The pieces: point arrays, LineStrings, MultiLineStrings.
    tolerance : float, optional
        End points closer than this are one vertex (default ``config.PLOTTER_MERGE_RTOL`` of
        the drawing's size).

    Returns
    -------
    list of (k, 2) float64
        The trails; a closed trail repeats its first point at the end.
    """
    pieces = _as_point_lists(lines)
    if not pieces:
        return []
    segs = np.concatenate([np.stack((p[:-1], p[1:]), axis=1) for p in pieces if len(p) >= 2])
    coords = segs.reshape(-1, 2)
    ids, verts = _vertex_ids(coords, _tolerance(coords, tolerance, segs))
    e = ids.reshape(-1, 2)
    e = e[e[:, 0] != e[:, 1]]
    if not len(e):
        return []
    e = np.unique(np.sort(e, axis=1), axis=0)
    return [verts[t] for t in _trails(e, verts)]


def _as_point_lists(lines) -> list:
    if isinstance(lines, shapely.Geometry):
        lines = [lines]
    out = []
    for item in lines:
        if isinstance(item, shapely.Geometry):
            rings, open_ = _collect([item])
            out += [np.vstack((r, r[:1])) for r in rings] + open_
        else:
            arr = np.asarray(item, dtype=np.float64)
            if arr.ndim != 2 or arr.shape[1] != 2:
                raise ValueError(f"a line must be a (k, 2) array of points; got shape {arr.shape}")
            if not np.isfinite(arr).all():
                raise ValueError("line coordinates must be finite")
            if len(arr) >= 2:
                out.append(arr)
    return out


def _pair_odd(odd: np.ndarray, verts: np.ndarray) -> np.ndarray:
    """Pair odd-degree vertices, nearest pairs first (greedy matching on a k-NN graph)."""
    if not len(odd):
        return np.zeros((0, 2), dtype=np.int64)
    pts = verts[odd]
    k = min(len(odd), 9)
    nb = nearest(pts, k)
    gap = pts[nb] - pts[:, None, :]
    dist = gap[..., 0] * gap[..., 0] + gap[..., 1] * gap[..., 1]  # squared: same order
    a = np.repeat(np.arange(len(odd)), k - 1)
    b = nb[:, 1:].reshape(-1)
    d = dist[:, 1:].reshape(-1)
    order = np.lexsort((b, a, d))
    used = np.zeros(len(odd), dtype=bool)
    pairs = []
    for i in order.tolist():
        u, v = int(a[i]), int(b[i])
        if not used[u] and not used[v] and u != v:
            used[u] = used[v] = True
            pairs.append((u, v))
    rest = np.flatnonzero(~used)
    if len(rest):  # leftovers: pair along a sweep in x
        rest = rest[np.lexsort((pts[rest, 1], pts[rest, 0]))]
        pairs += list(zip(rest[0::2].tolist(), rest[1::2].tolist(), strict=True))
    return odd[np.asarray(pairs, dtype=np.int64).reshape(-1, 2)]


def _trails(edges: np.ndarray, verts: np.ndarray) -> list:
    """Vertex sequences of the trails covering ``edges`` (unique, undirected)."""
    nv = len(verts)
    deg = np.bincount(edges.reshape(-1), minlength=nv)
    odd = np.flatnonzero(deg % 2 == 1)
    virtual = _pair_odd(odd, verts)
    both = np.vstack((edges, virtual)) if len(virtual) else edges
    m = len(both)
    real = np.arange(m) < len(edges)
    # adjacency as CSR of (edge id) per vertex
    ends = np.concatenate((both[:, 0], both[:, 1]))
    eid = np.concatenate((np.arange(m), np.arange(m)))
    order = np.argsort(ends, kind="stable")
    adj = eid[order]
    indptr = np.concatenate(([0], np.cumsum(np.bincount(ends, minlength=nv))))
    circuits = _euler(both, adj, indptr, nv)
    trails = []
    for verts_seq, edge_seq in circuits:
        # rotate the circuit to begin after a virtual move, then cut at each virtual move
        vr = np.flatnonzero(~real[edge_seq])
        if not len(vr):
            trails.append(verts_seq)
            continue
        k = int(vr[0])
        n = len(edge_seq)
        vs = np.concatenate((verts_seq[k + 1 : -1], verts_seq[: k + 1], verts_seq[k + 1 : k + 2]))
        es = np.concatenate((edge_seq[k + 1 :], edge_seq[: k + 1]))
        assert len(es) == n
        cur = [int(vs[0])]
        for j in range(n):
            if real[es[j]]:
                cur.append(int(vs[j + 1]))
            else:
                if len(cur) >= 2:
                    trails.append(np.asarray(cur, dtype=np.int64))
                cur = [int(vs[j + 1])]
        if len(cur) >= 2:
            trails.append(np.asarray(cur, dtype=np.int64))
    return trails


def _euler(edges, adj, indptr, nv):
    """Euler circuits (Hierholzer) of every component of an all-even multigraph."""
    used = np.zeros(len(edges), dtype=bool)
    ptr = indptr[:-1].copy()
    out = []
    a, b = edges[:, 0].tolist(), edges[:, 1].tolist()
    adj_l, end_l = adj.tolist(), indptr[1:].tolist()
    ptr_l = ptr.tolist()
    used_l = used.tolist()
    for s in range(nv):
        if ptr_l[s] >= end_l[s]:
            continue
        # skip used edges at s
        while ptr_l[s] < end_l[s] and used_l[adj_l[ptr_l[s]]]:
            ptr_l[s] += 1
        if ptr_l[s] >= end_l[s]:
            continue
        stack_v, stack_e = [s], [-1]
        path_v, path_e = [], []
        while stack_v:
            v = stack_v[-1]
            p = ptr_l[v]
            while p < end_l[v] and used_l[adj_l[p]]:
                p += 1
            ptr_l[v] = p
            if p == end_l[v]:
                path_v.append(stack_v.pop())
                path_e.append(stack_e.pop())
            else:
                e = adj_l[p]
                used_l[e] = True
                w = b[e] if a[e] == v else a[e]
                stack_v.append(w)
                stack_e.append(e)
        # path_v is the circuit reversed; path_e[i] is the edge into path_v[i] (last is -1)
        vs = np.asarray(path_v[::-1], dtype=np.int64)
        es = np.asarray(path_e[::-1][1:], dtype=np.int64)
        out.append((vs, es))
    return out


# --- short pen-up travel --------------------------------------------------------------------


def travel(paths, *, start=None) -> tuple[float, float]:
    """Pen-up and pen-down length of drawing ``paths`` in the given order and direction.

    Parameters
    ----------
    paths : sequence of (k, 2) array_like
        Each drawn from its first point to its last.
    start : (float, float), optional
        Where the pen starts (default: the first path's start, so no first move counts).

    Returns
    -------
    up, down : float
        Pen-up travel between paths (from ``start`` to the first) and drawn length.
    """
    pts = [np.asarray(p, dtype=np.float64).reshape(-1, 2) for p in paths]
    pts = [p for p in pts if len(p)]
    if not pts:
        return 0.0, 0.0
    down = float(sum(np.hypot(*np.diff(p, axis=0).T).sum() for p in pts))
    heads = np.array([p[0] for p in pts])
    tails = np.array([p[-1] for p in pts])
    up = float(np.hypot(*(heads[1:] - tails[:-1]).T).sum())
    if start is not None:
        up += float(np.hypot(*(heads[0] - np.asarray(start, dtype=np.float64))))
    return up, down


def order_paths(
    paths,
    *,
    start=None,
    reverse: bool = True,
    closed=None,
    improve: bool = True,
    neighbours: int = config.PLOTTER_NEIGHBOURS,
    max_passes: int = config.PLOTTER_MAX_PASSES,
) -> tuple[np.ndarray, np.ndarray]:
    """Order paths to make the pen-up travel between them short.

    A greedy nearest-neighbour tour from ``start`` (each path entered at its nearer end when
    ``reverse``), then 2-opt: a move reverses a run of consecutive paths (and each path's
    direction), kept when it shortens the travel; candidates are the ``neighbours`` nearest
    path ends of each end; passes repeat until none improves (at most ``max_passes``).

    Parameters
    ----------
    paths : sequence of (k, 2) array_like
        The paths (each at least one point).
    start : (float, float), optional
        The pen's home (default: the first path's first point).
    reverse : bool
        Allow drawing a path backwards.
    closed : (n,) bool, optional
        Closed rings (start = end; never reversed, as it would change nothing).
    improve : bool
        Run 2-opt after the greedy tour.
    neighbours : int
        Candidate list size of 2-opt.
    max_passes : int
        Most 2-opt passes.

    Returns
    -------
    order : (n,) int64
        Path indices in drawing order.
    flipped : (n,) bool
        Per position of ``order``: draw that path from its last point to its first.

    Raises
    ------
    ValueError
        For an empty path, non-finite coordinates or a bad option.
    """
    pts = [np.asarray(p, dtype=np.float64).reshape(-1, 2) for p in paths]
    n = len(pts)
    if any(len(p) == 0 for p in pts):
        raise ValueError("every path needs at least one point")
    if int(neighbours) < 1 or int(max_passes) < 0:
        raise ValueError("neighbours must be >= 1 and max_passes >= 0")
    if n == 0:
        return np.zeros(0, dtype=np.int64), np.zeros(0, dtype=bool)
    ports = np.zeros((2 * n, 2), dtype=np.float64)
    ports[0::2] = [p[0] for p in pts]
    ports[1::2] = [p[-1] for p in pts]
    if not np.isfinite(ports).all():
        raise ValueError("path coordinates must be finite")
    home = ports[0] if start is None else np.asarray(start, dtype=np.float64).reshape(2)
    if not np.isfinite(home).all():
        raise ValueError(f"start must be a finite point; got {start!r}")
    can_flip = np.full(n, bool(reverse))
    if closed is not None:
        can_flip &= ~np.asarray(closed, dtype=bool).reshape(n)
    tour, flip = nearest_tour(ports, can_flip, home)
    if improve and n > 1:
        k = min(int(neighbours) + 1, 2 * n)
        nb = np.ascontiguousarray(nearest(ports, k))
        span = float(np.ptp(ports, axis=0).max()) + float(np.abs(ports).max())
        eps = span * 1e-12
        two_opt(
            ports, tour, flip, can_flip, nb, home, eps, int(max_passes), config.PLOTTER_OR_WINDOW
        )
    return tour.astype(np.int64), flip.astype(bool)


def layer_paths(
    geoms,
    *,
    order: str = "travel",
    merge: bool = True,
    dedupe: bool = True,
    tolerance=None,
    start=None,
) -> Paths:
    """The paths a machine follows for one layer: each segment once, merged, ordered.

    Parameters
    ----------
    geoms : sequence of shapely geometries
        Everything on the layer: polygons (every ring is a closed path), lines, rings.
        Points are not paths and are ignored.
    order : {"travel", "file"}
        ``"travel"``: short pen-up travel (:func:`order_paths`); ``"file"``: closed rings first,
        then lines, in the order given.
    merge : bool
        Join open pieces into the fewest trails (:func:`merge_lines`).
    dedupe : bool
        Draw every segment once (repeated rings dropped, shared segments cut out).
    tolerance : float, optional
        Vertices closer than this are one (default ``config.PLOTTER_MERGE_RTOL`` of the size).
    start : (float, float), optional
        The pen's home for ``order="travel"`` (default: the top-left corner of the layer).

    Returns
    -------
    Paths
    """
    if order not in ORDERS:
        raise ValueError(f"order must be one of {', '.join(ORDERS)}; got {order!r}")
    rings, lines = _collect(geoms)
    everything = rings + lines
    if not everything:
        return Paths([], np.zeros(0, dtype=bool))
    coords = np.concatenate(everything)
    tol = _tolerance(coords, tolerance, [np.vstack((r, r[:1])) for r in rings] + lines)
    tiny = sum(1 for r in rings if float(np.ptp(r, axis=0).max()) <= tol)
    if tiny:  # they collapse to a point: say so rather than drop them silently
        warnings.warn(
            f"{tiny} closed paths are no bigger than the vertex merge tolerance {tol:.3g} "
            "and are left out (pass a smaller tolerance, or scale the drawing)",
            stacklevel=2,
        )
    if dedupe:
        rings, lines = _dedupe(rings, lines, tol)
    if merge and lines:
        lines = merge_lines(lines, tolerance=tol)
    paths = rings + lines
    closed = np.array([True] * len(rings) + [False] * len(lines), dtype=bool)
    if order == "file" or len(paths) < 2:
        return Paths(paths, closed)
    if start is None:
        start = (float(coords[:, 0].min()), float(coords[:, 1].max()))
    drawn = [np.vstack((p, p[:1])) if c else p for p, c in zip(paths, closed, strict=True)]
    tour, flip = order_paths(drawn, start=start, closed=closed)
    out = [
        paths[i][::-1] if f else paths[i] for i, f in zip(tour.tolist(), flip.tolist(), strict=True)
    ]
    return Paths(out, closed[tour])


def network_lines(segments, outline=None, *, order: str = "travel") -> list:
    """An edge network (and an outline) as the fewest strokes, ordered, each segment once.

    Parameters
    ----------
    segments : (m, 2, 2) array_like
        Edge end points (``diagram.edges.coords``).
    outline : shapely geometry, optional
        A polygon whose rings are drawn with the network (the diagram's boundary).
    order : {"travel", "file"}
        As in :func:`layer_paths`.

    Returns
    -------
    list of shapely.LineString
        Closed trails repeat their first point.
    """
    arr = np.asarray(segments, dtype=np.float64).reshape(-1, 2, 2)
    geoms = [shapely.MultiLineString(list(arr))] if len(arr) else []
    if outline is not None and not outline.is_empty:
        geoms.append(shapely.boundary(outline))
    drawn = layer_paths(geoms, order=order)
    return [shapely.LineString(p) for p in _as_drawn(drawn)]
