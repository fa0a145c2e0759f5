"""PNG output with pillow: coloured cells, thin dark edges, sites as dots, upright."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from PIL import Image, ImageColor, ImageDraw

from .. import config
from .render import RingContext, as_boundary, as_geometries, data_bounds, palette, trace

__all__ = ["render_image", "write_png"]

_EDGE = (38, 43, 51)


def _rgb(value) -> tuple[int, int, int]:
    """Any pillow colour spec or RGB triple as an ``(r, g, b)`` tuple."""
    if isinstance(value, str):
        return ImageColor.getrgb(value)[:3]
    r, g, b = (int(c) for c in list(value)[:3])
    return r, g, b


def _is_single_colour(value) -> bool:
    if isinstance(value, str):
        return True
    values = list(value)
    return len(values) in (3, 4) and all(isinstance(v, int | np.integer) for v in values)


def _cell_colours(colors, n: int, seed: int) -> list[tuple[int, int, int]]:
    if colors is None:
        return [tuple(c) for c in palette(n, seed).tolist()]
    if _is_single_colour(colors):
        return [_rgb(colors)] * n
    values = list(colors)
    if len(values) != n:
        raise ValueError(f"colors has {len(values)} entries for {n} geometries")
    return [_rgb(v) for v in values]


def check_png_size(size, supersample: int = 2) -> tuple[int, int]:
    """``(size, supersample)`` as ints, or ``ValueError`` when the picture cannot be drawn.

    :func:`render_image` calls it, and the command line before any work (``voroforge
    voronoi -o a.geojson -o b.png --size 1000000`` wrote a.geojson, then failed).
    """
    size = int(size)
    if size < 8:
        raise ValueError(f"size must be at least 8 pixels; got {size}")
    ss = max(1, int(supersample))
    if (size * ss) ** 2 > config.MAX_PIXELS:
        most = math.isqrt(config.MAX_PIXELS) // ss
        raise ValueError(
            f"size {size} px is too large: {size} x {size} pixels drawn at {ss}x supersampling "
            f"need about {3 * (size * ss) ** 2 / 2**30:.0f} GB; use at most {most}"
        )
    return size, ss


def render_image(
    geoms,
    *,
    size: int = 1024,
    sites=None,
    boundary=None,
    colors=None,
    seed: int = 0,
    background="white",
    edge_color=_EDGE,
    edge_width: float = 1.0,
    site_radius: float | None = None,
    supersample: int = 2,
    marks=None,
    legend=None,
    lines=None,
) -> Image.Image:
    """Draw polygons (for example ``diagram.cells``) into a pillow image.

    Parameters
    ----------
    geoms : sequence of shapely Polygon or MultiPolygon
        Cells to fill; empty geometries are skipped. Holes stay transparent to what is below.
    size : int
        Length in pixels of the longer side; the other side follows the data's aspect ratio.
    sites : (n, 2) array_like, optional
        Points drawn as dots.
    boundary : shapely geometry or (xmin, ymin, xmax, ymax), optional
        Domain outline, drawn twice as thick as the edges.
    colors : colour or sequence of colours, optional
        One colour for all cells, or one per cell (pillow colour names, ``#rrggbb`` or RGB
        tuples). Default: a distinct light colour per cell, deterministic from ``seed``.
    seed : int
        Seed of the default colours.
    background : colour
        Colour outside the cells.
    edge_color : colour
        Colour of edges, outline and sites.
    edge_width : float
        Edge width in pixels.
    site_radius : float, optional
        Dot radius in pixels (default ``size / 400``, at least 1.5).
    supersample : int
        Draw this many times larger and shrink, for smooth edges (1 turns it off).
    marks : sequence of (x, y, shape, colour), optional
        Markers drawn on top at a fixed size in pixels (visible however small the spot):
        ``shape`` is ``"circle"``, ``"square"``, ``"triangle"`` or ``"diamond"``.
    legend : sequence of (shape, colour, text), optional
        A key drawn in the top-left corner, one row per entry.
    lines : sequence of (geometry, width, colour), optional
        Line work drawn over the cells, in order: every line of each geometry (LineString,
        MultiLineString, LinearRing or polygon outlines) stroked ``width`` wide in data
        units, with round joins and ends.

    Returns
    -------
    PIL.Image.Image
        An RGB image, y axis up.
    """
    size, ss = check_png_size(size, supersample)
    cells = as_geometries(geoms)
    bound = as_boundary(boundary)
    pts = None if sites is None else np.asarray(sites, dtype=np.float64).reshape(-1, 2)
    fills = _cell_colours(colors, len(cells), seed)
    edge = _rgb(edge_color)

    strokes = _strokes(lines)
    drawn = cells
    if strokes:
        drawn = np.concatenate((cells, np.asarray([g for g, _, _ in strokes], dtype=object)))
    xmin, ymin, xmax, ymax = data_bounds(drawn, pts, bound)
    w, h = xmax - xmin, ymax - ymin
    margin = max(4, round(size * 0.02))
    longer = size - 2 * margin
    out_w = size if w >= h else max(2 * margin + 1, round(longer * w / h) + 2 * margin)
    out_h = size if h > w else max(2 * margin + 1, round(longer * h / w) + 2 * margin)
    scale = longer / max(w, h) * ss
    off_x = (out_w * ss - w * scale) / 2.0
    off_y = (out_h * ss - h * scale) / 2.0

    def to_pixels(xy: np.ndarray) -> np.ndarray:
        return np.column_stack(
            (off_x + (xy[:, 0] - xmin) * scale, off_y + (ymax - xy[:, 1]) * scale)
        )

    image = Image.new("RGB", (out_w * ss, out_h * ss), _rgb(background))
    draw = ImageDraw.Draw(image)
    outlines: list[list[tuple[float, float]]] = []
    for geom, colour in zip(cells, fills, strict=True):
        ctx = RingContext()
        if trace(ctx, geom, to_pixels) == 0:
            continue
        outlines.extend(ctx.rings)
        has_holes = any(len(p.interiors) for p in getattr(geom, "geoms", [geom]))
        if not has_holes:
            for ring in ctx.rings:
                draw.polygon(ring, fill=colour)
            continue
        # Even-odd fill through a mask, so holes never paint over other cells.
        image.paste(colour, *_even_odd_mask(ctx.rings))

    line_w = max(1, round(edge_width * ss))
    for ring in outlines:
        draw.line([*ring, ring[0]], fill=edge, width=line_w, joint="curve")
    for geom, width, colour in strokes:
        _stroke(draw, geom, width * scale, colour, to_pixels)
    if bound is not None:
        ctx = RingContext()
        trace(ctx, bound, to_pixels)
        for ring in ctx.rings:
            draw.line([*ring, ring[0]], fill=edge, width=2 * line_w, joint="curve")
    if pts is not None and len(pts):
        r = (max(1.5, size / 400.0) if site_radius is None else float(site_radius)) * ss
        for x, y in to_pixels(pts).tolist():
            draw.ellipse((x - r, y - r, x + r, y + r), fill=edge)

    r_mark = max(6.0, size / 90.0) * ss
    for x, y, shape, colour in marks or []:
        ((px, py),) = to_pixels(np.array([[x, y]], dtype=np.float64)).tolist()
        _mark(draw, px, py, shape, r_mark, _rgb(colour), max(2, round(1.5 * ss)))
    if legend:
        _legend(draw, legend, r_mark, ss)
    if ss > 1:
        image = image.reduce(ss)
    return image


def _strokes(lines) -> list:
    """``render_image``'s ``lines`` checked: (geometry, width >= 0, RGB) per entry."""
    import shapely

    out = []
    for entry in lines or []:
        try:
            geom, width, colour = entry
        except (TypeError, ValueError):
            raise ValueError("lines must be (geometry, width, colour) triples") from None
        if not isinstance(geom, shapely.Geometry):
            raise ValueError(f"a line must be a shapely geometry, got {type(geom).__name__}")
        w = float(width)
        if not (math.isfinite(w) and w >= 0):
            raise ValueError(f"a line width must be a finite number >= 0, got {width!r}")
        if not geom.is_empty:
            out.append((geom, w, _rgb(colour)))
    return out


