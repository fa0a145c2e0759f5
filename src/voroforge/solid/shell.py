"""Perforated shells: a surface thickened, with Voronoi openings (``solid.shell``; lamp shades).

The openings are the Voronoi cells of seeds on the surface, shrunk by half the web width:
a point of the thickened surface is material where the gap ``(d2 - d1) / 2`` between its
nearest and second-nearest seed is below half the web (it lies near a cell boundary), or
where it is within ``rim`` of the surface's open boundary. Meshed on the implicit route
(slabbed marching cubes): watertight by construction.
"""

from __future__ import annotations

import numpy as np

from .. import config
from .fields import as_size
from .implicit import march
from .kernels import two_nearest
from .sdf import mesh_sdf_block
from .surfaces import boundary_edges, sample_even

__all__ = ["shell"]

# up to this many openings, the grid samples' two nearest seeds come from a scan of every
# seed (half a KD-tree's CPU at 90 seeds: ``kernels.two_nearest``), beyond it from the tree
_BRUTE_SEEDS = 256
# the rim's queries, in runs of this many points by height, each scanning the open
# boundary's points within its heights' reach
_RIM_RUN = 4096


def _boundary_points(verts, faces, step: float) -> np.ndarray:
    """Points every ``step`` along the mesh's open boundary edges (empty when closed).

    Vertices at one position are one (an unwelded mesh, every triangle with its own three
    vertices as STL gives them, had every edge open: the rim covered the whole surface and
    no opening was cut).
    """
    verts, same = np.unique(verts, axis=0, return_inverse=True)
    b = boundary_edges(same.reshape(-1)[faces])
    if not len(b):
        return np.zeros((0, 3))
    p, q = verts[b[:, 0]], verts[b[:, 1]]
    n = np.maximum(np.ceil(np.linalg.norm(q - p, axis=1) / step).astype(int), 1)
    t = np.concatenate([np.arange(k) / k for k in n])
    idx = np.repeat(np.arange(len(b)), n)
    return p[idx] + t[:, None] * (q - p)[idx]


def _with_rim(f_web, xyz, bpts, rim_w: float) -> np.ndarray:
    """``min(f_web, d - rim_w)``, ``d`` each point's distance to the open boundary's points.

    A boundary point farther than the reach ``f_web + rim_w`` changes nothing, and the
    height difference bounds the distance from below: points farther in height from every
    boundary point than their reach are not queried (most of a lamp shade's: its rims are
    two circles at its ends), the others are taken in runs sorted by height, each run
    scanning only the boundary points within its heights' reach (``kernels.two_nearest``).
    The same values as a KD-tree's nearest distance (a nearer point within the reach is
    always in the run's window; beyond the reach the value is ``f_web`` either way).
    """
    out = f_web.copy()
    reach = f_web + rim_w
    live = np.flatnonzero(reach > 0)  # elsewhere f_web <= -rim_w <= d - rim_w already
    bp = bpts[np.argsort(bpts[:, 2], kind="stable")]
    if len(bp) == 1:  # two_nearest scans two points at least: the one twice
        bp = np.vstack([bp, bp])
    bz = bp[:, 2]
    z = xyz[live, 2]
    k = np.searchsorted(bz, z)
    below = np.abs(z - bz[np.maximum(k - 1, 0)])
    above = np.abs(bz[np.minimum(k, len(bz) - 1)] - z)
    live = live[np.minimum(below, above) < reach[live]]
    live = live[np.argsort(xyz[live, 2], kind="stable")]
    for r0 in range(0, len(live), _RIM_RUN):
        idx = live[r0 : r0 + _RIM_RUN]
        zr, rr = xyz[idx, 2], reach[idx]
        lo = np.searchsorted(bz, float((zr - rr).min()), side="left")
        hi = np.searchsorted(bz, float((zr + rr).max()), side="right")
        if hi - lo < 2:  # two points at least (the others are beyond the reach anyway)
            lo = min(lo, len(bz) - 2)
            hi = lo + 2
        d = two_nearest(xyz[idx], bp[lo:hi])[0]
        out[idx] = np.minimum(out[idx], d - rim_w)
    return out


