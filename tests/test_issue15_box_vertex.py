"""A Voronoi vertex just inside, on or just past a box side (issue 15): valid shared cells.

Random sites with one box side moved onto one of their Voronoi vertices (its float
coordinate, as the default's cells give it; /tmp/lead/s34/sidesweep.py, seeds 0-5). The
exact vertex lies within rounding of the side, on either side of it, and each cut cell
decided alone where it was: the two crossings of the side by its edges came out in the
reversed order, or one cell kept the vertex and its neighbour a crossing an ulp away (a
gap, area off by 1e-9; Euler's count off). Now a vertex within reach of a side is put on
it, with the crossings of its edges, in every cell at it (``kernels.cellcut.on_sides``),
unless a site of the vertex lies within that reach of the side or of another of its sites
(``kernels.cellcut.side_reaches``): the end of a strip a few ulps wide along a side
(``test_issue15_ulp_strips._box_side_strips``) put on the side left the strip's site out
of its own cell, unflagged (21 diagrams of 450).
"""

from __future__ import annotations

import numpy as np
import pytest
import shapely

import voroforge as vf
from test_issue15_ulp_strips import _box_side_strips, _shared_vertices_ok

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
    "seed1_72": (
        [
            ("0x1.f4719036ae9f2p+9", "0x1.f468ffd025b50p+9"),
            ("0x1.f4057652f084ap+9", "0x1.f4461826589ebp+9"),
            ("0x1.f4038ba205921p+9", "0x1.f43d09660d872p+9"),
            ("0x1.f40a6085f56f7p+9", "0x1.f449b647769dep+9"),
            ("0x1.f409de2416d54p+9", "0x1.f40b6a4aa9726p+9"),
            ("0x1.f47c420b555e5p+9", "0x1.f467819e9ae44p+9"),
            ("0x1.f4561940bdf4bp+9", "0x1.f464c7ff2d124p+9"),
            ("0x1.f41b5e05f10adp+9", "0x1.f40d4077a3e5dp+9"),
            ("0x1.f42939fa019a7p+9", "0x1.f46167f3fe55bp+9"),
            ("0x1.f460b1da1ecd2p+9", "0x1.f45bda4a5a2f3p+9"),
        ],
        (
            "0x1.f4742093cee8dp+9",
            "0x1.f3c0000000000p+9",
            "0x1.f4c0000000000p+9",
            "0x1.f4c0000000000p+9",
        ),
        ("0x1.f4742093cee8dp+9", "0x1.f4545060748d8p+9"),
    ),
    "seed1_84": (
        [
            ("-0x1.7d783f7a82399p+24", "-0x1.7d783f3ebae11p+24"),
            ("-0x1.7d783fde8663fp+24", "-0x1.7d783fcc4f056p+24"),
            ("-0x1.7d783f06b35bbp+24", "-0x1.7d783f31681f2p+24"),
            ("-0x1.7d783fad3e77ap+24", "-0x1.7d783f0ead6c1p+24"),
            ("-0x1.7d783f85ca78fp+24", "-0x1.7d783fbefe301p+24"),
            ("-0x1.7d783fa7ad88cp+24", "-0x1.7d783fba53001p+24"),
        ],
        (
            "-0x1.7d783f4b67c6bp+24",
            "-0x1.7d78408000000p+24",
            "-0x1.7d783e8000000p+24",
            "-0x1.7d783e8000000p+24",
        ),
        ("-0x1.7d783f4b67c6bp+24", "-0x1.7d783eda2fcc5p+24"),
    ),
    "seed2_17": (
        [
            ("0x1.f45a3ed430c64p+9", "0x1.f405c48c3689dp+9"),
            ("0x1.f454244a0f080p+9", "0x1.f46552358c21cp+9"),
            ("0x1.f40523dad03fbp+9", "0x1.f401f75710237p+9"),
            ("0x1.f472297ff8480p+9", "0x1.f4729d3de787bp+9"),
            ("0x1.f4169a57d3b40p+9", "0x1.f47612e8186e8p+9"),
            ("0x1.f4340c0133432p+9", "0x1.f442701bf9e55p+9"),
            ("0x1.f43c458878ea4p+9", "0x1.f42ae15fb9a2cp+9"),
            ("0x1.f4712f0e8620ap+9", "0x1.f44e275c7c44fp+9"),
            ("0x1.f4775b3ecdfc6p+9", "0x1.f44fa02f1d525p+9"),
            ("0x1.f47661c2630d6p+9", "0x1.f441f2b73eb25p+9"),
        ],
        (
            "0x1.f3c0000000000p+9",
            "0x1.f43ff4edeff6bp+9",
            "0x1.f4c0000000000p+9",
            "0x1.f4c0000000000p+9",
        ),
        ("0x1.f3f3b25b3c3b5p+9", "0x1.f43ff4edeff6bp+9"),
    ),
    "seed3_3": (
        [
            ("0x1.55cc117ef46b9p+19", "0x1.55cc1d7c5571ep+19"),
            ("0x1.55cc120375226p+19", "0x1.55cc17ce1cc77p+19"),
            ("0x1.55cc1e4ef9efap+19", "0x1.55cc1af29bf7ep+19"),
            ("0x1.55cc17cee6644p+19", "0x1.55cc1a056ff64p+19"),
        ],
        (
            "0x1.55cbf00000000p+19",
            "0x1.55cbf00000000p+19",
            "0x1.55cc300000000p+19",
            "0x1.55cc1add6e610p+19",
        ),
        ("0x1.55cc142a1755ap+19", "0x1.55cc1add6e610p+19"),
    ),
    "seed5_140": (
        [
            ("0x1.206cca1c79c7cp-2", "0x1.ec5a81e827de6p-2"),
            ("0x1.60a8bdbd289d6p-1", "0x1.0795e9b1cae60p-2"),
            ("0x1.01c41595b1b66p-1", "0x1.3319a53aff442p-2"),
            ("0x1.ae22796ce0af5p-1", "0x1.0f7d6c58f363ep-2"),
            ("0x1.5f442c73d7e91p-1", "0x1.9c1b248b45f92p-2"),
            ("0x1.787dd6d95f778p-4", "0x1.7b010d440045fp-1"),
            ("0x1.270e814aff67fp-1", "0x1.4fb5cab8d3fe0p-3"),
            ("0x1.5ab11aba50d4ep-1", "0x1.64d9709457614p-1"),
            ("0x1.4af41476de7a8p-3", "0x1.d4a4153dbd400p-8"),
            ("0x1.5076983195f70p-1", "0x1.7850c9a7b764dp-1"),
            ("0x1.61ba2b411b5b7p-1", "0x1.51c5fc45546dap-2"),
            ("0x1.ee7ff2759c082p-2", "0x1.77cdf73e6f480p-1"),
            ("0x1.ba5e45d3a45ecp-3", "0x1.7e13eba6f863cp-3"),
            ("0x1.5f7fba1afc3c4p-3", "0x1.09fb798f08258p-3"),
            ("0x1.0a649f9cb2a14p-2", "0x1.2edfa25152fd3p-1"),
            ("0x1.da7c94405cdeep-1", "0x1.130566b14bb2ap-1"),
            ("0x1.2b2412d99f5b4p-2", "0x1.c5276a0b91190p-2"),
        ],
        (
            "0x1.5e1ca7ceaa9fcp-2",
            "-0x1.0000000000000p-1",
            "0x1.8000000000000p+0",
            "0x1.8000000000000p+0",
        ),
        ("0x1.5e1ca7ceaa9fcp-2", "0x1.27581c8033ab2p-2"),
    ),
    # (halfplane39) a vertex 1-4 ulps inside a side, far from the origin: the half-plane
    # cells lacked the third site of a box-side vertex (the watch band is relative to the
    # cell, the side snap's reach absolute: halfplane_finish.watch_sides), and a crossing
    # took the place of a vertex 4 ulps inside or outside, beyond the snap's reach (a
    # sliver gap or overlap, 1e-10 of the box: halfplane_settle.emit_exact keeps such a
    # crossing where it is)
    "seed0_4": (
        [
            ("-0x1.7d783fc62d6bdp+24", "-0x1.7d783fe01d2edp+24"),
            ("-0x1.7d783fb62ff4ap+24", "-0x1.7d783f69f3d6cp+24"),
            ("-0x1.7d783f72271ffp+24", "-0x1.7d783f30b6cb7p+24"),
            ("-0x1.7d783f7084a5ep+24", "-0x1.7d783fb62a070p+24"),
            ("-0x1.7d783f964c6cep+24", "-0x1.7d783f2e8f9fcp+24"),
            ("-0x1.7d783f5f9d45cp+24", "-0x1.7d783f0a79e34p+24"),
            ("-0x1.7d783fa16eb66p+24", "-0x1.7d783f72880d5p+24"),
        ],
        (
            "-0x1.7d783f866536dp+24",
            "-0x1.7d78408000000p+24",
            "-0x1.7d783e8000000p+24",
            "-0x1.7d783e8000000p+24",
        ),
        ("-0x1.7d783f866536dp+24", "-0x1.7d783f54102bfp+24"),
    ),
    "seed0_28": (
        [
            ("0x1.55cc127208bc7p+19", "0x1.55cc1973a3aeap+19"),
            ("0x1.55cc0a9e38392p+19", "0x1.55cc07dc970b9p+19"),
            ("0x1.55cc17368c11cp+19", "0x1.55cc0f3a8e025p+19"),
            ("0x1.55cc04c6545b3p+19", "0x1.55cc02cc59b3fp+19"),
            ("0x1.55cc1796e04cap+19", "0x1.55cc1b887f72fp+19"),
            ("0x1.55cc1c7dd89d0p+19", "0x1.55cc1052a62eap+19"),
            ("0x1.55cc04e9198d0p+19", "0x1.55cc073895e4cp+19"),
        ],
        (
            "0x1.55cc0654e0946p+19",
            "0x1.55cbf00000000p+19",
            "0x1.55cc300000000p+19",
            "0x1.55cc300000000p+19",
        ),
        ("0x1.55cc0654e0946p+19", "0x1.55cc144e42cfcp+19"),
    ),
    "seed3_9": (
        [
            ("-0x1.7d783f477b79ap+24", "-0x1.7d783ffcdc5c4p+24"),
            ("-0x1.7d783f3069178p+24", "-0x1.7d783f90d99b1p+24"),
            ("-0x1.7d783f906f797p+24", "-0x1.7d783f70091e7p+24"),
            ("-0x1.7d783fb84909fp+24", "-0x1.7d783f1cffcd8p+24"),
            ("-0x1.7d783fc9b17d7p+24", "-0x1.7d783f75107bep+24"),
            ("-0x1.7d783fd4fb381p+24", "-0x1.7d783f6246335p+24"),
            ("-0x1.7d783f191ca57p+24", "-0x1.7d783f1e0b864p+24"),
            ("-0x1.7d783fdd8599cp+24", "-0x1.7d783f60089a0p+24"),
            ("-0x1.7d783f1b81b0dp+24", "-0x1.7d783fccbac0bp+24"),
            ("-0x1.7d783f95d3850p+24", "-0x1.7d783f496ea96p+24"),
            ("-0x1.7d783f430bb55p+24", "-0x1.7d783f8c7f9c2p+24"),
            ("-0x1.7d783f5c837e3p+24", "-0x1.7d783f54c1bb5p+24"),
        ],
        (
            "-0x1.7d78408000000p+24",
            "-0x1.7d783f43d6a6bp+24",
            "-0x1.7d783e8000000p+24",
            "-0x1.7d783e8000000p+24",
        ),
        ("-0x1.7d783fbc7d67dp+24", "-0x1.7d783f43d6a6bp+24"),
    ),
    "seed3_138": (
        [
            ("0x1.55cc14af11f9ap+19", "0x1.55cc0799d37c1p+19"),
            ("0x1.55cc017a2549fp+19", "0x1.55cc06fd71637p+19"),
            ("0x1.55cc13d47ec8ap+19", "0x1.55cc0cbc0899ep+19"),
            ("0x1.55cc13919160ep+19", "0x1.55cc1428b3c78p+19"),
            ("0x1.55cc1f6d5f43bp+19", "0x1.55cc0eb31f36fp+19"),
            ("0x1.55cc141dfafc1p+19", "0x1.55cc08b12cd6cp+19"),
            ("0x1.55cc14ef03effp+19", "0x1.55cc02641476fp+19"),
            ("0x1.55cc0a855e4eep+19", "0x1.55cc0bad989a9p+19"),
            ("0x1.55cc1c3679d57p+19", "0x1.55cc002005a6cp+19"),
            ("0x1.55cc05a2b5b56p+19", "0x1.55cc08a7a9196p+19"),
            ("0x1.55cc0318c9ffcp+19", "0x1.55cc0a4621509p+19"),
            ("0x1.55cc1904c7787p+19", "0x1.55cc0e18c3f68p+19"),
            ("0x1.55cc1b8301a18p+19", "0x1.55cc0948406e9p+19"),
            ("0x1.55cc001866736p+19", "0x1.55cc16924a2d5p+19"),
            ("0x1.55cc03aeb45fap+19", "0x1.55cc18a880f06p+19"),
            ("0x1.55cc10677995bp+19", "0x1.55cc094e2ab36p+19"),
            ("0x1.55cc13821c970p+19", "0x1.55cc150c478e8p+19"),
            ("0x1.55cc1be02e549p+19", "0x1.55cc0eba54f92p+19"),
            ("0x1.55cc111eb8bc3p+19", "0x1.55cc0ae4abc2dp+19"),
            ("0x1.55cc05ea3e3abp+19", "0x1.55cc1f2158913p+19"),
            ("0x1.55cc09dbae1a8p+19", "0x1.55cc0c73000e9p+19"),
            ("0x1.55cc03a1f8f14p+19", "0x1.55cc07a2e7fc3p+19"),
            ("0x1.55cc0b4dfe569p+19", "0x1.55cc1b7394f30p+19"),
            ("0x1.55cc1b8cb1223p+19", "0x1.55cc1a5f51b42p+19"),
        ],
        (
            "0x1.55cbf00000000p+19",
            "0x1.55cbf00000000p+19",
            "0x1.55cc1341e11f1p+19",
            "0x1.55cc300000000p+19",
        ),
        ("0x1.55cc1341e11f1p+19", "0x1.55cc0aa99588ap+19"),
    ),
}


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
def test_side_a_few_ulps_from_the_vertex(name, ulps, corner, algorithm):
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


# (lo, seed) of _box_side_strips whose strip ends a vertex put on the side took out of
# their own cells (the reach without the guard of ``cellcut.side_reaches``)
STRIPS = [(0.5, 3), (7.0, 1), (7.0, 3), (1234.5, 10), (5e5, 29), (3e7, 5), (3e7, 10)]


@pytest.mark.parametrize(("lo", "seed"), STRIPS)
def test_strip_ends_at_a_side_keep_their_sites(lo, seed, algorithm):
    pts, box = _box_side_strips(lo, seed)
    d = vf.voronoi(pts, box, algorithm=algorithm)
    cells = np.asarray(d.cells, dtype=object)
    assert shapely.is_valid(cells).all()
    assert not len(d.unresolved)
    own = shapely.intersects(cells, shapely.points(pts))
    assert own[d.duplicate_of < 0].all(), np.flatnonzero(~own)
    assert d.areas.sum() == pytest.approx(1.0, rel=1e-12)
    assert _shared_vertices_ok(d) == []
    r = d.describe()
    assert r.euler_ok and r.convex_ok, str(r)
