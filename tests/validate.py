"""Invariant checks run on every triangulation and diagram the tests build.

``validate_triangulation`` and ``validate_diagram`` raise ``AssertionError`` with a message
naming the broken invariant. They check properties any correct answer has (never a stored
snapshot), so they can be applied to any input.
"""

from __future__ import annotations

from collections import defaultdict

import numpy as np
import shapely
from scipy.spatial import cKDTree

from reference import exact_circumcentres, exact_incircle_signs, exact_orient, first_occurrence

# Nothing here calls the engine's predicates or circumcentres: float filters with Shewchuk's
# error bounds (doubled for margin) decide the clear cases and reference.py's exact rational
# arithmetic the rest, so an error in the engine's own predicates cannot hide itself.
_EPS = 2.0**-53
_CCW_BOUND = (3.0 + 16.0 * _EPS) * _EPS
_ICC_BOUND = (10.0 + 96.0 * _EPS) * _EPS
#: Circumcentres: allowed error, in units of the conditioning bound of ``_circumcentre_tol``.
CIRCUMCENTRE_ULPS = 16.0
#: Above this many points the empty-circle check only tests points near each circumcentre.
EXHAUSTIVE_MAX = 2000


# ---------------------------------------------------------------------------------------------
# triangulations
# ---------------------------------------------------------------------------------------------


