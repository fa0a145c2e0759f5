"""Findings of the second independent check (2026-12-04 night), fixed by the lead.

Each test is the checker's minimal input: a small convex solid far out, a seed count that
asked for tens of GiB, a boundary width that reached the seeding as NaN, an empty format
list, cells written as float32 PLY/GLB at UTM offsets, and mesh containers that are closed
and oriented but not valid solids.
"""

from __future__ import annotations

import subprocess
import sys
import warnings
from fractions import Fraction

import numpy as np
import pytest
import trimesh
import trimesh.creation as tc

import voroforge as vf
from voroforge.io import mesh as meshio


def _tetra_volume(T) -> float:
    a, b, c, d = ([Fraction(float(v)) for v in row] for row in T)
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    w = [d[i] - a[i] for i in range(3)]
    det = (
        u[0] * (v[1] * w[2] - v[2] * w[1])
        - u[1] * (v[0] * w[2] - v[2] * w[0])
        + u[2] * (v[0] * w[1] - v[1] * w[0])
    )
    return float(abs(det) / 6)


@pytest.mark.parametrize(
    "side, offset, rtol",
    [
        (1e-3, (5e5, 4e6, 100), 1e-5),  # was -0.00117 for 1.7e-10
        (1e-3, (1e5, 1e5, 100), 1e-6),  # was 6.2e-6
        (1.0, (5e5, 4e6, 100), 1e-8),  # was 0.1706 for 0.1667 (planes: ulp 4.7e-10 at 4e6)
        (1e-2, (1e6, 1e6, 1e6), 1e-6),  # was 0.0
        (1e-3, (4e6, 4e6, 100), 1e-5),  # could not be closed
        (1e-6, (5e5, 4e6, 100), 1e-2),  # 1000 ulps wide: was refused as flat
    ],
)
def test_convex_volume_far_from_the_origin(side, offset, rtol):
    """The rtol is the input's own rounding: corners at 4e6 are 1e-6 of a 1e-3 solid apart."""
    T = np.array([[0, 0, 0], [side, 0, 0], [0, side, 0], [0, 0, side]]) + offset
    exact = _tetra_volume(T)
    c = vf.Convex(points=T)
    assert c.volume == pytest.approx(exact, rel=rtol)
    P = T.mean(0) + np.eye(3) * 1e-2 * side
    d = vf.voronoi3d(P, c)
    assert d.volumes.sum() == pytest.approx(exact, rel=rtol)
    assert d.describe()["euler_ok"]


def _build(tmp_path, body: str):
    f = tmp_path / "d.toml"
    f.write_text(body)
    return subprocess.run(
        [sys.executable, "-m", "voroforge", "build", str(f), "-o", str(tmp_path / "out")],
        capture_output=True,
        text=True,
        timeout=120,
    )


DESIGN = """[design]
name = "t"
seed = 1
[boundary]
shape = "rectangle"
width = {width}
height = 60
[seeds]
method = "random"
count = {count}
[output]
formats = {formats}
"""


@pytest.mark.parametrize(
    "width, count, formats, message",
    [
        (100, 1000000000, '["svg"]', "seeds.count: 1,000,000,000 seeds, at most 2,000,000"),
        (100, 10000000000000, '["svg"]', "seeds.count: 10,000,000,000,000 seeds, at most"),
        ("1e308", 10, '["svg"]', "boundary.width: must be at most 1e+100"),
        (100, 10, "[]", "output.formats: is empty"),
    ],
)
def test_design_limits_are_clear_errors(tmp_path, width, count, formats, message):
    r = _build(tmp_path, DESIGN.format(width=width, count=count, formats=formats))
    assert r.returncode == 2, r.stderr
    assert "voroforge: error:" in r.stderr and message in r.stderr, r.stderr
    assert "Traceback" not in r.stderr


def test_populate_count_limit():
    from shapely.geometry import box

    from voroforge.design import populate

    with pytest.raises(ValueError, match="too large"):
        populate.random(box(0, 0, 1, 1), 10**12, seed=0)


FAR = np.random.default_rng(4).random((40, 3)) * 1e-3 + (5e5, 4e6, 100)


