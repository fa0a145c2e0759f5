"""Containers of 3D diagrams: a box, a convex solid (:class:`Convex`), a closed triangle mesh.

Every container becomes a *template*: a convex polyhedron ``(TV, TF, TR)`` in the layout of
:mod:`kernels.polyhedron` whose faces carry wall labels ``-1 - w``, plus the wall planes
``WP (W, 4)`` (``a x + b y + c z <= d``), or for a :class:`Convex` far from the origin ``WP (W,
7)``: rows ``(a, b, c, d, ox, oy, oz)`` meaning ``a (x - ox) + b (y - oy) + c (z - oz) <= d``
about one origin ``o`` near the solid (a power-of-two multiple, so that ``p - o`` is exact for
every point of the solid), and ``TV`` relative to ``o``: an offset ``d`` kept in one double in
absolute coordinates places a wall at 4e6 only to 2.3e-10. Each cell starts as a copy of the
template (a big :class:`Convex`: each cell that reaches a wall, :mod:`engine.hull3d`). A box
numbers its walls as voro++ does (0 x-min, 1 x-max, 2 y-min, 3 y-max, 4 z-min, 5 z-max); a
:class:`Convex` numbers them in the order of its half-spaces (after merging coplanar hull
facets). A mesh container's cells are built in its bounding box and then cut by the mesh
(:mod:`engine.mesh3d`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..config import (
    AREA_MAX,
    CONVEX_EXACT_ROWS,
    CONVEX_EXACT_THIN,
    CONVEX_FAR_ORIGIN,
    CONVEX_THIN_AXES,
    CONVEX_THIN_MERGE,
    FLAT_RTOL,
    OUTSIDE3D_BLOCK,
    OUTSIDE3D_RTOL,
    VOLUME_RANGE,
)

#: the cube's faces, outward counter-clockwise; corner ``k`` is ``(k & 1, k >> 1 & 1, k >> 2)``
_CUBE_RINGS = ((0, 4, 6, 2), (1, 3, 7, 5), (0, 1, 5, 4), (2, 6, 7, 3), (0, 2, 3, 1), (4, 5, 7, 6))


@dataclass(frozen=True)
class Template:
    """A container as the cell builder sees it (see the module docstring)."""

    TV: np.ndarray
    TF: np.ndarray
    TR: np.ndarray
    WP: np.ndarray
    kind: str
    volume: float
    bounds: np.ndarray  # (2, 3) lower and upper corner
    #: the walls in absolute coordinates ``(W, 4)`` (``Diagram3D.walls``); None: ``WP``
    walls: np.ndarray | None = None
    #: a hull's float cut (:func:`_hull_template`): where four or more walls meet it keeps
    #: one vertex that their rounded rows need not all pass through (:func:`exact_twin`)
    float_cut: bool = False

    @property
    def origin(self) -> np.ndarray:
        """The point ``TV`` and the rows of ``WP`` are relative to (zero unless ``WP`` has 7)."""
        return self.WP[0, 4:7].copy() if self.WP.shape[1] > 4 else np.zeros(3)

    def absolute_walls(self) -> np.ndarray:
        """The wall rows ``(W, 4)`` in absolute coordinates."""
        return self.WP if self.walls is None else self.walls

    def scaled(self, k: int) -> Template:
        """The same container with coordinates times ``2**k`` (exact)."""
        if k == 0:
            return self
        WP = self.WP.copy()
        WP[:, 3:] = np.ldexp(WP[:, 3:], k)  # the offsets and (7 columns) the origin
        walls = None
        if self.walls is not None:
            walls = self.walls.copy()
            walls[:, 3] = np.ldexp(walls[:, 3], k)
        return replace(
            self,
            TV=np.ldexp(self.TV, k),
            WP=WP,
            volume=float(np.ldexp(self.volume, 3 * k)),
            bounds=np.ldexp(self.bounds, k),
            walls=walls,
        )


def box_template(lo, hi, labels=None) -> Template:
    """The box ``lo..hi`` (3,) as a template; wall ``w`` is label ``-1 - w`` unless given."""
    lo = np.asarray(lo, np.float64)
    hi = np.asarray(hi, np.float64)
    TV = np.array(
        [[(lo, hi)[k & 1][0], (lo, hi)[k >> 1 & 1][1], (lo, hi)[k >> 2][2]] for k in range(8)]
    )
    labels = [-1 - w for w in range(6)] if labels is None else labels
    TF = np.array([[labels[f], 4 * f, 4] for f in range(6)], np.int64)
    TR = np.array(_CUBE_RINGS, np.int64).ravel()
    WP = np.array(
        [
            [-1, 0, 0, -lo[0]],
            [1, 0, 0, hi[0]],
            [0, -1, 0, -lo[1]],
            [0, 1, 0, hi[1]],
            [0, 0, -1, -lo[2]],
            [0, 0, 1, hi[2]],
        ],
        np.float64,
    )
    with np.errstate(over="ignore", under="ignore"):  # out of range: check_volume says so
        vol = float(np.prod(hi - lo))
    return Template(TV, TF, TR, WP, "box", vol, np.array([lo, hi]))


def check_volume(t: Template, limits=VOLUME_RANGE) -> None:
    """Raise ``ValueError`` when the container's volume lies outside ``limits``.

    (:data:`VOLUME_RANGE`, meshes too since 2026-12-05) or when its bounding box's
    largest face area exceeds :data:`AREA_MAX`.
    """
    lo, hi = limits
    with np.errstate(over="ignore", under="ignore", invalid="ignore"):
        sides = np.sort(np.ptp(np.asarray(t.bounds, np.float64), axis=0))
        area = float(sides[1] * sides[2])
    side = float(sides[2])
    if lo <= t.volume <= hi and area <= AREA_MAX:
        return
    if lo <= t.volume <= hi:
        raise ValueError(
            f"the container's largest face in these units ({area:.3g}; sides {sides[2]:.3g} "
            f"and {sides[1]:.3g}) is past {AREA_MAX:g}, where 3D face areas would overflow: "
            "scale the points (and the container) down (a power of two scales exactly)"
        )
    what = "overflow" if not t.volume < hi else "underflow"
    raise ValueError(
        f"the container's volume in these units ({t.volume:.3g}; largest side {side:.3g}) is "
        f"outside {lo:g}..{hi:g}, where 3D cell volumes would {what}: scale the points (and "
        f"the container) so that its volume lies in that range, e.g. a cube's sides between "
        f"about {lo ** (1 / 3):.0e} and {hi ** (1 / 3):.0e} (a power of two scales exactly)"
    )


class Convex:
    """A convex container: half-spaces ``a x + b y + c z <= d`` or the hull of points.

    Parameters
    ----------
    halfspaces : (k, 4) array_like, optional
        Rows ``[a, b, c, d]``. The region must be bounded and have volume.
    points : (m, 3) array_like, optional
        The container is their convex hull (coplanar hull facets merged into one wall).

    With ``halfspaces`` the template is the exact polytope of the rows as the cells use them
    (each divided by its normal's norm, far from the origin kept about an origin near the
    solid): its vertices are correctly rounded, its volume good to about an ulp
    (:mod:`engine.polytope3d`); a row that only touches it makes no face. With ``points``
    it is the box cut by the hull's rows in floating point (corners where four or more
    facets meet stay one vertex; the exact polytope of the rounded rows splits them into
    several ulps apart, and cells built from it were 24x slower). Where sites put a bisector
    through such a corner (lattices: a cell failed, or two cells named a vertex apart),
    :func:`.voronoi3d.voronoi3d` builds the cells again from that exact polytope
    (:func:`exact_twin`). A hull of at most :data:`CONVEX_EXACT_ROWS` walls, or a thin one,
    builds that polytope at once and takes its volume (the float cut's was 5.3e-10 off for a
    1 x 1e-9 x 1e-9 box, whose cells sum exactly).

    Examples
    --------
    >>> import voroforge as vf
    >>> c = vf.Convex(halfspaces=[[1, 1, 1, 1], [-1, 0, 0, 0], [0, -1, 0, 0], [0, 0, -1, 0]])
    >>> round(c.volume, 6)
    0.166667
    """

    def __init__(self, halfspaces=None, *, points=None):
        if (halfspaces is None) == (points is None):
            raise ValueError("Convex needs exactly one of halfspaces=(k, 4) or points=(m, 3)")
        if points is not None:
            from .inputs import as_points

            pts = as_points(points, dim=3, name="Convex points")
            box = np.array([pts.min(axis=0), pts.max(axis=0)])
            N, corners, tris = _hull_planes(pts, far_origin(*box))
            hs = _hull_rows(pts, N, corners)

            def local(o):
                return _hull_rows(pts, N, corners, o)
        else:
            try:
                hs = np.array(halfspaces, dtype=np.float64, copy=True)
            except (TypeError, ValueError) as exc:
                raise ValueError(f"halfspaces must be a (k, 4) real array ({exc})") from None
            if hs.ndim != 2 or hs.shape[1] != 4 or len(hs) < 4:
                raise ValueError(f"halfspaces must have shape (k, 4) with k >= 4; got {hs.shape}")
            if not np.isfinite(hs).all():
                raise ValueError("halfspaces contains NaN or infinite values")
            # rows far from 1 are scaled by their largest normal component first: the norm of
            # [1e155, 1e155, 0] overflowed (the row became 0 and was dropped), of [1e-300, 0,
            # 0] underflowed (a "zero normal")
            big = np.abs(hs[:, :3]).max(axis=1)
            if (big == 0).any():
                raise ValueError(f"halfspace {int(np.flatnonzero(big == 0)[0])} has a zero normal")
            far = (big < 1e-150) | (big > 1e150)
            with np.errstate(over="ignore"):
                hs[far] /= big[far, None]
            if not np.isfinite(hs[:, 3]).all():
                w = int(np.flatnonzero(~np.isfinite(hs[:, 3]))[0])
                raise ValueError(f"halfspace {w}: its offset over its normal overflows float64")
            raw = hs
            norm = np.linalg.norm(hs[:, :3], axis=1)
            hs = hs / norm[:, None]
            box = None

            def local(o):
                return _local_rows(raw, norm, hs, o)

        self.halfspaces = hs
        self._template = _convex_template(hs, box, local, None if points is not None else raw)
        if points is not None and self._template.float_cut and self._template.WP.shape[1] > 4:
            # far out, the volume of the hull's triangles about the origin (exact
            # differences): the template's float cut treats walls within 1e-12 of a vertex
            # as through it, and a rotated cube at 1e6, its faces split by the corners'
            # rounding into nearly coplanar walls, measured 1.5e-12 off its cells' sum
            t = self._template
            self._template = replace(t, volume=_hull_volume(pts - t.origin, tris))
        self._exact: Template | None = None
        t = self._template
        if (
            points is not None
            and t.float_cut  # (else the template is that polytope: containers._Degenerate)
            and (
                len(hs) <= CONVEX_EXACT_ROWS
                or t.volume < CONVEX_EXACT_THIN * float(np.ptp(t.bounds, axis=0).max()) ** 3
            )
        ):
            # the cells sum to the exact polytope of the rows, not to the float cut (or, far
            # out, the hull's triangles): its volume, and it is the exact twin (built once)
            lo, hi = np.asarray(t.bounds, np.float64) - t.origin
            TV, TF, TR, vol = _exact_template(np.ascontiguousarray(t.WP[:, :4]), lo, hi)
            self._template = replace(t, volume=vol)
            self._exact = replace(t, TV=TV, TF=TF, TR=TR, float_cut=False, volume=vol)
        self.volume = self._template.volume

    def _twin(self) -> Template:
        """The template's :func:`exact_twin` (made once; itself when it is exact)."""
        if not self._template.float_cut:
            return self._template
        if self._exact is None:
            self._exact = exact_twin(self._template)
        return self._exact

    def __repr__(self) -> str:
        return f"Convex({len(self.halfspaces)} half-spaces, volume {self.volume:.6g})"


