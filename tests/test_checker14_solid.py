"""checker14 F2-F5: extrude's relief and overlapping parts, foam pore sizes, thin walls.

References are independent of the builders: shapely's union area for extruded volumes,
a per-cell Chebyshev LP on scipy's ConvexHull planes for the foam pores, the 3D diagram's
face table and the box for the foam walls, the meshes' own coordinates for slabs and shells.
"""

import math
import warnings

import numpy as np
import pytest

shapely = pytest.importorskip("shapely")
trimesh = pytest.importorskip("trimesh")
linprog = pytest.importorskip("scipy.optimize").linprog

import voroforge as vf  # noqa: E402
from voroforge import solid  # noqa: E402

# --- F2: relief heights --------------------------------------------------------------------


@pytest.mark.parametrize(
    "relief",
    [
        lambda xy: np.where(xy[:, 0] > 5, np.nan, 1.0),
        lambda xy: np.full(len(xy), np.inf),
        lambda xy: np.where(xy[:, 1] < 1, -np.inf, 0.0),
    ],
)
def test_relief_non_finite_heights_are_refused(relief):
    with pytest.raises(ValueError, match=r"non-finite heights at \(x, y\)"):
        solid.extrude(shapely.box(0, 0, 10, 10), 3.0, relief=relief, max_area=0.5)


@pytest.mark.parametrize("bad", [lambda xy: np.ones(3), lambda xy: np.ones((len(xy), 2))])
def test_relief_of_the_wrong_shape_is_refused(bad):
    with pytest.raises(ValueError, match=r"one height per point"):
        solid.extrude(shapely.box(0, 0, 10, 10), 3.0, relief=bad, max_area=0.5)


def test_a_finite_relief_still_builds():
    m = solid.extrude(
        shapely.box(0, 0, 10, 10), 1.0, relief=lambda xy: 0.1 * xy[:, 0], max_area=0.5
    )
    assert m.is_volume and np.isfinite(m.vertices).all()
    # a linear top is followed exactly: 10 x 10 x (1 + mean 0.5)
    assert math.isclose(m.volume, 150.0, rel_tol=1e-9)


# --- F3: overlapping parts are unioned -----------------------------------------------------


@pytest.mark.parametrize(
    "parts",
    [
        [shapely.box(0, 0, 2, 2), shapely.box(1, 1, 3, 3)],
        [shapely.box(0, 0, 4, 4), shapely.box(1, 1, 2, 2)],  # one inside the other
        [shapely.Point(x, 0.3 * x).buffer(1.0, 16) for x in (0.0, 1.2, 2.1, 5.0)],
        [shapely.box(0, 0, 4, 4).difference(shapely.box(1, 1, 3, 3)), shapely.box(2, 2, 5, 5)],
    ],
)
def test_overlapping_multipolygon_extrudes_the_union(parts):
    g = shapely.MultiPolygon(parts)
    assert not g.is_valid
    union = shapely.union_all(parts)
    h = 2.5
    m = solid.extrude(g, h)
    assert m.is_volume
    assert math.isclose(m.volume, union.area * h, rel_tol=1e-9)
    pieces = len(shapely.get_parts(union))
    assert len(m.split(only_watertight=False)) == pieces


def test_overlapping_parts_in_a_collection_are_unioned():
    g = shapely.GeometryCollection(
        [shapely.MultiPolygon([shapely.box(0, 0, 2, 2)]), shapely.box(1, 0, 3, 1)]
    )
    m = solid.extrude(g, 1.0)
    assert math.isclose(m.volume, shapely.union_all(shapely.get_parts(g)).area, rel_tol=1e-12)


# --- F4: foam pores are the inscribed balls ------------------------------------------------


def _reference_balls(d, n, wall):
    """Each cell's largest ball at ``wall / 2`` from every face: its own LP per cell."""
    from scipy.spatial import ConvexHull

    out = []
    for i in range(n):
        ch = ConvexHull(np.asarray(d.cell(i).vertices))
        a, b = ch.equations[:, :3], -ch.equations[:, 3] - wall / 2
        r = linprog(
            [0, 0, 0, -1],
            A_ub=np.column_stack([a, np.linalg.norm(a, axis=1)]),
            b_ub=b,
            bounds=[(None, None)] * 4,
        )
        assert r.success
        out.append((a, b, r.x[3]))
    return out


