"""An exact 3D power cell with Fractions (tests only; slow, obviously correct).

Site ``i``'s power cell is the container cut by every radical plane
``|x - p_i|^2 - w_i <= |x - p_j|^2 - w_j``, that is
``2 (p_j - p_i) . x <= |p_j|^2 - |p_i|^2 - w_j + w_i``, each cut made exactly on
:class:`fractions.Fraction` vertices (a crossing is ``u + t (v - u)`` with
``t = s_u / (s_u - s_v)``, the same rational from either face). The volume is a sum of
exact tetrahedra. Nothing is searched, rounded or named: every site cuts. Vertices are held
as reduced homogeneous integers ``(X, Y, Z, D)``, ``D > 0`` (the point ``(X, Y, Z) / D``), so
the same point from two faces is the same key; planes as integers (floats are dyadic).

Faces carry label sets: ``-1 - w`` for container wall ``w`` (the box's walls in voro++'s
order ``x0, x1, y0, y1, z0, z1``, or the ``walls`` rows), a site's number for a radical
plane. A plane that lies on a face already there (two sites' planes coincide) joins that
face's set, so a caller can accept either owner of such a face.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from math import gcd

import numpy as np


@dataclass
class ExactCell:
    """``faces``: ``(labels (frozenset), ring (list of Fraction triples, outward))``."""

    faces: list
    volume: Fraction

    @property
    def empty(self) -> bool:
        return self.volume == 0

    def neighbour_sets(self) -> list[frozenset]:
        """Label sets of the faces of positive area."""
        return [lab for lab, ring in self.faces if any(area_vector(ring))]

    def vertices(self) -> set:
        return {v for _, ring in self.faces for v in ring}


def _fr(x) -> Fraction:
    return Fraction(float(x))


def _dot(a, v):
    return a[0] * v[0] + a[1] * v[1] + a[2] * v[2]


def _cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def area_vector(ring):
    """Twice the area vector of a planar ring of Fraction triples (zero when degenerate)."""
    s = [Fraction(0)] * 3
    for k in range(len(ring)):
        c = _cross(ring[k], ring[(k + 1) % len(ring)])
        s = [s[0] + c[0], s[1] + c[1], s[2] + c[2]]
    return s


def volume(faces) -> Fraction:
    """Exact volume of a closed polyhedron of outward Fraction rings (a fan of tetrahedra)."""
    if not faces:
        return Fraction(0)
    o = faces[0][1][0]
    total = Fraction(0)
    for _, ring in faces:
        a = _sub(ring[0], o)
        for k in range(1, len(ring) - 1):
            b, c = _sub(ring[k], o), _sub(ring[k + 1], o)
            total += _dot(a, _cross(b, c))
    return total / 6


def _point(x) -> Fraction:
    """A homogeneous vertex as a Fraction triple."""
    return (Fraction(x[0], x[3]), Fraction(x[1], x[3]), Fraction(x[2], x[3]))


def _reduce(X, Y, Z, D):
    if D < 0:
        X, Y, Z, D = -X, -Y, -Z, -D
    g = gcd(gcd(X, Y), gcd(Z, D))
    return (X // g, Y // g, Z // g, D // g)


def _homogeneous(v):
    """A triple of Fractions (or floats) as a reduced homogeneous integer vertex."""
    f = [Fraction(x) for x in v]
    D = f[0].denominator * f[1].denominator * f[2].denominator
    return _reduce(*(int(x * D) for x in f), D)


def _plane(a, b):
    """``a . x <= b`` (Fractions) as integers ``(A, B)`` with the same half-space."""
    m = 1
    for x in (*a, b):
        m = m * Fraction(x).denominator // gcd(m, Fraction(x).denominator)
    return [int(x * m) for x in a], int(b * m)


def box_faces(lo, hi, labels=(-1, -2, -3, -4, -5, -6)):
    """The box ``lo..hi`` as outward homogeneous rings, walls in voro++'s order."""
    x0, y0, z0 = (_fr(v) for v in lo)
    x1, y1, z1 = (_fr(v) for v in hi)

    def p(a, b, c):
        return _homogeneous((x1 if a else x0, y1 if b else y0, z1 if c else z0))

    rings = [
        [p(0, 0, 0), p(0, 0, 1), p(0, 1, 1), p(0, 1, 0)],  # x0, normal -x
        [p(1, 0, 0), p(1, 1, 0), p(1, 1, 1), p(1, 0, 1)],  # x1
        [p(0, 0, 0), p(1, 0, 0), p(1, 0, 1), p(0, 0, 1)],  # y0
        [p(0, 1, 0), p(0, 1, 1), p(1, 1, 1), p(1, 1, 0)],  # y1
        [p(0, 0, 0), p(0, 1, 0), p(1, 1, 0), p(1, 0, 0)],  # z0
        [p(0, 0, 1), p(1, 0, 1), p(1, 1, 1), p(0, 1, 1)],  # z1
    ]
    return [(frozenset([lab]), r) for lab, r in zip(labels, rings, strict=True)]


def _flat(ring) -> bool:
    """Whether a convex homogeneous ring has zero area (all its vertices on one line)."""
    o = ring[0]
    # v - o scaled by D_v D_o > 0: the same direction, in integers
    d = [tuple(v[m] * o[3] - o[m] * v[3] for m in range(3)) for v in ring[1:]]
    d = [e for e in d if any(e)]
    return all(not any(_cross(d[0], e)) for e in d[1:])


