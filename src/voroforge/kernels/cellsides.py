"""Box sides for cut cells: which Voronoi vertices are put on a side, and where.

A Voronoi vertex within rounding of a box side is on it to rounding: every cell at the vertex
puts it, and the crossings of its edges with that side, at one point computed from the
vertex's name alone (:func:`side_reaches`, :func:`on_sides`). Split from
:mod:`kernels.cellcut`, which uses these for every cut cell (and re-exports them).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..config import BOX_SIDE_REACH_ULPS, NJIT
from .predicates import orient2d

_U = 2.0**-53
_TINY = 2.0**-1074  # a stay's reach is negative even where its centre's bound is 0


@njit(**NJIT)
def side_reach(x, y, err):
    """How near a box side a centre ``(x, y)`` with rounding bound ``err`` is put on it.

    Four times the bound (its class's, so that every member of a merged vertex decides
    alike) and ``BOX_SIDE_REACH_ULPS`` ulps of its larger coordinate. Lattices whose step is
    2 ulps of their offset keep their vertices an ulp or more inside the sides
    (``test_lattice_a_few_ulps_apart_is_exact``).
    """
    big = max(abs(x), abs(y))
    return 4.0 * err + BOX_SIDE_REACH_ULPS * math.ldexp(1.0, math.frexp(big)[1] - 53)


@njit(**NJIT)
def near_sides(x, y, e, box):
    """Bits of the box sides (1, 2, 4, 8: left, bottom, right, top) within ``e`` of ``(x, y)``.

    As :func:`on_sides` takes them: a side only along its extent (widened by ``e``), and of
    two opposite sides the first.
    """
    bits = 0
    if box[1] - e <= y <= box[3] + e:
        if abs(x - box[0]) <= e:
            bits |= 1
        elif abs(x - box[2]) <= e:
            bits |= 4
    if box[0] - e <= x <= box[2] + e:
        if abs(y - box[1]) <= e:
            bits |= 2
        elif abs(y - box[3]) <= e:
            bits |= 8
    return bits


@njit(**NJIT)
def class_err(cls, err):
    """Per triangle, the largest rounding bound in its class (one vertex, one bound).

    The cells' tests of a vertex against the box (:func:`side_reaches`) must decide
    alike for every triangle of a merged class, whose members share the centre's bits but
    not their bounds.
    """
    big = np.zeros_like(err)
    for t in range(cls.shape[0]):
        c = cls[t]
        if err[t] > big[c]:
            big[c] = err[t]
    out = np.zeros_like(err)
    for t in range(cls.shape[0]):
        out[t] = big[cls[t]]
    return out


@njit(**NJIT)
def side_reaches(xs, ys, tri, cls, cx, cy, err, box):
    """Per triangle, how near a box side its centre is put on it; negative: never.

    :func:`side_reach` of the centre with its class's rounding bound ``err[t]``
    (:func:`class_err`), so every cell at a vertex decides alike. A vertex is left where
    it is (-1, for its whole class) when a site of its triangles lies within that reach
    of a side it would be put on, or two of them lie within twice of each other: moving
    the vertex by its reach would take such a site out of its own cell (a strip a few
    ulps wide along the side; issue 15, ``test_issue15_ulp_strips``), where the cut's
    own vertices keep it in.
    """
    nt = cls.shape[0]
    reach = np.zeros(nt)
    stay = np.zeros(nt, dtype=np.bool_)
    for t in range(nt):
        x = cx[t]
        y = cy[t]
        b = err[t]
        # an ulp of the larger coordinate is at most 2 * _U of it: a centre inside by more
        # than that bound is put on no side (most of them: no frexp)
        e = 4.0 * b + 2.0 * _U * max(abs(x), abs(y))
        if box[0] + e < x < box[2] - e and box[1] + e < y < box[3] - e:
            reach[t] = e
            continue
        e = side_reach(x, y, b)
        reach[t] = e
        bits = near_sides(x, y, e, box)
        if bits == 0:
            continue
        for k in range(3):
            s = tri[3 * t + k]
            s2 = tri[3 * t + (k + 1) % 3]
            if near_sides(xs[s], ys[s], e, box) & bits or (
                abs(xs[s] - xs[s2]) <= 2.0 * e and abs(ys[s] - ys[s2]) <= 2.0 * e
            ):
                stay[cls[t]] = True
    for t in range(nt):
        if stay[cls[t]]:
            # negative: never put on a side; its size is the centre's rounding bound
            # (cellcut: a centre inside, or past a side, by more than that is so exactly)
            reach[t] = -max(err[t], _TINY)
    return reach


@njit(**NJIT)
def on_sides(t, cx, cy, reach, box):
    """Triangle ``t``'s centre put on the box sides it lies within ``reach[t]`` of.

    Returns ``(x, y, hit)``. A Voronoi vertex that close to a side (inside, on or past it)
    is on it to rounding: the crossings of the side by its edges and the vertex itself
    round in any order there (two crossings of one side reversed, a vertex an ulp past
    the side), and each cell's own cut decides differently. Every cell at the vertex puts
    it, and the crossings of its edges with that side, at this one point (a corner when
    it is within reach of two sides), computed from the vertex's name alone.
    ``reach`` is :func:`side_reaches`' (-1: the vertex stays where it is).
    """
    x = cx[t]
    y = cy[t]
    e = reach[t]
    if e < 0.0:
        return x, y, False
    bits = near_sides(x, y, e, box)
    x, y = onto_sides(x, y, bits, box)
    return x, y, bits != 0


@njit(**{**NJIT, "inline": "always"})  # on every vertex a cell writes: no call
def onto_sides(x, y, bits, box):
    """``(x, y)`` put on the box sides set in ``bits`` (:func:`near_sides`' 1, 2, 4, 8)."""
    if bits & 1:
        x = box[0]
    elif bits & 4:
        x = box[2]
    if bits & 2:
        y = box[1]
    elif bits & 8:
        y = box[3]
    return x, y


@njit(**NJIT)
def on_side(x, y, side, box):
    """Whether ``(x, y)`` lies on box side ``side`` (-1..-4), exactly."""
    if side == -1:
        return x == box[0]
    if side == -2:
        return y == box[1]
    if side == -3:
        return x == box[2]
    return y == box[3]


@njit(**NJIT)
def vertex_at(t, cx, cy, reach, box):
    """Triangle ``t``'s centre as cells write it: on a side when within reach of it."""
    x, y, _ = on_sides(t, cx, cy, reach, box)
    return x, y


@njit(**NJIT)
def past_side(t, side, cx, cy, reach, box):
    """Whether triangle ``t``'s centre lies past box side ``side`` by more than its reach.

    A negative reach (a centre never put on a side) counts by its size, the centre's
    rounding bound: past by more than that is past exactly.
    """
    if t < 0:
        return False
    e = abs(reach[t])
    if side == -1:
        return cx[t] < box[0] - e
    if side == -2:
        return cy[t] < box[1] - e
    if side == -3:
        return cx[t] > box[2] + e
    return cy[t] > box[3] + e


@njit(**NJIT)
def end_past(i, j, c, t, side, xs, ys, cx, cy, reach, box):
    """Whether the end of neighbour ``j``'s edge at triangle ``t`` lies past ``side``.

    The centre of ``t`` past the side by more than its reach (:func:`past_side`); past a
    hull end (``t`` -1) the edge is a ray from the other triangle's centre, ``(i, j, c)``'s,
    away from ``c``: its end at infinity is past the side when the ray does not turn back
    towards the box (the sign of a difference of two doubles, exact).
    """
    if t >= 0:
        return past_side(t, side, cx, cy, reach, box)
    if c < 0 or c == i or c == j:
        return False
    o = orient2d(xs[i], ys[i], xs[j], ys[j], xs[c], ys[c])
    if not (o > 0.0 or o < 0.0):
        return False
    dx = xs[j] - xs[i]
    dy = ys[j] - ys[i]
    # perpendicular to i -> j, on the side away from c
    ux = dy if o > 0.0 else -dy
    uy = -dx if o > 0.0 else dx
    if side == -1:
        return ux <= 0.0
    if side == -2:
        return uy <= 0.0
    if side == -3:
        return ux >= 0.0
    return uy >= 0.0