@pytest.mark.parametrize(("seed", "wall"), [(3, 1.0), (5, 4.0), (8, 0.3)])
def test_foam_pores_are_the_inscribed_diameters(seed, wall):
    n = 30
    pts = np.random.default_rng(seed).random((n, 3)) * 20
    d = vf.voronoi3d(pts, (0, 0, 0, 20, 20, 20))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        m = solid.foam(d, wall=wall)
    pores = m.metadata["pores"]
    ref = _reference_balls(d, n, wall)
    rr = np.array([r for _, _, r in ref])
    size = np.asarray(pores["size"])
    clear = np.abs(rr) > 1e-6 * 20  # not at the edge of being swallowed
    assert np.allclose(size[clear], np.where(rr > 0, 2 * rr, 0.0)[clear], rtol=1e-6, atol=1e-7)
    for (a, b, _), c, s in zip(ref, pores["centre"], size, strict=True):
        if s > 0:  # the recorded ball lies inside the bubble
            assert (a @ c + 0.5 * s - b).max() <= 1e-7 * 20


def test_foam_pore_check_counts_the_true_small_pores():
    pts = np.random.default_rng(3).random((30, 3)) * 20
    d = vf.voronoi3d(pts, (0, 0, 0, 20, 20, 20))
    m = solid.foam(d, wall=1.0)
    rr = np.array([r for _, _, r in _reference_balls(d, 30, 1.0)])
    rep = solid.check(m, min_pore=4.0, max_overhang=None)
    assert rep.by_kind().get("small_pore", 0) == int((2 * rr < 4.0).sum())


# --- F5: thin walls ------------------------------------------------------------------------


@pytest.mark.parametrize("wall", [0.01, 1.0])
def test_foam_walls_are_the_diagram_faces(wall):
    pts = np.random.default_rng(3).random((30, 3)) * 20
    d = vf.voronoi3d(pts, (0, 0, 0, 20, 20, 20))
    m = solid.foam(d, wall=wall)
    w = m.metadata["walls"]
    at, th = np.asarray(w["at"]), np.asarray(w["thickness"])
    on_box = (np.abs(at) < 1e-9).any(axis=1) | (np.abs(at - 20) < 1e-9).any(axis=1)
    assert np.allclose(th[on_box], wall / 2) and np.allclose(th[~on_box], wall)
    cells = np.asarray(d.faces.cells)
    if wall == 0.01:  # every face keeps a facet on both sides: one wall per diagram face
        assert on_box.sum() == (cells[:, 1] < 0).sum()
        assert (~on_box).sum() == (cells[:, 1] >= 0).sum()
    else:  # never more than the faces
        assert on_box.sum() <= (cells[:, 1] < 0).sum()
        assert (~on_box).sum() <= (cells[:, 1] >= 0).sum()
    for limit, expect in [(wall / 4, 0), (0.75 * wall, on_box.sum()), (2 * wall, len(th))]:
        rep = solid.check(m, min_wall=limit, max_overhang=None)
        assert rep.by_kind().get("thin_wall", 0) == expect
    assert "thin_wall" not in solid.check(m, max_overhang=None).by_kind()


def test_foam_skin_is_half_a_wall_on_a_single_cell():
    m = solid.foam([trimesh.creation.box((10, 10, 10))], wall=2.0)
    th = np.asarray(m.metadata["walls"]["thickness"])
    # the box minus an 8-cube: 1 thick on each of the six sides
    assert len(th) == 6 and np.allclose(th, 1.0)
    assert math.isclose(m.volume, 10**3 - 8**3, rel_tol=1e-12)


