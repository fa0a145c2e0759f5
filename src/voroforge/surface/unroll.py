"""Unroll panels into flat, labelled parts laid out on sheets, and write them as DXF/SVG.

Each panel's exterior is unfolded as a fan from one corner (the sharpest): every triangle of
the fan keeps its three 3D edge lengths, so every boundary edge of the flat part has its 3D
length (to rounding) even when the panel is slightly bent; for a planar panel the fan is its
plane, rigidly. Each hole (an opening) is unfolded the same way, as its own fan, so its edges
keep their 3D lengths too, and placed by the least-squares rigid map onto where the panel's
best-fit plane puts it relative to the exterior.
Parts are turned to their smallest bounding rectangle and packed in shelves (rows of
bounding boxes a gap apart, so no two parts overlap), sheet after sheet; each part carries
its panel's label.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import shapely

from ..io.atomic import write_atomically

__all__ = ["CutSheets", "Part", "UnrollWarning", "flatten", "unroll"]


class UnrollWarning(UserWarning):
    """Panels whose unfolded outline crosses itself (bent far off their plane)."""


def _fan(P: np.ndarray, normal: np.ndarray) -> np.ndarray:
    """Ring ``P (m, 3)`` unfolded as a fan from ``P[0]``: every spoke and edge length kept."""
    m = len(P)
    out = np.zeros((m, 2))
    out[1] = (np.linalg.norm(P[1] - P[0]), 0.0)
    for k in range(2, m):
        a = np.linalg.norm(P[k] - P[0])
        b = np.linalg.norm(P[k] - P[k - 1])
        base = out[k - 1] - out[0]
        d = math.hypot(*base)
        u = base / d
        x = (a * a - b * b + d * d) / (2 * d)
        y = math.sqrt(max(a * a - x * x, 0.0))
        side = np.cross(P[k - 1] - P[0], P[k] - P[0]) @ normal
        if side < 0:
            y = -y
        out[k] = out[0] + x * u + y * np.array([-u[1], u[0]])
    return out


def _apex(P: np.ndarray) -> int:
    """The ring's sharpest corner (smallest interior angle): a good apex for the fan."""
    a = np.roll(P, 1, axis=0) - P
    b = np.roll(P, -1, axis=0) - P
    cos = np.einsum("ij,ij->i", a, b) / (
        np.linalg.norm(a, axis=1) * np.linalg.norm(b, axis=1) + 1e-300
    )
    return int(np.argmax(cos))


def flatten(panels, p: int) -> list[np.ndarray]:
    """Panel ``p`` flattened: its rings as ``(k, 2)`` arrays (exterior counter-clockwise).

    Every ring's edge lengths equal the 3D ones to rounding (see the module docstring).
    """
    rings = panels.polygon(p)
    ext = rings[0]
    rel = ext - ext[0]  # about a ring vertex: far from the origin no offset^2 cancels
    vec = 0.5 * np.cross(rel, np.roll(rel, -1, axis=0)).sum(axis=0)
    normal = vec / max(np.linalg.norm(vec), 1e-300)
    s = _apex(ext)
    order = np.roll(np.arange(len(ext)), -s)
    flat_ext = np.zeros((len(ext), 2))
    flat_ext[order] = _fan(ext[order], normal)
    out = [flat_ext]
    if len(rings) > 1:
        allp = np.concatenate(rings)
        c = allp.mean(axis=0)
        _, _, wt = np.linalg.svd(allp - c, full_matrices=False)
        e1, e2 = wt[0], wt[1]
        if np.cross(e1, e2) @ normal < 0:
            e2 = -e2
        proj = [np.stack([(r - c) @ e1, (r - c) @ e2], axis=1) for r in rings]
        # where each hole goes: the projection's rigid map onto the unfolded exterior; the
        # hole itself unfolded as a fan (its edge lengths kept) and fitted rigidly there
        spot = _rigid(proj[0], flat_ext)
        for h3, h2 in zip(rings[1:], proj[1:], strict=True):
            order = np.roll(np.arange(len(h3)), -_apex(h3))
            fan = np.zeros((len(h3), 2))
            fan[order] = _fan(h3[order], normal)
            out.append(_rigid(fan, spot(h2))(fan))
    return out


def _rigid(X: np.ndarray, Y: np.ndarray):
    """The rotation and shift taking points ``X (k, 2)`` nearest to ``Y`` (Kabsch)."""
    xm, ym = X.mean(axis=0), Y.mean(axis=0)
    u, _, vt = np.linalg.svd((X - xm).T @ (Y - ym))
    r = u @ vt
    if np.linalg.det(r) < 0:
        u[:, -1] = -u[:, -1]
        r = u @ vt
    return lambda P: (P - xm) @ r + ym


@dataclass(frozen=True)
class Part:
    """One flat part on a sheet."""

    panel: int  #: position in the Panels
    label: str
    sheet: int
    rings: tuple  #: (k, 2) arrays in sheet coordinates, exterior first
    label_at: tuple[float, float]
    label_height: float

    @property
    def polygon(self):
        """The part as a shapely Polygon."""
        return shapely.Polygon(self.rings[0], list(self.rings[1:]))


