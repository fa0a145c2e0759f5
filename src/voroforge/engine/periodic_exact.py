"""Vertices of the periodic copies' diagram that rounded copies moved: made exact.

In a box whose copies are rounded sums (``0.2255... + 3`` is no float: the copy lies up to
half an ulp of 3 from the exact image), a vertex computed from copies is the circumcentre
of points that are not the torus's sites. Where two of its sites are close beside a long
bisector, that half ulp is amplified by the ratio of the bisector's reach to the sites'
gap: two sites 5e-9 apart on a sloped line and a third about 1 away in a 3 x 2 box at the
origin put the vertex computed from their copies shifted by a period 3e-8 off (1e8 times
the copies' rounding), while the originals' cells, computed from exact sites, had it right
to an ulp; :func:`.periodic_ties.tie_images` then made every copy of the vertex the box's
member, the wrong one (a sliver of 2.8e-8 of the box's area given to the wrong cell,
nothing listed in ``unresolved``).

:func:`exact_vertices` bounds, for each vertex of the diagram of the copies with a
rounded copy among its three cells, how far the copies' rounding can have moved it (first
order in the rounding, the circumcentre's sensitivity to its sites); where that exceeds
``PERIODIC_EXACT_ULPS`` ulps of the vertex, it is recomputed from the exact images
(the sites plus whole periods, in rationals) and rounded once. The rings and edges holding
it take that point; a ring that this makes invalid keeps its old points and its site is
listed in ``unresolved``.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import shapely

from ..config import PERIODIC_EXACT_SAFETY, PERIODIC_EXACT_ULPS
from .bitmix import splitmix64
from .diagram import Diagram, Edges, buffers, domain_of, frame_exponent
from .periodic_frame import two_sum_error


def copy_errors(sites: np.ndarray, source: np.ndarray, shift: np.ndarray, box) -> np.ndarray:
    """How far each copy lies from its exact image (``(N,)``, an upper bound; 0: exact).

    ``sites`` are the copies (:func:`.periodic._images`: ``site + (a w, b h)`` in floats,
    ``w``, ``h`` the box's rounded sizes), ``source`` and ``shift`` each copy's site and
    whole periods ``(a, b)``. The exact image is ``site + (a, b)`` periods, the periods
    ``x1 - x0``, ``y1 - y0`` in rationals.
    """
    x0, y0, x1, y1 = box
    size = (x1 - x0, y1 - y0)
    period = (Fraction(x1) - Fraction(x0), Fraction(y1) - Fraction(y0))
    orig = np.flatnonzero(~shift.any(axis=1))  # source-major: site i's original copy
    base = sites[orig[source]]
    err = np.zeros(len(sites))
    for k in range(2):
        t = shift[:, k].astype(np.float64) * size[k]
        # the product and the period rounded: one value per whole number of periods
        keys, inv = np.unique(shift[:, k], return_inverse=True)
        dt = np.array([abs(float(Fraction(float(a) * size[k]) - int(a) * period[k])) for a in keys])
        err += np.abs(two_sum_error(base[:, k], t)) + dt[inv.ravel()]
    return err


def exact_vertices(d: Diagram, source: np.ndarray, shift: np.ndarray, box):
    """``d`` with the vertices that rounded copies moved recomputed exactly.

    Parameters
    ----------
    d : Diagram
        The diagram of the copies (a rectangular domain).
    source, shift : (N,) int64, (N, 2) int64
        Each copy's site and whole periods.
    box : (xmin, ymin, xmax, ymax)

    Returns
    -------
    d : Diagram
        ``d`` itself where nothing moved, else a new diagram (edges resolved).
    unresolved : (m,) int64
        The sites of the cells around a vertex that stays where it was computed, because
        its exact point would make one of their rings invalid.
    """
    none = np.zeros(0, dtype=np.int64)
    ext = d.sites
    err = copy_errors(ext, source, shift, box)
    if not err.any():
        return d, none
    edges = d.edges
    seg, pairs = edges.coords, edges.pairs
    bad = err > 0
    sel = np.flatnonzero(bad[pairs[:, 0]] | bad[pairs[:, 1]])
    if not len(sel):
        return d, none
    grown = domain_of(d).bounds
    pts, cells, m = _vertex_cells(seg[sel], pairs[sel], grown)
    if not len(pts):
        return d, none
    a, b, c = ext[cells[:m, 0]], ext[cells[:m, 1]], ext[cells[:m, 2]]
    ea, eb, ec = err[cells[:m, 0]], err[cells[:m, 1]], err[cells[:m, 2]]
    ab, ac = b - a, c - a
    det = np.abs(ab[:, 0] * ac[:, 1] - ab[:, 1] * ac[:, 0])
    r = np.hypot(pts[:m, 0] - a[:, 0], pts[:m, 1] - a[:, 1])
    lab, lac = np.hypot(ab[:, 0], ab[:, 1]), np.hypot(ac[:, 0], ac[:, 1])
    bound = np.full(len(pts), np.inf)  # a side point: its exact crossing, always
    with np.errstate(divide="ignore", invalid="ignore"):
        bound[:m] = PERIODIC_EXACT_SAFETY * r * (lac * (ea + eb) + lab * (ea + ec)) / det
    ulp = np.spacing(np.abs(pts).max(axis=1))
    moved = np.flatnonzero(~(bound <= PERIODIC_EXACT_ULPS * ulp))
    if not len(moved):
        return d, none
    new = np.full((len(moved), 2), np.nan)
    vert = moved < m
    new[vert] = _centres(ext, source, shift, cells[moved[vert]], box)
    if not vert.all():
        new[~vert] = _crossings(
            ext, source, shift, cells[moved[~vert], :2], pts[moved[~vert]], box, grown
        )
    old = pts[moved]
    off = np.abs(new - old).max(axis=1) > PERIODIC_EXACT_ULPS * ulp[moved]
    change = np.flatnonzero(off & np.isfinite(new).all(axis=1))
    if not len(change):
        return d, none
    out, stay = _replaced(d, seg, pairs, sel, old[change], new[change], cells[moved[change]])
    return out, np.unique(source[stay[stay >= 0]]).astype(np.int64)


def _vertex_cells(seg: np.ndarray, pairs: np.ndarray, grown):
    """The edges' end points held by three cells, then those on a side held by two.

    ``grown``: the grown box, whose sides cut the cells. Returns ``(points (v, 2),
    cells (v, 3), m)``: the first ``m`` are vertices, the others side points (cell -1 third).
    """
    p = seg.reshape(-1, 2)
    bits = np.ascontiguousarray(p).view(np.int64)
    cell = np.repeat(pairs, 2, axis=0)  # both ends of an edge: its two cells
    rows = np.column_stack(
        (np.repeat(bits, 2, axis=0), np.column_stack((cell[:, 0], cell[:, 1])).reshape(-1))
    )
    order = np.lexsort((rows[:, 2], rows[:, 1], rows[:, 0]))
    rows = rows[order]
    rows = rows[np.r_[True, (rows[1:] != rows[:-1]).any(axis=1)]]
    step = (rows[1:, 0] != rows[:-1, 0]) | (rows[1:, 1] != rows[:-1, 1])
    start = np.flatnonzero(np.r_[True, step])
    count = np.diff(np.r_[start, len(rows)])
    three = start[count == 3]
    two = start[count == 2]
    at = rows[two, :2].copy().view(np.float64)
    gx0, gy0, gx1, gy1 = grown
    side = (at[:, 0] == gx0) | (at[:, 0] == gx1) | (at[:, 1] == gy0) | (at[:, 1] == gy1)
    two = two[side]
    cells = np.full((len(three) + len(two), 3), -1, dtype=np.int64)
    cells[: len(three)] = rows[three[:, None] + np.arange(3), 2]
    cells[len(three) :, :2] = rows[two[:, None] + np.arange(2), 2]
    pts = rows[np.concatenate((three, two)), :2].copy().view(np.float64)
    return pts, cells, len(three)


def _two_sum(a, b):
    s = a + b
    bv = s - a
    return s, (a - (s - bv)) + (b - bv)


def _split(a):
    t = 134217729.0 * a
    hi = t - (t - a)
    return hi, a - hi


def _two_prod(a, b):
    p = a * b
    ah, al = _split(a)
    bh, bl = _split(b)
    return p, ((ah * bh - p) + ah * bl + al * bh) + al * bl


def _add(x, y):
    s, e = _two_sum(x[0], y[0])
    e = e + (x[1] + y[1])
    return _two_sum(s, e)


def _mul(x, y):
    p, e = _two_prod(x[0], y[0])
    e = e + (x[0] * y[1] + x[1] * y[0])
    return _two_sum(p, e)


def _div(x, y):
    q = x[0] / y[0]
    r = _add(x, _neg(_mul((q, 0.0 * q), y)))
    q2 = r[0] / y[0]
    return _two_sum(q, q2)


def _neg(x):
    return -x[0], -x[1]


def _dd_images(ext, source, shift, cells, box):
    """The exact images of the copies ``cells`` ``(v, k)`` as double-doubles, per axis."""
    x0, y0, x1, y1 = box
    orig = np.flatnonzero(~shift.any(axis=1))
    site = ext[orig[source[cells]]]  # (v, k, 2)
    k = shift[cells].astype(np.float64)
    img = []
    for ax, (lo, hi) in enumerate(((x0, x1), (y0, y1))):
        w, dw = _two_sum(hi, -lo)
        # site + k (w + dw) per copy, as double-double
        kw = _two_prod(k[:, :, ax], w)
        kd = _two_prod(k[:, :, ax], dw)
        img.append(_add(_add((site[:, :, ax], 0.0 * site[:, :, ax]), kw), kd))
    return img


def _crossings(ext, source, shift, cells, pts, box, grown):
    """Where the exact bisectors of the copies ``cells`` ``(v, 2)`` cross the box's sides.

    ``pts`` are on the sides of the grown box ``grown`` (the side of x where a point's x is
    a side's, else of y); ``box`` gives the periods.
    """
    img = _dd_images(ext, source, shift, cells, box)
    ax = (img[0][0][:, 0], img[0][1][:, 0])
    ay = (img[1][0][:, 0], img[1][1][:, 0])
    bx = _add((img[0][0][:, 1], img[0][1][:, 1]), _neg(ax))
    by = _add((img[1][0][:, 1], img[1][1][:, 1]), _neg(ay))
    half = _add(_mul(bx, bx), _mul(by, by))
    half = (0.5 * half[0], 0.5 * half[1])
    out = pts.copy()
    on_x = (pts[:, 0] == grown[0]) | (pts[:, 0] == grown[2])
    zero = 0.0 * pts[:, 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        # on x = X: (X - ax) bx + (y - ay) by = |b - a|^2 / 2; on y = Y likewise
        dx = _add((pts[:, 0], zero), _neg(ax))
        y = _add(ay, _div(_add(half, _neg(_mul(dx, bx))), by))
        dy = _add((pts[:, 1], zero), _neg(ay))
        x = _add(ax, _div(_add(half, _neg(_mul(dy, by))), bx))
    out[:, 1] = np.where(on_x, y[0], pts[:, 1])
    out[:, 0] = np.where(on_x, pts[:, 0], x[0])
    return out


def _centres(ext, source, shift, cells, box):
    """The circumcentres ``(v, 2)`` of the exact images of the copies ``cells`` (v, 3).

    In double-double: each image is its site plus whole periods, the period ``x1 - x0``
    as an exact two-term sum; the differences to the first image are exact sums of a few
    double-doubles (two copies a period apart and ulps apart), so the centre is its
    image plus a quotient good to ~1e-30 relative, rounded once (nan where collinear).
    """
    img = _dd_images(ext, source, shift, cells, box)
    # differences to the first image
    bx = _add((img[0][0][:, 1], img[0][1][:, 1]), _neg((img[0][0][:, 0], img[0][1][:, 0])))
    by = _add((img[1][0][:, 1], img[1][1][:, 1]), _neg((img[1][0][:, 0], img[1][1][:, 0])))
    cx = _add((img[0][0][:, 2], img[0][1][:, 2]), _neg((img[0][0][:, 0], img[0][1][:, 0])))
    cy = _add((img[1][0][:, 2], img[1][1][:, 2]), _neg((img[1][0][:, 0], img[1][1][:, 0])))
    det = _add(_mul(bx, cy), _neg(_mul(by, cx)))
    det = (2.0 * det[0], 2.0 * det[1])
    b2 = _add(_mul(bx, bx), _mul(by, by))
    c2 = _add(_mul(cx, cx), _mul(cy, cy))
    with np.errstate(divide="ignore", invalid="ignore"):
        ux = _div(_add(_mul(cy, b2), _neg(_mul(by, c2))), det)
        uy = _div(_add(_mul(bx, c2), _neg(_mul(cx, b2))), det)
        vx = _add((img[0][0][:, 0], img[0][1][:, 0]), ux)
        vy = _add((img[1][0][:, 0], img[1][1][:, 0]), uy)
    out = np.column_stack((vx[0] + vx[1], vy[0] + vy[1]))
    out[det[0] == 0] = np.nan
    return out


def _matches(points, cell, old, cells, table=None):
    """Per point: the index of ``old`` it equals bit for bit, ``cell`` one of its ``cells``.

    ``-1`` where none (``old``: distinct points). ``table``: :func:`_table` of ``old`` and
    ``cells`` (made here where None).
    """
    out = np.full(len(points), -1, dtype=np.int64)
    if table is None:
        table = _table(old, cells)
    if table is None:  # pragma: no cover - a collision of the 64-bit mix
        return _matches_sorted(points, cell, old, cells)
    if not len(points) or not len(table[0]):
        return out
    hs, order, tx, ty, tc, seen = table
    bits = np.ascontiguousarray(points).view(np.int64)
    qh = _mix(bits[:, 0], bits[:, 1], cell)
    # only the keys the table may hold are searched (a random search per point was 0.21 s
    # of the pass on 1e4 sites on a slope-2 line)
    at = np.flatnonzero(seen[qh & np.uint64(len(seen) - 1)])
    qh = qh[at]
    pos = np.minimum(np.searchsorted(hs, qh), len(hs) - 1)
    row = order[pos]
    hit = (hs[pos] == qh) & (tx[row] == bits[at, 0]) & (ty[row] == bits[at, 1])
    hit &= tc[row] == cell[at]
    out[at[hit]] = row[hit] // 3
    return out


def _matches_sorted(points, cell, old, cells):
    """:func:`_matches` by numbering the bits present (no table)."""
    out = np.full(len(points), -1, dtype=np.int64)
    key = np.ascontiguousarray(old).view(np.int64)
    bits = np.ascontiguousarray(points).view(np.int64)
    near = np.flatnonzero(np.isin(bits[:, 0], key[:, 0]))
    if not len(near):
        return out
    # rows (x bits, y bits, cell) as one int64: the bits numbered among those present
    tx, ty, tc = np.repeat(key[:, 0], 3), np.repeat(key[:, 1], 3), cells.reshape(-1) + 1
    ux, ix = np.unique(np.concatenate((tx, bits[near, 0])), return_inverse=True)
    uy, iy = np.unique(np.concatenate((ty, bits[near, 1])), return_inverse=True)
    _, pair = np.unique(ix.ravel() * len(uy) + iy.ravel(), return_inverse=True)
    code = pair.ravel() * (int(cell.max(initial=0)) + 2)
    tk = code[: len(tx)] + tc
    qk = code[len(tx) :] + cell[near] + 1
    order = np.argsort(tk, kind="stable")
    pos = np.minimum(np.searchsorted(tk[order], qk), len(tk) - 1)
    hit = tk[order][pos] == qk
    out[near[hit]] = order[pos[hit]] // 3
    return out


def _table(old, cells):
    """Rows ``(x bits, y bits, cell)`` of the points ``old`` and each of their ``cells``.

    Keyed by a 64-bit mix of the three, sorted (a search per point, not a sort of the
    diagram's points with them: numbering the bits with ``np.unique`` cost 0.83 s of the
    exact pass on 1e4 sites on a slope-2 line). :func:`_matches` checks every field of a
    hit; None where two rows share a key (:func:`_matches_sorted` is used then).
    """
    key = np.ascontiguousarray(old).view(np.int64)
    tx = np.repeat(key[:, 0], 3)
    ty = np.repeat(key[:, 1], 3)
    tc = np.ascontiguousarray(cells, dtype=np.int64).reshape(-1)
    h = _mix(tx, ty, tc)
    order = np.argsort(h, kind="stable")
    hs = h[order]
    if (hs[1:] == hs[:-1]).any():  # pragma: no cover - a collision of the 64-bit mix
        return None
    # which keys' low bits occur: a point whose key's do not is in no row
    seen = np.zeros(1 << max(10, int(8 * len(h)).bit_length()), dtype=bool)
    seen[h & np.uint64(len(seen) - 1)] = True
    return hs, order, tx, ty, tc, seen


def _mix(x, y, c):
    """A 64-bit mix of three int64 arrays (:func:`.bitmix.splitmix64` of a weighted sum)."""
    with np.errstate(over="ignore"):
        h = x.view(np.uint64) * np.uint64(0x9E3779B97F4A7C15)
        h ^= y.view(np.uint64) * np.uint64(0xBF58476D1CE4E5B9) + np.uint64(0x94D049BB133111EB)
        h ^= np.ascontiguousarray(c, dtype=np.int64).view(np.uint64) * np.uint64(0xD6E8FEB86659FD93)
    return splitmix64(h)


def _replaced(d: Diagram, seg, pairs, sel, old, new, cells):
    """``d`` with the points ``old`` of the rings and edges of ``cells`` moved to ``new``.

    ``sel``: the edges that can hold them (those of a rounded copy).
    """
    coords, ring, poly, geom = buffers(d)
    rid = np.repeat(np.arange(len(ring) - 1), np.diff(ring))
    pid = np.repeat(np.arange(len(poly) - 1), np.diff(poly))
    gid = np.repeat(np.arange(len(geom) - 1), np.diff(geom))
    point_cell = gid[pid[rid]]
    table = _table(old, cells)
    which = _matches(coords, point_cell, old, cells, table)
    at = np.flatnonzero(which >= 0)
    out = coords.copy()
    out[at] = new[which[at]]
    changed = np.unique(point_cell[at])
    lost = _invalid(out, coords, (ring, poly, geom), changed)
    keep = np.ones(len(old), dtype=bool)
    if len(lost):
        back = np.isin(point_cell, lost)
        keep[np.unique(which[back & (which >= 0)])] = False
        # every ring holding a vertex that stays: old points back
        back = (which >= 0) & ~keep[np.maximum(which, 0)]
        out[back] = coords[back]
    stay = cells[~keep].ravel()
    if not keep.any():
        return d, stay
    seg_out = seg.copy()
    for end in range(2):  # (only the edges of a rounded copy hold such points)
        w = np.full(len(seg), -1, dtype=np.int64)
        w[sel] = _matches(seg[sel, end], pairs[sel, 0], old, cells, table)
        w2 = np.full(len(seg), -1, dtype=np.int64)
        w2[sel] = _matches(seg[sel, end], pairs[sel, 1], old, cells, table)
        ok = (w >= 0) & (w2 == w) & keep[np.maximum(w, 0)]
        seg_out[ok, end] = new[w[ok]]
    result = Diagram(
        d.sites,
        d.duplicate_of,
        domain_of(d),
        (out, ring, poly, geom),
        Edges(seg_out, pairs),
        d.algorithm,
        frame_exponent(d),
        d.unresolved,
    )
    return result, stay


def _invalid(new, old, offsets, cells):
    """The ``cells`` whose rings ``new`` are invalid or turned round where ``old`` were not."""
    if not len(cells):
        return cells
    ring, poly, geom = offsets
    lo, hi = ring[poly[geom[cells]]], ring[poly[geom[cells + 1]]]
    length = hi - lo
    idx = np.repeat(lo - np.cumsum(length) + length, length) + np.arange(int(length.sum()))
    ids = np.repeat(np.arange(len(cells)), length)
    before = shapely.linearrings(old[idx], indices=ids)
    after = shapely.linearrings(new[idx], indices=ids)
    ok = shapely.is_valid(shapely.polygons(after))
    if not ok.all():  # (the rings before only where one after is not valid)
        ok[~ok] = ~shapely.is_valid(shapely.polygons(before[~ok]))
    ok &= shapely.is_ccw(after) == shapely.is_ccw(before)
    return cells[~ok]
