"""A Voronoi vertex just inside, on or just past a box side (issue 15): valid shared cells.

Random sites with one box side moved onto one of their Voronoi vertices (its float
coordinate, as the default's cells give it; /tmp/lead/s34/sidesweep.py, seed 0). The exact
vertex lies within rounding of the side, on either side of it, and each cut cell decided
alone where it was: the two crossings of the side by its edges came out in the reversed
order, or one cell kept the vertex and its neighbour a crossing an ulp away (a gap, area
off by 1e-9; Euler's count off). Now a vertex within reach of a side is put on it, with
the crossings of its edges, in every cell at it (``kernels.cellcut.on_sides``).
"""

from __future__ import annotations

import numpy as np
import pytest
import shapely

import voroforge as vf

from validate import validate_diagram

H = float.fromhex

# name: (sites, box with one side through the vertex, the vertex) as float.hex
CASES = {
    "seed0_9": (
        [
            ("-0x1.7d783f2a3e369p+24", "-0x1.7d783f9e4162fp+24"),
            ("-0x1.7d783faca90aep+24", "-0x1.7d783f0187762p+24"),
            ("-0x1.7d783f3803e63p+24", "-0x1.7d783f83b3f82p+24"),
            ("-0x1.7d783f93cea02p+24", "-0x1.7d783f1f5a440p+24"),
        ],
        (
            "-0x1.7d78408000000p+24",
            "-0x1.7d7840235025bp+24",
            "-0x1.7d783e8000000p+24",
            "-0x1.7d783e8000000p+24",
        ),
        ("-0x1.7d78404b41a60p+24", "-0x1.7d7840235025bp+24"),
    ),
    "seed0_11": (
        [
            ("0x1.a684325d847afp-2", "0x1.69f50fe7732c6p-1"),
            ("0x1.3382062be6e03p-2", "0x1.0b5c89083c1c2p+0"),
            ("0x1.26e156fc18a72p+0", "0x1.c1774e5bff9afp-2"),
            ("0x1.00f81aab30ebdp+0", "0x1.1f009cac197d7p+0"),
            ("0x1.4825e6a5d2256p+0", "0x1.24cf7552d8dd8p+0"),
            ("0x1.72be15d39b690p-1", "0x1.4799ade01c050p+0"),
            ("0x1.4623d78a7473ap+0", "0x1.9b7b8c8c6ddaap-1"),
            ("0x1.0daeac1f4d61ep+0", "0x1.36be10bd4f248p+0"),
            ("0x1.8d632625fbe14p-1", "0x1.29ede5250bf7ep+0"),
            ("0x1.0066cc2beff6cp+0", "0x1.3016d70f6c78ap-1"),
            ("0x1.1151a8bf14454p+0", "0x1.bdca6570c85a0p-1"),
            ("0x1.934c24d6bc927p-2", "0x1.61fc9d8025698p-1"),
            ("0x1.7eb5f6d6deb19p-2", "0x1.8d65c1968158ep-1"),
            ("0x1.750324bda107ep-1", "0x1.728db6d0e5c0cp-1"),
        ],
        (
            "-0x1.999999999999ap-3",
            "-0x1.999999999999ap-3",
            "0x1.ccccccccccccdp+0",
            "0x1.f3497b6ba9356p-1",
        ),
        ("0x1.37339c646c8b2p+0", "0x1.f3497b6ba9356p-1"),
    ),
    "seed0_34": (
        [
            ("-0x1.7d783ff44c2ddp+24", "-0x1.7d783f30c3520p+24"),
            ("-0x1.7d783f17ae269p+24", "-0x1.7d783f3f527e0p+24"),
            ("-0x1.7d783f811ee61p+24", "-0x1.7d783f27fdbfbp+24"),
            ("-0x1.7d783fff05985p+24", "-0x1.7d783f5583d0cp+24"),
            ("-0x1.7d783f3b8c98bp+24", "-0x1.7d783fac6041cp+24"),
            ("-0x1.7d783f24b7b7cp+24", "-0x1.7d783ffff38c5p+24"),
            ("-0x1.7d783f5e2d5ebp+24", "-0x1.7d783fb2f017ap+24"),
            ("-0x1.7d783f5f123d9p+24", "-0x1.7d783fbfa6f58p+24"),
            ("-0x1.7d783fca4bdddp+24", "-0x1.7d783f5fb3f3fp+24"),
            ("-0x1.7d783f80c8e13p+24", "-0x1.7d783fd00e5f7p+24"),
            ("-0x1.7d783f1d23a3dp+24", "-0x1.7d783f1e1be86p+24"),
            ("-0x1.7d783f734f7c3p+24", "-0x1.7d783f4b3d4a7p+24"),
            ("-0x1.7d783f8c71eb4p+24", "-0x1.7d783f32d49b9p+24"),
        ],
        (
            "-0x1.7d78408000000p+24",
            "-0x1.7d78408000000p+24",
            "-0x1.7d783f59be856p+24",
            "-0x1.7d783e8000000p+24",
        ),
        ("-0x1.7d783f59be856p+24", "-0x1.7d783ff5723b8p+24"),
    ),
    "seed0_139": (
        [
            ("-0x1.7d783f85d5bd9p+24", "-0x1.7d783f41815abp+24"),
            ("-0x1.7d783f2fdca8dp+24", "-0x1.7d783fb6d4273p+24"),
            ("-0x1.7d783f2b5ebf7p+24", "-0x1.7d783f462a128p+24"),
        ],
        (
            "-0x1.7d78408000000p+24",
            "-0x1.7d78408000000p+24",
            "-0x1.7d783e8000000p+24",
            "-0x1.7d783f7caa7f3p+24",
        ),
        ("-0x1.7d783f5b87868p+24", "-0x1.7d783f7caa7f3p+24"),
    ),
    "seed0_146": (
        [
            ("0x1.f6d74bcf5d942p-1", "0x1.0a53b55e39083p+0"),
            ("0x1.a553de60f70f7p-2", "0x1.aa5801d096d45p-2"),
            ("0x1.4559626929d30p-1", "0x1.486c79659f4ddp+0"),
            ("0x1.c2bbec28b9f6fp-2", "0x1.5ffaf1062b70bp-2"),
            ("0x1.013021222e5c2p-1", "0x1.0ba476353ba05p+0"),
            ("0x1.3e0380fe3dba2p+0", "0x1.56a89f5efab27p-2"),
            ("0x1.81399ba30778dp-2", "0x1.0e353de4f12c0p+0"),
            ("0x1.783832f849a78p-1", "0x1.cae4c0c5597bfp-2"),
            ("0x1.1e144b5071997p+0", "0x1.ab9d9163929bdp-2"),
            ("0x1.84244c4e9c14cp-1", "0x1.0ef516a66da16p-1"),
            ("0x1.27487fd199d1ap+0", "0x1.7ccb99ed9194ap-1"),
        ],
        (
            "-0x1.999999999999ap-3",
            "-0x1.999999999999ap-3",
            "0x1.f3fdf17ed8460p-1",
            "0x1.ccccccccccccdp+0",
        ),
        ("0x1.f3fdf17ed8460p-1", "0x1.32457a86ac654p-1"),
    ),
}