def _halfedge_ends(triangles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    flat = triangles.ravel().astype(np.int64)
    nxt = triangles[:, [1, 2, 0]].ravel().astype(np.int64)
    return flat, nxt


def _normalised(pts: np.ndarray) -> np.ndarray:
    """``pts`` scaled by a power of two (exactly) so the largest magnitude is in [0.5, 1).

    The float checks below then neither overflow nor underflow for inputs at any scale.
    """
    big = np.abs(pts).max(initial=0.0)
    return np.ldexp(pts, -int(np.frexp(big)[1])) if big > 0 else pts


def _all_collinear(pts: np.ndarray) -> bool:
    """Exactly: do all the (unique) points lie on one line?"""
    if len(pts) < 3:
        return True
    a = pts[0]
    far = np.argmax(((pts - a) ** 2).sum(1))
    b = pts[far]
    return all(exact_orient(a, b, c) == 0 for c in pts)


def orient_signs(a: np.ndarray, b: np.ndarray, c: np.ndarray) -> np.ndarray:
    """Exact signs of ``orient(a[k], b[k], c[k])`` for ``(m, 2)`` arrays (+1 counter-clockwise).

    A float filter settles the clear cases; the rest go to :func:`reference.exact_orient`.
    """
    a, b, c = (np.asarray(v, dtype=np.float64).reshape(-1, 2) for v in (a, b, c))
    left = (a[:, 0] - c[:, 0]) * (b[:, 1] - c[:, 1])
    right = (a[:, 1] - c[:, 1]) * (b[:, 0] - c[:, 0])
    det = left - right
    bound = 2.0 * _CCW_BOUND * (np.abs(left) + np.abs(right))
    out = np.sign(det).astype(np.int64)
    for k in np.flatnonzero(~(np.abs(det) > bound)):  # also NaN or inf: decide exactly
        out[k] = exact_orient(a[k], b[k], c[k])
    return out


def _incircle_unsure(pts, tri, ti, pi):
    """Of the (triangle, point) pairs, those the float incircle filter cannot prove <= 0."""
    a, b, c = (pts[tri[ti, j]] for j in range(3))
    d = pts[pi]
    adx, ady = a[:, 0] - d[:, 0], a[:, 1] - d[:, 1]
    bdx, bdy = b[:, 0] - d[:, 0], b[:, 1] - d[:, 1]
    cdx, cdy = c[:, 0] - d[:, 0], c[:, 1] - d[:, 1]
    bc, cb, ca, ac, ab, ba = bdx * cdy, cdx * bdy, cdx * ady, adx * cdy, adx * bdy, bdx * ady
    al, bl, cl = adx * adx + ady * ady, bdx * bdx + bdy * bdy, cdx * cdx + cdy * cdy
    det = al * (bc - cb) + bl * (ca - ac) + cl * (ab - ba)
    perm = (np.abs(bc) + np.abs(cb)) * al + (np.abs(ca) + np.abs(ac)) * bl
    perm += (np.abs(ab) + np.abs(ba)) * cl
    unsure = ~(det <= -2.0 * _ICC_BOUND * perm)
    return ti[unsure], pi[unsure]


def _incircle_candidates(pts: np.ndarray, triangles: np.ndarray, cand: np.ndarray):
    """(triangle, point) pairs whose incircle sign the float filter cannot prove <= 0.

    Same filter and error bound as Shewchuk's (doubled for margin), evaluated with numpy:
    everything else is certainly outside or on the circumcircle.
    """
    out_t, out_p = [], []
    cx, cy = pts[cand, 0], pts[cand, 1]
    block = max(1, 400_000 // max(len(cand), 1))
    for s in range(0, len(triangles), block):
        tri = triangles[s : s + block]
        a, b, c = pts[tri[:, 0]], pts[tri[:, 1]], pts[tri[:, 2]]
        adx = a[:, :1] - cx
        ady = a[:, 1:] - cy
        bdx = b[:, :1] - cx
        bdy = b[:, 1:] - cy
        cdx = c[:, :1] - cx
        cdy = c[:, 1:] - cy
        bc = bdx * cdy
        cb = cdx * bdy
        ca = cdx * ady
        ac = adx * cdy
        ab = adx * bdy
        ba = bdx * ady
        al = adx * adx + ady * ady
        bl = bdx * bdx + bdy * bdy
        cl = cdx * cdx + cdy * cdy
        det = al * (bc - cb) + bl * (ca - ac) + cl * (ab - ba)
        perm = (np.abs(bc) + np.abs(cb)) * al
        perm += (np.abs(ca) + np.abs(ac)) * bl
        perm += (np.abs(ab) + np.abs(ba)) * cl
        unsure = det > -2.0 * _ICC_BOUND * perm
        unsure &= cand[None, :] != tri[:, :1]
        unsure &= cand[None, :] != tri[:, 1:2]
        unsure &= cand[None, :] != tri[:, 2:3]
        ti, pi = np.nonzero(unsure)
        out_t.append(ti + s)
        out_p.append(cand[pi])
    if not out_t:
        return np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
    return np.concatenate(out_t), np.concatenate(out_p)


def _near_circumcentre_candidates(pts, triangles, cand):
    """(triangle, point) pairs with the point near the circumcircle (KD-tree, padded radius)."""
    tree = cKDTree(pts[cand])
    p = pts[triangles]
    a = p[:, 0]
    d = p[:, 1] - a
    e = p[:, 2] - a
    bl = (d**2).sum(1)
    cl = (e**2).sum(1)
    den = 0.5 / (d[:, 0] * e[:, 1] - d[:, 1] * e[:, 0])
    centre = (
        a
        + np.stack(((e[:, 1] * bl - d[:, 1] * cl), (d[:, 0] * cl - e[:, 0] * bl)), 1) * den[:, None]
    )
    r = np.sqrt(((p - centre[:, None, :]) ** 2).sum(-1)).max(1)
    span = np.abs(p - centre[:, None, :]).max((1, 2)) + np.abs(centre).max(1)
    pad = r * 1e-6 + span * 1e-9
    lists = tree.query_ball_point(centre, r + pad)
    ti = np.repeat(np.arange(len(triangles)), [len(x) for x in lists])
    pi = cand[np.concatenate([np.asarray(x, dtype=np.int64) for x in lists])] if len(ti) else ti
    keep = (pi != triangles[ti, 0]) & (pi != triangles[ti, 1]) & (pi != triangles[ti, 2])
    return ti[keep], pi[keep]


def check_empty_circumcircles(pts: np.ndarray, triangles: np.ndarray, cand: np.ndarray) -> None:
    """No point of ``cand`` strictly inside any triangle's circumcircle (exact incircle)."""
    if len(triangles) == 0 or len(cand) == 0:
        return
    if len(cand) <= EXHAUSTIVE_MAX:
        ti, pi = _incircle_candidates(pts, triangles, cand)
    else:
        ti, pi = _near_circumcentre_candidates(pts, triangles, cand)
        ti, pi = _incircle_unsure(pts, triangles, ti, pi)
    # every pair the filter left, exactly (reference.exact_incircle's determinant in integers)
    inside = np.flatnonzero(exact_incircle_signs(pts, triangles, ti, pi) > 0)[:5]
    bad = list(zip(ti[inside].tolist(), pi[inside].tolist(), strict=True))
    assert not bad, f"points inside circumcircles (triangle, point): {bad}"


def validate_triangulation(tri) -> None:
    """Assert every structural and Delaunay invariant of a :class:`Triangulation`."""
    pts = np.asarray(tri.points, dtype=np.float64)
    n = len(pts)
    assert pts.shape == (n, 2)
    pts = _normalised(pts)
    dup = first_occurrence(pts)
    assert np.array_equal(np.asarray(tri.duplicate_of), dup), "duplicate_of is wrong"
    uniq = np.flatnonzero(dup < 0)
    T = np.asarray(tri.triangles)
    he = np.asarray(tri.halfedges)
    hull = np.asarray(tri.hull).astype(np.int64)
    assert T.ndim == 2 and T.shape[1] == 3, f"triangles shape {T.shape}"
    assert np.issubdtype(T.dtype, np.integer) and np.issubdtype(he.dtype, np.integer)
    t = len(T)
    assert he.shape == (3 * t,), f"halfedges shape {he.shape} for {t} triangles"
    assert len(set(hull.tolist())) == len(hull), "hull repeats a point"
    assert np.all(dup[hull] < 0) if len(hull) else True, "hull uses a duplicate point"

    if t == 0:
        assert _all_collinear(pts[uniq]), "no triangles although the points are not collinear"
        assert set(hull.tolist()) == set(uniq.tolist()), "collinear hull must list every point"
        if len(hull) >= 2:
            d = pts[hull[-1]] - pts[hull[0]]
            proj = (pts[hull] - pts[hull[0]]) @ d
            assert np.all(np.diff(proj) > 0), "collinear hull is not in order along the line"
        return

    assert T.min() >= 0 and T.max() < n, "triangle index out of range"
    used = np.unique(T)
    assert np.array_equal(used, uniq), (
        f"triangles must use exactly the unique points: missing "
        f"{np.setdiff1d(uniq, used)[:10]}, extra {np.setdiff1d(used, uniq)[:10]}"
    )

    # counter-clockwise, positive area (sign-exact)
    bad = np.flatnonzero(orient_signs(pts[T[:, 0]], pts[T[:, 1]], pts[T[:, 2]]) <= 0)
    assert not len(bad), f"triangles not strictly counter-clockwise: {bad[:10].tolist()}"

    # halfedges
    start, end = _halfedge_ends(T)
    assert he.min() >= -1 and he.max() < 3 * t, "halfedge out of range"
    inner = np.flatnonzero(he >= 0)
    twin = he[inner].astype(np.int64)
    assert np.all(twin != inner), "halfedge is its own twin"
    assert np.array_equal(he[twin], inner), "halfedges not symmetric"
    assert np.array_equal(start[twin], end[inner]) and np.array_equal(end[twin], start[inner]), (
        "twin halfedges do not have reversed endpoints"
    )
    directed = start * n + end
    assert len(np.unique(directed)) == 3 * t, "a directed edge appears twice (non-manifold)"
    boundary = np.flatnonzero(he < 0)
    reverse = set((end[boundary] * n + start[boundary]).tolist())
    assert not reverse & set(directed.tolist()), "a hull halfedge has an unlinked twin"

    # hull is the boundary cycle, counter-clockwise and convex
    h = len(hull)
    hull_edges = set((hull * n + np.roll(hull, -1)).tolist())
    bnd_edges = set((start[boundary] * n + end[boundary]).tolist())
    assert hull_edges == bnd_edges, "hull is not the cycle of boundary halfedges"
    hp = pts[hull]
    turns = orient_signs(np.roll(hp, 1, axis=0), hp, np.roll(hp, -1, axis=0))
    assert turns.min() >= 0, "hull is not convex and counter-clockwise"  # collinear allowed
    x, y = hp[:, 0] - hp[0, 0], hp[:, 1] - hp[0, 1]
    assert (x * np.roll(y, -1) - np.roll(x, -1) * y).sum() > 0, "hull is clockwise"

    # counts: Euler V - E + F = 1 and t = 2 n' - 2 - h
    nu = len(uniq)
    edges = (3 * t + h) // 2
    assert (3 * t + h) % 2 == 0
    assert nu - edges + t == 1, f"Euler: V={nu} E={edges} F={t}"
    assert t == 2 * nu - 2 - h, f"{t} triangles, expected 2*{nu}-2-{h}"

    check_empty_circumcircles(pts, T.astype(np.int64), uniq)
    if hasattr(tri, "circumcenters"):  # a real Triangulation (tests also validate plain records)
        scale = np.abs(np.asarray(tri.points, dtype=np.float64)).max(initial=0.0)
        shift = -int(np.frexp(scale)[1]) if scale > 0 else 0
        check_circumcentres(pts, T.astype(np.int64), np.ldexp(np.asarray(tri.circumcenters), shift))


def _circumcentre_tol(pts: np.ndarray, triangles: np.ndarray) -> np.ndarray:
    """Error a float circumcentre may have, from the conditioning of each triangle.

    With ``L`` the longest edge and ``D`` twice the area, the centre's offset from a corner
    is ``N / (2 D)`` with ``|N| <= L^3``: rounding ``N`` costs ``eps L^3 / D`` and rounding
    ``D`` (relative error ``eps L^2 / D``) as much again times ``R / L <= L^2 / D``; plus an
    ulp of the coordinates themselves. ``CIRCUMCENTRE_ULPS`` times that.
    """
    p = pts[triangles]
    edges = p - np.roll(p, -1, axis=1)
    longest = np.sqrt((edges**2).sum(-1).max(1))
    d, e = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]
    twice = np.abs(d[:, 0] * e[:, 1] - d[:, 1] * e[:, 0])
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        cond = longest**2 / twice
        tol = CIRCUMCENTRE_ULPS * _EPS * longest * cond * (1.0 + cond)
    return tol + 2.0 * np.spacing(np.abs(p).max((1, 2)))


def check_circumcentres(pts: np.ndarray, triangles: np.ndarray, centres: np.ndarray) -> None:
    """``centres[k]`` is the circumcentre of triangle ``k`` to within its conditioning.

    The reference is reference.py's exact rational circumcentre, rounded once (an
    independent formula), for every triangle up to ``EXHAUSTIVE_MAX`` of them; above that
    a float formula of its own screens them and the exact one judges the suspects.
    Triangles too ill-conditioned for any float centre (infinite bound) are not judged.
    """
    centres = np.asarray(centres, dtype=np.float64)
    assert centres.shape == (len(triangles), 2), f"circumcenters shape {centres.shape}"
    tol = _circumcentre_tol(pts, triangles)
    judged = np.flatnonzero(np.isfinite(tol))
    if len(triangles) > EXHAUSTIVE_MAX:
        p = pts[triangles[judged]].astype(np.longdouble)
        d, e = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]
        with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
            den = 2 * (d[:, 0] * e[:, 1] - d[:, 1] * e[:, 0])
            bl, cl = (d**2).sum(1), (e**2).sum(1)
            ux = p[:, 0, 0] + (e[:, 1] * bl - d[:, 1] * cl) / den
            uy = p[:, 0, 1] + (d[:, 0] * cl - e[:, 0] * bl) / den
            err = np.maximum(np.abs(ux - centres[judged, 0]), np.abs(uy - centres[judged, 1]))
        judged = judged[~(err <= 0.5 * tol[judged])]
    want = exact_circumcentres(pts, triangles[judged])  # reference.exact_circumcentre's, batched
    off = ~(np.abs(centres[judged] - want).max(1, initial=0.0) <= tol[judged])
    bad = [
        (k, centres[k].tolist(), w.tolist())
        for k, w in zip(judged[off][:3].tolist(), want[off][:3], strict=True)
    ]
    assert not bad, f"circumcentres off (triangle, got, exact): {bad}"


