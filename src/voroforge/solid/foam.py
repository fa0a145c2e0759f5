"""Closed-cell foams: every cell shrunk into a bubble, walls between them (``solid.foam``)."""

from __future__ import annotations

import warnings

import numpy as np
from scipy.spatial import HalfspaceIntersection, QhullError

from ..config import FOAM_FACE_AREA_RTOL, FOAM_LP_CELLS, SOLID_FOAM_CONVEX_RTOL
from .fields import as_size
from .graph import cell_meshes, convex_cell_meshes
from .hulls import convex_mesh

__all__ = ["bubbles", "foam"]


def _planes(cell) -> tuple[np.ndarray, np.ndarray]:
    """Unique outward face planes ``n . x <= c`` of a convex cell mesh.

    Triangles of (nearly) zero area are left out: a ring with three collinear vertices (where
    a mesh cut joined a cell's parts) fans into one, whose normal trimesh gives as zero or
    rounding makes point anywhere; its row ``0 <= 0`` moved in by the wall read ``0 <= -w/2``
    and the cell lost its bubble. Each face keeps its plane from its other triangles.
    """
    tri = np.asarray(cell.triangles)
    # The normals from the corners (trimesh's face_normals are zero below an absolute area:
    # every face of a cell 1e-6 across, whose bubble was then lost).
    cross = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    twice = np.linalg.norm(cross, axis=1)
    n = cross / np.where(twice > 0, twice, 1.0)[:, None]
    c = np.einsum("ij,ij->i", n, tri.mean(axis=1))
    sound = 0.5 * twice > FOAM_FACE_AREA_RTOL * max(cell.scale, 1e-300) ** 2
    if not sound.any():  # a degenerate cell: its triangles as they are
        sound[:] = True
    key = np.round(np.column_stack([n, c / max(cell.scale, 1e-300)]), 9)
    _, first = np.unique(key[sound], axis=0, return_index=True)
    first = np.sort(np.flatnonzero(sound)[first])
    cen = cell.vertices[cell.faces[first]].mean(axis=1)
    return np.column_stack([n[first], c[first]]), cen


def _chebyshev(a: np.ndarray, c: np.ndarray):
    """Centre and radius of the largest ball inside ``a x <= c`` (None when empty)."""
    from scipy.optimize import linprog

    norm = np.linalg.norm(a, axis=1)
    res = linprog(
        [0, 0, 0, -1],
        A_ub=np.column_stack([a, norm]),
        b_ub=c,
        bounds=[(None, None)] * 3 + [(0, None)],
    )
    if not res.success:
        return None, 0.0
    return res.x[:3], float(res.x[3])


