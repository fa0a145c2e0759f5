"""A frame for periodic diagrams whose images are not float64 numbers in the user's frame.

Where the box straddles a power of two (its lower corner at ``2**42 - 1.5``, a few units
wide), the float spacing doubles across the box: a site below ``2**42`` shifted by the
box's size lands where its image is not a float, so the copies are not exact shifts of
their sites and the cells of a site and of its image disagree by an ulp (areas off by
1e-4 of the box, Euler failing, sites of a box a few ulps wide lost).

Such a diagram is computed in a frame where every copy is exact: the box's lower corner is
moved to ``2**j + 2 size`` on each axis, ``2**j >= 8 size``, so the grown box lies in one
binade. ``site - corner`` is exact (Sterbenz: a far box's sites are within a factor two of
its corner) and so is adding the new corner: both are checked on every site by the
two-sum residual (:func:`corner_frame`), else the frame is not used; nor is it near zero,
where the user's floats are the finer ones. The cells are moved
back at the end, one rounding per coordinate (:func:`to_user_frame`); the unwrapped cells
of a site and of its image by a box shift are rounded alike wherever the two can be floats
(:func:`_consistent`).
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np


def two_sum_error(a: np.ndarray, b) -> np.ndarray:
    """The rounding error of ``a + b`` (Knuth's two-sum): zero where the sum is exact."""
    s = a + b
    bv = s - a
    av = s - bv
    return (a - av) + (b - bv)


def corner_frame(pts: np.ndarray, box):
    """The frame's corner ``(2,)`` where every site and copy of ``pts`` is exact, or None.

    Parameters
    ----------
    pts : (n, 2) float64
        Sites in the box (wrapped).
    box : (xmin, ymin, xmax, ymax)

    Returns
    -------
    (2,) float64 or None
        ``corner``: the sites are ``pts - box[:2] + corner`` there, exactly, and so are
        their shifts by up to two box sizes on each axis.
    """
    x0, y0, x1, y1 = box
    lo = np.array([x0, y0])
    size = np.array([x1 - x0, y1 - y0])
    if not (size > 0).all() or not np.isfinite(size).all():
        return None
    if size.min() <= 2.0**-400 or max(abs(v) for v in box) >= 2.0**400:
        # squares of the cells' coordinates under- or overflow there (GEOS, the spike
        # test): a wrapped diagram is rescaled first (periodic._rescaled), then moved
        return None
    if Fraction(x1) - Fraction(x0) != size[0] or Fraction(y1) - Fraction(y0) != size[1]:
        return None
    _, e = np.frexp(size)  # size < 2**e
    # the frame's floats are no coarser than the user's anywhere copies go (2 sizes around
    # the box, past the margins' cap): near zero the user's frame is the finer one
    near = np.minimum(np.abs(lo - 2.0 * size), np.abs(lo + 3.0 * size))
    across = np.sign(lo - 2.0 * size) != np.sign(lo + 3.0 * size)
    if across.any() or (near < np.ldexp(1.0, e + 4)).any():
        return None
    corner = np.ldexp(1.0, e + 3) + 2.0 * size
    if two_sum_error(np.ldexp(1.0, e + 3), 2.0 * size).any():
        return None
    if two_sum_error(pts, -lo).any():
        return None
    rel = pts - lo
    local = rel + corner
    if two_sum_error(rel, corner).any() or two_sum_error(corner, size).any():
        return None
    for a in (-2.0, -1.0, 1.0, 2.0):
        if two_sum_error(local, a * size).any():
            return None
    return corner


def to_local(pts: np.ndarray, box, corner: np.ndarray):
    """The sites and the box in the frame of ``corner`` (exact: see :func:`corner_frame`)."""
    x0, y0, x1, y1 = box
    lo = np.array([x0, y0])
    size = np.array([x1 - x0, y1 - y0])
    local = (pts - lo) + corner
    hi = corner + size
    return local, (corner[0], corner[1], hi[0], hi[1])


def to_user_frame(xy: np.ndarray, box, corner: np.ndarray, consistent: bool, plain=None, flip=None):
    """Points ``(m, 2)`` of the frame of ``corner`` moved back into the user's frame.

    ``xy - corner`` is exact (the frame's grown box lies in one binade with its corner);
    adding the box's corner rounds once. With ``consistent``, the copies of one point by box
    shifts are rounded alike (:func:`_consistent`), except the classes of the points
    ``plain`` (a mask), which keep the nearest float.
    """
    x0, y0, x1, y1 = box
    lo = np.array([x0, y0])
    size = np.array([x1 - x0, y1 - y0])
    rel = xy - corner
    out = rel + lo
    if consistent and len(xy):
        for k in range(2):
            out[:, k] = _consistent(rel[:, k], out[:, k], lo[k], size[k], plain, flip)
    return out


def cells_to_user_frame(coords, offsets, extra, box, corner, consistent: bool):
    """The cells' buffers and the points ``extra`` moved back (:func:`to_user_frame`).

    ``offsets = (ring, poly, geom)``. Rounding the copies of a vertex alike can put two
    vertices a fraction of an ulp apart in the wrong order (their classes are rounded on
    floats an odd number of ulps apart): the classes of the vertices of a cell that is then
    invalid take the other float beside their farthest copy's value, still shifted alike
    (a box 255 x 257 ulps across 2**45: valid cells that tile exactly), and where a cell
    stays invalid, the nearest floats, until every cell is valid (a few rounds).

    Returns
    -------
    bufs : (coords, ring, poly, geom)
        Without the points rounding made redundant (:func:`drop_repeats`); a ring that
        rounding pinched (a vertex twice) is split there (:func:`split_pinched`).
    extra : (k, 2) float64
    apart : (m,) int64
        With ``consistent``, the cells holding a vertex whose copies (the points of the
        cells equal modulo the box in the frame) are not exact shifts of each other once
        moved back (:func:`mismatched`): two copies in the coarser binade a box size apart,
        the size not a multiple of their ulp, cannot both be floats, and a class given the
        nearest floats (above) is not shifted alike. Without ``consistent``: the cells
        that fold once rounded (:func:`_merge_folds`).
    """
    import shapely

    ring, poly, geom = offsets
    xy = np.concatenate((coords, extra))
    plain = np.zeros(len(xy), dtype=bool)
    flip = np.zeros(len(xy), dtype=bool)
    for _ in range(6):
        out = to_user_frame(xy, box, corner, consistent, plain, flip)
        bufs = drop_repeats((np.ascontiguousarray(out[: len(coords)]), ring, poly, geom))
        if not consistent:
            out, bufs, folded = _merge_folds(xy, out, len(coords), offsets, bufs)
            break
        cells = shapely.from_ragged_array(
            shapely.GeometryType.MULTIPOLYGON, bufs[0], tuple(bufs[1:])
        )
        bad = np.flatnonzero(~shapely.is_valid(cells))
        if not len(bad):
            break
        lo = ring[poly[geom[bad]]]
        hi = ring[poly[geom[bad + 1]]]
        mark = np.zeros(len(xy) + 1, dtype=np.int64)
        np.add.at(mark, lo, 1)
        np.add.at(mark, hi, -1)
        more = np.cumsum(mark)[:-1] > 0
        if not (more & ~plain).any():
            break
        plain |= more & flip
        flip |= more
    bufs = split_pinched(bufs)
    apart = np.zeros(0, dtype=np.int64) if consistent else folded
    if consistent and len(coords):
        off = mismatched(coords - corner, out[: len(coords)], box)
        if off.any():
            rid = np.repeat(np.arange(len(ring) - 1), np.diff(ring))
            pid = np.repeat(np.arange(len(poly) - 1), np.diff(poly))
            gid = np.repeat(np.arange(len(geom) - 1), np.diff(geom))
            apart = np.unique(gid[pid[rid[off]]]).astype(np.int64)
    return bufs, out[len(coords) :], apart


def _merge_folds(xy, out, m: int, offsets, bufs):
    """Rounded points ``out`` and buffers where no cell folds on two vertices an ulp apart.

    Two vertices of a cell closer than the user's floats can order them (a tiny edge, a
    fraction of an ulp long) round to neighbouring floats in the wrong order, and the ring
    crosses itself there (500 sites on a sloped line in a 3 x 2 box at 4e12, wrapped: a
    vertex pair 0.05 x 0.13 ulps apart rounded to (4159, 1392), (4159, 1391) ulps, a
    bow-tie). In an invalid cell, a ring's next point within an ulp of a point on each axis
    takes that point's value: every copy of it (the points equal in the frame: the
    neighbours' and the edges' copies too, so the cells still meet), a few rounds; the tiny
    edge rounds away (:func:`drop_repeats`). ``m``: the points of ``xy`` that are the cells'.

    A cell narrower than an ulp whose long sides cross once rounded (two nearly parallel
    edges a fraction of an ulp apart) stays invalid: it keeps the part its ring winds round
    the right way (GEOS's ``buffer(0)``; the crossed tip, a fraction of an ulp squared, is
    left to its neighbours) and is returned in ``folded``, its site then unresolved.

    Returns
    -------
    out : (k, 2) float64
    bufs : (coords, ring, poly, geom)
    folded : (f,) int64
    """
    import shapely

    ring, poly, geom = offsets
    cls = None
    if not m:
        return out, bufs, np.zeros(0, dtype=np.int64)
    for _ in range(4):
        bad = _invalid(bufs)
        if not len(bad):
            return out, bufs, bad
        # the points of the bad cells' rings, each with the next one along its ring
        rings = np.concatenate([np.arange(poly[geom[g]], poly[geom[g + 1]]) for g in bad])
        length = ring[rings + 1] - ring[rings] - 1  # without the closing point
        at = np.repeat(ring[rings] - np.cumsum(length) + length, length) + np.arange(
            int(length.sum())
        )
        nxt = at + 1
        a, b = out[at], out[nxt]
        near = (np.abs(b - a) <= np.spacing(np.maximum(np.abs(a), np.abs(b)))).all(axis=1)
        near &= (a != b).any(axis=1)
        if not near.any():
            break
        if cls is None:
            _, cls = np.unique(xy, axis=0, return_inverse=True)
            cls = cls.ravel()
        value = np.full((int(cls.max()) + 1, 2), np.nan)
        value[cls[nxt[near]]] = a[near]
        take = ~np.isnan(value[cls, 0])
        out = np.where(take[:, None], value[cls], out)
        bufs = drop_repeats((np.ascontiguousarray(out[:m]), ring, poly, geom))
    bad = _invalid(bufs)
    if len(bad):
        cells = shapely.from_ragged_array(
            shapely.GeometryType.MULTIPOLYGON, bufs[0], tuple(bufs[1:])
        )
        for g in bad:
            cells[g] = _wound(cells[g])
        _, c, offs = shapely.to_ragged_array(cells)
        bufs = (np.ascontiguousarray(c), *offs)
    return out, bufs, bad.astype(np.int64)


def _wound(cell):
    """The parts of a self-crossing ``cell`` that its rings wind round the way they turn.

    GEOS's ``make_valid`` splits the rings where they cross into parts; a part is kept
    where the winding number of its rings about a point inside it has the sign of their
    signed area (the cell's own side), not where a crossed loop turns back.
    """
    import shapely

    # about a point of the cell (exact differences: a cell is a few ulps across), where GEOS
    # places the crossings and a point inside a part without the far coordinates' rounding
    o = shapely.get_coordinates(cell)[0]
    local = shapely.transform(cell, lambda xy: xy - o)
    fixed = shapely.get_parts(shapely.make_valid(local))
    fixed = fixed[shapely.get_type_id(fixed) == 3]
    rings = [
        np.asarray(r.coords) for p in shapely.get_parts(local) for r in (p.exterior, *p.interiors)
    ]
    sign = np.sign(sum(_area(r[:-1]) for r in rings))
    keep = []
    for part in fixed:
        q = np.asarray(shapely.point_on_surface(part).coords)[0]
        turns = sum(_winding(r, q) for r in rings)
        if turns * sign > 0:
            keep.append(shapely.transform(part, lambda xy: xy + o))
    return shapely.MultiPolygon(keep)


def _winding(ring: np.ndarray, q: np.ndarray) -> int:
    """The winding number of the closed ring ``(k, 2)`` (last point = first) about ``q``."""
    a = ring[:-1] - q
    b = ring[1:] - q
    cross = a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]
    up = (a[:, 1] <= 0) & (b[:, 1] > 0) & (cross > 0)
    down = (a[:, 1] > 0) & (b[:, 1] <= 0) & (cross < 0)
    return int(up.sum() - down.sum())


