"""Surface Morph onto a sphere patch that contains the pole (checker21 F7).

The default ``polar = (0, pi / 2)`` maps the UV square's whole v = 0 edge to the pole: morphed
rings used to repeat that point (zero-length edges, a zero normal), so unroll, openings and
thicken failed. Checked against independent references: 3D edge lengths, the true sphere
(radius, radial normals), the hemisphere's area, trimesh's watertightness and volume.
"""

import math
import warnings

import numpy as np
import pytest
import shapely

from voroforge import surface

R = 1.0
POLE = np.array([0.0, 0.0, R])


def _cells(n=30, seed=0):
    rng = np.random.default_rng(seed)
    pts = rng.random((n, 2)) * [2 * math.pi, 2.0]
    box = shapely.box(0, 0, 2 * math.pi, 2.0)
    vor = shapely.voronoi_polygons(shapely.MultiPoint(pts), extend_to=box)
    return [g.intersection(box) for g in shapely.get_parts(vor)], box.bounds


@pytest.fixture(scope="module")
def dome():
    cells, bounds = _cells()
    return surface.morph(cells, surface.sphere_patch(R), bounds=bounds)


def _edges(ring):
    return np.linalg.norm(np.roll(ring, -1, axis=0) - ring, axis=1)


def test_rings_have_no_repeated_points_and_lie_on_the_sphere(dome):
    assert np.isfinite(dome.vertices).all()
    assert np.allclose(np.linalg.norm(dome.vertices, axis=1), R, atol=1e-12)
    at_pole = 0
    for p in range(len(dome)):
        for ring in dome.polygon(p):
            assert len(ring) >= 3
            assert _edges(ring).min() > 1e-9
        at_pole += int((np.linalg.norm(dome.polygon(p)[0] - POLE, axis=1) < 1e-12).sum())
    assert at_pole >= 3  # the panels around the pole each meet it once
    # the panels still cover the hemisphere (2 pi r^2), as before the merge
    assert dome.areas().sum() == pytest.approx(2 * math.pi * R * R, rel=2e-4)


@pytest.mark.parametrize("holes", [False, True])
def test_unroll_keeps_3d_edge_lengths(dome, holes):
    P = dome.openings(0.5) if holes else dome
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        sheets = P.unroll()
    assert len(sheets.parts) == len(P)
    # a part that crosses itself is said, by its label (it cannot be cut as it is)
    crossed = [part.label for part in sheets.parts if not part.polygon.is_valid]
    said = [str(w.message) for w in caught if issubclass(w.category, surface.UnrollWarning)]
    if crossed:
        assert len(said) == 1 and f"({', '.join(crossed)})" in said[0], said
    else:
        assert said == []
    # a panel far from planar (one wraps the pole: 3x its size off its plane) may fold over
    # itself when unrolled; the rest are simple polygons
    bent = P.planarity().relative > 0.5
    for k, part in enumerate(sheets.parts):
        rings3 = P.polygon(k)
        assert len(part.rings) == len(rings3)
        flat = np.asarray(part.rings[0], float)
        if np.allclose(flat[0], flat[-1]):
            flat = flat[:-1]
        assert np.isfinite(flat).all()
        l3 = np.sort(_edges(rings3[0]))
        l2 = np.sort(_edges(flat))
        np.testing.assert_allclose(l2, l3, rtol=0, atol=1e-9)
        assert part.polygon.is_valid or bent[k]


def test_thicken_gives_watertight_solids_along_the_sphere_normal(dome):
    trimesh = pytest.importorskip("trimesh")
    t = 0.01
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        P = dome.openings(0.5)
        solids = P.thicken(t)
    total = 0.0
    for p, m in enumerate(solids):
        assert isinstance(m, trimesh.Trimesh)
        assert np.isfinite(m.vertices).all()
        assert m.is_watertight and m.volume > 0
        n = len(P._all_index(p))
        base, top = m.vertices[:n], m.vertices[n:]
        # offset along the sphere's radial normal (the surface's side), the pole included
        side = 1.0 if np.sum((top - base) * base) > 0 else -1.0
        np.testing.assert_allclose(top - base, side * t * base / R, atol=1e-8)
        total += m.volume
    # the shell between r and r + t over the hemisphere minus the openings: roughly
    # t x the panels' area (a loose independent check that no solid is inside out)
    area = P.areas().sum()
    assert total == pytest.approx(t * area, rel=0.05)


def test_design_file_dome_builds_every_output(tmp_path):
    from voroforge.cli import main

    design = tmp_path / "dome.toml"
    design.write_text(
        '[design]\nname = "md"\nseed = 1\nunits = "m"\n'
        '[boundary]\nshape = "rectangle"\nwidth = 600\nheight = 200\n'
        '[seeds]\nmethod = "random"\ncount = 30\n[cells]\nweb = 4\n'
        '[output]\nformats = ["dxf", "svg"]\n'
        '[surface]\nshape = "sphere_patch"\nradius = 1\nmode = "morph"\n'
        'thickness = 0.01\nmeshes = ["obj"]\n'
    )
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        rc = main(["build", str(design), "-o", str(tmp_path / "out")])
    assert rc in (0, None)
    names = sorted(p.name for p in (tmp_path / "out").iterdir())
    assert any(n.endswith(".dxf") for n in names)
    assert any(n.endswith(".svg") for n in names)
    objs = [p for p in (tmp_path / "out").iterdir() if p.suffix == ".obj"]
    assert objs
    trimesh = pytest.importorskip("trimesh")
    scene = trimesh.load(objs[0], force="scene", process=False)
    for g in scene.geometry.values():
        assert np.isfinite(g.vertices).all()
