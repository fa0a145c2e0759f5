"""Slow, obviously correct oracles the engine is compared against.

Nothing here is clever: exact rational arithmetic with :class:`fractions.Fraction`,
brute-force nearest sites and Voronoi cells built as intersections of bisector half-planes.
Use them on small inputs only.
"""

from __future__ import annotations

from fractions import Fraction
from itertools import combinations

import numpy as np
import shapely


def _fr(v) -> Fraction:
    """Exact rational value of a float (every finite double is a dyadic rational)."""
    return Fraction(float(v))


def _sign(v: Fraction) -> int:
    return (v > 0) - (v < 0)


def exact_orient(a, b, c) -> int:
    """Sign of the orientation of ``a, b, c``: +1 counter-clockwise, -1 clockwise, 0 collinear."""
    ax, ay, bx, by, cx, cy = (_fr(v) for v in (*a, *b, *c))
    return _sign((bx - ax) * (cy - ay) - (by - ay) * (cx - ax))


def exact_incircle(a, b, c, d) -> int:
    """Sign of the incircle determinant: +1 when ``d`` is strictly inside the circle through
    the counter-clockwise ``a, b, c`` (-1 outside, 0 on it)."""
    ax, ay, bx, by, cx, cy, dx, dy = (_fr(v) for v in (*a, *b, *c, *d))
    adx, ady = ax - dx, ay - dy
    bdx, bdy = bx - dx, by - dy
    cdx, cdy = cx - dx, cy - dy
    alift = adx * adx + ady * ady
    blift = bdx * bdx + bdy * bdy
    clift = cdx * cdx + cdy * cdy
    det = (
        alift * (bdx * cdy - cdx * bdy)
        + blift * (cdx * ady - adx * cdy)
        + clift * (adx * bdy - bdx * ady)
    )
    return _sign(det)


def exact_twice_area(points, tri) -> Fraction:
    """Twice the signed area of triangle ``tri`` (indices into ``points``), exactly."""
    a, b, c = (points[i] for i in tri)
    ax, ay, bx, by, cx, cy = (_fr(v) for v in (*a, *b, *c))
    return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax)


def first_occurrence(points) -> np.ndarray:
    """``duplicate_of`` computed with a dictionary: -1 or the index of the first equal point."""
    seen: dict[tuple[float, float], int] = {}
    out = np.full(len(points), -1, dtype=np.int64)
    for i, (x, y) in enumerate(np.asarray(points, dtype=np.float64).reshape(-1, 2)):
        key = (float(x) + 0.0, float(y) + 0.0)  # + 0.0 folds -0.0 into 0.0
        if key in seen:
            out[i] = seen[key]
        else:
            seen[key] = i
    return out


def brute_delaunay_ok(points, triangles) -> bool:
    """True when no point lies strictly inside the circumcircle of any triangle (exact).

    Also requires every triangle to be counter-clockwise with positive area. O(t n) with
    Fractions: small inputs only.
    """
    pts = np.asarray(points, dtype=np.float64)
    for tri in np.asarray(triangles).reshape(-1, 3):
        a, b, c = (pts[i] for i in tri)
        if exact_orient(a, b, c) <= 0:
            return False
        for k in range(len(pts)):
            if k in tri:
                continue
            if exact_incircle(a, b, c, pts[k]) > 0:
                return False
    return True


def brute_convex_hull(points) -> set[int]:
    """Indices of the strict convex hull vertices (collinear points on hull edges excluded).

    Point ``i`` is a vertex when, for some other point ``j``, every point lies weakly to the
    left of the directed line ``i -> j`` and those on the line lie on ``j``'s side of ``i``
    (exact orientation). O(n^3): tiny inputs only.
    """
    pts = np.asarray(points, dtype=np.float64)
    uniq = np.flatnonzero(first_occurrence(pts) < 0).tolist()
    out = set()
    for i in uniq:
        others = [j for j in uniq if j != i]
        for j in others:
            ok = True
            for k in others:
                s = exact_orient(pts[i], pts[j], pts[k])
                if s < 0:
                    ok = False
                    break
                if s == 0:
                    d = pts[k] - pts[i]
                    e = pts[j] - pts[i]
                    if float(np.dot(d, e)) < 0:
                        ok = False
                        break
            if ok:
                out.add(i)
                break
    return out


