"""Density-weighted moments of clipped cells: the integrals behind CVT energy and centroids.

For every cell ``g`` with site ``z_g``: ``mass = ∫ρ``, ``first = ∫ρ (x - z_g)`` and
``second = ∫ρ |x - z_g|^2`` over the cell (holes and parts included).

- ``density=None``: closed-form polygon moments (exact).
- a callable ``ρ(x, y)``: every triangle of a triangulation of each cell part gets Radon's
  7-point rule, exact for polynomials of degree 5. A hole-free part whose fan from its first
  vertex has no negatively oriented triangle (convex or star-shaped from there) uses that fan;
  any other part (a hole, a concave ring) is triangulated by GEOS (constrained Delaunay), so
  every node lies in the cell: ``ρ`` is never evaluated in a hole or past a concave edge
  (checker15 F6; the signed fan sampled it there).
- a raster ``(array (h, w), (xmin, ymin, xmax, ymax))``: the piecewise-constant density is
  integrated exactly, cell by pixel (row 0 is the top, as in an image; 0 outside the box).

The moments are computed for ``ρ`` scaled by a power of two so that its largest value is in
``[0.5, 1)`` (exact): a density of 1e-308 or 1e300 has the masses and centroids of a
density of 1 (its masses were subnormal and ``1 / mass`` overflowed: checker12 F1).
:meth:`Integrator.scaled` returns them so, in units of ``2**exponent``; calling the
integrator returns the true ones.
"""

from __future__ import annotations

import numpy as np
import shapely

from ..config import INTEGRATE_COVER_RTOL
from ..kernels.moments import raster_moments, uniform_moments
from .readonly import readonly

_S15 = np.sqrt(15.0)
_A1 = (6.0 - _S15) / 21.0
_A2 = (6.0 + _S15) / 21.0
#: Radon's degree-5 rule on a triangle: barycentric nodes (7, 3) and weights (sum 1).
RADON_NODES = np.array(
    [
        [1 / 3, 1 / 3, 1 / 3],
        [_A1, _A1, 1 - 2 * _A1],
        [_A1, 1 - 2 * _A1, _A1],
        [1 - 2 * _A1, _A1, _A1],
        [_A2, _A2, 1 - 2 * _A2],
        [_A2, 1 - 2 * _A2, _A2],
        [1 - 2 * _A2, _A2, _A2],
    ]
)
RADON_WEIGHTS = np.array(
    [9 / 40] + [(155 - _S15) / 1200] * 3 + [(155 + _S15) / 1200] * 3, dtype=np.float64
)


def unit_exponent_of(values) -> int:
    """``e`` such that the largest of ``values`` (>= 0) scaled by ``2**-e`` is in ``[0.5, 1)``.

    0 when all are 0 (or there are none).
    """
    top = float(np.max(values, initial=0.0))
    return int(np.frexp(top)[1]) if top > 0.0 else 0


def as_raster(density):
    """``(values (h, w) float64, box (4,) float64)`` from a raster spec, or None."""
    if isinstance(density, tuple) and len(density) == 2:
        values, bounds = density
    elif hasattr(density, "bounds") and (hasattr(density, "values") or hasattr(density, "array")):
        values = density.values if hasattr(density, "values") else density.array
        bounds = density.bounds
    else:
        return None
    if np.iscomplexobj(values) or np.iscomplexobj(bounds):  # the cast drops the imaginary part
        raise ValueError("density raster values and bounds must be real numbers, not complex")
    try:
        arr = np.array(values, dtype=np.float64, copy=True)
        box = np.array(bounds, dtype=np.float64).reshape(-1)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"density raster must be (array (h, w), bounds): {exc}") from None
    if arr.ndim != 2 or arr.shape[0] == 0 or arr.shape[1] == 0:
        raise ValueError(f"density raster must be a non-empty 2D array; got shape {arr.shape}")
    if not np.isfinite(arr).all() or (arr < 0).any():
        raise ValueError("density raster values must be finite and non-negative")
    if box.shape != (4,) or not np.isfinite(box).all() or not (box[0] < box[2] and box[1] < box[3]):
        raise ValueError(
            f"density raster bounds must be (xmin, ymin, xmax, ymax) with xmin < xmax, "
            f"ymin < ymax; got {np.asarray(bounds).tolist()}"
        )
    return np.ascontiguousarray(arr), box


