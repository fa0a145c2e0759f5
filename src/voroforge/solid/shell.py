"""Perforated shells: a surface thickened, with Voronoi openings (``solid.shell``; lamp shades).

The openings are the Voronoi cells of seeds on the surface, shrunk by half the web width:
a point of the thickened surface is material where the gap ``(d2 - d1) / 2`` between its
nearest and second-nearest seed is below half the web (it lies near a cell boundary), or
where it is within ``rim`` of the surface's open boundary. Meshed on the implicit route
(slabbed marching cubes): watertight by construction.
"""

from __future__ import annotations

import numpy as np
from scipy.spatial import cKDTree

from .. import config
from .fields import as_size
from .implicit import march
from .kernels import two_nearest
from .sdf import mesh_sdf_block

__all__ = ["shell"]

# up to this many openings, the grid samples' two nearest seeds come from a scan of every
# seed (half a KD-tree's CPU at 90 seeds: ``kernels.two_nearest``), beyond it from the tree
_BRUTE_SEEDS = 256


def _boundary_points(m, step: float) -> np.ndarray:
    """Points every ``step`` along the mesh's open boundary edges (empty when closed)."""
    e = np.sort(np.asarray(m.edges), axis=1)
    uniq, cnt = np.unique(e, axis=0, return_counts=True)
    b = uniq[cnt == 1]
    if not len(b):
        return np.zeros((0, 3))
    p, q = m.vertices[b[:, 0]], m.vertices[b[:, 1]]
    n = np.maximum(np.ceil(np.linalg.norm(q - p, axis=1) / step).astype(int), 1)
    t = np.concatenate([np.arange(k) / k for k in n])
    idx = np.repeat(np.arange(len(b)), n)
    return p[idx] + t[:, None] * (q - p)[idx]


def _with_rim(f_web, xyz, btree, rim_w: float, h: float) -> np.ndarray:
    """``min(f_web, d - rim_w)``, ``d`` each point's distance to the open boundary's points.

    A boundary point farther than ``f_web + rim_w`` changes nothing, so the points are
    queried in groups of that reach (doubling from ``h``) with it as the search's bound: the
    same values, and the many points far from the rim stop early (the lamp shade's 0.9M
    queries: 1.4 s of CPU unbounded). Points farther in height alone from every boundary
    point than their reach are not queried at all.
    """
    out = f_web.copy()
    reach = f_web + rim_w
    live = np.flatnonzero(reach > 0)  # elsewhere f_web <= -rim_w <= d - rim_w already
    # the height to the nearest boundary point's height bounds d from below: a point that
    # far from every rim's heights is not queried (most of a lamp shade's: its rims are two
    # circles at its ends)
    bz = np.sort(np.asarray(btree.data)[:, 2])
    z = xyz[live, 2]
    k = np.searchsorted(bz, z)
    below = np.abs(z - bz[np.maximum(k - 1, 0)])
    above = np.abs(bz[np.minimum(k, len(bz) - 1)] - z)
    live = live[np.minimum(below, above) < reach[live]]
    level = np.maximum(np.ceil(np.log2(reach[live] / h)), 0).astype(np.int64)
    for lv in np.unique(level):
        idx = live[level == lv]
        bound = h * 2.0 ** int(lv) * (1 + 1e-9)  # >= every reach of the group
        d = btree.query(xyz[idx], distance_upper_bound=bound, workers=-1)[0]
        out[idx] = np.minimum(out[idx], d - rim_w)  # inf (none within the bound): f_web
    return out