def _stroke(draw, geom, width_px: float, colour, to_pixels) -> None:
    """Every line of ``geom`` drawn ``width_px`` wide, round joins and (wide lines) ends."""
    import shapely

    if geom.geom_type.endswith("Polygon"):
        geom = geom.boundary
    w = max(1, round(width_px))
    r = (w - 1) / 2.0  # the cap's disc as wide as the line pillow draws
    for part in shapely.get_parts(geom):
        xy = to_pixels(shapely.get_coordinates(part))
        if len(xy) < 2:
            continue
        draw.line([tuple(p) for p in xy.tolist()], fill=colour, width=w, joint="curve")
        if w >= 3:  # round ends, so pieces of one line join without notches
            for x, y in (xy[0], xy[-1]):
                draw.ellipse((x - r, y - r, x + r, y + r), fill=colour)


#: Marker shapes of :func:`render_image` (``marks=``), as unit polygons (None: a circle).
MARK_SHAPES = {
    "circle": None,
    "square": [(-0.8, -0.8), (0.8, -0.8), (0.8, 0.8), (-0.8, 0.8)],
    "triangle": [(0.0, -1.0), (0.95, 0.75), (-0.95, 0.75)],
    "diamond": [(0.0, -1.1), (1.0, 0.0), (0.0, 1.1), (-1.0, 0.0)],
}