@pytest.mark.parametrize("suffix", [".ply", ".glb", ".obj"])
def test_cli_cell_meshes_keep_far_coordinates(tmp_path, suffix):
    """``voronoi3d -o X.ply/.glb`` wrote float32: at (5e5, 4e6) every cell collapsed (volume 0)."""
    pts = tmp_path / "p.npy"
    np.save(pts, FAR)
    out = tmp_path / f"cells{suffix}"
    r = subprocess.run(
        [sys.executable, "-m", "voroforge", "voronoi3d", str(pts), "-o", str(out)],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert r.returncode == 0, r.stderr
    d = vf.voronoi3d(FAR)
    loaded = trimesh.load(out, process=False)
    parts = loaded.dump() if isinstance(loaded, trimesh.Scene) else [loaded]
    total = sum(abs(m.volume) for m in parts)
    assert total == pytest.approx(d.volumes.sum(), rel=1e-6)
    lo = np.min([m.bounds[0] for m in parts], axis=0)
    hi = np.max([m.bounds[1] for m in parts], axis=0)
    np.testing.assert_allclose(hi - lo, np.ptp(d.vertices, axis=0), rtol=1e-6)


def test_mesh_write_glb_far_and_stl_warns(tmp_path):
    box = tc.box((1e-2, 2e-2, 3e-2))
    box.apply_translation((5e5, 4e6, 100))
    meshio.write(box, tmp_path / "b.glb")
    back = trimesh.load(tmp_path / "b.glb", process=False)
    back = back.dump()[0] if isinstance(back, trimesh.Scene) else back
    assert abs(back.volume) == pytest.approx(box.volume, rel=1e-6)
    with pytest.warns(UserWarning, match="float32"):
        meshio.write(box, tmp_path / "b.stl")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        meshio.write(tc.box((1, 2, 3)), tmp_path / "near.stl")  # near the origin: no warning
    # a slab thinner than float32 holds there: the size hardly moves but the slab collapses
    slab = tc.box((100, 100, 1e-9))
    slab.apply_translation((50, 50, 10))
    with pytest.warns(UserWarning, match="distinct vertices fall onto others"):
        meshio.write(slab, tmp_path / "slab.stl")


def _boxes(*moves, scale=None):
    vs, fs = [], []
    for k, mv in enumerate(moves):
        b = tc.box((1, 1, 1))
        if scale is not None and k:
            b.apply_scale(scale)
        b.apply_translation(mv)
        fs.append(b.faces + 8 * k)
        vs.append(b.vertices)
    return np.vstack(vs), np.vstack(fs)


@pytest.mark.parametrize(
    "mesh",
    [
        _boxes((0, 0, 0), (0.5, 0.2, 0.1)),  # two overlapping boxes as one mesh
        _boxes((0, 0, 0), (0, 0, 0), scale=0.3),  # an inner shell facing outwards
    ],
    ids=["overlapping", "nested_outward"],
)
def test_mesh_containers_that_are_not_solids(mesh):
    P = np.random.default_rng(0).random((20, 3)) * 0.5 - 0.25
    # refused up front since 391d90a (shells that overlap or nest the same way), or by the
    # cut's volume check where the up-front test cannot be sure
    with pytest.raises(ValueError, match="intersects itself|not a valid solid"):
        vf.voronoi3d(P, mesh)


def test_mesh_faces_must_be_integers():
    b = tc.box((1, 1, 1))
    P = np.random.default_rng(0).random((5, 3)) * 0.5 - 0.25
    with pytest.raises(ValueError, match="integer vertex indices"):
        vf.voronoi3d(P, (b.vertices, b.faces + 0.5))
    d = vf.voronoi3d(P, (b.vertices, b.faces.astype(float)))  # whole numbers are fine
    assert d.volumes.sum() == pytest.approx(1.0, rel=1e-12)


def test_periodic_power_with_an_empty_cell():
    """A site whose power cell is empty made the periodic margin double until memory ran out."""
    P = np.array([[0.5, 0.5, 0.5], [0.52, 0.5, 0.5], [0.1, 0.2, 0.3], [0.8, 0.7, 0.2]])
    W = np.array([0.1, 0.0, 0.0, 0.0])
    d = vf.voronoi3d(P, (0, 0, 0, 1, 1, 1), weights=W, periodic=True)
    assert d.volumes[1] == 0.0
    assert d.volumes.sum() == pytest.approx(1.0, rel=1e-12)
    # brute force: each sample point's power-nearest site over the 27 images
    q = np.random.default_rng(0).random((40000, 3))
    shifts = np.array([(a, b, c) for a in (-1, 0, 1) for b in (-1, 0, 1) for c in (-1, 0, 1)])
    pw = ((q[:, None, None] - P[None, :, None] - shifts[None, None]) ** 2).sum(-1).min(-1) - W
    share = np.bincount(pw.argmin(1), minlength=4) / len(q)
    np.testing.assert_allclose(share, d.volumes, atol=0.01)


@pytest.mark.parametrize("offset, tiny", [(1e5, 1e-6), (1e5, 1e-8), (4e6, 1e-5)])
def test_power_fit_far_from_the_origin(offset, tiny):
    """Newton runs near the origin: at 1e5 a cell of area 2e-7 had stalled at 6e-6 relative."""
    rng = np.random.default_rng(0)
    P = rng.random((20, 2)) * 2 + offset
    t = np.r_[tiny, np.ones(19)]
    t = t / t.sum() * 4.0
    d = vf.power_fit(P, t, (offset, offset, offset + 2, offset + 2))
    assert (np.abs(d.areas - t) / t).max() <= 1e-6


def test_power_fit_says_when_rounding_limits_a_far_cell():
    P = np.random.default_rng(0).random((20, 2)) * 2 + 4e6
    t = np.r_[1e-8, np.ones(19)]
    t = t / t.sum() * 4.0
    with pytest.raises(RuntimeError, match="rounding alone limits its area"):
        vf.power_fit(P, t, (4e6, 4e6, 4e6 + 2, 4e6 + 2))
