"""power_fit's steps on the transport dual (issue 15, fit3): ``powerfit.fit_dual``.

The dual objective ``Phi(w) = sum_i int_cell_i (|x - p_i|^2 - w_i) + w . t`` is concave with
gradient ``t - areas`` (checked by central differences against shapely's areas of the
cells); its damped steps fit from starts where cells are empty in the domain (sites in a
U notch, from zero weights: Kitagawa-Merigot-Thibert's line search cannot start there), and
power_fit uses them after the breakout. Every fit is checked independently: shapely areas
of the cells clipped to the domain, tiling, and brute-force ownership of sample points.
"""

import numpy as np
import pytest
import shapely
from shapely.geometry import Point, box

import voroforge as vf
import voroforge.engine.capacity as capacity
import voroforge.engine.powerfit as powerfit
from voroforge.engine.domain import make_domain
from voroforge.engine.integrate import Integrator
from voroforge.engine.power import power_diagram

from reference import check_power_fit

TOL = 1e-6
NOTCH = box(0, 0, 1, 1).difference(box(0.3, 0.3, 0.7, 1.0))


def _problem(geom, n, seed):
    rng = np.random.default_rng(seed)
    pts = rng.random((n, 2))
    t = rng.random(n) + 0.5
    return pts, t / t.sum() * geom.area


def test_objective_gradient_is_targets_minus_areas():
    pts, t = _problem(NOTCH, 60, 3)
    dom = make_domain(NOTCH, pts)
    w = np.random.default_rng(4).random(60) * 1e-2
    moments = Integrator(None, 60)

    def phi(w):
        return powerfit._objective(power_diagram(pts, w, dom), w, t, pts, moments)

    cells = np.asarray(power_diagram(pts, w, dom).cells, dtype=object)
    areas = shapely.area(shapely.intersection(cells, NOTCH))
    h = 1e-6
    for i in (0, 7, 31, 59):
        e = np.zeros(60)
        e[i] = h
        grad = (phi(w + e) - phi(w - e)) / (2 * h)
        assert abs(grad - (t[i] - areas[i])) <= 1e-6 * t.max()
    # concave along a random line: midpoint above the chord
    s = np.random.default_rng(5).standard_normal(60) * 1e-2
    assert phi(w) >= 0.5 * (phi(w + s) + phi(w - s)) - 1e-15


@pytest.mark.parametrize("geom", [NOTCH, box(0, 0, 1, 1).difference(Point(0.5, 0.5).buffer(0.3))])
def test_fit_dual_from_empty_cells(geom):
    """Zero weights leave every site in the notch or hole with no area in the domain."""
    pts, t = _problem(geom, 150, 1)
    dom = make_domain(geom, pts)
    hull = make_domain(shapely.convex_hull(geom), pts)
    w0 = np.zeros(150)
    assert (power_diagram(pts, w0, dom).areas <= 0.0).sum() > 15
    d, w, err, it = powerfit.fit_dual(pts, t, dom, hull, w0, TOL, 200)
    assert err <= TOL
    check_power_fit(d, pts, t, geom, TOL, samples=3000)


def test_power_fit_in_a_notch_takes_the_dual_steps(monkeypatch):
    """Where the breakout pushed cells back out (forced here), the dual's steps finish."""
    calls = []
    real, breakout = capacity.fit_dual, capacity.fit_breakout

    def spy(*args):
        got = real(*args)
        calls.append(got[2])
        return got

    def pushed_back(*args):
        got = breakout(*args)
        return None if got is None else (got[0], got[1], True)

    def fail(*args):
        raise AssertionError("the relaxed density's continuation ran")

    monkeypatch.setattr(capacity, "fit_dual", spy)
    monkeypatch.setattr(capacity, "fit_breakout", pushed_back)
    monkeypatch.setattr(capacity, "_gap_continuation", fail)
    pts, t = _problem(NOTCH, 400, 21)
    fit = vf.power_fit(pts, t, NOTCH)
    assert calls and calls[-1] <= TOL
    check_power_fit(fit, pts, t, NOTCH, TOL, samples=3000)
