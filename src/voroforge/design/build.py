"""Build a design's outputs: SVG/DXF layers, PNG preview, GeoJSON, GIF sweep, check reports.

:func:`build` computes a design (:func:`voroforge.design.compute.compute`) and writes the
files it names; :func:`check_design` runs the fabrication check with the design's limits;
:func:`write_starter` writes the commented starter design. The writers are deterministic,
so the same file and seed give byte-identical outputs.

Examples
--------
>>> design = {
...     "boundary": {"shape": "rectangle", "width": 120, "height": 80},
...     "seeds": {"method": "poisson", "radius": 12},
...     "cells": {"web": 3, "fillet": 1.5},
... }
>>> import tempfile
>>> [p.name for p in build(design, tempfile.mkdtemp())]
['design.svg', 'design.png']
"""

from __future__ import annotations

from dataclasses import replace
from importlib import resources
from pathlib import Path

import numpy as np
import shapely

from .. import config
from .compute import MM_PER_UNIT, Result, Stage, as_design_error, compute
from .designfile import DesignError, Issue, find_file, load, located
from .schema import Design

__all__ = [
    "DesignWarning",
    "build",
    "check_design",
    "products",
    "render_preview",
    "starter",
    "write_starter",
]


class DesignWarning(UserWarning):
    """A design that builds but probably not as meant (``voroforge build`` prints it)."""


# --- outputs ------------------------------------------------------------------------------


#: The product names of ``output.layers`` (``labels`` is made by :func:`_labels`).
PRODUCTS = ("frame", "openings", "cells", "edges", "sites", "boundary", "curves")


def products(result: Result, *, kerf: float = 0.0, names=PRODUCTS) -> dict[str, list]:
    """The geometry of the named products, optionally kerf-compensated (polygons only).

    Only the products named are made (the unique edges, say, cost a pass over every cell).
    """
    from .fabrication import kerf as apply_kerf

    def frame():
        return [apply_kerf(result.frame, kerf, role="part") if kerf > 0 else result.frame]

    def openings():
        holes = list(result.openings)
        return list(apply_kerf(holes, kerf, role="hole")) if kerf > 0 and holes else holes

    def cells():
        live = [c for c in result.cells if not c.is_empty]
        return list(apply_kerf(live, kerf, role="part")) if kerf > 0 and live else live

    def boundary():  # the outline is the part's edge too: cut on a layer, it grows like the frame
        return [apply_kerf(result.boundary, kerf, role="part") if kerf > 0 else result.boundary]

    made = {
        "frame": frame,
        "openings": openings,
        "cells": cells,
        "edges": lambda: [result.edges],
        "sites": lambda: [shapely.MultiPoint(result.sites)],
        "boundary": boundary,
        # seeds.method = "curves": the cell edges along the seed curves (veins, seams)
        "curves": lambda: [result.extra["curve_edges"]] if "curve_edges" in result.extra else [],
    }
    return {name: made[name]() for name in names}


def _labels(result: Result) -> list:
    """Each live cell's number (its index, as in GeoJSON ``cell``) as single-stroke text."""
    from ..io.labels import cell_labels

    cells = np.asarray(result.cells, dtype=object)
    lines, _, _ = cell_labels(cells, max_height=result.design.output.label_height)
    return [g for g in lines if not g.is_empty]


def _uses(result: Result, product: str) -> bool:
    for what in result.design.output.layers.values():
        if product in ([what] if isinstance(what, str) else what):
            return True
    return False


def _layers(result: Result, kerf: float) -> dict[str, list]:
    """Layer name -> geometry of ``output.layers`` (made once, then reused by every writer)."""
    layers = result.design.output.layers
    # keyed by what decides it: an editor may reuse a result's extra with other [output] keys
    spec = tuple((k, v if isinstance(v, str) else tuple(v)) for k, v in layers.items())
    key = ("layers", float(kerf), spec, result.design.output.label_height)
    if key in result.extra:
        return result.extra[key]
    wanted = {n for what in layers.values() for n in ([what] if isinstance(what, str) else what)}
    made = products(result, kerf=kerf, names=[n for n in PRODUCTS if n in wanted])
    if "labels" in wanted:
        made["labels"] = _labels(result)
    out = {}
    for name, what in layers.items():
        names = [what] if isinstance(what, str) else list(what)
        out[name.upper()] = [g for n in names for g in made[n]]
    result.extra[key] = out
    return out


