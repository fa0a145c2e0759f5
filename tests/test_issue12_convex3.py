"""``Convex(points=)``: a hull the float cut refuses, and folded float-built cells (issue 12).

FLAT_CUT (the 20 corners of a relaxed cell of a box at 1e6, 31 walls): the template's float
cut (``containers.cut_template``) lost its rings among walls ulps apart and the container
was refused as "degenerate half-spaces"; it is now the exact polytope of the same rows.
FOLDED (16 hull points and 6 sites at ~1000): the float build gave a cell whose rings ran
through two vertices of other cells, 0.18 nearer their sites (volume right, mesh folded);
such a build is detected (``voronoi3d._folded``: a vertex past one of its cell's bisectors)
and the cells are built again from the exact twin. References: the exact rational hull
(brute force), brute-force half-space cells, the nearest site of every vertex.
"""

from __future__ import annotations

import sys
import warnings
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from scipy.spatial import ConvexHull

import voroforge as vf
from voroforge.engine import voronoi3d as V3
from voroforge.engine.containers import as_container
from voroforge.engine.inputs import working_frame

sys.path.insert(0, str(Path(__file__).parent))
from reference3d import brute_volumes  # noqa: E402
from test_issue12_hullball_volume import _exact_hull_volume  # noqa: E402
from test_solid_subdivide_far import FLAT_CUT, FOLDED, LOST  # noqa: E402


def _inside_sites(v, k, seed):
    """``k`` random sites well inside the hull of ``v``."""
    o = v.mean(axis=0)
    eq = ConvexHull(v - o).equations
    x = np.random.default_rng(seed).uniform(v.min(axis=0), v.max(axis=0), size=(4000, 3))
    s = x[((x - o) @ eq[:, :3].T + eq[:, 3] < -1e-3 * np.ptp(v)).all(axis=1)][:k]
    assert len(s) == k
    return s


def _check_cells(d, seeds, c):
    """Volumes against brute-force half-space cells; every cell convex, its vertices its own."""
    scale = float(np.ptp(np.asarray(c._template.bounds), axis=0).max())
    assert abs(d.volumes.sum() - c.volume) <= 1e-12 * c.volume
    ref = brute_volumes(seeds, c.halfspaces)
    assert np.abs(d.volumes - ref).max() <= 1e-9 * c.volume
    for i in range(len(seeds)):
        cv = np.asarray(d.cell(i).vertices)
        o = cv.mean(axis=0)
        # a folded cell's vertices span more than its volume (FOLDED: 2.571 against 2.217)
        assert abs(ConvexHull(cv - o).volume - d.volumes[i]) <= 1e-9 * c.volume
        dist = np.linalg.norm(cv[:, None] - seeds[None], axis=2)
        assert (dist[:, i] - dist.min(axis=1)).max() <= 1e-9 * scale


def test_float_cut_refused_hull_builds():
    v = np.array(FLAT_CUT)
    exact = _exact_hull_volume(v)
    c = vf.Convex(points=v)  # raised "degenerate half-spaces"
    assert abs(float(Fraction(c.volume) / exact - 1)) <= 1e-12
    near = vf.Convex(points=v - 1e6)  # the same hull near the origin built
    assert abs(near.volume - c.volume) <= 1e-12 * c.volume
    hs = c.halfspaces
    o = np.round(v.mean(axis=0))
    assert ((v - o) @ hs[:, :3].T - (hs[:, 3] - o @ hs[:, :3].T)).max() <= 1e-9
    seeds = _inside_sites(v, 8, 3)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        d = vf.voronoi3d(seeds, c)
    _check_cells(d, seeds, c)


@pytest.mark.parametrize("shift", [0.0, -1000.0])
@pytest.mark.parametrize("case", ["folded", "lost"])
def test_convex_cells_not_folded(case, shift):
    v, seeds = (np.asarray(x, float) for x in (FOLDED if case == "folded" else LOST))
    v, seeds = v + shift * (case == "folded"), seeds + shift * (case == "folded")
    c = vf.Convex(points=v)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        d = vf.voronoi3d(seeds, c)
    _check_cells(d, seeds, c)


def _float_build(seeds, c):
    t = as_container(c, seeds)
    work, k = working_frame(seeds, extra=t.bounds, cap=V3.FRAME3D_CAP_EXP)
    P = np.ascontiguousarray(work)
    W = np.zeros(len(P))
    return V3._convex_cells(P, W, t.scaled(k), None), P, W


def _brute_folded(res, P, W, rel=1e-9):
    """Whether a cell of ``res`` has a vertex nearer another site by ``rel`` of the extent."""
    site = np.zeros(len(res.cells), np.int64)
    site[res.pos] = res.cells
    scale = float(np.ptp(P, axis=0).max() + np.ptp(res.vertices, axis=0).max())
    for b, i in enumerate(site):
        q = res.vertices[res.vid[res.voff[b] : res.voff[b + 1]]]
        pw = ((q[:, None] - P[None]) ** 2).sum(axis=2) - W
        if (pw[:, i] - pw.min(axis=1)).max() > rel * scale**2:
            return True
    return False


@pytest.mark.parametrize("case", ["folded", "lost", "sphere"])
def test_fold_detector_against_brute_force(case):
    # the detector flags a float build exactly when a vertex is nearer another site by far
    # more than rounding (FOLDED's float build at this commit: yes; LOST's and a random
    # hull's: no). Whether the float build folds is the kernels' business.
    if case == "sphere":
        rng = np.random.default_rng(5)
        v = rng.normal(size=(300, 3))
        v = 50.0 * v / np.linalg.norm(v, axis=1)[:, None] + 1000.0
        seeds = 1000.0 + rng.uniform(-25, 25, size=(1500, 3))
    else:
        v, seeds = (np.asarray(x, float) for x in (FOLDED if case == "folded" else LOST))
    c = vf.Convex(points=v)
    res, P, W = _float_build(seeds, c)
    if ((res.status != 0) & (res.status != 1)).any():
        pytest.skip("the float build failed (rebuilt from the exact twin anyway)")
    assert V3._folded(res, P, W) == _brute_folded(res, P, W)