def _mark(draw, x: float, y: float, shape: str, r: float, colour, width: int) -> None:
    """An outlined marker with a dot at its centre, centred on pixel ``(x, y)``."""
    if shape not in MARK_SHAPES:
        raise ValueError(f"mark shape must be one of {', '.join(MARK_SHAPES)}; got {shape!r}")
    unit = MARK_SHAPES[shape]
    if unit is None:
        draw.ellipse((x - r, y - r, x + r, y + r), outline=colour, width=width)
    else:
        pts = [(x + u * r, y + v * r) for u, v in unit]
        draw.line([*pts, pts[0]], fill=colour, width=width, joint="curve")
    d = max(1.0, r / 5.0)
    draw.ellipse((x - d, y - d, x + d, y + d), fill=colour)


def _legend(draw, rows, r: float, ss: int) -> None:
    """A white box with one marker and its text per row, in the top-left corner."""
    from PIL import ImageFont

    try:
        font = ImageFont.load_default(size=max(10, round(1.6 * r)))
    except TypeError:  # pillow < 10.1: one bitmap size
        font = ImageFont.load_default()
    pad = r
    step = 2.6 * r
    widths = [draw.textlength(str(text), font=font) for _, _, text in rows]
    box = (pad, pad, pad + 4 * r + max(widths) + pad, pad + step * len(rows) + pad * 0.6)
    draw.rectangle(box, fill=(255, 255, 255), outline=(90, 90, 90), width=max(1, ss))
    for k, (shape, colour, text) in enumerate(rows):
        cy = pad + step * (k + 0.5) + pad * 0.3
        _mark(draw, pad + 2 * r, cy, shape, r * 0.8, _rgb(colour), max(2, round(1.5 * ss)))
        draw.text((pad + 3.6 * r, cy), str(text), fill=(20, 20, 20), font=font, anchor="lm")


def _even_odd_mask(rings) -> tuple[tuple[int, int], Image.Image]:
    """Top-left corner and ``L`` mask of the even-odd fill of ``rings`` (pixel coordinates)."""
    xy = np.array([p for ring in rings for p in ring])
    x0, y0 = (int(v) for v in np.floor(xy.min(axis=0)))
    x1, y1 = (int(v) for v in np.ceil(xy.max(axis=0)))
    size = (x1 - x0 + 1, y1 - y0 + 1)
    inside = np.zeros((size[1], size[0]), dtype=bool)
    for ring in rings:
        # each ring is drawn into its own bounding box only: a cell's hole costs its own
        # pixels, not the whole panel's
        r = np.asarray(ring, dtype=np.float64)
        rx0, ry0 = (int(v) for v in np.floor(r.min(axis=0)))
        rx1, ry1 = (int(v) for v in np.ceil(r.max(axis=0)))
        single = Image.new("1", (rx1 - rx0 + 1, ry1 - ry0 + 1), 0)
        ImageDraw.Draw(single).polygon([(x - rx0, y - ry0) for x, y in r.tolist()], fill=1)
        inside[ry0 - y0 : ry1 - y0 + 1, rx0 - x0 : rx1 - x0 + 1] ^= np.asarray(single, dtype=bool)
    return (x0, y0), Image.fromarray(inside.astype(np.uint8) * 255, "L")


def write_png(
    geoms,
    path,
    *,
    size: int = 1024,
    sites=None,
    boundary=None,
    colors=None,
    seed: int = 0,
    **options,
) -> Path:
    """Write polygons (for example ``diagram.cells``) to a PNG file.

    Parameters
    ----------
    geoms : sequence of shapely Polygon or MultiPolygon
        Cells to fill.
    path : str or Path
        Output file.
    size, sites, boundary, colors, seed, **options
        As for :func:`render_image`.

    Returns
    -------
    Path
        The file written.

    Examples
    --------
    >>> import shapely, tempfile, pathlib
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "square.png"
    >>> write_png([shapely.box(0, 0, 2, 1)], out, size=64).name
    'square.png'
    """
    image = render_image(
        geoms, size=size, sites=sites, boundary=boundary, colors=colors, seed=seed, **options
    )
    from .atomic import write_atomically

    # atomically: an interrupted save leaves the old file or none, never half a PNG
    return write_atomically(path, lambda tmp: image.save(tmp, format="PNG", optimize=False))
