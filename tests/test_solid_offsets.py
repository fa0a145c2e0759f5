"""solid.lattice and solid.check do not depend on where the solid lies (checker7 R5).

A lattice far from the origin used to leave its pockets unfilled (their volume about the
origin was rounding noise), split into several bodies (manifold3d's union tolerance grows
with the coordinates) and ``check`` reported the leftover cavities as floating parts.
"""

import numpy as np
import pytest

import voroforge as vf
from voroforge import solid

P0 = np.random.default_rng(4).random((25, 3))


def _lattice(off, scale=1.0):
    s = 10.0 * scale
    d = vf.voronoi3d(P0 * s + off, (off, off, off, off + s, off + s, off + s))
    return solid.lattice(d, radius=0.3 * s)


@pytest.fixture(scope="module")
def origin():
    return _lattice(0.0)


@pytest.mark.parametrize("off", [5e5, 2.0**19, -3e7])
def test_lattice_translated(origin, off):
    m = _lattice(off)
    p0, p = origin.metadata["parts"], m.metadata["parts"]
    assert p0["pockets"] == 3  # the family: overlapping hulls enclose three tiny pockets
    assert p["pockets"] == p0["pockets"]
    assert p["pocket_volume"] == pytest.approx(p0["pocket_volume"], rel=1e-6)
    # the nodes far out are the Voronoi vertices rounded there (ulp 4e-9 at 3e7)
    assert p["hull_volume"] == pytest.approx(p0["hull_volume"], rel=1e-10)
    assert m.is_watertight
    r = solid.check(m, max_overhang=None)
    assert r.stats["bodies"] == 1 and r.stats["voids"] == 0
    assert r.stats["volume"] == pytest.approx(p0["hull_volume"], rel=1e-10)
    assert not [v for v in r.violations if v.kind in ("floating_part", "trapped_void")]


@pytest.mark.parametrize("scale", [1e-3, 1e3])
def test_lattice_scaled(origin, scale):
    p0 = origin.metadata["parts"]
    p = _lattice(0.0, scale).metadata["parts"]
    assert p["pockets"] == p0["pockets"]
    assert p["hull_volume"] / scale**3 == pytest.approx(p0["hull_volume"], rel=1e-12)


@pytest.mark.parametrize("off", [0.0, 5e5, 4e6, -3e7])
def test_check_inward_shell_is_trapped_void(off):
    """A small cavity (an inward shell) is a trapped void wherever it lies, never a part."""
    import trimesh

    outer = trimesh.creation.box((10.0, 10.0, 10.0))
    cav = trimesh.creation.box((0.01, 0.02, 0.03))
    cav.apply_translation((1.0, 2.0, 3.0))
    cav.invert()
    m = trimesh.util.concatenate([outer, cav])
    m.apply_translation((off, off, off))
    r = solid.check(m, max_overhang=None)
    kinds = r.by_kind()
    assert kinds.get("trapped_void") == 1 and "floating_part" not in kinds
    assert r.stats["bodies"] == 1 and r.stats["voids"] == 1
    void = next(v for v in r.violations if v.kind == "trapped_void")
    assert void.value == pytest.approx(6e-6, rel=1e-6)
    assert r.stats["volume"] == pytest.approx(1000.0 - 6e-6, rel=1e-12)
