"""Convex containers whose walls meet at tiny angles (issue 12, checker4 F1 and its scan).

A roof of slope ``h`` over the unit cube: a gable (two walls, a ridge), a pyramid (four walls
through one apex), a hip with three walls through one apex and a hip with a ridge between
two three-wall corners. The walls' determinant at a corner is ~8 h^2: below the float
naming's 1e-13 no quadruple named it (``status 4``, even with one site), and a bisector
through a ridge of nearly parallel walls was solved 5e-9 off that bisector (two cells'
volumes off by 7e-10, their sum still right). Such names are now solved exactly.
"""

import sys
from pathlib import Path

import numpy as np
import pytest

import voroforge as vf

sys.path.insert(0, str(Path(__file__).parent))
from reference3d import brute_volumes  # noqa: E402

BASE = [[-1, 0, 0, 0], [1, 0, 0, 1], [0, -1, 0, 0], [0, 1, 0, 1], [0, 0, -1, 0]]


def _roof(kind, h):
    gable = [[0, -2 * h, 1, 1], [0, 2 * h, 1, 1 + 2 * h]]
    return (
        BASE
        + {
            "gable": gable,
            "pyramid": gable + [[-2 * h, 0, 1, 1], [2 * h, 0, 1, 1 + 2 * h]],
            "hip3": gable + [[-2 * h, 0, 1, 1]],
            "hip4": gable + [[-4 * h, 0, 1, 1], [4 * h, 0, 1, 1 + 4 * h]],
        }[kind]
    )


def _check(d, c, sites):
    assert d.volumes.sum() == pytest.approx(c.volume, rel=1e-12, abs=0)
    assert d.describe()["euler_ok"]
    # every cell as the brute-force reference has it (Qhull on each cell's half-spaces)
    ref = brute_volumes(sites, c.halfspaces)
    assert np.abs(d.volumes - ref).max() <= 1e-12 * c.volume


@pytest.mark.parametrize("kind", ["gable", "pyramid", "hip3", "hip4"])
@pytest.mark.parametrize("h", [1e-7, 1e-9, 1e-11, 1e-13, 1e-16])
def test_roof_of_tiny_slope(kind, h):
    c = vf.Convex(halfspaces=_roof(kind, h))
    rng = np.random.default_rng(1)
    for n in (1, 5, 50):
        sites = rng.random((n, 3))
        _check(vf.voronoi3d(sites, c), c, sites)


def test_bisector_through_a_shallow_ridge():
    # the float solve put the vertex on the ridge and site 2 / site 3 bisector 4.6e-9 off
    # that bisector: cell 2 came out smaller than in the unit box under the roof
    h = 1e-9
    c = vf.Convex(halfspaces=_roof("gable", h))
    sites = np.random.default_rng(1).random((5, 3))
    d = vf.voronoi3d(sites, c)
    box = vf.voronoi3d(sites, (0, 0, 0, 1, 1, 1))
    extra = d.volumes - box.volumes  # the roof only adds, at most h / 2 in all
    assert extra.min() >= -1e-15
    assert extra.sum() == pytest.approx(h / 2, abs=1e-15)
    _check(d, c, sites)


@pytest.mark.parametrize("h", [1e-7, 1e-10, 1e-13])
def test_rotated_roof(h):
    # the same roofs with no wall on an axis: no coordinate is snapped onto a wall
    from scipy.spatial.transform import Rotation

    q = Rotation.from_euler("xyz", [0.3, -0.7, 1.1]).as_matrix()
    rows = np.array(_roof("hip4", h), float)
    rows[:, :3] = rows[:, :3] @ q.T  # n . x <= d becomes (q n) . (q x) <= d
    c = vf.Convex(halfspaces=rows)
    sites = np.random.default_rng(2).random((30, 3)) @ q.T
    _check(vf.voronoi3d(sites, c), c, sites)


@pytest.mark.parametrize(
    "extra",
    [
        [[0, 0, 1, 1]],  # the top wall twice
        [[0, 0, 2, 2]],  # twice, scaled
        [[0, 0, 1, 1 + 1e-16]],  # an ulp above
        [[1e-17, 0, 1, 1]],  # tilted below an ulp
        [[1e-13, 0, 1, 1]],  # tilted: meets the top wall at angle 1e-13 (outside the cube)
    ],
)
def test_duplicate_and_near_duplicate_walls(extra):
    c = vf.Convex(halfspaces=[*BASE, [0, 0, 1, 1], *extra])
    assert c.volume == pytest.approx(1.0, rel=1e-12)
    sites = np.random.default_rng(0).random((30, 3))
    _check(vf.voronoi3d(sites, c), c, sites)


@pytest.mark.parametrize("h", [1e-5, 1e-7, 1e-11])
def test_roof_at_utm_offsets(h):
    # the vertex is solved exactly relative to its site (predicates3d.vertex_offset): an
    # exactly rounded absolute vertex at 4e6 keeps ~5e-10 of a unit cell (sums 5e-11 off);
    # the float solve of the base was 8e-12 off at slope 1e-7
    o = np.array([5e5, 4e6, 100.0])
    hs = np.array(_roof("hip4", h), float)
    hs[:, 3] += hs[:, :3] @ o
    c = vf.Convex(halfspaces=hs)
    rng = np.random.default_rng(1)
    for n in (1, 5, 50):
        d = vf.voronoi3d(o + rng.random((n, 3)), c)
        assert d.volumes.sum() == pytest.approx(c.volume, rel=1e-12, abs=0)
        assert d.describe()["euler_ok"]