class Integrator:
    """Computes cell moments for one density; output arrays are reused between calls.

    Parameters
    ----------
    density : None, callable, (array (h, w), bounds) or object with ``values``/``array`` and
        ``bounds``
        See the module docstring.
    n : int
        Number of cells (sizes the reusable outputs).

    Attributes
    ----------
    exponent : int
        :meth:`scaled`'s moments are those of ``ρ * 2**-exponent`` (0 for a uniform
        density; for a raster fixed by its largest value; for a callable by the largest
        value at the latest call's nodes): the true ones are ``np.ldexp(moment, exponent)``.
    """

    def __init__(self, density, n: int):
        self.kind = "uniform"
        self.raster = None
        self.func = None
        self.exponent = 0
        if density is not None:
            ras = as_raster(density)
            if ras is not None:
                self.kind = "raster"
                values, box = ras
                self.exponent = unit_exponent_of(values)
                self.raster = (np.ldexp(values, -self.exponent), box)
            elif callable(density):
                self.kind = "callable"
                self.func = density
            else:
                raise ValueError(
                    "density must be None, a callable rho(x, y), or a raster "
                    f"(array (h, w), (xmin, ymin, xmax, ymax)); got {type(density).__name__}"
                )
        self.mass = np.zeros(n)
        self.first = np.zeros((n, 2))
        self.second = np.zeros(n)

    def __call__(self, buffers, origin):
        """``(mass (n,), first (n, 2), second (n,))`` of the cells in GeoArrow ``buffers``.

        The returned arrays are this integrator's own buffers: copy them to keep them. A
        density whose moments leave float64's range gives 0 or inf (use :meth:`scaled`).
        """
        self.scaled(buffers, origin)
        if self.exponent:
            with np.errstate(over="ignore", under="ignore"):
                for arr in (self.mass, self.first, self.second):
                    np.ldexp(arr, self.exponent, out=arr)
        return self.mass, self.first, self.second

    def scaled(self, buffers, origin):
        """As :meth:`__call__`, in units of ``2**self.exponent`` (see the class)."""
        coords, ring, poly, geom = buffers
        # the sites as a read-only view: a frozen diagram's (power fit) or a fresh array
        # (Lloyd's iterate); numba types the flag, and uniform_moments compiled twice
        origin = readonly(origin, np.float64)
        if self.kind == "uniform":
            uniform_moments(coords, ring, poly, geom, origin, self.mass, self.first, self.second)
        elif self.kind == "raster":
            values, box = self.raster
            raster_moments(
                coords, ring, poly, geom, origin, values, box, self.mass, self.first, self.second
            )
        else:
            self._quadrature(coords, ring, poly, geom, origin)
        return self.mass, self.first, self.second

    def _quadrature(self, coords, ring, poly, geom, origin):
        n = len(geom) - 1
        n_ring = len(ring) - 1
        poly_of_ring = np.repeat(np.arange(len(poly) - 1), np.diff(poly))
        cell_of_poly = np.repeat(np.arange(n), np.diff(geom))
        cell_of_ring = cell_of_poly[poly_of_ring]
        hole = np.arange(n_ring) != poly[poly_of_ring]
        open_len = np.maximum(np.diff(ring) - 1, 0)  # closed rings repeat the first vertex
        n_tri = np.maximum(open_len - 2, 0)
        tri_ring = np.repeat(np.arange(n_ring), n_tri)
        start = np.zeros(n_ring + 1, dtype=np.int64)
        np.cumsum(n_tri, out=start[1:])
        k = np.arange(start[-1]) - start[tri_ring] + 1
        i0 = ring[:-1][tri_ring]
        o = origin[cell_of_ring[tri_ring]]
        v0 = coords[i0] - o
        v1 = coords[i0 + k] - o
        v2 = coords[i0 + k + 1] - o
        e1 = v1 - v0
        e2 = v2 - v0
        area = 0.5 * (e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0])
        ring_area = np.bincount(tri_ring, area, minlength=n_ring)
        sign = np.where(ring_area >= 0.0, 1.0, -1.0) * np.where(hole, -1.0, 1.0)
        scale = area * sign[tri_ring]
        cell = cell_of_ring[tri_ring]
        # a part's fan is its triangulation when no triangle is negative (winding argument:
        # the signed fan sums to the ring's winding number) and it has no hole
        poly_of_tri = poly_of_ring[tri_ring]
        bad = np.zeros(len(poly) - 1, dtype=np.bool_)
        bad[poly_of_ring[hole]] = True
        bad[poly_of_tri[scale < 0.0]] = True
        if bad.any():
            keep = (scale > 0.0) & ~bad[poly_of_tri]  # zero triangles add exactly 0
            fan_of = np.flatnonzero(bad)
            t = _triangulate(coords, ring, poly, fan_of)
            if t is not None:
                tri, owner, ok = t
                signed_fan = np.zeros(len(bad), dtype=np.bool_)
                signed_fan[fan_of[~ok]] = True  # GEOS failed on these: the signed fan, as before
                keep |= signed_fan[poly_of_tri]
                tcell = cell_of_poly[fan_of[owner]]
                to = origin[tcell]
                t0, t1, t2 = tri[:, 0] - to, tri[:, 1] - to, tri[:, 2] - to
                f1, f2 = t1 - t0, t2 - t0
                tarea = np.abs(0.5 * (f1[:, 0] * f2[:, 1] - f1[:, 1] * f2[:, 0]))
                v0 = np.concatenate([v0[keep], t0])
                v1 = np.concatenate([v1[keep], t1])
                v2 = np.concatenate([v2[keep], t2])
                o = np.concatenate([o[keep], to])
                scale = np.concatenate([scale[keep], tarea])
                cell = np.concatenate([cell[keep], tcell])
        # nodes (T, 7, 2) relative to the site
        nodes = (
            RADON_NODES[None, :, 0, None] * v0[:, None, :]
            + RADON_NODES[None, :, 1, None] * v1[:, None, :]
            + RADON_NODES[None, :, 2, None] * v2[:, None, :]
        )
        ax = (nodes[:, :, 0] + o[:, None, 0]).ravel()
        ay = (nodes[:, :, 1] + o[:, None, 1]).ravel()
        rho = _evaluate(self.func, ax, ay).reshape(nodes.shape[:2])
        self.exponent = unit_exponent_of(rho)
        if self.exponent:
            rho = np.ldexp(rho, -self.exponent)
        wq = rho * RADON_WEIGHTS[None, :] * scale[:, None]
        self.mass[:] = np.bincount(cell, wq.sum(axis=1), minlength=n)
        self.first[:, 0] = np.bincount(cell, (wq * nodes[:, :, 0]).sum(axis=1), minlength=n)
        self.first[:, 1] = np.bincount(cell, (wq * nodes[:, :, 1]).sum(axis=1), minlength=n)
        r2 = nodes[:, :, 0] ** 2 + nodes[:, :, 1] ** 2
        self.second[:] = np.bincount(cell, (wq * r2).sum(axis=1), minlength=n)