# the half-plane cells (kernels/halfplane*, not the dual's cut) leave a gap of ~1e-9 of
# the box's area there (a sliver under an ulp wide at offset -2.5e7), inside their own
# certificate's 1e-9 tiling tolerance; the dual's cells tile to 1e-12
HALFPLANE_GAPS = {("seed0_9", -2, True), ("seed0_9", -1, True), ("seed0_34", 1, False)}


def _case(name):
    sites, box, vertex = CASES[name]
    p = np.array([[H(x), H(y)] for x, y in sites])
    return p, tuple(H(v) for v in box), (H(vertex[0]), H(vertex[1]))


def _moved(box, vertex, ulps, corner):
    """The box with the side through ``vertex`` moved ``ulps`` ulps (both sides: ``corner``)."""
    b = list(box)
    side = [k for k in range(4) if b[k] == vertex[k % 2]]
    assert len(side) == 1
    k = side[0]
    for j in (k - k % 2, k - k % 2 + 1) if corner else (k,):
        v = vertex[j % 2]
        for _ in range(abs(ulps)):
            v = np.nextafter(v, np.inf if ulps > 0 else -np.inf)
        b[j] = float(v)
    return tuple(b)


def _check(p, box, algorithm):
    d = vf.voronoi(p, box, algorithm=algorithm)
    cells = np.asarray(d.cells, dtype=object)
    assert shapely.is_valid(cells).all(), [c.wkt for c in cells if not c.is_valid]
    area = (box[2] - box[0]) * (box[3] - box[1])
    assert d.areas.sum() == pytest.approx(area, rel=1e-12)
    r = d.describe()
    assert r.euler_ok, str(r)
    assert r.convex_ok, str(r)
    return d


@pytest.mark.parametrize("name", list(CASES))
def test_vertex_at_a_box_side(name, algorithm):
    p, box, _ = _case(name)
    d = _check(p, box, algorithm)
    validate_diagram(d, p, samples=500)


@pytest.mark.parametrize("corner", [False, True])
@pytest.mark.parametrize("ulps", [-4, -2, -1, 1, 2, 4])
@pytest.mark.parametrize("name", list(CASES))
def test_side_a_few_ulps_from_the_vertex(name, ulps, corner, algorithm, request):
    if algorithm == "halfplane" and (name, ulps, corner) in HALFPLANE_GAPS:
        request.applymarker(pytest.mark.xfail(strict=True, reason="half-plane gap, see above"))
    p, box, vertex = _case(name)
    _check(p, _moved(box, vertex, ulps, corner), algorithm)


@pytest.mark.parametrize("name", list(CASES))
def test_vertex_on_a_box_corner(name, algorithm):
    p, box, vertex = _case(name)
    _check(p, _moved(box, vertex, 0, True), algorithm)


@pytest.mark.parametrize("name", list(CASES))
def test_algorithms_agree(name):
    p, box, _ = _case(name)
    cells = [
        np.asarray(vf.voronoi(p, box, algorithm=a).cells, dtype=object)
        for a in ("delaunay", "fortune", "halfplane")
    ]
    area = (box[2] - box[0]) * (box[3] - box[1])
    for other in cells[1:]:
        diff = shapely.area(shapely.symmetric_difference(cells[0], other))
        assert diff.max() <= 1e-9 * area