# ---------------------------------------------------------------------------------------------
# diagrams
# ---------------------------------------------------------------------------------------------


def _csr_pairs(indptr, indices, n) -> set[tuple[int, int]]:
    indptr = np.asarray(indptr)
    indices = np.asarray(indices)
    assert indptr.shape == (n + 1,), f"indptr shape {indptr.shape}"
    assert indptr[0] == 0 and indptr[-1] == len(indices) and np.all(np.diff(indptr) >= 0)
    src = np.repeat(np.arange(n), np.diff(indptr))
    assert len(indices) == 0 or (indices.min() >= 0 and indices.max() < n)
    assert np.all(src != indices), "a cell is its own neighbour"
    directed = set(zip(src.tolist(), indices.tolist(), strict=True))
    assert len(directed) == len(indices), "a neighbour is listed twice"
    assert all((j, i) in directed for i, j in directed), "neighbours are not symmetric"
    return {(i, j) for i, j in directed if i < j}


def domain_scale(geom) -> float:
    xmin, ymin, xmax, ymax = geom.bounds
    return float(max(xmax - xmin, ymax - ymin))


def overlay_frame(dom) -> tuple[np.ndarray, float]:
    """Origin and snap grid for robust overlays of geometries in the domain ``dom``."""
    origin = np.array(dom.centroid.coords[0]) if dom.area > 0 else np.zeros(2)
    return origin, 1e-12 * domain_scale(dom)


