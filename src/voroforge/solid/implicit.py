"""The implicit route: a signed-distance field on a voxel grid, meshed by marching cubes.

The grid is swept in slabs along z (bounded memory: one slab at a time); consecutive slabs
share one plane of samples, copied bit for bit, so their marching-cubes vertices on that
plane are identical and merge exactly. Unions are minima of distances (smooth minima for
organic nodes), trims are maxima: no mesh booleans, watertight by construction.
"""

from __future__ import annotations

import numpy as np

from .. import config
from ..engine.csr import used_only
from .kernels import taubin
from .sdf import capsules_block, mesh_sdf_block
from .threemf import on_grid

__all__ = ["Bare", "capsules_mesh", "march", "prefetch_container", "signed_volume", "spare_core"]

_SLAB = 96  # z planes per slab
_JITTER = np.sqrt([2.0, 3.0, 5.0]) * 1e-3


def signed_volume(m) -> float:
    """Signed volume of a closed triangle mesh (divergence theorem; fast, no caching)."""
    t = np.asarray(m.vertices)[np.asarray(m.faces)]
    return float(np.einsum("ij,ij->i", t[:, 0], np.cross(t[:, 1], t[:, 2])).sum() / 6.0)


def _inward(m) -> bool:
    """Whether the faces point inwards: those at the highest vertex must face up (cheap)."""
    v, f = np.asarray(m.vertices), np.asarray(m.faces)
    top = int(np.argmax(v[:, 2]))
    t = v[f[(f[:, 0] == top) | (f[:, 1] == top) | (f[:, 2] == top)]]  # not any(axis=1): 10x
    n = np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])
    return float(n[:, 2].sum()) < 0


class Bare:
    """A closed triangle mesh as bare arrays and a metadata dict, without trimesh.

    What a design build previews and writes (:func:`voroforge.solid.render.preview`,
    :func:`voroforge.solid.threemf.write_3mf`) needs no more, and trimesh's import is about
    0.3 s of a first build. :meth:`trimesh` gives the Trimesh the public builders return.

    Attributes
    ----------
    vertices : (n, 3) float64
    faces : (t, 3) int64
        Every vertex used.
    metadata : dict
    """

    #: A container field started ahead of its lattice (:func:`prefetch_container`).
    _ahead = None

    def __init__(self, vertices, faces, metadata=None):
        self.vertices = np.asarray(vertices, dtype=np.float64)
        self.faces = np.asarray(faces, dtype=np.int64)
        self.metadata = dict(metadata or {})

    @property
    def bounds(self) -> np.ndarray:
        """``[[xmin, ymin, zmin], [xmax, ymax, zmax]]`` (every vertex is used)."""
        return np.array([self.vertices.min(axis=0), self.vertices.max(axis=0)])

    def trimesh(self):
        """The same mesh as a ``trimesh.Trimesh`` (``process=False``), metadata copied."""
        import trimesh

        m = trimesh.Trimesh(self.vertices, self.faces, process=False)
        m.metadata.update(self.metadata)
        return m


