"""Property tests of the design layer's curve flattening and fields (hypothesis, few examples)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from voroforge.design import attractors as at
from voroforge.io.readers.dxf import bulge_polyline
from voroforge.io.readers.svg import svg_arc

coord = st.floats(-100, 100, allow_nan=False)


def _circle_centre(a, b, c):
    """Circumcentre of three points."""
    d = 2 * (a[0] * (b[1] - c[1]) + b[0] * (c[1] - a[1]) + c[0] * (a[1] - b[1]))
    ux = ((a @ a) * (b[1] - c[1]) + (b @ b) * (c[1] - a[1]) + (c @ c) * (a[1] - b[1])) / d
    uy = ((a @ a) * (c[0] - b[0]) + (b @ b) * (a[0] - c[0]) + (c @ c) * (b[0] - a[0])) / d
    return np.array([ux, uy])


@settings(max_examples=25)
@given(
    x0=coord, y0=coord, x1=coord, y1=coord,
    grow=st.floats(1.05, 4.0), large=st.booleans(), sweep=st.booleans(),
    tol=st.sampled_from([1e-3, 1e-2, 0.1]),
)  # fmt: skip
def test_svg_circular_arc_lies_on_its_circle(x0, y0, x1, y1, grow, large, sweep, tol):
    p0, p1 = np.array([x0, y0]), np.array([x1, y1])
    chord = np.linalg.norm(p1 - p0)
    assume(chord > 1e-3)
    r = grow * chord / 2
    # an arc within ``tol`` of its chord is flattened to that one segment (no circle to
    # check): only arcs that bulge out by more than the tolerance
    half = math.sqrt(max(r * r - chord * chord / 4, 0.0))
    assume((r + half if large else r - half) > 2 * tol)
    pts = np.vstack((p0, svg_arc(p0, r, r, 0.0, int(large), int(sweep), p1, tol)))
    assert np.array_equal(pts[-1], p1)
    c = _circle_centre(pts[0], pts[len(pts) // 2], pts[-1])
    dist = np.linalg.norm(pts - c, axis=1)
    assert dist == pytest.approx(r, rel=1e-7, abs=1e-9)
    # chords within the tolerance of the arc
    mids = (pts[1:] + pts[:-1]) / 2
    assert (r - np.linalg.norm(mids - c, axis=1)).max() <= tol * (1 + 1e-9)
    # the large-arc flag picks the arc longer than half the circle
    length = np.linalg.norm(np.diff(pts, axis=0), axis=1).sum()
    assert (length > math.pi * r * (1 - 1e-3)) == bool(large)
    # sweep flag 1: positive angle direction in SVG coordinates (counter-clockwise here)
    a0 = np.arctan2(*(pts[0] - c)[::-1])
    a1 = np.arctan2(*(pts[1] - c)[::-1])
    turn = (a1 - a0 + np.pi) % (2 * np.pi) - np.pi
    assert (turn > 0) == bool(sweep)


@settings(max_examples=25)
@given(
    x0=coord, y0=coord, x1=coord, y1=coord,
    bulge=st.floats(-4, 4).filter(lambda b: abs(b) > 1e-3),
)  # fmt: skip
def test_dxf_bulge_arc_has_the_included_angle(x0, y0, x1, y1, bulge):
    a, b = np.array([x0, y0]), np.array([x1, y1])
    chord = np.linalg.norm(b - a)
    assume(chord > 1e-2)
    tol = 1e-3
    pts = bulge_polyline(np.array([a, b]), np.array([bulge, 0.0]), False, tol)
    assert np.array_equal(pts[0], a) and np.array_equal(pts[-1], b)
    theta = 4 * math.atan(bulge)
    r = chord / (2 * abs(math.sin(theta / 2)))
    if len(pts) == 2:
        # the chord alone: allowed only when the arc's sagitta is within the tolerance
        assert r * (1 - math.cos(theta / 2)) <= tol * (1 + 1e-9)
        return
    c = _circle_centre(pts[0], pts[len(pts) // 2], pts[-1])
    assert np.linalg.norm(pts - c, axis=1) == pytest.approx(r, rel=1e-7)
    length = np.linalg.norm(np.diff(pts, axis=0), axis=1).sum()
    assert length <= r * abs(theta) * (1 + 1e-12)
    # chords of sagitta <= tol are shorter than their arcs by a factor >= 1 - tol / (3 r)
    assert length >= r * abs(theta) - abs(theta) * tol / 2
    # positive bulge: counter-clockwise, so the arc lies to the right of the chord a -> b
    u, w = b - a, pts[len(pts) // 2] - a
    side = u[0] * w[1] - u[1] * w[0]
    assert (side < 0) == (bulge > 0)


@settings(max_examples=20)
@given(
    radius=st.floats(0.5, 50),
    strength=st.floats(0, 2),
    kind=st.sampled_from(at.FALLOFFS),
    power=st.floats(0.5, 4),
    d=st.lists(st.floats(0, 100), min_size=2, max_size=20),
)
def test_point_attractor_profile(radius, strength, kind, power, d):
    a = at.PointAttractor([[0.0, 0.0]], radius=radius, strength=strength, falloff=kind, power=power)
    dist = np.sort(np.asarray(d))
    v = a(np.column_stack((dist, np.zeros_like(dist))))
    assert ((v >= 0) & (v <= strength)).all()
    assert (np.diff(v) <= 1e-15).all()
    assert (v[dist >= radius] == 0).all()
    assert a(np.zeros((1, 2)))[0] == strength