def _seed_points(openings) -> np.ndarray:
    """``openings`` given as points: a finite (k, 3) array of 2 distinct seeds at least.

    A (3, 2) array (a 2D design's seeds) was read as 2 seeds, NaN rows were taken and one
    seed (or copies of one) gave a plain shell, all without a word.
    """
    seeds = np.array(openings, dtype=np.float64)
    if seeds.ndim != 2 or seeds.shape[1] != 3:
        raise ValueError(f"openings: seed points as a (k, 3) array, got shape {seeds.shape}")
    bad = np.flatnonzero(~np.isfinite(seeds).all(axis=1))
    if len(bad):
        raise ValueError(f"openings: seed points must be finite (row {int(bad[0])} is not)")
    if len(np.unique(seeds, axis=0)) < 2:
        raise ValueError(f"openings: at least 2 distinct seed points, got {len(seeds)} rows")
    return seeds


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
    bare: bool = False,
):
    """A surface thickened into a shell with Voronoi openings.

    Parameters
    ----------
    mesh_or_cells : trimesh.Trimesh or voroforge.solid.implicit.Bare
        The surface (open, like a lamp shade, or closed): anything with ``vertices``
        (n, 3) and ``faces`` (t, 3), such as :func:`voroforge.solid.surfaces.revolve`'s.
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
        Seed of the even surface sampling (:func:`voroforge.solid.surfaces.sample_even`).
    bare : bool
        Return a :class:`~voroforge.solid.implicit.Bare` mesh (no trimesh import).

    Returns
    -------
    trimesh.Trimesh or Bare
        Watertight. ``metadata["pores"]`` holds each opening's seed and approximate
        inscribed diameter (nearest-seed distance minus the web); ``metadata["walls"]``
        the thickness (``at`` (1, 3) a point of the surface, ``thickness`` (1,)).
    """
    surf = mesh_or_cells
    if not (hasattr(surf, "vertices") and hasattr(surf, "faces")):
        raise ValueError(f"shell: expected a trimesh.Trimesh surface, got {type(surf).__name__}")
    verts = np.asarray(surf.vertices, dtype=np.float64)
    faces = np.asarray(surf.faces, dtype=np.int64)
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
        if k > config.SOLID_MAX_OPENINGS:
            raise ValueError(
                f"openings: at most {config.SOLID_MAX_OPENINGS:,} seeds on one shell, got {k:,}"
            )
        seeds = sample_even(surf, k, seed=seed)
    else:
        seeds = _seed_points(openings)
    wmin = float(np.min(wfun(np.vstack([seeds, verts[:1]]))))
    rim_w = 2.0 * wmin if rim is None else float(rim)
    h = config.SOLID_VOXEL * min(t, wmin) if voxel is None else float(voxel)
    if not (np.isfinite(h) and h > 0):
        raise ValueError(f"voxel must be a finite number > 0, got {voxel!r}")
    band = 0.5 * t + 3.0 * h
    tris = np.ascontiguousarray(verts[faces])
    tzlo, tzhi = tris[:, :, 2].min(axis=1), tris[:, :, 2].max(axis=1)
    tree = None
    if len(seeds) > _BRUTE_SEEDS:
        from scipy.spatial import cKDTree

        tree = cKDTree(seeds)
    bpts = _boundary_points(verts, faces, 0.5 * h)

    def evaluate(shape, origin, krange):
        z0, z1 = origin[2] - band, origin[2] + h * (shape[2] - 1) + band
        sel = (tzhi >= z0) & (tzlo <= z1)
        d = mesh_sdf_block(surf, shape, origin, h, band=band, signed=False, tris=tris[sel])
        g = d - np.float32(0.5 * t)
        near = np.flatnonzero(g.ravel() < 3.0 * h)
        if len(seeds) >= 2 and len(near):
            ijk = np.column_stack(np.unravel_index(near, shape)).astype(np.float64)
            xyz = origin + h * ijk
            if tree is None:
                d1, d2 = two_nearest(xyz, seeds)
            else:  # every core queries its share of the points (the same answers)
                dd, _ = tree.query(xyz, k=2, workers=-1)
                d1, d2 = dd[:, 0], dd[:, 1]
            f_web = 0.5 * (d2 - d1) - 0.5 * wfun(xyz)
            if len(bpts):
                f_web = _with_rim(f_web, xyz, bpts, rim_w)
            flat = g.ravel()
            flat[near] = np.maximum(flat[near], f_web.astype(np.float32))
            g = flat.reshape(shape)
        return g

    used = verts[np.unique(faces)]
    lo, hi = used.min(axis=0) - band, used.max(axis=0) + band
    m = march(evaluate, lo, hi, h, smoothing=smoothing, bare=bare)
    if len(seeds) >= 2:
        nn = two_nearest(seeds, seeds)[1]  # the nearest other seed (itself at 0)
        size = np.maximum(nn - wfun(seeds), 0.0)
    else:
        size = np.zeros(0)
    # the shell's one wall thickness, at a point of the surface (``check(min_wall=)``)
    walls = {"at": used[:1].copy(), "thickness": np.array([t])}
    m.metadata.update({"kind": "shell", "pores": {"centre": seeds, "size": size}, "walls": walls})
    return m
