"""Box sides a float cut lost between two parallel bisectors, put back by name.

Sites exactly on one line (a diagonal an ulp apart, issue 15) have parallel bisectors: the
middle site's cell is a strip whose ends lie on box sides, between the crossings of its two
bisectors with each side. Where those crossings are less than an ulp apart (the strips of
``test_issue15_ulps_box``: crossings of the top side half an ulp apart), the float cut
clips the side edge away and its ring goes from one neighbour's edge straight to the
other's, a vertex of two parallel lines that does not exist (the collinear Delaunay cells
wrote one in the middle of the box; the half-plane settling refused the ring and the
cell was written as cut, its side points off the crossings its neighbours name). The
exact ring has the box sides between the two edges: :func:`restore_sides` puts their
labels back (and corners between them), so the ring's side points become the canonical
crossings (:func:`.vertex.box_crossing`), the bits every cell at them computes.

Labels are ring owners: a site index (``>= 0``) or a box side (-1..-4: left, bottom,
right, top, the side codes of :func:`.vertex.box_crossing`); label ``u`` owns the edge from
vertex ``u`` to ``u + 1``, and a counter-clockwise ring meets the sides in the order
left, bottom, right, top.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import NJIT
from .predicates import orient2d, orient2d_fast
from .vertex import box_crossing


@njit(**NJIT)
def parallel_between(i, a, b, xs, ys):
    """Whether site ``i`` lies strictly between sites ``a`` and ``b`` on one line (exact).

    Then the bisectors of ``i`` with ``a`` and with ``b`` are parallel: the edges of ``i``'s
    cell on them meet at no vertex.
    """
    if a < 0 or b < 0 or a == b or a == i or b == i:
        return False
    # opposite directions from i (most pairs of consecutive neighbours are not: no exact test)
    if (xs[a] - xs[i]) * (xs[b] - xs[i]) + (ys[a] - ys[i]) * (ys[b] - ys[i]) >= 0.0:
        return False
    if orient2d(xs[a], ys[a], xs[b], ys[b], xs[i], ys[i]) != 0.0:
        return False
    moved = False
    for p, q, c in ((xs[a], xs[b], xs[i]), (ys[a], ys[b], ys[i])):
        if p != q:
            if not (min(p, q) < c < max(p, q)):
                return False
            moved = True
    return moved


@njit(inline="always", **NJIT)
def may_have_parallel(i, lab, m, xs, ys):
    """Whether some consecutive labels of a ring may be a :func:`parallel_between` pair.

    The callers' screen before :func:`restore_sides` (``lab[u - 1]`` then ``lab[u]``).
    Inlined and without exact code: False where each pair of sites is proven not to lie in
    opposite directions from ``i`` on one line (a dot product that is not negative, or
    orient2d's float filter finding the three not collinear), as on every ring but a
    strip's; the hot loop then makes no call (``restore_sides`` takes four arrays).
    """
    if m < 2:
        return False
    xi = xs[i]
    yi = ys[i]
    b = lab[m - 1]
    for u in range(m):
        a = b
        b = lab[u]
        if a < 0 or b < 0:
            continue
        if (xs[a] - xi) * (xs[b] - xi) + (ys[a] - yi) * (ys[b] - yi) >= 0.0:
            continue
        det = orient2d_fast(xs[a], ys[a], xs[b], ys[b], xi, yi)
        if det != det:
            return True  # NaN: collinear, or the filter could not decide
    return False


@njit(**NJIT)
def _next_side(s):
    """The side a counter-clockwise ring meets after side ``s`` (left, bottom, right, top)."""
    return s - 1 if s > -4 else -1


@njit(**NJIT)
def _corner(s, box):
    """The corner between side ``s`` and :func:`_next_side` of it."""
    if s == -1:
        return box[0], box[1]
    if s == -2:
        return box[2], box[1]
    if s == -3:
        return box[2], box[3]
    return box[0], box[3]


@njit(**NJIT)
def _end_side(i, j, xs, ys, box, leaving):
    """The side where the edge of neighbour ``j`` leaves the box (``leaving``) or enters it.

    The edge runs with ``i``'s cell on its left, along ``(-(yj - yi), xj - xi)``. Of the
    two sides it can leave by, the one whose canonical crossing lies on the box's extent
    (both: the nearer along the edge). Returns ``(side, x, y)``; side 0 where none does.
    """
    dx = -(ys[j] - ys[i])
    dy = xs[j] - xs[i]
    if not leaving:
        dx = -dx
        dy = -dy
    best = 0
    bx = np.nan
    by = np.nan
    bt = np.inf
    for s in (
        -3 if dx > 0.0 else (-1 if dx < 0.0 else 0),
        -4 if dy > 0.0 else (-2 if dy < 0.0 else 0),
    ):
        if s == 0:
            continue
        x, y = box_crossing(i, j, xs, ys, s, box)
        if not (x == x and y == y and box[0] <= x <= box[2] and box[1] <= y <= box[3]):
            continue
        t = x * dx + y * dy
        if t < bt:
            bt = t
            best = s
            bx = x
            by = y
    return best, bx, by


@njit(**NJIT)
def side_path(i, a, b, xs, ys, box):
    """The sides between the edges of neighbours ``a`` then ``b`` with parallel bisectors.

    Returns ``(first, count, xa, ya, xb, yb)``: the sides ``first``, :func:`_next_side`
    of it, ... (``count`` of them) that a counter-clockwise ring of ``i`` runs along from
    ``a``'s edge to ``b``'s, and where the two edges meet them (the canonical crossings);
    ``count`` 0 where the bisectors do not cross the box's sides.
    """
    sa, xa, ya = _end_side(i, a, xs, ys, box, True)
    sb, xb, yb = _end_side(i, b, xs, ys, box, False)
    if sa == 0 or sb == 0:
        return 0, 0, xa, ya, xb, yb
    count = 1
    s = sa
    while s != sb and count < 5:
        s = _next_side(s)
        count += 1
    return sa, count if count < 5 else 0, xa, ya, xb, yb


@njit(**NJIT)
def restore_sides(i, lab, sure, m, xs, ys, box):
    """Put back the box sides between consecutive neighbours with parallel bisectors.

    ``lab[:m]`` is a ring's labels and ``sure[:m]`` flags of its edges (both in place; the
    arrays need room); returns the new length. The two edges and the sides put between
    them are not sure (0). A ring whose neighbours are not on one line with ``i`` is left
    as it is.
    """
    u = 0
    while u < m:
        a = lab[u - 1] if u > 0 else lab[m - 1]
        b = lab[u]
        if parallel_between(i, a, b, xs, ys):
            first, count, _, _, _, _ = side_path(i, a, b, xs, ys, box)
            if count > 0 and m + count <= min(lab.shape[0], sure.shape[0]):
                for k in range(m - 1, u - 1, -1):
                    lab[k + count] = lab[k]
                    sure[k + count] = sure[k]
                s = first
                for k in range(count):
                    lab[u + k] = s
                    sure[u + k] = 0.0
                    s = _next_side(s)
                sure[u - 1 if u > 0 else m + count - 1] = 0.0
                sure[u + count] = 0.0
                m += count
                u += count
        u += 1
    return m


@njit(**NJIT)
def _no_triangle(a, b, nbrs, tris, nn):
    """Whether neighbour ``b`` follows ``a`` in ``nbrs[:nn]`` with no triangle between."""
    for k in range(nn):
        if nbrs[k] == a:
            return nbrs[k + 1 if k + 1 < nn else 0] == b and tris[k] < 0
    return False


@njit(**NJIT)
def restore_side_vertices(i, px, py, pw, m, nbrs, tris, nn, xs, ys, box):
    """:func:`restore_sides` on a cut cell's ring: vertex ``v`` starts edge ``pw[v]``.

    Only where no Delaunay triangle lies between the two neighbours (``nbrs[:nn]`` in
    rotation order, ``tris[k]`` the triangle after ``nbrs[k]``, -1 past a hull end or for
    sites on one line): otherwise a neighbour between them (a site off the line whose edge
    the cut lost) ends the strip, and the chain of centres puts it back. The vertex
    between the two parallel edges becomes the first edge's crossing, the corners, and the
    second edge's crossing (the canonical crossings); returns the new length.
    """
    if not may_have_parallel(i, pw, m, xs, ys):
        return m
    v = 0
    while v < m:
        a = pw[v - 1] if v > 0 else pw[m - 1]
        b = pw[v]
        if parallel_between(i, a, b, xs, ys) and _no_triangle(a, b, nbrs, tris, nn):
            first, count, xa, ya, xb, yb = side_path(i, a, b, xs, ys, box)
            if count > 0 and m + count <= px.shape[0]:
                for k in range(m - 1, v, -1):
                    px[k + count] = px[k]
                    py[k + count] = py[k]
                    pw[k + count] = pw[k]
                px[v] = xa
                py[v] = ya
                s = first
                for k in range(count):
                    pw[v + k] = s
                    if k + 1 < count:
                        px[v + k + 1], py[v + k + 1] = _corner(s, box)
                    s = _next_side(s)
                px[v + count] = xb
                py[v + count] = yb
                pw[v + count] = b
                m += count
                v += count
        v += 1
    return m
