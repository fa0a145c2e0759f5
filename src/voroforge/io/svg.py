"""SVG output: cells, boundary and sites as separate layers, in data units, upright."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import shapely

from ..config import ARC_TOLERANCE
from .arcs import bulges_of_rings
from .plotter import layer_paths
from .render import (
    PathContext,
    as_boundary,
    as_geometries,
    data_bounds,
    digits_for,
    format_number,
    palette,
    trace,
)

__all__ = ["layers_string", "svg_string", "write_layers", "write_svg"]

_UNITS = ("px", "mm", "cm", "in", "pt")
_DEFAULT_PIXELS = 800.0


# xml.sax.saxutils has these two, but importing it loads urllib.request and ssl (~0.07 s of
# every build that writes an SVG); the same rules, for the text this writer emits:
def _escape(text: str) -> str:
    """``text`` with ``&``, ``<`` and ``>`` as XML entities."""
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def _quoteattr(value: str) -> str:
    """``value`` escaped and quoted as an XML attribute value, quotes included.

    Double quotes unless the value holds one (then single quotes, or ``&quot;`` when it
    holds both); newlines, returns and tabs as character references so they survive
    attribute normalisation.
    """
    value = _escape(value).replace("\n", "&#10;").replace("\r", "&#13;").replace("\t", "&#9;")
    if '"' not in value:
        return f'"{value}"'
    if "'" not in value:
        return f"'{value}'"
    return '"' + value.replace('"', "&quot;") + '"'


def _colour(value) -> str:
    """Return an SVG colour: strings pass through, RGB triples become ``#rrggbb``."""
    if isinstance(value, str):
        return value
    r, g, b = (int(c) for c in list(value)[:3])
    return f"#{r:02x}{g:02x}{b:02x}"


def _fills(fill, n: int, seed: int) -> tuple[str | None, list[str] | None]:
    """Split ``fill`` into a group-level colour or one colour per cell."""
    if isinstance(fill, str) and fill == "auto":
        return None, [_colour(c) for c in palette(n, seed)]
    if isinstance(fill, str) or fill is None:
        return fill or "none", None
    values = list(fill)
    if len(values) in (3, 4) and all(isinstance(v, int | np.integer) for v in values):
        return _colour(values), None
    if len(values) != n:
        raise ValueError(f"fill has {len(values)} colours for {n} geometries")
    return None, [_colour(v) for v in values]