def _invalid(bufs) -> np.ndarray:
    """The cells of the buffers ``(coords, ring, poly, geom)`` that are not valid polygons.

    Judged once their pinched rings are split (:func:`split_pinched`, done afterwards): a
    ring that touches itself is not a fold.
    """
    import shapely

    coords, ring, poly, geom = split_pinched(bufs)
    cells = shapely.from_ragged_array(shapely.GeometryType.MULTIPOLYGON, coords, (ring, poly, geom))
    return np.flatnonzero(~shapely.is_valid(cells))


def periods(rel: np.ndarray, w: float):
    """``(a, c, exact)`` on one axis: ``rel = a w + c`` with ``a`` whole, ``0 <= c < w``.

    ``exact`` (per point): ``a w`` and ``rel - a w`` are floats without rounding, so ``c``
    is the exact offset of the point in its copy of the box.
    """
    a = np.floor(rel / w)
    c = rel - a * w
    a = np.where(c >= w, a + 1, a)
    a = np.where(c < 0, a - 1, a)
    c = rel - a * w
    exact = (whole_times(a, w) & (two_sum_error(rel, -(a * w)) == 0)) & (c >= 0) & (c < w)
    return a, c, exact


def whole_times(a: np.ndarray, w: float) -> np.ndarray:
    """Whether ``a * w`` is a float without rounding, for the whole numbers ``a``."""
    if not len(a):
        return np.ones(0, dtype=bool)
    if a.max() - a.min() > 64:
        keys, inv = np.unique(a, return_inverse=True)
        ok = np.array([Fraction(t * w) == int(t) * Fraction(w) for t in keys], dtype=bool)
        return ok[inv.ravel()]
    first = int(a.min())  # a few periods either way: one check per whole number between
    ok = [Fraction(t * w) == t * Fraction(w) for t in range(first, int(a.max()) + 1)]
    return np.array(ok, dtype=bool)[(a - first).astype(np.int64)]


