"""Containers of 3D diagrams: a box, a convex solid (:class:`Convex`), a closed triangle mesh.

Every container becomes a *template*: a convex polyhedron ``(TV, TF, TR)`` in the layout of
:mod:`kernels.polyhedron` whose faces carry wall labels ``-1 - w``, plus the wall planes
``WP (W, 4)`` (``a x + b y + c z <= d``). Each cell starts as a copy of the template. A box
numbers its walls as voro++ does (0 x-min, 1 x-max, 2 y-min, 3 y-max, 4 z-min, 5 z-max); a
:class:`Convex` numbers them in the order of its half-spaces (after merging coplanar hull
facets). A mesh container's cells are built in its bounding box and then cut by the mesh
(:mod:`engine.mesh3d`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..config import AREA_MAX, VOLUME_RANGE

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

    def scaled(self, k: int) -> Template:
        """The same container with coordinates times ``2**k`` (exact)."""
        if k == 0:
            return self
        WP = self.WP.copy()
        WP[:, 3] = np.ldexp(WP[:, 3], k)
        return Template(
            np.ldexp(self.TV, k),
            self.TF,
            self.TR,
            WP,
            self.kind,
            float(np.ldexp(self.volume, 3 * k)),
            np.ldexp(self.bounds, k),
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

    (:data:`VOLUME_RANGE`; :data:`MESH_VOLUME_RANGE` for a mesh) or when its bounding box's
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
            hs = _hull_halfspaces(pts)
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
            hs = hs / np.linalg.norm(hs[:, :3], axis=1)[:, None]
        self.halfspaces = hs
        self._template = _convex_template(hs)
        self.volume = self._template.volume

    def __repr__(self) -> str:
        return f"Convex({len(self.halfspaces)} half-spaces, volume {self.volume:.6g})"


def _hull_halfspaces(pts: np.ndarray) -> np.ndarray:
    from scipy.spatial import ConvexHull, QhullError

    try:
        hull = ConvexHull(pts)
    except (QhullError, ValueError) as exc:
        raise ValueError(
            f"Convex points span no volume (Qhull: {str(exc).splitlines()[0]})"
        ) from None
    eq = hull.equations  # n . x + off <= 0, unit normals
    hs = np.column_stack([eq[:, :3], -eq[:, 3]])
    # merge the triangulated facets of one plane
    scale = float(np.abs(pts).max()) or 1.0
    keep: list[np.ndarray] = []
    for row in hs:
        if not any(
            np.abs(row[:3] - k[:3]).max() < 1e-12 and abs(row[3] - k[3]) < 1e-12 * scale
            for k in keep
        ):
            keep.append(row)
    return np.array(keep)


def _convex_template(hs: np.ndarray) -> Template:
    from scipy.optimize import linprog

    from ..kernels.cells3d import container_cut

    lo = np.zeros(3)
    hi = np.zeros(3)
    for a in range(3):
        for sgn, out in ((1.0, lo), (-1.0, hi)):
            c = np.zeros(3)
            c[a] = sgn
            res = linprog(
                c, A_ub=hs[:, :3], b_ub=hs[:, 3], bounds=[(None, None)] * 3, method="highs"
            )
            if res.status == 2:
                raise ValueError("the half-spaces of the Convex container have no common point")
            if res.status == 3:
                raise ValueError(
                    "the Convex container is unbounded (add half-spaces that close it)"
                )
            if res.status != 0:
                raise ValueError(f"could not bound the Convex container ({res.message})")
            out[a] = res.x[a]
    size = hi - lo
    far = float(max(np.abs(lo).max(), np.abs(hi).max()))
    if size.min() <= max(1e-12 * size.max(), 16.0 * np.spacing(far), 1e-300):
        raise ValueError("the Convex container has no volume (it is flat)")
    pad = 0.01 * size.max()
    k = len(hs)
    # Cut and measure in a frame centred on the solid: in absolute coordinates a small solid
    # far out lost its volume to cancellation (a tetrahedron of side 1e-3 at (5e5, 4e6, 100):
    # -0.00117 for 1.7e-10) or could not be closed at all.
    c = 0.5 * (lo + hi)
    d = hs[:, 3] - hs[:, :3] @ c
    t = box_template(lo - c - pad, hi - c + pad, labels=[-1 - (k + b) for b in range(6)])
    TV, TF, TR = t.TV, t.TF, t.TR
    for w in range(k):
        st, TV, TF, TR = container_cut(
            TV, TF, TR, hs[w, 0], hs[w, 1], hs[w, 2], d[w], -1 - w, 4 * (len(TV) + 8 * k + 64)
        )
        if st == 2:
            raise ValueError("the Convex container has no volume")
        if st not in (0, 1):
            raise ValueError("could not build the Convex container (degenerate half-spaces)")
    if (TF[:, 0] < -k).any():
        raise ValueError("could not close the Convex container (its half-spaces leave it open)")
    # tidy: walls never reached (redundant half-spaces) keep their numbers; volume from faces
    from ..kernels.polyhedron import moments

    vol = moments(TV, TF, len(TF), TR)[0]
    TV = TV + c
    return Template(TV, TF, TR, hs.copy(), "convex", float(vol), np.array([TV.min(0), TV.max(0)]))


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