def shell(
    mesh_or_cells,
    thickness=2.0,
    openings=60,
    *,
    web=1.5,
    field=None,
    rim=None,
    voxel=None,
    smoothing: int = 5,
    seed: int = 0,
):
    """A surface thickened into a shell with Voronoi openings.

    Parameters
    ----------
    mesh_or_cells : trimesh.Trimesh
        The surface (open, like a lamp shade, or closed).
    thickness : float
        Shell thickness (> 0), centred on the surface.
    openings : int, (k, 3) array_like or None
        Number of openings (seeds sampled evenly on the surface), the seed points
        themselves (projected onto nothing: used as given), or None for a plain shell.
    web : float or (far, near)
        Width of the material between openings; with ``field`` the pair of widths at
        field 0 and 1 (openings graded, for example by height with a plane field).
    field : callable, optional
        A 0..1 3D field grading ``web``.
    rim : float, optional
        Solid band along the surface's open boundary (default: twice the smallest web).
    voxel : float, optional
        Grid spacing (default ``config.SOLID_VOXEL`` times the smaller of thickness and web).
    smoothing : int
        Taubin iterations after marching cubes.
    seed : int
        Seed of the even surface sampling.

    Returns
    -------
    trimesh.Trimesh
        Watertight. ``metadata["pores"]`` holds each opening's seed and approximate
        inscribed diameter (nearest-seed distance minus the web).
    """
    import trimesh

    if not isinstance(mesh_or_cells, trimesh.Trimesh):
        raise ValueError(
            f"shell: expected a trimesh.Trimesh surface, got {type(mesh_or_cells).__name__}"
        )
    surf = mesh_or_cells
    t = float(thickness)
    if not (np.isfinite(t) and t > 0):
        raise ValueError(f"thickness must be a finite number > 0, got {thickness!r}")
    wfun = as_size(web, field, "web")
    if openings is None:
        seeds = np.zeros((0, 3))
    elif np.ndim(openings) == 0:
        k = int(openings)
        if k < 2:
            raise ValueError(f"openings: at least 2 seeds, got {openings!r}")
        seeds, _ = trimesh.sample.sample_surface_even(surf, k, seed=seed)
        seeds = np.asarray(seeds)
    else:
        seeds = np.array(openings, dtype=np.float64).reshape(-1, 3)
    wmin = float(np.min(wfun(np.vstack([seeds, surf.vertices[:1]]))))
    rim_w = 2.0 * wmin if rim is None else float(rim)
    h = config.SOLID_VOXEL * min(t, wmin) if voxel is None else float(voxel)
    if not (np.isfinite(h) and h > 0):
        raise ValueError(f"voxel must be a finite number > 0, got {voxel!r}")
    band = 0.5 * t + 3.0 * h
    tris = np.ascontiguousarray(surf.vertices[surf.faces], dtype=np.float64)
    tzlo, tzhi = tris[:, :, 2].min(axis=1), tris[:, :, 2].max(axis=1)
    tree = cKDTree(seeds) if len(seeds) >= 2 else None
    bpts = _boundary_points(surf, 0.5 * h)
    btree = cKDTree(bpts) if len(bpts) else None

    def evaluate(shape, origin, krange):
        z0, z1 = origin[2] - band, origin[2] + h * (shape[2] - 1) + band
        sel = (tzhi >= z0) & (tzlo <= z1)
        d = mesh_sdf_block(surf, shape, origin, h, band=band, signed=False, tris=tris[sel])
        g = d - np.float32(0.5 * t)
        near = np.flatnonzero(g.ravel() < 3.0 * h)
        if tree is not None and len(near):
            ijk = np.column_stack(np.unravel_index(near, shape)).astype(np.float64)
            xyz = origin + h * ijk
            if len(seeds) <= _BRUTE_SEEDS:
                d1, d2 = two_nearest(xyz, seeds)
            else:  # every core queries its share of the points (the same answers)
                dd, _ = tree.query(xyz, k=2, workers=-1)
                d1, d2 = dd[:, 0], dd[:, 1]
            f_web = 0.5 * (d2 - d1) - 0.5 * wfun(xyz)
            if btree is not None:
                f_web = _with_rim(f_web, xyz, btree, rim_w, h)
            flat = g.ravel()
            flat[near] = np.maximum(flat[near], f_web.astype(np.float32))
            g = flat.reshape(shape)
        return g

    lo, hi = surf.bounds[0] - band, surf.bounds[1] + band
    m = march(evaluate, lo, hi, h, smoothing=smoothing)
    if len(seeds) >= 2:
        nn = tree.query(seeds, k=2)[0][:, 1]
        size = np.maximum(nn - wfun(seeds), 0.0)
    else:
        size = np.zeros(0)
    m.metadata.update({"kind": "shell", "pores": {"centre": seeds, "size": size}})
    return m
