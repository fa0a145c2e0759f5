"""Design files with a ``[solid]`` section: build the solid, write meshes and a preview, check.

Called by :func:`voroforge.design.build.build` and ``check_design`` when the file has a
``[solid]`` table (``voroforge build`` / ``voroforge check``).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..config import SOLID_FOAM_DRAWS, SOLID_MAX_VOXELS
from .render import preview

__all__ = ["build_solid", "check_solid", "make_solid", "preview"]


def _path(base, name: str) -> Path:
    p = Path(name)
    return p if p.is_absolute() or base is None else Path(base) / p


def _field(s):
    from . import fields

    if not s.fields:
        return None
    fs = []
    for f in s.fields:
        kw = {"radius": f.radius, "strength": f.strength, "falloff": f.falloff}
        if f.type == "point":
            fs.append(fields.point(f.points, **kw))
        elif f.type == "curve":
            fs.append(fields.curve([np.asarray(f.points, dtype=np.float64)], **kw))
        else:
            fs.append(fields.plane(f.origin, f.normal, **kw))
    g = fields.combine(fs) if len(fs) > 1 else fs[0]
    return g.invert() if s.invert_field else g


_STL = np.dtype([("normal", "<f4", 3), ("corners", "<f4", (3, 3)), ("attr", "<u2")])


def _stl_bare(path: Path):
    """A binary STL's triangles as a :class:`~.implicit.Bare` mesh, or None for other files.

    Three vertices a face, as the file lists them. The implicit route only takes the
    container's triangles and bounds, which are those of ``io.mesh.read`` (float32
    coordinates as float64, the file's face order): no merged vertex list, no trimesh.
    """
    from .implicit import Bare

    data = path.read_bytes()
    n = int.from_bytes(data[80:84], "little") if len(data) >= 84 else 0
    if n == 0 or len(data) != 84 + _STL.itemsize * n:
        return None
    corners = np.frombuffer(data, dtype=_STL, count=n, offset=84)["corners"]
    v = corners.reshape(-1, 3).astype(np.float64)
    if not np.isfinite(v).all():
        return None
    return Bare(v, np.arange(3 * n, dtype=np.int64).reshape(-1, 3))


def _check_voxel(voxel, lo, hi):
    """Refuse ``[solid] voxel`` whose grid over ``lo..hi`` alone has too many samples.

    The marching-cubes grid covers at least the box ``lo..hi`` (the container, or the
    shell's surface), so a count past ``SOLID_MAX_VOXELS`` there is refused at the key's
    line before the cells are built (the route itself would refuse after that work).
    """
    from ..design.designfile import DesignError

    if not voxel:
        return
    n = float(np.prod(np.floor((np.asarray(hi) - np.asarray(lo)) / float(voxel)) + 1.0))
    if not n <= SOLID_MAX_VOXELS:
        raise DesignError.at(
            "solid.voxel",
            f"a voxel of {voxel:g} gives a grid of at least {n:.3g} samples over the solid's "
            f"box (at most {SOLID_MAX_VOXELS:.3g}); use a larger voxel",
        )


def _cells(s, base, stage, bare=False):
    from ..design.designfile import DesignError
    from ..engine.voronoi3d import voronoi3d
    from ..io.mesh import read
    from .cells import relax, subdivide

    mesh = None
    if isinstance(s.container, str):
        path = _path(base, s.container)
        # a lattice with a skin or smooth nodes takes the implicit route, which reads only
        # the container's triangles: a binary STL's need no trimesh
        implicit = s.kind == "lattice" and (s.skin > 0 or s.nodes == "smooth")
        if bare and implicit and path.suffix.lower() == ".stl" and path.is_file():
            mesh = _stl_bare(path)
            if mesh is not None and s.voxel and s.skin > 0:
                from .implicit import prefetch_container

                # the skin's grid is the container's box: its field while the cells relax
                prefetch_container(mesh, s.skin, s.voxel)
        if mesh is None:
            try:
                mesh = read(path)
            except (OSError, ValueError) as exc:  # missing, or not a mesh: at the key's line
                raise DesignError.at("solid.container", str(exc)) from None
        box = tuple(np.concatenate(mesh.bounds))
    else:
        box = tuple(s.container)
    lo, hi = np.array(box[:3]), np.array(box[3:])
    if s.kind == "lattice" and (s.skin > 0 or s.nodes == "smooth"):
        _check_voxel(s.voxel, lo, hi)
    # a foam's bubbles lie in its cells: they are cut by the mesh, and its sites inside it
    clip = mesh if s.kind == "foam" and mesh is not None else None
    if clip is not None:
        clip, pts = _foam_sites(clip, s, lo, hi)
    else:
        pts = np.random.default_rng(s.seed).uniform(lo, hi, size=(s.cells, 3))
    where = box if clip is None else clip
    if s.relax:
        stage(f"relaxing {s.cells} cells ({s.relax} steps)")
        pts = relax(pts, where, iterations=s.relax)
    stage(f"3D Voronoi of {s.cells} cells")
    cells = voronoi3d(pts, where)
    if s.subdivide:
        stage(f"subdividing ({s.subdivide} levels)")
        if clip is not None:  # leaves fill their cell's hull: a cut cell must be convex
            cells = _convex_cells(cells)
        cells = subdivide(cells, s.subdivide_count, levels=s.subdivide, field=_field(s))
    return cells, mesh


def _foam_sites(mesh, s, lo, hi):
    """``(container, sites)``: a foam's mesh container (closed) and ``s.cells`` sites in it.

    The sites are drawn in the mesh's box and kept where they lie in the solid, in draw
    order, until there are enough (the same seed gives the same sites).
    """
    from ..design.designfile import DesignError
    from ..engine.mesh3d import as_mesh_container, sites_inside

    try:
        box_mesh, _ = as_mesh_container((mesh.vertices, mesh.faces))
        # voronoi3d's own check of the mesh: an open one is refused naming its open edges
        from ..engine.voronoi3d import voronoi3d

        voronoi3d(np.zeros((0, 3)), (mesh.vertices, mesh.faces))
    except ValueError as exc:
        raise DesignError.at("solid.container", str(exc)) from None
    rng = np.random.default_rng(s.seed)
    got = np.zeros((0, 3))
    for _ in range(SOLID_FOAM_DRAWS):
        p = rng.uniform(lo, hi, size=(max(s.cells, 64), 3))
        got = np.vstack([got, p[sites_inside(box_mesh, p)]])
        if len(got) >= s.cells:
            return (mesh.vertices, mesh.faces), got[: s.cells]
    raise DesignError.at(
        "solid.container",
        f"could not place {s.cells} sites inside the container mesh in {SOLID_FOAM_DRAWS} draws "
        "of its bounding box (is it a thin or empty solid?)",
    )


def make_solid(design, base=None, stage=None, *, bare: bool = False):
    """The solid a design's ``[solid]`` section describes (a watertight Trimesh).

    With ``bare``, a lattice the implicit route builds and a shell come as a
    :class:`~voroforge.solid.implicit.Bare` mesh (what :func:`build_solid` previews and
    writes, without trimesh's import); every other solid is a Trimesh either way.
    """
    # each kind imports only its own builder, from its module: the package's attribute of
    # the same name can be the submodule (bound when something imported it first)
    stage = stage or (lambda name: None)
    s = design.solid
    f = _field(s)
    if s.kind == "extrude":
        from ..design.compute import compute
        from .extrude import extrude

        result = compute(design, base, progress=stage)
        stage("extruding")
        return extrude(result, s.thickness)
    if s.kind == "shell":
        from ..io.mesh import read
        from .shell import shell
        from .surfaces import revolve

        # a profile's surface as bare arrays: no trimesh
        surf = read(_path(base, s.surface)) if s.surface else revolve(s.profile, s.sections)
        v = np.asarray(surf.vertices if hasattr(surf, "vertices") else surf[0], dtype=np.float64)
        if len(v):
            _check_voxel(s.voxel, v.min(axis=0), v.max(axis=0))
        stage(f"shell with {s.openings} openings")
        return shell(
            surf,
            s.thickness,
            s.openings or None,
            web=s.web,
            field=f,
            rim=s.rim,
            voxel=s.voxel,
            smoothing=s.smoothing,
            seed=s.seed,
            bare=bare,
        )
    cells, mesh = _cells(s, base, stage, bare=bare)
    if s.kind == "lattice":
        from .lattice import lattice

        stage("lattice")
        return lattice(
            cells,
            s.radius,
            nodes=s.nodes,
            field=f,
            container=mesh,
            skin=s.skin,
            voxel=s.voxel,
            smoothing=s.smoothing,
            bare=bare,
        )
    from .foam import foam

    stage("foam")
    if mesh is None:
        return foam(cells, s.wall, field=f)
    return foam(_convex_cells(cells), s.wall, field=f, container=_trimesh(mesh))


def _trimesh(mesh):
    import trimesh

    if isinstance(mesh, trimesh.Trimesh):
        return mesh
    return trimesh.Trimesh(np.asarray(mesh.vertices), np.asarray(mesh.faces), process=True)


def _convex_cells(cells):
    """The cells (cut by a mesh container) as convex meshes; a non-convex one is an error."""
    from ..design.designfile import DesignError
    from .graph import convex_cell_meshes

    try:
        return convex_cell_meshes(
            cells,
            "the container mesh cuts cells into non-convex pieces",
            "a foam needs a convex container mesh, or one whose concave parts no cell reaches",
        )
    except ValueError as exc:
        raise DesignError.at("solid.container", str(exc)) from None


def _write_mesh(m, path: Path, fmt: str, units: str) -> Path:
    from ..io.mesh import Arrays, write
    from .threemf import write_3mf

    if fmt == "3mf":
        # the implicit route's vertices lie on a decimal grid: their text by a kernel
        return write_3mf(m, path, units=units)
    # a Bare mesh as io.mesh's Arrays (the same file as from a Trimesh)
    mesh = m if hasattr(m, "is_volume") else Arrays(m.vertices, m.faces)
    return write(mesh, path, units=units)


def _on_thread(run):
    """Start ``run()`` on a second thread; ``join()`` waits and gives its error or None."""
    import threading

    error = []

    def target():
        try:
            run()
        except Exception as exc:  # handed to the calling thread by join()
            error.append(exc)

    thread = threading.Thread(target=target, name="voroforge-solid-files", daemon=True)
    thread.start()

    def join():
        thread.join()
        return error[0] if error else None

    return join


def build_solid(design, base, out: Path, stage, *, preview_only: bool = False) -> list[Path]:
    """Build the solid and write ``[solid] formats`` (meshes and a PNG preview) to ``out``.

    A bare mesh (the implicit route's lattices, shells) has its mesh files written on a
    second thread while the preview renders, where a core is free
    (:func:`voroforge.solid.implicit.spare_core`): the 3MF's text kernel, deflate and the
    preview's z-buffer release the GIL, and both only read the mesh's arrays. The files
    are those written one after the other; the list follows ``formats`` either way.
    """
    s = design.solid
    stem = design.output.stem or design.design.name
    units = design.design.units
    m = make_solid(design, base, stage, bare=True)
    formats = ["png"] if preview_only else list(s.formats)
    paths = {fmt: out / f"{stem}.{fmt}" for fmt in formats}
    meshes = [fmt for fmt in formats if fmt != "png"]
    join = None
    from .implicit import spare_core

    if "png" in paths and meshes and not hasattr(m, "is_volume") and spare_core():
        stage("writing " + ", ".join(paths[fmt].name for fmt in meshes))
        join = _on_thread(lambda: [_write_mesh(m, paths[fmt], fmt, units) for fmt in meshes])
    else:
        for fmt in meshes:
            stage(f"writing {paths[fmt].name}")
            _write_mesh(m, paths[fmt], fmt, units)
    try:
        if "png" in paths:
            stage(f"writing {paths['png'].name}")
            preview(m, paths["png"], size=s.png_size, view=s.view)
    finally:
        # the mesh files are complete before anything returns or propagates; a preview's
        # error goes first, the writer's is raised after a successful preview
        error = join() if join is not None else None
    if error is not None:
        raise error
    return [paths[fmt] for fmt in formats]


def check_solid(design, base=None, stage=None):
    """Build the solid and run :func:`voroforge.solid.check` with the section's limits."""
    from .check import check

    s = design.solid
    m = make_solid(design, base, stage)
    return check(
        m,
        min_strut=s.min_strut,
        min_pore=s.min_pore,
        min_wall=s.min_wall,
        max_overhang=s.max_overhang,
    )