def mismatched(rel: np.ndarray, out: np.ndarray, box) -> np.ndarray:
    """The points ``(m,)`` of vertex classes whose copies in ``out`` are not exact shifts.

    ``rel (m, 2)`` are the points' exact offsets from the box's corner in a frame where
    copies are exact shifts (two points are copies of one vertex when their offsets differ
    by whole box sizes on both axes); ``out (m, 2)`` the points in the user's frame. A class
    is mismatched when two of its copies differ by anything but their shift, exactly: a gap
    or an overlap of the unwrapped cells there. Decided exactly (rationals where the float
    decomposition is not exact).
    """
    x0, y0, x1, y1 = box
    size = (x1 - x0, y1 - y0)
    m = len(rel)
    a = np.zeros((m, 2))
    c = np.zeros((m, 2))
    exact = np.ones(m, dtype=bool)
    for k in range(2):
        a[:, k], c[:, k], ok = periods(rel[:, k], size[k])
        exact &= ok
    keys = np.column_stack((c, np.zeros((m, 2))))
    for j in np.flatnonzero(~exact):
        # offsets in rationals: the class's key as an exact pair of floats (c = hi + lo)
        for k in range(2):
            r = Fraction(float(rel[j, k]))
            w = Fraction(size[k])
            t = r // w
            rest = r - t * w
            hi = float(rest)
            a[j, k] = float(t)
            keys[j, k], keys[j, 2 + k] = hi, float(rest - Fraction(hi))
    _, first, cls = np.unique(keys, axis=0, return_index=True, return_inverse=True)
    cls = cls.ravel()
    ref = first[cls]  # each class's first member
    bad = np.zeros(m, dtype=bool)
    for k in range(2):
        t = a[:, k] - a[ref, k]
        shift = t * size[k]
        base = out[ref, k]
        sure = exact & exact[ref] & whole_times(t, size[k])
        bad |= sure & ((two_sum_error(base, shift) != 0) | (base + shift != out[:, k]))
        for j in np.flatnonzero(~sure):
            diff = Fraction(float(out[j, k])) - Fraction(float(base[j]))
            bad[j] |= diff != int(t[j]) * Fraction(size[k])
    worse = np.zeros(len(first), dtype=bool)
    worse[cls[bad]] = True
    return worse[cls]