def svg_string(
    geoms,
    *,
    sites=None,
    boundary=None,
    width: float | None = None,
    units: str | None = None,
    stroke: str = "#262b33",
    fill="auto",
    stroke_width: float | None = None,
    site_radius: float | None = None,
    seed: int = 0,
) -> str:
    """Render geometries as an SVG document; see :func:`write_svg` for the parameters.

    Returns
    -------
    str
        The SVG document.
    """
    cells = as_geometries(geoms)
    bound = as_boundary(boundary)
    pts = None if sites is None else np.asarray(sites, dtype=np.float64).reshape(-1, 2)
    if units is not None and units not in _UNITS:
        raise ValueError(f"units must be one of {', '.join(_UNITS)}; got {units!r}")

    xmin, ymin, xmax, ymax = data_bounds(cells, pts, bound)
    span = max(xmax - xmin, ymax - ymin)
    sw = span / 800.0 if stroke_width is None else float(stroke_width)
    radius = span / 400.0 if site_radius is None else float(site_radius)
    pad = 2.0 * max(sw, radius)
    xmin, ymin, xmax, ymax = xmin - pad, ymin - pad, xmax + pad, ymax + pad
    w, h = xmax - xmin, ymax - ymin
    digits = digits_for(span)

    # Output size: 1 data unit = 1 ``units`` unless ``width`` says otherwise.
    if width is None:
        out_w = w if units is not None else _DEFAULT_PIXELS * w / max(w, h)
    else:
        out_w = float(width)
    out_h = out_w * h / w
    suffix = units if units not in (None, "px") else ""

    def num(v: float) -> str:
        return format_number(v, digits)

    def flip(xy: np.ndarray) -> np.ndarray:
        return np.column_stack((xy[:, 0], -xy[:, 1]))

    group_fill, cell_fills = _fills(fill, len(cells), seed)
    out = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        '<svg xmlns="http://www.w3.org/2000/svg" version="1.1" '
        f'width="{format_number(out_w, 4)}{suffix}" height="{format_number(out_h, 4)}{suffix}" '
        f'viewBox="{num(xmin)} {num(-ymax)} {num(w)} {num(h)}">',
    ]
    cell_attrs = f'fill-rule="evenodd" stroke={_quoteattr(stroke)} stroke-width="{num(sw)}"'
    if group_fill is not None:
        cell_attrs += f" fill={_quoteattr(_colour(group_fill))}"
    out.append(f'<g id="cells" {cell_attrs} stroke-linejoin="round">')
    for i, geom in enumerate(cells):
        ctx = PathContext(digits)
        if trace(ctx, geom, flip) == 0:
            continue
        extra = "" if cell_fills is None else f" fill={_quoteattr(cell_fills[i])}"
        out.append(f'<path id="cell-{i}"{extra} d="{ctx}"/>')
    out.append("</g>")

    if bound is not None:
        ctx = PathContext(digits)
        trace(ctx, bound, flip)
        out.append(
            f'<g id="boundary" fill="none" fill-rule="evenodd" stroke={_quoteattr(stroke)} '
            f'stroke-width="{num(2.0 * sw)}" stroke-linejoin="round">'
        )
        out.append(f'<path d="{ctx}"/>')
        out.append("</g>")

    if pts is not None:
        out.append(f'<g id="sites" fill={_quoteattr(stroke)} stroke="none">')
        r = num(radius)
        out.extend(f'<circle cx="{num(x)}" cy="{num(-y)}" r="{r}"/>' for x, y in pts.tolist())
        out.append("</g>")
    out.append("</svg>")
    return "\n".join(out) + "\n"


def write_svg(
    geoms,
    path,
    *,
    sites=None,
    boundary=None,
    width: float | None = None,
    units: str | None = None,
    stroke: str = "#262b33",
    fill="auto",
    stroke_width: float | None = None,
    site_radius: float | None = None,
    seed: int = 0,
) -> Path:
    """Write polygons (for example ``diagram.cells``) to an SVG file.

    The document has three layers, ``<g id="cells">``, ``<g id="boundary">`` and
    ``<g id="sites">``. Each non-empty geometry is one closed ``<path id="cell-i">`` (holes
    and parts as further sub-paths, filled even-odd). The ``viewBox`` is in data units with the
    y axis flipped, so the picture is upright and coordinates can be read back as ``(x, -y)``.

    Parameters
    ----------
    geoms : sequence of shapely Polygon or MultiPolygon
        Cells to draw; empty geometries and ``None`` are skipped (indices are kept in ids).
    path : str or Path
        Output file.
    sites : (n, 2) array_like, optional
        Points drawn as small dots.
    boundary : shapely geometry or (xmin, ymin, xmax, ymax), optional
        Domain outline, drawn on its own layer.
    width : float, optional
        Width of the drawing in ``units``. Default: the data width when ``units`` is given
        (1 data unit = 1 unit, handy with ``units="mm"`` for cutters), else 800 px on the
        longer side.
    units : {"mm", "cm", "in", "pt", "px"}, optional
        Units of ``width`` and ``height``.
    stroke : str
        Colour of edges, outline and sites.
    fill : "auto", "none", colour, or sequence of colours
        ``"auto"`` gives every cell its own light colour (deterministic from ``seed``).
    stroke_width : float, optional
        Edge width in data units (default 1/800 of the longer side); the outline is twice that.
    site_radius : float, optional
        Dot radius in data units (default 1/400 of the longer side).
    seed : int
        Seed of the ``"auto"`` colours.

    Returns
    -------
    Path
        The file written.

    Examples
    --------
    >>> import shapely, tempfile, pathlib
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "square.svg"
    >>> write_svg([shapely.box(0, 0, 1, 1)], out, units="mm").name
    'square.svg'
    """
    text = svg_string(
        geoms,
        sites=sites,
        boundary=boundary,
        width=width,
        units=units,
        stroke=stroke,
        fill=fill,
        stroke_width=stroke_width,
        site_radius=site_radius,
        seed=seed,
    )
    return _write_text(Path(path), text)