def symmetric_difference_areas(a, b, dom) -> np.ndarray:
    """Area of ``a[i] ^ b[i]`` computed in the (centred, snap-rounded) frame of ``dom``.

    Snapping moves each vertex by at most the grid, so the result is also returned less
    ``4 * grid * perimeter`` (clamped at zero): what remains is a real difference.
    """
    origin, grid = overlay_frame(dom)
    a = shapely.transform(np.asarray(a, dtype=object), lambda xy: xy - origin)
    b = shapely.transform(np.asarray(b, dtype=object), lambda xy: xy - origin)
    raw = shapely.area(shapely.symmetric_difference(a, b, grid_size=grid))
    slack = 4 * grid * (shapely.length(a) + shapely.length(b))
    return np.maximum(raw - slack, 0.0)


def validate_diagram(d, points, domain=None, *, samples: int = 2000, seed: int = 0) -> None:
    """Assert the invariants of a clipped Voronoi diagram ``d`` of ``points``.

    Parameters
    ----------
    d : Diagram
    points : (n, 2) array_like
        The sites as given to ``vf.voronoi``.
    domain : shapely geometry, optional
        The expected domain; ``d.boundary`` is used (and compared with it) when given.
    samples : int
        Random points of the domain checked for nearest-site ownership.
    """
    pts = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    n = len(pts)
    sites = np.asarray(d.sites)
    if not np.array_equal(sites, pts):
        # documented: only values below 2**-188 of the largest magnitude may be rounded
        big = np.abs(pts).max(initial=0.0)
        moved = sites != pts
        assert np.all(np.abs(pts[moved]) < big * 2.0**-186), "sites differ from the input"
        assert np.all(np.abs(sites - pts) <= big * 2.0**-238), "sites moved too far"
        pts = sites
    dom = d.boundary
    assert dom is not None and not dom.is_empty and dom.is_valid
    area = dom.area
    scale = domain_scale(dom)
    # absolute tolerance: relative to the domain's size, but never below a few ulps of its
    # coordinates (at x = 4e6 one ulp is 1e-9)
    tol = 1e-9 * scale + 8 * np.spacing(np.abs(dom.bounds).max())
    if domain is not None:
        diff = symmetric_difference_areas([dom], [domain], domain)[0]
        assert diff <= 1e-12 * domain.area, f"boundary differs from the domain by area {diff}"

    cells = np.asarray(d.cells, dtype=object)
    assert cells.shape == (n,), f"cells shape {cells.shape}"
    dup = first_occurrence(pts)
    assert np.array_equal(np.asarray(d.duplicate_of), dup), "duplicate_of is wrong"
    areas = np.asarray(d.areas, dtype=np.float64)
    centroids = np.asarray(d.centroids, dtype=np.float64)
    assert areas.shape == (n,) and centroids.shape == (n, 2)
    if n == 0:
        return

    types = shapely.get_type_id(cells)
    assert np.all(np.isin(types, [3, 6])), f"cells must be (Multi)Polygons, got types {set(types)}"
    assert np.all(shapely.is_valid(cells)), (
        f"invalid cells: {[shapely.is_valid_reason(c) for c in cells if not c.is_valid][:3]}"
    )
    empty = shapely.is_empty(cells)
    assert np.all(empty[dup >= 0]), "duplicate sites must have empty cells"

    # areas and centroids are those of the geometries
    geom_area = shapely.area(cells)
    assert np.allclose(areas, geom_area, rtol=1e-9, atol=1e-12 * area), "areas != cell areas"
    assert np.all(areas[empty] == 0)
    assert np.all(np.isnan(centroids[empty])), "empty cells must have NaN centroids"
    ne = ~empty
    cen = shapely.get_coordinates(shapely.centroid(cells[ne]))
    assert np.allclose(centroids[ne], cen, rtol=0, atol=tol), "centroids != cell centroids"

    # the cells tile the domain. Overlays run on copies moved to the domain's centre and
    # snap-rounded to a grid far below the tolerances: GEOS's floating overlay can return
    # nonsense for cells whose shared vertices differ in the last bit.
    total = areas.sum()
    assert abs(total - area) <= 1e-9 * area, f"areas sum to {total}, domain area {area}"
    origin, grid = overlay_frame(dom)
    loc = shapely.transform(cells, lambda xy: xy - origin)
    dom_loc = shapely.transform(dom, lambda xy: xy - origin)
    otol = 1e-9 * area + 4 * grid * (shapely.length(cells).sum() + dom.length)
    union = shapely.union_all(loc[ne], grid_size=grid)
    assert abs(union.area - area) <= otol, f"union area {union.area} != {area}"
    outside = shapely.difference(union, dom_loc, grid_size=grid).area
    assert outside <= otol, f"cells extend outside the domain by area {outside}"
    tree = shapely.STRtree(cells)
    ii, jj = tree.query(cells, predicate="intersects")
    keep = ii < jj
    ii, jj = ii[keep], jj[keep]
    overlap = shapely.area(shapely.intersection(loc[ii], loc[jj], grid_size=grid))
    worst = [(int(ii[k]), int(jj[k]), float(overlap[k])) for k in np.argsort(-overlap)[:3]]
    assert overlap.sum() <= otol, f"cells overlap (i, j, area): {worst}"

    # each site inside the domain lies in its own cell
    site_geoms = shapely.points(pts)
    inside = shapely.covers(dom, site_geoms) & (dup < 0)
    far = ~shapely.dwithin(cells[inside], site_geoms[inside], tol)
    assert not far.any(), f"sites not in their own cell: {np.flatnonzero(inside)[far][:10]}"

    # random points belong to the cell of their nearest site
    uniq = np.flatnonzero(dup < 0)
    rng = np.random.default_rng(seed)
    xmin, ymin, xmax, ymax = dom.bounds
    q = rng.uniform((xmin, ymin), (xmax, ymax), size=(4 * samples, 2))
    q = q[shapely.contains_xy(dom, q[:, 0], q[:, 1])][:samples]
    # plus a point inside every cell, so the check runs however thin the domain is
    q = np.concatenate((q, shapely.get_coordinates(shapely.point_on_surface(cells[ne]))))
    assert len(q) > 0 or not ne.any(), "no sample points although some cells are not empty"
    if len(q):
        k = min(3, len(uniq))
        dist, idx = cKDTree(pts[uniq]).query(q, k=k)
        dist = dist.reshape(len(q), k)
        idx = uniq[idx.reshape(len(q), k)]
        qg = shapely.points(q)
        ok = shapely.covers(cells[idx[:, 0]], qg)
        for r in np.flatnonzero(~ok):
            ties = idx[r][dist[r] <= dist[r, 0] * (1 + 1e-9) + 1e-12 * scale]
            if not any(cells[j].covers(qg[r]) or cells[j].distance(qg[r]) <= tol for j in ties):
                raise AssertionError(
                    f"sample {q[r].tolist()} is not in the cell of its nearest site {idx[r, 0]}"
                )

    # neighbours and edges
    indptr, indices = d.neighbors
    nb = _csr_pairs(indptr, indices, n)
    coords, pairs = d.edges
    coords = np.asarray(coords, dtype=np.float64)
    pairs = np.asarray(pairs)
    m = len(pairs)
    assert coords.shape == (m, 2, 2) and pairs.shape == (m, 2), "edges have the wrong shape"
    if m == 0:
        assert not nb, "neighbours without edges"
    else:
        lo = np.minimum(pairs[:, 0], pairs[:, 1]).tolist()
        hi = np.maximum(pairs[:, 0], pairs[:, 1]).tolist()
        assert set(zip(lo, hi, strict=True)) == nb, "neighbors != edge pairs"
        _check_edges(coords, pairs, cells, pts, dup, dom, tol)
    _check_no_missing_neighbours(cells, pts, dup, nb, tree, tol, scale)


