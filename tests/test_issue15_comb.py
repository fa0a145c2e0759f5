"""Issue 15: a polygon outline that meets every cell (a comb) made the diagram quadratic.

Every test against the whole domain (GEOS's rectangle clip, its prepared point location,
the boundary query) read all its vertices once per cell. ``engine.pieces`` now reads only
the boundary near the cell: the rectangle clip reads each ring with its far chunks replaced
by detours (:func:`voroforge.engine.pieces._detoured`), points are located in the domain
cut near them, and whether a geometry meets the boundary is asked of chunks of it.

Checks against independent references: the clip of the whole domain (the construction the
pieces replace, kept here as the slow reference) on random rectangles of many sizes over
adversarial domains, bit for bit; GEOS's prepared point location and boundary predicate on
the whole domain; and a comb diagram's cells against shapely's intersection of the
rectangle diagram's cells with the comb.
"""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from shapely import affinity

import voroforge as vf
from voroforge.engine import pieces as pieces_module
from voroforge.engine.domain import Domain
from voroforge.engine.pieces import PIECE_SMALL, Pieces

from catalogue import comb_outline, holed_square, saw_outline


def _domains():
    comb = comb_outline(80)
    hole_teeth = shapely.Polygon(
        comb.exterior.coords,
        [shapely.box(i + 0.2, 300, i + 0.4, 700).exterior.coords for i in range(80)],
    )
    return {
        "comb": comb,
        "comb_reversed": comb.reverse(),
        "comb_far": affinity.translate(comb, 3e13, 7e14),
        "comb_rotated": affinity.rotate(comb, 33, origin=(0, 0)),
        "comb_holes": hole_teeth,
        "saw": saw_outline(200),
        "holed": holed_square(12),
        "multi": shapely.MultiPolygon(
            [comb_outline(40), affinity.translate(comb_outline(40).reverse(), 0, 1100)]
        ),
    }


def _pieces(geom, boxes):
    """Pieces of ``geom`` for cells whose boxes are ``boxes`` (k, 4)."""
    closed = np.concatenate(
        [[(b[0], b[1]), (b[2], b[1]), (b[2], b[3]), (b[0], b[3]), (b[0], b[1])] for b in boxes]
    ).astype(np.float64)
    offsets = np.arange(0, 5 * len(boxes) + 1, 5)
    dom = Domain(geom, tuple(shapely.bounds(geom)), False)
    got = Pieces(dom, closed, offsets, np.arange(len(boxes)), len(boxes))
    got.local = True  # (the chunks whatever the rings' lengths)
    return got


def _random_boxes(geom, count, seed):
    """Boxes from 1e-6 of the domain's size to the whole of it, anywhere over its box."""
    rng = np.random.default_rng(seed)
    x0, y0, x1, y1 = shapely.bounds(geom)
    size = max(x1 - x0, y1 - y0) * 10.0 ** rng.uniform(-6, 0, count)
    c = rng.uniform([x0, y0], [x1, y1], (count, 2))
    half = size[:, None] * rng.uniform(0.05, 0.5, (count, 2))
    lo, hi = c - half, c + half
    ok = (hi > lo).all(axis=1)  # (far out, a tiny box can round to a point)
    return np.hstack((lo, hi))[ok]


@pytest.mark.parametrize("name", list(_domains()))
def test_pieces_are_the_whole_domain_clipped(name):
    geom = _domains()[name]
    assert shapely.is_valid(geom)
    assert shapely.get_num_coordinates(geom) > PIECE_SMALL
    boxes = _random_boxes(geom, 300, seed=len(name))
    pieces = _pieces(geom, boxes)
    for b in boxes:
        rect = pieces._grown(*b)
        ref = shapely.clip_by_rect(geom, *rect)  # the slow reference: the whole domain
        if not shapely.is_valid(ref):
            ref = shapely.intersection(geom, shapely.box(*rect))
        got = pieces.around(*b)
        assert shapely.to_wkb(got) == shapely.to_wkb(ref), (name, rect)


@pytest.mark.parametrize("name", list(_domains()))
def test_points_located_as_the_whole_domain(name, monkeypatch):
    monkeypatch.setattr(pieces_module, "PIECE_RAY_SPAN", 0)  # every point located locally
    geom = _domains()[name]
    rng = np.random.default_rng(7)
    boxes = _random_boxes(geom, 300, seed=3 + len(name))
    # points anywhere in each box, and on the boundary: vertices and points an ulp off edges
    xy = rng.uniform(boxes[:, :2], boxes[:, 2:])
    ring = shapely.get_coordinates(shapely.get_exterior_ring(shapely.get_parts(geom)[0]))
    pick = rng.integers(0, len(ring) - 1, 200)
    t = rng.random((200, 1))
    on = ring[pick] + t * (ring[pick + 1] - ring[pick])
    on = np.concatenate((on, np.nextafter(on, on + 1.0), ring[pick]))
    b_on = np.hstack((on - 0.01, on + 0.01))
    xy = np.concatenate((xy, on))
    pieces = _pieces(geom, np.concatenate((boxes, b_on)))
    got = pieces.holds(xy)
    prepared = shapely.from_wkb(shapely.to_wkb(geom))
    shapely.prepare(prepared)
    assert (got == shapely.intersects_xy(prepared, xy[:, 0], xy[:, 1])).all()


@pytest.mark.parametrize("name", ["comb", "holed", "multi"])
def test_meets_boundary_as_the_whole_boundary(name):
    geom = _domains()[name]
    boxes = _random_boxes(geom, 400, seed=11)
    pieces = _pieces(geom, boxes)
    polys = shapely.box(boxes[:, 0], boxes[:, 1], boxes[:, 2], boxes[:, 3])
    lines = shapely.linestrings(boxes.reshape(-1, 2, 2))
    for g in (polys, lines):
        ref = shapely.intersects(shapely.boundary(geom), g)
        assert (pieces.meets_boundary(g) == ref).all()


@pytest.mark.parametrize(
    "geom", [comb_outline(150), affinity.translate(comb_outline(150).reverse(), 1e13, 0)]
)
def test_comb_cells_are_the_box_cells_cut(geom, monkeypatch):
    monkeypatch.setattr(pieces_module, "PIECE_RAY_SPAN", 0)  # every point located locally
    monkeypatch.setattr(pieces_module, "PIECE_BIG_RING", 0)  # the chunks on every domain
    x0, y0, x1, y1 = geom.bounds
    p = np.random.default_rng(5).random((600, 2)) * [x1 - x0, y1 - y0] + [x0, y0]
    cut = vf.voronoi(p, geom).cells
    whole = vf.voronoi(p, (x0, y0, x1, y1)).cells
    ref = shapely.intersection(whole, geom)
    scale = (x1 - x0) * (y1 - y0) * 1e-12
    assert np.all(shapely.area(shapely.symmetric_difference(cut, ref)) <= scale)
    assert np.all(shapely.is_valid(cut))
    # a site in the domain is in its own cell, one outside it has no cell there
    inside = shapely.intersects_xy(geom, p[:, 0], p[:, 1])
    assert shapely.intersects_xy(cut[inside], p[inside, 0], p[inside, 1]).all()
    assert np.isclose(shapely.area(cut).sum(), geom.area, rtol=1e-12)