def _tapered(result: Result, lines, width: float, colour) -> list:
    """Lines cut in short pieces, each stroked 3.2 to 10 ``width`` wide as the field rises.

    Without attractors every piece gets 6 ``width``. With a curve attractor on a leaf's
    midrib, the midrib is drawn thickest and the veins thin out towards the margin.
    """
    pieces = shapely.get_parts(shapely.segmentize(lines, 6.0 * width))
    segs = []
    for line in pieces:
        xy = shapely.get_coordinates(line)
        segs += [shapely.LineString(xy[i : i + 2]) for i in range(len(xy) - 1)]
    if not segs:
        return []
    mids = shapely.get_coordinates(shapely.centroid(np.asarray(segs, dtype=object)))
    from .compute import attractor_field

    try:  # inline attractors; one read from a file is not found without the design's folder
        field_fn = attractor_field(result.design)
    except (ValueError, OSError):
        field_fn = None
    values = np.full(len(segs), 0.4) if field_fn is None else np.clip(field_fn(mids), 0, 1)
    widths = 2.0 * width * (1.6 + 3.4 * values)
    return [(g, float(w), colour) for g, w in zip(segs, widths.tolist(), strict=True)]


def render_preview(result: Result, *, size: int = 1200):
    """A PIL image of the design: openings in colour on the panel, or edges for line work."""
    from ..io.png import render_image
    from ..io.render import palette

    layers = result.design.output.layers
    first = next(iter(layers.values()), "frame")
    first = first if isinstance(first, str) else first[0]
    mode = result.design.output.png
    if mode == "layers" and first == "edges":
        xmin, ymin, xmax, ymax = result.boundary.bounds
        width = max(xmax - xmin, ymax - ymin) / 900.0  # half a stroke, in design units
        ink = (25, 25, 35)
        traced = "curve_edges" in result.extra
        # a hierarchy (traced curves, recursion) reads by weight and tone: finest lightest
        strokes = [
            (shapely.line_merge(result.edges), 2 * width, (120, 124, 132) if traced else ink)
        ]
        levels = result.extra.get("levels") or []
        if len(levels) > 1:  # recursion: the first level's edges drawn heavier
            from . import cellops

            top = cellops.edges_to_lines(cellops.explode(np.asarray(levels[0].cells)), merge=True)
            heavy = (1.4 if traced else 2.6) * 2 * width
            strokes.append((top, heavy, (70, 74, 84) if traced else ink))
        if traced:  # the cell edges along the seed curves (veins) heaviest, tapering
            strokes += _tapered(result, result.extra["curve_edges"], width, ink)
        return render_image([], size=size, lines=strokes, edge_width=0.0, boundary=result.boundary)
    if mode == "layers" and first in ("frame", "boundary"):
        return render_image([result.frame], size=size, colors=[(52, 58, 70)], edge_width=0.6)
    geoms = [result.frame, *result.openings]
    colours = [(236, 236, 240)] + [
        tuple(c) for c in palette(len(result.openings), result.design.design.seed).tolist()
    ]
    sites = result.sites if result.design.output.png_sites else None
    return render_image(geoms, size=size, colors=colours, edge_width=0.6, sites=sites)


def _source_crs(result: Result, base: Path | None):
    """The ``"crs"`` member of the boundary's or the seeds' GeoJSON file, or None.

    QGIS writes one for projected data; copying it keeps the output where the input was.
    """
    import warnings

    from ..io.readers.geojson import geojson_crs

    d = result.design
    files = {"boundary.file": d.boundary.file if d.boundary.shape == "file" else None}
    files["seeds.file"] = d.seeds.file if d.seeds.method == "file" else None
    found = {}
    for key, name in files.items():
        if not name or Path(name).suffix.lower() not in (".geojson", ".json"):
            continue
        try:
            crs = geojson_crs(find_file(base, name, ""))
        except (OSError, ValueError, DesignError):
            continue
        if crs is not None:
            found[key] = crs
    if len(found) == 2 and found["boundary.file"] != found["seeds.file"]:
        named = {
            k: c.get("properties", {}).get("name", c) if isinstance(c, dict) else c
            for k, c in found.items()
        }
        warnings.warn(  # checker25 F8: mixed silently, the output claiming the boundary's
            f"seeds.file: its GeoJSON crs {named['seeds.file']} is not boundary.file's "
            f"{named['boundary.file']}; nothing is reprojected (the output claims the "
            "boundary's): reproject one file",
            DesignWarning,
            stacklevel=3,
        )
    return next(iter(found.values()), None)