def _inscribed(systems):
    """Chebyshev centre and radius of each ``(a, c, x0, s)``: the largest ball in ``a x <= c``.

    Each system is posed in its own frame ``x = x0 + s y`` (``x0`` a point near the cell,
    ``s`` its size: every block is of order one for the solver's absolute tolerances) and
    all are one LP of independent blocks, the radius free: a negative radius is an empty
    region (a ``r >= 0`` bound would make the whole LP infeasible for one swallowed cell).
    Returns centres (n, 3) and radii (n,) (radius -inf where a block could not be solved:
    the LP of that system alone is then tried).
    """
    from scipy.optimize import linprog
    from scipy.sparse import coo_matrix

    n = len(systems)
    centres, radii = np.zeros((n, 3)), np.full(n, -np.inf)
    for lo in range(0, n, FOAM_LP_CELLS):
        part = systems[lo : lo + FOAM_LP_CELLS]
        rows, cols, vals, rhs = [], [], [], []
        r0 = 0
        for j, (a, c, x0, sc) in enumerate(part):
            k = len(a)
            an = np.column_stack([a, np.linalg.norm(a, axis=1)])
            rr = np.repeat(np.arange(r0, r0 + k), 4)
            rows.append(rr)
            cols.append(np.tile(np.arange(4 * j, 4 * j + 4), k))
            vals.append(an.ravel())
            rhs.append((c - a @ x0) / sc)
            r0 += k
        m = len(part)
        a_ub = coo_matrix(
            (np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(r0, 4 * m)
        ).tocsc()
        cost = np.zeros(4 * m)
        cost[3::4] = -1.0
        res = linprog(cost, A_ub=a_ub, b_ub=np.concatenate(rhs), bounds=(None, None))
        if not res.success:
            continue
        y = res.x.reshape(m, 4)
        for j, (_, _, x0, sc) in enumerate(part):
            centres[lo + j] = x0 + sc * y[j, :3]
            radii[lo + j] = sc * y[j, 3]
    return centres, radii


def bubbles(cells, wall, *, field=None):
    """Each cell shrunk by half the local wall thickness on every face (convex bubbles).

    Returns
    -------
    list of (Trimesh or None, centre (3,), inscribed radius)
        ``None`` where the wall swallows the cell (it stays solid). The centre and radius
        are the bubble's largest inscribed ball (its Chebyshev centre: an LP of its planes).
        ``cells`` is a 3D diagram or a list of meshes (each shrunk as the intersection of its
        faces' half-spaces; :func:`foam` refuses cells that are not convex).
    """
    return _bubbles(cell_meshes(cells), as_size(wall, field, "wall"))[0]


def _convex(cells3d):
    return convex_cell_meshes(
        cells3d, "foam", "a bubble is its cell shrunk face by face, so its walls would be thicker"
    )


def _held(container, bs) -> None:
    """Raise where a bubble reaches outside ``container`` (exact parity of its vertices)."""
    from ..engine.mesh3d import as_mesh_container, sites_inside

    mc, _ = as_mesh_container(container)
    live = [i for i, (b, _, _) in enumerate(bs) if b is not None]
    if not live:
        return
    verts = [np.asarray(bs[i][0].vertices) for i in live]
    inside = sites_inside(mc, np.vstack(verts))  # one search grid for all bubbles
    owner = np.repeat(live, [len(v) for v in verts])
    if not inside.all():
        i = int(owner[np.argmin(inside)])
        raise ValueError(
            f"foam: bubble {i} of {len(bs)} reaches outside container= (the container "
            "must hold the cells: pass the mesh they were built in)"
        )


def _bubbles(cells, size):
    """:func:`bubbles` and each cell's faces: ``(planes (k, 4), face points (k, 3), walls)``."""
    systems, faces = [], []
    for cell in cells:
        pl, cen = _planes(cell)
        w = np.broadcast_to(np.asarray(size(cen), dtype=np.float64), (len(pl),))
        faces.append((pl, cen, w))
        systems.append((pl[:, :3], pl[:, 3] - 0.5 * w, cell.center_mass, max(cell.scale, 1e-300)))
    ball, ball_r = _inscribed(systems)
    out = []
    for i, (cell, (a, c, x0, sc)) in enumerate(zip(cells, systems, strict=True)):
        slack = c - a @ x0
        if not np.isfinite(ball_r[i]):  # the joint LP failed: this cell's own
            b_c, b_r = _chebyshev(a, c)
            ball[i], ball_r[i] = (x0, 0.0) if b_c is None else (b_c, b_r)
        if slack.min() > 1e-6 * cell.scale:  # the centroid is inside: the interior point
            centre = x0
            if slack.min() > ball_r[i]:  # its clearance bounds the inscribed radius
                ball[i], ball_r[i] = x0, float(slack.min())
        else:
            centre = ball[i]
        rad = float(ball_r[i])
        if rad <= 1e-6 * cell.scale:
            out.append((None, x0, 0.0))
            continue
        try:  # in the cell's frame x = x0 + sc y (Qhull's tolerances are absolute)
            rows = np.column_stack([a, -(c - a @ x0) / sc])
            y = HalfspaceIntersection(rows, (centre - x0) / sc).intersections
            b = convex_mesh(x0 + sc * y)
        except QhullError:
            out.append((None, x0, 0.0))
            continue
        out.append((b, ball[i].copy(), rad))
    return out, faces


def _walls(cells, bs, faces):
    """Each wall a bubble's facet meets: ``(points (k, 3), thickness (k,))``.

    A face two cells share (the same plane, normals opposite, the one's face point inside
    the other's bounds) is a wall ``w_i / 2 + w_j / 2`` thick where both bubbles have a
    facet on it (listed once); a face no other cell shares is the container's skin, half a
    wall (the cells fill the container). A facet whose other side is solid (no bubble, or
    that bubble's plane left no facet) is thicker and not listed.
    """
    from scipy.spatial import cKDTree

    if not cells:
        return np.zeros((0, 3)), np.zeros(0)
    lo = np.min([c.bounds[0] for c in cells], axis=0)
    hi = np.max([c.bounds[1] for c in cells], axis=0)
    span = max(float(np.max(hi - lo)), 1e-300)
    pl = np.vstack([f[0] for f in faces])
    pts = np.vstack([f[1] for f in faces])
    w = np.concatenate([f[2] for f in faces])
    owner = np.repeat(np.arange(len(cells)), [len(f[0]) for f in faces])
    # whether the bubble has a facet on each face's moved plane (3 corners on it at least)
    facet = np.zeros(len(pl), dtype=bool)
    at = 0
    for cell, (b, _, _), (p, _, wf) in zip(cells, bs, faces, strict=True):
        if b is not None:
            d = np.abs(np.asarray(b.vertices) @ p[:, :3].T - (p[:, 3] - 0.5 * wf))
            facet[at : at + len(p)] = (d <= 1e-7 * cell.scale).sum(axis=0) >= 3
        at += len(p)
    key = np.column_stack([pl[:, :3], pl[:, 3] / span])
    tree = cKDTree(key)
    hits = tree.query_ball_point(-key, 1e-6)
    bounds = np.array([c.bounds for c in cells])
    tol = 1e-6 * span
    where, thick = [], []
    for i in np.flatnonzero(facet):
        other = [
            j
            for j in hits[i]
            if owner[j] != owner[i]
            and np.all(pts[i] >= bounds[owner[j], 0] - tol)
            and np.all(pts[i] <= bounds[owner[j], 1] + tol)
        ]
        if not other:  # the container's skin
            where.append(pts[i])
            thick.append(0.5 * w[i])
        elif facet[other[0]] and owner[i] < owner[other[0]]:
            where.append(pts[i])
            thick.append(0.5 * (w[i] + w[other[0]]))
    return np.array(where).reshape(-1, 3), np.array(thick, dtype=np.float64)


def foam(cells3d, wall=1.2, *, field=None, container=None):
    """A closed-cell foam: the container with every cell's bubble taken out.

    Parameters
    ----------
    cells3d : Diagram3D or list of convex Trimesh
        The cells (``vf.voronoi3d(...)`` or convex meshes); a cell a concave mesh container
        cut into a non-convex piece is refused, naming it.
    wall : float or (far, near)
        Wall thickness between neighbouring bubbles (each side gives half; the container's
        skin is half a wall too, as every cell is shrunk by half the wall on every face).
        With ``field``: the pair of thicknesses at field 0 and 1.
    field : callable, optional
        A 0..1 3D field (:mod:`voroforge.solid.fields`), sampled at each face's centre.
    container : Trimesh, optional
        The outer solid (default: the convex hull of the cells: exact for box and convex
        containers; for cells built in a concave mesh pass that mesh, else a warning says
        the hull holds more than the cells). A bubble reaching outside it is refused.

    Returns
    -------
    trimesh.Trimesh
        Watertight: the outer surface and one inward-facing surface per bubble (the bubbles
        are closed voids; :func:`voroforge.solid.check` lists them as trapped).
        ``metadata["pores"]`` holds each bubble's largest inscribed ball: its centre and
        diameter (0 for a cell the walls fill: a warning says how many, and
        ``check(min_pore=...)`` lists them). ``metadata["walls"]`` holds the walls
        between bubbles and the skin (``at`` (k, 3) on each wall, ``thickness`` (k,)), what
        ``check(min_wall=...)`` compares.

    Examples
    --------
    >>> import trimesh
    >>> from voroforge import solid
    >>> m = solid.foam([trimesh.creation.box((10, 10, 10))], wall=2.0)
    >>> round(float(m.volume), 6)  # 10**3 - 8**3
    488.0
    """
    import trimesh

    cells = _convex(cells3d)
    given_hull = container is None
    if container is None:
        container = convex_mesh(np.vstack([c.vertices for c in cells]))
        held = sum(c.volume for c in cells)
        if held < container.volume * (1.0 - SOLID_FOAM_CONVEX_RTOL):
            warnings.warn(
                f"foam: the cells fill {held:.6g} of their convex hull's {container.volume:.6g}"
                " (a concave container, a torus's hole): the default container is that hull,"
                " so the foam fills the rest; pass container= (the mesh the cells were built"
                " in)",
                stacklevel=2,
            )
    bs, faces = _bubbles(cells, as_size(wall, field, "wall"))
    if not given_hull:
        _held(container, bs)
    parts = [container]
    centres, sizes = [], []
    for b, centre, rad in bs:
        if b is None:  # the walls fill this cell: a pore of size 0, which check() lists
            centres.append(centre)
            sizes.append(0.0)
            continue
        inv = b.copy()
        inv.invert()
        parts.append(inv)
        centres.append(centre)
        sizes.append(2.0 * rad)
    closed = sum(b is None for b, _, _ in bs)
    if closed:
        warnings.warn(
            f"foam: walls of {wall!r} fill {closed} of {len(bs)} cells (no bubble left there; "
            f"{len(bs) - closed} remain)",
            stacklevel=2,
        )
    m = trimesh.util.concatenate(parts)
    m.metadata.update(
        {
            "kind": "foam",
            "pores": {"centre": np.array(centres).reshape(-1, 3), "size": np.array(sizes)},
            "walls": dict(zip(("at", "thickness"), _walls(cells, bs, faces), strict=True)),
        }
    )
    return m
