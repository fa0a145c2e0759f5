"""3D containers found by an independent check (checker4): extreme half-space rows, cells a
mesh container splits into pieces or wraps round a hole (describe's Euler check)."""

import warnings

import numpy as np
import pytest

import voroforge as vf

trimesh = pytest.importorskip("trimesh")

CUBE = [[1, 0, 0, 1], [-1, 0, 0, 0], [0, 1, 0, 1], [0, -1, 0, 0], [0, 0, 1, 1], [0, 0, -1, 0]]


@pytest.mark.parametrize(
    ("rows", "volume"),
    [
        (CUBE + [[1e155, 1e155, 0, 1e155]], 0.5),  # x + y <= 1: its norm overflowed (volume 1)
        (CUBE + [[1e-300, 0, 0, 1e-300]], 1.0),  # x <= 1: its norm underflowed ("zero normal")
        (np.array(CUBE, float) * 1e200, 1.0),  # "unbounded"
        (np.array(CUBE, float) * 1e-300, 1.0),
        (CUBE + [[0.3, 0.4, 0, 0.5]], 5.0 / 6.0),  # cuts the triangle (1, 1/2), (1, 1), (1/3, 1)
    ],
)
def test_halfspace_rows_of_any_magnitude(rows, volume):
    c = vf.Convex(halfspaces=rows)
    assert c.volume == pytest.approx(volume, rel=1e-12)
    d = vf.voronoi3d(np.random.default_rng(0).random((20, 3)) * [0.5, 0.5, 1], c)
    assert d.volumes.sum() == pytest.approx(volume, rel=1e-12)


@pytest.mark.parametrize("h", [1e-5, 1e-6, 3e-7])
def test_convex_roof_nearly_flat(h):
    # three roof walls of slope 2h meet at a ridge: their determinant (8 h^2) was below the
    # sites' 1e-10 and no quadruple named the corner (RuntimeError "status 4", even with one
    # site); a wall triple is named down to 1e-13, and below that by its exact determinant
    # (every slope: tests/test_issue12_convex.py)
    base = [[-1, 0, 0, 0], [1, 0, 0, 1], [0, -1, 0, 0], [0, 1, 0, 1], [0, 0, -1, 0]]
    roof = [[0, -2 * h, 1, 1], [0, 2 * h, 1, 1 + 2 * h], [-2 * h, 0, 1, 1]]
    c = vf.Convex(halfspaces=base + roof)
    for n in (1, 30):
        d = vf.voronoi3d(np.random.default_rng(0).random((n, 3)), c)
        assert d.volumes.sum() == pytest.approx(c.volume, rel=1e-12)
        assert d.describe()["euler_ok"]


def test_halfspace_offset_that_overflows_is_a_clear_error():
    with pytest.raises(ValueError, match="halfspace 6: its offset over its normal overflows"):
        vf.Convex(halfspaces=CUBE + [[1e-310, 0, 0, 1e300]])


def _unit_box(shift=(0.0, 0.0, 0.0)):
    b = trimesh.creation.box(extents=(1, 1, 1))
    b.apply_translation(np.add((0.5, 0.5, 0.5), shift))
    return b


def test_euler_of_a_cell_split_into_pieces():
    # two unit boxes 1 apart: the second site's cell is a half box and the whole other box
    two = trimesh.util.concatenate([_unit_box(), _unit_box((2, 0, 0))])
    d = vf.voronoi3d([[0.25, 0.5, 0.5], [0.75, 0.5, 0.5]], two)
    assert d.volumes.tolist() == pytest.approx([0.5, 1.5], rel=1e-12)
    assert d.pieces.tolist() == [1, 2]
    r = d.describe()
    assert r["euler_ok"], r["euler_failures"]


def test_euler_of_a_cell_with_a_handle():
    # one site in a torus: its cell is the whole torus (V - E + F = 0), a valid cell
    t = trimesh.creation.torus(1.0, 0.3, major_sections=24, minor_sections=12)
    d = vf.voronoi3d([[1.0, 0.0, 0.0]], t)
    assert d.volumes.sum() == pytest.approx(t.volume, rel=1e-9)
    assert d.describe()["euler_ok"]


def test_euler_still_fails_on_an_open_cell():
    # the check is not vacuous: drop a face of a convex cell and it fails
    d = vf.voronoi3d(np.random.default_rng(1).random((8, 3)), (0, 0, 0, 1, 1, 1))
    cf, lab, farea, roff, ring = d.cell_face_table()
    assert d.describe()["euler_ok"]
    keep = np.ones(len(lab), bool)
    keep[cf[3]] = False  # cell 3 loses its first face

    class Open:
        def __init__(self, d):
            self._d = d

        def __getattr__(self, k):
            return getattr(self._d, k)

        def __len__(self):
            return len(self._d)

        def cell_face_table(self):
            counts = np.diff(cf) - (np.arange(len(cf) - 1) == 3)
            rows = np.flatnonzero(keep)
            ro = np.concatenate(([0], np.cumsum(np.diff(roff)[rows])))
            rg = np.concatenate([ring[roff[f] : roff[f + 1]] for f in rows])
            return np.concatenate(([0], np.cumsum(counts))), lab[rows], farea[rows], ro, rg

    from voroforge.engine.describe3d import describe3d

    r = describe3d(Open(d))
    assert not r["euler_ok"] and r["euler_failures"] == [3]


@pytest.mark.parametrize("k", [-298, -268, 260, 330])
def test_mesh_cut_scales_exactly_past_the_mesh_range(k, monkeypatch):
    # the mesh cut squared cross products and area vectors in the caller's units: at 2**260
    # they overflowed (a cell lost: "not a valid solid"), at 2**-268 they underflowed. Each
    # is now scaled by a power of two first; the mesh range (engine.voronoi3d checks
    # MESH_VOLUME_RANGE) is lifted here to probe the cut across the containers' range
    import voroforge.engine.voronoi3d as v3
    from voroforge.config import VOLUME_RANGE

    monkeypatch.setattr(v3, "MESH_VOLUME_RANGE", VOLUME_RANGE)
    m = trimesh.creation.icosphere(subdivisions=1)
    sites = np.random.default_rng(3).uniform(-0.5, 0.5, (40, 3))
    unit = vf.voronoi3d(sites, m)
    mk = trimesh.Trimesh(np.ldexp(m.vertices, k), m.faces, process=False)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        d = vf.voronoi3d(np.ldexp(sites, k), mk)
    assert (d.volumes == np.ldexp(unit.volumes, 3 * k)).all()
    # the centroids too: kernels.meshcut3d scales each cell's moments by a power of two
    # (they overflowed past 2**256 and underflowed below 2**-256)
    assert np.array_equal(d.centroids, np.ldexp(unit.centroids, k), equal_nan=True)
    assert (d.face_areas == np.ldexp(unit.face_areas, 2 * k)).all()
    assert (d.face_normals == unit.face_normals).all()


def test_unit_normals_at_any_scale():
    from voroforge.engine.mesh3d import unit_normals

    e1 = np.array([[1.0, 0, 0], [1.0, 2.0, 0], [0, 0, 0]])
    e2 = np.array([[0, 1.0, 0], [2.0, 4.0, 0], [1.0, 0, 0]])  # a needle, a zero edge
    for k in (-1000, -500, 0, 500, 1000):
        n, ok = unit_normals(np.ldexp(e1, k), np.ldexp(e2, k))
        assert ok.tolist() == [True, False, False]
        assert n.tolist() == [[0, 0, 1], [0, 0, 0], [0, 0, 0]]