def _geojson(result: Result, path: Path, base: Path | None = None) -> Path:
    from ..io.geojson import write_geojson

    crs = _source_crs(result, base)
    what = result.design.output.geojson
    if what == "cells":  # the rows of design.features (one per seed-file row for file seeds)
        from .features import cell_features

        geoms, sites, props = cell_features(result)
        return write_geojson(geoms, path, sites=sites, properties=props, crs=crs)
    geoms = _labels(result) if what == "labels" else products(result, names=[what])[what]
    if what == "edges":
        geoms = list(shapely.get_parts(result.edges))
    return write_geojson(geoms, path, crs=crs)


def _parquet(result: Result, path: Path, base: Path | None = None) -> Path:
    """The GeoJSON cells' rows as GeoParquet, the source file's CRS included."""
    from .features import cell_features, write_parquet

    member = _source_crs(result, base)
    crs = (member.get("properties") or {}).get("name") if member else None
    geoms, sites, props = cell_features(result)
    return write_parquet(geoms, path, sites=sites, properties=props, crs=crs)


def _inputs_named_like(design, base: Path | None, out: Path, stem: str) -> list[tuple[str, Path]]:
    """``(key, path)`` of every file the design reads that an output would write over.

    Every string value of the design that names an existing file (relative to ``base``) is
    an input; a build writes ``<stem>.<suffix>`` and ``<stem>-<part>`` files into ``out``
    (a design named "pts" reading ``seeds.file = "pts.geojson"`` replaced its own seeds).
    """
    found = []
    folder = out.resolve()

    def walk(node, key):
        if isinstance(node, dict):
            for k, v in node.items():
                walk(v, f"{key}.{k}" if key else str(k))
        elif isinstance(node, (list, tuple)):
            first = node[0] if node else None
            if isinstance(first, (list, tuple)) and first:
                first = first[0]
            if isinstance(first, (int, float)):  # coordinates (a polygon of 200k points)
                return
            for i, v in enumerate(node):
                walk(v, f"{key}.{i}")
        elif isinstance(node, str) and node and "\n" not in node and len(node) < 4096:
            p = Path(node)
            if not p.is_absolute() and base is not None:
                p = base / p
            try:
                hit = p.is_file() and p.resolve().parent == folder
            except OSError:
                return
            if hit and (p.name.startswith(f"{stem}.") or p.name.startswith(f"{stem}-")):
                found.append((key, p))

    walk(design.model_dump(), "")
    return found


