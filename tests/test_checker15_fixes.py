"""checker15 F6, F5, F2: callable densities stay in the cells, nested edges once, power_fit note.

F6: ``vf.lloyd``'s callable density was integrated on a signed fan of each ring, sampling
it in holes and past concave edges. F5: ``cellops.explode`` kept a parent's edge and its
children's pieces of it (T-junctions) as different segments. F2: ``power_fit``'s rounding
note took a thin strip's width as the square root of its area.
"""

from __future__ import annotations

import re

import numpy as np
import pytest
import shapely
from shapely.geometry import Polygon, box

import voroforge as vf
from voroforge.design import boundary as bd
from voroforge.design import cellops as co
from voroforge.design import recursive as rc
from voroforge.engine import capacity
from voroforge.engine.diagram import buffers
from voroforge.engine.integrate import Integrator

FRAME = Polygon(box(0, 0, 1, 1).exterior.coords, [box(0.3, 0.3, 0.7, 0.7).exterior.coords[::-1]])
C_SHAPE = [(0, 0), (1, 0), (1, 0.2), (0.2, 0.2), (0.2, 0.8), (1, 0.8), (1, 1), (0, 1)]


def _in_hole(x, y):
    return (np.abs(x - 0.5) < 0.2) & (np.abs(y - 0.5) < 0.2)


def _poly(x, y):  # degree 3: Radon's rule is exact on any triangulation of the cell
    return 1.0 + x * x * y + 0.5 * y**3


def test_density_inside_a_hole_is_never_sampled():
    pts = np.random.default_rng(0).random((12, 2))
    uniform = vf.lloyd(pts, FRAME, iterations=1)
    for inside in (1000.0, np.nan):  # NaN only in the hole was refused
        got = vf.lloyd(
            pts,
            FRAME,
            iterations=1,
            density=lambda x, y, v=inside: np.where(_in_hole(x, y), v, 1.0),
        )
        np.testing.assert_allclose(got.points, uniform.points, rtol=0, atol=1e-13)
        assert got.energy[0] == pytest.approx(uniform.energy[0], rel=1e-12)


@pytest.mark.parametrize("first", range(4))
def test_density_outside_a_concave_outline_is_never_sampled(first):
    ring = np.roll(np.asarray(C_SHAPE, dtype=float), -first, axis=0)
    dom = shapely.Polygon(ring)
    sites = np.array([[0.1, 0.5], [0.6, 0.1]])

    def gap(x, y):
        return np.where((x > 0.2) & (y > 0.2) & (y < 0.8), 1e3, 1.0)

    uniform = vf.lloyd(sites, dom, iterations=1)
    got = vf.lloyd(sites, dom, iterations=1, density=gap)
    np.testing.assert_allclose(got.points, uniform.points, rtol=0, atol=1e-13)


def test_callable_moments_match_a_fine_raster_in_a_holed_domain():
    """Masses and centroids of cells around a hole against a 2000 x 2000 raster of the same
    density (pixel-exact clipping, an independent code path); 1e6 inside the hole."""
    rng = np.random.default_rng(5)
    z = rng.random((80, 2))
    z = z[~_in_hole(z[:, 0], z[:, 1])]
    d = vf.voronoi(z, FRAME)
    assert (shapely.area(np.asarray(d.cells)) > 0).all()
    cells = np.asarray(d.cells)
    concave = shapely.area(shapely.convex_hull(cells)) > shapely.area(cells) * (1 + 1e-9)
    assert concave.sum() >= 4  # the cells around the hole's corners
    m = 2000
    c = (np.arange(m) + 0.5) / m
    xx, yy = np.meshgrid(c, c[::-1])  # row 0 is the top
    raster = (_poly(xx, yy), (0.0, 0.0, 1.0, 1.0))
    ref = [np.copy(a) for a in Integrator(raster, len(z))(buffers(d), z)]

    def dens(x, y):
        return np.where(_in_hole(x, y), 1e6, _poly(x, y))

    got = Integrator(dens, len(z))(buffers(d), z)
    np.testing.assert_allclose(got[0], ref[0], rtol=1e-5)
    cen_got = got[1] / got[0][:, None]
    cen_ref = ref[1] / ref[0][:, None]
    np.testing.assert_allclose(cen_got, cen_ref, rtol=0, atol=1e-5)
    # and exactly what a polynomial density gives there, to rounding
    exact = Integrator(_poly, len(z))(buffers(d), z)
    np.testing.assert_allclose(got[0], exact[0], rtol=1e-12)


