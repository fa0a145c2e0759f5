"""The exact convex polytope of half-spaces: a :class:`~.containers.Convex` container's template.

A box around the solid is cut by each row ``a x + b y + c z <= d`` in turn. Every vertex is
kept exactly, as homogeneous integers ``(X, Y, Z, D)`` (``D > 0``) solved from the three rows
that made it (a row of doubles times a power of two is a row of integers with the same
half-space), and in floats as its correctly rounded coordinates. Which side of a row a vertex
lies on is decided in floats where the rounding cannot change the sign and exactly otherwise,
so a row through a vertex, an edge or a face (a duplicate, a redundant or a nearly parallel
row) cuts nothing and leaves no sliver face, and a row that does cut makes the faces the exact
polytope has, however small. The volume is the sum of the tetrahedra from one vertex to each
face's fan: all of them are non-negative (the polytope is convex), so each is rounded once
from its exact value and their ``math.fsum`` is good to about an ulp of the volume.

The float cut this replaces (``kernels.polyhedron.cut`` on the box, once
``kernels.cells3d.container_cut``) decided "on the plane" within 1e-12 of the solid's size:
the 40 rounded walls of a 1e-3 slab at (5e5, 4e6, 100) came out 5.8e-11 off the exact
volume of its rows (now 0), its cells 1.8e-11 off that volume (now 3e-16).
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np

#: the cube's faces, outward counter-clockwise; corner ``k`` is ``(k & 1, k >> 1 & 1, k >> 2)``
#: (as :mod:`engine.containers`; face ``f`` lies on the box's row ``f``)
_CUBE_RINGS = ((0, 4, 6, 2), (1, 3, 7, 5), (0, 1, 5, 4), (2, 6, 7, 3), (0, 2, 3, 1), (4, 5, 7, 6))
#: a float side within this many units of the sum of its terms' magnitudes is decided exactly
#: (the vertex's rounding, ulp/2 of each coordinate, plus four roundings of the sum: 5 ulp/2)
_SIDE_FILTER = 8.0 * np.finfo(np.float64).eps


def row_ints(row) -> tuple[int, int, int, int]:
    """The doubles ``row`` (4,) times the power of two that makes all four integers."""
    fr = [Fraction(float(x)) for x in row]
    den = max(f.denominator for f in fr)  # powers of two: the largest is a multiple of all
    return tuple(int(f * den) for f in fr)


def _det3(a, b, c):
    return (
        a[0] * (b[1] * c[2] - b[2] * c[1])
        - a[1] * (b[0] * c[2] - b[2] * c[0])
        + a[2] * (b[0] * c[1] - b[1] * c[0])
    )


def solve3(r1, r2, r3):
    """The point on the integer rows' three planes: ``(X, Y, Z, D)``, ``D > 0``; None: dependent."""
    D = _det3(r1, r2, r3)
    if D == 0:
        return None
    n = (r1, r2, r3)
    X = _det3(*[(r[3], r[1], r[2]) for r in n])
    Y = _det3(*[(r[0], r[3], r[2]) for r in n])
    Z = _det3(*[(r[0], r[1], r[3]) for r in n])
    if D < 0:
        return (-X, -Y, -Z, -D)
    return (X, Y, Z, D)


def _det4(p, q, r, s):
    """The determinant of the rows ``p, q, r, s`` (4,) of integers."""
    m01 = p[0] * q[1] - p[1] * q[0]
    m02 = p[0] * q[2] - p[2] * q[0]
    m03 = p[0] * q[3] - p[3] * q[0]
    m12 = p[1] * q[2] - p[2] * q[1]
    m13 = p[1] * q[3] - p[3] * q[1]
    m23 = p[2] * q[3] - p[3] * q[2]
    n01 = r[0] * s[1] - r[1] * s[0]
    n02 = r[0] * s[2] - r[2] * s[0]
    n03 = r[0] * s[3] - r[3] * s[0]
    n12 = r[1] * s[2] - r[2] * s[1]
    n13 = r[1] * s[3] - r[3] * s[1]
    n23 = r[2] * s[3] - r[3] * s[2]
    return m01 * n23 - m02 * n13 + m03 * n12 + m12 * n03 - m13 * n02 + m23 * n01


