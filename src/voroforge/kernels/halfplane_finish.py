"""The half-plane cell's float cut handed to its exact finishing (:mod:`.halfplane_settle`).

:func:`finish_cell` takes the float cell that :func:`.halfplane._cells` cut, marks its
sure edges, keeps the watched sites near it, adds those a box-side vertex needs
(:func:`watch_sides`), settles it, puts the box sides it has at the corners right
(:func:`close_corners`, exact signs), and emits it exactly (or as cut, when that fails).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import (
    HALFPLANE_MERGE_RTOL,
    HALFPLANE_REACH_RTOL,
    HALFPLANE_SLACK2,
    HALFPLANE_SNAP_PRE,
    HALFPLANE_SURE_FAR,
    HALFPLANE_SURE_RTOL,
    HALFPLANE_SURE_SIN2,
    NJIT,
)
from ..config import HALFPLANE_MERGE_WIDE_MAX as MERGE_WIDE_MAX
from .distance_exact import compare
from .halfplane_settle import BOTTOM, LEFT, RIGHT, TOP, emit_exact, emit_float, settle_ring
from .sidegap import may_have_parallel, restore_sides

#: (2 r)^2 / r^2 with a margin against rounding: a site farther than twice the cell's
#: radius from its site cannot cut it
REACH = 4.0 * (1.0 + HALFPLANE_REACH_RTOL)
#: The float cut's vertices are off by up to e = 2^-40 of the box's radius ``R`` about the
#: site (HALFPLANE_SLACK2 = (e / R)^2), so the true cell's radius is up to ``r + e``: the
#: reach tests take ``r^2 + PAD * (e / R)^2 R^2``, PAD * (e / R)^2 = (2 R e + e^2) / R^2
#: (absolute: a 1e-12 cluster in a 1e6 box has a float cell far smaller than the true one,
#: and the true cell's neighbours past twice its radius were never cut, checker5 F6)
PAD = 2.0 / HALFPLANE_SLACK2**0.5 + 1.0
#: the side snap's reach about a vertex on a box side, over the box's magnitude (|x| + |y|
#: of its farthest corner): four times HALFPLANE_SNAP_PRE, which bounds the snap's reach
#: (:func:`.halfplane_settle._side_snap`), as :func:`.halfplane_settle._crossing_at_end`'s
#: screen
SIDE_WATCH = 4.0 * HALFPLANE_SNAP_PRE
_U = 2.0**-53


@njit(**NJIT)
def far_pad(r2, cx, cy):
    """What a site on a vertex's circle to the settling's merge band adds to ``r^2``.

    The cell's vertices lie within ``r`` (``r2 = r^2``) of its site ``(cx, cy)``; a site
    within the merge band (:func:`.halfplane_settle._merge_tol`: ulps of the vertex's
    magnitude, wider than ``HALFPLANE_REACH_RTOL`` of ``r^2`` far from the origin) of such a
    vertex's circle is within ``4 (r^2 + far_pad)`` of the site squared: the diagonal of a
    float-rotated lattice's square at 1e7 lies ``2 (1 + 1.6e-9) r`` away, and names the
    vertex. The search gathers those sites (:mod:`.halfplane`), and :func:`finish_cell`
    watches them.

    Zero where the band is past ``MERGE_WIDE_MAX`` of ``r^2`` (sites ulps apart, which the
    settling decides by exact tests alone).
    """
    r = np.sqrt(r2)
    band = HALFPLANE_MERGE_RTOL * r2 + 16.0 * _U * r * (abs(cx) + abs(cy) + r)
    return band if band <= MERGE_WIDE_MAX * r2 else 0.0


@njit(inline="always", **NJIT)
def _watch(watch, keep, t):
    """``watch[:keep]`` with candidate ``t`` added if it is not there yet; the new count."""
    for w in range(keep):
        if watch[w] == t:
            return keep
    watch[keep] = t
    return keep + 1


@njit(**NJIT)
def watch_circles(sx, sy, cx, cy, cand, nc, watch, keep, reach2):
    """Add to ``watch[:keep]`` the candidates within ``reach2`` of the site; the new count.

    ``cand[:nc]`` are the search's candidates (sorted indices into ``sx, sy``), ``(cx, cy)``
    the cell's site. See :func:`finish_cell`: far from the origin, a site on a vertex's
    circle to the settling's merge band can lie past the search's reach.
    """
    for c in range(nc):
        t = cand[c]
        qx = sx[t] - cx
        qy = sy[t] - cy
        if qx * qx + qy * qy > reach2:
            continue
        keep = _watch(watch, keep, t)
    return keep


@njit(**NJIT)
def watch_sides(px, py, po, a, m, sx, sy, cx, cy, cand, nc, watch, keep, box, reach2):
    """Add to ``watch[:keep]`` the candidates that a vertex on a box side needs; the new count.

    A Voronoi vertex within reach of a box side is put on it (the side snap of
    :mod:`.halfplane_settle`), so its crossing takes the vertex of a site whose bisector
    passes within that reach of the float cell's vertex on the side. The reach is absolute
    (ulps of the box's coordinates), the watch band of the cut relative to the cell, so a
    small cell far from the origin misses such sites: they are looked for here, among all
    of the search's candidates ``cand[:nc]`` (sorted indices into ``sx, sy``), and only
    for cells with a vertex on a box side (``po`` labels below 0, :func:`finish_cell`
    calls it for those only): a few per diagram. Such a site is within ``2 r + side`` of
    the cell's site (``reach2``: ``REACH (r^2 + pad)``, the search's reach): the farther
    candidates (gathered, never cut) are not looked at.
    """
    side = SIDE_WATCH * (max(abs(box[0]), abs(box[2])) + max(abs(box[1]), abs(box[3])))
    side2 = side * side
    lim = (np.sqrt(reach2) + side) ** 2
    for c in range(nc):
        t = cand[c]
        qx = sx[t] - cx
        qy = sy[t] - cy
        h = 0.5 * (qx * qx + qy * qy)
        if 2.0 * h > lim:
            continue
        near = False
        for u in range(m):
            if po[a + u] < 0 or po[a + (u - 1 if u > 0 else m - 1)] < 0:
                s = qx * px[a + u] + qy * py[a + u] - h
                near = near or s * s < 2.0 * side2 * h
        if not near:
            continue
        keep = _watch(watch, keep, t)
    return keep


@njit(**NJIT)
def finish_cell(
    k,
    sx,
    sy,
    sidx,
    xs,
    ys,
    box,
    px,
    py,
    po,
    ss,
    ox,
    oy,
    oo,
    lab,
    vx,
    vy,
    cand,
    nc,
    watch,
    a,
    m,
    r2,
    nw,
    left,
    budget,
):
    """Settle the float cell (polygon ``a``) exactly and emit it to the scratch output.

    A plain call from :func:`.halfplane._cells`, once per cell (not ``inline="always"``: the
    settling it inlines was then typed and lowered again inside the cell loop, 9 s of the
    2D suite's compile CPU; the call costs nothing measurable next to the settling).

    Returns the emitted length, or -2 when settling would visit more than ``left`` (what
    the search left of the budget) vertex-site pairs, or cost more than ``budget`` work
    units (:func:`.halfplane_settle.settle_ring`): the cell is then hard, see
    :func:`.halfplane._cells`.
    """
    cx = sx[k]
    cy = sy[k]
    for u in range(m):
        lab[u] = po[a + u]
        un = u + 1 if u + 1 < m else 0
        vx[u] = px[a + un] - px[a + u]  # edge vectors (vx, vy are free until settle_ring)
        vy[u] = py[a + un] - py[a + u]
    # the cut's crossings are off by ulps of the polygon they cut, which started as the box:
    # its squared radius about the site bounds their error (not the final cell's)
    far2 = 0.0
    for bx in (box[0] - cx, box[2] - cx):
        for by in (box[1] - cy, box[3] - cy):
            far2 = max(far2, bx * bx + by * by)
    for u in range(m):
        # a long float edge is a true edge (rounding moves its ends by ulps only), unless an
        # end is where nearly parallel bisectors cross (sites a few ulps apart): that
        # crossing can be anywhere along them, and so can the edge. Both relative to the
        # rounding of the crossings, ulps of the box over the angle at each end (a 1e-9
        # cluster in a 1e6 box: ends off by 10% of the cell, a neighbour out of order)
        un = u + 1 if u + 1 < m else 0
        e2 = vx[u] * vx[u] + vy[u] * vy[u]
        ss[u] = 1.0 if e2 > HALFPLANE_SURE_RTOL * r2 else 0.0
        for w in (u - 1 if u > 0 else m - 1, un):
            f2 = vx[w] * vx[w] + vy[w] * vy[w]
            cr = vx[u] * vy[w] - vy[u] * vx[w]
            if (
                cr * cr <= HALFPLANE_SURE_SIN2 * e2 * f2
                or cr * cr <= HALFPLANE_SURE_FAR * far2 * f2
            ):
                ss[u] = 0.0
    # only sites within 2 (r + e) of the final cell can matter to its vertices (PAD)
    reach2 = REACH * (r2 + PAD * HALFPLANE_SLACK2 * far2)
    keep = np.int64(0)
    for c in range(nw):
        t = watch[c]
        qx = sx[t] - cx
        qy = sy[t] - cy
        if qx * qx + qy * qy <= reach2:
            watch[keep] = t
            keep += 1
    # far out, a site on a vertex's circle to the settling's merge band can lie past the
    # reach (:func:`far_pad`): such candidates are watched too (twice the band: a margin)
    band = 4.0 * r2 + 8.0 * far_pad(r2, cx, cy)
    if band > reach2:
        keep = watch_circles(sx, sy, cx, cy, cand, nc, watch, keep, band)
    touches = False
    for u in range(m):
        touches = touches or po[a + u] < 0
    if touches:  # (a call, not inlined: the cell loop's code stays as small as it was)
        keep = watch_sides(px, py, po, a, m, sx, sy, cx, cy, cand, nc, watch, keep, box, reach2)
    if m * keep > left:
        return -2
    # cand (the search's list) is free now: settle_ring's scratch for sites on a circle.
    # Settling has a budget of its own, counted in its exact tests and named vertices: a
    # cell whose vertices have many sites on their circles to rounding (sites on one
    # circle) is hard however few sites its search visited
    # a side the float cut lost between two parallel bisectors (sites on one line) is put
    # back, so that settling names the ring's side points by their crossings
    ml = m
    if may_have_parallel(sidx[k], lab, m, xs, ys):
        ml = restore_sides(sidx[k], lab, ss, m, xs, ys, box)
    ms, _ = settle_ring(sidx[k], lab, ml, ss, watch, keep, sidx, xs, ys, vx, vy, cand, box, budget)
    if ms == -2:
        return -2
    if ms >= 3:
        ms = close_corners(sidx[k], lab, ms, vx, vy, watch, keep, sidx, xs, ys, box)
    # emitted to scratch first: only then is the exact length known, and a rebuilt chunk's
    # output (see _second_pass) has exactly the room the first pass counted
    c = -1
    if ms >= 3:
        c = emit_exact(sidx[k], lab, ms, vx, vy, xs, ys, box, watch, keep, sidx, ox, oy, oo, cand)
    if c < 0:
        c = emit_float(px, py, po, a, m, cx, cy, box, ox, oy, oo)
    return c


@njit(**NJIT)
def _side_of(i, j, x, y, xs, ys, w):
    """Exact sign of ``|c - i|^2 - |c - j|^2`` at ``c = (x, y)``: -1 nearer ``i``, 1 nearer ``j``.

    A float filter first (the bound of :mod:`.cornercut`'s sign), then
    :func:`.distance_exact.compare`; ``w`` is its scratch, made on first need (returned).
    """
    dx = xs[j] - xs[i]
    dy = ys[j] - ys[i]
    ux = x - xs[i]
    uy = y - ys[i]
    h = 0.5 * (dx * dx + dy * dy)
    s = dx * ux + dy * uy - h
    # (plus an absolute term far above the subnormals: products that underflow go exact)
    e = 16.0 * _U * (abs(dx * ux) + abs(dy * uy) + abs(h)) + 2.0**-1000
    if s > e:
        return 1.0, w
    if s < -e:
        return -1.0, w
    if w.shape[0] == 0:
        w = np.zeros((9, 64))
    return float(compare(x, y, xs[i], ys[i], xs[j], ys[j], np.int64(0), w)), w


@njit(**NJIT)
def _end_corner(side, box):
    """The corner where box side ``side`` ends, going counter-clockwise round the box."""
    if side == BOTTOM:
        return box[2], box[1]
    if side == RIGHT:
        return box[2], box[3]
    if side == TOP:
        return box[0], box[3]
    return box[0], box[1]


@njit(**NJIT)
def _corner_in_cell(i, j, x, y, watch, keep, sidx, xs, ys, w):
    """Whether no watched site other than ``i``, ``j`` is strictly nearer ``(x, y)`` than ``i``."""
    for c in range(keep):
        q = sidx[watch[c]]
        if q != i and q != j:
            s, w = _side_of(i, q, x, y, xs, ys, w)
            if s > 0.0:
                return False, w
    return True, w


@njit(**NJIT)
def close_corners(i, lab, m, vx, vy, watch, keep, sidx, xs, ys, box):
    """Settle the box sides of a settled ring ``lab[:m]`` at the corners; the new length.

    The float cut keeps a box corner whose bisector value rounds to 0 as a vertex on the
    bisector (:func:`.clip.cut_ring`), so where a bisector passes an ulp or two inside a
    corner the ring goes from one side straight to the site and loses the next side's
    edge, a few ulps long, and where it passes an ulp outside, the ring keeps a side the
    cell does not reach: the cell ends at the corner while its neighbour ends at the
    crossing of that side (issue 15: sites (0, 0), (1, 1) in the box (-0.2, -0.2, 1.2,
    1.2), whose corners (1.2, -0.2) and (-0.2, 1.2) lie 2^-54 inside site 0's side of
    x + y = 1: no shared edge, and a hole's edge crossed an ulp apart). Decided by exact
    signs (:func:`_side_of`) at a side ``s`` next to a site ``j`` in the ring:

    - ``s`` then ``j``: the bisector leaves the cell through ``s``, so ``s``'s start corner
      strictly nearer ``j`` means ``s`` has no edge (removed), and its end corner strictly
      nearer ``i`` (and than every watched site, ``watch[:keep]`` sorted indices mapped by
      ``sidx``) means the cell turns that corner: the next side goes in between;
    - ``j`` then ``s``: the same with ``s``'s end corner and the side before ``s``.

    A side between two sites is kept (their vertex was not named by the settling). The
    vertices ``vx, vy`` of :func:`.halfplane_settle.settle_ring` move with their labels.
    """
    sides = False
    for t in range(m):
        sides = sides or lab[t] < 0
    if not sides:
        return m  # (most cells: no side, nothing to decide, nothing allocated)
    cap = min(lab.shape[0], vx.shape[0])
    w = np.zeros((0, 0))
    u = np.int64(0)
    steps = 0
    while u < m and m >= 3 and steps < 16:
        a = lab[u - 1] if u > 0 else lab[m - 1]
        b = lab[u]
        if (a < 0) == (b < 0):
            u += 1
            continue
        if a < 0:  # along side a, then site b
            j = b
            at = u - 1 if u > 0 else m - 1  # where side a is in the ring
            other = lab[at - 1] if at > 0 else lab[m - 1]  # the label before it
            prev_side = a + 1 if a < LEFT else TOP
            far_x, far_y = _end_corner(prev_side, box)  # where a starts
            add = a - 1 if a > TOP else LEFT
            x, y = _end_corner(a, box)  # where a ends
        else:  # site a, then side b
            j = a
            at = u
            other = lab[u + 1] if u + 1 < m else lab[0]  # the label after it
            add = b + 1 if b < LEFT else TOP
            far_x, far_y = _end_corner(b, box)  # where b ends
            x, y = _end_corner(add, box)  # where b starts
        s, w = _side_of(i, j, far_x, far_y, xs, ys, w)
        if s > 0.0 and other < 0 and m > 3:
            # the side's far corner is j's: the bisector meets the side past it
            for t in range(at, m - 1):
                lab[t] = lab[t + 1]
                vx[t] = vx[t + 1]
                vy[t] = vy[t + 1]
            m -= 1
            u = 0
            steps += 1
            continue
        s, w = _side_of(i, j, x, y, xs, ys, w)
        ok = s < 0.0 and m + 1 < cap
        for t in range(m):
            ok = ok and lab[t] != add
        if ok:
            ok, w = _corner_in_cell(i, j, x, y, watch, keep, sidx, xs, ys, w)
        if not ok:
            u += 1
            continue
        for t in range(m, u, -1):
            lab[t] = lab[t - 1]
            vx[t] = vx[t - 1]
            vy[t] = vy[t - 1]
        lab[u] = add
        m += 1
        steps += 1
    return m