def build(
    source,
    out_dir=".",
    *,
    overrides: dict | None = None,
    preview: bool = False,
    progress: Stage | None = None,
) -> list[Path]:
    """Build a design file and write every output it names.

    Parameters
    ----------
    source : str, Path, dict or Design
        A TOML design file, its parsed mapping, or a validated design.
    out_dir : str or Path
        Output folder; created if missing.
    overrides : dict, optional
        ``{"seeds.count": 500, "cells.web": 2}`` (dotted keys, values or TOML strings).
    preview : bool
        Write only the PNG preview (at most 800 px).
    progress : callable, optional
        Called with the name of each stage.

    Returns
    -------
    list of Path
        The files written, in the order of ``output.formats``.

    Raises
    ------
    DesignError
        For a bad design file (each issue names key and line).
    """
    stage = progress or (lambda name: None)
    if isinstance(source, Design):
        design, base = source, None
        if overrides:
            design, base = load(design.model_dump(), overrides=overrides)
    else:
        design, base = load(source, overrides=overrides)
    stem = design.output.stem or design.design.name
    clash = _inputs_named_like(design, base, Path(out_dir), stem)
    if clash:
        key, path = clash[0]
        with located(source, overrides):
            raise DesignError.at(
                key,
                f"{path} is read by the design and named like its outputs ({stem}.* and "
                f"{stem}-* in {Path(out_dir)}): the build would write over it; give another "
                "output folder or set output.stem",
            )
    if design.solid is not None:  # a printable 3D product: voroforge.solid builds it
        from ..solid.build import build_solid

        out = Path(out_dir)
        out.mkdir(parents=True, exist_ok=True)
        with located(source, overrides):
            return build_solid(design, base, out, stage, preview_only=preview)
    if design.surface is not None:  # onto a curved surface: voroforge.surface builds it
        from ..surface.build import build_surface

        out = Path(out_dir)
        out.mkdir(parents=True, exist_ok=True)
        with located(source, overrides):
            return build_surface(design, base, out, stage, preview=preview)
    with located(source, overrides):
        result = compute(design, base, progress=stage)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    o = design.output
    stem = o.stem or design.design.name
    written: list[Path] = []
    if preview:
        stage("writing preview")
        path = out / f"{stem}.png"
        return [_save_png(render_preview(result, size=min(o.png_size, 800)), path, optimize=False)]
    if "svg" in o.formats and design.design.units not in ("mm", "cm", "in"):
        with located(source, overrides):
            raise DesignError.at(
                "output.formats",
                f"svg needs design.units mm, cm or in; not {design.design.units!r} "
                "(drop svg, or draw in mm)",
            )
    kerf = o.kerf
    if "svg" in o.formats or "dxf" in o.formats:
        _warn_empty_layers(result)
        _warn_coincident_layers(_layers(result, kerf))
        _warn_kerf_losses(result, kerf)
    for fmt in o.formats:
        path = out / f"{stem}.{fmt}"
        stage(f"writing {path.name}")
        if fmt == "svg":
            from ..io.svg import write_layers

            written.append(
                write_layers(
                    path,
                    _layers(result, kerf),
                    units=design.design.units,
                    stroke_width=_stroke_width(design),
                    # kerf-compensated parts reach kerf / 2 past the outline: keep them on the page
                    bounds=_page(result, kerf, source, overrides, base),
                    order=o.order,
                    merge=o.merge_lines,
                )
            )
        elif fmt == "dxf":
            from ..io.dxf import write_dxf

            written.append(
                write_dxf(
                    None,
                    path,
                    layers=_layers(result, kerf),
                    units=design.design.units,
                    arc_tolerance=o.arc_tolerance,
                    order=o.order,
                    merge=o.merge_lines,
                    point_marks=o.site_marks,
                    point_radius=max(_stroke_width(design), 0.5),
                )
            )
        elif fmt == "png":
            written.append(_save_png(render_preview(result, size=o.png_size), path))
        elif fmt == "geojson":
            written.append(_geojson(result, path, base))
        elif fmt == "parquet":
            with located(source, overrides), as_design_error("output.formats"):
                written.append(_parquet(result, path, base))
        elif fmt == "gif":
            with located(source, overrides):
                written.append(_gif(design, base, path, stage))
    if _uses(result, "labels"):
        written += _write_legend(result, out / f"{stem}-labels")
    if o.pieces:
        written += _write_pieces(result, out / f"{stem}-pieces", kerf, stage)
    if design.fabrication.report:
        report = _report(result)
        text = out / f"{stem}-check.txt"
        written.append(_save_text(text, report.table(max_rows=None) + "\n"))  # every row
        written.append(report.write_png(out / f"{stem}-check.png", size=min(o.png_size, 1200)))
    return written


def _save_png(image, path: Path, **options) -> Path:
    """Save a PIL image as PNG atomically: Ctrl-C leaves the old file or none, never half."""
    from ..io.atomic import write_atomically

    return write_atomically(path, lambda tmp: image.save(tmp, format="PNG", **options))


def _save_text(path: Path, text: str) -> Path:
    """Write UTF-8 text atomically (:func:`voroforge.io.atomic.write_atomically`)."""
    from ..io.atomic import write_atomically

    return write_atomically(path, lambda tmp: Path(tmp).write_text(text, encoding="utf-8"))


