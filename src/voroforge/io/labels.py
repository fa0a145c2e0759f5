"""Single-stroke text for engraving: cell numbers a laser or plotter draws as lines.

Laser and plotter software cannot be relied on for fonts, and an outline font would be cut
as closed shapes. :data:`GLYPHS` is a small single-stroke alphabet (digits, capitals, ``-``,
``.``, ``#``, space) drawn on a 4 x 6 grid as polylines; :func:`text_lines` sets a string as
a MultiLineString, and :func:`cell_labels` places one label inside each polygon, centred on
its largest inscribed circle and sized to fit in it.

Examples
--------
>>> import shapely
>>> lines = text_lines("12", 0.0, 0.0, 6.0)
>>> lines.geom_type, round(lines.bounds[3] - lines.bounds[1], 6)
('MultiLineString', 6.0)
"""

from __future__ import annotations

import math

import numpy as np
import shapely

__all__ = ["GLYPHS", "cell_labels", "label_spots", "text_lines", "text_width"]

_O = [(0, 1), (0, 5), (1, 6), (3, 6), (4, 5), (4, 1), (3, 0), (1, 0), (0, 1)]
_P = [(0, 0), (0, 6), (3, 6), (4, 5), (4, 4), (3, 3), (0, 3)]

#: Strokes of each character on a 4 wide x 6 high grid (y up), as polylines.
GLYPHS: dict[str, list[list[tuple[float, float]]]] = {
    "0": [_O, [(1, 1), (3, 5)]],
    "1": [[(1, 5), (2, 6), (2, 0)], [(1, 0), (3, 0)]],
    "2": [[(0, 5), (1, 6), (3, 6), (4, 5), (4, 4), (0, 0), (4, 0)]],
    "3": [
        [(0, 5), (1, 6), (3, 6), (4, 5), (4, 4), (3, 3), (1, 3)],
        [(3, 3), (4, 2), (4, 1), (3, 0), (1, 0), (0, 1)],
    ],
    "4": [[(3, 0), (3, 6), (0, 2), (4, 2)]],
    "5": [[(4, 6), (0, 6), (0, 3), (3, 3), (4, 2), (4, 1), (3, 0), (0, 0)]],
    "6": [[(4, 5), (3, 6), (1, 6), (0, 5), (0, 1), (1, 0), (3, 0), (4, 1), (4, 2), (3, 3), (0, 3)]],
    "7": [[(0, 6), (4, 6), (1, 0)]],
    "8": [
        [(1, 3), (0, 4), (0, 5), (1, 6), (3, 6), (4, 5), (4, 4), (3, 3), (1, 3)],
        [(1, 3), (0, 2), (0, 1), (1, 0), (3, 0), (4, 1), (4, 2), (3, 3)],
    ],
    "9": [[(4, 3), (1, 3), (0, 4), (0, 5), (1, 6), (3, 6), (4, 5), (4, 1), (3, 0), (1, 0), (0, 1)]],
    "A": [[(0, 0), (0, 4), (2, 6), (4, 4), (4, 0)], [(0, 3), (4, 3)]],
    "B": [[*_P, (0, 3)], [(3, 3), (4, 2), (4, 1), (3, 0), (0, 0)]],
    "C": [[(4, 5), (3, 6), (1, 6), (0, 5), (0, 1), (1, 0), (3, 0), (4, 1)]],
    "D": [[(0, 0), (0, 6), (2, 6), (4, 4), (4, 2), (2, 0), (0, 0)]],
    "E": [[(4, 6), (0, 6), (0, 0), (4, 0)], [(0, 3), (3, 3)]],
    "F": [[(4, 6), (0, 6), (0, 0)], [(0, 3), (3, 3)]],
    "G": [[(4, 5), (3, 6), (1, 6), (0, 5), (0, 1), (1, 0), (3, 0), (4, 1), (4, 3), (2, 3)]],
    "H": [[(0, 0), (0, 6)], [(4, 0), (4, 6)], [(0, 3), (4, 3)]],
    "I": [[(1, 6), (3, 6)], [(2, 6), (2, 0)], [(1, 0), (3, 0)]],
    "J": [[(4, 6), (4, 1), (3, 0), (1, 0), (0, 1)]],
    "K": [[(0, 0), (0, 6)], [(4, 6), (0, 2)], [(1, 3), (4, 0)]],
    "L": [[(0, 6), (0, 0), (4, 0)]],
    "M": [[(0, 0), (0, 6), (2, 3), (4, 6), (4, 0)]],
    "N": [[(0, 0), (0, 6), (4, 0), (4, 6)]],
    "O": [_O],
    "P": [_P],
    "Q": [_O, [(2, 2), (4, 0)]],
    "R": [_P, [(2, 3), (4, 0)]],
    "S": [
        [
            (4, 5),
            (3, 6),
            (1, 6),
            (0, 5),
            (0, 4),
            (1, 3),
            (3, 3),
            (4, 2),
            (4, 1),
            (3, 0),
            (1, 0),
            (0, 1),
        ]
    ],
    "T": [[(0, 6), (4, 6)], [(2, 6), (2, 0)]],
    "U": [[(0, 6), (0, 1), (1, 0), (3, 0), (4, 1), (4, 6)]],
    "V": [[(0, 6), (2, 0), (4, 6)]],
    "W": [[(0, 6), (1, 0), (2, 4), (3, 0), (4, 6)]],
    "X": [[(0, 0), (4, 6)], [(0, 6), (4, 0)]],
    "Y": [[(0, 6), (2, 3), (4, 6)], [(2, 3), (2, 0)]],
    "Z": [[(0, 6), (4, 6), (0, 0), (4, 0)]],
    "-": [[(1, 3), (3, 3)]],
    ".": [[(1.6, 0), (2.4, 0), (2.4, 0.8), (1.6, 0.8), (1.6, 0)]],
    "#": [[(1, 0), (1.5, 6)], [(2.5, 0), (3, 6)], [(0, 2), (4, 2)], [(0, 4), (4, 4)]],
    " ": [],
}