def _write_text(path: Path, text: str) -> Path:
    """Write ``text`` to ``path`` atomically (:func:`voroforge.io.atomic.write_atomically`)."""
    from .atomic import write_atomically

    return write_atomically(path, lambda tmp: Path(tmp).write_text(text, encoding="utf-8"))


# --- Fabrication layers (cut / score / engrave) -------------------------------------------

#: Stroke colours of the conventional fabrication layers (laser software maps colours to jobs).
LAYER_STROKES = {
    "CUT": "#ff0000",
    "SCORE": "#0000ff",
    "ENGRAVE": "#000000",
    "SITES": "#808080",
    "BOUNDARY": "#ff00ff",
    "MARK": "#ff8000",
}
_INKSCAPE = "http://www.inkscape.org/namespaces/inkscape"


def _layer_id(name: str) -> str:
    text = "".join(c if c.isalnum() or c in "-_" else "-" for c in str(name).strip())
    if not text:
        raise ValueError(f"invalid layer name {name!r}")
    return text if not text[0].isdigit() else "layer-" + text


def _line_path(xy: np.ndarray, num) -> str:
    """SVG path data of an open polyline (data coordinates, y flipped here)."""
    pts = [f"{num(x)},{num(-y)}" for x, y in np.asarray(xy)[:, :2].tolist()]
    return "M" + pts[0] + "".join("L" + p for p in pts[1:])


def _arc_path(ring, num) -> str:
    """SVG path data of a closed ring of ``(x, y, bulge)`` (data coordinates, y flipped here).

    Straight segments become ``L``, bulged ones circular ``A`` arcs: a counter-clockwise arc
    in data coordinates (bulge > 0) turns clockwise once y points down, so its sweep flag is 0.
    """
    parts = [f"M{num(ring[0][0])},{num(-ring[0][1])}"]
    n = len(ring)
    for i in range(n):
        x0, y0, b = ring[i]
        x1, y1, _ = ring[(i + 1) % n]
        end = f"{num(x1)},{num(-y1)}"
        if i == n - 1 and not b:
            break  # Z draws the last straight segment
        if not b:
            parts.append("L" + end)
            continue
        theta = 4.0 * math.atan(abs(b))
        chord = math.hypot(x1 - x0, y1 - y0)
        r = num(chord / (2.0 * math.sin(theta / 2.0)))
        large = 1 if theta > math.pi else 0
        sweep = 0 if b > 0 else 1
        parts.append(f"A{r},{r} 0 {large} {sweep} {end}")
    return "".join(parts) + "Z"


