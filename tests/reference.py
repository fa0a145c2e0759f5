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
    return _sign(_incircle_det(ax - dx, ay - dy, bx - dx, by - dy, cx - dx, cy - dy))


def _incircle_det(adx, ady, bdx, bdy, cdx, cdy):
    """The incircle determinant from the three points' offsets to the fourth (Fractions,
    Python ints, or numpy object arrays of them: exact either way)."""
    alift = adx * adx + ady * ady
    blift = bdx * bdx + bdy * bdy
    clift = cdx * cdx + cdy * cdy
    return (
        alift * (bdx * cdy - cdx * bdy)
        + blift * (cdx * ady - adx * cdy)
        + clift * (adx * bdy - bdx * ady)
    )


def dyadic_integers(points) -> tuple[np.ndarray, int]:
    """Integers ``K`` (a numpy object array of Python ints) and one power of two ``s`` with
    ``points == K / s`` exactly: every finite double is ``numerator / 2**k``, and the
    largest of those denominators is a multiple of all the others."""
    pts = np.asarray(points, dtype=np.float64)
    ratios = [v.as_integer_ratio() for v in pts.ravel().tolist()]
    s = max((d for _, d in ratios), default=1)
    K = np.zeros(len(ratios), dtype=object)
    K[:] = [num * (s // d) for num, d in ratios]
    return K.reshape(pts.shape), s


def exact_incircle_signs(points, triangles, ti, pi) -> np.ndarray:
    """:func:`exact_incircle` of ``triangles[ti[m]]`` and ``points[pi[m]]`` for every ``m``.

    The same determinant in exact integer arithmetic: the points as integers over one common
    power of two (:func:`dyadic_integers`), which scales the determinant (of degree 4 in the
    coordinates) by a positive factor and so keeps its sign. Python ints in numpy object
    arrays: one conversion per point, not four Fractions per pair.
    """
    K, _ = dyadic_integers(np.asarray(points, dtype=np.float64).reshape(-1, 2))
    T = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
    ti = np.asarray(ti, dtype=np.int64)
    d = K[np.asarray(pi, dtype=np.int64)]
    adx, ady = (K[T[ti, 0], q] - d[:, q] for q in (0, 1))
    bdx, bdy = (K[T[ti, 1], q] - d[:, q] for q in (0, 1))
    cdx, cdy = (K[T[ti, 2], q] - d[:, q] for q in (0, 1))
    det = _incircle_det(adx, ady, bdx, bdy, cdx, cdy)
    return (det > 0).astype(np.int64) - (det < 0).astype(np.int64)


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


def exact_pixel_labels(key, labels, x, y, sites, metric="euclidean") -> np.ndarray:
    """Float argmin ``labels`` of a raster with its near ties decided in rationals.

    ``key (..., n)`` holds the float keys (squared distance, or the distance for
    ``"manhattan"``/``"chebyshev"``) of pixel centres ``x, y (...)`` to ``sites (n, 2)``;
    where keys lie within 16 ulps of a pixel's smallest, the exactly nearest site wins, exact
    ties to the lowest index. Returns the corrected labels (a new array).
    """
    out = np.array(labels, copy=True)
    k1 = np.take_along_axis(key, out[..., None], axis=-1)[..., 0]
    near = key <= k1[..., None] * (1.0 + 16.0 * 2.0**-53) + 1e-320

    def exact(qx, qy, i):
        dx, dy = abs(qx - _fr(sites[i, 0])), abs(qy - _fr(sites[i, 1]))
        if metric == "euclidean":
            return dx * dx + dy * dy
        return dx + dy if metric == "manhattan" else max(dx, dy)

    for idx in zip(*np.nonzero(near.sum(axis=-1) > 1), strict=True):
        qx, qy = _fr(x[idx]), _fr(y[idx])
        out[idx] = min(np.flatnonzero(near[idx]), key=lambda i, qx=qx, qy=qy: (exact(qx, qy, i), i))
    return out


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
    cells = np.full(len(pts), None, dtype=object)
    for i in range(len(pts)):
        if dup[i] >= 0:
            cells[i] = shapely.Polygon()
            continue
        cells[i] = _voronoi_cell(pts[i], pts[uniq[uniq != i]], domain)
    return cells


def _voronoi_cell(p: np.ndarray, others: np.ndarray, domain):
    """Cell of site ``p`` among the distinct sites ``others``, clipped to ``domain``.

    The half-planes are applied nearest site first with :func:`_clip_halfplane`. Most of
    them leave the polygon whole: a vectorised screen skips those that miss every vertex by
    far more than rounding, and each of the others is tried with the arithmetic of
    :func:`_clip_halfplane` itself, so the cell is the one the plain one-at-a-time loop
    builds, without its cost on cocircular inputs where every bisector is tried.
    """
    xmin, ymin, xmax, ymax = domain.bounds
    # Work in coordinates centred on the site so large offsets keep their precision.
    box = np.array([[xmin, ymin], [xmax, ymin], [xmax, ymax], [xmin, ymax]], dtype=np.float64) - p
    q_all = others - p
    order = np.argsort((q_all**2).sum(1), kind="stable")
    q_all = q_all[order]
    half = 0.5 * np.hypot(q_all[:, 0], q_all[:, 1])
    c_all = 0.5 * (q_all[:, 0] * q_all[:, 0] + q_all[:, 1] * q_all[:, 1])
    poly = box
    j, m = 0, len(q_all)
    while j < m and len(poly):
        # The bisector is |q|/2 away from the site; once that exceeds the farthest
        # vertex of the current (convex) polygon no later half-plane can cut it.
        reach = np.sqrt((poly**2).sum(1).max())
        beyond = half[j:] > reach * (1 + 1e-12)
        stop = j + (int(np.argmax(beyond)) if beyond.any() else m - j)
        qs, cs = q_all[j:stop], c_all[j:stop]
        side = poly[:, :1] * qs[:, 0] + poly[:, 1:] * qs[:, 1] - cs  # (vertices, half-planes)
        margin = 1e-9 * (reach * 2.0 * half[j:stop] + cs)  # far above rounding
        cut = None
        for k in (j + np.flatnonzero((side > -margin).any(0))).tolist():
            q = q_all[k]
            c = 0.5 * float(q @ q)
            if (poly @ q - c > 0).any():  # what _clip_halfplane decides
                cut = k
                break
        if cut is None:
            break
        poly = _clip_halfplane(poly, q, c)
        j = cut + 1
    if len(poly) < 3:
        return shapely.Polygon()
    region = shapely.Polygon(poly + p)
    return shapely.intersection(shapely.make_valid(region), domain)


def exact_cell(points, i: int, box) -> list[tuple[Fraction, Fraction]]:
    """Site ``i``'s Voronoi cell in ``box`` with every bisector cut exactly: Fraction vertices.

    ``points`` (n, 2) floats, ``box`` (xmin, ymin, xmax, ymax); sites equal to site ``i``
    are skipped. The ring is counter-clockwise, as the box's.
    """
    x0, y0, x1, y1 = (_fr(b) for b in box)
    ring = [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]
    px, py = _fr(points[i][0]), _fr(points[i][1])
    for j in range(len(points)):
        qx, qy = _fr(points[j][0]), _fr(points[j][1])
        if j == i or (qx == px and qy == py):
            continue
        # twice the signed side of each vertex: <= 0 on site i's side of the bisector
        val = [(qx - px) * (2 * a - px - qx) + (qy - py) * (2 * b - py - qy) for a, b in ring]
        if all(v <= 0 for v in val):
            continue
        out = []
        for k in range(len(ring)):
            v0, v1 = val[k], val[(k + 1) % len(ring)]
            (ax, ay), (bx, by) = ring[k], ring[(k + 1) % len(ring)]
            if v0 <= 0:
                out.append((ax, ay))
            if (v0 < 0 < v1) or (v1 < 0 < v0):
                t = v0 / (v0 - v1)
                out.append((ax + t * (bx - ax), ay + t * (by - ay)))
        ring = out
    return ring


def all_triples(n: int):
    """Every index triple ``i < j < k`` below ``n`` (for exhaustive tiny checks)."""
    return combinations(range(n), 3)


# ---------------------------------------------------------------------------------------------
# circumcentres
# ---------------------------------------------------------------------------------------------


def exact_circumcentre(a, b, c) -> tuple[float, float]:
    """Circumcentre of ``a, b, c`` computed exactly with Fractions, rounded once at the end.

    Each coordinate is the double nearest the true centre (Python rounds ``int / int``
    correctly). Raises ``ZeroDivisionError`` for exactly collinear points.
    """
    ax, ay, bx, by, cx, cy = (_fr(v) for v in (*a, *b, *c))
    dx, dy, ex, ey = bx - ax, by - ay, cx - ax, cy - ay
    det = 2 * (dx * ey - dy * ex)
    bl = dx * dx + dy * dy
    cl = ex * ex + ey * ey
    ux = ax + (ey * bl - dy * cl) / det
    uy = ay + (dx * cl - ex * bl) / det
    return float(ux), float(uy)


def exact_circumcentres(points, triangles) -> np.ndarray:
    """:func:`exact_circumcentre` of every triangle, as an ``(t, 2)`` array.

    The same formula in Python integers over one common power of two
    (:func:`dyadic_integers`); each coordinate is one ``int / int`` division, which Python
    rounds correctly, as ``float(Fraction)`` does. Raises ``ZeroDivisionError`` for an
    exactly collinear triangle.
    """
    K, s = dyadic_integers(np.asarray(points, dtype=np.float64).reshape(-1, 2))
    T = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
    ax, ay = K[T[:, 0], 0], K[T[:, 0], 1]
    dx, dy = K[T[:, 1], 0] - ax, K[T[:, 1], 1] - ay
    ex, ey = K[T[:, 2], 0] - ax, K[T[:, 2], 1] - ay
    det = 2 * (dx * ey - dy * ex)
    bl = dx * dx + dy * dy
    cl = ex * ex + ey * ey
    # a + n / det in the points' units: (A det + N) / (det s), A and N in integers
    ux = (ax * det + (ey * bl - dy * cl)) / (det * s)
    uy = (ay * det + (dx * cl - ex * bl)) / (det * s)
    return np.column_stack((ux.astype(np.float64), uy.astype(np.float64))).reshape(-1, 2)


# ---------------------------------------------------------------------------------------------
# moments
# ---------------------------------------------------------------------------------------------


def exact_ring_moments(ring, origin=(0.0, 0.0)) -> tuple[Fraction, Fraction, Fraction, Fraction]:
    """Signed area, first moments and polar second moment of a ring, exactly.

    ``ring`` is a ``(k, 2)`` sequence of vertices, closed or not. Returns the Fractions
    ``(∫1, ∫(x - ox), ∫(y - oy), ∫|x - o|^2)`` over the ring's interior, with the sign of its
    orientation (positive counter-clockwise), from the shoelace formulas.
    """
    xy = np.asarray(ring, dtype=np.float64).reshape(-1, 2)
    if len(xy) and np.array_equal(xy[0], xy[-1]):
        xy = xy[:-1]
    ox, oy = _fr(origin[0]), _fr(origin[1])
    pts = [(_fr(x) - ox, _fr(y) - oy) for x, y in xy.tolist()]
    m0 = mx = my = m2 = Fraction(0)
    for k, (x0, y0) in enumerate(pts):
        x1, y1 = pts[(k + 1) % len(pts)]
        cr = x0 * y1 - x1 * y0
        m0 += cr
        mx += (x0 + x1) * cr
        my += (y0 + y1) * cr
        m2 += (x0 * x0 + x0 * x1 + x1 * x1 + y0 * y0 + y0 * y1 + y1 * y1) * cr
    return m0 / 2, mx / 6, my / 6, m2 / 12


def exact_polygon_moments(geom, origin=(0.0, 0.0)) -> tuple[Fraction, Fraction, Fraction, Fraction]:
    """Area, first moments and polar second moment of a (Multi)Polygon about ``origin``.

    Exteriors add and holes subtract whatever their orientation; exact Fractions of the
    geometry's own (float) vertices.
    """
    total = [Fraction(0)] * 4
    for part in shapely.get_parts(geom):
        if part.is_empty:
            continue
        rings = [part.exterior, *part.interiors]
        for r, ring in enumerate(rings):
            mom = exact_ring_moments(np.asarray(ring.coords), origin)
            sign = 1 if mom[0] >= 0 else -1
            if r:
                sign = -sign
            total = [t + sign * m for t, m in zip(total, mom, strict=True)]
    return tuple(total)


def holds_exactly(ring, q) -> bool:
    """Whether the closed ring of float vertices (first == last) holds point ``q``, exactly.

    Points on the ring count as held (crossing parity, each turn as an exact Fraction).
    """
    inside = False
    qx, qy = (Fraction(float(v)) for v in q)
    pts = [(Fraction(float(x)), Fraction(float(y))) for x, y in ring]
    for (ax, ay), (bx, by) in zip(pts[:-1], pts[1:], strict=True):
        turn = (bx - ax) * (qy - ay) - (by - ay) * (qx - ax)
        if (ay > qy) != (by > qy):
            if turn == 0:
                return True
            if (turn > 0) == (by > ay):
                inside = not inside
        elif turn == 0 and min(ax, bx) <= qx <= max(ax, bx) and min(ay, by) <= qy <= max(ay, by):
            return True
    return inside


def exact_area(geom) -> Fraction:
    """The exact area (Fraction) of a (Multi)Polygon's own float vertices; holes subtract.

    The area of :func:`exact_polygon_moments`, by the same shoelace sum in integers: every
    coordinate of a ring is an integer over one power of two.
    """
    total = Fraction(0)
    for part in shapely.get_parts(geom):
        if part.is_empty:
            continue
        for r, ring in enumerate([part.exterior, *part.interiors]):
            area = abs(_ring_area(np.asarray(ring.coords)))
            total += -area if r else area
    return total


def _ring_area(ring) -> Fraction:
    """The signed shoelace area of a ring (closed or not) of floats, exactly."""
    xy = np.asarray(ring, dtype=np.float64).reshape(-1, 2)
    if len(xy) and np.array_equal(xy[0], xy[-1]):
        xy = xy[:-1]
    if not len(xy):
        return Fraction(0)
    ratios = [v.as_integer_ratio() for v in xy.ravel().tolist()]
    den = max(d for _, d in ratios)  # every denominator is a power of two
    ints = [n * (den // d) for n, d in ratios]
    xs, ys = ints[0::2], ints[1::2]
    cross = sum(
        x0 * y1 - x1 * y0
        for x0, y0, x1, y1 in zip(xs, ys, xs[1:] + xs[:1], ys[1:] + ys[:1], strict=True)
    )
    return Fraction(cross, 2 * den * den)


def triangulated_moments(cells, sites) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Mass, first and second moments of unit density about each site, from GEOS triangles.

    Independent of the shoelace formulas: each cell is cut into triangles by GEOS and the
    moments of a triangle are those of its centroid plus its spread.
    """
    n = len(cells)
    mass = np.zeros(n)
    first = np.zeros((n, 2))
    second = np.zeros(n)
    for i, cell in enumerate(cells):
        if cell.is_empty:
            continue
        tris = shapely.get_parts(shapely.constrained_delaunay_triangles(cell))
        for t in tris:
            a, b, c = shapely.get_coordinates(t)[:3] - sites[i]
            area = 0.5 * abs((b - a)[0] * (c - a)[1] - (b - a)[1] * (c - a)[0])
            g = (a + b + c) / 3
            mass[i] += area
            first[i] += area * g
            spread = ((a - g) ** 2 + (b - g) ** 2 + (c - g) ** 2).sum() / 12
            second[i] += area * ((g**2).sum() + spread)
    return mass, first, second


def pixel_density_moments(cells, sites, values, bounds) -> tuple[np.ndarray, np.ndarray]:
    """Mass and first moment of a raster density over each cell, from GEOS overlays.

    ``values`` is an ``(h, w)`` image covering ``bounds`` (row 0 at the top), 0 outside; the
    sum over pixels of value × (area, first moment about the site) of cell ∩ pixel.
    """
    h, w = values.shape
    x0, y0, x1, y1 = bounds
    dx, dy = (x1 - x0) / w, (y1 - y0) / h
    n = len(cells)
    mass = np.zeros(n)
    first = np.zeros((n, 2))
    for r in range(h):
        for c in range(w):
            pix = shapely.box(x0 + c * dx, y1 - (r + 1) * dy, x0 + (c + 1) * dx, y1 - r * dy)
            piece = shapely.intersection(cells, pix)
            a = shapely.area(piece)
            ok = a > 0
            g = shapely.get_coordinates(shapely.centroid(piece[ok]))
            mass[ok] += values[r, c] * a[ok]
            first[ok] += values[r, c] * a[ok, None] * (g - sites[ok])
    return mass, first


def brute_lloyd_step(points, domain) -> np.ndarray:
    """One Lloyd step: every site moves to the GEOS centroid of its :func:`brute_voronoi` cell.

    Sites whose cell is empty stay put (duplicates) unless they lie outside the domain (in a
    hole, or with other sites nearer to all of it): those move to the domain's nearest point.
    """
    z = np.array(points, dtype=np.float64).reshape(-1, 2)
    cells = brute_voronoi(z, domain)
    ok = ~shapely.is_empty(cells)
    z[ok] = shapely.get_coordinates(shapely.centroid(cells[ok]))
    for i in np.flatnonzero(~ok):
        p = shapely.Point(z[i])
        if not domain.covers(p):
            z[i] = shapely.shortest_line(domain, p).coords[0]
    return z


# ---------------------------------------------------------------------------------------------
# power diagrams
# ---------------------------------------------------------------------------------------------


def power_owner(points, weights) -> np.ndarray:
    """Index owning each site's coordinates: the heaviest copy, the first among equals."""
    pts = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    best: dict[tuple[float, float], int] = {}
    for i, (x, y) in enumerate(pts.tolist()):
        key = (x + 0.0, y + 0.0)
        if key not in best or weights[i] > weights[best[key]]:
            best[key] = i
    return np.array([best[(x + 0.0, y + 0.0)] for x, y in pts.tolist()], dtype=np.int64)


def brute_power(points, weights, domain) -> np.ndarray:
    """Power cells: cell ``i`` = domain ∩ every ``|x-p_i|^2 - w_i <= |x-p_j|^2 - w_j``.

    One half-plane per other owning site, no early stop (weights break the distance bound
    :func:`brute_voronoi` uses). Copies that :func:`power_owner` does not pick get an empty
    polygon, like cells that no half-plane leaves anything of.

    Returns
    -------
    (n,) object array of shapely geometries
    """
    pts = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    w = np.asarray(weights, dtype=np.float64)
    owner = power_owner(pts, w)
    x0, y0, x1, y1 = domain.bounds
    cells = []
    for i in range(len(pts)):
        if owner[i] != i:
            cells.append(shapely.Polygon())
            continue
        p = pts[i]
        poly = np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]]) - p
        for j in np.flatnonzero(owner == np.arange(len(pts))):
            if j == i or len(poly) == 0:
                continue
            d = pts[j] - p
            # the weight difference first: |d|^2 + w_i would round |d|^2 away when the
            # weights are huge and nearly equal
            poly = _clip_halfplane(poly, 2.0 * d, float(d @ d) + (w[i] - w[j]))
        if len(poly) < 3:
            cells.append(shapely.Polygon())
            continue
        cells.append(shapely.intersection(shapely.Polygon(poly + p).buffer(0), domain))
    return np.array(cells, dtype=object)


# ---------------------------------------------------------------------------------------------
# natural neighbours
# ---------------------------------------------------------------------------------------------


def brute_sibson(sites, queries, *, pad: float = 20.0) -> np.ndarray:
    """Sibson coordinates by their definition: the area each cell loses to an inserted query.

    For each query ``q`` the Voronoi cell of ``q`` among ``sites + [q]`` is built by brute
    force, and weight ``i`` is the area it takes from site ``i``'s :func:`brute_voronoi`
    cell, divided by its own area. Both diagrams are clipped to the sites' bounding box
    padded by ``pad`` times its size; a query whose new cell reaches that box (outside the
    convex hull) raises ``ValueError``. A query on a site gets weight 1 there.

    Returns
    -------
    (m, n) float64
        Row ``k`` holds the weights of query ``k``; each row sums to 1.
    """
    s = np.asarray(sites, dtype=np.float64).reshape(-1, 2)
    q = np.asarray(queries, dtype=np.float64).reshape(-1, 2)
    lo, hi = s.min(0), s.max(0)
    margin = pad * (hi - lo).max()
    box = shapely.box(lo[0] - margin, lo[1] - margin, hi[0] + margin, hi[1] + margin)
    before = brute_voronoi(s, box)
    out = np.zeros((len(q), len(s)))
    for k, qk in enumerate(q):
        hit = np.flatnonzero((s == qk).all(1))
        if len(hit):
            out[k, hit[0]] = 1.0
            continue
        cell = _voronoi_cell(qk, s[first_occurrence(s) < 0], box)
        if shapely.intersects(cell, box.exterior):
            raise ValueError(f"query {qk.tolist()} is outside the sites' convex hull")
        stolen = shapely.area(shapely.intersection(before, cell))
        stolen[stolen < 1e-12 * cell.area] = 0.0  # cells that only touch the new one
        out[k] = stolen / stolen.sum()
    return out


def check_power_fit(fit, pts, targets, dom, rtol, seed=0, samples=4000) -> None:
    """Assert a ``power_fit`` result independently of the engine.

    Each cell clipped to ``dom`` by shapely has its target area to ``2 * rtol``, the cells
    tile the domain, and random points of the domain clear of a power tie lie in the cell
    of the site least in power distance (brute force over all sites).
    """
    cells = np.asarray(fit.cells, dtype=object)
    t = np.asarray(targets, dtype=np.float64)
    areas = shapely.area(shapely.intersection(cells, dom))
    assert np.max(np.abs(areas - t) / t) <= 2 * rtol
    assert abs(shapely.area(shapely.union_all(cells)) - dom.area) <= 1e-9 * dom.area
    rng = np.random.default_rng(seed)
    x0, y0, x1, y1 = dom.bounds
    q = rng.uniform((x0, y0), (x1, y1), size=(samples, 2))
    q = q[shapely.contains_xy(dom, q[:, 0], q[:, 1])]
    w = np.asarray(fit.weights)
    pw = ((q[:, None, :] - pts[None, :, :]) ** 2).sum(axis=2) - w[None, :]
    order = np.sort(pw, axis=1)
    clear = order[:, 1] - order[:, 0] > 1e-9
    owner = np.argmin(pw, axis=1)[clear]
    assert shapely.contains(cells[owner], shapely.points(q[clear])).all()


def periodic_reference_areas(points, box, k: int = 2) -> np.ndarray:
    """Areas of the original sites' cells in the plain diagram of (2k + 1)^2 copies of ``box``.

    The slow reference of a periodic diagram: every site copied by whole box sizes, the
    copies' ordinary diagram in the grown box, the middle copy's areas read back.
    """
    import voroforge as vf

    x0, y0, x1, y1 = box
    w, h = x1 - x0, y1 - y0
    shifts = [(a * w, b * h) for a in range(-k, k + 1) for b in range(-k, k + 1)]
    ext = np.concatenate([points + s for s in shifts])
    d = vf.voronoi(ext, (x0 - k * w, y0 - k * h, x1 + k * w, y1 + k * h))
    mid = shifts.index((0.0, 0.0))
    return np.asarray(d.areas)[mid * len(points) : (mid + 1) * len(points)]