@dataclass(frozen=True)
class CutSheets:
    """Flat parts laid out on sheets of ``size``; ``parts`` in panel order."""

    parts: tuple
    size: tuple[float, float]
    count: int
    gap: float

    def sheet(self, k: int) -> list[Part]:
        """The parts on sheet ``k``."""
        return [p for p in self.parts if p.sheet == k]

    def _offset(self, k: int) -> float:
        return k * (self.size[0] + 2 * self.gap)

    def write_dxf(self, path, *, layer: str = "CUT", label_layer: str = "LABELS", units="mm"):
        """Sheets side by side in one DXF R2000: closed outlines on ``layer``, labels as TEXT.

        Written without ezdxf (:class:`voroforge.io.dxf.R2000`, the bytes ezdxf writes with
        its fixed test metadata) unless a name needs ezdxf's escapes. Returns the path
        (written atomically).
        """
        from ..io.dxf import R2000, UNITS

        if units not in UNITS:
            raise ValueError(f"units must be one of {sorted(UNITS)}; got {units!r}")
        cut, lab = layer.upper(), label_layer.upper()
        names = [cut, lab, *(p.label for p in self.parts)]
        if cut == lab or not all(n.isascii() and "\n" not in n for n in names):
            return self._write_dxf_ezdxf(path, cut, lab, units)
        if {cut, lab} & {"0", "DEFPOINTS"}:
            return self._write_dxf_ezdxf(path, cut, lab, units)
        doc = R2000()
        doc.layer(cut, 1)
        doc.layer(lab, 3)
        for part in self.parts:
            dx = self._offset(part.sheet)
            for ring in part.rings:
                rows = [(float(x + dx), float(y), 0.0) for x, y in ring]
                doc.lwpolyline(cut, rows, closed=True)
            x, y = part.label_at
            doc.text(lab, part.label, float(x + dx), float(y), float(part.label_height))
        text = doc.document(units)
        return _atomic(path, lambda f: f.write(text), text=True)

    def _write_dxf_ezdxf(self, path, cut: str, lab: str, units: str):
        import ezdxf

        from ..io.dxf import UNITS

        doc = ezdxf.new("R2000")
        doc.header["$INSUNITS"] = UNITS[units]
        doc.header["$MEASUREMENT"] = 0 if units in ("in", "ft") else 1
        doc.layers.add(cut, color=1)
        doc.layers.add(lab, color=3)
        msp = doc.modelspace()
        for part in self.parts:
            dx = self._offset(part.sheet)
            for ring in part.rings:
                msp.add_lwpolyline(
                    [(float(x + dx), float(y)) for x, y in ring],
                    close=True,
                    dxfattribs={"layer": cut},
                )
            x, y = part.label_at
            t = msp.add_text(
                part.label,
                height=float(part.label_height),
                dxfattribs={"layer": lab},
            )
            t.set_placement(
                (float(x + dx), float(y)), align=ezdxf.enums.TextEntityAlignment.MIDDLE_CENTER
            )
        return _atomic(path, lambda f: doc.write(f), text=True)

    def write_svg(self, path, *, layer: str = "CUT", label_layer: str = "LABELS", units="mm"):
        """Sheets side by side in one SVG (Inkscape layers ``layer`` and ``label_layer``)."""
        w = self._offset(self.count) - 2 * self.gap
        h = self.size[1]
        cut, text = [], []
        for part in self.parts:
            dx = self._offset(part.sheet)
            for ring in part.rings:
                d = " ".join(f"{x + dx:.6f},{h - y:.6f}" for x, y in ring)
                cut.append(f'<path d="M {d} Z"/>')
            x, y = part.label_at
            text.append(
                f'<text x="{x + dx:.6f}" y="{h - y:.6f}" font-size="{part.label_height:.6f}" '
                f'text-anchor="middle" dominant-baseline="middle">{part.label}</text>'
            )
        stroke = 0.01 if units == "mm" else 0.001
        svg = (
            '<?xml version="1.0" encoding="UTF-8"?>\n'
            '<svg xmlns="http://www.w3.org/2000/svg" '
            'xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape" '
            f'width="{w:.6f}{units}" height="{h:.6f}{units}" viewBox="0 0 {w:.6f} {h:.6f}">\n'
            f'<g id="{layer.upper()}" inkscape:groupmode="layer" inkscape:label="{layer.upper()}" '
            f'fill="none" stroke="#ff0000" stroke-width="{stroke}">\n' + "\n".join(cut) + "\n</g>\n"
            f'<g id="{label_layer.upper()}" inkscape:groupmode="layer" '
            f'inkscape:label="{label_layer.upper()}" fill="#00a000" font-family="sans-serif">\n'
            + "\n".join(text)
            + "\n</g>\n</svg>\n"
        )
        return _atomic(path, lambda f: f.write(svg), text=True)