def layers_string(
    layers: dict,
    *,
    units: str = "mm",
    stroke_width: float = 0.01,
    colours: dict | None = None,
    fills: dict | None = None,
    margin: float = 0.0,
    bounds=None,
    arcs: bool = True,
    arc_tolerance: float = ARC_TOLERANCE,
    order: str = "file",
    dedupe: bool = True,
    merge: bool = True,
    point_radius: float | None = None,
    legend=None,
    non_scaling=(),
) -> str:
    """Render fabrication layers as an SVG document; see :func:`write_layers`.

    Returns
    -------
    str
        The SVG document.
    """
    if units not in _UNITS:
        raise ValueError(f"units must be one of {', '.join(_UNITS)}; got {units!r}")
    if not stroke_width > 0:
        raise ValueError(f"stroke_width must be positive; got {stroke_width!r}")
    if not margin >= 0:
        raise ValueError(f"margin must be >= 0; got {margin!r}")
    content = {str(name): as_geometries(geoms) for name, geoms in layers.items()}
    ids = [_layer_id(name) for name in content]
    if len(set(ids)) != len(ids):
        raise ValueError(f"layer names collide: {', '.join(content)}")
    if bounds is None:
        every = [g for geoms in content.values() for g in geoms]
        xmin, ymin, xmax, ymax = data_bounds(np.array(every, dtype=object).reshape(-1))
    else:
        xmin, ymin, xmax, ymax = (float(v) for v in bounds)
    xmin, ymin, xmax, ymax = xmin - margin, ymin - margin, xmax + margin, ymax + margin
    w, h = xmax - xmin, ymax - ymin
    digits = digits_for(max(w, h))
    suffix = "" if units == "px" else units

    def num(v: float) -> str:
        return format_number(v, digits)

    def flip(xy: np.ndarray) -> np.ndarray:
        return np.column_stack((xy[:, 0], -xy[:, 1]))

    strokes = {**LAYER_STROKES, **{str(k).upper(): v for k, v in (colours or {}).items()}}
    fill_of = {str(k).upper(): v for k, v in (fills or {}).items()}
    out = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        '<svg xmlns="http://www.w3.org/2000/svg" '
        f'xmlns:inkscape="{_INKSCAPE}" version="1.1" '
        f'width="{num(w)}{suffix}" height="{num(h)}{suffix}" '
        f'viewBox="{num(xmin)} {num(-ymax)} {num(w)} {num(h)}">',
    ]
    for (name, geoms), ident in zip(content.items(), ids, strict=True):
        stroke = _colour(strokes.get(name.upper(), "#000000"))
        fill = fill_of.get(name.upper())
        fill_attr = "none" if fill is None else _colour(fill)
        screen = name.upper() in {str(k).upper() for k in non_scaling}
        width = (
            '1.5" vector-effect="non-scaling-stroke' if screen else format_number(stroke_width, 6)
        )
        out.append(
            f'<g id={_quoteattr(ident)} inkscape:groupmode="layer" '
            f"inkscape:label={_quoteattr(name)} fill={_quoteattr(fill_attr)} "
            f'fill-rule="evenodd" stroke={_quoteattr(stroke)} '
            f'stroke-width="{width}" '
            'stroke-linejoin="round" stroke-linecap="round">'
        )
        drawn = layer_paths(geoms, order=order, dedupe=dedupe, merge=merge)
        options = {"arcs": arcs, "tolerance": arc_tolerance}
        fitted = iter(bulges_of_rings(drawn.rings(), **options))
        for xy, closed in zip(drawn.paths, drawn.closed.tolist(), strict=True):
            if closed:  # one closed path per ring, fillets as true arcs
                out.append(f'<path d="{_arc_path(next(fitted).tolist(), num)}"/>')
            else:
                out.append(f'<path d="{_line_path(xy, num)}"/>')
        r = num(max(stroke_width, 0.5) if point_radius is None else point_radius)
        for geom in geoms:
            if geom.is_empty:
                continue
            for pt in shapely.get_parts(geom):
                if pt.geom_type == "Point":
                    out.append(f'<circle cx="{num(pt.x)}" cy="{num(-pt.y)}" r="{r}"/>')
        out.append("</g>")
    if legend:
        out.extend(_legend(legend, xmin, ymax, max(w, h), num))
    out.append("</svg>")
    return "\n".join(out) + "\n"


def _legend(rows, xmin: float, ymax: float, span: float, num) -> list[str]:
    """A ``LEGEND`` layer: one coloured line of text per row, top left."""
    size = span / 45.0
    out = [
        '<g id="LEGEND" inkscape:groupmode="layer" inkscape:label="LEGEND" '
        f'font-family="sans-serif" font-size="{num(size)}" stroke="none">'
    ]
    height = size * (1.4 * len(rows) + 0.8)
    out.append(
        f'<rect x="{num(xmin + size * 0.4)}" y="{num(-ymax + size * 0.4)}" '
        f'width="{num(size * (0.62 * max(len(str(t)) for t, _ in rows) + 1.2))}" '
        f'height="{num(height)}" fill="#ffffff" '
        'fill-opacity="0.85" stroke="#555555" stroke-width="1" '
        'vector-effect="non-scaling-stroke"/>'
    )
    for k, (text, colour) in enumerate(rows):
        y = -ymax + size * (0.4 + 1.4 * (k + 1))
        out.append(
            f'<text x="{num(xmin + size)}" y="{num(y)}" fill={_quoteattr(_colour(colour))}>'
            f"{_escape(str(text))}</text>"
        )
    out.append("</g>")
    return out