def _check_edges(coords, pairs, cells, pts, dup, dom, tol) -> None:
    """Edges: on their pair's bisector, on both cells' boundaries, once, ends at vertices."""
    n = len(pts)
    lo = np.minimum(pairs[:, 0], pairs[:, 1])
    hi = np.maximum(pairs[:, 0], pairs[:, 1])
    assert pairs.min() >= 0 and pairs.max() < n and np.all(pairs[:, 0] != pairs[:, 1])
    assert np.all(dup[pairs] < 0), "an edge belongs to a duplicate site"
    length = np.hypot(*(coords[:, 1] - coords[:, 0]).T)
    assert np.all(length > 0), "zero-length edge"
    # on the bisector of its two sites
    for end in (0, 1):
        da = np.hypot(*(coords[:, end] - pts[pairs[:, 0]]).T)
        db = np.hypot(*(coords[:, end] - pts[pairs[:, 1]]).T)
        bad = np.abs(da - db) > 1e-9 * (da + db) + tol
        assert not bad.any(), f"edges off the bisector: {np.flatnonzero(bad)[:10]}"
    # an end away from the domain's boundary is a Voronoi vertex: no site is nearer than the
    # edge's own two and a third is as near (a wrong circumcentre moves it off that circle)
    uniq = np.flatnonzero(dup < 0)
    if len(uniq) >= 3:
        ends = coords.reshape(-1, 2)
        inner = shapely.distance(dom.boundary, shapely.points(ends)) > tol
        own = np.repeat(pairs, 2, axis=0)[inner]
        x = ends[inner]
        dist, _ = cKDTree(pts[uniq]).query(x, k=3)
        dist = dist.reshape(len(x), 3)
        mine = np.hypot(*(x - pts[own[:, 0]]).T)
        slack = 1e-9 * (mine + dist[:, 2]) + tol
        bad = ~(mine <= dist[:, 0] + slack) | ~(dist[:, 2] <= dist[:, 0] + slack)
        assert not bad.any(), f"edge ends that are not Voronoi vertices: {x[bad][:5].tolist()}"
    # on both cells' boundaries
    t = np.linspace(0, 1, 5)
    along = coords[:, :1] + t[None, :, None] * (coords[:, 1:] - coords[:, :1])
    probe = shapely.points(along)
    bounds = shapely.boundary(cells)
    for side in (0, 1):
        gap = shapely.distance(bounds[pairs[:, side]][:, None], probe).max(1)
        bad = gap > tol
        assert not bad.any(), f"edges not on the boundary of cell {side}: {np.flatnonzero(bad)[:5]}"
    # each piece of shared boundary once
    groups: dict[tuple[int, int], list[int]] = defaultdict(list)
    for k, key in enumerate(zip(lo.tolist(), hi.tolist(), strict=True)):
        groups[key].append(k)
    for key, ks in groups.items():
        if len(ks) > 1:
            lines = shapely.linestrings(coords[ks])
            merged = shapely.union_all(lines).length
            assert merged >= length[ks].sum() * (1 - 1e-9), f"edges of pair {key} overlap"