def brute_nearest(sites, queries) -> tuple[np.ndarray, np.ndarray]:
    """Nearest site index (first occurrence on ties) and its squared distance, by brute force."""
    s = np.asarray(sites, dtype=np.float64).reshape(-1, 2)
    q = np.asarray(queries, dtype=np.float64).reshape(-1, 2)
    idx = np.zeros(len(q), dtype=np.int64)
    best = np.zeros(len(q))
    for start in range(0, len(q), 512):
        block = q[start : start + 512]
        d2 = ((block[:, None, :] - s[None, :, :]) ** 2).sum(-1)
        k = np.argmin(d2, axis=1)  # argmin returns the first occurrence of the minimum
        idx[start : start + 512] = k
        best[start : start + 512] = d2[np.arange(len(block)), k]
    return idx, best


def _clip_halfplane(poly: np.ndarray, q: np.ndarray, c: float) -> np.ndarray:
    """Clip a convex polygon (k, 2) to ``{x : q . x <= c}`` (one Sutherland-Hodgman step)."""
    s = poly @ q - c
    inside = s <= 0
    if inside.all():
        return poly
    if not inside.any():
        return poly[:0]
    out = []
    k = len(poly)
    for i in range(k):
        u, v = poly[i], poly[(i + 1) % k]
        su, sv = s[i], s[(i + 1) % k]
        if su <= 0:
            out.append(u)
        if (su < 0 < sv) or (sv < 0 < su):
            t = su / (su - sv)
            out.append(u + t * (v - u))
    return np.array(out).reshape(-1, 2)


def brute_voronoi(points, domain) -> np.ndarray:
    """Voronoi cells clipped to ``domain``, one half-plane at a time.

    Cell ``i`` is ``domain`` intersected with ``{x : |x - p_i| <= |x - p_j|}`` for every other
    distinct site ``j``. The first occurrence of a duplicated site owns the cell; later
    copies get an empty polygon.

    Parameters
    ----------
    points : (n, 2) array_like
    domain : shapely Polygon or MultiPolygon

    Returns
    -------
    (n,) object array of shapely geometries
    """
    pts = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    dup = first_occurrence(pts)
    uniq = np.flatnonzero(dup < 0)
    xmin, ymin, xmax, ymax = domain.bounds
    cells = np.full(len(pts), None, dtype=object)
    for i in range(len(pts)):
        if dup[i] >= 0:
            cells[i] = shapely.Polygon()
            continue
        p = pts[i]
        # Work in coordinates centred on the site so large offsets keep their precision.
        box = (
            np.array([[xmin, ymin], [xmax, ymin], [xmax, ymax], [xmin, ymax]], dtype=np.float64) - p
        )
        others = uniq[uniq != i]
        q_all = pts[others] - p
        order = np.argsort((q_all**2).sum(1), kind="stable")
        poly = box
        for j in order:
            if len(poly) == 0:
                break
            q = q_all[j]
            # The bisector is |q|/2 away from the site; once that exceeds the farthest
            # vertex of the current (convex) polygon no later half-plane can cut it.
            reach = np.sqrt((poly**2).sum(1).max())
            if 0.5 * np.hypot(q[0], q[1]) > reach * (1 + 1e-12):
                break
            poly = _clip_halfplane(poly, q, 0.5 * float(q @ q))
        if len(poly) < 3:
            cells[i] = shapely.Polygon()
            continue
        region = shapely.Polygon(poly + p)
        cells[i] = shapely.intersection(shapely.make_valid(region), domain)
    return cells


def all_triples(n: int):
    """Every index triple ``i < j < k`` below ``n`` (for exhaustive tiny checks)."""
    return combinations(range(n), 3)
