"""``solid.cells.subdivide`` far from the origin: leaves trimesh calls convex and closed.

Leaves at offsets 1e5 .. 1e9 were convex to an ulp, but their fan triangles (three nearly
collinear ring vertices) had normals rounding chose, and trimesh's ``is_convex`` rejected
most (104 of 128 at 1e5). Each leaf is now the hull of its vertices with slivers' corners
left out; three parents on which 12cff29's engine gave a folded cell, lost volume, or
refused the container are split from half-spaces. References: the parents' volumes
(scipy's hull, box sizes), nearest-seed membership of every leaf vertex, and point samples
(each clear sample in exactly one leaf, tested by the leaves' own face planes).
"""

import numpy as np
import pytest

import voroforge as vf

trimesh = pytest.importorskip("trimesh")
from scipy.spatial import ConvexHull  # noqa: E402

from voroforge import solid  # noqa: E402
from voroforge.solid import cells as C  # noqa: E402

FOLDED = (
    [
        (1003.6224236531932, 1007.1494984708557, 1007.2130887318446),
        (1005.036029253037, 1007.912049971047, 1008.3153936025549),
        (1003.7869669096538, 1007.0202341126414, 1006.690949177759),
        (1003.8773571570592, 1007.0354280570429, 1006.6612946692204),
        (1006.8091916464408, 1004.8428964061416, 1007.8136210752782),
        (1006.4358940483418, 1004.8403943191383, 1007.4732053642606),
        (1006.1909388253605, 1008.2011156480066, 1009.5620323886251),
        (1006.7816986057683, 1004.7153832061238, 1007.873697517757),
        (1005.937454539256, 1005.2093895794418, 1010.0),
        (1004.628675420542, 1005.7602077246984, 1010.0),
        (1003.8925367221747, 1005.9901908372931, 1008.7761191886432),
        (1003.5298265938413, 1006.7115423995159, 1007.5429771838051),
        (1004.2018879835665, 1005.769294508203, 1007.3855881755396),
        (1003.7002196428789, 1006.5532286764537, 1007.0040010193025),
        (1005.997110810362, 1007.5280871062859, 1010.0),
        (1006.4357093570958, 1004.8350945117381, 1007.4765802160255),
    ],
    [
        (1006.191979107042, 1007.2294850543132, 1009.0329526096657),
        (1005.1788142114746, 1007.5022880623266, 1008.7786259672017),
        (1004.4436598073509, 1005.7459879710997, 1007.9071078608425),
        (1005.0093391220362, 1007.2027196358297, 1008.9367287520797),
        (1004.2188610139001, 1006.6540194441686, 1008.2793171935557),
        (1005.275560054204, 1005.7468371748845, 1009.4728535227226),
    ],
)
LOST = (
    [
        (100004.16954053559, 100008.79211988417, 100005.22178660019),
        (100004.06121082083, 100008.44158324515, 100005.14201459217),
        (100003.85332809814, 100007.72208721249, 100002.09612854371),
        (100001.76327437098, 100008.01014481696, 100001.34356571919),
        (100000.88349488396, 100008.96865832235, 100004.35170150001),
        (100000.3124588732, 100010.0, 100004.34395948934),
        (100004.32635255148, 100009.22800364949, 100000.91777523182),
        (100004.32635442505, 100009.22800972383, 100000.9177773393),
        (100004.54282336494, 100010.0, 100005.49666520505),
        (100001.18740607704, 100009.31070424423, 100000.08791665273),
        (100001.14708556539, 100009.40176538112, 100000.0),
        (100000.81533355368, 100010.0, 100000.0),
        (100004.2769989942, 100009.13983728565, 100005.30091703123),
        (100003.81699501986, 100010.0, 100000.1319355705),
        (100003.27126183712, 100010.0, 100000.0),
        (100004.5644673276, 100010.0, 100001.18561867918),
    ],
    [
        (100004.09487172189, 100009.58613492128, 100004.84551730113),
        (100004.46739103876, 100009.99463959104, 100004.16873326647),
        (100001.49951155193, 100009.27905650823, 100002.67803622756),
        (100001.46253096002, 100008.89345542296, 100000.82334896986),
        (100002.14826251114, 100009.90381083266, 100002.88090890895),
    ],
)
FLAT_CUT = [
    (1000001.0924463723, 1000010.0, 1000000.0),
    (1000006.1228850575, 1000010.0, 1000005.7596810203),
    (1000006.8130468224, 1000006.5104222589, 1000002.9944933999),
    (1000006.6008035375, 1000005.2187640347, 1000001.4354601442),
    (1000006.3099337998, 1000004.5975534427, 1000000.4694961203),
    (1000006.0135544499, 1000004.4698111063, 1000000.0),
    (1000006.2221809443, 1000004.7305563072, 1000001.4492598017),
    (1000005.7526109047, 1000007.0389137855, 1000005.9510242128),
    (1000004.7547650514, 1000006.0094182253, 1000006.3831813263),
    (1000004.4394346144, 1000005.0089271299, 1000005.480618579),
    (1000004.5286348243, 1000005.5756523798, 1000006.1725855202),
    (1000002.0025918867, 1000004.3190303321, 1000003.9807830557),
    (1000003.5713751846, 1000005.8508764534, 1000006.2260780354),
    (1000000.0, 1000010.0, 1000002.2494504586),
    (1000000.0, 1000003.5290849592, 1000001.287810513),
    (1000004.2389398253, 1000008.5603090826, 1000007.48729578),
    (1000004.3369132418, 1000010.0, 1000007.8272534831),
    (1000000.0, 1000010.0, 1000000.0),
    (1000000.0, 1000003.3324495554, 1000000.0),
    (1000005.7244787876, 1000010.0, 1000006.8173667279),
]


