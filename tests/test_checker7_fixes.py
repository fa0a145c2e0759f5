"""Inputs an independent checker found mishandled in the design layer and studio (session 40)."""

from __future__ import annotations

import json
import warnings
from pathlib import Path

import numpy as np
import pytest
import shapely

import voroforge as vf
from voroforge import config
from voroforge.design.build import build
from voroforge.design.populate import poisson

EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "laser-panel.toml"


@pytest.mark.parametrize(
    "key", ["cells.web", "cells.fillet", "seeds.radius", "fabrication.min_web"]
)
def test_studio_survives_a_huge_slider_value(key):
    # 1e308 was accepted, then every controls() (the page's state message) raised
    # OverflowError: the socket dropped and no page could connect until a restart
    pytest.importorskip("starlette")
    from voroforge.studio.session import Session

    s = Session(str(EXAMPLE))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        s.apply({"op": "set", "key": key, "value": 1e308})
        ctl = s.controls()
    json.dumps(ctl, allow_nan=False)  # finite: JSON has no Infinity
    for c in ctl:
        assert np.isfinite([c["min"], c["max"], c["step"]]).all(), c


def test_huge_margin_is_refused_without_overflow():
    pytest.importorskip("starlette")
    from voroforge.studio.session import Session

    s = Session(str(EXAMPLE))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        r = s.apply({"op": "set", "key": "boundary.margin", "value": 1e308})
    assert r.kind == "error" and "boundary.margin" in json.dumps(r.issues)


def test_poisson_radius_past_the_boundary_keeps_one_seed():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        a = poisson(shapely.box(0, 0, 10, 10), 1e308, seed=3)
        b = poisson(shapely.box(0, 0, 10, 10), 50.0, seed=3)
    assert len(a) == 1 and np.array_equal(a, b)


def _design(cells, product):
    return {
        "design": {"name": "o", "seed": 1},
        "boundary": {"shape": "rectangle", "width": 100, "height": 100},
        "seeds": {"method": "random", "count": 20},
        "cells": cells,
        "output": {"formats": ["geojson"], "geojson": product},
    }


@pytest.mark.parametrize(
    "cells, product",
    [({}, "cells"), ({"web": 2}, "cells"), ({"fillet": 2}, "cells"), ({"web": 2}, "openings"),
     ({"web": 2}, "frame")],
)  # fmt: skip
def test_design_geojson_follows_the_right_hand_rule(tmp_path, cells, product):
    # RFC 7946 3.1.6: exteriors counter-clockwise, holes clockwise (buffered cells and
    # openings were all clockwise)
    written = build(_design(cells, product), tmp_path)
    path = next(p for p in written if str(p).endswith(".geojson"))
    rings = 0
    for f in json.loads(Path(path).read_text())["features"]:
        g = f["geometry"]
        if not g:
            continue
        polys = [g["coordinates"]] if g["type"] == "Polygon" else g["coordinates"]
        for poly in polys:
            assert shapely.LinearRing(poly[0]).is_ccw
            assert not any(shapely.LinearRing(h).is_ccw for h in poly[1:])
            rings += 1
    assert rings > 0


def test_circle_segments_have_a_bound(tmp_path):
    from voroforge.design.boundary import circle
    from voroforge.design.designfile import DesignError

    d = {
        "design": {"name": "c"},
        "boundary": {"shape": "circle", "radius": 10, "segments": 10**6},
        "seeds": {"method": "random", "count": 10},
    }
    with pytest.raises((DesignError, ValueError), match="boundary.segments"):
        build(d, tmp_path)
    with pytest.raises(ValueError, match="segments"):
        circle(1.0, segments=config.BOUNDARY_MAX_SEGMENTS + 1)
    assert len(circle(1.0, segments=config.BOUNDARY_MAX_SEGMENTS).exterior.coords) > 60000


def _issue_keys(text: str, tmp_path) -> tuple[list[str], list[int | None]]:
    from voroforge.design.designfile import DesignError, load

    f = tmp_path / "d.toml"
    f.write_text(text)
    with pytest.raises(DesignError) as info:
        load(f)
    return [i.key for i in info.value.issues], [i.line for i in info.value.issues]


def test_a_bad_value_does_not_hide_the_sections_cross_key_checks(tmp_path):
    # F10: pydantic skips a section's checks between keys once one key of it is bad
    keys, lines = _issue_keys(
        '[design]\nname = "x"\n[boundary]\nshape = "circle"\nradius = -2\n'
        '[seeds]\nmethod = "random"\ncount = 3\n[output]\nformats = ["gif"]\npng_size = -5\n',
        tmp_path,
    )
    assert keys == ["boundary.radius", "output.gif", "output.png_size"]
    assert lines == sorted(lines)


def test_the_second_look_adds_nothing_that_follows_from_the_bad_value(tmp_path):
    # radius left out must not also read "shape = 'circle' needs radius"; a bad method or
    # shape picks the section's rules, so nothing more is said about that section
    keys, _ = _issue_keys(
        '[boundary]\nshape = "blob"\nradius = 3\n[seeds]\nmethod = "bogus"\n', tmp_path
    )
    assert keys == ["boundary.shape", "seeds.method"]
    keys, _ = _issue_keys(
        '[boundary]\nshape = "circle"\nradius = -1\n[seeds]\nmethod = "random"\ncount = 0\n',
        tmp_path,
    )
    assert keys == ["boundary.radius", "seeds.count"]


