"""checker14 F9: Convex(points=) whose hull facets are coplanar only to rounding.

Cells got vertices far outside the container (0.94 of a 10-unit cell) and were non-convex:
the float-cut template's nearly parallel walls placed them; voronoi3d now checks the cells'
vertices against the walls and builds them again from the exact polytope of the same rows.
References: scipy's hull of the points (its planes and volume) and the Convex's own rows.
"""

import warnings

import numpy as np
import pytest
from scipy.spatial import ConvexHull

import voroforge as vf

EPS = np.finfo(np.float64).eps
CUBE = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)
#: the corners of a Voronoi cell of a 10-box at (1e5, 1e5, 0) (checker14 f9.py) and 4 sites
F9_V = np.array(
    [
        [100010.0, 100004.24471474906, 0.0],
        [100006.02591528952, 100006.52051551022, 1.517509481695933],
        [100010.0, 100004.49731716547, 3.607629597247798],
        [100006.03294128197, 100006.41042544351, 0.0],
        [100004.32635255148, 100009.22800364948, 0.91777523182959],
        [100004.56446732761, 100010.0, 1.1856186791898482],
        [100010.0, 100010.0, 4.486178334232246],
        [100003.81168297071, 100010.0, 0.0],
        [100010.0, 100010.0, 0.0],
        [100003.81699501986, 100010.0, 0.13193557050268984],
    ]
)
F9_S = np.array(
    [
        [100009.32864194651, 100004.87735036018, 2.6439200389174586],
        [100007.91328032664, 100008.60988679112, 1.2657045109918987],
        [100008.61266367242, 100008.0970693857, 1.5534151803947727],
        [100007.88262297242, 100007.7107810973, 0.5020850226146885],
    ]
)


def _check(d, V, S, off, hull_slack, vol_slack):
    """Cells convex, inside the hull of ``V`` (to ``hull_slack``), volumes sum to its volume."""
    o = np.array([off, off, 0.0])
    h = ConvexHull(V - o)
    assert d.describe()["convex"], d.describe()["nonconvex_cells"]
    for i in range(len(S)):
        P = np.asarray(d.cell(i).vertices) - o
        assert (h.equations[:, :3] @ P.T + h.equations[:, 3][:, None]).max() <= hull_slack
    assert d.volumes.sum() == pytest.approx(h.volume, rel=0, abs=vol_slack)


@pytest.mark.parametrize("eps", [1e-15, 1e-13, 1e-11, 1e-9])
def test_jittered_cube(eps):
    rng = np.random.default_rng(0)
    for _ in range(30):
        V = CUBE + rng.normal(size=CUBE.shape) * eps
        F = rng.random((6, 3))
        F[np.arange(6), rng.integers(0, 3, 6)] = rng.integers(0, 2, 6)
        V = np.vstack([V, F + rng.normal(size=F.shape) * eps])
        S = rng.random((5, 3)) * 0.8 + 0.1
        C = vf.Convex(points=V)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            d = vf.voronoi3d(S, C)
        # the container's own rows hold every vertex to a few ulps (were 2.7e-5 out)
        H = C.halfspaces
        for i in range(5):
            P = np.asarray(d.cell(i).vertices)
            assert (P @ H[:, :3].T - H[:, 3]).max() <= 64 * EPS * 4
        # the hull of the points: within the merge of nearly coplanar facets (1e-12)
        _check(d, V, S, 0.0, 2e-12, 2e-11)


@pytest.mark.parametrize("off", [0.0, 1e5, 5e5])
def test_f9_cell_corners(off):
    shift = np.array([off - 1e5, off - 1e5, 0.0])
    V, S = F9_V + shift, F9_S + shift
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        d = vf.voronoi3d(S, vf.Convex(points=V))
    # a vertex was 0.94 outside; now within a few ulps of the coordinates plus the merge of
    # nearly coplanar facets (containers._hull_planes: 1e-12 of the extent, 6.2 here)
    _check(d, V, S, off, 4 * np.spacing(max(off, 10.0)) + 1e-11, 1e-10)
    assert (d.volumes > 0).all()
