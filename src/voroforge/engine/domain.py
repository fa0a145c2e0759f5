"""The domain that cells are clipped to: a rectangle or any polygonal region with holes."""

from __future__ import annotations

import re
from dataclasses import dataclass

import numpy as np
import shapely

from ..config import DOMAIN_GEOS_EXP
from .inputs import unit_exponent


@dataclass(frozen=True)
class Domain:
    """A validated clipping domain.

    Attributes
    ----------
    geometry : shapely.Polygon or shapely.MultiPolygon
        The region (a box polygon for rectangles).
    bounds : tuple of 4 floats
        ``(xmin, ymin, xmax, ymax)``.
    is_rect : bool
        True when the region is exactly its bounding box (cells need no polygon clipping).
    """

    geometry: shapely.Geometry
    bounds: tuple[float, float, float, float]
    is_rect: bool

    @property
    def area(self) -> float:
        """Area of the region."""
        if self.is_rect:
            x0, y0, x1, y1 = self.bounds
            return (x1 - x0) * (y1 - y0)
        # GEOS's shoelace products overflow first: a square with a hole at 1e154 (area
        # 8.7e307) read inf; at unit size (power of two, exact) and scaled back
        e = _unit_exponent(shapely.get_coordinates(self.geometry))
        if not e:
            return float(shapely.area(self.geometry))
        with np.errstate(over="ignore"):
            return float(np.ldexp(shapely.area(self.scaled(-e).geometry), 2 * e))

    def scaled(self, k: int) -> Domain:
        """The image under multiplication by ``2**k`` (exact, barring over/underflow)."""
        if k == 0:
            return self
        b = np.ldexp(np.array(self.bounds, dtype=np.float64), k)
        if self.is_rect:
            return _rect(b)
        geom = shapely.transform(self.geometry, lambda xy: np.ldexp(xy, k))
        return Domain(geom, tuple(float(v) for v in b), False)


def shifted(dom: Domain, c) -> Domain:
    """The domain moved by ``-c`` (each coordinate minus ``c``, rounded once)."""
    c = np.asarray(c, dtype=np.float64)
    b = np.array(dom.bounds, dtype=np.float64) - np.r_[c, c]
    if dom.is_rect:
        return _rect(b)
    geom = shapely.transform(dom.geometry, lambda xy: xy - c)
    return Domain(geom, tuple(float(v) for v in b), False)


def _rect(bounds) -> Domain:
    x0, y0, x1, y1 = (float(v) for v in bounds)
    return Domain(shapely.box(x0, y0, x1, y1), (x0, y0, x1, y1), True)


def padded_bounds(sites: np.ndarray, pad: float = 0.1) -> tuple[float, float, float, float]:
    """Bounding box of ``sites`` grown by ``pad`` of its size on every side.

    A degenerate extent (one site, or sites on a vertical/horizontal line) is padded by
    ``pad`` of the larger side, or by ``pad * max(1, |coordinate|)`` when both sides are 0.
    A box past float64's range is clamped to it: sites spanning more than ~1.6e308 (whose
    extent, or padded sides, overflow) get a box with finite sides, at most the largest double
    (a site there lies on the box's side).
    """
    if len(sites) == 0:
        raise ValueError("boundary=None needs at least one site to define the domain's extent")
    lo = sites.min(axis=0)
    hi = sites.max(axis=0)
    top = float(np.finfo(np.float64).max)
    with np.errstate(over="ignore"):
        size = hi - lo
    if np.isfinite(size).all():
        big = float(size.max())
        if big == 0.0:
            big = max(1.0, float(np.abs(lo).max()))
        padx = pad * (size[0] if size[0] > 0 else big)
        pady = pad * (size[1] if size[1] > 0 else big)
    else:  # the extent overflows (sites past +-9e307 on both sides): pad by its halves
        half = hi * 0.5 - lo * 0.5
        padx, pady = (min(2.0 * (pad * float(h if h > 0 else half.max())), top) for h in half)
    with np.errstate(over="ignore"):
        box = [lo[0] - padx, lo[1] - pady, hi[0] + padx, hi[1] + pady]
    for k in (0, 1):  # a pad below half an ulp (subnormal sites, a line far out) rounds away
        if not box[k] < box[k + 2]:
            box[k], box[k + 2] = np.nextafter(lo[k], -np.inf), np.nextafter(hi[k], np.inf)
    return tuple(min(max(float(v), -top), top) for v in box)


