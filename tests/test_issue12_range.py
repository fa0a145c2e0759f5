"""Issue 12, range: 3D diagrams scaled by a power of two are the same bits, scaled.

Face areas and normals and the flatness test behind the neighbours are computed in the
working frame (engine.diagram3d), so only the container's volume (engine.containers.
VOLUME_RANGE) and its largest face (AREA_MAX) bound the scales; past them a clear
ValueError. Before, area norms overflowed past sides of ~1e77 and underflowed below ~1e-77,
and the volume range stopped sides at ~1e-66..1e66.
"""

import warnings

import numpy as np
import pytest

import voroforge as vf
from voroforge.config import AREA_MAX, VOLUME_RANGE


def _fixture(how, aspect=0):
    """Sites, container and weights of a small fixture (the flat one: z times 2**-aspect)."""
    g = np.random.default_rng(11)
    S = g.random((40, 3))
    S[:, 2] = np.ldexp(S[:, 2], -aspect)
    box = np.array([0.0, 0.0, 0.0, 1.0, 1.0, np.ldexp(1.0, -aspect)])
    w = np.ldexp(g.random(40) * 1e-3, -2 * aspect) if how == "weights" else None
    return S, (None if how == "default" else box), w


def _call(S, box, w, k, periodic):
    return vf.voronoi3d(
        np.ldexp(S, k),
        None if box is None else tuple(np.ldexp(box, k)),
        weights=None if w is None else np.ldexp(w, 2 * k),
        periodic=periodic,
    )


def _same_scaled(unit, d, k):
    assert (d.volumes == np.ldexp(unit.volumes, 3 * k)).all()
    assert (d.vertices == np.ldexp(unit.vertices, k)).all()
    assert (d.centroids == np.ldexp(unit.centroids, k)).all()
    for a, b in zip(unit.neighbors, d.neighbors, strict=True):
        assert (a == b).all()
    for a, b in ((unit.faces.indptr, d.faces.indptr), (unit.faces.indices, d.faces.indices)):
        assert (a == b).all()
    assert (unit.faces.cells == d.faces.cells).all()
    assert (d.face_areas == np.ldexp(unit.face_areas, 2 * k)).all()
    assert (d.face_normals == unit.face_normals).all()
    assert np.isfinite(d.face_areas).all() and (d.face_areas > 0).any()
    t0 = unit.cell_face_table()[2]
    t1 = d.cell_face_table()[2]
    assert (t1 == np.ldexp(t0, 2 * k)).all()
    desc = d.describe()
    assert desc["euler_ok"] and desc["convex"], desc


# the unit box's volume times 2**(3k) within VOLUME_RANGE: k from -298 to 332 (the default
# box, padded, to 328)
KS = [-296, -280, -240, -200, -160, -120, -80, -40, 40, 80, 120, 160, 200, 240, 280, 320, 328]


@pytest.mark.parametrize("k", KS)
@pytest.mark.parametrize("how", ["box", "default", "weights", "periodic"])
def test_power_of_two_scales_are_the_same_bits(k, how):
    S, box, w = _fixture(how)
    periodic = how == "periodic"
    unit = _call(S, box, w, 0, periodic)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        d = _call(S, box, w, k, periodic)
        _same_scaled(unit, d, k)


@pytest.mark.parametrize("k", [-264, -240, -120, 120, 240, 360, 380])
def test_flat_box_sides_past_1e100(k):
    # a slab of sides 1, 1 and 2**-100 scaled by 2**k: its volume 2**(3k - 100) bounds k to
    # -265..365 (at -264 its sides are 2.1e-80 and 1.6e-110, at 360 2.3e108 and 1.8e78);
    # 380 is past the range
    S, box, w = _fixture("box", aspect=100)
    lo, hi = np.log2(VOLUME_RANGE)
    inside = lo <= 3 * k - 100 <= hi and 2 * k <= np.log2(AREA_MAX)
    if not inside:
        with pytest.raises(ValueError, match="scale the points"):
            _call(S, box, w, k, False)
        return
    unit = _call(S, box, w, 0, False)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        _same_scaled(unit, _call(S, box, w, k, False), k)