def _triangulate(coords, ring, poly, parts):
    """Triangles of the polygon ``parts`` by GEOS (constrained Delaunay), or None if it fails.

    Returns ``(triangles (t, 3, 2), part (t,) index into parts, covered (len(parts),) bool)``:
    a part whose triangles' areas miss its own area is left out (``covered`` False).
    """
    rings, owner_ring = _ranges(poly[parts], poly[parts + 1])
    idx, ring_of = _ranges(ring[rings], ring[rings + 1])
    try:
        lr = shapely.linearrings(coords[idx], indices=ring_of)
        polys = shapely.polygons(lr, indices=owner_ring)
        tris, owner = shapely.get_parts(
            shapely.constrained_delaunay_triangles(polys), return_index=True
        )
    except shapely.errors.ShapelyError:
        return None
    tri = shapely.get_coordinates(tris).reshape(-1, 4, 2)[:, :3]
    e1, e2 = tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
    got = np.bincount(
        owner, np.abs(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]) / 2, minlength=len(parts)
    )
    want = shapely.area(polys)
    ok = np.abs(got - want) <= INTEGRATE_COVER_RTOL * want
    sel = ok[owner]
    return tri[sel], owner[sel], ok


def _ranges(starts, stops):
    """Concatenated ``arange(starts[i], stops[i])`` and the ``i`` of each entry."""
    lens = stops - starts
    which = np.repeat(np.arange(len(lens)), lens)
    return np.repeat(starts - np.cumsum(lens) + lens, lens) + np.arange(lens.sum()), which


def _evaluate(func, x, y):
    try:
        vals = np.asarray(func(x, y), dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"density(x, y) must return real values for array inputs: {exc}") from None
    try:
        vals = np.broadcast_to(vals, x.shape)
    except ValueError:
        raise ValueError(
            f"density(x, y) must return one value per point: got shape {vals.shape} for "
            f"{x.shape} points"
        ) from None
    if not np.isfinite(vals).all() or (vals < 0).any():
        raise ValueError("density(x, y) must return finite, non-negative values")
    return vals
