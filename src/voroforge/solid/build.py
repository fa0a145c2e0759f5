"""Design files with a ``[solid]`` section: build the solid, write meshes and a preview, check.

Called by :func:`voroforge.design.build.build` and ``check_design`` when the file has a
``[solid]`` table (``voroforge build`` / ``voroforge check``).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

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


def _cells(s, base, stage):
    from ..engine.voronoi3d import voronoi3d
    from ..io.mesh import read
    from .cells import relax, subdivide

    mesh = None
    if isinstance(s.container, str):
        mesh = read(_path(base, s.container))
        box = tuple(np.concatenate(mesh.bounds))
    else:
        box = tuple(s.container)
    lo, hi = np.array(box[:3]), np.array(box[3:])
    pts = np.random.default_rng(s.seed).uniform(lo, hi, size=(s.cells, 3))
    if s.relax:
        stage(f"relaxing {s.cells} cells ({s.relax} steps)")
        pts = relax(pts, box, iterations=s.relax)
    stage(f"3D Voronoi of {s.cells} cells")
    cells = voronoi3d(pts, box)
    if s.subdivide:
        stage(f"subdividing ({s.subdivide} levels)")
        cells = subdivide(cells, s.subdivide_count, levels=s.subdivide, field=_field(s))
    return cells, mesh


def _revolve(profile, sections: int):
    import trimesh

    prof = np.asarray(profile, dtype=np.float64)
    return trimesh.creation.revolve(prof, sections=sections)


def make_solid(design, base=None, stage=None):
    """The solid a design's ``[solid]`` section describes (a watertight Trimesh)."""
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

        surf = read(_path(base, s.surface)) if s.surface else _revolve(s.profile, s.sections)
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
        )
    cells, mesh = _cells(s, base, stage)
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
        )
    from .foam import foam

    stage("foam")
    return foam(cells, s.wall, field=f)


_PREVIEW_FACES = 30_000  # more triangles than this are simplified before drawing
_PREVIEW_FACES_MAX = 120_000  # the software renderer pays per face (~1 s per 70k at 900 px)


def _shown(m, view, cut: bool):
    """The mesh a preview draws: ``m`` simplified, and cut when ``cut``.

    The cut keeps the half away from the camera (closed voids and skins show their inside).
    Both go through one manifold3d object: a big mesh is simplified by edge collapse
    (``SOLID_PREVIEW_SIMPLIFY`` of its size: under a pixel, where clustering vertices on a
    grid crumpled thin struts), then trimmed by the plane through its centre. A mesh that
    manifold3d refuses is drawn as it is.
    """
    from ..config import SOLID_PREVIEW_SIMPLIFY
    from ..io.render3d import _rotation
    from .booleans import from_manifold, status_name, to_manifold

    big = len(m.faces) > _PREVIEW_FACES
    if not (cut or big):
        return m
    man = to_manifold(m)
    if status_name(man) != "NoError":
        return m
    if big:
        man = man.simplify(float(m.scale) * SOLID_PREVIEW_SIMPLIFY)
    if cut:
        d = _rotation(view).T @ np.array([0.0, 1.0, 0.0])  # the camera looks along d
        c = m.bounds.mean(axis=0)
        man = man.trim_by_plane(tuple(d), float(d @ c))
    return from_manifold(man)


def _cluster(m, cell: float):
    """Vertex-clustering decimation for previews: vertices snapped to ``cell`` and merged."""
    import trimesh

    key = np.floor(np.asarray(m.vertices) / cell).astype(np.int64)
    _, inv, cnt = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    inv = inv.reshape(-1)
    v = np.stack([np.bincount(inv, m.vertices[:, i]) / cnt for i in range(3)], axis=1)
    f = inv[np.asarray(m.faces)]
    f = f[(f[:, 0] != f[:, 1]) & (f[:, 1] != f[:, 2]) & (f[:, 0] != f[:, 2])]
    return trimesh.Trimesh(v, f, process=False)


def preview(m, path, *, size=900, view=(35.0, 25.0), cut=None) -> Path:
    """A shaded PNG of a solid (software renderer, no GPU or display).

    ``cut`` (default: when the solid hides its inside: closed voids or a skin) renders the
    half away from the camera, so the cells show.
    """
    import trimesh

    from ..io.render3d import render

    if cut is None:
        meta = m.metadata or {}
        cut = meta.get("kind") == "foam" or bool(meta.get("skin"))
    from ..io.render3d import _rotation

    shown = _shown(m, view, cut)
    cell = shown.scale / 400.0
    while len(shown.faces) > _PREVIEW_FACES_MAX and cell < shown.scale / 50:  # beyond the pixels
        shown = _cluster(shown, cell)
        cell *= 1.5
    # the painter's algorithm wants small faces: split long ones (few: CAD faces, cut planes)
    v, f = trimesh.remesh.subdivide_to_size(shown.vertices, shown.faces, max_edge=shown.scale / 16)
    # the renderer pays per face: drop the ones facing away before it sees them
    t = v[f]
    n = np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])
    f = f[(n @ _rotation(view).T)[:, 1] <= 0]
    w = int(size)
    return render(
        [(v, f)], path, size=(w, int(w * 0.8)), view=view, edges=False, colors=[(196, 205, 214)]
    )


def build_solid(design, base, out: Path, stage, *, preview_only: bool = False) -> list[Path]:
    """Build the solid and write ``[solid] formats`` (meshes and a PNG preview) to ``out``."""
    from ..io.mesh import write

    s = design.solid
    stem = design.output.stem or design.design.name
    m = make_solid(design, base, stage)
    written = []
    formats = ["png"] if preview_only else s.formats
    for fmt in formats:
        path = out / f"{stem}.{fmt}"
        stage(f"writing {path.name}")
        if fmt == "png":
            written.append(preview(m, path, size=s.png_size, view=s.view))
        else:
            written.append(write(m, path, units=design.design.units))
    return written


def check_solid(design, base=None, stage=None):
    """Build the solid and run :func:`voroforge.solid.check` with the section's limits."""
    from .check import check

    s = design.solid
    m = make_solid(design, base, stage)
    return check(m, min_strut=s.min_strut, min_pore=s.min_pore, max_overhang=s.max_overhang)