def write_layers(
    path,
    layers: dict,
    *,
    units: str = "mm",
    stroke_width: float = 0.01,
    colours: dict | None = None,
    fills: dict | None = None,
    margin: float = 0.0,
    bounds=None,
    arcs: bool = True,
    arc_tolerance: float = ARC_TOLERANCE,
    order: str = "file",
    dedupe: bool = True,
    merge: bool = True,
    point_radius: float | None = None,
    legend=None,
    non_scaling=(),
) -> Path:
    """Write fabrication layers (cut, score, engrave, ...) to an SVG file for a laser cutter.

    Each layer is an Inkscape layer ``<g id="CUT" inkscape:groupmode="layer">`` with a
    hairline stroke in the layer's colour (red cut, blue score, black engrave by default) and
    no fill. Every polygon ring is its own closed ``<path d="M...Z">`` (fillets as true
    circular arcs); lines are open paths,
    points small circles. One data unit is one ``units`` unit: ``width="600mm"`` with a
    ``viewBox`` in millimetres, y axis up (coordinates read back as ``(x, -y)``).

    Parameters
    ----------
    path : str or Path
        Output file.
    layers : dict of str to sequence of shapely geometries
        Layers in drawing order, for example ``{"CUT": [frame], "SCORE": edges}``.
    units : {"mm", "cm", "in", "pt", "px"}
        Unit of the data and of ``width``/``height``.
    stroke_width : float
        Stroke width in data units (0.01 mm: the hairline laser software expects).
    colours : dict of str to colour, optional
        Stroke colour per layer name, over :data:`LAYER_STROKES`.
    fills : dict of str to colour, optional
        Fill per layer (default none: cutters want outlines only).
    margin : float
        Space around the drawing in data units.
    bounds : (xmin, ymin, xmax, ymax), optional
        Page extent in data units (default: the geometry's bounds).
    arcs : bool
        Write runs of chords that lie on one circle (fillets, round buffers) as true SVG arcs
        (``A``), found as for DXF bulges (:func:`voroforge.io.arcs.arc_runs`).
    arc_tolerance : float
        Largest distance of a vertex from the arc that replaces it, in data units.
    order : {"file", "travel"}
        Path order within a layer: as given (rings, then lines), or ordered for short pen-up
        travel from the layer's top-left corner (:func:`voroforge.io.plotter.layer_paths`).
    dedupe : bool
        Draw every segment of a layer once: a ring that repeats another is dropped, segments
        shared with earlier geometry are cut out (frame and openings, neighbouring cells).
    merge : bool
        Join open line pieces into the fewest strokes, through junctions.
    point_radius : float, optional
        Radius of the circles drawn for points (default ``max(stroke_width, 0.5)``).
    legend : sequence of (text, colour), optional
        A key drawn in the top-left corner on a ``LEGEND`` layer (for overlays, not cuts).
    non_scaling : sequence of str
        Layers drawn with ``vector-effect="non-scaling-stroke"`` at 1.5 screen pixels, so
        their marks stay visible at any zoom (overlays).

    Returns
    -------
    Path
        The file written (atomically: a temporary file renamed into place).

    Examples
    --------
    >>> import shapely, tempfile, pathlib
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "panel.svg"
    >>> write_layers(out, {"CUT": [shapely.box(0, 0, 60, 40)]}).name
    'panel.svg'
    """
    text = layers_string(
        layers,
        units=units,
        stroke_width=stroke_width,
        colours=colours,
        fills=fills,
        margin=margin,
        bounds=bounds,
        arcs=arcs,
        arc_tolerance=arc_tolerance,
        order=order,
        dedupe=dedupe,
        merge=merge,
        point_radius=point_radius,
        legend=legend,
        non_scaling=non_scaling,
    )
    return _write_text(Path(path), text)