def _consistent(rel: np.ndarray, plain: np.ndarray, lo: float, w: float, keep=None, flip=None):
    """Coordinates on one axis whose copies by box shifts are exact shifts of each other.

    ``rel`` are the exact offsets from the box's corner, ``plain`` their rounded sums with
    it. The offsets that differ by whole periods (one class) are rounded once, at the copy
    farthest from zero (the coarsest float spacing), and the others are that value shifted
    by the periods between them, where every such shift is a float; other classes, and
    those of the points ``keep`` (a mask), keep ``plain``. The classes of the points
    ``flip`` (a mask) take the other float beside the farthest copy's exact value (rounded
    the other way), still shifted alike.
    """
    a = np.floor(rel / w)
    c = rel - a * w
    a = np.where(c >= w, a + 1, a)
    a = np.where(c < 0, a - 1, a)
    c = rel - a * w
    ok = (two_sum_error(rel, -(a * w)) == 0) & (c >= 0) & (c < w)
    if not ok.all():
        return plain
    keys, cls = np.unique(c, return_inverse=True)
    far = np.full(len(keys), -np.inf) if lo >= 0 else np.full(len(keys), np.inf)
    if lo >= 0:
        np.maximum.at(far, cls, a)
    else:
        np.minimum.at(far, cls, a)
    # the plain value of the farthest copy of each class
    at_far = a == far[cls]
    base = np.zeros(len(keys))
    base[cls[at_far]] = plain[at_far]
    if flip is not None and flip.any():
        turn = np.zeros(len(keys), dtype=bool)
        turn[cls[flip]] = True
        err = np.zeros(len(keys))
        err[cls[at_far]] = two_sum_error(rel[at_far], lo)  # exact value - base
        side = np.where(err > 0, np.inf, -np.inf)
        base = np.where(turn & (err != 0), np.nextafter(base, side), base)
    k = (a - far[cls]) * w
    out = base[cls] + k
    bad = two_sum_error(base[cls], k) != 0
    if keep is not None:
        bad |= keep
    if bad.any():
        worse = np.zeros(len(keys), dtype=bool)
        worse[cls[bad]] = True
        out = np.where(worse[cls], plain, out)
    return out