def march(evaluate, lo, hi, h, *, smoothing: int = 0, progress=None, bare: bool = False):
    """Mesh the zero level set of ``evaluate`` over the box ``lo..hi`` at spacing ``h``.

    Parameters
    ----------
    evaluate : callable
        ``evaluate(shape, origin, z_range) -> (nx, ny, nz) float32`` field on the block of
        samples ``origin + h * (i, j, k)`` (negative inside). Called once per slab along z,
        in order; where a core is free (:func:`spare_core`), every slab's but the first on a
        second thread while the previous slab is meshed (so it must not depend on state the
        caller changes meanwhile).
    lo, hi : (3,) float
        The region; the grid adds two samples of margin, which must be outside.
    h : float
        Grid spacing.
    smoothing : int
        Taubin smoothing iterations (volume-preserving, topology unchanged).
    progress : callable, optional
        Called with the fraction done after each slab.
    bare : bool
        Return a :class:`Bare` mesh (no trimesh import) instead of a Trimesh.

    Returns
    -------
    trimesh.Trimesh or Bare
        Its vertices rounded to :func:`grid_decimals` places (``metadata["decimals"]``).
    """
    from skimage.measure import marching_cubes

    lo, n = _grid(lo, hi, h)
    verts, faces, nv = [], [], 0
    prev = None
    bounds: list[int] = []
    slabs = _slabs(lo, n, h)
    for (_, _, (k0, k1)), g in zip(slabs, _evaluated(evaluate, slabs), strict=True):
        g = np.asarray(g, dtype=np.float32)
        if prev is not None:
            g[:, :, 0] = prev  # the shared plane, bit for bit
        g[g == 0] = np.float32(1e-6 * h)  # no vertex exactly on a sample
        prev = g[:, :, -1].copy()
        if (g < 0).any() and (g > 0).any():
            v, f, _, _ = marching_cubes(g, 0.0, method="lewiner", allow_degenerate=False)
            v = v.astype(np.float64)
            v[:, 2] += k0
            verts.append(v)
            faces.append(f.astype(np.int64) + nv)
            nv += len(v)
        bounds.extend((k0, k1))
        if progress is not None:
            progress(k1 / (n[2] - 1))
    if not verts:
        raise ValueError("the solid is empty at this resolution (nothing inside the field)")
    v = np.vstack(verts)
    f = np.vstack(faces)
    # only vertices on a shared slab plane can repeat (each slab's own are unique already)
    planes = np.array(sorted(set(bounds)), dtype=np.float64)
    on = np.isin(v[:, 2], planes)
    idx = np.flatnonzero(on)
    remap = np.arange(len(v))
    if len(idx):
        sub = v[idx]
        order = np.lexsort((sub[:, 0], sub[:, 1], sub[:, 2]))
        s_sorted = sub[order]
        new = np.concatenate([[True], (np.diff(s_sorted, axis=0) != 0).any(axis=1)])
        grp = np.cumsum(new) - 1
        first = idx[order][new]
        remap[idx[order]] = first[grp]
    f = remap[f]
    f = f[(f[:, 0] != f[:, 1]) & (f[:, 1] != f[:, 2]) & (f[:, 0] != f[:, 2])]
    v, f = used_only(v, f)  # the vertices the faces use, in their order
    m = Bare(v * h + lo[None], f)
    if _inward(m):  # orientation follows the field's sign convention: make it outward
        m.faces = np.ascontiguousarray(m.faces[:, ::-1])
    if smoothing:
        m.vertices = taubin(m.vertices, m.faces, int(smoothing))
    # a decimal grid 1e5 times finer than the voxel: far below the surface's accuracy, and
    # the 3MF text of such numbers is written by a kernel (solid.threemf), not float repr
    d = grid_decimals(h)
    m.vertices = on_grid(m.vertices, d)
    m.metadata["decimals"] = d
    return m if bare else m.trimesh()


#: Whether the build's steps use a second thread: None decides per call (:func:`spare_core`),
#: True or False forces it (the values are the same either way).
THREADS: bool | None = None


def spare_core() -> bool:
    """Whether a second thread can expect a core of its own (:data:`THREADS` decides first).

    Where the process may run on two cores or more and the load average leaves one idle
    (below ``cores - 1.5``, as ``make -l`` limits its jobs). On a busy machine a second
    thread only time-slices with the first: no wall time saved, some CPU spent switching
    (about 0.2 s of a solid build's CPU at load 2 on two cores).
    """
    if THREADS is not None:
        return bool(THREADS)
    import os

    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    try:
        load = os.getloadavg()[0]
    except (AttributeError, OSError):  # no load average here: trust the core count
        load = 0.0
    return (cores or 1) >= 2 and load < (cores or 1) - 1.5