@pytest.mark.parametrize("k", [-300, -340, -480, 334, 360, 480])
@pytest.mark.parametrize("how", ["box", "default", "periodic"])
def test_past_the_range_raises_naming_it(k, how):
    S, box, w = _fixture(how)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(ValueError, match=r"outside 1e-270\.\.1e\+300"):
            _call(S, box, w, k, how == "periodic")


def test_flat_box_past_the_largest_face_raises():
    # sides 2**500, 2**500, 2**-500: volume 2**500 is in range, its faces (2**1000) are not
    with pytest.raises(ValueError, match="largest face"):
        vf.voronoi3d(
            np.ldexp(np.random.default_rng(1).random((10, 3)), 400) * [1, 1, 2.0**-1000],
            (0.0, 0.0, 0.0, 2.0**500, 2.0**500, 2.0**-500),
        )


def test_utm_offset_unchanged():
    # far from the origin (x ~ 5e5): the working frame is the caller's (frame 0), the
    # areas the plain fan's
    g = np.random.default_rng(8)
    S = np.array([5e5, 4e6, 100.0]) + 1000 * g.random((300, 3))
    d = vf.voronoi3d(S)
    assert d._frame == 0
    assert abs(d.volumes.sum() - d.container_volume) <= 1e-12 * d.container_volume
    assert np.isfinite(d.face_areas).all()
    desc = d.describe()
    assert desc["euler_ok"] and desc["convex"]


def _mesh_case(k):
    import trimesh

    m = trimesh.creation.icosphere(subdivisions=1)
    S = np.random.default_rng(3).uniform(-0.5, 0.5, (40, 3))
    mk = trimesh.Trimesh(np.ldexp(m.vertices, k), m.faces, process=False)
    return np.ldexp(S, k), mk


@pytest.mark.parametrize("k", [-120, -60, 60])
def test_mesh_container_areas_in_its_vertices_frame(k):
    # a mesh diagram (engine.mesh3d builds it) takes its frame from its vertices: finite
    # areas scaled exactly where the cut is (below 2**60 here: the cut itself is not scale
    # exact at 2**120 and up, before and after this change)
    pytest.importorskip("trimesh")
    unit = vf.voronoi3d(*_mesh_case(0))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        d = vf.voronoi3d(*_mesh_case(k))
        assert (d.volumes == np.ldexp(unit.volumes, 3 * k)).all()
        assert (d.face_areas == np.ldexp(unit.face_areas, 2 * k)).all()
        assert (d.face_normals == unit.face_normals).all()


@pytest.mark.parametrize("k", [-296, -240, 240, 328])
def test_mesh_container_over_the_boxes_range(k):
    # meshes now have the boxes' range (they kept 1e-200..1e200: the cut's moments
    # overflowed past 2**256): the same cells scaled, centroids included
    pytest.importorskip("trimesh")
    unit = vf.voronoi3d(*_mesh_case(0))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        d = vf.voronoi3d(*_mesh_case(k))
    assert (d.volumes == np.ldexp(unit.volumes, 3 * k)).all()
    assert np.array_equal(d.centroids, np.ldexp(unit.centroids, k), equal_nan=True)


@pytest.mark.parametrize("k", [-310, 340])
def test_mesh_container_past_the_range_raises(k):
    pytest.importorskip("trimesh")
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the refusal, not an overflow warning before it
        with pytest.raises(ValueError, match=r"outside 1e-270\.\.1e\+300"):
            vf.voronoi3d(*_mesh_case(k))


@pytest.mark.parametrize("k", [-296, 260, 328])
def test_torus_container_over_the_boxes_range(k):
    # a torus's cells need manifold3d, which sees coordinates past 2**200 scaled by a power
    # of two (config.MANIFOLD_SAFE): at 2**260 and 2**-260 its cells came back short
    # ("not a valid solid"); now the same cells, scaled
    trimesh = pytest.importorskip("trimesh")
    m = trimesh.creation.torus(1.0, 0.4)
    S = np.random.default_rng(4).uniform(-1.4, 1.4, (120, 3)) * [1, 1, 0.3]
    unit = vf.voronoi3d(S, m)
    mk = trimesh.Trimesh(np.ldexp(m.vertices, k), m.faces, process=False)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        d = vf.voronoi3d(np.ldexp(S, k), mk)
    assert (d.volumes == np.ldexp(unit.volumes, 3 * k)).all()
    assert np.array_equal(d.centroids, np.ldexp(unit.centroids, k), equal_nan=True)