def _length_checks(cells, seg):
    lines = shapely.linestrings(seg)
    total = shapely.length(lines).sum()
    union = shapely.union_all(lines)
    assert total == pytest.approx(union.length, rel=1e-9)  # nothing drawn twice
    # nothing lost, nothing added (the cells' own outlines, to rounding: a child's corner
    # lies on its parent's edge to rounding only, so their union has near-doubles)
    outlines = shapely.union_all(shapely.boundary(np.asarray(cells)))
    eps = 1e-9 * np.hypot(*np.ptp(seg.reshape(-1, 2), axis=0))
    assert outlines.difference(union.buffer(eps)).length == 0.0
    assert union.difference(outlines.buffer(eps)).length == 0.0
    assert union.length <= outlines.length * (1 + 1e-12)


def test_explode_t_junctions_once():
    cells = [box(0, 0, 2, 2), box(2, 0, 3, 1), box(2, 1, 3, 2)]
    seg = co.explode(cells)
    _length_checks(cells, seg)
    assert shapely.length(shapely.linestrings(seg)).sum() == pytest.approx(13.0)


def test_explode_parents_and_children_once():
    panel = shapely.difference(bd.rectangle(200, 100), bd.circle(15, center=(60, 50)))
    levels = rc.subdivide(panel, 12, depth=1, count=4, seed=3, web=0.0)
    cells = np.concatenate([levels[0].cells, levels[1].cells])
    _length_checks(cells, co.explode(cells))


def test_far_note_measures_a_strip_by_its_width():
    class D:  # the smallest target's cell: a strip 5e-11 x 1e-6
        cells = [box(0.5, 0, 0.5 + 5e-11, 1e-6), box(0, 0, 0.5, 1e-6)]

    dom = box(0, 0, 1, 1e-6)
    note = capacity._far_note(np.array([5e-17, 0.5e-6]), dom, 1e-6, D())
    wide, limit = (float(v) for v in re.findall(r"about ([0-9.e+-]+)", note)[:2])
    assert wide == pytest.approx(5e-11, rel=1e-3)
    ulp = np.spacing(1.0)
    assert limit == pytest.approx(2 * ulp / 5e-11, rel=0.01)  # perimeter * ulp / area
    assert "origin" not in note  # the input is at the origin already
    # a square cell far out keeps the old estimate and the hint
    far = box(1e8, 0, 1e8 + 1, 1)

    class F:
        cells = [box(1e8, 0, 1e8 + 1e-4, 1e-4), far]

    note = capacity._far_note(np.array([1e-8, 1.0]), far, 1e-9, F())
    limit = float(re.findall(r"about ([0-9.e+-]+)", note)[1])
    assert limit == pytest.approx(4 * np.spacing(1e8 + 1) / 1e-4, rel=0.01)
    assert "origin" in note


def test_power_fit_thin_strip_message_is_not_below_the_error_reached():
    rng = np.random.default_rng(3)
    for shape in ((30, 2), (30, 2)):
        rng.random(shape)  # the checker's draws before this case
    pts = rng.random((20, 2)) * [1, 1e-6]
    dom = box(0, 0, 1, 1e-6)
    t = np.r_[1e-9, np.ones(19)]
    t = t * dom.area / t.sum()
    with pytest.raises(RuntimeError) as info:
        vf.power_fit(pts, t, dom)
    msg = str(info.value)
    err = float(re.search(r"relative area error ([0-9.e+-]+)", msg).group(1))
    wide, limit = (float(v) for v in re.findall(r"about ([0-9.e+-]+)", msg)[:2])
    assert limit >= err  # float64 allows no better than the fit reached
    assert wide < 1e-9  # a strip ~5e-11 wide, not sqrt(5e-17) = 7e-9