def drop_repeats(bufs):
    """Buffers without the points rounding made redundant in a ring.

    Moving the cells back rounds vertices that were apart onto one point (a repeated point)
    or onto a line through their neighbours, the ring turning back on itself there (a spike:
    the middle point of three on a line, outside the segment of the other two). Both are
    dropped until none is left. A ring left with fewer than four points (a cell narrower
    than the user's float spacing) is dropped, and with it its polygon when it was the
    exterior.
    """
    for _ in range(64):
        coords, ring, poly, geom = bufs
        if not len(coords):
            return bufs
        rid = np.repeat(np.arange(len(ring) - 1), np.diff(ring))
        drop = _redundant(coords, ring, rid)
        if not drop.any():
            return bufs
        bufs = _without(bufs, rid, ~drop)
    return bufs


def split_pinched(bufs):
    """Buffers where each exterior ring that passes a point twice is split into its loops.

    Rounding can bring two vertices of a cell's narrow neck onto one float point: the ring
    touches itself there (invalid). Its loops that turn the ring's way become polygons of
    the cell, touching at that point (the cell's holes go with the largest); a loop that
    turns the other way, or has no area, is rounding noise and is dropped. (A wrapped cell
    at 4e12 in a box 12 ulps tall, united from two pieces of a strip, came back pinched.)
    """
    coords, ring, poly, geom = bufs
    if len(ring) < 2:
        return bufs
    rid = np.repeat(np.arange(len(ring) - 1), np.diff(ring))
    body = np.ones(len(coords), dtype=bool)
    body[ring[1:] - 1] = False  # the closing points
    at = np.flatnonzero(body)
    order = np.lexsort((coords[at, 1], coords[at, 0], rid[at]))
    a = at[order]
    twice = (rid[a[1:]] == rid[a[:-1]]) & (coords[a[1:]] == coords[a[:-1]]).all(axis=1)
    pinched = np.unique(rid[a[1:]][twice])
    exterior = np.zeros(len(ring) - 1, dtype=bool)
    exterior[poly[:-1]] = True
    pinched = pinched[exterior[pinched]]
    if not len(pinched):
        return bufs
    import shapely

    cells = shapely.from_ragged_array(shapely.GeometryType.MULTIPOLYGON, coords, (ring, poly, geom))
    pid = np.repeat(np.arange(len(poly) - 1), np.diff(poly))
    gid = np.repeat(np.arange(len(geom) - 1), np.diff(geom))
    for g in np.unique(gid[pid[pinched]]):
        parts = []
        for p in range(geom[g], geom[g + 1]):
            rings = [coords[ring[r] : ring[r + 1]] for r in range(poly[p], poly[p + 1])]
            loops = _loops(rings[0][:-1])
            sign = np.sign(_area(rings[0][:-1]))
            loops = [q for q in loops if len(q) >= 3 and np.sign(_area(q)) == sign]
            if not loops:
                continue
            big = max(range(len(loops)), key=lambda j: abs(_area(loops[j])))
            for j, q in enumerate(loops):
                parts.append(shapely.Polygon(q, rings[1:] if j == big else None))
        cells[g] = shapely.MultiPolygon(parts)
    _, c, offsets = shapely.to_ragged_array(cells)
    return (np.ascontiguousarray(c), *offsets)