def test_extrude_slab_thickness_and_lowest_relief_top():
    m = solid.extrude(shapely.box(0, 0, 10, 10), 1.0, relief=lambda xy: -0.05 * xy[:, 0])
    (value,) = m.metadata["walls"]["thickness"]
    top = np.asarray(m.vertices)[:, 2]
    assert value == top[top > 0].min() == pytest.approx(0.5)
    rep = solid.check(m, min_wall=0.6, max_overhang=None)
    assert rep.by_kind() == {"thin_wall": 1}
    assert solid.check(m, min_wall=0.4, max_overhang=None).ok
    two = solid.extrude(
        shapely.MultiPolygon([shapely.box(0, 0, 1, 1), shapely.box(3, 0, 4, 1)]), 0.3
    )
    assert solid.check(two, min_wall=0.5, max_overhang=None).by_kind()["thin_wall"] == 2


def test_shell_thickness_is_a_wall():
    surf = trimesh.creation.cylinder(radius=10.0, height=12.0, sections=48)
    keep = surf.face_normals[:, 2] ** 2 < 0.5
    tube = trimesh.Trimesh(surf.vertices, surf.faces[keep], process=True)
    m = solid.shell(tube, thickness=1.0, openings=None, voxel=0.4, smoothing=2)
    (t,) = m.metadata["walls"]["thickness"]
    assert t == 1.0
    # the mesh's own thickness: its volume over the tube's area (rounded ends add a little)
    assert 0.9 < m.volume / tube.area < 1.15
    assert solid.check(m, min_wall=1.5, max_overhang=None).by_kind().get("thin_wall") == 1
    assert "thin_wall" not in solid.check(m, min_wall=0.8, max_overhang=None).by_kind()


# --- F8 (schema side): [solid] validation errors name the key and line ----------------------

_DESIGN = """[design]
name = "t"
units = "mm"

[solid]
kind = "foam"
container = [0, 0, 0, 20, 20, 20]
cells = 12
wall = 1.2
"""


def _issues(tmp_path, old, new):
    from voroforge.design.designfile import DesignError, load

    p = tmp_path / "t.toml"
    p.write_text(_DESIGN.replace(old, new, 1), encoding="utf-8")
    with pytest.raises(DesignError) as err:
        load(p)
    return [(i.key, i.line, i.message) for i in err.value.issues]


@pytest.mark.parametrize(
    ("old", "new"),
    [
        ('kind = "foam"', 'kind = "foma"'),
        ("container = [0, 0, 0, 20, 20, 20]", "container = [0, 0, 0, 20, 20, 0]"),
        ('kind = "foam"', 'kind = "shell"'),
    ],
)
def test_a_bad_solid_adds_no_2d_errors(tmp_path, old, new):
    keys = [k for k, _, _ in _issues(tmp_path, old, new)]
    assert keys and all(k.startswith("solid") for k in keys), keys


def test_a_nan_container_is_not_finite_at_its_line(tmp_path):
    got = _issues(tmp_path, "20, 20, 20]", "20, 20, nan]")
    assert any(k.startswith("solid.container") and ln == 7 and "finite" in m for k, ln, m in got)
    assert not any("max must exceed" in m for _, _, m in got)


@pytest.mark.parametrize("key", ["wall", "radius"])
def test_a_size_pair_without_fields_names_its_key(tmp_path, key):
    got = _issues(tmp_path, "wall = 1.2", f"{key} = [2.0, 0.5]")
    assert (f"solid.{key}", 9) in [(k, ln) for k, ln, _ in got], got
    assert any("[[solid.fields]]" in m for _, _, m in got)


# --- F11: shell seed points are validated ---------------------------------------------------


@pytest.mark.parametrize(
    ("openings", "match"),
    [
        (np.zeros((3, 2)) + np.arange(3)[:, None], r"\(k, 3\)"),
        (np.ones((4, 2)), r"\(k, 3\)"),
        (np.array([[0.0, 0, 0], [1, 1, np.nan]]), "finite"),
        (np.array([[10.0, 0, 0]]), "2 distinct"),
        (np.array([[10.0, 0, 0]] * 5), "2 distinct"),
    ],
)
def test_shell_seed_points_are_checked(openings, match):
    tube = trimesh.creation.cylinder(radius=10.0, height=12.0, sections=16)
    with pytest.raises(ValueError, match=match):
        solid.shell(tube, thickness=1.0, openings=openings, voxel=0.5)