def _check_no_missing_neighbours(cells, pts, dup, nb, tree, tol, scale) -> None:
    """Every shared boundary of positive length is an edge (and so a neighbour pair)."""
    bounds = shapely.boundary(cells)
    # cells narrower than ``tol`` (sites closer than it) would all look adjacent: shrink it
    uniq = np.flatnonzero(dup < 0)
    if len(uniq) > 1:
        spacing = cKDTree(pts[uniq]).query(pts[uniq], k=2)[0][:, 1].min()
        near_tol = min(tol, 0.01 * spacing)
    else:
        near_tol = tol
    near_i, near_j = tree.query(cells, predicate="dwithin", distance=near_tol)
    keep = near_i < near_j
    near_i, near_j = near_i[keep], near_j[keep]
    missing = [
        (i, j) for i, j in zip(near_i.tolist(), near_j.tolist(), strict=True) if (i, j) not in nb
    ]
    if missing:
        a = np.array(missing)
        # each cell buffered once (cells meeting at one vertex make ~n^2 / 2 such pairs)
        grown = np.full(len(cells), None, dtype=object)
        used = np.unique(a[:, 1])
        grown[used] = shapely.buffer(cells[used], tol)
        shared = shapely.length(shapely.intersection(bounds[a[:, 0]], grown[a[:, 1]]))
        # two cells touching at a corner share ~2 sqrt(2) tol of buffered boundary: tol has
        # a few ulps of the coordinates' magnitude in it (far from the origin, not tiny)
        bad = shared > 1e-6 * scale + 4.0 * tol
        assert not bad.any(), f"cells share a boundary but are not neighbours: {a[bad][:5]}"