def cut(faces, a, b, label):
    """Homogeneous ``faces`` cut by ``a . x <= b`` (Fractions), the cap labelled ``label``.

    Returns the new faces; ``[]`` when nothing of positive volume is left.
    """
    A, B = _plane(a, b)
    s = {}  # the sign-true value A . X - B D of each vertex
    for _, ring in faces:
        for v in ring:
            if v not in s:
                s[v] = A[0] * v[0] + A[1] * v[1] + A[2] * v[2] - B * v[3]
    if max(s.values()) <= 0:
        # no cut; a face lying on the plane takes the label too (coinciding planes)
        out = []
        for lab, ring in faces:
            if all(s[v] == 0 for v in ring) and not _flat(ring):
                lab = lab | {label}
            out.append((lab, ring))
        return out
    if min(s.values()) >= 0:
        return []
    out = []
    on = {}  # cap edges, reversed: start -> end
    for lab, ring in faces:
        sv = [s[v] for v in ring]
        if min(sv) >= 0:
            continue  # wholly on the plane's far side (or on it: the cap replaces it)
        if max(sv) <= 0:
            ring2 = ring  # wholly kept
        else:
            kept = []
            for k, u in enumerate(ring):
                v = ring[(k + 1) % len(ring)]
                su, sv_ = s[u], s[v]
                if su <= 0:
                    kept.append(u)
                if (su < 0 < sv_) or (sv_ < 0 < su):
                    # the crossing (s_v u - s_u v) / (s_v D_u - s_u D_v), the same from
                    # either end once reduced
                    q = _reduce(*(sv_ * u[m] - su * v[m] for m in range(4)))
                    s[q] = 0  # on the plane by construction
                    kept.append(q)
            ring2 = [q for k, q in enumerate(kept) if q != kept[k - 1]]
            if len(ring2) < 3 or _flat(ring2):
                continue
        for k, u in enumerate(ring2):
            v = ring2[(k + 1) % len(ring2)]
            if s[u] == 0 and s[v] == 0:
                on[v] = u
        out.append((lab, ring2))
    start = next(iter(on))
    cap = [start]
    while on[cap[-1]] != start:
        cap.append(on[cap[-1]])
        if len(cap) > len(on):
            raise AssertionError("the cap does not close")
    out.append((frozenset([label]), cap))
    return out


def exact_power_cell(points, i, box, weights=None, walls=None) -> ExactCell:
    """Site ``i``'s exact power cell in ``box = (x0, y0, z0, x1, y1, z1)``.

    ``walls`` (optional, ``(k, 4)`` rows ``[a, b, c, d]``, inside ``a x + b y + c z <= d``):
    a convex container inside the box, its faces labelled ``-1 - row``; the box's own faces
    are then labelled ``-1000 - side`` (they bound only). Exact duplicates of ``p_i``: the
    heavier site owns the cell, the lowest index on equal weights.
    """
    P = np.asarray(points, np.float64)
    W = np.zeros(len(P)) if weights is None else np.asarray(weights, np.float64)
    labels = (-1, -2, -3, -4, -5, -6) if walls is None else tuple(-1000 - k for k in range(6))
    faces = box_faces(box[:3], box[3:], labels)
    for k, row in enumerate(np.asarray([] if walls is None else walls, np.float64).reshape(-1, 4)):
        faces = cut(faces, [_fr(x) for x in row[:3]], _fr(row[3]), -1 - k)
        if not faces:
            return ExactCell([], Fraction(0))
    p = [_fr(x) for x in P[i]]
    wi = _fr(W[i])
    pp = _dot(p, p)
    # nearest first by power distance (the result does not depend on the order; only the
    # size of the intermediate cells does)
    order = np.argsort(((P - P[i]) ** 2).sum(1) - W, kind="stable")
    r2 = _reach(faces, p)
    for j in order:
        j = int(j)
        if j == i:
            continue
        q = [_fr(x) for x in P[j]]
        a = [2 * (q[m] - p[m]) for m in range(3)]
        b = _dot(q, q) - pp - _fr(W[j]) + wi
        if not any(a):  # a duplicate of p_i
            if b < 0 or (b == 0 and j < i):
                return ExactCell([], Fraction(0))
            continue
        # an exact skip: every vertex lies within sqrt(r2) of p_i, so a plane farther than
        # that from p_i (on the far side) cannot reach the cell
        gap = b - _dot(a, p)
        if r2 is not None and gap > 0 and gap * gap > _dot(a, a) * r2:
            continue
        faces = cut(faces, a, b, j)
        if not faces:
            return ExactCell([], Fraction(0))
        r2 = _reach(faces, p)
    rings = [(lab, [_point(v) for v in ring]) for lab, ring in faces]
    return ExactCell(rings, volume(rings))


def _reach(faces, p) -> Fraction | None:
    """An upper bound on the squared distance from ``p`` to every vertex of ``faces``.

    Each offset is exact, then rounded once to a float (``int / int`` rounds correctly);
    the float sum of squares is widened by far more than its few roundings. ``None`` past
    float range. Only a skip test depends on it.
    """
    pts = {v for _, ring in faces for v in ring}
    pr = [x.as_integer_ratio() for x in p]
    try:
        r2 = max(
            sum(((v[m] * pr[m][1] - pr[m][0] * v[3]) / (v[3] * pr[m][1])) ** 2 for m in range(3))
            for v in pts
        )
    except OverflowError:
        return None
    return Fraction(r2 * (1 + 1e-9) + 1e-300) if r2 < 1e300 else None