def _loops(pts: np.ndarray) -> list:
    """The simple loops of a closed walk ``pts`` (first point not repeated at its end)."""
    out = []
    stack: list = []
    seen: dict = {}
    for p in map(tuple, pts.tolist()):
        if p in seen:
            k = seen[p]
            loop = stack[k:]
            for q in loop[1:]:
                del seen[q]
            del stack[k + 1 :]
            out.append(np.array(loop))
        else:
            seen[p] = len(stack)
            stack.append(p)
    out.append(np.array(stack))
    return out


def _area(pts: np.ndarray) -> float:
    """Twice the signed area of the closed walk ``pts``, about its first point."""
    v = pts - pts[0]
    return float((v[:-1, 0] * v[1:, 1] - v[:-1, 1] * v[1:, 0]).sum()) if len(v) > 2 else 0.0


def _redundant(coords: np.ndarray, ring: np.ndarray, rid: np.ndarray) -> np.ndarray:
    """The points of the rings that repeat their predecessor or are the tip of a spike."""
    drop = np.zeros(len(coords), dtype=bool)
    drop[1:] = (coords[1:] == coords[:-1]).all(axis=1) & (rid[1:] == rid[:-1])
    if drop.any():
        return drop
    # closed rings: the neighbours of point k (not the closing point) along its ring
    start = ring[:-1][rid]
    end = ring[1:][rid] - 1  # the closing point repeats the first
    k = np.arange(len(coords))
    prev = np.where(k == start, end - 1, k - 1)
    nxt = k + 1
    inner = k < end
    a = coords[prev]
    b = coords
    c = coords[np.minimum(nxt, len(coords) - 1)]
    u = b - a
    v = c - b
    back = inner & ((u * v).sum(axis=1) < 0)
    cross = u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]
    scale = np.abs(u).sum(axis=1) * np.abs(v).sum(axis=1)
    for j in np.flatnonzero(back & (np.abs(cross) <= 1e-9 * scale)):
        ax, ay, bx, by, cx, cy = (Fraction(float(t)) for t in (*a[j], *b[j], *c[j]))
        if (bx - ax) * (cy - by) == (by - ay) * (cx - bx):
            drop[j] = True
            if k[j] == start[j]:
                drop[end[j]] = True  # the closing point is the same point
                break  # one spike at a ring's start per pass: its closing point moves
    return drop


def _without(bufs, rid: np.ndarray, keep: np.ndarray):
    """Buffers with only the points ``keep``; rings under four points are dropped."""
    coords, ring, poly, geom = bufs
    coords = coords.copy()
    # a ring whose first point goes: its next kept point starts it and closes it
    first = ring[:-1]
    lost = ~keep[first] & (np.diff(ring) > 0)
    for r in np.flatnonzero(lost):
        alive = np.flatnonzero(keep[ring[r] : ring[r + 1] - 1])
        if len(alive):
            coords[ring[r + 1] - 1] = coords[ring[r] + alive[0]]
            keep[ring[r + 1] - 1] = True
    count = np.bincount(rid[keep], minlength=len(ring) - 1)
    live_ring = count >= 4
    pid = np.repeat(np.arange(len(poly) - 1), np.diff(poly))
    live_poly = live_ring[poly[:-1]] if len(poly) > 1 else np.zeros(0, dtype=bool)
    live_ring &= live_poly[pid]
    keep &= live_ring[rid]
    new_ring = np.zeros(int(live_ring.sum()) + 1, dtype=np.int64)
    np.cumsum(count[live_ring], out=new_ring[1:])
    rings_per_poly = np.bincount(pid[live_ring], minlength=len(poly) - 1)
    new_poly = np.zeros(int(live_poly.sum()) + 1, dtype=np.int64)
    np.cumsum(rings_per_poly[live_poly], out=new_poly[1:])
    gid = np.repeat(np.arange(len(geom) - 1), np.diff(geom))
    polys_per_geom = np.bincount(gid[live_poly], minlength=len(geom) - 1)
    new_geom = np.zeros(len(geom), dtype=np.int64)
    np.cumsum(polys_per_geom, out=new_geom[1:])
    return np.ascontiguousarray(coords[keep]), new_ring, new_poly, new_geom