def _hull_planes(pts: np.ndarray, o=None) -> tuple[np.ndarray, list]:
    """The unit normals ``(W, 3)`` of the hull of ``pts`` and each plane's corners (numbers).

    ``o``: the origin a far solid's walls are kept about (:func:`far_origin`); the merge of
    nearly coplanar facets then allows the rounding of ``p - o`` (exact: nothing), not of
    ``p`` (at 1e9, facets of a 1e-3 slab 1.4e-5 apart were merged and its volume came out
    8e-4 too large).

    The hull's facets are an affine invariant: Qhull sees the points on their principal
    axes, each scaled to unit extent (a slab 1e-9 thin is a cube to it; on the raw points its
    side facets' normals were off by ~1e-7 and the container came out "open" or
    "unbounded"). Each facet's plane is then computed from the raw points exactly
    (integers): its normal rounded once, its offset the largest of its corners' exactly
    rounded. Triangles of one plane give the same bits and are merged, and so are those
    within 1e-12 of one plane (as Qhull's were).

    A thin hull (principal extents' ratio below :data:`CONVEX_THIN_AXES`) groups its
    triangles by their exact planes, merges nearly coplanar ones only within
    :data:`CONVEX_THIN_MERGE` of its thickness, and gives a wall whose normal is no double
    the double nearest its direction (:func:`.hullnormals.close_normal`): rounded normals
    and a merge within 1e-12 of the extent left wedges outside a disk 1e-9 thick (checker33
    F1: 2.5e-8..1.7e-4 of its volume).
    """
    from scipy.spatial import ConvexHull, QhullError, cKDTree

    c = pts.mean(axis=0)
    q = pts - c
    size = float(np.abs(q).max())
    if not size > 0:
        raise ValueError("Convex points span no volume (they are all the same point)")
    q = q / size
    _, _, vt = np.linalg.svd(q, full_matrices=False)
    y = q @ vt.T  # principal axes, widest first
    ext = np.ptp(y, axis=0)
    if not ext[2] > FLAT_RTOL * ext[0]:
        what = "collinear" if not ext[1] > FLAT_RTOL * ext[0] else "coplanar"
        raise ValueError(
            f"Convex points are {what} to within {ext[2] * size:.3g} ({ext[2] / ext[0]:.2g} "
            f"of their extent {ext[0] * size:.3g}): they span no volume (a container must be "
            f"thicker than {FLAT_RTOL:g} of its extent)"
        )
    try:
        hull = ConvexHull(y / ext)
    except (QhullError, ValueError) as exc:
        raise ValueError(
            f"Convex points span no volume (Qhull: {str(exc).splitlines()[0]})"
        ) from None
    # outward in the raw frame: Qhull's normal m (of y = M x + b) is M^T m there
    out = (hull.equations[:, :3] / ext) @ vt
    thin = bool(ext[2] < CONVEX_THIN_AXES * ext[0])
    rows: dict = {}  # unit normal (thin: exact plane) -> its corners (point numbers)
    seen: dict = {}  # point number -> its integers (_point_ints)
    normals = []
    planes = []  # thin: each row's exact outward normal (integers, no common factor)
    for tri, w in zip(hull.simplices, out, strict=True):
        a, b, e = (_point_ints(pts, i, seen) for i in tri)
        u = [b[k] - a[k] for k in range(3)]
        v = [e[k] - a[k] for k in range(3)]
        n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
        big = max(abs(x) for x in n)
        if big == 0:
            continue  # a sliver Qhull made of three collinear points: no plane
        f = np.array([x / big for x in n])  # exact quotients, each rounded once
        nu = f / np.sqrt(f @ f)
        sign = 1
        if nu @ w < 0:
            nu = -nu
            sign = -1
        nu = nu + 0.0  # -0.0 -> 0.0: one key per plane
        key = nu.tobytes()
        if thin:
            g = math.gcd(*n)
            key = tuple(sign * x // g for x in n)
        if key not in rows:
            rows[key] = []
            normals.append(nu)
            planes.append(key)
        rows[key].extend(int(t) for t in tri)
    N = np.array(normals)
    corners = list(rows.values())
    # triangles of one face whose corners rounding left off coplanar are one wall (as
    # Qhull's were): normals within 1e-12, or far from the origin within the corners'
    # rounding over the extent (a unit cube at 1e6: 1e-10; kept apart, one far rotated
    # cube's cells summed 1.1e-8 off: open, see the report), and every corner within that
    # rounding of the kept plane
    big = float(np.abs(pts if o is None else pts - o).max())
    eps64 = 64.0 * np.finfo(float).eps
    tilt = max(1e-12, eps64 * big / (ext[0] * size))
    tol = eps64 * max(big, 1e-300) + 1e-12 * ext[0] * size
    if thin:
        tol = min(tol, CONVEX_THIN_MERGE * ext[2] * size)
    keep = np.ones(len(N), bool)
    pairs = cKDTree(N).query_pairs(tilt, p=np.inf, output_type="ndarray")
    for i, j in sorted(map(tuple, np.sort(pairs, axis=1))):
        if keep[i] and keep[j]:
            q = pts[corners[i] + corners[j]] - pts[corners[i][0]]
            if np.abs(q @ N[i]).max() <= tol:
                corners[i] += corners[j]
                keep[j] = False
    kept = np.flatnonzero(keep)
    corners = [corners[i] for i in kept]
    exact = [planes[i] for i in kept] if thin else None
    return _exact_normals(pts, N[kept], corners, seen, exact), corners, hull.simplices


def _significant(x: int) -> int:
    """The bits of ``x`` between its highest and lowest set bits (0 for 0)."""
    return (abs(x) >> ((x & -x).bit_length() - 1)).bit_length() if x else 0


def _exact_normals(pts, N, corners, seen: dict, planes=None) -> np.ndarray:
    """``N``, exact where a plane's corners are exactly coplanar and its normal fits a double.

    ``planes`` (a thin hull's): each row's exact normal; where the above leaves the unit
    normal, the double nearest that normal's direction (:func:`.hullnormals.close_normal`).

    That normal is the cross product of corner differences (exact, in integers) scaled by a
    power of two (largest component in [1, 2): an axis-aligned wall's normal is the unit
    vector, which :func:`.kernels.vertex3d.axis_snap` reads); other planes keep their unit
    normals.
    Unit normals are rounded, so four or more facets through one corner (a lattice ball's
    hull, every corner) met in several points ulps apart: the float template kept one, a
    bisector through it failed a cell (status 3, 4) or named a vertex two ways, and the
    cells were built again from the exact polytope (``exact_twin``: ~2x the build). Exact
    normals (and offsets, exact from them: :func:`_hull_rows`) meet at the corner itself.
    """
    out = N.copy()
    for w, cs in enumerate(corners):
        if not _exact_normal(pts, N, cs, seen, out, w) and planes is not None:
            from .hullnormals import close_normal

            out[w] = close_normal(planes[w])
    return out


def _exact_normal(pts, N, cs, seen: dict, out: np.ndarray, w: int) -> bool:
    """Set ``out[w]`` to the exact normal of the corners ``cs`` where there is one (True)."""
    ps = [_point_ints(pts, t, seen) for t in dict.fromkeys(cs)]
    a = ps[0]
    # corner differences of 30+ significant bits make products past a double (random
    # points: every plane, skipped before the cross products: Convex of 2,000 points
    # on a sphere 0.41 s before exact normals, 0.53 without this test, 0.43)
    if any(_significant(p[k] - a[k]) > 30 for p in ps[1:] for k in range(3)):
        return False
    m = None
    for b in ps[1:]:
        u = [b[k] - a[k] for k in range(3)]
        for e in ps[2:]:
            v = [e[k] - a[k] for k in range(3)]
            m = [
                u[1] * v[2] - u[2] * v[1],
                u[2] * v[0] - u[0] * v[2],
                u[0] * v[1] - u[1] * v[0],
            ]
            if any(m):
                break
        if m is not None and any(m):
            break
    if m is None or not any(m):
        return False
    if any(sum(m[k] * (p[k] - a[k]) for k in range(3)) for p in ps):
        return False  # corners coplanar only to the merge's tolerance
    low = min((x & -x).bit_length() - 1 for x in m if x)  # common factor 2**low
    m = [x >> low for x in m]
    top = max(abs(x) for x in m).bit_length()
    if top > 53:
        return False  # not a double: the unit normal, rounded once
    n = np.array([np.ldexp(float(x), 1 - top) for x in m])  # (an axis wall's is 1)
    out[w] = n if n @ N[w] > 0 else -n
    return True


def _hull_volume(q: np.ndarray, tris: np.ndarray) -> float:
    """The volume of the hull of ``q`` from its triangles ``tris`` (tetrahedra to a centre)."""
    c = q[np.unique(tris)].mean(axis=0)
    a, b, e = (q[tris[:, k]] - c for k in range(3))
    det = np.einsum("ij,ij->i", a, np.cross(b, e))
    return math.fsum(np.abs(det)) / 6.0


def _hull_rows(pts, N, corners, o=None) -> np.ndarray:
    """Rows ``(W, 4)`` of the planes of :func:`_hull_planes`, about the origin ``o`` if given.

    The offset is the largest of the corners' ``n . (p - o)``, exact in integers, rounded
    once: about ``o`` near the solid it is good to an ulp of the solid's size, where in
    absolute coordinates (``o`` None) only to an ulp of its distance from the origin.
    """
    oi = [0, 0, 0] if o is None else _ints(o)
    seen: dict = {}  # point number -> its integers (_point_ints)
    rows_out = []
    q = pts - (0.0 if o is None else o)
    slack = 1e-9 * float(np.abs(q).max())
    for n, cs in zip(N, corners, strict=True):
        nn = _ints(n)
        # and every point the plane through its corners may not hold: Qhull's triangles of
        # a facet it merged are not all faces of the hull (16 points at 1e5: points 6e-3
        # past one, the container 8.4e-4 smaller than the hull)
        s = q @ n
        past = np.flatnonzero(s >= s[list(cs)].max() - slack)
        ps = [_point_ints(pts, t, seen) for t in set(cs) | set(past.tolist())]
        d = max(sum(nn[k] * (p[k] - oi[k]) for k in range(3)) for p in ps) / _ONE**2
        rows_out.append([*n, d])
    return np.array(rows_out)


def far_origin(lo, hi) -> np.ndarray | None:
    """The origin a Convex with bounds ``lo, hi`` keeps its walls about, or None (near).

    The centre rounded to a multiple of the power of two above the largest extent: every
    point of the solid minus it is exact (both are multiples of the point's ulp, the
    difference below the extent), and so is scaling it by a power of two.
    """
    lo = np.asarray(lo, np.float64)
    hi = np.asarray(hi, np.float64)
    size = float((hi - lo).max())
    c = 0.5 * lo + 0.5 * hi
    if not float(np.abs(c).max()) > CONVEX_FAR_ORIGIN * size or not size > 0:
        return None
    step = np.ldexp(1.0, int(np.frexp(size)[1]))
    return np.round(c / step) * step + 0.0


def _local_rows(raw, norm, unit, o) -> np.ndarray:
    """Rows ``(W, 4)`` of the half-spaces ``raw`` about ``o``: unit normals, exact offsets.

    The normal is ``unit``'s (``raw``'s over its float ``norm``, as ``Convex.halfspaces``),
    the offset ``(d - n . o) / norm`` computed exactly and rounded once.
    """
    from fractions import Fraction

    out = unit.copy()
    of = [Fraction(float(x)) for x in o]
    for w, r in enumerate(raw):
        e = Fraction(float(r[3])) - sum(Fraction(float(r[k])) * of[k] for k in range(3))
        out[w, 3] = float(e / Fraction(float(norm[w])))
    return out


#: :func:`_ints`' unit: every double of a Convex hull's range is an integer multiple of it
#: (the volume range keeps coordinates above 1e-90; subnormal bits below 2**-1100 are lost)
_ONE = 2**1100


def _point_ints(pts, i, seen: dict) -> list[int]:
    """:func:`_ints` of point ``pts[i]``, kept in ``seen``.

    A hull point is a corner of ~6 facets: 28,000 conversions for the hull of 2,000 points
    took 0.37 s.
    """
    x = seen.get(int(i))
    if x is None:
        x = seen[int(i)] = _ints(pts[i])
    return x


def _ints(x) -> list[int]:
    """``x`` (3,) doubles as integers in units of ``1 / _ONE`` (exact above 2**-1047)."""
    out = []
    for m, ex in zip(*np.frexp(x), strict=True):
        k = int(np.ldexp(m, 53))
        s = 1100 + int(ex) - 53
        out.append(k << s if s >= 0 else k >> -s)
    return out


def _convex_template(
    hs: np.ndarray, box: np.ndarray | None = None, local=None, raw=None
) -> Template:
    """The template of the half-spaces ``hs``; ``box`` (2, 3): its bounds where known (a hull).

    Otherwise the bounds are linear programs (HiGHS: feasible to ~1e-7, so a slab thinner
    than that may not be bounded right, and one that looks flat is bounded again on scaled
    offsets; a hull's own points bound it exactly). ``local(o)``:
    the same half-spaces about the origin ``o`` (exact offsets), used when the solid lies
    far from the origin (:func:`far_origin`). ``raw``: the rows as the user gave them; a row
    that makes no face of their exact polytope is left out of the template, whose rows are
    rounded (``[1, 1, 1, 3]`` on the unit cube touches its corner; divided by its norm and
    rounded it passes an ulp inside and cut a face of three vertices: checker33 F2).
    """
    if box is not None:
        lo, hi = box
    else:
        lo, hi = _lp_bounds(hs, 0)
    if box is None and _flat(lo, hi):
        # HiGHS's tolerances are absolute: a 1e-9 x 1e-9 x 1e-16 slab at the origin bounded
        # as 0 thick (the same slab x 1e3 as 1e-13). Solved again with the offsets scaled by
        # a power of two to about 1 (exact); only where the first answer refused the solid
        lo, hi = _lp_bounds(hs, -int(np.frexp(float(np.abs(hs[:, 3]).max()))[1]))
    size = hi - lo
    far = float(max(np.abs(lo).max(), np.abs(hi).max()))
    if _flat(lo, hi):
        raise ValueError(
            f"the Convex container has no volume (it is flat: {size.min():.3g} thick, within "
            f"an ulp of its coordinates ({np.spacing(far):.3g}) or 1e-12 of its extent)"
        )
    k = len(hs)
    o = None if local is None else far_origin(lo, hi)
    if box is not None:  # a hull's points
        return _hull_template(hs, lo, hi, o, local)
    # far out: walls about the origin o near the solid, exactly (module docstring)
    rows = hs if o is None else local(o)
    at = np.zeros(3) if o is None else o
    skip = None
    if raw is not None:
        _, RF, _, _ = _exact_template(raw, lo, hi)
        skip = np.ones(k, bool)
        skip[-1 - RF[:, 0]] = False  # every face is a row's: the box left none
    TV, TF, TR, vol = _exact_template(rows, lo - at, hi - at, skip)
    if o is None:
        return Template(TV, TF, TR, hs.copy(), "convex", vol, np.array([TV.min(0), TV.max(0)]))
    WP = np.ascontiguousarray(np.column_stack([rows, np.tile(o, (k, 1))]))
    bounds = np.array([TV.min(0) + o, TV.max(0) + o])
    return Template(TV, TF, TR, WP, "convex", vol, bounds, hs.copy())


def _flat(lo, hi) -> bool:
    """Whether the box ``lo..hi`` is too thin to hold a solid.

    Down to an ulp of its coordinates: far out the walls are kept about an origin near the
    solid, exactly (a 1 x 1e-9 x 1e-9 box at 1e6, 8.6 ulps thick, had been refused at 16).
    """
    size = hi - lo
    far = float(max(np.abs(lo).max(), np.abs(hi).max()))
    return bool(size.min() <= max(1e-12 * size.max(), np.spacing(far), 1e-300))


def _lp_bounds(hs: np.ndarray, e: int) -> tuple[np.ndarray, np.ndarray]:
    """The bounds of the rows ``hs`` by six linear programs, on the offsets times ``2**e``."""
    from scipy.optimize import linprog

    b = np.ldexp(hs[:, 3], e)
    lo = np.zeros(3)
    hi = np.zeros(3)
    for a in range(3):
        for sgn, out in ((1.0, lo), (-1.0, hi)):
            c = np.zeros(3)
            c[a] = sgn
            res = linprog(c, A_ub=hs[:, :3], b_ub=b, bounds=[(None, None)] * 3, method="highs")
            if res.status == 2:
                raise ValueError("the half-spaces of the Convex container have no common point")
            if res.status == 3:
                raise ValueError(
                    "the Convex container is unbounded (add half-spaces that close it)"
                )
            if res.status != 0:
                raise ValueError(f"could not bound the Convex container ({res.message})")
            out[a] = res.x[a]
    return np.ldexp(lo, -e), np.ldexp(hi, -e)


def _hull_template(hs, lo, hi, o, local) -> Template:
    """A hull's template: the box cut by its rows in floating point (``container_cut``).

    Not the exact polytope of the rounded rows (:func:`_exact_template`): where four or more
    facets meet at one of the points, the rounded rows meet in several vertices ulps apart
    (the hull of 1,000 points on a sphere: 3,988 template vertices for 1,000), and every cell
    starts from the template: 2,000 cells in it took 37.9 s instead of 1.55 s. The float cut
    merges those corners; the hull's volume is its own triangles' (exact differences).
    """
    k = len(hs)
    pad = 0.01 * float((hi - lo).max())
    if o is not None:
        # far out: walls about the origin o near the solid, exactly (module docstring)
        rows = local(o)
        WP = np.ascontiguousarray(np.column_stack([rows, np.tile(o, (k, 1))]))
        cut = True
        try:
            TV, TF, TR, vol = cut_template(rows[:, :3], rows[:, 3], lo - o - pad, hi - o + pad)
        except _Degenerate:
            # the float cut lost its rings among walls ulps apart (a relaxed cell of a box
            # at 1e6, 31 walls); the exact polytope of the same rows holds them
            TV, TF, TR, vol = _exact_template(rows, lo - o, hi - o)
            cut = False
        bounds = np.array([TV.min(0) + o, TV.max(0) + o])
        return Template(TV, TF, TR, WP, "convex", float(vol), bounds, hs.copy(), cut)
    # cut in a frame centred on the solid: in absolute coordinates a small solid far out
    # lost its volume to cancellation
    c = 0.5 * (lo + hi)
    d = hs[:, 3] - hs[:, :3] @ c
    try:
        TV, TF, TR, vol = cut_template(hs[:, :3], d, lo - c - pad, hi - c + pad)
    except _Degenerate:  # (as above)
        TV, TF, TR, vol = _exact_template(np.ascontiguousarray(hs), lo, hi)
        return Template(TV, TF, TR, hs.copy(), "convex", vol, np.array([TV.min(0), TV.max(0)]))
    TV = TV + c
    bounds = np.array([TV.min(0), TV.max(0)])
    return Template(TV, TF, TR, hs.copy(), "convex", float(vol), bounds, None, True)


def exact_twin(t: Template) -> Template:
    """The exact polytope of a float-cut hull template's rows (:mod:`engine.polytope3d`).

    Where four or more of a hull's walls meet, its float cut keeps one vertex; their rounded
    rows meet in several points ulps apart, so the exact tests of the cell builder, which
    place a vertex by three of its walls, see a cluster whose order the float ring does not
    hold. A bisector through such a corner (lattice sites and the hull of lattice points,
    issue 12) then cut a ring of that cluster in four places (``status 3``), left a vertex
    unnamed (4) or named differently by two cells (unmatched vertices). The exact polytope
    of the same rows holds each corner as its rows do. Same walls, origin, volume and bounds.
    """
    o = t.origin
    rows = np.ascontiguousarray(t.WP[:, :4])
    lo, hi = np.asarray(t.bounds, np.float64) - o
    TV, TF, TR, _ = _exact_template(rows, lo, hi)
    return replace(t, TV=TV, TF=TF, TR=TR, float_cut=False)


def cut_template(N, d, lo, hi):
    """The box ``lo..hi`` cut by the half-spaces ``N x <= d``: ``(TV, TF, TR, volume)``."""
    from ..kernels.polyhedron import moments
    from ..kernels.template3d import cut_all

    k = len(N)
    t = box_template(lo, hi, labels=[-1 - (k + b) for b in range(6)])
    # every plane in one call (a call a plane allocated the arrays anew: the 3,996 planes
    # of the hull of 2,000 points on a sphere took 12-36 s); the same cuts, bit for bit
    N = np.ascontiguousarray(N, np.float64)
    d = np.ascontiguousarray(d, np.float64)
    st, _, TV, TF, TR = cut_all(t.TV, t.TF, t.TR, N, d, -1)
    if st == 2:
        raise ValueError("the Convex container has no volume")
    if st != 0:
        raise _Degenerate("could not build the Convex container (degenerate half-spaces)")
    if (TF[:, 0] < -k).any():
        raise ValueError("could not close the Convex container (its half-spaces leave it open)")
    # walls never reached (redundant half-spaces) keep their numbers; volume from faces
    return TV, TF, TR, moments(TV, TF, len(TF), TR)[0]


class _Degenerate(ValueError):
    """The float cut of a template failed (``cut_template``): the exact polytope may not."""


def _exact_template(rows, lo, hi, skip=None):
    """The exact polytope of ``rows`` (:mod:`engine.polytope3d`) found in the box ``lo..hi``.

    The box only has to hold the solid: its bounds come from a linear program good to ~1e-7,
    so a pad of 1% of the extent (then 1000 and 1e6 times that) allows for them; a solid
    still reaching the box's walls is unbounded.
    """
    from .polytope3d import exact_polytope

    k = len(rows)
    size = float((np.asarray(hi) - np.asarray(lo)).max())
    for grow in (0.01, 10.0, 1e4):
        TV, TF, TR, vol = exact_polytope(rows, lo - grow * size, hi + grow * size, skip)
        if not (TF[:, 0] < -k).any():
            return TV, TF, TR, vol
    raise ValueError("could not close the Convex container (its half-spaces leave it open)")


def _few_bits(x: np.ndarray) -> np.ndarray:
    """``x > 0`` rounded up to 4 significant bits.

    The default box's pad: the walls of dyadic input (grids, lattices) are then exact, so
    the co-spherical and mirror-symmetric vertices the walls make are exact too (with
    ``lo - 0.15`` they would be off by a rounding, and the exact predicates would keep the
    tiny faces that rounding makes).
    """
    m, e = np.frexp(x)
    return np.ldexp(np.ceil(m * 16.0) / 16.0, e)


def as_container(container, pts: np.ndarray) -> Template:
    """The template of a user's container (``None``, a 6-tuple, :class:`Convex`); mesh: None."""
    from ..config import VORONOI3D_PAD

    if container is None:
        if len(pts) == 0:
            return box_template(np.zeros(3), np.ones(3))
        lo = pts.min(axis=0)
        hi = pts.max(axis=0)
        span = hi - lo
        big = float(span.max())
        if big == 0.0:
            big = max(float(np.abs(lo).max()), 1.0)
        span = np.maximum(span, big)  # flat input: pad every axis by the largest extent
        pad = _few_bits(VORONOI3D_PAD * span)
        return box_template(lo - pad, hi + pad)
    if isinstance(container, Convex):
        return container._template
    if isinstance(container, (tuple, list, np.ndarray)) and np.asarray(
        container, dtype=object
    ).shape == (6,):
        try:
            b = np.array(container, dtype=np.float64)
        except (TypeError, ValueError):
            raise ValueError(
                "a box container is (xmin, ymin, zmin, xmax, ymax, zmax) numbers"
            ) from None
        if not np.isfinite(b).all():
            raise ValueError(f"box container has non-finite bounds: {b.tolist()}")
        if not (b[3:] > b[:3]).all():
            raise ValueError(
                f"box container needs xmin < xmax, ymin < ymax, zmin < zmax; got {b.tolist()}"
            )
        return box_template(b[:3], b[3:])
    raise TypeError("not a box or Convex container")


def maybe_outside(P: np.ndarray, t: Template) -> np.ndarray:
    """``(n,) bool``: the sites ``P`` (working frame) that may lie outside template ``t``.

    A box's walls are compared exactly (a site on a wall is inside); a Convex's in floats,
    so a site within :data:`OUTSIDE3D_RTOL` of a wall's scale of its outside is included.
    """
    WP = t.WP
    if t.kind == "box" and WP.shape[1] == 4:
        lo, hi = t.bounds
        return ((P < lo) | (P > hi)).any(axis=1)
    out = np.zeros(len(P), np.bool_)
    n = WP[:, :3]
    for a in range(0, len(P), OUTSIDE3D_BLOCK):
        Q = P[a : a + OUTSIDE3D_BLOCK]
        if WP.shape[1] > 4:
            Q = Q - WP[0, 4:7]
        s = Q @ n.T - WP[:, 3]
        scale = np.abs(WP[:, 3]) + np.abs(Q).max(axis=1)[:, None] * np.abs(n).sum(axis=1)
        out[a : a + OUTSIDE3D_BLOCK] = (s > -OUTSIDE3D_RTOL * scale).any(axis=1)
    return out