def _page(result: Result, kerf: float, source, overrides, base):
    """The SVG page: the boundary's box (plus kerf / 2), or the source drawing's page."""
    d = result.design
    if d.output.page == "boundary":
        # kerf-compensated parts reach kerf / 2 past the outline: keep them on the page
        return tuple(np.add(result.boundary.bounds, np.multiply([-1, -1, 1, 1], kerf / 2)))
    with located(source, overrides):
        if d.boundary.shape != "file" or Path(d.boundary.file).suffix.lower() != ".svg":
            raise DesignError.at("output.page", "'source' needs boundary.file to be an SVG")
        from ..io.readers.svg import svg_in_mm, svg_page

        path = find_file(base, d.boundary.file, "boundary.file")
        try:
            page = np.asarray(svg_page(path), dtype=np.float64)
        except ValueError as exc:
            raise DesignError.at("output.page", str(exc)) from None
    if svg_in_mm(path):
        page = page / MM_PER_UNIT[d.design.units]
    return tuple(page.tolist())


def _write_legend(result: Result, stem: Path) -> list[Path]:
    """``-labels.csv`` and ``-labels.json``: each label's cell, place, height and area."""
    import csv
    import io
    import json

    from ..io.labels import cell_labels

    cells = np.asarray(result.cells, dtype=object)
    _, centres, heights = cell_labels(cells, max_height=result.design.output.label_height)
    rows = []
    for i in np.flatnonzero(heights > 0).tolist():
        rows.append(
            {
                "label": str(i),
                "cell": i,
                "x": round(float(centres[i, 0]), 6),
                "y": round(float(centres[i, 1]), 6),
                "height": round(float(heights[i]), 6),
                "area": round(float(cells[i].area), 6),
                "opening": bool(result.mask[i]),
                "level": int(result.level[i]),
            }
        )
    buf = io.StringIO()
    writer = csv.DictWriter(buf, fieldnames=list(rows[0]) if rows else ["label", "cell"])
    writer.writeheader()
    writer.writerows(rows)
    paths = [stem.with_suffix(".csv"), stem.with_suffix(".json")]
    _save_text(paths[0], buf.getvalue())
    _save_text(paths[1], json.dumps(rows, indent=1) + "\n")
    return paths


def _write_pieces(result: Result, stem: Path, kerf: float, stage: Stage) -> list[Path]:
    """Every cell as its own closed part, laid out apart, with its number engraved."""
    from ..io.labels import cell_labels
    from .fabrication import kerf as apply_kerf
    from .fabrication import pack_pieces

    o = result.design.output
    cells = np.asarray(result.cells, dtype=object)
    live = np.flatnonzero(~shapely.is_empty(cells)) if len(cells) else np.zeros(0, dtype=int)
    parts = cells[live]
    labels, _, _ = cell_labels(parts, [str(i) for i in live], max_height=o.label_height)
    if kerf > 0:
        parts = apply_kerf(parts, kerf, role="part")
    xmin, _, xmax, _ = result.boundary.bounds
    gap = max(2.0 / MM_PER_UNIT[result.design.design.units], 2.0 * kerf)
    shift = pack_pieces(parts, width=xmax - xmin, gap=gap)
    moved = [
        shapely.transform(g, lambda xy, d=d: xy + d) for g, d in zip(parts, shift, strict=True)
    ]
    text = [
        shapely.transform(g, lambda xy, d=d: xy + d) for g, d in zip(labels, shift, strict=True)
    ]
    layers = {"CUT": moved, "ENGRAVE": [t for t in text if not t.is_empty]}
    written = []
    for fmt in ("svg", "dxf"):
        if fmt not in o.formats:
            continue
        path = stem.with_suffix(f".{fmt}")
        stage(f"writing {path.name}")
        if fmt == "svg":
            from ..io.svg import write_layers

            written.append(
                write_layers(
                    path,
                    layers,
                    units=result.design.design.units,
                    stroke_width=_stroke_width(result.design),
                    order=o.order,
                )
            )
        else:
            from ..io.dxf import write_dxf

            written.append(
                write_dxf(
                    None,
                    path,
                    layers=layers,
                    units=result.design.design.units,
                    arc_tolerance=o.arc_tolerance,
                    order=o.order,
                )
            )
    return written


def _stroke_width(design: Design) -> float:
    """SVG stroke width in design units: as given, else a 0.01 mm laser hairline.

    Laser drivers take only hairlines (about 0.001 in or less) as vector cuts, so the default
    is 0.01 mm whatever the units (0.01 in would be engraved, not cut).
    """
    given = design.output.stroke_width
    return given if given is not None else config.HAIRLINE_MM / MM_PER_UNIT[design.design.units]