def _atomic(path, write, *, text: bool) -> Path:
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)

    def into(tmp: str) -> None:
        with open(tmp, "w" if text else "wb", encoding="utf-8" if text else None) as f:
            write(f)

    return write_atomically(path, into)  # the mode of every other output, not mkstemp's 0600


def _upright(rings: list[np.ndarray]) -> list[np.ndarray]:
    """Rings turned so the exterior's smallest bounding rectangle lies wide and flat.

    The rectangle ends up axis-aligned with its long side horizontal, its corner at the origin.
    """
    poly = shapely.Polygon(rings[0])
    rect = np.asarray(shapely.minimum_rotated_rectangle(poly).exterior.coords)[:4]
    e0, e1 = rect[1] - rect[0], rect[2] - rect[1]
    edge = e0 if np.linalg.norm(e0) >= np.linalg.norm(e1) else e1
    ang = -math.atan2(edge[1], edge[0])
    c, s = math.cos(ang), math.sin(ang)
    rot = np.array([[c, s], [-s, c]])
    out = [r @ rot for r in rings]
    lo = out[0].min(axis=0)
    return [r - lo for r in out]


def unroll(
    panels,
    *,
    sheet: tuple[float, float] | None = None,
    gap: float | None = None,
    labels=None,
) -> CutSheets:
    """Flatten every panel and pack the parts on sheets.

    Parameters
    ----------
    panels : Panels
    sheet : (width, height), optional
        Sheet size (model units). Default: one sheet about twice as wide as tall that
        holds everything.
    gap : float, optional
        Space between parts and to the sheet's edge (default 4% of the median part size).
    labels : sequence of str, optional
        One label per panel (default the panel ids).

    Returns
    -------
    CutSheets
    """
    n = len(panels)
    if n == 0:
        raise ValueError("nothing to unroll: no panels")
    names = [str(i) for i in panels.ids] if labels is None else [str(s) for s in labels]
    if len(names) != n:
        raise ValueError(f"labels: need {n}, got {len(names)}")
    flat = [_upright(flatten(panels, p)) for p in range(n)]
    dims = np.array([r[0].max(axis=0) for r in flat])
    g = float(np.median(dims.max(axis=1))) * 0.04 if gap is None else float(gap)
    if not g >= 0:
        raise ValueError(f"gap must be >= 0; got {gap!r}")
    if sheet is None:
        total = float(((dims[:, 0] + g) * (dims[:, 1] + g)).sum())
        width = max(float(dims[:, 0].max()) + 2 * g, math.sqrt(2.4 * total))
        height = math.inf
    else:
        width, height = (float(x) for x in sheet)
        if not (width > 0 and height > 0):
            raise ValueError(f"sheet must be (width, height) > 0; got {sheet!r}")
    too_big = (dims[:, 0] + 2 * g > width) | (dims[:, 1] + 2 * g > height)
    if too_big.any():
        p = int(np.flatnonzero(too_big)[0])
        raise ValueError(
            f"panel {names[p]} ({dims[p, 0]:.4g} x {dims[p, 1]:.4g}) does not fit the sheet "
            f"{width:.4g} x {height:.4g} with gap {g:.4g}"
        )
    order = np.lexsort((-dims[:, 0], -dims[:, 1]))  # tallest first: tight shelves
    placed: dict[int, tuple[int, float, float]] = {}
    k, x, y, row = 0, g, g, 0.0
    for p in order:
        w, h = dims[p]
        if x + w + g > width:  # next shelf
            x, y, row = g, y + row + g, 0.0
        if y + h + g > height:  # next sheet
            k, x, y, row = k + 1, g, g, 0.0
        placed[int(p)] = (k, x, y)
        x += w + g
        row = max(row, h)
    count = k + 1
    if sheet is None:
        height = y + row + g
    parts = []
    for p in range(n):
        k, x, y = placed[p]
        rings = tuple(r + (x, y) for r in flat[p])
        poly = shapely.Polygon(rings[0], list(rings[1:]))
        spot = poly.point_on_surface() if len(rings) > 1 else shapely.Point(rings[0].mean(axis=0))
        if not poly.contains(spot):
            spot = poly.point_on_surface()
        size = math.sqrt(max(poly.area, 0.0))
        parts.append(Part(p, names[p], k, rings, (spot.x, spot.y), 0.18 * size))
    crossed = [p for p in range(n) if not parts[p].polygon.is_valid]
    if crossed:  # the edge lengths are kept, but such a part cannot be cut
        import warnings

        from .panels import listed

        shown = listed(names[p] for p in crossed)
        warnings.warn(
            f"unroll: {len(crossed)} of {n} panels ({shown}) unfold into outlines that cross "
            "themselves (bent far off their plane): planarize first, or use more cells",
            UnrollWarning,
            stacklevel=2,
        )
    return CutSheets(tuple(parts), (width, height), count, g)