def _closed_convex(leaves):
    for m in leaves:
        assert m.is_watertight and m.is_winding_consistent
        assert m.is_convex
        assert m.body_count == 1


def _centred_volume(leaves, o):
    return sum(m.copy().apply_translation(-np.asarray(o)).volume for m in leaves)


def _one_leaf_each(leaves, lo, hi, n=3000, seed=0):
    """Every sample clear of the leaves' face planes lies in exactly one leaf."""
    rng = np.random.default_rng(seed)
    x = rng.uniform(lo, hi, size=(n, 3))
    count = np.zeros(n, dtype=np.int64)
    clear = np.ones(n, dtype=bool)
    delta = 1e-6 * float(np.max(np.asarray(hi) - np.asarray(lo)))
    for m in leaves:
        c = np.asarray(m.vertices).mean(axis=0)
        nrm = np.asarray(m.face_normals)
        a = np.asarray(m.triangles[:, 0]) - c
        s = ((x - c)[:, None, :] * nrm[None]).sum(axis=2) - (a * nrm).sum(axis=1)[None]
        top = s.max(axis=1)
        count += top < -delta
        clear &= np.abs(top) > delta
    assert clear.sum() > 0.9 * n
    assert (count[clear] == 1).all()


@pytest.mark.parametrize(
    ("off", "levels"), [(0.0, 1), (1e5, 2), (1e7, 1), (1e9, 2), (-1e9, 1), (3.3e8, 1)]
)
def test_far_leaves_are_convex_and_tile(off, levels):
    rng = np.random.default_rng(0)
    box = (off, off, off, off + 10, off + 10, off + 10)
    d = vf.voronoi3d(off + rng.random((12, 3)) * 10, box)
    counts = (3, 9) if levels == 1 else (2, 5)
    leaves = solid.cells.subdivide(
        d, counts, levels=levels, seed=0, field=lambda x: (x[:, 0] - off) / 10
    )
    assert len(leaves) > 50
    _closed_convex(leaves)
    area = sum(m.area for m in leaves)
    ulp = np.spacing(abs(off) + 10.0)
    assert abs(_centred_volume(leaves, [off] * 3) - 1000.0) <= ulp * area + 1e-13 * 1000
    _one_leaf_each([m.copy().apply_translation([-off] * 3) for m in leaves], 0.0, 10.0)


def _nearest_seed_leaves(leaves, seeds, size):
    """Every leaf's vertices are nearest to one seed (to 1e-9 of the size)."""
    owners = set()
    for m in leaves:
        x = np.asarray(m.vertices)
        dist = np.linalg.norm(x[:, None, :] - seeds[None], axis=2)
        ok = (dist <= dist.min(axis=1, keepdims=True) + 1e-9 * size).all(axis=0)
        assert ok.any()
        owners.add(int(np.flatnonzero(ok)[0]) if ok.sum() == 1 else -1)
    return owners


@pytest.mark.parametrize("case", ["folded", "lost"])
def test_engine_cells_checked_against_the_parent(case):
    v, s = FOLDED if case == "folded" else LOST
    v, s = np.array(v), np.array(s)
    leaves = C._split(v, s)
    _closed_convex(leaves)
    o = v.mean(axis=0)
    ref = ConvexHull(v - o).volume
    assert abs(_centred_volume(leaves, o) - ref) <= 1e-9 * ref
    assert len(leaves) == len(s)
    owners = _nearest_seed_leaves(leaves, s, float(np.ptp(v, axis=0).max()))
    assert owners == set(range(len(s)))


def test_container_the_float_cut_refuses():
    v = np.array(FLAT_CUT)
    o = v.mean(axis=0)
    rng = np.random.default_rng(3)
    eq = ConvexHull(v - o).equations
    x = rng.uniform(v.min(axis=0), v.max(axis=0), size=(400, 3))
    s = x[((x - o) @ eq[:, :3].T + eq[:, 3] < -1e-3).all(axis=1)][:6]
    leaves = C._split(v, s)
    _closed_convex(leaves)
    ref = ConvexHull(v - o).volume
    assert abs(_centred_volume(leaves, o) - ref) <= 1e-9 * ref
    assert _nearest_seed_leaves(leaves, s, float(np.ptp(v, axis=0).max())) == set(range(6))


def test_sliver_corner_left_out():
    """A point 1e-12 off a hull edge's midpoint is left out; one 1e-3 off is kept."""
    cube = np.array([[i, j, k] for i in (0, 1) for j in (0, 1) for k in (0, 1)], float) + 1e5
    for off, kept in ((1e-12, 8), (1e-3, 9)):
        p = np.vstack([cube, [1e5 + 0.5, 1e5 - off, 1e5 - off]])
        m = C._hull_mesh(p)
        assert len(m.vertices) == kept
        assert m.is_convex and m.is_watertight