def clipped_like_shapely(p: np.ndarray, geom) -> np.ndarray:
    """``vf.voronoi(p, geom)``'s cells, checked against shapely's clip of the box cells.

    The cells equal the rectangle diagram's cells intersected with ``geom`` (symmetric
    difference under 1e-12 of the box), are valid, tile the domain's area, and every site
    inside the domain lies in its own cell. Returns the cells.
    """
    import voroforge as vf

    x0, y0, x1, y1 = geom.bounds
    cut = vf.voronoi(p, geom).cells
    ref = shapely.intersection(vf.voronoi(p, (x0, y0, x1, y1)).cells, geom)
    scale = (x1 - x0) * (y1 - y0) * 1e-12
    assert np.all(shapely.area(shapely.symmetric_difference(cut, ref)) <= scale)
    assert np.all(shapely.is_valid(cut))
    assert np.isclose(shapely.area(cut).sum(), geom.area, rtol=1e-12)
    inside = shapely.intersects_xy(geom, p[:, 0], p[:, 1])
    assert shapely.intersects_xy(cut[inside], p[inside, 0], p[inside, 1]).all()
    return cut


def edges_are_the_cells(d, scale: float) -> None:
    """``d.edges``: each end a vertex of both its cells bit for bit; per pair, their length."""
    cells = d.cells
    verts = [set(map(tuple, shapely.get_coordinates(c).tolist())) for c in cells]
    got = {}
    for (a, b), (i, j) in zip(d.edges.coords.tolist(), d.edges.pairs.tolist(), strict=True):
        for q in (tuple(a), tuple(b)):
            assert q in verts[i] and q in verts[j]
        got[(i, j)] = got.get((i, j), 0.0) + float(np.hypot(b[0] - a[0], b[1] - a[1]))
    tree = shapely.STRtree(cells)
    ii, jj = tree.query(cells, predicate="intersects")
    for i, j in zip(ii.tolist(), jj.tolist(), strict=True):
        if i < j:
            shared = shapely.intersection(shapely.boundary(cells[i]), shapely.boundary(cells[j]))
            length = shapely.length(shared)
            assert abs(got.pop((i, j), 0.0) - length) <= 1e-9 * scale
    assert not got  # (no edge between cells that share no boundary)