def _evaluated(evaluate, slabs):
    """Each slab's field in turn, the next one evaluated on a second thread meanwhile.

    While the caller marches a slab (scikit-image's marching cubes holds the GIL), the
    next slab's field is sampled (kernels that release it): at most two slabs' fields
    are held at once. An error of ``evaluate`` is raised where its slab is taken.
    """
    import threading

    def start(slab):
        box = {}

        def run():
            try:
                box["field"] = evaluate(*slab)
            except Exception as exc:  # raised by the caller's thread, below
                box["error"] = exc

        thread = threading.Thread(target=run, name="voroforge-slab", daemon=True)
        thread.start()
        return thread, box

    if len(slabs) < 2 or not spare_core():
        yield from (evaluate(*slab) for slab in slabs)
        return
    pending = None
    for i, slab in enumerate(slabs):
        if pending is None:
            field = evaluate(*slab)  # the first slab on the caller's thread
        else:
            pending[0].join()
            if "error" in pending[1]:
                raise pending[1]["error"]
            field = pending[1]["field"]
        pending = start(slabs[i + 1]) if i + 1 < len(slabs) else None
        yield field


def _grid(lo, hi, h):
    """:func:`march`'s grid over ``lo..hi``: its first sample and its (3,) sample counts."""
    # a small irrational offset keeps samples off the axis-aligned planes of CAD meshes (a ray
    # along a mesh face would make the inside parity ambiguous)
    lo = np.asarray(lo, np.float64) - 2 * h - h * _JITTER
    hi = np.asarray(hi, np.float64) + 2 * h
    count = float(np.prod(np.ceil((hi - lo) / h) + 1.0))  # in floats: no int64 overflow
    if not count <= config.SOLID_MAX_VOXELS:
        raise ValueError(
            f"the voxel grid would have {count:.3g} samples "
            f"(at most {config.SOLID_MAX_VOXELS:.3g}); use a larger voxel"
        )
    n = np.ceil((hi - lo) / h).astype(np.int64) + 1
    return lo, n


def _slabs(lo, n, h):
    """The grid's slabs along z: ``(shape, origin, (k0, k1))``, sharing their end planes."""
    out = []
    k0 = 0
    while k0 < n[2] - 1:
        k1 = min(k0 + _SLAB, n[2] - 1)
        origin = lo + np.array([0.0, 0.0, k0 * h])
        out.append(((int(n[0]), int(n[1]), int(k1 - k0 + 1)), origin, (k0, k1)))
        k0 = k1
    return out


def grid_decimals(h: float) -> int:
    """Decimal places of the implicit route's vertices at voxel ``h`` (a grid <= 1e-5 h)."""
    return int(np.ceil(5.0 - np.log10(h)))


class _ContainerField:
    """``(shape, origin, z_top) -> sdf`` of a container (and its skin), blocks computed ahead.

    :meth:`start` computes the blocks of a grid's slabs on a second thread (the distance and
    parity kernels release the GIL); a call for one of them waits for it and takes it, any
    other block is computed on the spot. The same values either way.
    """

    def __init__(self, container, skin, h):
        self.tris = np.ascontiguousarray(container.vertices[container.faces], dtype=np.float64)
        self.zmin = self.tris[:, :, 2].min(axis=1)
        self.band = max(3.0 * h, 1.5 * skin + 2 * h)
        self.container, self.skin, self.h = container, float(skin), float(h)
        self.ahead: dict = {}

    def block(self, shape, origin, z_top):
        sel = self.zmin <= z_top + self.band  # parity needs everything below the slab too
        tris = self.tris[sel]
        return mesh_sdf_block(self.container, shape, origin, self.h, band=self.band, tris=tris)

    def start(self, lo, hi):
        """Compute the blocks of :func:`march`'s slabs over ``lo..hi`` on a second thread."""
        import threading

        jobs = []
        for shape, origin, _ in _slabs(*_grid(lo, hi, self.h), self.h):
            z_top = origin[2] + self.h * (shape[2] - 1)
            key = (shape, origin.tobytes(), z_top)
            self.ahead[key] = [threading.Event(), None]
            jobs.append((key, shape, origin, z_top))

        def run():
            for key, shape, origin, z_top in jobs:
                slot = self.ahead[key]
                try:
                    slot[1] = self.block(shape, origin, z_top)
                except Exception:  # the caller computes this block again, and raises
                    pass
                finally:
                    slot[0].set()

        threading.Thread(target=run, name="voroforge-container", daemon=True).start()
        return self

    def __call__(self, shape, origin, z_top):
        slot = self.ahead.pop((tuple(shape), np.asarray(origin).tobytes(), z_top), None)
        if slot is not None:
            slot[0].wait()
            if slot[1] is not None:
                return slot[1]
        return self.block(shape, origin, z_top)


