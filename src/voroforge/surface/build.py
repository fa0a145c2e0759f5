"""Build a design's ``[surface]`` section: panels on the surface, previews, solids, cut sheets.

:func:`build_surface` is what ``voroforge build`` calls for a design file with a ``[surface]``
table: ``output.formats`` picks the files (``png`` a shaded 3D preview, ``dxf``/``svg`` the
unrolled, labelled cut sheets), ``surface.meshes`` the panel solids (3MF, OBJ, GLB, ...).
Cut sheets use the first ``output.layers`` name for the outlines and a second one (if given,
else ``LABELS``) for the labels.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..io.atomic import write_atomically
from .schema import SurfaceSection

__all__ = ["build_surface", "surface_of", "surface_panels"]


def surface_of(sec: SurfaceSection, base: Path | None = None):
    """The :class:`~voroforge.surface.Surface` a ``[surface]`` section describes."""
    from . import shapes

    res = sec.resolution
    if sec.shape == "cylinder":
        return shapes.cylinder(sec.radius, sec.height, resolution=res)
    if sec.shape == "sphere_patch":
        return shapes.sphere_patch(
            sec.radius,
            polar=tuple(math.radians(a) for a in sec.polar),
            azimuth=tuple(math.radians(a) for a in sec.azimuth),
            resolution=res,
        )
    if sec.shape == "sphere":
        return shapes.sphere(sec.radius, subdivisions=4 if res is None else min(8, res))
    if sec.shape == "saddle":
        return shapes.saddle(sec.width, sec.depth, sec.rise, resolution=res)
    if sec.shape == "torus":
        return shapes.torus(sec.major, sec.minor, resolution=res)
    if sec.shape == "parametric":
        from .expr import parametric_map

        try:
            return shapes.parametric(parametric_map(sec.x, sec.y, sec.z), resolution=res)
        except ValueError as exc:
            if "non-finite" not in str(exc):
                raise
            from ..design.designfile import DesignError

            raise DesignError.at(
                "surface.x", f"x, y, z give non-finite points on the surface's UV grid ({exc})"
            ) from None
    from ..design.designfile import find_file

    path = None if sec.file is None else find_file(base, sec.file, "surface.file")
    if sec.shape == "heightfield":
        w = sec.width
        d = sec.depth if sec.depth is not None else w
        z = np.asarray(sec.heights, float) if path is None else _height_samples(path, sec.rise)
        return shapes.heightfield(z, (-w / 2, -d / 2, w / 2, d / 2))
    return shapes.mesh(path)


def _height_samples(path: Path, rise: float) -> np.ndarray:
    """Height samples from a file: CSV/TXT or NPY in model units, an image's grey 0..1 * rise.

    Row ``j`` of the result is at ``y = ymin + j dy``; an image's top row is its far edge
    (``ymax``), as it looks from above.
    """
    from ..design.designfile import DesignError

    ext = path.suffix.lower()
    try:
        if ext == ".npy":
            z = np.load(path, allow_pickle=False)
        elif ext in (".csv", ".txt"):
            text = path.read_text(encoding="utf-8")
            z = np.loadtxt(text.splitlines(), delimiter="," if "," in text else None, ndmin=2)
        elif ext in (".png", ".jpg", ".jpeg", ".tif", ".tiff"):
            from ..io.readers.files import open_image

            with open_image(path) as im:
                grey = np.asarray(
                    im.convert("I;16") if im.mode.startswith("I;16") else im.convert("L")
                )
            top = 65535.0 if grey.dtype == np.uint16 else 255.0
            if not rise:
                raise DesignError.at("surface.rise", "an image height field needs rise (its white)")
            z = grey[::-1].astype(float) / top * rise
        else:
            raise DesignError.at(
                "surface.file",
                f"height samples must be .csv, .txt, .npy or an image; got {path.name}",
            )
    except (OSError, ValueError) as exc:
        if isinstance(exc, DesignError):
            raise
        raise DesignError.at(
            "surface.file", f"cannot read height samples from {path.name}: {exc}"
        ) from None
    z = np.asarray(z, dtype=float)
    if not np.isfinite(z).all():
        bad = np.argwhere(~np.isfinite(z))[0]
        raise DesignError.at(
            "surface.file",
            f"height samples in {path.name} must be finite; row {bad[0]}, column "
            f"{bad[-1]} is {z[tuple(bad)]}",
        )
    return z


def _unroll(panels, sheet):
    """``panels.unroll(sheet=)``; a panel the sheet cannot hold is an error at the key."""
    try:
        return panels.unroll(sheet=sheet)
    except ValueError as exc:
        if sheet is None or "sheet" not in str(exc):
            raise
        from ..design.designfile import DesignError

        raise DesignError.at("surface.sheet", str(exc)) from None


def surface_panels(design, base: Path | None = None, *, progress=None):
    """``(surface, panels, extra)`` of a design with a ``[surface]`` section (no files)."""
    from .morph import morph
    from .voronoi import voronoi

    stage = progress or (lambda name: None)
    sec = design.surface
    S = surface_of(sec, base)
    extra: dict = {}
    if sec.mode == "morph":
        from ..design.compute import compute

        result = compute(design, base, progress=stage)
        stage("morphing onto the surface")
        panels = morph(result, S, what=sec.what)
        extra["result"] = result
    else:
        n = sec.count or design.seeds.count
        if n is None:
            from ..design.designfile import DesignError

            raise DesignError.at(
                "surface.count", "mode = 'voronoi' needs surface.count or seeds.count"
            )
        if n < 2:
            from ..design.designfile import DesignError

            key = "surface.count" if sec.count else "seeds.count"
            raise DesignError.at(key, f"mode = 'voronoi' needs at least 2 cells; got {n}")
        relax = sec.relax if sec.relax is not None else design.relax.iterations
        stage(f"surface Voronoi of {n} cells, {relax} relaxation steps")
        vd = voronoi(S, n, relax=relax, method=sec.method, seed=design.design.seed)
        extra["voronoi"] = vd
        panels = vd.panels()
        if not len(panels):  # e.g. two cells of a torus: bands, no flat panel to cut
            from ..design.designfile import DesignError

            key = "surface.count" if sec.count else "seeds.count"
            raise DesignError.at(
                key,
                f"none of the {n} cells makes a panel (each is a band or has a hole: "
                "Panels.missing); use more cells",
            )
    if sec.planarize is not None:
        stage("planarizing")
        panels = panels.planarize(sec.planarize)
    if sec.openings is not None:
        panels = panels.openings(sec.openings)
    elif sec.openings_near is not None:
        panels = panels.openings(
            (sec.openings_near, sec.openings_far),
            attractors=sec.attractors,
            radius=sec.attractor_radius,
        )
    return S, panels, extra


def _solids(sec: SurfaceSection, panels):
    """The panel solids as :class:`voroforge.io.mesh.Arrays` (written without trimesh)."""
    solids = []
    if sec.thickness is not None:
        solids += panels.thicken(sec.thickness, arrays=True)
    if sec.frame is not None:
        solids += panels.frame(sec.frame, arrays=True)
    return solids


def render_panels(panels, path, *, size=900, view=(35.0, 30.0)):
    """A shaded PNG of the panels (one colour per panel, both sides) via ``io.render3d``.

    Plain polygons are drawn whole with their outlines; panels with holes are triangulated.
    """
    from ..io.render import palette
    from ..io.render3d import render

    cols = [tuple(int(c) for c in rgb) for rgb in palette(len(panels), 3).tolist()]
    if all(len(r) == 1 for r in panels.rings) and panels.uv is None:
        items = [(panels.vertices, [r[0], r[0][::-1]]) for r in panels.rings]
        return render(items, path, size=(size, int(size * 0.75)), view=view, colors=cols)
    faces, owner = panels.triangulate()  # no trimesh import for a preview
    items = []
    for p in range(len(panels)):
        f = faces[owner == p]
        items.append((panels.vertices, [*f, *f[:, ::-1]]))
    return render(items, path, size=(size, int(size * 0.75)), view=view, colors=cols, edges=False)


def build_surface(design, base, out: Path, stage, *, preview: bool = False) -> list[Path]:
    """Write a ``[surface]`` design's outputs into ``out``; returns the paths in order."""
    from ..design.designfile import DesignError

    sec = design.surface
    o = design.output
    stem = o.stem or design.design.name
    units = design.design.units
    for fmt in o.formats:
        if fmt in ("geojson", "gif"):
            raise DesignError.at("output.formats", f"{fmt!r} is not written for a [surface] design")
    S, panels, extra = surface_panels(design, base, progress=stage)
    written: list[Path] = []
    names = [k.upper() for k in o.layers] or ["CUT"]
    cut = names[0]
    label = names[1] if len(names) > 1 else "LABELS"
    sheets = None
    formats = ["png"] if preview else list(o.formats)
    for fmt in formats:
        path = out / f"{stem}.{fmt}"
        stage(f"writing {path.name}")
        if fmt == "png":
            size = min(o.png_size, 800) if preview else o.png_size
            shown = panels
            if "result" in extra:  # a coarser morph draws the same at a fraction of the faces
                from .morph import morph

                shown = morph(extra["result"], S, what=sec.what, segment=1 / 48, simplify=1e-3)
            written.append(render_panels(shown, path, size=size, view=sec.view))
        else:
            if sheets is None:
                stage("unrolling")
                sheets = _unroll(panels, sec.sheet)
            if fmt == "dxf":
                written.append(
                    sheets.write_dxf(path, layer=cut, label_layer=label, units=design.design.units)
                )
            else:
                written.append(
                    sheets.write_svg(path, layer=cut, label_layer=label, units=design.design.units)
                )
    if preview:
        return written
    if sec.unroll and sheets is None:
        sheets = _unroll(panels, sec.sheet)
        written.append(
            sheets.write_dxf(
                out / f"{stem}-sheets.dxf", layer=cut, label_layer=label, units=design.design.units
            )
        )
    if sec.meshes:
        from ..io.mesh import write

        solids = _solids(sec, panels) or panels.thicken(
            float(np.linalg.norm(np.ptp(panels.vertices, axis=0))) * 0.004, arrays=True
        )
        for fmt in sec.meshes:
            path = out / f"{stem}-panels.{fmt}"
            stage(f"writing {path.name}")
            written.append(write(solids, path, units=design.design.units))
    if panels.report is not None:
        rep = panels.report
        text = out / f"{stem}-planarity.txt"
        ab, rel = rep.planarity
        bad = list(map(int, panels.ids[rep.not_planar]))
        lines = [
            f"planarize tolerance {rep.tolerance:g} {units}, {rep.iterations} iterations",
            f"panels {len(panels)}; largest deviation {ab.max():.3g} ({rel.max():.3g} of an edge)",
            f"not planar to tolerance: {len(rep.not_planar)} {bad}",
            "over negative Gaussian curvature (no convex planar hexagons there): "
            f"{len(rep.negative_curvature)}",
            f"largest distance from the surface: {rep.surface_distance:.3g}",
            f"crossing themselves: {len(rep.self_intersecting)} "
            f"{list(map(int, panels.ids[rep.self_intersecting]))}",
            f"turned over: {len(rep.flipped)} {list(map(int, panels.ids[rep.flipped]))}",
            f"border vertices left out of straight runs: {rep.dropped}",
        ]
        body = "\n".join(lines) + "\n"
        write_atomically(text, lambda tmp, body=body: Path(tmp).write_text(body, encoding="utf-8"))
        written.append(text)
    return written