_ADVANCE = 5.0  # glyph width 4 + 1 of spacing, in grid units
_HEIGHT = 6.0


def text_width(text: str, height: float) -> float:
    """Width of ``text`` set at ``height`` (cap height) by :func:`text_lines`."""
    n = len(str(text))
    return 0.0 if n == 0 else (_ADVANCE * n - 1.0) * float(height) / _HEIGHT


def text_lines(text, x: float, y: float, height: float) -> shapely.MultiLineString:
    """Single-stroke polylines of ``text`` centred on ``(x, y)``, ``height`` tall.

    Parameters
    ----------
    text : str or int
        Digits, capital letters (lower case is upper-cased), ``-``, ``.``, ``#``, spaces.
    x, y : float
        Centre of the text.
    height : float
        Cap height, in drawing units (> 0).

    Returns
    -------
    shapely.MultiLineString

    Raises
    ------
    ValueError
        For a character without a glyph or a bad height.
    """
    s = str(text).upper()
    h = float(height)
    if not (math.isfinite(h) and h > 0):
        raise ValueError(f"height must be positive; got {height!r}")
    bad = sorted({c for c in s if c not in GLYPHS})
    if bad:
        raise ValueError(f"no single-stroke glyph for {''.join(bad)!r} (digits, A-Z, - . #)")
    k = h / _HEIGHT
    x0 = float(x) - text_width(s, h) / 2.0
    y0 = float(y) - h / 2.0
    strokes = []
    for i, c in enumerate(s):
        for stroke in GLYPHS[c]:
            xy = np.asarray(stroke, dtype=np.float64)
            strokes.append(np.column_stack((x0 + (xy[:, 0] + _ADVANCE * i) * k, y0 + xy[:, 1] * k)))
    return shapely.MultiLineString(strokes)


def label_spots(polygons) -> tuple[np.ndarray, np.ndarray]:
    """Centre and radius of the largest inscribed circle of each polygon (empty: NaN, 0).

    Returns
    -------
    centres : (n, 2) float64
    radii : (n,) float64
    """
    polys = np.asarray(polygons, dtype=object).reshape(-1)
    centres = np.full((len(polys), 2), np.nan)
    radii = np.zeros(len(polys))
    live = np.flatnonzero(~shapely.is_empty(polys)) if len(polys) else np.zeros(0, dtype=int)
    if not len(live):
        return centres, radii
    xmin, ymin, xmax, ymax = shapely.bounds(polys[live]).T
    tol = np.maximum(np.minimum(xmax - xmin, ymax - ymin) * 1e-3, 1e-12)
    if hasattr(shapely, "maximum_inscribed_circle"):
        circles = shapely.maximum_inscribed_circle(polys[live], tolerance=tol)
        centres[live] = shapely.get_coordinates(shapely.get_point(circles, 0))
        radii[live] = shapely.length(circles)
        return centres, radii
    from shapely.ops import polylabel  # shapely 2.0

    for j, i in enumerate(live.tolist()):
        part = max(shapely.get_parts(polys[i]), key=lambda g: g.area)
        c = polylabel(part, tolerance=float(tol[j]))
        centres[i] = (c.x, c.y)
        radii[i] = float(shapely.distance(c, part.boundary))
    return centres, radii


def cell_labels(polygons, labels=None, *, max_height: float | None = None, fill: float = 0.8):
    """One single-stroke label inside each polygon, centred on its largest inscribed circle.

    The text is sized so that its box fits in ``fill`` of that circle's diameter (and is at
    most ``max_height`` tall), so it stays inside the polygon.

    Parameters
    ----------
    polygons : (n,) sequence of shapely Polygon/MultiPolygon
        The cells; empty ones get no label.
    labels : (n,) sequence of str or int, optional
        The texts (default: the index of each polygon, ``0..n-1``).
    max_height : float, optional
        Largest cap height.
    fill : float
        Share of the inscribed diameter the text's box diagonal may take (0 < fill <= 1).

    Returns
    -------
    lines : (n,) object array of MultiLineString
        Empty for empty polygons.
    centres : (n, 2) float64
        Where each label is (NaN for empty polygons).
    heights : (n,) float64
        Cap height of each label (0 for empty polygons).
    """
    polys = np.asarray(polygons, dtype=object).reshape(-1)
    texts = [str(i) for i in range(len(polys))] if labels is None else [str(t) for t in labels]
    if len(texts) != len(polys):
        raise ValueError(f"{len(texts)} labels for {len(polys)} polygons")
    if not 0 < fill <= 1:
        raise ValueError(f"fill must be in (0, 1]; got {fill!r}")
    centres, radii = label_spots(polys)
    out = np.full(len(polys), shapely.MultiLineString(), dtype=object)
    heights = np.zeros(len(polys))
    for i, (t, r) in enumerate(zip(texts, radii.tolist(), strict=True)):
        if r <= 0 or not t:
            continue
        aspect = (_ADVANCE * len(t) - 1.0) / _HEIGHT  # width / height
        h = fill * 2.0 * r / math.hypot(1.0, aspect)
        if max_height is not None:
            h = min(h, float(max_height))
        heights[i] = h
        out[i] = text_lines(t, centres[i, 0], centres[i, 1], h)
    return out, centres, heights
