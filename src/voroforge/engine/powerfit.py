"""Newton on the transport dual where cells may be empty: :func:`fit_dual`.

:func:`.power.fit_weights` is Kitagawa, Merigot and Thibert's damped Newton (2019): a step
is taken only where every cell keeps area and the area error shrinks. From a start where
some cells are slivers or empty (sites stranded in a hole or notch, just let out by
:func:`.power.fit_breakout`), its full steps empty cells and it takes 1/16-1/4 steps
for many rounds (a U notch, 4,000 sites: 28 steps, 43 diagrams). Here the steps follow the
dual objective instead, which is concave and defined for empty cells too:

``Phi(w) = sum_i  integral over cell i of (|x - p_i|^2 - w_i)  +  w . targets``

(the cells clipped to the domain), with gradient ``targets - areas``. A step solves
``(L_dom + mu L_hull) s = targets - areas`` (the domain's Hessian, regularised by the one on
its convex hull, where every cell keeps area and the graph is connected: Levenberg and
Marquardt) and is halved until ``Phi`` rises by Armijo's fraction of ``s``'s slope and
every cell keeps area on the hull; a cell may empty in the domain on the way. ``mu`` falls
after a full step and rises after a halved one; once every cell has area in the domain it
is dropped and the steps are Newton's, whose last steps are then accepted by the error's
fall (``Phi``'s own rise is below its rounding there).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from scipy.sparse.csgraph import connected_components

from ..config import (
    POWER_DUAL_ARMIJO,
    POWER_DUAL_MU_DOWN,
    POWER_DUAL_MU_OFF,
    POWER_DUAL_MU_START,
    POWER_DUAL_MU_UP,
)
from .diagram import buffers
from .integrate import Integrator
from .power import hessian, newton_steps, power_diagram, power_diagrams

__all__ = ["fit_dual"]


def _objective(d, w, targets, pts, moments) -> float:
    """The dual objective ``Phi(w)`` of the diagram ``d`` of weights ``w``."""
    second = moments(buffers(d), pts)[2]
    return float(second.sum() + w @ (targets - d.areas))


def fit_dual(pts, targets, dom, hull, w0, tol, max_iter):
    """Weights whose power cells in ``dom`` have ``targets`` areas, from any start.

    Parameters
    ----------
    pts : (n, 2) float64
        Distinct validated sites.
    targets : (n,) float64
        Target areas, summing to ``dom``'s area.
    dom, hull : Domain
        The domain and its convex hull.
    w0 : (n,) float64
        Starting weights: every cell must have area on ``hull`` (not modified).
    tol : float
        Largest relative area error to stop at.
    max_iter : int
        Most steps.

    Returns
    -------
    diagram : PowerDiagram
    weights : (n,) float64
    error : float
        Largest relative area error reached (inf where ``w0`` leaves a hull cell empty).
    iterations : int
        Steps taken.
    """
    n = len(pts)
    moments = Integrator(None, n)
    w = w0.copy()
    d, dh = power_diagrams(pts, w, (dom, hull))
    if not (dh.areas > 0.0).all():
        return d, w, np.inf, 0
    floor = 0.5 * min(float(targets.min()), float(dh.areas.min()))
    areas = d.areas
    phi = _objective(d, w, targets, pts, moments)
    err = float(np.max(np.abs(areas - targets) / targets))
    mu, it = POWER_DUAL_MU_START, 0
    while err > tol and it < max_iter:
        it += 1
        r = targets - areas
        lap, deg = hessian(d, pts)
        if mu > 0.0:
            laph, degh = hessian(dh, pts)
            lap, deg = lap + mu * laph, deg + mu * degh
        got = None
        for step in newton_steps(lap.tocsc(), deg, r):
            got = _search(pts, dom, hull, w, step, targets, r, phi, floor, mu > 0.0, moments)
            if got is not None:
                break
        if got is None:
            break  # no rise at float precision
        w, d, dh, phi, alpha = got
        areas = d.areas
        err = float(np.max(np.abs(areas - targets) / targets))
        mu = mu / POWER_DUAL_MU_DOWN if alpha == 1.0 else mu * POWER_DUAL_MU_UP
        if mu < POWER_DUAL_MU_OFF and (areas > 0.0).all() and _connected(d, pts):
            mu = 0.0
    return d, w, err, it


def _search(pts, dom, hull, w, step, targets, r, phi, floor, with_hull, moments):
    """Halve ``step`` until ``Phi`` rises enough (hull cells keep ``floor``), or the error falls.

    The error's fall (every cell keeping area) is accepted once the hull is dropped: near
    the fit ``Phi``'s rise is below its rounding.

    Returns ``(w, d, dh, phi, alpha)`` of the step taken (``dh`` None without the hull), or
    None after 40 halvings.
    """
    slope = float(r @ step)
    norm = float(np.linalg.norm(r))
    alpha = 1.0
    for _ in range(40):
        w_try = w + alpha * step
        if with_hull:
            d, dh = power_diagrams(pts, w_try, (dom, hull))
        else:
            d, dh = power_diagram(pts, w_try, dom), None
        phi_try = _objective(d, w_try, targets, pts, moments)
        keeps = dh is None or bool(dh.areas.min() >= floor)
        if keeps and phi_try >= phi + POWER_DUAL_ARMIJO * alpha * slope:
            return w_try, d, dh, phi_try, alpha
        a = d.areas
        if dh is None and a.min() > 0.0 and np.linalg.norm(targets - a) <= (1 - alpha / 2) * norm:
            return w_try, d, dh, phi_try, alpha
        alpha *= 0.5
    return None


def _connected(d, pts) -> bool:
    """Whether the cells' edge graph in the domain is connected (its Hessian regular)."""
    lap, _ = hessian(d, pts)
    return connected_components(sp.csr_matrix(lap), directed=False)[0] == 1