def _warn_empty_layers(result: Result) -> None:
    """Warn about SVG/DXF layers with nothing on them (a cut file that cuts nothing)."""
    import warnings

    made = _layers(result, 0.0)
    for name, what in result.design.output.layers.items():
        names = [what] if isinstance(what, str) else list(what)
        if all(g.is_empty for g in made[name.upper()]):
            hint = ""
            if "frame" in names and len(result.openings):
                hint = (
                    ": the openings fill the whole boundary (set cells.web or cells.inset, "
                    "or draw the edges)"
                )
            warnings.warn(
                f"output.layers.{name}: the layer is empty ({', '.join(names)}){hint}",
                DesignWarning,
                stacklevel=3,
            )


def _warn_kerf_losses(result: Result, kerf: float) -> None:
    """Warn about openings the kerf shrinks to nothing (left out of the cut file)."""
    import warnings

    from .fabrication import kerf as apply_kerf

    holes = list(result.openings)
    if kerf <= 0 or not holes:
        return
    lost = int(np.count_nonzero(shapely.is_empty(apply_kerf(holes, kerf, role="hole"))))
    if lost:
        warnings.warn(
            f"output.kerf: {lost} of {len(holes)} openings are narrower than the kerf {kerf:g} "
            "and are left out of the cut (too small to cut: a smaller kerf, or larger openings)",
            DesignWarning,
            stacklevel=3,
        )


def _warn_coincident_layers(layers: dict) -> None:
    """Warn when two layers draw the same segment (the machine would pass over it twice).

    Within a layer the writers draw every segment once (:mod:`voroforge.io.plotter`).
    """
    import warnings

    from ..io.plotter import coincident_segments

    names = list(layers)
    for i, a in enumerate(names):
        for b in names[i + 1 :]:
            n = coincident_segments(layers[a], layers[b])
            if n:
                warnings.warn(
                    f"output.layers: {a} and {b} share {n} segments, so they are cut or "
                    "drawn twice (put the products on one layer, or use a kerf)",
                    DesignWarning,
                    stacklevel=3,
                )


def _gif(design: Design, base: Path | None, path: Path, stage: Stage) -> Path:
    from ..io.gif import palette_frame, write_gif

    gif = design.output.gif
    values = gif.sweep()
    keys = [repr(v) for v in values]
    designs = sweep_designs(design)
    last = {k: i for i, k in enumerate(keys)}  # a value shown again (bounce) is drawn once

    def frames():
        kept = {}  # only frames still to be shown again, and only as palette images
        for i, (k, v) in enumerate(zip(keys, values, strict=True)):
            frame = kept.pop(k, None) if last[k] == i else kept.get(k)
            if frame is None:
                stage(f"gif frame {i + 1}/{len(keys)}")
                try:
                    image = render_preview(compute(designs[k], base), size=gif.size)
                except DesignError as exc:  # a value the schema takes and the geometry refuses
                    raise _sweep_error(gif, v, exc) from None
                frame = palette_frame(image)
                if last[k] > i:
                    kept[k] = frame
            yield frame

    return write_gif(frames(), path, fps=gif.fps)


def _sweep_error(gif, v, exc: DesignError) -> DesignError:
    """``exc`` of the design with ``gif.key = v``, said of the sweep's keys."""
    where = "output.gif.values" if gif.values is not None else "output.gif.start"
    return DesignError(
        [
            Issue(
                where if it.key == gif.key else "output.gif.key",
                None,
                f"{gif.key} = {v!r}: {it.key}: " + it.message.removesuffix(" (from --set)"),
            )
            for it in exc.issues
        ]
    )


def sweep_designs(design: Design) -> dict[str, Design]:
    """The design of each distinct value of its ``[output.gif]`` sweep, by ``repr(value)``.

    Raises
    ------
    DesignError
        At ``output.gif.key`` when the key is no key of a design, at ``output.gif.values``
        (or ``start``/``stop``) when a value is not one the key accepts: ``voroforge check``
        says so as ``build`` does.
    """
    gif = design.output.gif
    data = design.model_dump()
    out = {}
    for v in gif.sweep():
        if repr(v) in out:
            continue
        try:
            out[repr(v)], _ = load(data, overrides={gif.key: v})
        except DesignError as exc:
            raise _sweep_error(gif, v, exc) from None
    return out