def make_domain(boundary, sites: np.ndarray) -> Domain:
    """Validate ``boundary`` and return a :class:`Domain`.

    Parameters
    ----------
    boundary : None, (xmin, ymin, xmax, ymax) or shapely Polygon/MultiPolygon
        None means the sites' bounding box padded by 10%.
    sites : (n, 2) float64
        Used only when ``boundary`` is None.

    Raises
    ------
    ValueError
        For a malformed rectangle, an empty, invalid or non-polygonal geometry, naming why.
    """
    if boundary is None:
        return _rect(padded_bounds(sites))
    if isinstance(boundary, shapely.Geometry):
        return _from_geometry(boundary)
    try:
        vals = np.asarray(boundary, dtype=np.float64)
    except (TypeError, ValueError):
        raise ValueError(
            "boundary must be None, (xmin, ymin, xmax, ymax) or a shapely Polygon/MultiPolygon;"
            f" got {type(boundary).__name__}"
        ) from None
    if vals.shape != (4,):
        raise ValueError(
            f"boundary rectangle must be (xmin, ymin, xmax, ymax); got shape {vals.shape}"
        )
    if not np.isfinite(vals).all():
        raise ValueError(f"boundary rectangle has non-finite values: {vals.tolist()}")
    if not (vals[0] < vals[2] and vals[1] < vals[3]):
        raise ValueError(
            f"boundary rectangle needs xmin < xmax and ymin < ymax; got {vals.tolist()}"
        )
    return _rect(vals)


def _from_geometry(geom: shapely.Geometry) -> Domain:
    kind = shapely.get_type_id(geom)
    if kind not in (3, 6):  # Polygon, MultiPolygon
        raise ValueError(
            f"boundary geometry must be a Polygon or MultiPolygon; got {geom.geom_type}"
        )
    if geom.is_empty:
        raise ValueError("boundary geometry is empty")
    coords = shapely.get_coordinates(geom)
    if not np.isfinite(coords).all():
        raise ValueError("boundary geometry has non-finite coordinates")
    # GEOS's validity check squares coordinates: past ~1e150 it raised GEOSException
    # ("Segment vertex does not intersect ring") on a valid square with a hole; a
    # power-of-two scale is exact and keeps every relation, so check near unit size
    e = _unit_exponent(coords)
    check = geom if not e else shapely.transform(geom, lambda c: np.ldexp(c, -e))
    if not shapely.is_valid(check):
        reason = shapely.is_valid_reason(check)
        if check is not geom:  # the reason's point back in the user's frame
            reason = re.sub(
                r"\[([-+0-9.eE]+) ([-+0-9.eE]+)\]",
                lambda m: f"[{np.ldexp(float(m[1]), e):.17g} {np.ldexp(float(m[2]), e):.17g}]",
                reason,
            )
        raise ValueError(f"boundary geometry is invalid: {reason}{_shared_edge(check)}")
    area = shapely.area(check)  # in the scaled frame: the area of a polygon at 1e200 is inf
    if not area > 0.0:
        raise ValueError("boundary geometry has zero area")
    bounds = tuple(float(v) for v in shapely.bounds(geom))
    if kind == 3 and shapely.get_num_interior_rings(geom) == 0:
        # exactly the box: the ring's vertices are its four corners, all of them (a right
        # triangle with axis-aligned legs has corner vertices too, but only three)
        ring = shapely.get_coordinates(shapely.get_exterior_ring(geom))
        corners = {(x, y) for x in (bounds[0], bounds[2]) for y in (bounds[1], bounds[3])}
        if set(map(tuple, ring.tolist())) == corners:
            return Domain(geom, bounds, True)
    return Domain(geom, bounds, False)


def _unit_exponent(coords: np.ndarray) -> int:
    """0, or the power of two that brings coordinates past ``2**±DOMAIN_GEOS_EXP`` near 1."""
    return unit_exponent(float(np.abs(coords).max(initial=0.0)), DOMAIN_GEOS_EXP)


def _shared_edge(geom: shapely.Geometry) -> str:
    """What to add to the invalidity reason of a MultiPolygon whose parts share an edge.

    GEOS calls it a self-intersection; the parts are valid each and their interiors are
    disjoint, but their boundaries meet along a segment (parts touching at points are valid
    and accepted).
    """
    if shapely.get_type_id(geom) != 6:
        return ""
    parts = shapely.get_parts(geom)
    if not shapely.is_valid(parts).all():
        return ""
    tree = shapely.STRtree(parts)
    left, right = tree.query(parts, predicate="intersects")
    merge = (
        "; parts may touch only at points: merge them first, e.g."
        " shapely.union_all(shapely.get_parts(g)) or shapely.ops.unary_union)"
    )
    for a, b in zip(left.tolist(), right.tolist(), strict=True):
        if a >= b:
            continue
        if shapely.relate_pattern(parts[a], parts[b], "T********"):
            return f" (parts {a} and {b} of the MultiPolygon overlap{merge}"
        if shapely.relate_pattern(parts[a], parts[b], "F***1****"):
            return f" (parts {a} and {b} of the MultiPolygon share an edge{merge}"
    return ""