@pytest.mark.parametrize("algorithm", ["delaunay", "fortune", "halfplane"])
def test_the_build_keeps_each_cells_reach_before_the_polygon_clip(algorithm):
    # scale's certificate on polygon domains needs the convex ring's radius (checker7 R1);
    # the build keeps it, so scale no longer builds the box diagram a second time
    from shapely.geometry import MultiPolygon, Point, box

    from voroforge.engine.diagram import convex_reach
    from voroforge.scale.tasks import radii

    rng = np.random.default_rng(3)
    holed = box(0, 0, 10, 10).difference(Point(5, 5).buffer(2))
    gap = MultiPolygon([box(0, 0, 4, 10), box(6, 0, 10, 10)])
    for dom, scale in ((holed, 1.0), (gap, 1.0), (gap, 1e-120), (holed, 1e120)):
        from shapely import affinity

        dom = affinity.scale(dom, scale, scale, origin=(0, 0))
        p = rng.random((600, 2)) * 10 * scale
        p = np.vstack([p[shapely.contains_xy(dom, p[:, 0], p[:, 1])], p[:3]])  # + duplicates
        d = vf.voronoi(p, dom, algorithm=algorithm)
        ref = radii(vf.voronoi(p, tuple(dom.bounds), algorithm=algorithm), p)
        assert np.array_equal(convex_reach(d), ref)
        # the ring reaches past the clipped cell somewhere (else the test shows nothing)
        assert (convex_reach(d) > radii(d, p) * (1 + 1e-9)).any()
    assert convex_reach(vf.voronoi(rng.random((50, 2)), (0, 0, 1, 1))) is None


@pytest.mark.parametrize("e", [660, 990, -990])
def test_polygon_domains_with_holes_at_extreme_scales(e):
    # GEOS's validity check raised GEOSException ("Segment vertex does not intersect ring")
    # on a valid square with a round hole scaled past ~1e150; it is checked scaled now
    from shapely import affinity
    from shapely.geometry import Point, box

    dom = box(0, 0, 10, 10).difference(Point(5, 5).buffer(2))
    q = np.random.default_rng(1).random((300, 2)) * 10
    q = q[shapely.contains_xy(dom, q[:, 0], q[:, 1])]
    s = 2.0**e
    d = vf.voronoi(q * s, affinity.scale(dom, s, s, origin=(0, 0)))
    cells = [shapely.transform(c, lambda c: c / s) for c in d.cells]  # exact: a power of two
    assert all(c.is_valid for c in cells)
    assert sum(c.area for c in cells) == pytest.approx(dom.area, rel=1e-12)
    assert all(shapely.intersects_xy(c, x, y) for c, (x, y) in zip(cells, q, strict=True))
    bowtie = shapely.Polygon([(0, 0), (1, 1), (1, 0), (0, 1)])
    with pytest.raises(ValueError, match=r"invalid: Self-intersection") as info:
        vf.voronoi(q[:1] * 0.05 * s, affinity.scale(bowtie, 10 * s, 10 * s, origin=(0, 0)))
    # the crossing named in the user's frame (5 s, 5 s), not in the frame it was checked in
    x, y = (float(v) for v in str(info.value).split("[")[1].rstrip("]").split())
    assert x == pytest.approx(5 * s, rel=1e-12) and y == pytest.approx(5 * s, rel=1e-12)


@pytest.mark.parametrize("e", [490, 505, -490, -500])
def test_power_diagrams_are_scaled_exactly_at_extreme_magnitudes(e):
    # squared distances near float64's limits: at 2**490 the cells' bits moved and areas
    # overflowed; they are built scaled by a power of two now, weights by its square
    from shapely import affinity
    from shapely.geometry import Point, box

    rng = np.random.default_rng(0)
    p, w = rng.random((30, 2)), rng.random(30) * 0.02
    s = 2.0**e
    for dom in ((0, 0, 1, 1), box(0, 0, 1, 1).difference(Point(0.5, 0.5).buffer(0.2))):
        ref = vf.power(p, w, dom)
        big = (0, 0, s, s) if isinstance(dom, tuple) else affinity.scale(dom, s, s, origin=(0, 0))
        d = vf.power(p * s, w * s * s, big)
        for c, r in zip(d.cells, ref.cells, strict=True):
            assert np.array_equal(
                np.ldexp(shapely.get_coordinates(c), -e), shapely.get_coordinates(r)
            )
        assert np.array_equal(np.ldexp(np.asarray(d.areas), -2 * e), np.asarray(ref.areas))


@pytest.mark.parametrize("s", [1e150, 1e-150, 1e154, 1e-154])
def test_power_fit_at_extreme_scales(s):
    # at 1e-150 Newton stalled after one step and the polygon clip raised GEOSException; at
    # 1e154 a polygon's area overflowed in GEOS and the fit returned unfitted cells
    from shapely import affinity
    from shapely.geometry import MultiPolygon, Point, box

    rng = np.random.default_rng(0)
    holed = box(0, 0, 1, 1).difference(Point(0.5, 0.5).buffer(0.2))
    gap = MultiPolygon([box(0, 0, 0.4, 1), box(0.6, 0, 1, 1)])
    for dom in (holed, gap):
        p = rng.random((40, 2))
        p = p[shapely.contains_xy(dom, p[:, 0], p[:, 1])]
        t = rng.random(len(p)) + 0.5
        t *= dom.area / t.sum()
        d = vf.power_fit(p * s, t * s * s, affinity.scale(dom, s, s, origin=(0, 0)))
        assert np.abs(np.asarray(d.areas) / (t * s * s) - 1).max() <= 1e-6