def _report(result: Result):
    from .fabrication import Report, check, design_corner_tolerance, sort_key

    f = result.design.fabrication
    limits = {
        "min_web": f.min_web,
        "min_opening": f.min_opening,
        "min_inside_radius": f.tool_radius,
        "corner_tolerance": design_corner_tolerance(result.design),
        "islands": f.islands,
        "keys": {
            "min_web": "fabrication.min_web",
            "min_opening": "fabrication.min_opening",
            "min_inside_radius": "fabrication.tool_radius",
        },
    }
    if "tile" not in result.extra:  # the frame as computed (tiling openings leave no slivers)
        return check(
            openings=result.openings, boundary=result.boundary, frame=result.frame, **limits
        )
    # A periodic tile is cut as copies side by side: openings cut by the tile's edge continue
    # in the next copy, so check the whole openings of 3 x 3 copies against each other (no
    # outline in reach) and report each violation of the torus once, located in the tile.
    xmin, ymin, xmax, ymax = result.extra["tile"]
    w, h = xmax - xmin, ymax - ymin
    whole = result.extra["tile_openings"]
    shift = [(dx, dy) for dy in (0, -1, 1) for dx in (0, -1, 1)]  # copy k's shift in tiles
    copies = [shapely.transform(whole, lambda xy, s=s: xy + (s[0] * w, s[1] * h)) for s in shift]
    holes = np.concatenate(copies) if len(whole) else whole
    far = shapely.box(xmin - 2 * w, ymin - 2 * h, xmax + 2 * w, ymax + 2 * h)
    tiled = check(openings=holes, boundary=far, **limits)
    n = max(len(whole), 1)
    kept: dict = {}  # torus key -> (whether its first opening is in the middle copy, violation)
    for v in tiled.violations:
        x, y = v.location
        spot = (xmin + (x - xmin) % w, ymin + (y - ymin) % h)
        a, b = v.items[0] if v.items else -1, v.items[-1] if v.items else -1
        if a < 0 or b < 0 or a == b:  # islands, one opening's own: the middle copy's
            if a < n if v.items else xmin <= x < xmax and ymin <= y < ymax:
                items = tuple(k % n if k >= 0 else k for k in v.items)
                kept[len(kept)] = (True, replace(v, location=spot, items=items))
            continue
        # A web between parallel edges has no one thinnest spot, so its copies differ: keep
        # one per pair of openings and shift between their copies, either way round.
        (i, ix, iy), (j, jx, jy) = (a % n, *shift[a // n]), (b % n, *shift[b // n])
        key = min((i, j, jx - ix, jy - iy), (j, i, ix - jx, iy - jy))
        middle = (ix, iy) == (0, 0) if key[0] == i else (jx, jy) == (0, 0)
        if key not in kept or middle and not kept[key][0]:
            kept[key] = (middle, replace(v, location=spot, items=key[:2]))
    found = sorted((v for _, v in kept.values()), key=sort_key)
    return Report(found, tiled.limits, result.frame, result.openings, tiled.keys)


def check_design(source, *, overrides: dict | None = None, progress: Stage | None = None):
    """Build a design's geometry and run the fabrication check with its ``[fabrication]`` limits.

    Returns
    -------
    voroforge.design.fabrication.Report
    """
    design, base = load(source, overrides=overrides)
    if design.output.gif is not None and "gif" in design.output.formats:
        with located(source, overrides):
            sweep_designs(design)  # a sweep build would refuse is refused here too
    if design.solid is not None:  # print checks of a 3D product (voroforge.solid)
        from ..solid.build import check_solid

        with located(source, overrides):
            return check_solid(design, base, progress)
    with located(source, overrides):
        return _report(compute(design, base, progress=progress))


def starter() -> str:
    """The commented starter design that ``voroforge new`` writes (package data).

    Returns
    -------
    str
        The TOML text of ``voroforge/design/data/starter.toml``.
    """
    return resources.files(__package__).joinpath("data", "starter.toml").read_text("utf-8")


def write_starter(path="design.toml", *, overwrite: bool = False) -> Path:
    """Write the commented starter design (:func:`starter`) to ``path``.

    Raises
    ------
    ValueError
        When the file exists and ``overwrite`` is false.
    """
    path = Path(path)
    if path.exists() and not overwrite:
        raise ValueError(f"{path}: already exists (use --force to overwrite)")
    return _save_text(path, starter())