class _Cutter:
    """The polytope while it is cut: exact vertices, float copies, faces as outward rings."""

    def __init__(self, rows: np.ndarray, lo, hi):
        k = len(rows)
        box = np.zeros((6, 4))
        for a in range(3):
            box[2 * a, a] = -1.0
            box[2 * a, 3] = -lo[a]
            box[2 * a + 1, a] = 1.0
            box[2 * a + 1, 3] = hi[a]
        self.rows = np.vstack([rows, box])  # rows k..k+5: the box's walls
        self.ints = [row_ints(r) for r in self.rows]
        self.k = k
        self.exact: list[tuple[int, int, int, int]] = []
        self.vf = np.zeros((64, 3))
        self.alive = np.zeros(64, bool)
        for c in range(8):
            bits = (c & 1, c >> 1 & 1, c >> 2)
            self._add(solve3(*[self.ints[k + 2 * a + bits[a]] for a in range(3)]))
        self.faces = {k + f: list(_CUBE_RINGS[f]) for f in range(6)}  # plane -> ring
        self.edges = {}  # directed edge (u, w) -> the plane of the face that has it
        self.vfaces: dict[int, set] = {}  # vertex -> the planes of its faces
        for p, ring in self.faces.items():
            self._link(p, ring)

    def _add(self, x) -> int:
        v = len(self.exact)
        if v == len(self.vf):
            self.vf = np.vstack([self.vf, np.zeros_like(self.vf)])
            self.alive = np.concatenate([self.alive, np.zeros_like(self.alive)])
        self.exact.append(x)
        self.vf[v] = (x[0] / x[3], x[1] / x[3], x[2] / x[3])  # int / int: correctly rounded
        self.alive[v] = True
        return v

    def _link(self, p, ring, on=True):
        """Enter (or remove) face ``p``'s ring in the edge and vertex-to-face maps."""
        for t in range(len(ring)):
            e = (ring[t - 1], ring[t])
            if on:
                self.edges[e] = p
                self.vfaces.setdefault(e[1], set()).add(p)
            else:
                del self.edges[e]
                self.vfaces[e[1]].discard(p)

    def _sides(self, p: int) -> np.ndarray:
        """Each vertex's side of row ``p``: -1 inside, 0 on it, 1 outside (dead ones: any)."""
        n = self.rows[p, :3]
        d = self.rows[p, 3]
        nv = len(self.exact)
        V = self.vf[:nv]
        s = V @ n - d
        bound = _SIDE_FILTER * (np.abs(V) @ np.abs(n) + abs(d)) + 1e-300
        side = np.where(s > bound, 1, np.where(s < -bound, -1, 0))
        a, b, c, e = self.ints[p]
        for v in np.flatnonzero((side == 0) & self.alive[:nv]):
            X, Y, Z, D = self.exact[v]
            t = a * X + b * Y + c * Z - e * D
            side[v] = (t > 0) - (t < 0)
        return side

    def cut(self, p: int) -> None:
        """Cut by row ``p``; raises ``ValueError`` when nothing of the solid is left inside."""
        side = self._sides(p)
        alive = self.alive[: len(side)]
        out = np.flatnonzero((side > 0) & alive)
        if not len(out):
            return  # the row touches the solid at most in a point, an edge or a face
        if not ((side < 0) & alive).any():
            raise ValueError(
                f"the Convex container has no volume: half-space {p} leaves none of it"
            )
        made: dict[frozenset, int] = {}
        changed = sorted(set().union(*(self.vfaces[v] for v in out.tolist())))
        rings = {}
        for f in changed:
            ring = self.faces[f]
            kept = []
            for t, u in enumerate(ring):
                w = ring[(t + 1) % len(ring)]
                if side[u] <= 0:
                    kept.append(u)
                if side[u] * side[w] < 0:
                    key = frozenset((u, w))
                    if key not in made:
                        g = self.edges[(w, u)]
                        x = solve3(self.ints[f], self.ints[g], self.ints[p])
                        made[key] = self._add(x)
                    kept.append(made[key])
            rings[f] = kept if any(side[v] < 0 for v in ring) else None
        ison = set(np.flatnonzero((side == 0) & alive).tolist()) | set(made.values())
        nxt = {}  # the new face's ring: each edge of another face on the plane, reversed
        for f in changed:
            self._link(f, self.faces[f], on=False)
            ring = rings[f]
            if ring is None:
                del self.faces[f]
                continue
            self.faces[f] = ring
            self._link(f, ring)
            for t in range(len(ring)):
                a, b = ring[t - 1], ring[t]
                if a in ison and b in ison:
                    nxt[b] = a
        old = [v for v in ison if v not in made.values()]
        for a in old:
            for b in old:
                f = self.edges.get((a, b))
                if f is not None and f not in rings:
                    nxt[b] = a
        self.alive[out] = False
        start = next(iter(nxt))
        ring = [start]
        while nxt[ring[-1]] != start:
            ring.append(nxt[ring[-1]])
            if len(ring) > len(nxt):
                break
        if len(ring) != len(nxt) or len(ring) < 3:
            raise ValueError(f"could not build the Convex container (half-space {p})")
        self.faces[p] = ring
        self._link(p, ring)

    def result(self):
        """``(TV, TF, TR, volume)``: the used vertices rounded, faces labelled ``-1 - row``."""
        used = sorted({v for ring in self.faces.values() for v in ring})
        new = {v: t for t, v in enumerate(used)}
        TV = self.vf[used].copy()
        TF = []
        TR = []
        for p in sorted(self.faces):
            ring = self.faces[p]
            TF.append((-1 - p, len(TR), len(ring)))
            TR.extend(new[v] for v in ring)
        # tetrahedra from vertex o to every face's fan: each >= 0 (convex), rounded once
        o = self.exact[used[0]]
        terms = []
        for ring in self.faces.values():
            a = self.exact[ring[0]]
            for t in range(1, len(ring) - 1):
                b = self.exact[ring[t]]
                c = self.exact[ring[t + 1]]
                det = _det4(a, b, c, o)
                if det:
                    terms.append(det / (a[3] * b[3] * c[3] * o[3]))
        vol = math.fsum(terms) / 6.0
        return TV, np.array(TF, np.int64), np.array(TR, np.int64), vol


def exact_polytope(rows: np.ndarray, lo, hi, skip=None):
    """The polytope of ``rows (k, 4)`` inside the box ``lo..hi``: ``(TV, TF, TR, volume)``.

    Faces carry ``-1 - w`` for row ``w``, and ``-1 - (k + b)`` for box wall ``b`` (0 x-min,
    1 x-max, ... as a box template) where the box still bounds the solid. Raises
    ``ValueError`` when a row leaves no volume. ``skip`` (k,) bool: rows left out (rows
    that, as the user gave them, only touch the solid: ``containers._convex_template``).
    """
    cutter = _Cutter(np.asarray(rows, np.float64), lo, hi)
    for p in range(len(rows)):
        if skip is None or not skip[p]:
            cutter.cut(p)
    return cutter.result()