def prefetch_container(container, skin: float, voxel: float) -> None:
    """Start a trimmed lattice's container field on a second thread, for what comes later.

    For :func:`capsules_mesh` with this ``container`` (a :class:`Bare` mesh, the same
    object), ``skin > 0`` and ``voxel``: with a skin the grid is the container's box, so
    its blocks are known before the struts are; a design build computes them while its
    cells relax. The first such call takes them (the same values as computed in place);
    the blocks are held by the container until then.
    """
    if not (isinstance(container, Bare) and skin > 0 and voxel and np.isfinite(voxel)):
        return
    if not spare_core():
        return
    h = float(voxel)
    if h <= 0:
        return
    field = _ContainerField(container, skin, h)
    lo, hi = container.bounds[0] - 2 * h, container.bounds[1] + 2 * h  # as capsules_mesh
    container._ahead = field.start(lo, hi)


def _container_field(container, skin, h):
    """A function ``(shape, origin, z_top) -> sdf`` of the container (and its skin)."""
    field = getattr(container, "_ahead", None)
    if field is not None:
        container._ahead = None  # one use
        if field.skin == float(skin) and field.h == float(h):
            return field
    return _ContainerField(container, skin, h)


def _reaching(c, below, origin, h, a, b, reach) -> np.ndarray:
    """Which struts' boxes hold a sample where the container's field ``c`` is under ``below``.

    Elsewhere the struts cannot change the trimmed field, so a strut whose box (``reach``
    about its segment, the samples the capsule kernel visits) holds no such sample is left
    out, the same field bit for bit: random cells fill the container's box, and most of an
    L-bracket's box is outside it. The struts' union ``g`` is at most its band, so where
    ``c`` is at least that band, ``max(g, c)`` is ``c`` (outside the container); with a skin,
    where ``c >= -skin / 2``, the skin's ``max(c, -c - skin)`` is ``c``, at most
    ``max(g, c)``, so the field is ``c`` there too (outside and in the skin's outer half).
    Counted by a summed-area table of the blocks of 4^3 samples that hold one: one lookup
    per strut.
    """
    live = c < below
    if live.all():
        return np.ones(len(a), dtype=bool)
    # blocks of 4 x 4 x 4 samples that hold one (a box touching such a block is kept: a
    # superset, safe), and their summed-area table
    n = np.array(c.shape)
    nb = -(-n // 4)
    pad = np.zeros(tuple(4 * nb), dtype=bool)
    pad[: n[0], : n[1], : n[2]] = live
    block = pad.reshape(nb[0], 4, nb[1], 4, nb[2], 4).any(axis=(1, 3, 5))
    sat = np.zeros(tuple(nb + 1), dtype=np.int32)
    sat[1:, 1:, 1:] = (
        block.cumsum(0, dtype=np.int32).cumsum(1, dtype=np.int32).cumsum(2, dtype=np.int32)
    )
    # the kernel's box, one sample wider each way, in blocks
    lo = np.floor((np.minimum(a, b) - reach[:, None] - origin) / h).astype(np.int64) - 1
    hi = np.ceil((np.maximum(a, b) + reach[:, None] - origin) / h).astype(np.int64) + 1
    lo = np.clip(lo, 0, n - 1) // 4
    hi = (np.clip(hi, -1, n - 1) + 1 + 3) // 4  # exclusive
    x0, y0, z0 = lo.T
    x1, y1, z1 = np.maximum(hi, lo).T
    count = (
        sat[x1, y1, z1]
        - sat[x0, y1, z1]
        - sat[x1, y0, z1]
        - sat[x1, y1, z0]
        + sat[x0, y0, z1]
        + sat[x0, y1, z0]
        + sat[x1, y0, z0]
        - sat[x0, y0, z0]
    )
    return count > 0


def capsules_mesh(
    struts, *, voxel=None, smoothing=10, container=None, skin=0.0, smooth=None, bare=False
):
    """Union of round-cone struts (smooth minimum at the nodes) meshed by marching cubes.

    Parameters
    ----------
    struts : dict
        ``a``, ``b`` (E, 3) end points and ``ra``, ``rb`` (E,) radii.
    voxel : float, optional
        Grid spacing (default ``config.SOLID_VOXEL`` times the smallest radius).
    smoothing : int
        Taubin iterations after marching cubes.
    container : Trimesh or Bare, optional
        Trim to this closed mesh; with ``skin > 0`` also keep a skin of that thickness.
    skin : float
        Skin thickness inside the container's surface.
    smooth : float, optional
        Blend radius of the smooth minimum at the nodes (default the mean radius; 0: a plain
        union, spherical nodes).
    bare : bool
        Return a :class:`Bare` mesh instead of a Trimesh.

    Returns
    -------
    trimesh.Trimesh or Bare
    """
    a, b = np.asarray(struts["a"]), np.asarray(struts["b"])
    ra, rb = np.asarray(struts["ra"]), np.asarray(struts["rb"])
    rmin = float(min(ra.min(), rb.min()))
    h = config.SOLID_VOXEL * rmin if voxel is None else float(voxel)
    if not (np.isfinite(h) and h > 0):
        raise ValueError(f"voxel must be a finite number > 0, got {voxel!r}")
    k = float(np.mean(np.concatenate([ra, rb]))) if smooth is None else float(smooth)
    rmax = float(max(ra.max(), rb.max()))
    reach = rmax + k + 3 * h
    lo = np.minimum(a.min(0), b.min(0)) - reach
    hi = np.maximum(a.max(0), b.max(0)) + reach
    zlo = np.minimum(a[:, 2], b[:, 2]) - reach
    zhi = np.maximum(a[:, 2], b[:, 2]) + reach
    cont = None
    if container is not None:
        cont = _container_field(container, skin, h)
        lo = np.maximum(lo, container.bounds[0] - 2 * h)
        hi = np.minimum(hi, container.bounds[1] + 2 * h)
        if skin > 0:
            lo, hi = container.bounds[0] - 2 * h, container.bounds[1] + 2 * h
    band = 3.0 * h + k
    # where the struts can change the container's trimmed field (_reaching); with a skin, a
    # margin of 1e-3 voxels keeps float32 rounding of -c - skin on the safe side
    below = np.float32(band if skin == 0 else -0.5 * skin + 1e-3 * h)

    def evaluate(shape, origin, krange):
        z0 = origin[2]
        z1 = origin[2] + h * (shape[2] - 1)
        sel = (zhi >= z0) & (zlo <= z1)
        c = None
        if cont is not None:
            c = cont(shape, origin, z1)
            reach = np.maximum(ra[sel], rb[sel]) + band
            sel[sel] = _reaching(c, below, origin, h, a[sel], b[sel], reach)
        g = capsules_block(shape, origin, h, a[sel], b[sel], ra[sel], rb[sel], smooth=k, band=band)
        if c is not None:
            g = np.maximum(g, c)
            if skin > 0:
                g = np.minimum(g, np.maximum(c, -c - np.float32(skin)))
        return g

    return march(evaluate, lo, hi, h, smoothing=smoothing, bare=bare)
