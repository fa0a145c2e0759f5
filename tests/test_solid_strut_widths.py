"""``solid.check``'s strut widths and a lattice's skin against the meshes themselves.

A strut was reported as ``2 r``, but a hull-route strut is a prism of ``segments`` sides
with its corners at ``r`` (8 sides: 0.924 of that across its flats) and marching cubes cuts
chords into an implicit strut (0.89-0.91 of it at the default voxel, half at a voxel of
``r``). ``check`` now reports the widest round rod inside: measured here on cross sections
of the mesh (trimesh's plane sections; the nearest section edge to the strut's axis).
A lattice's ``skin`` was not checked against ``min_wall``.
"""

import numpy as np
import pytest

trimesh = pytest.importorskip("trimesh")
pytest.importorskip("skimage")

from voroforge import solid  # noqa: E402
from voroforge.solid.check import strut_widths  # noqa: E402


def _inscribed_diameter(m, a, b):
    """Twice the least distance from the axis to the mesh's sections across the strut."""
    d = b - a
    n = d / np.linalg.norm(d)
    best = np.inf
    for f in np.linspace(0.3, 0.7, 15):
        o = a + f * d
        seg = trimesh.intersections.mesh_plane(m, n, o)
        p, q = seg[:, 0], seg[:, 1]
        pq = q - p
        t = np.clip(((o - p) * pq).sum(1) / np.maximum((pq * pq).sum(1), 1e-300), 0.0, 1.0)
        best = min(best, float(np.linalg.norm(o - (p + t[:, None] * pq), axis=1).min()))
    return 2.0 * best


def _strut(r, **kw):
    rng = np.random.default_rng(int(1000 * r) + len(kw))
    a = rng.uniform(0, 1, 3)
    u = rng.normal(size=3)
    b = a + 10 * r * u / np.linalg.norm(u)
    return a, b, solid.lattice((np.array([a, b]), np.array([[0, 1]])), radius=r, **kw)


@pytest.mark.parametrize("k", [5, 6, 8, 12])
def test_hull_strut_width_is_its_prism_inscribed_circle(k):
    a, b, m = _strut(0.7, segments=k)
    assert m.metadata["parts"]["method"] == "hull"
    w = strut_widths(m.metadata)[0]
    assert w == pytest.approx(_inscribed_diameter(m, a, b), rel=1e-9)
    assert w < 1.4  # the declared diameter
    rep = solid.check(m, min_strut=1.4, max_overhang=None)
    (v,) = [v for v in rep.violations if v.kind == "thin_strut"]
    assert v.value == pytest.approx(w)
    assert not [v for v in solid.check(m, min_strut=0.99 * w).violations if v.kind == "thin_strut"]


@pytest.mark.parametrize("q", [0.25, 0.5, 1.0])
@pytest.mark.parametrize("r", [0.3, 0.8])
def test_implicit_strut_width_is_below_the_mesh(r, q):
    a, b, m = _strut(r, route="implicit", voxel=q * r)
    w = strut_widths(m.metadata)[0]
    measured = _inscribed_diameter(m, a, b)
    assert measured < 2 * r  # the chords: the declared width was not true
    assert (0.75 if q <= 0.5 else 0.55) * measured <= w <= measured


def test_default_voxel_recorded():
    a, b, m = _strut(0.5, route="implicit")
    from voroforge import config

    assert m.metadata["voxel"] == pytest.approx(config.SOLID_VOXEL * 0.5)
    assert strut_widths(m.metadata)[0] <= _inscribed_diameter(m, a, b)


def test_lattice_skin_is_a_wall():
    import voroforge as vf

    box = trimesh.creation.box(extents=(6, 6, 6))
    pts = np.random.default_rng(0).uniform(-2.5, 2.5, (5, 3))
    cells = vf.voronoi3d(pts, (-3, -3, -3, 3, 3, 3))
    m = solid.lattice(cells, radius=0.4, container=box, skin=0.8, voxel=0.25)
    thin = [v for v in solid.check(m, min_wall=1.0).violations if v.kind == "thin_wall"]
    assert len(thin) == 1 and thin[0].value == pytest.approx(0.8)
    assert np.abs(thin[0].location).max() == pytest.approx(3.0, abs=0.2)  # on the skin
    assert not [v for v in solid.check(m, min_wall=0.7).violations if v.kind == "thin_wall"]
    # the skin is at least that thick: along lines in through the top, the first crossing
    # is the box's face and the next (the skin's inside, or a strut's) 0.8 or more below
    for x in (-1.1, 0.3, 1.7):
        seg = trimesh.intersections.mesh_plane(m, [1.0, 0.0, 0.0], [x, 0.0, 0.0])
        p, q = seg[:, 0], seg[:, 1]
        for y in (-1.3, 0.2, 1.9):
            c = (p[:, 1] - y) * (q[:, 1] - y) < 0
            t = (y - p[c, 1]) / (q[c, 1] - p[c, 1])
            z = np.sort(p[c, 2] + t * (q[c, 2] - p[c, 2]))[::-1]
            assert z[0] == pytest.approx(3.0, abs=0.02)
            assert z[0] - z[1] >= 0.8 - 0.05
